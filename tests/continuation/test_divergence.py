"""A diverging branch stops with a typed error before numpy overflows (issue 17).

Before, a component growing without bound made its typical size's square overflow in the
arclength weights (``scales*scales``: a RuntimeWarning, then NaN tangents), before any
typed error. The sizes are now kept within [1e-150, 1e150] (squares and reciprocal squares
normal floats) and a branch whose component outgrows that stops (status
``"nonfinite_residual"``, ``NonFiniteResidualError``). The suite turns warnings into
errors, so any numpy warning on these paths fails the tests.
"""

from __future__ import annotations

import pytest

from cusp.continuation import NonFiniteResidualError, Problem, ProblemDefinitionError, trace


def _cube() -> Problem:
    """x − p³ = 0: x = p³ grows without bound (no bounds given)."""
    return Problem(
        lambda u, p: [u[0] - p["p"] ** 3],
        ["x"],
        {"p": 1.0},
        jacobian=lambda u, p: [[1.0]],
        param_jacobian=lambda u, p, name: [-3.0 * p["p"] ** 2],
    )


def _steep() -> Problem:
    """x − 1e149·p = 0 from p = 1: x passes 1e150 at p = 10 (closed form)."""
    return Problem(lambda u, p: [u[0] - 1e149 * p["p"]], ["x"], {"p": 1.0})


@pytest.mark.parametrize("make, x0", [(_cube, 1.0), (_steep, 1e149)])
def test_diverging_branch_stops_without_warnings(make, x0):
    br = trace(make(), [x0], free="p", max_steps=5000, throw=False)
    assert br.status == "nonfinite_residual"
    assert "the branch diverges: x reached" in br.message and "bounds" in br.message
    # the points kept are finite and on the curve (x = p³, or x = 1e149·p)
    assert all(abs(x) < 1e151 for x in br["x"])
    prob = make()
    for x, p in zip(br["x"][-3:], br["p"][-3:]):
        r = prob.residual([x], {"p": p})[0]
        assert abs(r) <= 1e-9 * abs(x)


def test_diverging_branch_raises_the_typed_error():
    with pytest.raises(NonFiniteResidualError, match="the branch diverges") as info:
        trace(_steep(), [1e149], free="p", max_steps=5000)
    assert info.value.values["x"] > 1e150


def test_sizes_outside_the_range_are_refused_at_the_start():
    with pytest.raises(ProblemDefinitionError, match=r"scales\['x'\] must be a number in"):
        trace(_steep(), [1e149], free="p", scales={"x": 1e200})
    # a start at x = 1e200 (x − 1e200·p from p = 1) cannot be measured either
    far = Problem(lambda u, p: [u[0] - 1e200 * p["p"]], ["x"], {"p": 1.0})
    with pytest.raises(ProblemDefinitionError, match="typical size of x would be 1e\\+200"):
        trace(far, [1e200], free="p")
