"""Option refusals name the option the user set (issue 17, point 4)."""

from __future__ import annotations

import pytest

from cusp.continuation import ContinuationOptions, OptionsError


def test_a_ds_max_below_the_default_ds_min_is_named_as_ds_max():
    with pytest.raises(OptionsError, match=r"option 'ds_max' \(1e-11\) must be >= 'ds_min'"):
        ContinuationOptions(ds_max=1e-11)
    with pytest.raises(OptionsError, match=r"option 'ds_max' \(1e-11\)"):
        ContinuationOptions().replace(ds_max=1e-11)
    # both moved: the pair is named
    with pytest.raises(OptionsError, match=r"option 'ds_min' \(0.001\) must not exceed"):
        ContinuationOptions(ds_min=1e-3, ds_max=1e-4)
    assert ContinuationOptions().replace(ds_min=1e-12, ds_max=1e-11).ds == 1e-11  # ds clipped
