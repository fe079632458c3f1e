"""A curve started on a fold of its free parameter, or at a singular point (issue 17).

References in closed form: x² − p = 0 has its fold at (x, p) = (0, 0), where
[∂G/∂x, ∂G/∂p] = [2x, −1] = [0, −1] has the null vector (1, 0); x(p − x) = 0 (transcritical)
has [p − 2x, x] = [0, 0] at the origin, a two-dimensional null space.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sps

from cusp.continuation import (
    ConvergenceError,
    Problem,
    SingularPointError,
    trace,
)


def _parabola(analytic: bool, p0: float = 0.0) -> Problem:
    """x² − p = 0: the fold of p at x = 0, p = 0."""
    if not analytic:
        return Problem(lambda u, p: [u[0] ** 2 - p["p"]], ["x"], {"p": p0})
    return Problem(
        lambda u, p: [u[0] ** 2 - p["p"]],
        ["x"],
        {"p": p0},
        jacobian=lambda u, p: [[2.0 * u[0]]],
        param_jacobian=lambda u, p, name: [-1.0],
    )


@pytest.mark.parametrize("analytic", [True, False])
@pytest.mark.parametrize("direction", [1, -1])
def test_start_exactly_on_a_fold(analytic, direction):
    """Before: 'the starting point did not converge … residual norm 0' (Newton with p fixed
    factors [2x] = [0]). Now the tangent is the null vector (1, 0) of [2x, −1] at x = 0,
    oriented by x (p does not move along it) in the requested direction."""
    br = trace(_parabola(analytic), [0.0], free="p", bounds={"p": (-1.0, 1.0)}, direction=direction)
    assert br.status == "bound", br.message
    assert (br["x"][0], br["p"][0]) == (0.0, 0.0)  # the start is the fold itself
    assert np.allclose(br.tangents[0], [direction, 0.0], atol=1e-12)  # null vector (±1, 0)
    assert np.all(np.sign(br["x"][1:]) == direction)  # x moves as asked
    # every point on x² = p (closed form), ending at the bound p = 1, x = ±1
    assert np.max(np.abs(br["x"] ** 2 - br["p"])) <= 1e-10
    assert br["p"][-1] == 1.0 and abs(br["x"][-1] - direction) <= 1e-10
    start = br.special_points[0]
    assert start.details == {"fold_of": "p", "oriented_by": "x"}


@pytest.mark.parametrize("sparse", [True, False])
def test_start_on_a_fold_of_a_system(sparse):
    """x² + y² − p = 0, y − x = 0: the fold of p at the origin; the null vector of
    [[2x, 2y, −1], [−1, 1, 0]] = [[0, 0, −1], [−1, 1, 0]] is (1, 1, 0)/√2."""

    def residual(u, p):
        return np.array([u[0] ** 2 + u[1] ** 2 - p["p"], u[1] - u[0]])

    def jacobian(u, p):
        j = np.array([[2.0 * u[0], 2.0 * u[1]], [-1.0, 1.0]])
        return sps.csr_matrix(j) if sparse else j

    prob = Problem(
        residual,
        ["x", "y"],
        {"p": 0.0},
        jacobian=jacobian,
        param_jacobian=lambda u, p, name: np.array([-1.0, 0.0]),
    )
    br = trace(prob, [0.0, 0.0], free="p", bounds={"p": (-1.0, 1.0)})
    assert br.status == "bound", br.message
    t = br.tangents[0]
    assert abs(t[0] - t[1]) <= 1e-12 and t[0] > 0 and abs(t[2]) <= 1e-12
    # the end: x = y, 2x² = 1 (closed form x = 1/√2)
    assert abs(br["x"][-1] - 2**-0.5) <= 1e-10 and br["p"][-1] == 1.0


def test_start_a_hair_beyond_the_fold_is_corrected_onto_it():
    """p = −1e-12 has no solution of x² = p; the fold (p = 0) is 1e-12 away, within Newton's
    update tolerance √step_tol = 1e-6 relative: the start is the fold."""
    br = trace(_parabola(True, -1e-12), [0.0], free="p", bounds={"p": (-1.0, 1.0)})
    assert br.status == "bound", br.message
    assert abs(br["p"][0] + 1e-12) <= 1e-12  # moved by at most the 1e-12 to the fold


def test_start_beyond_the_fold_is_refused_with_the_reason():
    """p = −1e-3: the nearest solution (the fold, p = 0) is 1e-3 away, not at this p."""
    with pytest.raises(ConvergenceError) as info:
        trace(_parabola(True, -1e-3), [0.0], free="p", bounds={"p": (-1.0, 1.0)})
    text = str(info.value)
    assert "fold of p" in text and "p=0" in text and "x=0, p=-0.001" in text
    assert info.value.values == {"x": 0.0, "p": -1e-3}


@pytest.mark.parametrize("analytic", [True, False])
def test_start_at_a_branch_point_is_refused(analytic):
    """x(p − x) = 0 at the origin: [p − 2x, x] = [0, 0] (exactly, also by central
    differences: (h(p − h) − (−h)(p + h))/(2h) = p = 0), a two-dimensional null space."""
    kw = {}
    if analytic:
        kw = dict(
            jacobian=lambda u, p: [[p["p"] - 2.0 * u[0]]],
            param_jacobian=lambda u, p, name: [u[0]],
        )
    prob = Problem(lambda u, p: [u[0] * (p["p"] - u[0])], ["x"], {"p": 0.0}, **kw)
    with pytest.raises(SingularPointError) as info:
        trace(prob, [0.0], free="p", bounds={"p": (-1.0, 1.0)})
    assert info.value.values == {"x": 0.0, "p": 0.0}
    text = str(info.value)
    assert "x=0, p=0" in text and "branch point" in text and "Start off it" in text
    # off the point, the same problem traces through it (the branch x = p from (0.5, 0.5))
    br = trace(prob.with_params(p=0.5), [0.5], free="p", bounds={"p": (-1.0, 1.0)}, direction=-1)
    assert br.status == "bound" and br.special("branch_point")
