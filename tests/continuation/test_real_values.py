"""Complex results of user functions are refused, never cut to their real part (issue 17).

Before, ``np.asarray(x, dtype=float)`` dropped the imaginary part (a ComplexWarning, which
the test configuration turns into an error, but which users rarely see as such). Each
problem below returns a complex value whose imaginary part is known by construction.
"""

from __future__ import annotations

import cmath

import numpy as np
import pytest
import scipy.sparse as sps

from cusp.continuation import Event, Problem, ProblemDefinitionError, check_jacobian, trace


def _line(**kw) -> Problem:
    """x − p = 0 (the branch x = p; its Jacobian [1, −1])."""
    return Problem(lambda u, p: [u[0] - p["p"]], ["x"], {"p": 1.0}, **kw)


def _refused(prob, match, **kw):
    kw.setdefault("bounds", {"p": (-2.0, 2.0)})
    with pytest.raises(ProblemDefinitionError, match=match) as info:
        trace(prob, [1.0], free="p", **kw)
    return str(info.value)


def test_complex_residual_is_refused_naming_the_point():
    """x − p + 0.5j: imaginary part 0.5 everywhere, so already at the start (1, 1)."""
    prob = Problem(lambda u, p: np.array([u[0] - p["p"] + 0.5j]), ["x"], {"p": 1.0})
    text = _refused(prob, "the residual returned complex values")
    assert "x=1, p=1" in text and "imaginary part up to 0.5" in text


def test_residual_turning_complex_along_the_branch_is_refused():
    """x − √p (cmath): real for p ≥ 0, imaginary part √|p| once p < 0; the branch x = √p
    runs down to p = 0 and the corrector (or its differences) then evaluates p < 0."""
    prob = Problem(lambda u, p: [u[0] - cmath.sqrt(p["p"])], ["x"], {"p": 1.0})
    text = _refused(prob, "the residual", direction=-1)
    assert "complex values" in text


def test_zero_imaginary_part_is_taken():
    """A complex array with imaginary part exactly 0 loses nothing: the branch x = p."""
    prob = Problem(lambda u, p: np.array([u[0] - p["p"]], dtype=complex), ["x"], {"p": 1.0})
    br = trace(prob, [1.0], free="p", bounds={"p": (-2.0, 2.0)})
    assert br.status == "bound" and np.max(np.abs(br["x"] - br["p"])) <= 1e-12


@pytest.mark.parametrize("sparse", [False, True])
def test_complex_jacobian_is_refused(sparse):
    """∂R/∂x returned as 1 + 1j (the true value is 1)."""
    j = np.array([[1.0 + 1.0j]])
    prob = _line(jacobian=lambda u, p: sps.csr_matrix(j) if sparse else j)
    text = _refused(prob, "the jacobian returned complex values")
    assert "x=1, p=1" in text and "imaginary part up to 1" in text


def test_complex_param_jacobian_is_refused():
    """∂R/∂p returned as −1 + 2j (the true value is −1)."""
    prob = _line(param_jacobian=lambda u, p, name: np.array([-1.0 + 2.0j]))
    text = _refused(prob, r"the param_jacobian \(for 'p'\) returned complex values")
    assert "imaginary part up to 2" in text


def test_complex_event_is_refused():
    """The event x + 1j: imaginary part 1."""
    event = Event(lambda u, p: np.complex128(u[0] + 1.0j), label="bad")
    text = _refused(_line(), "event 'bad' returned complex values", events=[event])
    assert "x=1, p=1" in text


def test_protocol_object_returning_complex_is_refused():
    """Not a Problem: the branch system converts what any protocol object returns."""

    class Complex:
        unknowns = ("x",)
        params = {"p": 1.0}

        def residual(self, u, p):
            return np.array([u[0] - p["p"] + 0.25j])

        def jacobian(self, u, p):
            return np.array([[1.0]])

        def param_jacobian(self, u, p, name):
            return np.array([-1.0])

    _refused(Complex(), "the residual returned complex values")


def test_problem_wrappers_and_check_jacobian_refuse_complex():
    prob = Problem(lambda u, p: np.array([u[0] - p["p"] + 1e-3j]), ["x"], {"p": 1.0})
    with pytest.raises(ProblemDefinitionError, match="imaginary part up to 0.001"):
        prob.residual(np.array([1.0]), {"p": 1.0})
    # the differenced Jacobian evaluates the residual near the point: refused too
    with pytest.raises(ProblemDefinitionError, match="finite differences"):
        prob.jacobian(np.array([1.0]), {"p": 1.0})
    bad_jac = _line(jacobian=lambda u, p: [[1.0 + 1.0j]])
    with pytest.raises(ProblemDefinitionError, match="the jacobian returned complex"):
        check_jacobian(bad_jac, [1.0])


def test_complex_step_derivatives_still_work():
    """derivatives="complex" calls the residual with complex input on purpose: x² − p,
    whose branch x = √p ends at the bound p = 2 with x = √2 (closed form)."""
    prob = Problem(lambda u, p: [u[0] ** 2 - p["p"]], ["x"], {"p": 1.0}, derivatives="complex")
    br = trace(prob, [1.0], free="p", bounds={"p": (0.5, 2.0)})
    assert br.status == "bound" and abs(br["x"][-1] - 2**0.5) <= 1e-10
