"""Fold curves and cusps (two-parameter continuation)."""

import dataclasses
import math

import numpy as np
import pytest

import cusp.examples as ex
from cusp.continuation import Event, fold_curve, trace

X0 = ex.cusp_start()  # -1.324717957244746, root of x^3 - x + 1


def cusp_problem(analytic=True):
    return ex.cusp_normal_form(derivatives="analytic" if analytic else "central").problem


def cusp_folds(prob):
    br = trace(prob, [X0], free="b", bounds={"b": (-1.0, 1.0)})
    return br.special("fold")


@pytest.mark.parametrize("analytic", [True, False])
@pytest.mark.parametrize("which", [0, 1])
def test_cusp_normal_form_fold_curve(which, analytic):
    prob = cusp_problem(analytic)
    fold = cusp_folds(prob)[which]
    fc = fold_curve(prob, fold, free=("b", "a"), bounds={"a": (-1.0, 2.0)})
    assert fc.success and fc.info["direction"] == "both"
    a, b, x = fc["a"], fc["b"], fc["x"]
    # the fold curve (a, b) = (3x², −2x³): 4a³ = 27b² everywhere on it
    rel = np.abs(4 * a**3 - 27 * b**2) / np.maximum(1.0, 4 * np.abs(a) ** 3 + 27 * b**2)
    assert rel.max() <= 1e-10
    np.testing.assert_allclose(a, 3 * x**2, atol=1e-10)
    # it runs from a = 2 on one fold branch through the cusp to a = 2 on the other
    assert a[0] == 2.0 and a[-1] == 2.0 and np.sign(x[0]) == -np.sign(x[-1])
    cusps = fc.special("cusp")
    assert len(cusps) == 1
    c = cusps[0]
    assert c.status == "converged" and c.details["method"] == "Newton on [F; g; a]"
    for name in ("x", "a", "b"):
        assert abs(c.values[name]) <= 1e-10
    # the normal-form coefficient changes sign; the tangent's parameter components vanish
    assert c.details["coefficient_before"] * c.details["coefficient_after"] < 0
    assert max(abs(t) for t in c.details["tangent_parameters"].values()) < 1e-6
    before, after = c.details["fold_branches"]
    assert before["x"] * after["x"] < 0  # the two fold branches that meet
    start = fc.special("fold", label="start (fold)")
    assert len(start) == 1 and fc["a"][start[0].index] == 1.0


def test_one_direction_and_events_on_fold_curve():
    prob = cusp_problem()
    fold = cusp_folds(prob)[0]
    ev = Event(lambda u, p: p["a"] - 0.5, label="a=1/2")
    fc = fold_curve(
        prob,
        fold,
        free=("b", "a"),
        direction=-1,
        bounds={"a": (-1.0, 2.0)},
        events=[ev],
        targets={"b": [0.1]},
    )
    assert fc.info["direction"] == -1
    evs = fc.special("event", label="a=1/2")
    assert len(evs) == 2  # a = 1/2 before and after the cusp
    for e in evs:
        assert e.values["a"] == pytest.approx(0.5, abs=1e-12)
        assert 4 * e.values["a"] ** 3 == pytest.approx(27 * e.values["b"] ** 2, rel=1e-9)
    tg = fc.special("target")
    assert len(tg) == 1 and tg[0].values["b"] == 0.1
    # b = 0.1 on the fold curve: x = −(0.05)^{1/3}, a = 3x²
    assert tg[0].values["a"] == pytest.approx(3 * 0.05 ** (2 / 3), rel=1e-10)


def arch(e):
    """Shallow pinned sinusoidal arch, two-mode Ritz model (docs/test-problems.md §5): the
    gradient of Π = (1/8)(ξ1² − 2eξ1 + 4ξ2²)² + ξ1² + 16ξ2² − pξ1, without its Jacobian
    (central differences)."""
    return ex.shallow_arch(e, derivatives="central").problem


def test_arch_limit_point_meets_branch_point_at_sqrt22():
    br = trace(arch(6.0), [0.0, 0.0], free="p", bounds={"p": (-10, 100), "xi1": (-1, 13)})
    lp = br.special("fold")[0]
    fc = fold_curve(arch(6.0), lp, free=("p", "e"), bounds={"e": (3.0, 8.0)}, ds_max=2.0)
    codim2 = fc.special("codim2")
    assert len(codim2) == 1
    # at e = √22 (= 4.690415759823430, sympy: sqrt(22)) the limit point
    # ξ1 = e − √((e² − 4)/3) and the branch point ξ1 = e − √(e² − 16) coincide
    assert codim2[0].values["e"] == pytest.approx(math.sqrt(22.0), rel=1e-9)
    e = codim2[0].values["e"]
    assert codim2[0].values["xi1"] == pytest.approx(e - math.sqrt((e * e - 4) / 3), rel=1e-9)
    # the fold curve is the symmetric limit point: ξ2 = 0 and ξ1 = e − √((e²−4)/3)
    np.testing.assert_allclose(fc["xi1"], fc["e"] - np.sqrt((fc["e"] ** 2 - 4) / 3), atol=1e-8)
    assert np.max(np.abs(fc["xi2"])) < 1e-12


@pytest.mark.parametrize("rel", [-3e-11, -3e-12, 3e-12, 1e-11, 3e-11])
def test_fold_curve_starts_from_a_slightly_inexact_fold_with_differenced_jacobian(rel):
    # The arch has no Jacobian: g on the fold curve comes from central differences and
    # cannot get below ~1e-10. A start a few 1e-12 off the fold used to leave the corrector
    # cycling at that noise (the starting point "did not converge", or the second zero
    # eigenvalue was only bracketed); the noise floor of g is now part of the stopping test.
    br = trace(arch(6.0), [0.0, 0.0], free="p", bounds={"p": (-10, 100), "xi1": (-1, 13)})
    lp = br.special("fold")[0]
    values = dict(lp.values)
    values["xi1"] *= 1.0 + rel
    start = dataclasses.replace(lp, values=values)
    fc = fold_curve(arch(6.0), start, free=("p", "e"), bounds={"e": (3.0, 8.0)}, ds_max=2.0)
    assert fc.success
    codim2 = fc.special("codim2")
    assert len(codim2) == 1 and codim2[0].status == "converged"
    # sympy: sqrt(22) (see test_arch_limit_point_meets_branch_point_at_sqrt22)
    assert codim2[0].values["e"] == pytest.approx(math.sqrt(22.0), rel=1e-9)


def test_snap_back_fold_curve_closes_in_a_cusp():
    # truss (Green strain, EA = L = 1, H = 0.1) in series with a spring k_s under load control
    # P: unknowns (v, δ); the snap-back is a turning point of δ (a monitored unknown). The
    # snap-back disappears when k_s ≥ K H² (docs/test-problems.md §4): the two δ-turning points
    # meet in a cusp at k_s = K H², K = EA/l0³.
    H = 0.1
    K = 1 / math.hypot(1.0, H) ** 3
    prob = ex.snapback_monitor(H=H, ks=0.005, derivatives="complex").problem
    br = trace(
        prob, [0.0, 0.0], free="P", monitor=["delta"], bounds={"v": (-0.01, 0.25)}, ds_max=0.05
    )
    snap = br.special("fold", with_respect_to="delta")
    assert len(snap) == 2
    fc = fold_curve(prob, snap[0], free=("P", "ks"), bounds={"ks": (0.001, 0.02)}, ds_max=0.05)
    cusps = fc.special("cusp")
    assert len(cusps) == 1
    assert cusps[0].values["ks"] == pytest.approx(K * H**2, rel=1e-10)
    assert cusps[0].values["v"] == pytest.approx(H, rel=1e-10)
    # on the fold curve dδ/dv = 0: 1 + (K/k_s)(3t² − H²) = 0, t = v − H, so
    # v = H ∓ √((H² − k_s/K)/3) on the two halves (at the cusp k_s/K may exceed H² by an ulp
    # of rounding: the radicand is clipped at 0 there)
    ks = fc["ks"]
    assert np.all(ks / K <= H**2 * (1 + 1e-14))
    v_exact = H + np.sign(fc["v"] - H) * np.sqrt(np.maximum(H**2 - ks / K, 0.0) / 3)
    np.testing.assert_allclose(fc["v"], v_exact, atol=1e-10)


def test_fold_curve_input_errors():
    prob = cusp_problem()
    fold = cusp_folds(prob)[0]
    with pytest.raises(ValueError, match="kind 'fold'"):
        fold_curve(
            prob,
            cusp_folds(prob)[0].__class__(
                kind="event", index=0, values=fold.values, tangent=fold.tangent
            ),
            free=("b", "a"),
        )
    with pytest.raises(ValueError, match="not a parameter"):
        fold_curve(prob, fold, free=("b", "c"))
    with pytest.raises(ValueError, match="must differ"):
        fold_curve(prob, fold, free=("b", "b"))
    with pytest.raises(ValueError, match="direction"):
        fold_curve(prob, fold, free=("b", "a"), direction=2)
