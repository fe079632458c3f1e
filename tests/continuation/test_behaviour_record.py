"""The engine computes what it computed when the record was made, bit for bit (issue 28).

``tests/continuation/data/behaviour_record.json`` was written by
``python scripts/record_behaviour.py`` before the engine was split into concept packages; it
holds, for ~360 cases (the published-problem suite with its branch switches and perturbed
starts, every catalogue example under each derivative strategy, option variants, fold
curves, loci, failures, dense output), every special point's values in full ``repr`` and a
SHA-256 of the float64 bytes of every point, tangent and per-point statistic. A change of
one bit anywhere fails this test and names the case and the field.

The bits depend on the platform and on numpy's, scipy's and LAPACK's builds: the record
stores its environment, and in another one the comparison is skipped (regenerate the record
there from the revision it guards, then compare).
"""

from __future__ import annotations

import json

import pytest


@pytest.mark.slow
def test_the_engine_computes_the_recorded_points_bit_for_bit(load_script):
    recorder = load_script("record_behaviour")
    stored = json.loads(recorder.RECORD.read_text(encoding="utf-8"))
    if stored["environment"] != recorder.environment():
        pytest.skip(
            f"the record was made in {stored['environment']}, this is "
            f"{recorder.environment()}: bits are not comparable across builds"
        )
    now = recorder.compute()
    assert sorted(now) == sorted(stored["cases"])
    diff = recorder.differences(stored["cases"], now)
    assert not diff, f"{len(diff)} differences, the first:\n" + "\n".join(diff[:30])


def test_the_comparison_sees_one_changed_bit(load_script):
    """The reduction hashes every bit: a point moved by one ulp changes the record."""
    import numpy as np

    from cusp.examples import cusp_normal_form

    recorder = load_script("record_behaviour")
    br = cusp_normal_form().trace()
    before = recorder.reduce_branch(br)
    x = br["x"]
    x[3] = np.nextafter(x[3], np.inf)
    after = recorder.reduce_branch(br)
    assert recorder.differences(before, after) == [
        f"/columns/x: {before['columns']['x']!r} -> {after['columns']['x']!r}",
        f"/sha: {before['sha']!r} -> {after['sha']!r}",
    ]
