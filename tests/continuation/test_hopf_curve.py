"""Hopf curves and their codimension-2 points (issue 29) on normal forms whose Bautin,
Bogdanov–Takens and zero-Hopf points are known in closed form."""

from __future__ import annotations

import numpy as np
import pytest

from cusp.continuation import Problem, ProblemDefinitionError, hopf_curve, trace

#: codimension-2 points located to (issue 29)
TOL = 1e-8


def bautin_family() -> Problem:
    # w = x + iy: w' = (μ + iω)w + (β2/2)w|w|² − (1/4)w|w|⁴ with μ = β1 + 0.3β2,
    # ω = 1 + β2/2. Hopf curve μ = 0; in the ⟨q, q⟩ = 1 normalisation (x + iy = √2 z) the
    # cubic coefficient is β2, so l1 = β2/ω: the Bautin point is β2 = 0, β1 = 0
    def residual(u, p):
        x, y = u
        r2 = x * x + y * y
        mu, om = p["b1"] + 0.3 * p["b2"], 1 + 0.5 * p["b2"]
        g = mu + 0.5 * p["b2"] * r2 - 0.25 * r2 * r2
        return np.array([g * x - om * y, om * x + g * y])

    return Problem(residual, ["x", "y"], {"b1": -0.5, "b2": 0.6}, mass=True)


def test_bautin_point():
    prob = bautin_family()
    br = trace(prob, [0.0, 0.0], free="b1", bounds={"b1": (-0.5, 0.5)}, stability=True)
    (hopf,) = br.special("hopf")
    assert hopf.values["b1"] == pytest.approx(-0.18, abs=1e-12)  # μ = 0: β1 = −0.3·0.6
    assert hopf.details["first_lyapunov"] == pytest.approx(0.6 / 1.3, rel=1e-8)  # β2/ω
    curve = hopf_curve(prob, hopf, free=("b1", "b2"), bounds={"b2": (-1.0, 1.0)})
    (bautin,) = curve.special("bautin")
    assert abs(bautin.values["b1"]) < TOL and abs(bautin.values["b2"]) < TOL
    assert bautin.values["omega"] == pytest.approx(1.0, abs=TOL)
    # along the curve β1 = −0.3β2 and ω = 1 + β2/2
    assert np.max(np.abs(curve["b1"] + 0.3 * curve["b2"])) < 1e-9
    assert np.max(np.abs(curve["omega"] - 1 - 0.5 * curve["b2"])) < 1e-9


def bt_family() -> Problem:
    # x' = y, y' = β1 + β2/2 + β2 x + x² − xy: at x = y = 0 (β1 = −β2/2) the Jacobian is
    # [[0, 1], [β2, 0]] with trace −x: Hopf curve β1 = −β2/2, β2 < 0, ω = sqrt(−β2);
    # the Bogdanov–Takens point β1 = β2 = 0 (double zero eigenvalue, a Jordan block)
    return Problem(
        lambda u, p: np.array(
            [u[1], p["b1"] + 0.5 * p["b2"] + p["b2"] * u[0] + u[0] ** 2 - u[0] * u[1]]
        ),
        ["x", "y"], {"b1": 0.0, "b2": -1.0}, mass=True,
    )  # fmt: skip


def test_bogdanov_takens_point_ends_the_curve():
    prob = bt_family()
    br = trace(prob, [-0.2, 0.0], free="b1", bounds={"b1": (0.0, 1.0)}, stability=True)
    (hopf,) = br.special("hopf")
    assert hopf.values["b1"] == pytest.approx(0.5, abs=1e-12)
    assert hopf.details["omega"] == pytest.approx(1.0, rel=1e-12)
    curve = hopf_curve(prob, hopf, free=("b1", "b2"), bounds={"b2": (-2.0, 1.0)})
    (bt,) = curve.special("bogdanov_takens")
    assert abs(bt.values["b1"]) < TOL and abs(bt.values["b2"]) < TOL
    assert abs(bt.values["omega"]) < TOL
    assert curve.special("fold") == []  # the augmented curve's turn at ω = 0 is the BT point
    i = np.argmin(np.abs(curve["b2"] + 2.0))
    assert curve["omega"][i] == pytest.approx(np.sqrt(2.0), rel=1e-9)  # ω = sqrt(−β2)


def zero_hopf_family() -> Problem:
    # x' = β1 + x² − (y² + z²), (y + iz)' = (β2 + x + i(2 + x))(y + iz): equilibria
    # x = ±sqrt(−β1), y = z = 0 with eigenvalues 2x and β2 + x ± i(2 + x). Hopf curve
    # β2 = −x; the real eigenvalue 2x crosses 0 at the zero-Hopf point β1 = β2 = 0, ω = 2
    def residual(u, p):
        x, y, z = u
        g = p["b2"] + x
        return np.array([p["b1"] + x * x - (y * y + z * z), g * y - (2 + x) * z,
                         (2 + x) * y + g * z])  # fmt: skip

    return Problem(residual, ["x", "y", "z"], {"b1": -1.0, "b2": 0.5}, mass=True)


def test_zero_hopf_point():
    prob = zero_hopf_family()
    br = trace(prob, [-1.0, 0.0, 0.0], free="b2", bounds={"b2": (0.5, 1.5)}, stability=True)
    (hopf,) = br.special("hopf")
    assert hopf.values["b2"] == pytest.approx(1.0, abs=1e-12)
    curve = hopf_curve(prob, hopf, free=("b2", "b1"), bounds={"b1": (-2.0, 0.5)})
    (zh,) = curve.special("zero_hopf")
    assert abs(zh.values["b1"]) < TOL and abs(zh.values["b2"]) < TOL
    assert zh.values["omega"] == pytest.approx(2.0, abs=TOL)
    assert curve.special("bogdanov_takens") == [] and curve.special("bautin") == []


def test_hopf_curve_refuses_other_points():
    prob = bt_family()
    br = trace(prob, [-0.2, 0.0], free="b1", bounds={"b1": (0.0, 1.0)})
    with pytest.raises(ProblemDefinitionError, match="hopf_point"):
        hopf_curve(prob, br.special_points[0], free=("b1", "b2"))


def _brusselator(**derivatives) -> Problem:
    # x' = a − (b + 1)x + x²y, y' = bx − x²y: equilibrium (a, b/a), Hopf at b = 1 + a²
    # (trace 0: b − 1 − a² = 0; det = a² > 0), ω = a
    def residual(u, p):
        x, y = u
        return np.array([p["a"] - (p["b"] + 1) * x + x * x * y, p["b"] * x - x * x * y])

    return Problem(residual, ["x", "y"], {"a": 2.0, "b": 3.0}, mass=True, **derivatives)


def test_brusselator_hopf_curve_far_out_with_exact_derivatives():
    """b = 1 + a² traced over a ∈ [0.1, 50] (b from 1.01 to 2501) by complex steps."""
    prob = _brusselator(derivatives="complex")
    br = trace(prob, [2.0, 1.5], free="b", bounds={"b": (3, 7)}, stability=True)
    (h,) = br.special("hopf")
    curve = hopf_curve(prob, h, free=("b", "a"), bounds={"a": (0.1, 50.0)})
    assert curve.status == "bound"
    a, b = curve["a"], curve["b"]
    assert a.min() == pytest.approx(0.1) and a.max() == pytest.approx(50.0)
    np.testing.assert_allclose(b, 1 + a * a, rtol=1e-9)
    np.testing.assert_allclose(curve["omega"], a, rtol=1e-9)


def test_a_differenced_jacobian_failure_says_so():
    """The same curve with the Jacobian by finite differences: its rounding noise (about
    4e-10 at a = 2.56, against 1e-10 = tol) stops the curve near a = 2.57; the error says
    why and what to give."""
    from cusp.continuation import ContinuationError

    prob = _brusselator()
    br = trace(prob, [2.0, 1.5], free="b", bounds={"b": (3, 7)}, stability=True)
    (h,) = br.special("hopf")
    with pytest.raises(ContinuationError, match=r"finite differences.*jacobian="):
        hopf_curve(prob, h, free=("b", "a"), bounds={"a": (0.1, 50.0)})
