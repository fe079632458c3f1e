"""Oracle tests: the published problems of docs/test-problems.md against independently recomputed
references (mpmath at 40 digits or sympy, in `cusp.examples` or beside each literal).

A fold's parameter is compared to 1e-12 relative (the solver promises Newton refinement on an
augmented system to that accuracy); its state to the strategy's tolerance (the fixture
`state_rtol`: `STATE_RTOL` of tests/continuation/helpers.py). Branch and special
points are also checked against the example's own residual, never the solver's.
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import cusp.examples as ex

MAX_STEPS = 5000  # generous: these tests are about accuracy, not about the default step budget


def trace(*args, **kwargs):
    from cusp.continuation import trace as _trace

    kwargs.setdefault("max_steps", MAX_STEPS)
    return _trace(*args, **kwargs)


@pytest.fixture
def assert_on_branch(branch_residual_norms, assert_special_points_consistent):
    """``assert_on_branch(case, br, atol=1e-9)``: every point solves the example's own
    residual to ``atol``; the special points are the branch's columns."""

    def check(case, br, atol=1e-9):
        res = branch_residual_norms(case, br)
        assert res.max() <= atol, f"oracle residual up to {res.max():.3e} at point {res.argmax()}"
        assert_special_points_consistent(case, br)

    return check


def assert_fold(sp, free, ref_param, ref_state, state_rtol, wrt=None):
    """A refined fold: converged, its parameter to 1e-12 relative, its state to state_rtol."""
    assert sp.kind == "fold"
    assert sp.status == "converged", sp
    assert sp.with_respect_to == (wrt or free), sp
    name, value = ref_param
    assert sp.values[name] == pytest.approx(value, rel=1e-12, abs=0), (name, sp.values)
    for name, value in ref_state.items():
        assert sp.values[name] == pytest.approx(value, rel=state_rtol, abs=1e-300), name


# ---------------------------------------------------------------------------------------------
# 1. Cusp normal form x^3 - a x - b = 0, a = 1
# ---------------------------------------------------------------------------------------------


def test_cusp_references():
    # 2/(3 sqrt 3) at 40 digits: mp.mpf(2)/(3*mp.sqrt(3)) = 0.38490017945975050967276585366797...
    (x1, b1), (x2, b2) = ex.cusp_folds(1.0)
    assert (b1, b2) == (0.3849001794597505, -0.3849001794597505)
    assert (x1, x2) == (-0.5773502691896257, 0.5773502691896257)  # 1/sqrt 3, correctly rounded
    # the fold curve 4a^3 = 27b^2 through these folds
    assert 4 * 1.0**3 == pytest.approx(27 * b1**2, rel=1e-15)
    # u0 of the spec is minus the plastic number, root of x^3 - x + 1 = 0
    with mp.workdps(40):
        plastic = mp.findroot(lambda x: x**3 - x - 1, 1.3)
    assert ex.cusp_start() == -float(plastic) == -1.324717957244746


def test_cusp_both_folds_and_exact_bound(strategy, special, state_rtol, assert_on_branch):
    case = ex.cusp_normal_form(derivatives=strategy)
    br = trace(case.problem, u0=[-1.3247], free="b", bounds={"b": (-1.0, 1.0)})
    assert br.success, (br.status, br.message)
    # the start is corrected onto the branch at fixed b = -1
    assert br["b"][0] == -1.0
    assert br["x"][0] == pytest.approx(ex.cusp_start(), rel=1e-12)
    assert np.all(br["a"] == 1.0)
    folds = special(br, "fold")
    assert len(folds) == 2, [(sp.kind, sp.values) for sp in br.special_points]
    # path order: first the fold at x = -1/sqrt 3, b = +2/(3 sqrt 3), then its mirror image
    for sp, (x, b) in zip(folds, ex.cusp_folds(1.0), strict=True):
        assert_fold(sp, "b", ("b", b), {"x": x}, state_rtol)
    # the bound is hit to the last bit, and the branch says so
    assert br["b"][-1] == 1.0
    assert br["x"][-1] == pytest.approx(-ex.cusp_start(), rel=1e-12)  # b -> -b, x -> -x
    ends = special(br, "endpoint")
    assert ends and ends[-1].index == len(br["b"]) - 1
    assert "bound" in f"{br.status} {br.message}".lower()
    assert_on_branch(case, br, atol=1e-10)


def test_cusp_reverse_direction_finds_the_same_folds(special):
    case = ex.cusp_normal_form(b=1.0)  # start on the upper sheet at b = +1
    br = trace(
        case.problem, u0=[-ex.cusp_start()], free="b", bounds={"b": (-1.0, 1.0)}, direction=-1
    )
    assert br.success, (br.status, br.message)
    assert br["b"][0] == 1.0 and br["b"][-1] == -1.0
    folds = special(br, "fold")
    assert len(folds) == 2
    for sp, (x, b) in zip(folds, reversed(ex.cusp_folds(1.0)), strict=True):
        assert_fold(sp, "b", ("b", b), {"x": x}, 1e-9)


def trace_cusp_over_a(a, special):
    """Trace x³ − a x − b over b ∈ [−B, B], B = 2·2(a/3)^{3/2} + 0.1, from the lone real root
    at b = −B, and check both folds against the closed form b = ∓2 (a/3)^{3/2},
    x = ±sqrt(a/3) (ex.cusp_folds). Returns the branch, B and the two folds (``special``:
    the fixture)."""
    bmax = 2 * (a / 3) ** 1.5
    B = 2 * bmax + 0.1
    case = ex.cusp_normal_form(a=a, b=-B)  # u0: the lone real root at b = -B (numpy roots)
    br = trace(case.problem, u0=case.u0, free="b", bounds={"b": (-B, B)})
    folds = special(br, "fold")
    assert len(folds) == 2, a
    for sp, (x, b) in zip(folds, ex.cusp_folds(a), strict=True):
        assert_fold(sp, "b", ("b", b), {"x": x}, 1e-9)
    return br, B, folds


@settings(max_examples=12, deadline=None)
@given(a=st.floats(min_value=0.02, max_value=5.0))
def test_cusp_folds_over_a(a, special):
    """Property: at any a > 0 the folds are at b = -+2 (a/3)^(3/2), x = -+sqrt(a/3)."""
    br, B, _ = trace_cusp_over_a(a, special)
    assert br.success, (br.status, br.message)
    assert br["b"][-1] == B


def test_cusp_fold_parameters_relative_over_a_grid(special):
    """Both folds to 1e-12 *relative* in b over a ∈ [0.02, 5] (b from 1.1e-3 to 4.3), where
    the fold Newton's mixed stopping tolerance 1e-12·(1 + |z|) alone would not be relative;
    a = 0.2890625 is the value at which an earlier stopping rule failed."""
    worst = 0.0
    for a in [*np.geomspace(0.02, 5.0, 60), 0.2890625]:
        _, _, folds = trace_cusp_over_a(a, special)
        for sp, (_, b) in zip(folds, ex.cusp_folds(a), strict=True):
            worst = max(worst, abs(sp.values["b"] - b) / abs(b))
    print(f"worst relative fold parameter error over the grid: {worst:.2g}")


# ---------------------------------------------------------------------------------------------
# 2. Finite-difference Bratu
# ---------------------------------------------------------------------------------------------


def test_bratu_small_n_closed_forms_sympy():
    """N = 1: -8u + lam e^u = 0 and det J = -8 + lam e^u = 0 give u = 1, lam = 8/e.
    N = 2 (h = 1/3): the fold is u1 = u2 = 1, lam = 9/e; checked exactly, and as the unique
    fold near it by nsolve at 30 digits."""
    import sympy as sp

    u, lam = sp.symbols("u lam")
    sol = sp.solve([-8 * u + lam * sp.exp(u), -8 + lam * sp.exp(u)], [u, lam], dict=True)
    assert sol == [{u: 1, lam: 8 * sp.exp(-1)}]

    u1, u2 = sp.symbols("u1 u2")
    F = sp.Matrix([9 * (-2 * u1 + u2) + lam * sp.exp(u1), 9 * (u1 - 2 * u2) + lam * sp.exp(u2)])
    det = F.jacobian([u1, u2]).det()
    at = {u1: 1, u2: 1, lam: 9 * sp.exp(-1)}
    assert sp.simplify(F.subs(at)) == sp.zeros(2, 1)
    assert sp.simplify(det.subs(at)) == 0
    num = sp.nsolve([F[0], F[1], det], [u1, u2, lam], [0.9, 1.1, 3.3], prec=30)
    assert abs(num[2] - 9 / sp.E) < 1e-28 and abs(num[0] - 1) < 1e-28

    # and the discrete-shooting oracle reproduces both closed forms
    assert ex.bratu_fd_fold(1)[0] == pytest.approx(8 / math.e, rel=1e-15)
    assert ex.bratu_fd_fold(2)[0] == pytest.approx(9 / math.e, rel=1e-15)


def test_bratu_references_converge_like_h2():
    """lam*(N) -> lam* = 8(s^2 - 1) like h^2 (constant ~ -1.828), also at N = 99999."""
    lam_star, u_half = ex.bratu_continuum_fold()
    assert (
        lam_star == 3.513830719125161
    )  # docs/test-problems.md §2: the often-quoted ...162 is 2 ulp high
    assert u_half == pytest.approx(1.186842168634389, rel=1e-15)
    consts = []
    for n in (10, 20, 40, 80):
        h = 1.0 / (n + 1)
        consts.append((ex.bratu_fd_fold(n)[0] - lam_star) / h**2)
    assert all(-1.9 < c < -1.8 for c in consts), consts
    assert abs(consts[-1] - consts[-2]) < abs(consts[1] - consts[0])  # converging
    c_big = (ex.BRATU_FOLD_N99999 - lam_star) / 1e-5**2
    assert c_big == pytest.approx(consts[-1], rel=5e-3)


def _trace_bratu(case, n, **kw):
    mid = f"u{n // 2}"
    return trace(case.problem, u0=np.zeros(n), free="lam", bounds={mid: (-1.0, 2.5)}, **kw)


@pytest.mark.parametrize("n, lam_fold, u_fold", [(1, 8 / math.e, 1.0), (2, 9 / math.e, 1.0)])
def test_bratu_fd_small_n_fold(
    n, lam_fold, u_fold, strategy, special, state_rtol, assert_on_branch
):
    case = ex.bratu(n, derivatives=strategy)
    br = _trace_bratu(case, n)
    assert br.success, (br.status, br.message)
    assert br[f"u{n // 2}"][-1] == 2.5
    folds = special(br, "fold")
    assert len(folds) == 1, [(sp.kind, sp.values) for sp in br.special_points]
    assert_fold(
        folds[0],
        "lam",
        ("lam", lam_fold),
        {f"u{i}": u_fold for i in range(n)},
        state_rtol,
    )
    assert not special(br, "branch_point")
    assert_on_branch(case, br, atol=1e-8)


@pytest.mark.parametrize(
    "n, strategy",
    [(10, "analytic"), (10, "central"), (10, "forward"), (10, "complex")]
    + [(20, "analytic"), (20, "central")],
)
def test_bratu_fd_fold_vs_discrete_shooting(n, strategy, special, state_rtol, assert_on_branch):
    lam_ref, u1_ref = ex.bratu_fd_fold(n)  # mpmath shooting, 40 digits
    case = ex.bratu(n, derivatives=strategy)
    br = _trace_bratu(case, n)
    assert br.success, (br.status, br.message)
    folds = special(br, "fold")
    assert len(folds) == 1
    sp = folds[0]
    assert sp.status == "converged" and sp.with_respect_to == "lam"
    assert sp.values["lam"] == pytest.approx(lam_ref, rel=1e-10, abs=0)
    assert sp.values["u0"] == pytest.approx(u1_ref, rel=max(state_rtol, 1e-8))
    # symmetric about the midpoint
    u = np.array([sp.values[f"u{i}"] for i in range(n)])
    assert np.allclose(u, u[::-1], rtol=0, atol=1e-7)
    assert_on_branch(case, br, atol=1e-7 * (n + 1) ** 2)


@pytest.mark.slow
def test_bratu_fd_sparse_n99999_reaches_and_locates_its_fold(special):
    """N = 99999 (h = 1e-5, odd so that x = 1/2 is a grid point) with a scipy.sparse
    tridiagonal Jacobian and the parameter derivative supplied.

    The residual has an O(eps/h^2) ~ 1e-6 rounding floor (entries 2e10); a float64 Newton on
    the standard augmented fold system (F = 0, J phi = 0, l.phi = 1) with the same residual
    reaches lam to ~1e-11 absolute, so 1e-10 relative to the shooting value leaves a wide margin.
    Against the continuum lam* the discrete fold differs by -1.828 h^2 = -1.8e-10.
    """
    import time

    n = 99_999
    case = ex.bratu(n, sparse=True)
    # What a user would do: the state has 1e5 O(1) components, which in an unweighted 2-norm
    # would put the fold ~ sqrt(N) * 0.7 ~ 250 arclength units away; ContinuationOptions
    # documents that the state enters the arclength as a root-mean-square (state_weight = 1/n)
    # "so large discretisations take the same steps as small ones": keep the default ds.
    t0 = time.perf_counter()
    br = trace(
        case.problem, u0=np.zeros(n), free="lam", bounds={"u49999": (-1.0, 2.0)}, max_steps=400
    )
    elapsed = time.perf_counter() - t0
    assert br.success, (br.status, br.message)
    assert br["u49999"][-1] == 2.0
    folds = special(br, "fold")
    assert len(folds) == 1, [(sp.kind, sp.values["lam"]) for sp in br.special_points]
    sp = folds[0]
    assert sp.status == "converged" and sp.with_respect_to == "lam"
    lam_star, u_half = ex.bratu_continuum_fold()
    assert sp.values["lam"] == pytest.approx(ex.BRATU_FOLD_N99999, rel=1e-10, abs=0)
    assert abs(sp.values["lam"] - lam_star) <= 1e-9  # O(h^2): -1.8e-10 + solver error
    assert sp.values["u49999"] == pytest.approx(u_half, abs=1e-7)  # O(h^2) + solver error
    assert sp.values["u0"] == pytest.approx(3.99998243040404708562089e-5, rel=1e-7)  # shooting
    assert elapsed < 60.0, f"{elapsed:.1f} s"


# ---------------------------------------------------------------------------------------------
# 3. Von Mises truss
# ---------------------------------------------------------------------------------------------


def test_truss_green_both_limit_points(strategy, special, state_rtol, assert_on_branch):
    H = 0.5
    case = ex.truss_green(H=H, derivatives=strategy)
    br = trace(case.problem, u0=[0.0], free="P", bounds={"v": (-0.5, 1.5)})
    assert br.success, (br.status, br.message)
    assert br["v"][-1] == 1.5
    folds = special(br, "fold")
    assert len(folds) == 2
    for sp, (v, P) in zip(folds, ex.truss_green_limits(H=H), strict=True):
        assert_fold(sp, "P", ("P", P), {"v": v}, state_rtol)
    # P_max = (2/(3 sqrt 3)) EA H^3/l0^3 = 0.3849001794597505 * 0.125 / 1.25^1.5
    assert folds[0].values["P"] == pytest.approx(0.3849001794597505 * 0.125 / 1.25**1.5, rel=1e-12)
    assert_on_branch(case, br, atol=1e-10)


def test_truss_rotated_strain_limit_points(strategy, special, state_rtol, assert_on_branch):
    case = ex.truss_rotated(derivatives=strategy)  # EA = L = H = 1
    br = trace(case.problem, u0=[0.0], free="P", bounds={"v": (-0.5, 2.5)})
    assert br.success, (br.status, br.message)
    folds = special(br, "fold")
    assert len(folds) == 2
    for sp, (v, P) in zip(folds, ex.truss_rotated_limits(), strict=True):
        assert_fold(sp, "P", ("P", P), {"v": v}, state_rtol)
        y = 1.0 - sp.values["v"]
        # l^3 = L^2 l0
        assert (1.0 + y**2) ** 1.5 == pytest.approx(2**0.5, rel=state_rtol)
    # y_c = sqrt(2^(1/3) - 1) = 0.5098245285..., i.e. v = 0.4901754714...
    # (mpmath: mp.sqrt(mp.cbrt(2) - 1) at 30 digits = 0.509824528533958598086613462042)
    assert ex.truss_rotated_limits()[0][0] == pytest.approx(1 - math.sqrt(2 ** (1 / 3) - 1))
    assert_on_branch(case, br, atol=1e-10)


@pytest.mark.parametrize("strategy", ["analytic", "central", "complex"])
def test_truss_2dof_branch_point_before_limit_and_switch(
    strategy, special, state_rtol, assert_on_branch
):
    EA, L, H = 1.0, 1.0, 2.0  # H > sqrt(3) L: the branch point comes first
    ref = ex.truss_2dof_references(EA, L, H)
    # v_B = 2 - sqrt 2, P_B = 2 sqrt 2 / 5^1.5; v_L = 2 - 2/sqrt 3, P_L = (16/(3 sqrt 3))/5^1.5
    assert ref["bp_v"] == pytest.approx(2 - math.sqrt(2), rel=1e-15)
    assert ref["bp_P"] == pytest.approx(2 * math.sqrt(2) / 5**1.5, rel=1e-15)
    assert ref["lp_P"] == pytest.approx(16 / (3 * math.sqrt(3)) / 5**1.5, rel=1e-15)
    case = ex.truss_2dof(EA, L, H, derivatives=strategy)
    br = trace(case.problem, u0=[0.0, 0.0], free="P", bounds={"v": (-0.5, 1.0)})
    assert br.success, (br.status, br.message)
    bps, folds = special(br, "branch_point"), special(br, "fold")
    assert len(bps) == 1 and len(folds) == 1, [(s.kind, s.values) for s in br.special_points]
    bp, lp = bps[0], folds[0]
    assert bp.index < lp.index  # found before the limit point
    assert bp.status == "converged"
    assert bp.values["P"] == pytest.approx(ref["bp_P"], rel=1e-10)
    assert bp.values["v"] == pytest.approx(ref["bp_v"], rel=1e-9)
    assert abs(bp.values["u"]) < 1e-10
    assert_fold(lp, "P", ("P", ref["lp_P"]), {"v": ref["lp_v"]}, state_rtol)
    assert np.max(np.abs(br["u"])) < 1e-10  # the primary path stays symmetric
    assert_on_branch(case, br, atol=1e-10)

    # Branch switching onto the asymmetric path u^2 + y^2 = H^2 - 2L^2, P = 2 EA L^2 y/l0^3.
    ends = []
    for direction in (+1, -1):
        br2 = trace(case.problem, u0=bp, free="P", direction=direction, bounds={"u": (-1.0, 1.0)})
        assert br2.success, (br2.status, br2.message)
        u, v, P = np.asarray(br2["u"]), np.asarray(br2["v"]), np.asarray(br2["P"])
        assert np.max(np.abs(u)) > 0.5  # genuinely asymmetric
        assert abs(u[-1]) == 1.0  # ends on the bound of u, exactly
        y = H - v
        assert np.allclose(u**2 + y**2, H**2 - 2 * L**2, rtol=0, atol=1e-8)
        assert np.allclose(P, 2 * EA * L**2 * y / (L**2 + H**2) ** 1.5, rtol=0, atol=1e-9)
        assert_on_branch(case, br2, atol=1e-9)
        ends.append(u[-1])
    assert ends[0] == -ends[1]  # the two directions leave the branch point on opposite sides


# ---------------------------------------------------------------------------------------------
# 4. Truss + spring snap-back under displacement control
# ---------------------------------------------------------------------------------------------


def test_snapback_references():
    (v1, d1, _), (v2, d2, _) = ex.snapback_turning_points()
    assert v1 == 0.05948328406145619  # docs/test-problems.md §4
    assert v1 + v2 == pytest.approx(0.2, rel=1e-15)  # symmetric about t = 0
    # snap-back iff k_s < K H^2: 0.005 < 0.0098518...
    K = 1 / 1.01**1.5
    assert 0.005 < K * 0.01
    # d delta/dv = 0 there, checked by mpmath differentiation of delta(v)
    with mp.workdps(40):
        Km = 1 / mp.mpf("1.01") ** mp.mpf(1.5)
        H, ks = mp.mpf("0.1"), mp.mpf("0.005")
        delta = lambda v: v + Km * v * (H - v) * (2 * H - v) / ks  # noqa: E731
        assert abs(mp.diff(delta, mp.mpf(v1))) < 1e-14
        assert float(delta(mp.mpf(v1))) == pytest.approx(d1, rel=1e-15)


def test_snapback_turning_points_with_monitor(strategy, special, state_rtol, assert_on_branch):
    """Unknowns (v, delta), free P; delta-turning points reported as folds w.r.t. "delta"."""
    case = ex.snapback_monitor(derivatives=strategy)
    br = trace(
        case.problem, u0=[0.0, 0.0], free="P", bounds={"v": (-0.05, 0.25)}, monitor=["delta"]
    )
    assert br.success, (br.status, br.message)
    assert br["v"][-1] == 0.25
    wrt = [sp.with_respect_to for sp in special(br, "fold")]
    assert wrt == ["P", "delta", "delta", "P"], wrt
    for sp, (v, d, P) in zip(
        special(br, "fold", "delta"), ex.snapback_turning_points(), strict=True
    ):
        assert sp.status == "converged"
        assert sp.values["delta"] == pytest.approx(d, rel=1e-12, abs=0)
        assert sp.values["v"] == pytest.approx(v, rel=max(state_rtol, 1e-9))
        # P is not stationary at a delta-turning point (dP/dv * v/P = -0.9): a state variable
        assert sp.values["P"] == pytest.approx(P, rel=state_rtol)
    for sp, (v, P) in zip(special(br, "fold", "P"), ex.truss_green_limits(H=0.1), strict=True):
        assert_fold(sp, "P", ("P", P), {"v": v}, state_rtol)
    assert_on_branch(case, br, atol=1e-10)


def test_snapback_turning_points_as_folds_of_the_control(
    strategy, special, state_rtol, assert_on_branch
):
    """Unknown v, free parameter delta: the snap-back points are ordinary folds in delta."""
    case = ex.snapback_control(derivatives=strategy)
    br = trace(case.problem, u0=[0.0], free="delta", bounds={"v": (-0.05, 0.25)})
    assert br.success, (br.status, br.message)
    folds = special(br, "fold")
    assert len(folds) == 2
    for sp, (v, d, _) in zip(folds, ex.snapback_turning_points(), strict=True):
        assert_fold(sp, "delta", ("delta", d), {"v": v}, state_rtol)
    assert folds[0].values["v"] == pytest.approx(0.05948328406145619, rel=state_rtol)
    assert_on_branch(case, br, atol=1e-10)


# ---------------------------------------------------------------------------------------------
# 5. Shallow arch, two-mode Ritz model
# ---------------------------------------------------------------------------------------------


def test_arch_references():
    r6, r3 = ex.arch_references(6), ex.arch_references(3)
    assert r6["bp"][0][1] == pytest.approx(38.83281573, abs=5e-9)  # docs/test-problems.md §5
    assert r6["lp"][0][1] == pytest.approx(46.83718745, abs=5e-9)
    assert r6["bp"][0][1] == pytest.approx(12 + 6 * math.sqrt(20), rel=1e-15)  # 2e + 6 sqrt(e^2-16)
    assert r3["bp"] == []
    assert math.sqrt(22) < 6  # the branch point comes first iff e > sqrt 22


@pytest.mark.parametrize("e", [3, 4.5, 5, 6])
def test_arch_references_against_sympy(e):
    """The closed forms of ex.arch_references checked by sympy: the limit points are the roots
    of dp/dx on the symmetric path p = 2x + x(x - 2e)(x - e)/2, e -+ sqrt((e^2 - 4)/3); the
    branch points the real roots of Q + 16 = x^2 - 2ex + 16; both evaluated at 40 digits give
    the same floats."""
    import sympy as sp

    x, ee = sp.symbols("x e", real=True)
    p = 2 * x + x * (x - 2 * ee) * (x - ee) / 2
    e_val = sp.nsimplify(e)
    lps = sorted(sp.solve(sp.diff(p, x).subs(ee, e_val), x), key=lambda r: float(r))
    closed = [e_val - sp.sqrt((e_val**2 - 4) / 3), e_val + sp.sqrt((e_val**2 - 4) / 3)]
    assert all(sp.simplify(a - b) == 0 for a, b in zip(lps, closed, strict=True))
    pe = p.subs(ee, e_val)
    ref = ex.arch_references(e)
    assert ref["lp"] == [(float(r.evalf(40)), float(pe.subs(x, r).evalf(40))) for r in lps]
    Q16 = (x**2 - 2 * ee * x + 16).subs(ee, e_val)
    bps = sorted((r for r in sp.solve(Q16, x) if r.is_real), key=lambda r: float(r))
    assert ref["bp"] == [(float(r.evalf(40)), float(pe.subs(x, r).evalf(40))) for r in bps]


def test_arch_e6_branch_point_before_limit_point(strategy, special, state_rtol, assert_on_branch):
    e = 6.0
    ref = ex.arch_references(e)
    case = ex.shallow_arch(e, derivatives=strategy)
    br = trace(case.problem, u0=[0.0, 0.0], free="p", bounds={"xi1": (-1.0, 12.0)})
    assert br.success, (br.status, br.message)
    order = [
        sp.kind
        for sp in sorted(br.special_points, key=lambda s: s.index)
        if sp.kind in ("fold", "branch_point")
    ]
    # xi1 = 1.528 (BP), 2.734 (LP), 9.266 (LP), 10.472 (BP)
    assert order == ["branch_point", "fold", "fold", "branch_point"], order
    for sp, (x1, p) in zip(special(br, "branch_point"), ref["bp"], strict=True):
        assert sp.status == "converged"
        assert sp.values["p"] == pytest.approx(p, rel=1e-10)
        assert sp.values["xi1"] == pytest.approx(x1, rel=1e-9)
        assert abs(sp.values["xi2"]) < 1e-10
    for sp, (x1, p) in zip(special(br, "fold"), ref["lp"], strict=True):
        assert_fold(sp, "p", ("p", p), {"xi1": x1}, state_rtol)
    assert_on_branch(case, br, atol=1e-9)


def test_arch_e6_switch_to_asymmetric_branch(special, assert_on_branch):
    """Asymmetric path: Q = -16, i.e. (xi1 - e)^2 + 4 xi2^2 = e^2 - 16, and p = 8e - 6 xi1."""
    e = 6.0
    case = ex.shallow_arch(e)
    br = trace(case.problem, u0=[0.0, 0.0], free="p", bounds={"xi1": (-1.0, 2.0)})
    bp = special(br, "branch_point")[0]
    br2 = trace(case.problem, u0=bp, free="p", direction=+1, bounds={"xi2": (-1.0, 1.0)})
    assert br2.success, (br2.status, br2.message)
    x1, x2, p = (np.asarray(br2[k]) for k in ("xi1", "xi2", "p"))
    assert abs(x2[-1]) == 1.0
    assert np.allclose((x1 - e) ** 2 + 4 * x2**2, e**2 - 16, rtol=0, atol=1e-8)
    assert np.allclose(p, 8 * e - 6 * x1, rtol=0, atol=1e-8)
    assert_on_branch(case, br2, atol=1e-9)


def test_arch_e3_limit_points_only(strategy, special, state_rtol, assert_on_branch):
    e = 3.0
    ref = ex.arch_references(e)
    case = ex.shallow_arch(e, derivatives=strategy)
    br = trace(case.problem, u0=[0.0, 0.0], free="p", bounds={"xi1": (-1.0, 6.0)})
    assert br.success, (br.status, br.message)
    assert not special(br, "branch_point")
    folds = special(br, "fold")
    assert len(folds) == 2
    for sp, (x1, p) in zip(folds, ref["lp"], strict=True):
        assert_fold(sp, "p", ("p", p), {"xi1": x1}, state_rtol)
    assert np.max(np.abs(br["xi2"])) < 1e-12
    assert_on_branch(case, br, atol=1e-9)


# ---------------------------------------------------------------------------------------------
# 6. Cohesive bar
# ---------------------------------------------------------------------------------------------


def test_cohesive_exponential_smooth_fold(strategy, special, state_rtol, assert_on_branch):
    """U = 2 e^{-W} + W from W = 0 (U = 2), U decreasing first: fold at W = ln 2."""
    case = ex.cohesive_exponential(2.0, derivatives=strategy)
    br = trace(case.problem, u0=[0.0], free="U", direction=-1, bounds={"W": (-1.0, 3.0)})
    assert br.success, (br.status, br.message)
    assert br["W"][-1] == 3.0
    folds = special(br, "fold")
    assert len(folds) == 1
    W, U = ex.cohesive_exponential_fold(
        2.0
    )  # 1 + ln 2 = 1.6931471805599453094172321214581765680755
    assert U == pytest.approx(1.693147180559945, rel=1e-15)  # docs/test-problems.md §6, 16 digits
    assert_fold(folds[0], "U", ("U", U), {"W": W}, state_rtol)
    assert_on_branch(case, br, atol=1e-10)


@pytest.mark.parametrize("strategy", ["analytic", "central"])
def test_cohesive_linear_softening_kinks_traced_through(strategy, special, assert_on_branch):
    """Bilinear law (see cusp.examples.cohesive_bilinear): U(W) has a kinked maximum
    U = l + w0 = 2.01 at W = w0 = 0.01 and a kinked minimum U = 1 at W = 1. Tracing in U must
    pass both without failing; a turning point there has no smooth fold, so if one is reported
    as *converged* it must sit on the kink."""
    ell, w0 = 2.0, 0.01
    case = ex.cohesive_bilinear(ell, w0, derivatives=strategy)
    br = trace(case.problem, u0=[0.0], free="U", bounds={"W": (-0.5, 1.5)})
    assert br.success, (br.status, br.message)
    W, U = np.asarray(br["W"]), np.asarray(br["U"])
    assert W[-1] == 1.5 and U[-1] == pytest.approx(1.5, abs=1e-12)
    assert np.all(np.diff(W) > 0)  # never turns back in W
    assert np.any((W > 0.2) & (W < 0.9))  # passed through the softening segment
    assert U.max() <= ell + w0 + 1e-9 and U.max() > 1.9
    kinks = {(w0, ell + w0), (1.0, 1.0)}
    for sp in special(br, "fold"):
        if sp.status == "converged":
            assert any(
                abs(sp.values["W"] - wk) < 1e-8 and abs(sp.values["U"] - uk) < 1e-8
                for wk, uk in kinks
            ), sp.values
    assert_on_branch(case, br, atol=1e-10)


def test_cohesive_linear_softening_under_crack_opening_control(special):
    """The same bilinear law with W as the free parameter and U the unknown (U - l s(W) - W = 0):
    W never turns, and the kinked maximum of U is a turning point w.r.t. the monitored U.
    The branch must pass it and both kinks; a converged fold w.r.t. U must sit on a kink."""
    ell, w0 = 2.0, 0.01
    prob = ex.cohesive_bilinear_opening(ell, w0, derivatives="central").problem
    br = trace(prob, u0=[0.0], free="W", bounds={"W": (-0.5, 1.5)}, monitor=["U"])
    assert br.success, (br.status, br.message)
    W, U = np.asarray(br["W"]), np.asarray(br["U"])
    assert W[-1] == 1.5 and U[-1] == pytest.approx(1.5, abs=1e-12)
    assert np.all(np.diff(W) > 0)
    s_of_w = np.where(W <= w0, W / w0, np.where(W <= 1, (1 - W) / (1 - w0), 0.0))
    assert np.allclose(U, ell * s_of_w + W, rtol=0, atol=1e-10)
    kinks = {(w0, ell + w0), (1.0, 1.0)}
    for sp in special(br, "fold"):
        if sp.status == "converged":
            assert any(
                abs(sp.values["W"] - wk) < 1e-8 and abs(sp.values["U"] - uk) < 1e-8
                for wk, uk in kinks
            ), sp.values


# ---------------------------------------------------------------------------------------------
# Order of branch point and limit point on either side of the published thresholds
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("H, bp_first", [(1.5, False), (2.0, True), (3.0, True)])
def test_truss_2dof_order_of_branch_and_limit_point(H, bp_first, special):
    """The branch point y^2 = H^2 - 2L^2 precedes the limit point y^2 = H^2/3 iff H > sqrt 3 L
    (here L = 1; H = 1.5 lies between sqrt 2 and sqrt 3: limit point first)."""
    ref = ex.truss_2dof_references(1.0, 1.0, H)
    case = ex.truss_2dof(1.0, 1.0, H)
    v_end = max(ref["bp_v"], ref["lp_v"]) + 0.2
    br = trace(case.problem, u0=[0.0, 0.0], free="P", bounds={"v": (-0.5, v_end)})
    assert br.success, (br.status, br.message)
    order = [
        sp.kind
        for sp in sorted(br.special_points, key=lambda s: s.index)
        if sp.kind in ("fold", "branch_point")
    ]
    assert order == (["branch_point", "fold"] if bp_first else ["fold", "branch_point"]), order
    bp, lp = special(br, "branch_point")[0], special(br, "fold")[0]
    assert bp.values["P"] == pytest.approx(ref["bp_P"], rel=1e-10)
    assert lp.values["P"] == pytest.approx(ref["lp_P"], rel=1e-12)


@pytest.mark.parametrize("e, bp_first", [(4.5, False), (5.0, True), (6.0, True)])
def test_arch_order_of_branch_and_limit_point(e, bp_first, special):
    """The first branch point precedes the first limit point iff e > sqrt 22 = 4.690."""
    ref = ex.arch_references(e)
    case = ex.shallow_arch(e)
    x_end = max(ref["bp"][0][0], ref["lp"][0][0]) + 0.5
    br = trace(case.problem, u0=[0.0, 0.0], free="p", bounds={"xi1": (-1.0, x_end)})
    assert br.success, (br.status, br.message)
    order = [
        sp.kind
        for sp in sorted(br.special_points, key=lambda s: s.index)
        if sp.kind in ("fold", "branch_point")
    ]
    assert order == (["branch_point", "fold"] if bp_first else ["fold", "branch_point"]), order
    assert special(br, "branch_point")[0].values["p"] == pytest.approx(ref["bp"][0][1], rel=1e-10)
    assert special(br, "fold")[0].values["p"] == pytest.approx(ref["lp"][0][1], rel=1e-12)
