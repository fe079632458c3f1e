"""Behaviour of `trace` beyond the published problems: events, targets, step budget, failure
reporting, option validation, import hygiene and the Jacobian checker. Written from the API
specification only; the references are the cusp x^3 - x - b = 0 (exact) and the examples'
own residuals."""

from __future__ import annotations

import re
import subprocess
import sys

import numpy as np
import pytest

import cusp.examples as ex

BOUNDS = {"b": (-1.0, 1.0)}


def _cusp(**kw):
    from cusp.continuation import trace

    case = ex.cusp_normal_form()
    kw.setdefault("bounds", BOUNDS)
    kw.setdefault("max_steps", 5000)
    return case, trace(case.problem, u0=[-1.3247], free="b", **kw)


# ---------------------------------------------------------------------------------------------
# Events
# ---------------------------------------------------------------------------------------------


def test_user_event_located_and_inserted(special, assert_special_points_consistent):
    from cusp.continuation import Event

    case, br = _cusp(events=[Event(lambda u, p: u[0], direction=0, label="x0", terminal=False)])
    assert br.success, (br.status, br.message)
    ev = special(br, "event")
    # x crosses 0 once, on the middle sheet, where b = x^3 - x = 0
    assert len(ev) == 1, [(s.kind, s.values) for s in br.special_points]
    sp = ev[0]
    assert sp.label == "x0"
    assert sp.status == "converged"
    assert abs(sp.values["x"]) <= 1e-10
    assert abs(sp.values["b"]) <= 1e-10
    assert br["x"][sp.index] == sp.values["x"]  # inserted as a point of the branch
    # the event does not end the branch (terminal=False)
    assert br["b"][-1] == 1.0
    assert_special_points_consistent(case, br)


@pytest.mark.parametrize("direction, count", [(0, 3), (+1, 2), (-1, 1)])
def test_event_direction(direction, count, special):
    """b - 0.25 changes sign three times: upward on the lower and upper sheets, downward on the
    middle one. direction=+1 keeps only negative-to-positive crossings (scipy convention)."""
    from cusp.continuation import Event

    case, br = _cusp(
        events=[Event(lambda u, p: p["b"] - 0.25, direction=direction, label="quarter")]
    )
    ev = special(br, "event")
    assert len(ev) == count, [(s.kind, s.values) for s in br.special_points]
    for sp in ev:
        assert sp.values["b"] == pytest.approx(0.25, abs=1e-10)
        assert sp.label == "quarter"
        x = sp.values["x"]
        assert abs(x**3 - x - sp.values["b"]) <= 1e-10  # the corrector's default tol
    if direction == +1:
        assert ev[0].values["x"] < -1 / np.sqrt(3) and ev[1].values["x"] > 1 / np.sqrt(3)
    if direction == -1:
        assert abs(ev[0].values["x"]) < 1 / np.sqrt(3)


def test_terminal_event_ends_the_branch_there(special):
    from cusp.continuation import Event

    case, br = _cusp(events=[Event(lambda u, p: u[0], terminal=True, label="x0")])
    ev = special(br, "event")
    assert len(ev) == 1
    assert ev[0].index == len(br["b"]) - 1
    assert abs(br["x"][-1]) <= 1e-10
    assert br["b"][-1] < 0.3849001794597505  # stopped on the middle sheet, before b = 1
    assert isinstance(br.status, str) and br.status


# ---------------------------------------------------------------------------------------------
# Targets
# ---------------------------------------------------------------------------------------------


def test_targets_land_exactly(special, assert_special_points_consistent):
    case, br = _cusp(targets={"b": [0.1, 0.2]})
    tg = special(br, "target")
    # each of b = 0.1, 0.2 is crossed once on each of the three sheets
    assert len(tg) == 6, [(s.kind, s.values) for s in br.special_points]
    values = sorted(br["b"][sp.index] for sp in tg)
    assert values == [0.1, 0.1, 0.1, 0.2, 0.2, 0.2]  # exactly, to the last bit
    for sp in tg:
        assert sp.values["b"] in (0.1, 0.2)
        assert sp.label == f"b={sp.values['b']}"
        x = sp.values["x"]
        # on the branch to the corrector's tolerance (default tol = 1e-10, as in the other
        # branch checks of this suite)
        assert abs(x**3 - x - sp.values["b"]) <= 1e-10
    # on the three sheets: x1 < -1/sqrt3 < x2 < 1/sqrt3 < x3
    xs = sorted(sp.values["x"] for sp in tg if sp.values["b"] == 0.1)
    assert xs[0] < -0.58 < xs[1] < 0.57 < xs[2]
    assert_special_points_consistent(case, br)


# ---------------------------------------------------------------------------------------------
# Step budget, failures
# ---------------------------------------------------------------------------------------------


def test_max_steps_ends_incomplete_with_a_status_and_a_warning(branch_residual_norms):
    from cusp.continuation import MaxStepsWarning

    with pytest.warns(MaxStepsWarning):
        case, br = _cusp(max_steps=5)
    assert br.status == "max_steps" and not br.success
    assert len(br["b"]) <= 6
    assert br["b"][-1] < 1.0
    assert isinstance(br.status, str) and br.status
    assert re.search(r"step", f"{br.status} {br.message}", re.IGNORECASE), (br.status, br.message)
    assert np.all(branch_residual_norms(case, br) <= 1e-10)


def _nan_beyond_half():
    from cusp.continuation import Problem

    def residual(u, p):
        if p["b"] > 0.5:
            return np.array([np.nan])
        return np.array([u[0] ** 3 - p["a"] * u[0] - p["b"]])

    return Problem(residual, unknowns=["x"], params={"a": 1.0, "b": -1.0})


def test_nan_residual_stops_the_branch_with_a_clear_status(special):
    from cusp.continuation import trace

    br = trace(
        _nan_beyond_half(), u0=[-1.3247], free="b", bounds=BOUNDS, throw=False, max_steps=5000
    )
    assert not br.success
    b, x = np.asarray(br["b"]), np.asarray(br["x"])
    assert np.all(np.isfinite(b)) and np.all(np.isfinite(x))
    assert b.max() <= 0.5
    assert len(special(br, "fold")) == 2  # everything before the failure is kept
    assert re.search(r"nan|non-?finite|not finite", f"{br.status} {br.message}", re.IGNORECASE), (
        br.status,
        br.message,
    )


def test_nan_residual_raises_with_throw():
    """The spec only says "raises": require the package's typed numerical-failure exception
    (ConvergenceError or a sibling under continuation's own base class), naming the cause."""
    import cusp.continuation as continuation
    from cusp.continuation import trace

    base = getattr(continuation, "ContinuationError", continuation.ConvergenceError)
    with pytest.raises(base, match=r"(?i)nan|non-?finite|not finite"):
        trace(_nan_beyond_half(), u0=[-1.3247], free="b", bounds=BOUNDS, throw=True, max_steps=5000)


# ---------------------------------------------------------------------------------------------
# Options and input validation
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "kwargs, field",
    [
        ({"ds": -0.1}, "ds"),
        ({"ds": 0.0}, "ds"),
        ({"ds": float("nan")}, "ds"),
        ({"ds_min": -1e-3}, "ds_min"),
        ({"ds_max": 0.0}, "ds_max"),
        ({"ds_min": 0.5, "ds_max": 0.1}, "ds_min"),
        ({"max_steps": 0}, "max_steps"),
        ({"max_steps": -3}, "max_steps"),
    ],
)
def test_bad_options_raise_value_error_naming_the_field(kwargs, field):
    from cusp.continuation import ContinuationOptions

    with pytest.raises(ValueError, match=rf"\b{field}\b"):
        ContinuationOptions(**kwargs)


def test_options_are_frozen_and_keywords_override():
    import dataclasses

    from cusp.continuation import ContinuationOptions, MaxStepsWarning, trace

    opts = ContinuationOptions(ds=0.01, ds_max=0.05, max_steps=1000)
    with pytest.raises(dataclasses.FrozenInstanceError):
        opts.ds = 0.1
    case = ex.cusp_normal_form()
    br = trace(case.problem, u0=[-1.3247], free="b", bounds=BOUNDS, options=opts)
    assert br.success and br["b"][-1] == 1.0
    assert np.all(np.abs(br.stats["ds"]) <= 0.05 * (1 + 1e-12))
    with pytest.warns(MaxStepsWarning):
        br3 = trace(case.problem, u0=[-1.3247], free="b", bounds=BOUNDS, options=opts, max_steps=3)
    assert len(br3["b"]) <= 4


def test_bad_trace_keywords_raise_value_error():
    from cusp.continuation import trace

    case = ex.cusp_normal_form()
    with pytest.raises(ValueError, match=r"\bds\b"):
        trace(case.problem, u0=[-1.3247], free="b", ds=-1.0)
    with pytest.raises(ValueError, match=r"\bc\b"):
        trace(case.problem, u0=[-1.3247], free="c")
    with pytest.raises(ValueError):
        trace(case.problem, u0=[-1.3247, 0.0], free="b")
    with pytest.raises(ValueError, match="b"):
        trace(case.problem, u0=[-1.3247], free="b", bounds={"b": (1.0, -1.0)})


def test_bad_derivatives_strategy_raises():
    from cusp.continuation import Problem

    with pytest.raises(ValueError, match="derivatives"):
        Problem(
            ex.cusp_normal_form().residual,
            unknowns=["x"],
            params={"a": 1.0, "b": 0.0},
            derivatives="backward",
        )


# ---------------------------------------------------------------------------------------------
# Per-point diagnostics
# ---------------------------------------------------------------------------------------------


def test_stats_are_per_point_arrays():
    case, br = _cusp()
    n = len(br["b"])
    for key in ("newton_iterations", "rejected_steps", "residual_norm", "ds"):
        arr = np.asarray(br.stats[key])
        assert arr.shape == (n,), key
    assert np.all(np.asarray(br.stats["newton_iterations"]) >= 0)
    assert np.all(np.asarray(br.stats["rejected_steps"]) >= 0)
    assert np.all(np.asarray(br.stats["residual_norm"]) <= 1e-10)


# ---------------------------------------------------------------------------------------------
# Import hygiene
# ---------------------------------------------------------------------------------------------


def test_import_does_not_pull_sympy_or_matplotlib():
    code = (
        "import sys, cusp.continuation; "
        "print(sorted(m for m in ('sympy', 'matplotlib') if m in sys.modules))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        check=True,
        cwd=str(__import__("pathlib").Path(__file__).parents[2]),
    )
    assert out.stdout.strip() == "[]", out.stdout + out.stderr


# ---------------------------------------------------------------------------------------------
# check_jacobian
# ---------------------------------------------------------------------------------------------


def test_check_jacobian_accepts_correct_and_flags_wrong():
    from cusp.continuation import Problem, check_jacobian

    truss = ex.truss_2dof()  # EA = L = 1, H = 2
    res, jac, pjac = truss.residual, truss.jacobian, truss.param_jacobian
    u, p = np.array([0.2, 0.7]), {"P": 0.1}
    good = Problem(res, unknowns=["u", "v"], params={"P": 0.1}, jacobian=jac, param_jacobian=pjac)
    rep = check_jacobian(good, u, p)
    assert rep.ok
    # max_error is scaled so that 1 is the threshold (|a - fd| / (atol + rtol |fd|)); the
    # exact Jacobian of this polynomial residual must sit far below it
    assert rep.max_error < 1e-2

    def wrong(q, pp):
        J = jac(q, pp).copy()
        J[1, 0] += 0.5  # one wrong entry: row 1, column 0
        return J

    bad = Problem(res, unknowns=["u", "v"], params={"P": 0.1}, jacobian=wrong, param_jacobian=pjac)
    rep = check_jacobian(bad, u, p)
    assert not rep.ok
    assert rep.max_error > 0.1
    text = getattr(rep, "message", None) or str(rep)
    assert re.search(r"\(1,\s*0\)|\[1,\s*0\]|row 1\D+col(umn)?\s*0|row 1\b.*d/du\b", text), text


def test_check_jacobian_sparse():
    from cusp.continuation import check_jacobian

    case = ex.bratu(7, sparse=True)
    rep = check_jacobian(case.problem, np.linspace(0.1, 0.7, 7), {"lam": 2.0})
    assert rep.ok, getattr(rep, "message", rep)
