"""The work of a locus is bounded and its messages are in the scene's terms (issue 27,
point 5): energies at no more than ``ENERGY_ROWS`` rows, endings named by the path's events."""

from __future__ import annotations

import math

import numpy as np

from cusp.models import ContactLoss, ExponentialRoughSurface, manifold
from cusp.models.manifold import point_loci


def _loci(monkeypatch, limit: int):
    monkeypatch.setattr(manifold, "ENERGY_ROWS", limit)
    model = ContactLoss(ExponentialRoughSurface(2.0, 0.3, 0.1), 1000.0, 0.34, 850.0)
    return point_loci(model, "mu", (0.05, 1.0), at=[0.3])


def test_energies_beyond_the_row_limit_are_left_empty_with_a_message(monkeypatch):
    full = _loci(monkeypatch, 10_000)
    n = len(full.columns["mu"])
    assert n > 12
    thin = _loci(monkeypatch, 5)
    stride = -(-n // 5)
    (note,) = [m for m in thin.messages if m.startswith("the released energies are")]
    assert f"one row in {stride} of the loci" in note and f"of {n} rows" in note
    back, back_full = thin.columns["snap_back_energy"], full.columns["snap_back_energy"]
    mu = thin.columns["mu"]
    for i in range(n):
        if i % stride == 0 or mu[i] == 0.3:  # integrated: the same numbers as without limit
            assert back[i] == back_full[i] or (math.isnan(back[i]) and math.isnan(back_full[i]))
        else:
            assert math.isnan(back[i])
    assert np.array_equal(thin.columns["g_C"], full.columns["g_C"], equal_nan=True)


def test_locus_endings_name_the_path_events_not_the_chain_variables(monkeypatch):
    loci = _loci(monkeypatch, 10_000)
    endings = [m for m in loci.messages if m.startswith("locus of")]
    assert endings and all("B.t" not in m and "reached bound" not in m for m in endings)
    assert any("to the end of the range, mu = 0.05" in m for m in endings), endings
    assert any("where F'_T = 0" in m for m in endings), endings
