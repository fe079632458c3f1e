"""The symmetric-branch-point examples (`cusp.examples.symmetric`, `symmetric_cells`), checked
without the continuation engine's tracing: with the hand-written functions, every reference
solves the residual; at a branch point ∂R/∂u has a one-dimensional kernel (the stated mode)
and [∂R/∂u, ∂R/∂p] has rank n − 1 (∂R/∂p in the range: a branch point of the curve in
(u, p)), at a fold it has rank n; the analytic derivatives agree with `check_jacobian`; the
other branches' closed forms solve the residual and leave the branch point along the mode;
and the references equal their closed forms (literals with their provenance) and a sympy
derivation of the trivial branch's determinant.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sps

import cusp.examples as ex
from cusp.continuation import check_jacobian

#: Set-up name → (example factory, its pitchforks).
SETUPS = {
    "lorenz_stenflo": (ex.lorenz_stenflo, ex.lorenz_stenflo_pitchforks),
    "chen": (ex.chen, ex.chen_pitchforks),
    "hopfield": (ex.hopfield, ex.hopfield_pitchforks),
    "chafee_infante_n5": (
        lambda **kw: ex.chafee_infante(5, **kw),
        lambda: ex.chafee_infante_pitchforks(5),
    ),
    "chafee_infante_n10": (
        lambda **kw: ex.chafee_infante(10, **kw),
        lambda: ex.chafee_infante_pitchforks(10),
    ),
    "chafee_infante_n11_sparse": (
        lambda **kw: ex.chafee_infante(11, sparse=True, **kw),
        lambda: ex.chafee_infante_pitchforks(11),
    ),
    "chafee_infante_n60_sparse": (
        lambda **kw: ex.chafee_infante(60, sparse=True, **kw),
        lambda: ex.chafee_infante_pitchforks(60),
    ),
    "brusselator_cells": (ex.brusselator_cells, ex.brusselator_cells_pitchforks),
    "cstr_pair": (ex.cstr_pair, lambda: ex.cstr_pair_references()[1]),
}
NAMES = sorted(SETUPS)

#: Singular values below this fraction of the largest count as zero (the references are
#: correct to rounding, ~1e-16 relative), above GAP as clearly nonzero.
ZERO = 1e-12
GAP = 1e-6


def dense(a):
    return a.toarray() if sps.issparse(a) else np.asarray(a, dtype=float)


def split(example, values):
    u = np.array([values[k] for k in example.unknowns], dtype=float)
    p = {k: float(values[k]) for k in example.params}
    return u, p


def augmented(example, u, p):
    """[∂R/∂u, ∂R/∂p] with p the free parameter (n × (n + 1))."""
    jac = dense(example.jacobian(u, p))
    return np.column_stack([jac, example.param_jacobian(u, p, example.free)])


def svals(a):
    return np.linalg.svd(a, compute_uv=False)


# ---------------------------------------------------------------------------------------------
# References: residual, rank
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", NAMES)
def test_references_solve_the_residual(name):
    example = SETUPS[name][0]()
    refs = example.references()
    assert refs
    for ref in refs:
        assert set(ref.values) == {*example.unknowns, *example.params}
        assert ref.free == (example.free,) and ref.kind in ("fold", "branch_point")
        lo, hi = example.bounds[example.free]
        assert lo < ref.values[example.free] < hi
        u, p = split(example, ref.values)
        scale = max(1.0, np.abs(dense(example.jacobian(u, p))).max() * max(1.0, np.abs(u).max()))
        assert np.abs(example.residual(u, p)).max() <= 1e-12 * scale, ref


@pytest.mark.parametrize("name", NAMES)
def test_branch_points_and_folds_have_the_right_rank(name):
    """Branch point: ∂R/∂u has one zero singular value and [∂R/∂u, ∂R/∂p] (n × (n + 1)) has
    rank n − 1; fold: ∂R/∂u has one zero singular value and [∂R/∂u, ∂R/∂p] rank n."""
    example = SETUPS[name][0]()
    for ref in example.references():
        u, p = split(example, ref.values)
        s = svals(dense(example.jacobian(u, p)))
        assert s[-1] <= ZERO * s[0], (ref, s[-1] / s[0])  # singular
        assert s[-2] >= GAP * s[0], (ref, s[-2] / s[0])  # a one-dimensional kernel
        sa = svals(augmented(example, u, p))  # n values
        if ref.kind == "branch_point":
            assert sa[-1] <= ZERO * sa[0], (ref, sa[-1] / sa[0])  # ∂R/∂p in the range
            assert sa[-2] >= GAP * sa[0], ref  # rank exactly n − 1
        else:
            assert sa[-1] >= GAP * sa[0], ref  # a fold: full rank


@pytest.mark.parametrize("name", NAMES)
def test_pitchforks_are_the_branch_point_references_and_their_modes_span_the_kernel(name):
    make, pitchforks = SETUPS[name]
    example = make()
    forks = pitchforks()
    refs = [r for r in example.references() if r.kind == "branch_point"]
    assert [pf.values for pf in forks] == [r.values for r in refs]
    for pf in forks:
        u, p = split(example, pf.values)
        jac = dense(example.jacobian(u, p))
        mode = np.asarray(pf.mode)
        assert mode.shape == (example.problem.n,)
        assert np.linalg.norm(jac @ mode) <= ZERO * np.linalg.norm(jac) * np.linalg.norm(mode)
        kernel = np.linalg.svd(jac)[2][-1]
        cos = abs(kernel @ mode) / np.linalg.norm(mode)
        assert cos == pytest.approx(1.0, abs=1e-12)


def test_the_rank_checks_are_not_vacuous():
    """A branch point moved along the trivial branch is no branch point, and a fold is not a
    branch point."""
    example = ex.hopfield()
    ref = example.references()[0]
    u, p = split(example, {**ref.values, "lam": ref.values["lam"] * (1 + 1e-6)})
    s = svals(dense(example.jacobian(u, p)))
    assert s[-1] > ZERO * s[0]
    cstr = ex.cstr_pair()
    fold = cstr.references()[0]
    assert fold.kind == "fold"
    sa = svals(augmented(cstr, *split(cstr, fold.values)))
    assert sa[-1] > GAP * sa[0]


# ---------------------------------------------------------------------------------------------
# Derivatives
# ---------------------------------------------------------------------------------------------


def _generic_point(example):
    """A point away from the branch points: every unknown and parameter moved off."""
    n = example.problem.n
    u = 0.3 + 0.05 * np.sin(np.arange(1, n + 1))  # no symmetry left
    p = {k: v + 0.37 for k, v in example.params.items()}
    return u, p


@pytest.mark.parametrize("name", NAMES)
def test_analytic_derivatives_agree_with_check_jacobian(name):
    example = SETUPS[name][0]()
    prob = example.problem
    assert prob.has_jacobian
    points = [(example.u0, None), _generic_point(example)]
    points += [split(example, ref.values) for ref in example.references()]
    for u, p in points:
        report = check_jacobian(prob, u, p)
        assert report.ok, report.message


@pytest.mark.parametrize("name", NAMES)
def test_analytic_derivatives_agree_with_complex_steps(name):
    example = SETUPS[name][0]()
    u, p = _generic_point(example)
    jac = dense(example.jacobian(u, p))
    h = 1e-30  # complex step: exact to rounding
    cs = np.column_stack([example.residual(u + h * 1j * e, p).imag / h for e in np.eye(u.size)])
    np.testing.assert_allclose(jac, cs, rtol=1e-12, atol=1e-12 * np.abs(jac).max())
    for k in p:
        pc = {**p, k: p[k] + h * 1j}
        dp = example.residual(u, pc).imag / h
        np.testing.assert_allclose(example.param_jacobian(u, p, k), dp, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("derivatives", ["central", "forward", "complex"])
def test_every_derivative_strategy_builds_the_same_problem(derivatives):
    for name in NAMES:
        make = SETUPS[name][0]
        analytic, other = make(), make(derivatives=derivatives)
        assert not other.problem.has_jacobian
        assert other.unknowns == analytic.unknowns and other.params == analytic.params
        np.testing.assert_array_equal(other.u0, analytic.u0)
        u, p = _generic_point(analytic)
        ja, jo = dense(analytic.problem.jacobian(u, p)), dense(other.problem.jacobian(u, p))
        assert np.allclose(jo, ja, rtol=1e-5, atol=1e-5 * np.abs(ja).max()), name


def test_sparse_chafee_infante_is_the_dense_one():
    u = np.linspace(-0.4, 0.7, 9)
    p = {"lam": 2.5}
    sparse, dense_ = ex.chafee_infante(9, sparse=True), ex.chafee_infante(9)
    assert sps.issparse(sparse.jacobian(u, p)) and not sps.issparse(dense_.jacobian(u, p))
    np.testing.assert_array_equal(dense(sparse.jacobian(u, p)), dense_.jacobian(u, p))
    np.testing.assert_array_equal(sparse.residual(u, p), dense_.residual(u, p))
    fd = ex.chafee_infante(9, sparse=True, derivatives="central")
    assert sps.issparse(fd.problem.jacobian(u, p))


# ---------------------------------------------------------------------------------------------
# The other branches
# ---------------------------------------------------------------------------------------------

#: Amplitudes at which the other branches' closed forms are evaluated (within their domain:
#: |a| < μ for the Hopfield network, |a| < 1 for Chafee–Infante, |ξ| < A for the cells).
AMPLITUDES = (-0.45, -0.1, 1e-3, 0.2, 0.45)


def _closed_form_forks():
    out = []
    for name in NAMES:
        for i, pf in enumerate(SETUPS[name][1]()):
            if pf.point is not None:
                out.append(pytest.param(name, i, id=f"{name}-{i}"))
    return out


@pytest.mark.parametrize(("name", "i"), _closed_form_forks())
def test_other_branch_closed_form_solves_the_residual(name, i):
    example = SETUPS[name][0]()
    pf = SETUPS[name][1]()[i]
    for amp in AMPLITUDES:
        values = pf.point(amp)
        u, p = split(example, values)
        scale = max(1.0, np.abs(dense(example.jacobian(u, p))).max() * max(1.0, np.abs(u).max()))
        assert np.abs(example.residual(u, p)).max() <= 1e-12 * scale, amp
        assert max(abs(float(r)) for r in pf.other(values)) <= 1e-12 * scale, amp
        # a pitchfork: the free parameter is even in the amplitude
        assert pf.point(-amp)[example.free] == pytest.approx(values[example.free], rel=1e-14)
    # it starts at the branch point, along the mode
    start = pf.point(0.0)
    assert start == pytest.approx(pf.values, rel=1e-14, abs=1e-300)
    h = 1e-5
    plus, minus = split(example, pf.point(h))[0], split(example, pf.point(-h))[0]
    direction = (plus - minus) / (2 * h)
    mode = np.asarray(pf.mode)
    cos = abs(direction @ mode) / (np.linalg.norm(direction) * np.linalg.norm(mode))
    assert cos == pytest.approx(1.0, abs=1e-9)


@pytest.mark.parametrize(("name", "i"), _closed_form_forks())
def test_other_branch_closed_form_rejects_the_trivial_branch(name, i):
    """Off the branch point the trivial branch does not satisfy the other branch's closed
    form (so a switching test using it cannot pass on the wrong branch)."""
    example = SETUPS[name][0]()
    pf = SETUPS[name][1]()[i]
    free = example.free
    moved = dict(pf.values)
    moved[free] = pf.values[free] * 1.05
    if name == "brusselator_cells":  # the homogeneous state moves with B: y = B/A
        moved["y1"] = moved["y2"] = moved["B"] / moved["A"]
    u, p = split(example, moved)
    assert np.abs(example.residual(u, p)).max() < 1e-12  # still on the trivial branch
    assert max(abs(float(r)) for r in pf.other(moved)) > 1e-3


def test_other_branches_that_have_no_closed_form():
    """Chafee–Infante: only the modes with 2k = n + 1 or 3k = n + 1 have one (n = 5: k = 3
    and k = 2; n = 8: k = 3; n = 10: none of k = 1 … 3); the coupled tanks: none."""
    assert [pf.point is None for pf in ex.chafee_infante_pitchforks(5)] == [True, False, False]
    assert [pf.point is None for pf in ex.chafee_infante_pitchforks(8)] == [True, True, False]
    assert all(pf.point is None for pf in ex.chafee_infante_pitchforks(10))
    assert all(pf.other is None for pf in ex.cstr_pair_references()[1])


def test_pitchfork_table_covers_the_new_catalogue_entries():
    new = {"lorenz_stenflo", "chen", "hopfield", "chafee_infante", "chafee_infante_sparse"}
    new |= {"brusselator_cells", "cstr_pair"}
    assert set(ex.PITCHFORKS) == new and new <= set(ex.CATALOGUE)
    for name, forks in ex.PITCHFORKS.items():
        example = ex.CATALOGUE[name]()
        refs = [r.values for r in example.references() if r.kind == "branch_point"]
        assert [pf.values for pf in forks()] == refs


# ---------------------------------------------------------------------------------------------
# The references against their closed forms and literals
# ---------------------------------------------------------------------------------------------


def test_lorenz_stenflo_and_chen_references():
    (pf,) = ex.lorenz_stenflo_pitchforks()
    assert pf.values["r"] == 2.5  # r_c = 1 + s/a² = 1 + 1.5/1² (exact in binary)
    assert pf.mode == (1.0, 2.5, 0.0, -1.0)  # (1, r_c, 0, −1/a) with a = 1
    (pf,) = ex.chen_pitchforks()
    assert pf.values["c"] == 17.5  # c = a/2 = 35/2 (Chen & Ueta's a = 35)
    assert pf.mode == (1.0, 1.0, 0.0)  # x = y from a (y − x) = 0, z from x y − b z


def test_hopfield_weights_and_references():
    W = ex.hopfield_weights()
    # by hand: W_ij = (3 + 2 ξ²_i ξ²_j + ξ³_i ξ³_j)/4 − (3/2) δ_ij
    expected = [[0, 1, 0.5, 0], [1, 0, 0, 0.5], [0.5, 0, 0, 1], [0, 0.5, 1, 0]]
    np.testing.assert_array_equal(W, expected)
    # eigenvalues c_p − c̄ = 3 − 3/2, 2 − 3/2, 1 − 3/2 on the patterns, −3/2 on (1, −1, −1, 1)
    np.testing.assert_allclose(np.linalg.eigvalsh(W), [-1.5, -0.5, 0.5, 1.5], atol=1e-15)
    forks = ex.hopfield_pitchforks()
    assert [pf.values["lam"] for pf in forks] == [2 / 3, 2.0]  # λ = 1/μ, μ = 3/2, 1/2
    assert [pf.mode for pf in forks] == [(1, 1, 1, 1), (1, 1, -1, -1)]  # ξ¹, ξ² (stored)


def test_chafee_infante_references():
    # n = 5, h = π/6: λ_k = (4/h²) sin²(kπ/12) = (144/π²) sin²(kπ/12), with
    # sin²(π/12) = (2 − √3)/4, sin²(π/6) = 1/4, sin²(π/4) = 1/2
    lam = [pf.values["lam"] for pf in ex.chafee_infante_pitchforks(5)]
    closed = [36 * (2 - math.sqrt(3)) / math.pi**2, 36 / math.pi**2, 72 / math.pi**2]
    assert lam == pytest.approx(closed, rel=1e-15)
    # mpmath, 40 digits: h = mp.pi/6; [4/h**2*mp.sin(k*h/2)**2 for k in (1, 2, 3)]
    assert lam == pytest.approx(
        [0.97736145599267588752, 3.647562611124159772, 7.295125222248319544], rel=1e-16
    )
    # n = 10, same snippet with h = mp.pi/11 (λ_4 = 14.33 is outside the window λ ≤ 10)
    lam = [pf.values["lam"] for pf in ex.chafee_infante_pitchforks(10)]
    assert lam == pytest.approx(
        [0.99322120592894863805, 3.8924199485253852643, 8.462720387862970182], rel=1e-16
    )
    # the modes sin(k x_i): n = 5, k = 3 is (1, 0, −1, 0, 1), k = 2 is (√3/2)(1, 1, 0, −1, −1)
    modes = [pf.mode for pf in ex.chafee_infante_pitchforks(5)]
    np.testing.assert_allclose(modes[2], [1, 0, -1, 0, 1], atol=1e-15)
    np.testing.assert_allclose(modes[1], np.sqrt(3) / 2 * np.array([1, 1, 0, -1, -1]), atol=1e-15)


def test_chafee_infante_large_n_references_are_the_laplacians_eigenvalues():
    """n = 500 (sparse): the three references are the smallest eigenvalues of −Δ_h, computed
    here by LAPACK's tridiagonal eigensolver, and approach the continuum k² like
    k² (1 − k² h²/12) (the Taylor expansion of (4/h²) sin²(k h/2))."""
    from scipy.linalg import eigh_tridiagonal

    n = 500
    h = math.pi / (n + 1)
    example = ex.chafee_infante(n, sparse=True)
    lam = [r.values["lam"] for r in example.references()]
    eig = eigh_tridiagonal(np.full(n, 2 / h**2), np.full(n - 1, -1 / h**2), eigvals_only=True)
    # LAPACK's eigenvalues are accurate to a few ε‖Δ_h‖ = ε·4/h² ≈ 2e-11 absolute
    assert lam == pytest.approx(list(eig[:3]), rel=0, abs=50 * np.finfo(float).eps * 4 / h**2)
    for k, value in enumerate(lam, start=1):
        assert value == pytest.approx(k**2 * (1 - k**2 * h**2 / 12), rel=k**4 * h**4)


def test_chafee_infante_bifurcation_coefficient():
    """The docstring's λ ≈ λ_k (1 + c a²), c = Σ sin⁴/Σ sin² over the nodes (Lyapunov–Schmidt
    on the mode): sin⁴ = 3/8 − cos(2θ)/2 + cos(4θ)/8 and Σ_i cos(2π m i/(n + 1)) vanishes
    unless n + 1 divides m, so c = 3/4, or 1 where 2k = n + 1; checked against the exact
    branch of n = 5, k = 3 (c = 1)."""
    cases = ((10, 1, 0.75), (10, 3, 0.75), (5, 1, 0.75), (5, 3, 1.0), (7, 2, 0.75), (7, 4, 1.0))
    for n, k, c in cases:
        s = np.sin(k * np.pi * np.arange(1, n + 1) / (n + 1))
        assert (s**4).sum() / (s**2).sum() == pytest.approx(c, rel=1e-14)
    pf = ex.chafee_infante_pitchforks(5)[2]
    a = 1e-4  # λ = λ_3/(1 − a²) = λ_3 (1 + a² + O(a⁴))
    assert pf.point(a)["lam"] == pytest.approx(pf.values["lam"] * (1 + a**2), rel=1e-15)


def test_brusselator_cells_references():
    (pf,) = ex.brusselator_cells_pitchforks()
    # B_c = (1 + 2Dx)(1 + A²/(2Dy)) = 1.8 · 1.5 = 2.7 with A = 2, Dx = 0.4, Dy = 4
    assert pf.values["B"] == pytest.approx(2.7, rel=1e-15)
    assert pf.values["y1"] == pf.values["y2"] == pytest.approx(1.35, rel=1e-15)  # B_c/A
    # (A², −c, −A², c), c = B_c − 1 − 2Dx = 0.9
    np.testing.assert_allclose(pf.mode, [4, -0.9, -4, 0.9], rtol=1e-15)
    # supercritical: B(ξ) − B_c ≈ (1 + 2Dx)(4Dy/A² − 1) ξ²/(2Dy) = 1.8 · 3/8 ξ² = 0.675 ξ²
    xi = 1e-4
    assert ex.brusselator_cells_point(xi)["B"] - 2.7 == pytest.approx(0.675 * xi**2, rel=1e-3)


def test_cstr_pair_references():
    refs = ex.cstr_pair().references()
    assert [r.kind for r in refs] == ["fold", "branch_point", "branch_point", "fold"]
    x = [r.values["x1"] for r in refs]
    # folds: x (1 − x) = (1 + β)/B = 3/14, x = (1 ± √(1/7))/2;
    # branch points: x (1 − x) = (1 + β + 2κ)/B = 3.2/14, x = (1 ± √(3/35))/2
    r7, r35 = math.sqrt(1 / 7), math.sqrt(3 / 35)
    closed = [(1 - r7) / 2, (1 - r35) / 2, (1 + r35) / 2, (1 + r7) / 2]
    assert x == pytest.approx(closed, rel=1e-15)
    for r in refs:  # θ = k x, k = B/(1 + β) = 14/3; Da = x e^{−kx}/(1 − x)
        v = r.values
        assert v["x2"] == v["x1"] and v["theta1"] == v["theta2"]
        assert v["theta1"] == pytest.approx(14 / 3 * v["x1"], rel=1e-15)
        assert v["Da"] == pytest.approx(v["x1"] * math.exp(-v["theta1"]) / (1 - v["x1"]), rel=1e-14)
    # mpmath, 40 digits: x = (1 + sign*sqrt(1 - 4*q/B))/2, Da = x*exp(-k*x)/(1 - x) with
    # B = 14, q = 1 + beta (folds) and 1 + beta + 2*kappa (branch points), k = B/(1 + beta)
    da = [
        0.10573897827165065101,
        0.10504253864074781503,
        0.089521470760107885155,
        0.088931846185772802594,
    ]
    assert [r.values["Da"] for r in refs] == pytest.approx(da, rel=1e-15)
    forks = ex.cstr_pair_references()[1]
    for pf in forks:  # (x, 1/(1 − x), −x, −1/(1 − x))
        xb = pf.values["x1"]
        np.testing.assert_allclose(pf.mode, [xb, 1 / (1 - xb), -xb, -1 / (1 - xb)], rtol=1e-15)


# ---------------------------------------------------------------------------------------------
# A sympy derivation of the trivial branch's determinants
# ---------------------------------------------------------------------------------------------


def test_sympy_determinants_give_the_references():
    """The determinant of ∂R/∂u along each trivial branch, derived symbolically from the
    equations as printed in the docstrings (not from the example's code), vanishes exactly at
    the references' parameter values and nowhere else in the windows."""
    sp = pytest.importorskip("sympy")
    x, y, z, w, r, c = sp.symbols("x y z w r c")
    # Lorenz–Stenflo, a = 1, b = 7/10, s = 3/2
    a, b, s = 1, sp.Rational(7, 10), sp.Rational(3, 2)
    R = [a * (y - x) + s * w, r * x - x * z - y, x * y - b * z, -x - a * w]
    det = sp.Matrix(R).jacobian([x, y, z, w]).subs({x: 0, y: 0, z: 0, w: 0}).det()
    assert sp.solve(det, r) == [sp.Rational(5, 2)]
    # Chen, a = 35, b = 3
    R = [35 * (y - x), (c - 35) * x - x * z + c * y, x * y - 3 * z]
    det = sp.Matrix(R).jacobian([x, y, z]).subs({x: 0, y: 0, z: 0}).det()
    assert sp.solve(det, c) == [sp.Rational(35, 2)]
    # Chafee–Infante, n = 5: eigenvalues of −Δ_h are (2 − 2 cos(kπ/6))/h², h = π/6
    lap = sp.Matrix(5, 5, lambda i, j: -2 if i == j else (1 if abs(i - j) == 1 else 0))
    eig = sorted((-lap).eigenvals(), key=lambda e: float(e))
    h2 = (sp.pi / 6) ** 2
    lam = [pf.values["lam"] for pf in ex.chafee_infante_pitchforks(5)]
    assert [float(e / h2) for e in eig[:3]] == pytest.approx(lam, rel=1e-15)
    assert float(eig[3] / h2) > 10  # λ_4 = 3/h² = 10.94: outside the window
    # two Brusselator cells at the homogeneous state, A = 2, Dx = 2/5, Dy = 4
    B, x1, y1, x2, y2 = sp.symbols("B x1 y1 x2 y2")
    A, Dx, Dy = 2, sp.Rational(2, 5), 4
    R = [
        A - (B + 1) * x1 + x1**2 * y1 + Dx * (x2 - x1),
        B * x1 - x1**2 * y1 + Dy * (y2 - y1),
        A - (B + 1) * x2 + x2**2 * y2 + Dx * (x1 - x2),
        B * x2 - x2**2 * y2 + Dy * (y1 - y2),
    ]
    hom = {x1: A, y1: B / A, x2: A, y2: B / A}
    det = sp.Matrix(R).jacobian([x1, y1, x2, y2]).subs(hom).det()
    assert sp.solve(det, B) == [sp.Rational(27, 10)]
    # two tanks on the symmetric branch θ = k x, Da = x e^{−kx}/(1 − x), B = 14, β = 2,
    # κ = 1/10: the roots x in (0, 1) of the determinant
    Da, t1, t2, xs = sp.symbols("Da theta1 theta2 xs")
    Bt, beta, kappa = 14, 2, sp.Rational(1, 10)
    R = [
        -x1 + Da * (1 - x1) * sp.exp(t1),
        -t1 + Bt * Da * (1 - x1) * sp.exp(t1) - beta * t1 + kappa * (t2 - t1),
        -x2 + Da * (1 - x2) * sp.exp(t2),
        -t2 + Bt * Da * (1 - x2) * sp.exp(t2) - beta * t2 + kappa * (t1 - t2),
    ]
    k = sp.Rational(Bt, 1 + beta)
    sym = {x1: xs, x2: xs, t1: k * xs, t2: k * xs, Da: xs * sp.exp(-k * xs) / (1 - xs)}
    det = sp.simplify(sp.Matrix(R).jacobian([x1, t1, x2, t2]).subs(sym).det())
    roots = sorted(float(v) for v in sp.solve(sp.numer(sp.together(det)), xs))
    assert roots == pytest.approx([r.values["x1"] for r in ex.cstr_pair().references()], rel=1e-14)
