"""Self-checks of `cusp.examples`, so that neither the problems nor their references can
silently rot: every example evaluates at its start; its hand-written Jacobian and parameter
derivatives agree with finite differences (`check_jacobian`) and with complex steps; every
derivative strategy builds the same problem; and every stated reference satisfies its defining
equations (a fold: residual and det ∂G/∂z vanish, [J, ∂F/∂p] keeps full rank; a branch point:
[J, ∂F/∂p] loses rank; a cusp: also ⟨w, D²G[v, v]⟩ = 0). No solver output is involved except
in the last tests (`Example.trace`).
"""

from __future__ import annotations

import subprocess
import sys

import mpmath as mp
import numpy as np
import pytest
import scipy.sparse as sps

import cusp.examples as ex
from cusp.continuation import check_jacobian

NAMES = sorted(ex.CATALOGUE)

#: A generic point per example (away from special points and from the kinks of the bilinear
#: law), where the derivatives are compared; parameters are shifted by 0.37 there.
POINTS = {
    "cusp_normal_form": [0.3],
    "transcritical": [0.3],
    "pitchfork": [0.3],
    "bratu": [0.1, 0.3, 0.4, 0.2, 0.05, 0.1, 0.3, 0.4, 0.2, 0.05],
    "bratu_sparse": [0.1, 0.3, 0.4, 0.2, 0.05, 0.1, 0.3, 0.4, 0.2, 0.05],
    "truss_green": [0.3],
    "truss_rotated": [0.3],
    "truss_2dof": [0.2, 0.7],
    "snapback_monitor": [0.05, 0.3],
    "snapback_control": [0.05],
    "shallow_arch": [1.3, 0.4],
    "cohesive_exponential": [0.4],
    "cohesive_bilinear": [0.5],
    "cohesive_bilinear_opening": [0.3],
    "co_oxidation": [0.04, 0.35, 0.45],
    "ab_reactor": [0.3, 1.5],
    "pp2": [0.5, 0.2],
    "logistic_map": [0.3],
    "dd2": [0.3, 0.2],
    "enz": [0.5, 2.0],
    "cstr": [0.3, 1.5],
    "gray_scott": [0.6, 0.3],
    "brusselator": [2.1, 1.9, 2.2, 1.8, 2.3, 2.4, 2.2, 2.5],
    "lorenz": [0.5, 0.7, 0.3],
    "elastica": [0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5],
    "rigid_bar": [0.3],
    "rigid_bar_imperfect": [0.3],
    "subcritical_pitchfork": [0.3],
    "imperfect_transcritical": [0.3],
    "imperfect_pitchfork": [0.3],
    "narrow_transcritical": [0.3],
    "scaled_cusp": [0.3],
    "scaled_truss": [3e5],
    "scaled_ab": [3e5, 1.5e-6],
    "scaled_arch": [1.3, 0.4],
    "parallel_s_curves": [0.3],
    "lorenz_stenflo": [0.5, 0.7, 0.3, -0.2],
    "chen": [0.5, 0.7, 0.3],
    "hopfield": [0.3, -0.2, 0.5, 0.1],
    "chafee_infante": [0.1, 0.3, -0.4, 0.2, 0.05],
    "chafee_infante_sparse": [0.1, 0.3, -0.4, 0.2, 0.05, 0.1, 0.3, 0.4, -0.2, 0.05, 0.15],
    "brusselator_cells": [2.1, 0.6, 1.8, 0.7],
    "cstr_pair": [0.3, 1.5, 0.35, 1.6],
}


#: Examples with an unknown far below 1 in size (10⁻⁶): finite differences with the solver's
#: absolute step floor (central: ε^{1/3}·max(1, |x|) ≈ 6e-6) step over several times the
#: unknown itself, so away from the start their hand-written Jacobian is compared with
#: complex steps only (``test_analytic_derivatives_agree_with_complex_steps``).
TINY_UNKNOWNS = {"scaled_ab"}


def dense(a):
    return a.toarray() if sps.issparse(a) else np.asarray(a, dtype=float)


def test_catalogue_and_points_cover_the_same_examples():
    assert set(POINTS) == set(ex.CATALOGUE)


@pytest.mark.parametrize("name", NAMES)
def test_problem_evaluates_at_its_start(name):
    example = ex.CATALOGUE[name]()
    prob = example.problem
    assert example.u0.shape == (prob.n,)
    r = prob.residual(example.u0, prob.params)
    assert r.shape == (prob.n,) and np.all(np.isfinite(r))
    assert example.free in prob.params
    for key, (lo, hi) in example.bounds.items():
        assert key in (*prob.unknowns, example.free) and lo < hi
    assert set(example.monitor) <= set(prob.unknowns)
    assert example.unknowns == prob.unknowns and example.params == prob.params


@pytest.mark.parametrize("name", NAMES)
def test_analytic_derivatives_agree_with_finite_differences(name):
    example = ex.CATALOGUE[name]()
    prob = example.problem
    assert prob.has_jacobian
    report = check_jacobian(prob, example.u0)
    assert report.ok, report.message
    if name in TINY_UNKNOWNS:
        return
    u = np.asarray(POINTS[name], dtype=float)
    p = {k: v + 0.37 for k, v in prob.params.items()}
    report = check_jacobian(prob, u, p)
    assert report.ok, report.message


@pytest.mark.parametrize("name", NAMES)
def test_analytic_derivatives_agree_with_complex_steps(name):
    """Tighter than finite differences: the complex step is exact to rounding (every residual
    here is analytic near the point and accepts complex input)."""
    example = ex.CATALOGUE[name]()
    u = np.asarray(POINTS[name], dtype=float)
    p = {k: v + 0.37 for k, v in example.params.items()}
    jac = dense(example.jacobian(u, p))
    cs = np.column_stack([example.residual(u + 1e-30j * e, p).imag / 1e-30 for e in np.eye(u.size)])
    assert np.allclose(jac, cs, rtol=1e-12, atol=1e-12 * max(1.0, np.abs(jac).max()))
    h = 1e-6
    for k in p:
        pp, pm = dict(p), dict(p)
        pp[k] += h
        pm[k] -= h
        fdp = (example.residual(u, pp) - example.residual(u, pm)) / (2 * h)
        dp = example.param_jacobian(u, p, k)
        assert np.allclose(dp, fdp, rtol=1e-6, atol=1e-6), k


@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("derivatives", ["central", "forward", "complex"])
def test_every_derivative_strategy_builds_the_same_problem(name, derivatives):
    analytic = ex.CATALOGUE[name]()
    other = ex.CATALOGUE[name](derivatives=derivatives)
    assert not other.problem.has_jacobian and other.problem.derivatives == derivatives
    assert other.unknowns == analytic.unknowns and other.params == analytic.params
    np.testing.assert_array_equal(other.u0, analytic.u0)
    u = np.asarray(POINTS[name], dtype=float)
    p = analytic.params
    np.testing.assert_array_equal(other.problem.residual(u, p), analytic.problem.residual(u, p))
    ja, jo = dense(analytic.problem.jacobian(u, p)), dense(other.problem.jacobian(u, p))
    if name in TINY_UNKNOWNS and derivatives != "complex":
        return
    assert np.allclose(jo, ja, rtol=1e-5, atol=1e-5 * max(1.0, np.abs(ja).max()))


def test_unknown_derivative_strategy_is_rejected():
    with pytest.raises(ValueError, match="derivatives must be one of"):
        ex.cusp_normal_form(derivatives="backward")


def test_sparse_bratu_gives_sparse_jacobians():
    u = np.linspace(0.1, 0.7, 7)
    assert sps.issparse(ex.bratu(7, sparse=True).problem.jacobian(u, {"lam": 2.0}))
    assert sps.issparse(
        ex.bratu(7, sparse=True, derivatives="central").problem.jacobian(u, {"lam": 2.0})
    )
    assert not sps.issparse(ex.bratu(7).problem.jacobian(u, {"lam": 2.0}))


# ---------------------------------------------------------------------------------------------
# References satisfy their defining equations
# ---------------------------------------------------------------------------------------------


def _split(example, values):
    u = np.array([values[k] for k in example.unknowns], dtype=float)
    p = {k: float(values[k]) for k in example.params}
    return u, p


def _columns(example, u, p, names):
    """∂F/∂(names): Jacobian columns for unknowns, parameter derivatives for parameters."""
    jac = dense(example.jacobian(u, p))
    cols = []
    for name in names:
        if name in example.unknowns:
            cols.append(jac[:, example.unknowns.index(name)])
        else:
            cols.append(np.asarray(example.param_jacobian(u, p, name), dtype=float))
    return np.column_stack(cols)


def _variables(example, ref):
    """The variables of the fold system: the unknowns and the free parameter, without the one
    that turns (a fold in the free parameter: the unknowns)."""
    turning = ref.with_respect_to or ref.free[0]
    return [v for v in (*example.unknowns, ref.free[0]) if v != turning]


def _shifted(example, values, names, d):
    moved = dict(values)
    for name, dz in zip(names, d, strict=True):
        moved[name] = moved[name] + dz
    return _split(example, moved)


def _smallest_sv(a):
    return np.linalg.svd(a, compute_uv=False)[-1]


def _cusp_coefficient(example, ref, names):
    """⟨w, D²G[v, v]⟩ with unit null vectors of G's Jacobian in ``names``, by a central
    difference of that Jacobian along v, relative to the Jacobian's norm."""
    u, p = _split(example, ref.values)
    a = _columns(example, u, p, names)
    U, _, Vt = np.linalg.svd(a)
    v, w = Vt[-1], U[:, -1]
    h = 1e-5
    plus = _columns(example, *_shifted(example, ref.values, names, h * v), names)
    minus = _columns(example, *_shifted(example, ref.values, names, -h * v), names)
    return abs(w @ ((plus - minus) / (2 * h)) @ v) / max(1.0, np.linalg.norm(a))


def check_reference(example, ref):
    assert set(ref.values) == {*example.unknowns, *example.params}, ref
    assert ref.kind in ("fold", "branch_point", "cusp", "codim2", "kink"), ref
    u, p = _split(example, ref.values)
    jac = dense(example.jacobian(u, p))
    scale = max(1.0, np.abs(jac).max() * max(1.0, np.abs(u).max()))
    r = example.residual(u, p)
    assert np.abs(r).max() <= 1e-12 * scale, (ref, r)
    if ref.kind == "kink":
        return
    names = _variables(example, ref)
    full = [*example.unknowns, ref.free[0]]
    augmented = _columns(example, u, p, full)
    # the size of the derivatives: here, or at the start (where at a branch point of a normal
    # form they all vanish)
    size = max(
        np.linalg.norm(augmented),
        np.linalg.norm(_columns(example, example.u0, example.params, full)),
    )
    if ref.kind in ("fold", "cusp", "codim2"):
        assert _smallest_sv(_columns(example, u, p, names)) < 1e-9 * size, ref  # det = 0
    if ref.kind in ("fold", "cusp"):
        assert _smallest_sv(augmented) > 1e-6 * size, ref  # a fold, not a branch point
    if ref.kind in ("branch_point", "codim2"):
        assert _smallest_sv(augmented) < 1e-9 * size, ref  # [J, ∂F/∂p] loses rank
    if ref.kind == "cusp":
        assert _cusp_coefficient(example, ref, names) < 1e-7, ref


@pytest.mark.parametrize("name", NAMES)
def test_references_satisfy_their_defining_equations(name):
    example = ex.CATALOGUE[name]()
    refs = example.references()
    assert refs, name
    if name in RESCALED:  # checked in the base example's own variables
        check_rescaled_references(example, *RESCALED[name]())
        return
    for ref in refs:
        check_reference(example, ref)


#: The rescaled examples: their base example and factors. The rank tests of
#: ``check_reference`` compare derivative columns of very different sizes (a column scaled by
#: 10⁻⁸ looks singular), so their references are checked as the base example's references,
#: which satisfy their defining equations (above), multiplied by the factors.
RESCALED = {
    "scaled_cusp": lambda: (ex.cusp_normal_form(), {"b": 1e8}),
    "scaled_truss": lambda: (ex.truss_green(), {"v": 1e6}),
    "scaled_ab": lambda: (ex.ab_reactor(), {"u1": 1e6, "u2": 1e-6}),
    "scaled_arch": lambda: (ex.shallow_arch(6.0), {"p": 1e8}),
}


def check_rescaled_references(example, base, factors):
    """Each reference is the base example's, every value times its factor (to one rounding),
    the start and bounds likewise, and the scaled residual vanishes there as the base one
    does."""
    refs, base_refs = example.references(), base.references()
    assert len(refs) == len(base_refs)
    for ref, bref in zip(refs, base_refs):
        assert (ref.kind, ref.free, ref.with_respect_to) == (
            bref.kind,
            bref.free,
            bref.with_respect_to,
        )
        for k, v in bref.values.items():
            assert ref.values[k] == pytest.approx(v * factors.get(k, 1.0), rel=2.3e-16, abs=0)
        u, p = _split(example, ref.values)
        bu, bp = _split(base, bref.values)
        r, br = example.residual(u, p), base.residual(bu, bp)
        assert np.abs(r).max() <= 1e-12 * max(1.0, np.abs(dense(base.jacobian(bu, bp))).max())
        assert np.abs(br).max() <= 1e-12 * max(1.0, np.abs(dense(base.jacobian(bu, bp))).max())
    scale = [factors.get(k, 1.0) for k in base.unknowns]
    np.testing.assert_array_equal(example.u0, base.u0 * np.array(scale))
    for k, (lo, hi) in base.bounds.items():
        assert example.bounds[k] == (lo * factors.get(k, 1.0), hi * factors.get(k, 1.0))


OTHER_PARAMETERS = {
    "cusp a=0.02": lambda: ex.cusp_normal_form(a=0.02, b=-1.0),
    "cusp a=5": lambda: ex.cusp_normal_form(a=5.0, b=-9.0),
    "bratu N=1": lambda: ex.bratu(1),
    "bratu N=2": lambda: ex.bratu(2),
    "bratu N=31 sparse": lambda: ex.bratu(31, sparse=True),
    "truss_green H=0.1": lambda: ex.truss_green(H=0.1),
    "truss_2dof H=1.5": lambda: ex.truss_2dof(H=1.5),
    "truss_2dof H=3": lambda: ex.truss_2dof(H=3.0),
    "arch e=3": lambda: ex.shallow_arch(3.0),
    "arch e=4.5": lambda: ex.shallow_arch(4.5),
    "snapback ks=0.008": lambda: ex.snapback_monitor(ks=0.008),
    "ab p3=1.5": lambda: ex.ab_reactor(p3=1.5),
    "ab p3=2.45": lambda: ex.ab_reactor(p3=2.45),
    "cusp a=1e-4": lambda: ex.cusp_normal_form(a=1e-4),
    "arch e=4.8": lambda: ex.shallow_arch(4.8),
    "truss_2dof H=1.8": lambda: ex.truss_2dof(H=1.8),
    "imperfect transcritical eps<0": lambda: ex.imperfect_transcritical(-3e-3),
}


@pytest.mark.parametrize("label", sorted(OTHER_PARAMETERS))
def test_references_at_other_parameters(label):
    example = OTHER_PARAMETERS[label]()
    for ref in example.references():
        check_reference(example, ref)


def test_rescaled_truss_small():
    """The truss with v scaled by 10⁻⁶ (a suite problem besides the CATALOGUE's 10⁶)."""
    check_rescaled_references(ex.scaled_truss(1e-6), ex.truss_green(), {"v": 1e-6})


def test_the_checks_are_not_vacuous():
    """A fold is not a cusp, a fold moved along its branch is no fold, a point off the branch
    fails the residual, and a fold is not a branch point."""
    example = ex.cusp_normal_form()
    fold = example.references()[0]
    assert _cusp_coefficient(example, fold, ["x"]) > 1.0
    x = fold.values["x"] + 1e-6
    moved = fold._replace(values={"x": x, "a": 1.0, "b": x**3 - x})
    with pytest.raises(AssertionError):
        check_reference(example, moved)  # det J = 6e-6 |x|
    off = fold._replace(values={**fold.values, "b": fold.values["b"] + 1e-9})
    with pytest.raises(AssertionError):
        check_reference(example, off)
    with pytest.raises(AssertionError):
        check_reference(example, fold._replace(kind="branch_point"))
    truss = ex.truss_2dof()
    bp = truss.references()[0]
    with pytest.raises(AssertionError):
        check_reference(truss, bp._replace(kind="fold"))


def test_co_literals_agree_with_the_mpmath_computation():
    """CO_CUSP and CO_FOLDS_K04 (from the sympy elimination in test_cusp_models.py) against
    the hand elimination of `co_cusp` / `co_folds`, both at 40 digits."""
    ref = ex.co_cusp()
    with mp.workdps(40):
        for name, lit in ex.CO_CUSP.items():
            assert abs(ref[name] - mp.mpf(lit)) <= mp.mpf("1e-36") * abs(ref[name]), name
    folds = ex.co_folds(0.4)
    assert [f["q2"] for f in folds] == [float(v) for v in ex.CO_FOLDS_K04]


def test_closed_forms_of_the_references():
    """The references equal their closed forms where there is one (evaluated in float)."""
    assert ex.cusp_start() == -1.324717957244746
    assert ex.cusp_folds(1.0) == ((-0.5773502691896257, 0.3849001794597505),) + (
        (0.5773502691896257, -0.3849001794597505),
    )
    a, b = ex.cusp_fold_curve([-0.5, 0.25])
    np.testing.assert_allclose(4 * a**3, 27 * b**2, rtol=1e-15)
    assert ex.bratu_fd_fold(1)[0] == pytest.approx(8 / np.e, rel=1e-15)
    assert ex.bratu_fd_fold(2)[0] == pytest.approx(9 / np.e, rel=1e-15)
    lam, state = ex.bratu_fd_fold_state(2)
    assert lam == ex.bratu_fd_fold(2)[0] and state == pytest.approx((1.0, 1.0), rel=1e-15)
    assert ex.arch_codim2()["e"] == pytest.approx(np.sqrt(22.0), rel=1e-15)
    assert ex.ab_cusp() == {"u1": 0.5, "u2": 2.0, "p1": np.exp(-2), "p2": 14.0, "p3": 2.5}
    thetas = [(7 - np.sqrt(7)) / 3, (7 + np.sqrt(7)) / 3]
    for f, th in zip(ex.ab_folds(), thetas, strict=True):
        assert f["u2"] == pytest.approx(th, rel=1e-15)
        assert f["p1"] == pytest.approx((th - 1) * np.exp(-th), rel=1e-14)
    assert ex.cohesive_exponential_fold(2.0) == pytest.approx((np.log(2), 1 + np.log(2)))
    assert ex.snapback_cusp()["ks"] == pytest.approx(0.01 / 1.01**1.5, rel=1e-15)


# ---------------------------------------------------------------------------------------------
# Import hygiene and the convenience tracer
# ---------------------------------------------------------------------------------------------


def test_import_and_construction_are_light():
    """Building every example imports no mpmath, sympy or matplotlib, and no layer above the
    engine."""
    code = (
        "import sys, cusp.examples as ex\n"
        "[make() for make in ex.CATALOGUE.values()]\n"
        "print(sorted(m for m in sys.modules if m.split('.')[0] in ('mpmath', 'sympy',"
        " 'matplotlib') or m.startswith(('cusp.models', 'cusp.app', 'cusp.verification',"
        " 'cusp.scenes'))))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]", out.stdout + out.stderr


def test_example_trace_uses_its_free_parameter_bounds_and_monitor():
    br = ex.cusp_normal_form().trace()
    assert br.success and br["b"][-1] == 1.0
    b = [sp.values["b"] for sp in br.special("fold")]
    assert b == pytest.approx([0.3849001794597505, -0.3849001794597505], rel=1e-12)
    snap = ex.snapback_monitor().trace()
    assert [sp.with_respect_to for sp in snap.special("fold")] == ["P", "delta", "delta", "P"]
    short = ex.cusp_normal_form().trace(bounds={"b": (-1.0, 0.0)})
    assert short["b"][-1] == 0.0


def test_closed_forms_of_the_suite_references():
    """The references of the suite's examples against their closed forms or published values,
    evaluated in float (independently of the mpmath code that produced them)."""
    # pp2: the fold on the prey branch, published with the problem (0.83292932223415686);
    # the branch points u1 = 1/3 (p1 = (2/3)/(1 − e^{−5/3})) and u1 = 0 (p1 = 3/5)
    (_, uf, pf), (_, ub, pb), (_, u0, p0) = ex.pp2_references()
    assert pf == pytest.approx(0.83292932223415686, rel=1e-15)
    g = lambda u: 3 * u * (1 - u) / (1 - np.exp(-5 * u))  # noqa: E731
    assert g(uf) == pytest.approx(pf, rel=1e-15)
    assert (g(uf + 1e-6) < pf) and (g(uf - 1e-6) < pf)  # a maximum of p1 along the branch
    assert (ub, pb) == (1 / 3, pytest.approx((2 / 3) / (1 - np.exp(-5 / 3)), rel=1e-15))
    assert (u0, p0) == (0.0, 0.6)
    # enz: rho R'(s) = -1 at the folds, -3 at the branch points, s0 = s + rho R(s)
    for kind, s, s0 in ex.enz_symmetric_points():
        d = 1 + s + s**2
        assert 100 * (1 - s**2) / d**2 == pytest.approx(-1 if kind == "fold" else -3, rel=1e-12)
        assert s0 == pytest.approx(s + 100 * s / d, rel=1e-15)
    # CSTR: d ln Da/dx1 = 1/(x1 (1 - x1)) - k/(1 + k x1/gamma)^2 = 0, k = 16/3
    for f in ex.cstr_folds():
        x1, k = f["x1"], 16 / 3
        assert 1 / (x1 * (1 - x1)) == pytest.approx(k / (1 + k * x1 / 20) ** 2, rel=1e-12)
    # Gray-Scott (F = 0.04): fold k = sqrt(F)/2 - F = 0.06, v = sqrt(F) = 0.2, u = 1/2
    fold, bp = ex.gray_scott_references(0.04)
    assert fold[1] == pytest.approx({"u": 0.5, "v": 0.2, "k": 0.06}, rel=1e-15)
    assert bp[1] == {"u": 1.0, "v": 0.0, "k": -0.04}
    # Brusselator: every branch point makes the mode's 2 x 2 block singular
    c = ex.BRUSSELATOR
    for L, k in ex.brusselator_branch_points(4):
        m = 4 * 25 * np.sin(k * np.pi / 10) ** 2 / L**2
        block = [[c["B"] - 1 - c["Dx"] * m, c["A"] ** 2], [-c["B"], -(c["A"] ** 2) - c["Dy"] * m]]
        assert abs(np.linalg.det(block)) < 1e-9 * m**2 * c["Dx"] * c["Dy"]
    # elastica: the buckling loads 4n² sin²((2k − 1)π/(4n)), near the continuum ((2k − 1)π/2)²
    for k, P in enumerate(ex.elastica_buckling_loads(10)[:2], start=1):
        assert P == pytest.approx(400 * np.sin((2 * k - 1) * np.pi / 40) ** 2, rel=1e-14)
        assert P == pytest.approx(((2 * k - 1) * np.pi / 2) ** 2, rel=2e-2)
    # rigid bar: Koiter's two-thirds law, exact for this model
    theta, P = ex.rigid_bar_limit(0.01)
    assert np.sin(theta) ** 3 == pytest.approx(np.sin(0.01), rel=1e-14)
    assert P == pytest.approx((1 - np.sin(0.01) ** (2 / 3)) ** 1.5, rel=1e-14)
    # imperfect normal forms
    (fold,) = ex.imperfect_transcritical(5e-4).references()
    assert fold.values["x"] ** 2 == pytest.approx(5e-4) and fold.values["p"] == -2 * np.sqrt(5e-4)
    (fold,) = ex.imperfect_pitchfork(2e-3).references()
    assert fold.values["x"] == pytest.approx(0.1, rel=1e-15)
    assert fold.values["p"] == pytest.approx(-0.03, rel=1e-15)
