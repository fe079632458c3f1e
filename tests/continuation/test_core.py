"""Unit tests of the continuation core: options, problems, derivatives, events, targets,
bounds, failures, the step-level API and branch switching.

The published benchmark problems (docs/test-problems.md) are in test_published.py.
"""

import math
import subprocess
import sys

import numpy as np
import pytest
import scipy.sparse as sp

import cusp.examples as ex
from cusp.continuation import (
    ContinuationOptions,
    ConvergenceError,
    Event,
    MaxStepsWarning,
    NonFiniteResidualError,
    OptionsError,
    Problem,
    ProblemDefinitionError,
    StepGuardError,
    Tracer,
    check_jacobian,
    trace,
)

# cusp normal form x^3 - a x - b: folds at x = ±sqrt(a/3), b = ∓2 (a/3)^{3/2};
# at a = 1: |b| = 2/(3√3) = 0.38490017945975050967... (mpmath: 2/(3*mp.sqrt(3)))
B_FOLD = 2.0 / (3.0 * math.sqrt(3.0))
X0 = ex.cusp_start()  # -1.324717957244746, real root of x^3 - x + 1 (the plastic number, negated)


def cusp_problem(derivatives="central", analytic=False):
    return ex.cusp_normal_form(derivatives="analytic" if analytic else derivatives).problem


def folds(br, wrt=None):
    return [
        sp_
        for sp_ in br.special_points
        if sp_.kind == "fold" and (wrt is None or sp_.with_respect_to == wrt)
    ]


# --- --- options


@pytest.mark.parametrize(
    "field, value, fragment",
    [
        ("ds", 0.0, "'ds' must be a finite number > 0"),
        ("ds", float("nan"), "'ds'"),
        ("ds_max", -1.0, "'ds_max'"),
        ("tol", float("inf"), "'tol'"),
        ("max_steps", 0, "'max_steps' must be an integer >= 1"),
        ("max_steps", 2.5, "'max_steps'"),
        ("predictor", "euler", "'predictor' must be one of"),
        ("max_angle", 200.0, "'max_angle'"),
    ],
)
def test_options_validated_with_field_and_value(field, value, fragment):
    with pytest.raises(OptionsError, match=fragment) as info:
        ContinuationOptions(**{field: value})
    assert repr(value) in str(info.value) or field in str(info.value)
    assert isinstance(info.value, ValueError)


def test_options_inconsistent_bounds():
    with pytest.raises(OptionsError, match="ds_min"):
        ContinuationOptions(ds_min=1.0, ds_max=0.1, ds=0.5)
    with pytest.raises(OptionsError, match="unknown option"):
        ContinuationOptions().replace(dsmax=1.0)
    # overriding only ds_max keeps the default initial step inside it
    assert ContinuationOptions().replace(ds_max=0.01).ds == 0.01


def test_trace_rejects_unknown_keyword():
    # the entry points spell out their keywords (options among them): an unknown one is
    # Python's TypeError naming it; ContinuationOptions.replace names the allowed ones
    with pytest.raises(TypeError, match="step_size"):
        trace(cusp_problem(), [X0], free="b", step_size=0.1)
    with pytest.raises(OptionsError, match=r"unknown option\(s\) \['step_size'\]; allowed"):
        ContinuationOptions().replace(step_size=0.1)


# --- --- problems


def test_problem_validation_messages():
    f = lambda u, p: u  # noqa: E731
    with pytest.raises(ProblemDefinitionError, match="repeated"):
        Problem(f, ["x", "x"], {"a": 1.0})
    with pytest.raises(ProblemDefinitionError, match="'a' must be finite"):
        Problem(f, ["x"], {"a": float("nan")})
    with pytest.raises(ProblemDefinitionError, match="both an unknown and a parameter"):
        Problem(f, ["x"], {"x": 1.0})
    with pytest.raises(ProblemDefinitionError, match="derivatives must be one of"):
        Problem(f, ["x"], {"a": 1.0}, derivatives="symbolic")
    with pytest.raises(ProblemDefinitionError, match="free parameter 'c'"):
        trace(cusp_problem(), [X0], free="c")
    with pytest.raises(ProblemDefinitionError, match="u0 must hold 1 values"):
        trace(cusp_problem(), [X0, 0.0], free="b")


def test_wrong_residual_shape_is_reported():
    prob = Problem(lambda u, p: np.array([u[0], u[0]]), ["x"], {"a": 1.0})
    with pytest.raises(ProblemDefinitionError, match="must return 1 values"):
        trace(prob, [0.0], free="a")


def test_user_functions_may_return_lists_and_integer_arrays():
    # the branch system calls a Problem's own functions and normalises their results itself
    # (Problem.callbacks): lists, nested lists and integer arrays must trace exactly as floats
    def res(u, p):
        return [u[0] ** 3 - u[0] - p["b"]]

    lists = Problem(
        res,
        ["x"],
        {"b": -1.0},
        jacobian=lambda u, p: [[3 * u[0] ** 2 - 1]],
        param_jacobian=lambda u, p, n: np.array([-1]),
    )
    arrays = cusp_problem(analytic=True)
    a = trace(lists, [X0], free="b", bounds={"b": (-1.0, 1.0)})
    b = trace(arrays, [X0], free="b", bounds={"b": (-1.0, 1.0)})
    np.testing.assert_array_equal(a["x"], b["x"])
    np.testing.assert_array_equal(a["b"], b["b"])
    assert [sp_.values["b"] for sp_ in folds(a, "b")] == [sp_.values["b"] for sp_ in folds(b, "b")]


def test_bounds_on_fixed_parameter_rejected():
    with pytest.raises(ProblemDefinitionError, match="fixed parameters cannot be bounded"):
        trace(cusp_problem(), [X0], free="b", bounds={"a": (0, 2)})


def test_start_outside_bounds_rejected():
    with pytest.raises(ProblemDefinitionError, match=r"outside bounds\['b'\]"):
        trace(cusp_problem(), [X0], free="b", bounds={"b": (0.0, 1.0)})


def test_start_not_converging_raises_with_remedy():
    # x^2 + b^2 + 1 = 0 has no real solution
    prob = Problem(lambda u, p: np.array([u[0] ** 2 + p["b"] ** 2 + 1.0]), ["x"], {"b": 0.0})
    with pytest.raises(ConvergenceError) as info:
        trace(prob, [0.3], free="b")
    err = info.value
    assert "better initial guess" in err.remedy
    assert err.iterations > 0 and err.residual_norm > 0.5
    assert "x=" in str(err) and "b=0" in str(err)


# --- --- folds and derivatives


@pytest.mark.parametrize(
    "derivatives, analytic",
    [("central", True), ("central", False), ("forward", False), ("complex", False)],
)
def test_cusp_folds_every_derivative_strategy(derivatives, analytic):
    br = trace(cusp_problem(derivatives, analytic), [X0], free="b", bounds={"b": (-1.0, 1.0)})
    assert br.status == "bound" and br.success
    assert br["b"][-1] == 1.0  # ends exactly on the bound
    f = folds(br, "b")
    assert len(f) == 2 and all(sp_.status == "converged" for sp_ in f)
    # the fold parameter is stationary: exact to rounding whatever the derivative strategy
    assert f[0].values["b"] == pytest.approx(B_FOLD, rel=1e-12)
    assert f[1].values["b"] == pytest.approx(-B_FOLD, rel=1e-12)
    # the fold state is limited by the accuracy of the Jacobian (forward differences ~1e-8)
    xtol = 1e-6 if derivatives == "forward" else 1e-9
    assert f[0].values["x"] == pytest.approx(-1 / math.sqrt(3), abs=xtol)
    # special points are inserted: branch arrays hold their values at their index
    for sp_ in br.special_points:
        assert br["x"][sp_.index] == sp_.values["x"]
        assert br["b"][sp_.index] == sp_.values["b"]
    assert np.all(np.diff(br.s) >= 0)


def test_stats_are_per_point():
    br = trace(cusp_problem(analytic=True), [X0], free="b", bounds={"b": (-1.0, 1.0)})
    for key in ("newton_iterations", "rejected_steps", "residual_norm", "ds"):
        assert br.stats[key].shape == (len(br),)
    assert np.all(br.stats["residual_norm"] < 1e-9)
    # points inserted inside a step (the two folds) have no step of their own; the bound
    # b = 1 ends the last step, which was aimed at it
    inserted = {sp.index for sp in br.special_points if sp.kind == "fold"}
    ds = br.stats["ds"]
    assert {i for i in range(len(br)) if ds[i] == 0.0} == inserted
    assert all(br.stats["newton_iterations"][i] >= 1 for i in inserted)
    assert ds[-1] == pytest.approx(br.s[-1] - br.s[-2], rel=1e-12)


def test_check_jacobian_finds_wrong_entry():
    example = ex.cusp_normal_form()
    good = example.problem
    assert check_jacobian(good, [0.7], {"a": 1.0, "b": 0.2}).ok
    bad = Problem(
        example.residual,
        ["x"],
        {"a": 1.0, "b": -1.0},
        jacobian=lambda u, p: np.array([[3 * u[0] ** 2 + p["a"]]]),  # sign error
        param_jacobian=example.param_jacobian,
    )
    report = check_jacobian(bad, [0.7], {"a": 1.0, "b": 0.2})
    assert not report.ok
    assert report.worst[0][:2] == (0, "x")
    assert "row 0, d/dx" in report.message


def test_from_sympy_gives_exact_derivatives():
    sympy = pytest.importorskip("sympy")
    from cusp.continuation import from_sympy

    x, a, b = sympy.symbols("x a b")
    prob = from_sympy([x**3 - a * x - b], [x], {a: 1.0, b: -1.0})
    assert check_jacobian(prob, [0.3], {"a": 1.0, "b": 0.1}, rtol=1e-9).ok
    br = trace(prob, [X0], free="b", bounds={"b": (-1.0, 1.0)})
    assert sorted(sp_.values["b"] for sp_ in folds(br)) == pytest.approx(
        [-B_FOLD, B_FOLD], rel=1e-13
    )
    with pytest.raises(ProblemDefinitionError, match="neither unknowns"):
        from_sympy([x - sympy.Symbol("c")], [x], {a: 1.0})


def test_import_is_light():
    code = (
        "import sys, cusp.continuation; "
        "print(any(m.split('.')[0] in ('sympy', 'matplotlib') for m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


# --- --- targets, events, bounds


def test_targets_hit_exactly():
    br = trace(
        cusp_problem(analytic=True),
        [X0],
        free="b",
        bounds={"b": (-1.0, 1.0)},
        targets={"b": [0.1, 0.2], "x": [0.0]},
    )
    tb = [sp_ for sp_ in br.special_points if sp_.kind == "target" and sp_.with_respect_to == "b"]
    # b = 0.1 and 0.2 are each crossed three times (the S-shaped branch)
    assert sorted({sp_.values["b"] for sp_ in tb}) == [0.1, 0.2]
    assert len(tb) == 6
    tol = ContinuationOptions().tol  # the corrector's residual tolerance
    for sp_ in tb:
        x = sp_.values["x"]
        assert abs(x**3 - x - sp_.values["b"]) < tol
    tx = [sp_ for sp_ in br.special_points if sp_.with_respect_to == "x" and sp_.kind == "target"]
    assert len(tx) == 1 and tx[0].values["x"] == 0.0 and abs(tx[0].values["b"]) < 1e-14


def test_event_located_inserted_and_direction():
    # x^2 - 0.25 vanishes at x = ±1/2 (b = ∓3/8): upward crossing at x = +1/2 only
    ev_any = Event(lambda u, p: u[0] ** 2 - 0.25, label="x2")
    ev_up = Event(lambda u, p: u[0] - 0.5, direction=+1, label="x up")
    ev_down = Event(lambda u, p: u[0] - 0.5, direction=-1, label="x down")
    br = trace(
        cusp_problem(analytic=True),
        [X0],
        free="b",
        bounds={"b": (-1.0, 1.0)},
        events=[ev_any, ev_up, ev_down],
    )
    evs = br.special("event", label="x2")
    assert [round(e.values["x"], 12) for e in evs] == [-0.5, 0.5]
    for e in evs:
        assert abs(e.values["x"] ** 2 - 0.25) < 1e-12
        assert abs(e.values["x"] ** 3 - e.values["x"] - e.values["b"]) < ContinuationOptions().tol
        assert br["x"][e.index] == e.values["x"]
    assert len(br.special("event", label="x up")) == 1
    assert br.special("event", label="x down") == []


def test_terminal_event_ends_branch():
    ev = Event(lambda u, p: u[0], terminal=True, label="x=0")
    br = trace(cusp_problem(analytic=True), [X0], free="b", events=[ev])
    assert br.status == "terminal_event" and br.success
    assert abs(br["x"][-1]) < 1e-12 and abs(br["b"][-1]) < 1e-12
    assert len(folds(br)) == 1


def test_bound_on_unknown_is_exact():
    br = trace(cusp_problem(analytic=True), [X0], free="b", bounds={"x": (-2.0, 0.25)})
    assert br.status == "bound"
    assert br["x"][-1] == 0.25
    assert br.special_points[-1].kind == "endpoint"
    assert br.special_points[-1].label == "bound x=0.25"


def test_last_step_is_aimed_at_a_transversal_bound():
    # b = 1 is crossed with the tangent 80° from parallel to it: the last step ends on it
    # (Newton with b fixed from the tangent line's crossing) instead of passing and locating
    br = trace(cusp_problem(analytic=True), [X0], free="b", bounds={"b": (-1.0, 1.0)})
    end = br.special_points[-1]
    assert end.label == "bound b=1" and end.status == "converged"
    assert end.details["method"] == "step aimed at the bound"
    assert br["b"][-1] == 1.0
    # x^3 - x - 1 = 0 at b = 1: the plastic number (mpmath.findroot(lambda x: x**3 - x - 1,
    # 1.3) = 1.32471795724474602596...)
    assert br["x"][-1] == pytest.approx(1.324717957244746, abs=1e-12)
    assert br.stats["residual_norm"][-1] <= 1e-10
    # the tangent there is the curve's, (dx, db) ∝ (1, 3x² − 1), oriented along the branch;
    # it comes from the corrector's last factorization, one update from the point (the
    # accuracy of every step's tangent: 1e-5 relative here)
    t = br.tangents[-1]
    x = br["x"][-1]
    assert t[1] / t[0] == pytest.approx(3 * x**2 - 1, rel=1e-4) and t[1] > 0


def test_grazing_bound_is_located_not_aimed():
    # x = 1.2 is met on the last stretch, where the branch runs at 73° to the x axis
    # (db/dx = 3x² − 1 ≈ 3.3): a step aimed at it could miss it, so the crossing is located
    # inside the step instead
    br = trace(
        cusp_problem(analytic=True), [X0], free="b", bounds={"b": (-1.0, 1.0), "x": (-2.0, 1.2)}
    )
    end = br.special_points[-1]
    assert br.status == "bound" and end.label == "bound x=1.2" and br["x"][-1] == 1.2
    assert end.details["method"] == "Newton with the component fixed"
    assert br.stats["ds"][-1] == 0.0  # a point located inside the last step
    assert br["b"][-1] == pytest.approx(1.2**3 - 1.2, abs=1e-12)  # b = x³ − x exactly


def test_max_steps_is_an_incomplete_end_with_a_warning():
    with pytest.warns(MaxStepsWarning, match=r"max_steps=5 steps at x=.*incomplete"):
        br = trace(cusp_problem(analytic=True), [X0], free="b", max_steps=5)
    assert br.status == "max_steps" and not br.success
    assert "max_steps=5" in br.message and "Raise max_steps" in br.message
    assert br.info["steps"] == 5


def test_direction_minus_one():
    br = trace(cusp_problem(analytic=True), [X0], free="b", direction=-1, bounds={"b": (-3.0, 1.0)})
    assert br["b"][-1] == -3.0 and folds(br) == []


# --- --- failures


def nan_beyond(limit):
    def res(u, p):
        if p["b"] > limit:
            return np.array([np.nan])
        return np.array([u[0] ** 3 - u[0] - p["b"]])

    return Problem(res, ["x"], {"b": -1.0})


def test_nonfinite_residual_stops_with_status():
    br = trace(nan_beyond(-0.5), [X0], free="b", throw=False)
    assert br.status == "nonfinite_residual" and not br.success
    assert "not finite" in br.message
    # it stops where the central-difference stencil (h = eps^(1/3)·max(1,|b|) ≈ 6e-6) starts
    # to reach into the region where the residual is NaN
    h = np.finfo(float).eps ** (1 / 3)
    assert -0.5 - 2 * h < br["b"][-1] <= -0.5
    assert np.all(np.isfinite(br["x"]))


def test_nonfinite_residual_raises_by_default():
    with pytest.raises(NonFiniteResidualError, match="not finite"):
        trace(nan_beyond(-0.5), [X0], free="b")


def test_nonfinite_start_raises():
    with pytest.raises(NonFiniteResidualError, match="starting point"):
        trace(nan_beyond(-2.0), [X0], free="b")


def _wrong_jacobian_beyond(b_wrong, factor):
    """x³ + x − b = 0 whose analytic Jacobian is off by ``factor`` for b > ``b_wrong``: the
    curve b = x³ + x is regular, but Newton on the wrong Jacobian contracts by
    |1 − 1/factor| whatever the step (0.67 for factor 0.6, above 4·target_contraction)."""

    def res(u, p):
        return np.array([u[0] ** 3 + u[0] - p["b"]])

    def jac(u, p):
        wrong = factor if p["b"] > b_wrong else 1.0
        return np.array([[wrong * (3 * u[0] ** 2 + 1)]])

    return Problem(res, ["x"], {"b": 0.0}, jacobian=jac)


def test_guard_failure_is_typed_and_keeps_the_partial_branch():
    prob = _wrong_jacobian_beyond(0.5, 0.6)
    br = trace(prob, [0.0], free="b", bounds={"b": (-1.0, 1.0)}, throw=False)
    assert br.status == "guard_failure" and not br.success
    # the partial branch: every point on the curve (Newton with the wrong Jacobian still
    # converges on steps short enough, so it may end a little past b = 0.5), and it ends
    # soon after the Jacobian goes wrong
    assert 0.45 < br["b"][-1] <= 0.6
    assert np.allclose(br["x"] ** 3 + br["x"], br["b"], rtol=0, atol=1e-10)
    # the message names the point, the guard and a remedy
    assert "contraction guard" in br.message and "check_jacobian" in br.message
    assert f"b={br['b'][-1]:.10g}" in br.message
    with pytest.raises(StepGuardError) as info:
        trace(prob, [0.0], free="b", bounds={"b": (-1.0, 1.0)})
    err = info.value
    assert isinstance(err, ConvergenceError) and err.guard == "contraction"
    assert err.values["b"] == br["b"][-1] and "throw=False" in err.remedy


def test_convergence_failure_partial_branch():
    # a jump in the residual at b = 0 that no corrector can cross
    def res(u, p):
        return np.array([u[0] - p["b"] + (1.0 if p["b"] > 0 else 0.0) * (1 + u[0] ** 2)])

    prob = Problem(res, ["x"], {"b": -1.0})
    br = trace(prob, [-1.0], free="b", throw=False, max_steps=500)
    assert br.status in ("convergence_failure", "max_steps", "bound")
    if br.status == "convergence_failure":
        assert "ds=" in br.message and not br.success
    with pytest.raises(ConvergenceError) as info:
        trace(prob, [-1.0], free="b", max_steps=500)
    assert info.value.ds <= ContinuationOptions().ds_min * 1.0001


# --- --- step-level API


def test_step_api_matches_trace():
    prob = cusp_problem(analytic=True)
    tracer = Tracer(prob, free="b", bounds={"b": (-1.0, 1.0)})
    state = tracer.init([X0])
    states = [state]
    while not tracer.done(state):
        state = tracer.step(state)
        states.append(state)
    assert states[0].steps == 0 and states[1].steps == 1  # records are replaced, not mutated
    br = tracer.result(state)
    ref = trace(prob, [X0], free="b", bounds={"b": (-1.0, 1.0)})
    np.testing.assert_array_equal(br["b"], ref["b"])
    # an intermediate state gives a partial branch that says so
    partial = tracer.result(states[3])
    assert partial.status == "running" and len(partial) < len(br)


def test_secant_predictor():
    br = trace(
        cusp_problem(analytic=True), [X0], free="b", bounds={"b": (-1.0, 1.0)}, predictor="secant"
    )
    assert [sp_.values["b"] for sp_ in folds(br)] == pytest.approx([B_FOLD, -B_FOLD], rel=1e-12)


# --- --- sparse and branch switching


def bratu(n, *, analytic=True):
    # a sparse analytic Jacobian, or central differences grouped by the tridiagonal pattern
    return ex.bratu(n, derivatives="analytic" if analytic else "central", sparse=True).problem


def test_sparse_fd_with_sparsity_pattern_matches_analytic():
    n = 40
    kw = dict(free="lam", bounds={"lam": (-0.1, 4.0), f"u{n // 2}": (-1.0, 2.0)})
    a = trace(bratu(n), np.zeros(n), **kw)
    b = trace(bratu(n, analytic=False), np.zeros(n), **kw)
    fa, fb = folds(a, "lam"), folds(b, "lam")
    assert len(fa) == len(fb) == 1
    assert fb[0].values["lam"] == pytest.approx(fa[0].values["lam"], rel=1e-11)
    assert sp.issparse(bratu(n, analytic=False).jacobian(np.zeros(n), {"lam": 1.0}))


@pytest.mark.parametrize("kind", ["transcritical", "pitchfork"])
def test_branch_switching_simple(kind):
    # transcritical x (p - x): branches x = 0 and x = p (not orthogonal: needs the ABE);
    # pitchfork x (p - x^2): branches x = 0 and p = x^2
    if kind == "transcritical":
        example = ex.transcritical(p=-1.0, derivatives="central")
        on_other = lambda x, p: x - p  # noqa: E731
    else:
        example = ex.pitchfork(p=-1.0, derivatives="central")
        on_other = lambda x, p: p - x**2  # noqa: E731
    prob = example.problem
    br = trace(prob, [0.0], free="p", bounds={"p": (-1.0, 1.0)})
    bps = br.special("branch_point")
    assert len(bps) == 1 and abs(bps[0].values["p"]) < 1e-10
    assert folds(br) == []
    for direction in (1, -1):
        other = trace(
            prob, bps[0], free="p", direction=direction, bounds={"p": (-1.0, 1.0), "x": (-0.9, 0.9)}
        )
        assert other.success and len(other) > 3
        assert np.max(np.abs(other["x"])) > 0.5  # really left the trivial branch
        assert np.max(np.abs(on_other(other["x"], other["p"]))) < 1e-9


def test_start_on_bound_and_leave_through_it():
    # the branch starts exactly on b = 1 and moves outward: it ends there, at once
    prob = Problem(lambda u, p: np.array([u[0] - p["b"]]), ["x"], {"b": 1.0})
    br = trace(prob, [1.0], free="b", bounds={"b": (-1.0, 1.0)}, direction=1, max_steps=50)
    assert br.status == "bound" and br["b"][-1] == 1.0 and np.all(br["b"] == 1.0)
    inward = trace(prob, [1.0], free="b", bounds={"b": (-1.0, 1.0)}, direction=-1)
    assert inward.status == "bound" and inward["b"][-1] == -1.0


def test_corrector_takes_a_simplified_step_in_the_quadratic_regime():
    """Once an update is ≤ sqrt(step_tol)(1 + |z|) with the residual still above tol, the next
    iteration reuses the last factorization (no Jacobian evaluation) and still converges.

    x³ − x − b at b = −1 from x = −1.3 (the root is minus the plastic number, −1.32471795724
    4746..., mpmath: findroot(x**3 - x + 1, -1.3)); tol = 1e-14 keeps the residual above tol
    after the update of ~1e-6 that enters the quadratic regime."""
    from cusp.continuation import BranchSystem
    from cusp.continuation.systems._newton import NewtonSettings, newton

    calls = {"jacobian": 0}
    example = ex.cusp_normal_form()  # a = 1, b = -1

    def jac(u, p):
        calls["jacobian"] += 1
        return example.jacobian(u, p)

    prob = Problem(
        example.residual,
        unknowns=["x"],
        params=example.params,
        jacobian=jac,
        param_jacobian=example.param_jacobian,
    )
    system = BranchSystem(prob, "b")
    row = np.array([0.0, 1.0])
    settings = NewtonSettings(tol=1e-14, step_tol=1e-10, max_iterations=10)
    res = newton(system, np.array([-1.3, -1.0]), row, -1.0, settings)
    assert res.converged
    assert res.z[0] == pytest.approx(X0, rel=2e-16, abs=0)
    assert calls["jacobian"] == res.iterations - 1  # the last iteration was a chord step


@pytest.mark.parametrize("n", [0, 1, 2, 3, 32, 33])
def test_max_abs_matches_numpy_and_flags_nonfinite(n):
    """The max-norm's plain-Python paths (one, two, up to 32 entries) agree with numpy's
    ``max(abs(x))`` and return NaN whenever an entry is NaN or ±inf, wherever it sits."""
    from cusp.continuation.numerics._linalg import max_abs

    rng = np.random.default_rng(n)
    x = rng.standard_normal(n) * 10.0 ** rng.integers(-300, 300, n)
    assert max_abs(x) == (float(np.max(np.abs(x))) if n else 0.0)
    for i in range(n):
        for bad in (math.nan, math.inf, -math.inf):
            y = x.copy()
            y[i] = bad
            assert math.isnan(max_abs(y)), (n, i, bad)
    if n:  # overflow of a sum of finite entries is not a non-finite entry
        assert max_abs(np.full(n, 1e308)) == 1e308


def test_fold_newton_stopping_estimate():
    """The locating Newton stops once the estimated next update is below the tolerance, both
    relative to the components' magnitudes (typical sizes 1 here, so 1e-12·max(1, |z_i|))
    and relative to the located component z_k itself (``k_ratio`` = |z_k|/max(1, |z_k|)).
    Update sizes are the fold Newton's on the cusp's second fold (x = 1/√3,
    b = −2/(3√3) = −0.3849...): 1.64e-4 then 4.68e-8. With the Newton matrix's error δ known
    (exact Jacobian: a forward difference in its last row, δ = 1e-7) the estimate
    C·size² + δ·size, C = size/previous², is 8.5e-15 (the actual next update was 8.9e-16):
    below 1e-12·|b| = 3.8e-13. Unknown δ: the linear estimate size²/previous = 1.3e-11 is
    not, and neither is a large δ's."""
    from cusp.continuation.detection._bracket import newton_done

    b = 0.3849001794597505
    assert newton_done(2, 4.68e-8, 1.64e-4, 1e-12, stall=1e-6, perturbation=1e-7, k_ratio=b)
    assert not newton_done(2, 4.68e-8, 1.64e-4, 1e-12, stall=1e-6, k_ratio=b)
    assert not newton_done(2, 4.68e-8, 1.64e-4, 1e-12, stall=1e-6, perturbation=1e-3, k_ratio=b)
    # not yet in the quadratic regime (the update shrank by less than 100): no early stop
    assert not newton_done(2, 1e-6, 5e-5, 1e-12, stall=1e-6, perturbation=1e-7, k_ratio=b)
    # the same estimate with a fold parameter 100 times smaller than its typical size
    # (b = −0.00385, typical size 1): 8.5e-15 is below 1e-12 relative to the typical size
    # but not below 1e-12·|b| = 3.8e-15, so Newton goes on
    assert newton_done(2, 4.68e-8, 1.64e-4, 1e-12, stall=1e-6, perturbation=1e-7)
    small = b / 100
    assert not newton_done(2, 4.68e-8, 1.64e-4, 1e-12, stall=1e-6, perturbation=1e-7, k_ratio=small)
