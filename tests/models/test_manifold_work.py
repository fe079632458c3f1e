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


def _sliding_start_loci():
    # (g_A = 1 µm: at μ = 0.1 the block slides, F_A >= μF'_N, so the path has no C and C's
    # locus starts from rows of the first locus where C exists, at larger μ)
    model = ContactLoss(ExponentialRoughSurface(2.0, 0.3, 0.1), 1000.0, 1.0, 850.0)
    return point_loci(model, "mu", (0.05, 1.0))


def test_the_locus_of_c_passes_over_a_start_on_a_branch_point(monkeypatch):
    """A start of C's locus where the chain's Jacobian is singular is passed over for the next
    row; when every start is, the loci keep the first locus and say why C's is missing (they
    used to end the scene: exit 1 with the engine's advice in the chain's variables)."""
    from cusp.continuation import SingularPointError

    real, starts = manifold.locus, []

    def first_with_c_singular(chain, start, **kw):
        if "C" in start:
            starts.append(start["C"]["g"])
            if len(starts) == 1:
                raise SingularPointError("a branch point", values={})
        return real(chain, start, **kw)

    monkeypatch.setattr(manifold, "locus", first_with_c_singular)
    loci = _sliding_start_loci()
    assert "A-B-C-D" in loci.branches and len(starts) == 2 and starts[0] != starts[1]
    assert not [m for m in loci.messages if "not traced" in m]

    def always_singular(chain, start, **kw):
        if "C" in start:
            raise SingularPointError("a branch point", values={})
        return real(chain, start, **kw)

    monkeypatch.setattr(manifold, "locus", always_singular)
    loci = _sliding_start_loci()
    assert "A-B-C-D" not in loci.branches and len(loci.branches) == 1
    (note,) = [m for m in loci.messages if m.startswith("the locus of C is not traced")]
    tried = note.split("(mu = ")[1].split(")")[0].split(", ")
    assert len(set(tried)) == manifold._C_SEEDS, note
    assert np.all(np.isnan(loci.columns["g_C"]))  # (no C reported where none was traced)


def test_a_slip_area_at_rounding_level_does_not_set_its_own_size():
    """On a Gaussian surface of σ* = 0.0117 µm, A's Â_SL is rounding noise (about ±1e-24,
    error bound inf, as the loci's messages say). Sized from its value, it made C's locus in
    μ start on a branch point (its scaled column was 1e-24 of the others: exit 1) and, once
    started, creep after the noise to the 400-step work limit. Its size is now 1 (a share of
    the real contact area): C's locus runs from F'_T = 0 down to the C boundary."""
    from cusp.models import registry

    body = registry.build_body(
        "rough-gaussian", sigma=0.0117, nu=0.3, mu=0.1, E=0.2, radius=10.0, density=0.01,
        nominal_area=1e6,
    )  # fmt: skip
    model = ContactLoss(body, 1000.0, 0.1, 850.0)
    loci = point_loci(model, "mu", (0.1, 1000.0))
    with_c = loci.branches["A-B-C-D"]
    assert with_c.status == "bound" and len(with_c) < manifold.LOCUS_STEPS  # 208 rows here
    assert any("where C is no longer resolved" in m for m in loci.messages), loci.messages
    assert any("A_SL of A along the loci is resolved only to its error bound" in m
               for m in loci.messages)  # fmt: skip
