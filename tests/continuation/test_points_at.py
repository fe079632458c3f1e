"""``points_at``: dense output of a branch, each point corrected onto the curve."""

from __future__ import annotations

import numpy as np
import pytest

import cusp.examples as ex
from cusp.continuation import Problem, ProblemDefinitionError, points_at, trace


def _cusp(a=1.0):
    return ex.cusp_normal_form(a=a).problem


def _root(b, near):
    # the root of x^3 - x - b nearest to ``near`` (mpmath polyroots, 30 digits)
    return min(ex.cusp_real_roots(1.0, b, dps=30), key=lambda r: abs(r - near))


def test_points_at_the_free_parameter_are_exact_roots():
    prob = _cusp()
    br = trace(prob, [-1.3247], free="b", bounds={"b": (-1.0, 1.0)}, ds_max=0.5)
    # values between the coarse points of the lower branch (before the first fold at
    # b = 2/(3√3) = 0.3849)
    b = np.array([-0.97, -0.5, 0.0, 0.3])
    cols = points_at(prob, br, "b", b)
    np.testing.assert_array_equal(cols["b"], b)
    want = [_root(v, -1.0) for v in b]
    np.testing.assert_allclose(cols["x"], want, rtol=1e-15, atol=1e-15)
    assert np.all(cols["a"] == 1.0)


def test_points_at_an_unknown_follow_the_branch_through_the_folds():
    prob = _cusp()
    br = trace(prob, [-1.3247], free="b", bounds={"b": (-1.0, 1.0)})
    # x is monotone along this branch: x = 0 lies on the middle (unstable) part
    cols = points_at(prob, br, "x", [-1.2, -0.5, 0.0, 0.5, 1.2])
    x = cols["x"]
    np.testing.assert_allclose(cols["b"], x**3 - x, rtol=0, atol=1e-15)


def test_points_at_errors_name_the_problem():
    prob = _cusp()
    br = trace(prob, [-1.3247], free="b", bounds={"b": (-1.0, 1.0)})
    with pytest.raises(ProblemDefinitionError, match=r"b = 2\.0 is not reached"):
        points_at(prob, br, "b", [0.0, 2.0])
    with pytest.raises(ProblemDefinitionError, match="'y' is not traced"):
        points_at(prob, br, "y", 0.0)
    other = Problem(lambda u, p: u - p["c"], unknowns=["y"], params={"c": 0.0})
    with pytest.raises(ProblemDefinitionError, match="not the unknowns"):
        points_at(other, br, "b", 0.0)
    with pytest.raises(ProblemDefinitionError, match="finite"):
        points_at(prob, br, "b", float("nan"))
