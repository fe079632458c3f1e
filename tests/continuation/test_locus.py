"""Loci of located points (cusp.continuation.locus, point_locus): bound hits, targets and
corners of a loading program continued in a second parameter, against closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cusp.continuation import (
    ChainPoint,
    Event,
    PointChain,
    Problem,
    ProblemDefinitionError,
    locus,
    point_locus,
    trace,
)

# A two-leg loading program with closed forms (derived by hand, checked below by the
# residuals themselves):
#   leg 1, unknown x, control p:          x² − p·a = 0,        ends at p = 1:   x_A = √a
#   leg 2, unknown y, control q, x_A linked: y³ + y − x_A − q = 0, ends at q = 0 (B):
#          y_B is the real root of y³ + y = √a; C on leg 2 where y = 2·x_A:
#          q_C = 8·a^{3/2} + 2·√a − √a = 8·a^{3/2} + √a.
LEG1 = Problem(
    lambda u, p: [u[0] ** 2 - p["p"] * p["a"]],
    ["x"],
    {"p": 0.5, "a": 1.0},
    jacobian=lambda u, p: [[2.0 * u[0]]],
    param_jacobian=lambda u, p, name: [-p["a"]] if name == "p" else [-p["p"]],
)
LEG2 = Problem(
    lambda u, p: [u[0] ** 3 + u[0] - p["xA"] - p["q"]],
    ["y"],
    {"q": 0.0, "xA": 1.0},
    jacobian=lambda u, p: [[3.0 * u[0] ** 2 + 1.0]],
    param_jacobian=lambda u, p, name: [-1.0],
)


def _y_b(a: float) -> float:
    """Real root of y³ + y = √a by Cardano (closed form, independent of the solver)."""
    c = math.sqrt(a)
    r = math.sqrt(c * c / 4.0 + 1.0 / 27.0)
    return math.cbrt(c / 2.0 + r) + math.cbrt(c / 2.0 - r)


def _chain() -> PointChain:
    return PointChain(
        [
            ChainPoint("A", LEG1, "p", ("p", 1.0)),
            ChainPoint("B", LEG2, "q", ("q", 0.0), links={"xA": ("A", "x")}),
            ChainPoint("C", LEG2, "q", ("y", ("A", "x")), links={"xA": ("A", "x")}),
        ]
    )


def test_chain_of_corners_follows_the_closed_forms():
    # C is held at y = x_A here (q_C = x_A³): a link as the condition's target
    start = {"A": {"x": 1.0, "p": 1.0}, "B": {"y": 0.7, "q": 0.0}, "C": {"y": 1.0, "q": 1.0}}
    br = locus(_chain(), start, free="a", bounds={"a": (0.25, 9.0)})
    assert br.success and br.info["direction"] == "both"
    a = br["a"]
    assert a.min() == pytest.approx(0.25, abs=1e-14) and a.max() == pytest.approx(9.0, abs=1e-14)
    np.testing.assert_allclose(br["A.x"], np.sqrt(a), rtol=1e-12)
    np.testing.assert_allclose(br["B.y"], [_y_b(v) for v in a], rtol=1e-11)
    np.testing.assert_allclose(br["C.q"], a**1.5, rtol=1e-11)
    np.testing.assert_array_equal(br["A.p"], 1.0)
    np.testing.assert_array_equal(br["B.q"], 0.0)


def test_targets_and_events_are_located_along_a_locus():
    start = {"A": {"x": 1.0, "p": 1.0}, "B": {"y": 0.7, "q": 0.0}, "C": {"y": 1.0, "q": 1.0}}
    # event: B's y reaches 1 (y³ + y = 2 = √a: a = 4); target: C.q = 8 (a^{3/2} = 8: a = 4)
    ev = Event(lambda u, p: u[2] - 1.0, label="y_B = 1")
    br = locus(
        _chain(), start, free="a", bounds={"a": (0.5, 5.0)}, events=[ev], targets={"C.q": [8.0]}
    )
    (e,) = br.special("event")
    assert e.values["a"] == pytest.approx(4.0, rel=1e-12)
    (t,) = br.special("target")
    assert t.values["a"] == pytest.approx(4.0, rel=1e-12)


def test_a_parameter_held_by_a_condition_can_be_the_free_one():
    # B located at q = q_end, a chain parameter; continue in q_end at fixed a = 1
    chain = PointChain(
        [
            ChainPoint("A", LEG1, "p", ("p", 1.0)),
            ChainPoint("B", LEG2, "q", ("q", "q_end"), links={"xA": ("A", "x")}),
        ],
        params={"q_end": 0.0},
    )
    start = {"A": {"x": 1.0, "p": 1.0}, "B": {"y": 0.7, "q": 0.0}}
    br = locus(chain, start, free="q_end", direction=1, bounds={"q_end": (-1.0, 10.0)})
    # y³ + y = 1 + q_end along it
    y = br["B.y"]
    np.testing.assert_allclose(y**3 + y, 1.0 + br["q_end"], rtol=1e-12)
    assert br["q_end"][-1] == pytest.approx(10.0, abs=1e-13)


def test_point_locus_of_a_bound_hit_and_of_a_fold():
    prob = Problem(lambda u, p: [u[0] ** 3 - p["a"] * u[0] - p["b"]], ["x"], {"a": 1.0, "b": -1.0})
    br = trace(prob, [-1.3247], free="b", bounds={"b": (-1.0, 1.0)})
    end = br.special("endpoint")[-1]  # b = 1 on the upper sheet
    loc = point_locus(prob, end, free=("b", "a"), bounds={"a": (0.5, 3.0)})
    x = loc["x"]
    # the corrector's residual tolerance (ContinuationOptions.tol = 1e-10; differenced Jacobian)
    np.testing.assert_allclose(x**3 - loc["a"] * x, 1.0, rtol=1e-10)
    np.testing.assert_array_equal(loc["b"], 1.0)
    fold = br.special("fold")[0]
    curve = point_locus(prob, fold, free=("b", "a"), bounds={"a": (0.5, 3.0)})
    # fold curve of the cusp: 27 b² = 4 a³
    np.testing.assert_allclose(27.0 * curve["b"] ** 2, 4.0 * curve["a"] ** 3, rtol=1e-10)


def test_bad_chains_are_refused_with_the_reason():
    with pytest.raises(ProblemDefinitionError, match="distinct names"):
        PointChain([ChainPoint("A", LEG1, "p", ("p", 1.0))] * 2)
    with pytest.raises(ProblemDefinitionError, match="control 'z'"):
        PointChain([ChainPoint("A", LEG1, "z", ("p", 1.0))])
    with pytest.raises(ProblemDefinitionError, match="refers to"):
        PointChain([ChainPoint("B", LEG2, "q", ("q", 0.0), links={"xA": ("A", "x")})])
    with pytest.raises(ProblemDefinitionError, match="give its value"):
        PointChain([ChainPoint("A", LEG1, "p", ("p", "p_end"))])
    with pytest.raises(ProblemDefinitionError, match="missing"):
        locus(_chain(), {"A": {"x": 1.0, "p": 1.0}}, free="a")
    with pytest.raises(ProblemDefinitionError, match="not a parameter of the chain"):
        locus(_chain(), {}, free="mu")
