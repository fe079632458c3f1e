"""The tracer's state is immutable, and test functions belong to the curve system.

Stepping twice from the same state must give the same points bit for bit: on an ordinary
branch, and on a fold curve, whose bordering vectors change at every point (they used to be
updated in place on a shared system, so a second step from an old state used the borders of
a later point and landed ~1e-12 away).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from cusp.continuation import (
    BranchSystem,
    ContinuationOptions,
    Event,
    Problem,
    TestFunction,
    Tracer,
    trace,
)
from cusp.continuation.detection._cusp import Codim2Test, CuspTest
from cusp.continuation.detection._tests import BranchPointTest, ComponentTest, FoldTest
from cusp.continuation.systems._fold import FoldSystem


def _cusp(a=1.0, b=-1.0):
    """x³ − a x − b = 0 with its exact derivatives."""
    return Problem(
        lambda u, p: np.array([u[0] ** 3 - p["a"] * u[0] - p["b"]]),
        ["x"],
        {"a": a, "b": b},
        jacobian=lambda u, p: np.array([[3.0 * u[0] ** 2 - p["a"]]]),
        param_jacobian=lambda u, p, name: np.array([-1.0]) if name == "b" else -u[:1],
    )


# x0 = −1.324717957244746: the real root of x³ − x + 1 (minus the plastic number; mpmath
# findroot at 30 digits gives -1.32471795724474602596090885448)
X0 = -1.324717957244746


def _run(tracer, state):
    states = [state]
    while not tracer.done(states[-1]):
        states.append(tracer.step(states[-1]))
    return states


def _points(state):
    out = []
    p = state.last
    while p is not None:
        out.append((p.z.tobytes(), p.t.tobytes(), p.s, p.iterations, p.ds, p.special))
        p = p.prev
    return out


def _same(a, b):
    assert a.ds == b.ds and a.steps == b.steps and a.status == b.status
    assert a.n_points == b.n_points and a.stalled == b.stalled
    assert [None if v is None else float(v) for v in a.test_values] == [
        None if v is None else float(v) for v in b.test_values
    ]
    assert repr(_points(a)) == repr(_points(b))  # bitwise: bytes of every z and t


def test_stepping_twice_from_a_branch_state_is_bit_identical():
    event = Event(lambda u, p: u[0], label="x = 0")
    tracer = Tracer(
        _cusp(), free="b", bounds={"b": (-1.0, 1.0)}, targets={"x": [0.5]}, events=[event]
    )
    states = _run(tracer, tracer.init([X0]))
    assert states[-1].status == "bound" and len(states) > 10
    for i in range(len(states) - 1):
        again = tracer.step(states[i])
        _same(again, states[i + 1])
        _same(tracer.step(states[i]), again)


def _coupled():
    """Two unknowns, so the fold's bordering vectors really turn along the fold curve:
    x³ − a x − b + 0.3 x y = 0, y − sin x − x²/2 = 0 (complex-step derivatives)."""

    def residual(u, p):
        x, y = u
        return np.array([x**3 - p["a"] * x - p["b"] + 0.3 * y * x, y - np.sin(x) - 0.5 * x * x])

    return Problem(residual, ["x", "y"], {"a": 1.0, "b": -1.0}, derivatives="complex")


def _fold_tracer(problem, u0, direction):
    fold = trace(problem, u0, free="b", bounds={"b": (-3.0, 3.0)}).special("fold")[0]
    names = [*problem.unknowns, "b", "a"]
    z0 = np.array([fold.values[name] for name in names])
    options = ContinuationOptions(detect_branch_points=False)
    k = len(problem.unknowns)  # the fold is a turning point of b
    system = FoldSystem.through(problem, "b", "a", k, dict(problem.params), None, z0)
    tracer = Tracer.for_system(
        system,
        options=options,
        bounds={"a": (-1.0, 2.0)},
        direction=direction,
        tests=(CuspTest(), Codim2Test()),
    )
    return tracer, tracer.init_at(z0, start_label="start (fold)")


@pytest.mark.parametrize("direction", [1, -1])
@pytest.mark.parametrize("example", ["cusp", "coupled"])
def test_stepping_twice_from_a_fold_curve_state_is_bit_identical(example, direction):
    problem, u0 = (_cusp(), [X0]) if example == "cusp" else (_coupled(), [-1.3, 1.0])
    tracer, start = _fold_tracer(problem, u0, direction)
    states = _run(tracer, start)
    assert len(states) > 5
    systems = {id(s.system) for s in states}
    assert len(systems) == len(states)  # a new system (new borders) at every point
    for i in range(len(states) - 1):
        _same(tracer.step(states[i]), states[i + 1])
        # the borders a state carries are those of its own point, whatever came after
        np.testing.assert_array_equal(tracer.step(states[i]).system.b, states[i + 1].system.b)
    if example == "cusp" and direction == -1:  # a decreases to the cusp x = a = b = 0
        cusps = tracer.result(states[-1]).special("cusp")
        assert len(cusps) == 1 and abs(cusps[0].values["a"]) < 1e-10


def test_result_is_a_copy():
    tracer = Tracer(_cusp(), free="b", bounds={"b": (-1.0, 1.0)})
    state = _run(tracer, tracer.init([X0]))[-1]
    first = tracer.result(state)
    first.special("fold")[0].details["mine"] = 1
    assert "mine" not in tracer.result(state).special("fold")[0].details


def test_a_tracer_evaluates_the_generic_tests_then_those_it_is_given():
    options = ContinuationOptions()
    branch = Tracer(_cusp(), free="b", options=options)
    assert [type(t) for t in branch.tests] == [FoldTest, BranchPointTest]
    z0 = np.array([1.0 / math.sqrt(3.0), -2.0 / (3.0 * math.sqrt(3.0)), 1.0])
    fold = FoldSystem.through(_cusp(), "b", "a", 1, {"a": 1.0, "b": -1.0}, None, z0)
    tracer = Tracer.for_system(fold, options=options, tests=(CuspTest(), Codim2Test()))
    kinds = [type(t) for t in tracer.tests]
    assert kinds == [BranchPointTest, CuspTest, Codim2Test]  # no fold in a free parameter


class _Crossing(TestFunction):
    """A test function no part of the engine knows: x·(x − 1/2) changes sign at x = 0, ½."""

    __slots__ = ()
    kind = "crossing"

    def __init__(self) -> None:
        super().__init__("x(x - 1/2) = 0", "x")

    def value(self, system, z, t, sdet) -> float:
        return float(z[0] * (z[0] - 0.5))


def test_a_new_test_needs_no_change_of_the_tracer():
    options = ContinuationOptions()
    system = BranchSystem(_cusp(), "b", None, options.state_weight)
    tracer = Tracer.for_system(
        system, options=options, bounds={"b": (-1.0, 1.0)}, tests=(_Crossing(),)
    )
    branch = tracer.result(_run(tracer, tracer.init([X0]))[-1])
    found = sorted(sp.values["x"] for sp in branch.special("crossing"))
    # x = 0 and x = 1/2 lie on the branch (b = x³ − x: 0 and −3/8); located by Illinois on
    # the arc, polished onto the curve
    assert found == pytest.approx([0.0, 0.5], abs=1e-10)
    assert {sp.status for sp in branch.special("crossing")} == {"converged"}


def test_component_tests_locate_exactly():
    t = ComponentTest("x=0.25", "x", 0, 0.25)
    assert t.value(None, np.array([1.0, 0.0]), None, None) == 0.75
