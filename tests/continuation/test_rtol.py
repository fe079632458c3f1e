"""One accuracy knob, ``rtol``: what it sets, and dense output within it (issue 18)."""

import math

import numpy as np
import pytest

import cusp.examples as ex
from cusp.continuation import (
    AccuracyError,
    Branch,
    ContinuationOptions,
    OptionsError,
    Problem,
    ProblemDefinitionError,
    fold_curve,
    point_tol,
    quadrature_tol,
    trace,
)

# the cusp normal form's folds: b = ±2/(3√3) (sympy: solve([x**3 - x - b, 3*x**2 - 1]))
B_FOLD = 2.0 / (3.0 * math.sqrt(3.0))


def test_default_rtol_keeps_the_solver_tolerances_as_they_were():
    o = ContinuationOptions()
    assert o.rtol == 1e-3
    assert (o.tol, o.step_tol, o.curve_tol, o.locate_tol, o.quad_tol) == (
        1e-10, 1e-12, 0.02, 1e-12, 1e-13,
    )  # fmt: skip


def test_rtol_sets_the_tolerances_and_explicit_values_override():
    o = ContinuationOptions(rtol=1e-2)  # the loosest allowed
    # step_tol = locate_tol = (1e-2/1000)²; tol = 100·step_tol = 1e-8, clipped to at most
    # 1e-10; quad_tol = step_tol/10; curve_tol is a safety guard, fixed
    assert (o.tol, o.step_tol, o.curve_tol, o.locate_tol) == (1e-10, 1e-10, 0.02, 1e-10)
    assert o.quad_tol == quadrature_tol(1e-2) == 1e-11
    # floors at the rounding level
    assert point_tol(1e-6) == 1e-16 and ContinuationOptions(rtol=1e-13).locate_tol == 1e-15
    assert ContinuationOptions(rtol=1e-6).tol == 1e-12
    # a tolerance given stays; the others follow a new rtol through replace()
    o = ContinuationOptions(locate_tol=1e-15).replace(rtol=1e-5)
    assert o.locate_tol == 1e-15 and o.step_tol == 1e-16 and o.tol == 1e-12
    assert ContinuationOptions(rtol=1e-5) == ContinuationOptions().replace(rtol=1e-5)


@pytest.mark.parametrize("bad", [0.0, -1e-3, 0.5, 0.05, 1e-14, math.nan, True, "1e-3"])
def test_rtol_out_of_range_is_refused_by_name(bad):
    with pytest.raises(OptionsError, match="'rtol'"):
        ContinuationOptions(rtol=bad)


def _cusp_distance(br, cols):
    """Distance of points (x, b) from x³ − x − b = 0 in the branch's weighted metric (first
    order: |R| / |∇R| with the gradient in scaled coordinates)."""
    sx, sb = br.info["scales"]["x"], br.info["scales"]["b"]
    x, b = cols["x"], cols["b"]
    return np.abs(x**3 - x - b) / np.hypot((3 * x**2 - 1) * sx, sb)


@pytest.mark.parametrize("rtol", [1e-2, 1e-3, 1e-5, 1e-7, 1e-9])
def test_dense_output_is_within_rtol_of_the_cusp_curve(rtol):
    br = ex.cusp_normal_form().trace(rtol=rtol)
    s = np.linspace(br.s[0], br.s[-1], 4001)
    assert _cusp_distance(br, br.interpolate(s)).max() <= rtol
    at = br.interpolate_at("b", np.linspace(-0.99, 0.99, 41))
    assert _cusp_distance(br, at).max() <= rtol
    assert br.stats["interpolation_error"].max() <= 0.5 * rtol  # each step's measured arc
    # the folds, located by Newton, are far better than rtol
    folds = sorted(sp.values["b"] for sp in br.special("fold"))
    assert np.allclose(folds, [-B_FOLD, B_FOLD], rtol=0, atol=10 * rtol)


def test_dense_output_on_a_circle_at_points_and_by_a_component():
    # x² + b² = 1: the distance from the circle is exact, ||(x, b)|| − 1
    prob = Problem(lambda u, p: [u[0] ** 2 + p["b"] ** 2 - 1.0], ["x"], {"b": 0.0})
    for rtol in (1e-3, 1e-6, 1e-10):
        br = trace(prob, [1.0], free="b", bounds={"b": (-0.9, 0.9)}, rtol=rtol)
        cols = br.interpolate(np.linspace(br.s[0], br.s[-1], 2001))
        assert np.abs(np.hypot(cols["x"], cols["b"]) - 1.0).max() <= rtol
        at = br.interpolate_at("b", [0.05, 0.1234, 0.85])
        np.testing.assert_array_equal(at["b"], [0.05, 0.1234, 0.85])
        np.testing.assert_allclose(at["x"], np.sqrt(1 - at["b"] ** 2), rtol=0, atol=2 * rtol)


def test_looser_rtol_takes_fewer_points_on_the_cusp_branch():
    n = {r: len(ex.cusp_normal_form().trace(rtol=r)) for r in (1e-2, 1e-6, 1e-12)}
    assert n[1e-2] < n[1e-6] < n[1e-12]


def test_dense_output_on_a_fold_curve_both_halves():
    # the cusp's fold curve (a, b) = (3x², −2x³) (sympy: solve for the fold of x³ − a x − b)
    e = ex.cusp_normal_form()
    fold = e.trace().special("fold")[0]
    rtol = 1e-6
    fc = fold_curve(e.problem, fold, free=("b", "a"), bounds={"a": (-1.0, 2.0)}, rtol=rtol)
    assert fc.info["direction"] == "both"
    cols = fc.interpolate(np.linspace(fc.s[0], fc.s[-1], 3001))
    x, a, b = cols["x"], cols["a"], cols["b"]
    sc = fc.info["scales"]
    assert (np.abs(a - 3 * x**2) / sc["a"]).max() <= 10 * rtol
    assert (np.abs(b + 2 * x**3) / sc["b"]).max() <= 10 * rtol


def test_dense_output_refuses_what_it_cannot_give():
    br = ex.cusp_normal_form().trace()
    with pytest.raises(ProblemDefinitionError, match="arclength"):
        br.interpolate([br.s[-1] + 1.0])
    with pytest.raises(ProblemDefinitionError, match="not reached"):
        br.interpolate_at("b", [5.0])
    with pytest.raises(ProblemDefinitionError, match="not traced"):
        br.interpolate_at("a", [0.5])
    # a branch assembled by hand carries no interpolant
    bare = Branch(
        {"x": br["x"], "b": br["b"]}, variables=("x", "b"), s=br.s, tangents=br.tangents,
        special_points=[], status="bound", message="", stats={},
    )  # fmt: skip
    with pytest.raises(AccuracyError, match="no interpolant"):
        bare.interpolate([0.0])
    # a segment whose arc is off by more than rtol is refused, not evaluated
    stats = dict(br.stats)
    stats["interpolation_error"] = stats["interpolation_error"].copy()
    stats["interpolation_error"][3] = 1.0
    marked = Branch(
        {"x": br["x"], "b": br["b"]}, variables=("x", "b"), s=br.s, tangents=br.tangents,
        special_points=[], status="bound", message="", stats=stats, info=br.info,
    )  # fmt: skip
    with pytest.raises(AccuracyError, match="rows 2 and 3"):
        marked.interpolate([0.5 * (br.s[2] + br.s[3])])
    marked.interpolate([0.5 * (br.s[4] + br.s[5])])  # elsewhere fine
