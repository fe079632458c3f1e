"""Stability along branches and Hopf points (issue 29): located Hopf points against closed
forms, first Lyapunov coefficients against an independent 50-digit evaluation of
Kuznetsov's formula (the ``hopf_l1`` fixture: sympy derivatives, mpmath linear algebra)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sp
import sympy as sy

import cusp.examples as examples
from cusp.continuation import Problem, ProblemDefinitionError, trace

#: relative accuracy of a located Hopf parameter: rounding with an exact Jacobian; with a
#: differenced one the floor of its (Richardson-extrapolated) rounding, ~1e-10 to 3e-10 here
PARAM_RTOL = {"analytic": 1e-10, "central": 1e-9}
#: the first Lyapunov coefficient (issue 29: 1e-6 relative)
L1_RTOL = 1e-6


# ---------------------------------------------------------------- Brusselator
def brusselator(a: float, jac: str) -> Problem:
    def residual(u, p):
        x, y = u
        b = p["b"]
        return np.array([p["a"] - (b + 1) * x + x * x * y, b * x - x * x * y])

    def jacobian(u, p):
        x, y = u
        b = p["b"]
        return np.array([[-(b + 1) + 2 * x * y, x * x], [b - 2 * x * y, -x * x]])

    return Problem(
        residual, ["x", "y"], {"a": a, "b": 1.0},
        jacobian=jacobian if jac == "analytic" else None, mass=True,
    )  # fmt: skip


def brusselator_oracle(hopf_l1, a):
    x, y, A, B = sy.symbols("x y a b")
    f = [A - (B + 1) * x + x**2 * y, B * x - x**2 * y]
    a = sy.nsimplify(a)
    return hopf_l1(f, [x, y], {A: a, B: 1 + a**2, x: a, y: (1 + a**2) / a})


@pytest.mark.parametrize("jac", ["analytic", "central"])
@pytest.mark.parametrize("a", [1.5, 2.0, 3.0])
def test_brusselator_hopf_and_lyapunov(a, jac, hopf_l1):
    br = trace(brusselator(a, jac), [a, 1.0 / a], free="b", bounds={"b": (1.0, 3 + a * a)},
               stability=True)  # fmt: skip
    (hopf,) = br.special("hopf")
    assert hopf.status == "converged"
    b_hopf = 1 + a * a  # closed form: trace of the Jacobian 0 at x = a, y = b/a
    assert abs(hopf.values["b"] - b_hopf) <= PARAM_RTOL[jac] * b_hopf
    assert abs(hopf.details["omega"] - a) <= PARAM_RTOL[jac] * a  # ω² = det = a²
    omega, l1 = brusselator_oracle(hopf_l1, a)  # 50 digits, e.g. a = 2: l1 = -1/6
    assert float(omega) == pytest.approx(a, rel=1e-40)
    # closed form matching the oracle at a = 3/2, 2, 3: l1 = −(a² + 2)/(2a(2a² + 1))
    assert float(l1) == pytest.approx(-(a * a + 2) / (2 * a * (2 * a * a + 1)), rel=1e-15)
    assert hopf.details["first_lyapunov"] == pytest.approx(float(l1), rel=L1_RTOL)
    assert hopf.details["criticality"] == "supercritical"
    # stable before, a pair unstable after; the Hopf row is in the branch, in order
    assert br["n_unstable"][0] == 0 and br["n_unstable"][-1] == 2
    assert br["b"][hopf.index] == hopf.values["b"]
    assert np.all(np.diff(br.s) > 0)
    assert len(br.eigenvalues) == len(br)


# ---------------------------------------------------------------- Lorenz
SIGMA, BETA = 10.0, 8.0 / 3.0


def lorenz(jac: str) -> Problem:
    """The Lorenz equilibria of :func:`cusp.examples.lorenz` (σ = 10, β = 8/3) declared a
    vector field, from ρ = 2."""
    ex = examples.lorenz()
    return Problem(ex.residual, list(ex.unknowns), {**ex.params, "rho": 2.0},
                   jacobian=ex.jacobian if jac == "analytic" else None, mass=True)  # fmt: skip


@pytest.mark.parametrize("jac", ["analytic", "central"])
def test_lorenz_subcritical_hopf(jac, hopf_l1):
    x0 = math.sqrt(BETA * 1.0)  # C+ at r = 2: x = y = sqrt(β(r − 1)), z = r − 1
    br = trace(lorenz(jac), [x0, x0, 1.0], free="rho", bounds={"rho": (2.0, 30.0)}, stability=True)
    (hopf,) = br.special("hopf")
    r_h = SIGMA * (SIGMA + BETA + 3) / (SIGMA - BETA - 1)  # 24.736842105263158 = 470/19
    assert abs(hopf.values["rho"] - r_h) <= PARAM_RTOL[jac] * r_h
    x, y, z, r = sy.symbols("x y z r")
    s, b = sy.Integer(10), sy.Rational(8, 3)
    R = s * (s + b + 3) / (s - b - 1)
    X = sy.sqrt(b * (R - 1))
    # 50 digits: ω = 9.6245300637157564, l1 = 2.65518972583671e-4
    omega, l1 = hopf_l1([s * (y - x), r * x - y - x * z, x * y - b * z], [x, y, z],
                        {r: R, x: X, y: X, z: R - 1})  # fmt: skip
    assert hopf.details["omega"] == pytest.approx(float(omega), rel=1e-9)
    assert hopf.details["first_lyapunov"] == pytest.approx(float(l1), rel=L1_RTOL)
    assert hopf.details["criticality"] == "subcritical"
    assert list(np.unique(br["n_unstable"])) == [0, 2]


# ---------------------------------------------------------------- normal form
class HopfNormalForm:
    """x' = βx − y + (s/2)x(x² + y²), y' = x + βy + (s/2)y(x² + y²): in the ⟨q, q⟩ = 1
    normalisation (q = (1, −i)/√2, so x + iy = √2 z) its complex form is
    ż = (β + i)z + s z|z|², and l1 = s exactly. Exact second and third derivatives."""

    unknowns = ("x", "y")

    def __init__(self, s):
        self.s = s
        self.params = {"beta": -0.5}
        self.mass = sp.identity(2, format="csc")

    def residual(self, u, p):
        x, y = u
        r2, b, h = x * x + y * y, p["beta"], 0.5 * self.s
        return np.array([b * x - y + h * x * r2, x + b * y + h * y * r2])

    def jacobian(self, u, p):
        x, y = u
        b, h = p["beta"], 0.5 * self.s
        return np.array(
            [[b + h * (3 * x * x + y * y), -1 + 2 * h * x * y],
             [1 + 2 * h * x * y, b + h * (x * x + 3 * y * y)]]
        )  # fmt: skip

    def param_jacobian(self, u, p, name):
        return np.array(u, dtype=float)

    def second_derivative(self, u, p, a, c):
        # D²[v|v|²][a, c] = 2(a·c)v + 2(v·c)a + 2(v·a)c
        return 0.5 * self.s * (2 * (a @ c) * u + 2 * (u @ c) * a + 2 * (u @ a) * c)

    def third_derivative(self, u, p, a, c, d):
        return 0.5 * self.s * 2 * ((c @ d) * a + (a @ d) * c + (a @ c) * d)


@pytest.mark.parametrize("s", [-0.7, 1.3])
@pytest.mark.parametrize("exact", [True, False])
def test_normal_form_l1_is_s(s, exact):
    prob = HopfNormalForm(s)
    if not exact:
        prob = Problem(prob.residual, prob.unknowns, prob.params, mass=True)
    br = trace(prob, [0.0, 0.0], free="beta", bounds={"beta": (-0.5, 0.5)}, stability=True)
    (hopf,) = br.special("hopf")
    assert abs(hopf.values["beta"]) <= 1e-14  # β = 0
    assert hopf.details["omega"] == pytest.approx(1.0, rel=1e-13)
    assert hopf.details["first_lyapunov"] == pytest.approx(s, rel=1e-13 if exact else 1e-8)


# ---------------------------------------------------------------- neutral saddle
def bt_normal_form(b2: float) -> Problem:
    # x' = y, y' = β1 + β2 x + x² + xy; at y = 0, x = 0 (β1 = 0) the Jacobian is
    # [[0, 1], [β2, 0]]: eigenvalues ±sqrt(β2) — a neutral saddle for β2 > 0 (real ±1),
    # a Hopf point for β2 < 0 (±i, trace x changing sign)
    return Problem(
        lambda u, p: np.array([u[1], p["b1"] + p["b2"] * u[0] + u[0] ** 2 + u[0] * u[1]]),
        ["x", "y"], {"b1": -0.5, "b2": b2}, mass=True,
    )  # fmt: skip


def test_neutral_saddle_is_never_a_hopf_point():
    x0 = float(min(np.roots([1.0, 1.0, -0.5]), key=abs))  # x² + x − 0.5 = 0
    br = trace(bt_normal_form(1.0), [x0, 0.0], free="b1", bounds={"b1": (-0.5, 0.2)},
               stability=True)  # fmt: skip
    assert br["x"].min() < 0 < br["x"].max()  # the branch passes the neutral saddle x = 0
    assert br.special("hopf") == []
    assert set(br["n_unstable"].tolist()) == {1}  # a saddle throughout
    # the same family with β2 = −1: a Hopf point at β1 = 0, x = 0 with ω = 1
    x0 = float(min(np.roots([1.0, -1.0, -0.5]), key=abs))
    br = trace(bt_normal_form(-1.0), [x0, 0.0], free="b1", bounds={"b1": (-0.5, 0.2)},
               stability=True)  # fmt: skip
    (hopf,) = br.special("hopf")
    assert abs(hopf.values["b1"]) < 1e-12 and abs(hopf.values["x"]) < 1e-12
    assert hopf.details["omega"] == pytest.approx(1.0, rel=1e-10)


# ---------------------------------------------------------------- folds
def test_n_unstable_changes_by_one_at_folds():
    prob = Problem(lambda u, p: [p["b"] + u[0] - u[0] ** 3], ["x"], {"b": -1.0}, mass=True)
    br = trace(prob, [-1.3247], free="b", bounds={"b": (-1.0, 1.0)}, stability=True)
    folds = br.special("fold")
    assert len(folds) == 2  # b = ±2/(3√3)
    n = br["n_unstable"]
    assert n[0] == 0 and n[-1] == 0 and n.max() == 1  # stable, unstable middle, stable
    jumps = np.flatnonzero(np.diff(n))
    assert len(jumps) == 2 and all(abs(int(n[j + 1]) - int(n[j])) == 1 for j in jumps)
    for f in folds:  # the change happens at the fold's row
        assert any(j <= f.index <= j + 1 for j in jumps)
    assert br.special("hopf") == []


# ---------------------------------------------------------------- mass matrices
MASS = np.array([[2.0, 1.0], [0.0, 1.0]])


def test_brusselator_with_a_mass_matrix(hopf_l1):
    a = 2.0
    prob = brusselator(a, "analytic")
    prob = Problem(prob._residual, prob.unknowns, prob.params, jacobian=prob._jacobian, mass=MASS)
    br = trace(prob, [a, 1.0 / a], free="b", bounds={"b": (1.0, 8.0)}, stability=True)
    (hopf,) = br.special("hopf")
    # closed form: at x = a, y = b/a, J = [[b − 1, a²], [−b, −a²]], M⁻¹ = [[1/2, −1/2], [0, 1]]:
    # M⁻¹J = [[b − 1/2, a²], [−b, −a²]], trace 0 at b = a² + 1/2 (det = a²/2 > 0)
    x, y, A, B = sy.symbols("x y a b")
    f = sy.Matrix([A - (B + 1) * x + x**2 * y, B * x - x**2 * y])
    jac = (sy.Matrix(MASS.astype(int)).inv() * f.jacobian([x, y])).subs({x: A, y: B / A})
    (b_h,) = sy.solve(sy.Eq(jac.trace().subs(A, 2), 0), B)  # b = 9/2 at a = 2
    assert b_h == sy.Rational(9, 2)
    assert abs(hopf.values["b"] - 4.5) <= 1e-10 * 4.5
    omega, l1 = hopf_l1(list(f), [x, y], {A: 2, B: b_h, x: 2, y: b_h / 2},
                        mass=MASS.astype(int).tolist())  # fmt: skip
    assert hopf.details["omega"] == pytest.approx(float(omega), rel=1e-10)
    assert hopf.details["first_lyapunov"] == pytest.approx(float(l1), rel=L1_RTOL)


def test_singular_mass_matrix_matches_the_reduced_system(hopf_l1):
    """x' = a − (b+1)x + x²y, y' = bx − w, 0 = w − x²y: the Brusselator with an algebraic
    unknown w; its Hopf point is the Brusselator's (b = 1 + a², ω = a). The first Lyapunov
    coefficient is that of the reduced system in coordinates where q has the norm of its
    (x, y) part: l1 scales with |q|², so l1_DAE = l1_ODE·|q_xy|² with ⟨q, q⟩ = 1 over
    (x, y, w)."""
    a = 2.0

    def residual(u, p):
        x, y, w = u
        b = p["b"]
        return np.array([a - (b + 1) * x + w, b * x - w, w - x * x * y])

    mass = sp.diags([1.0, 1.0, 0.0]).tocsc()
    prob = Problem(residual, ["x", "y", "w"], {"b": 3.0}, mass=mass)
    br = trace(prob, [a, 1.5, a * 1.5], free="b", bounds={"b": (3.0, 7.0)}, stability=True)
    assert all(lam.size == 2 for lam in br.eigenvalues)  # the infinite eigenvalue dropped
    (hopf,) = br.special("hopf")
    assert abs(hopf.values["b"] - 5.0) <= 1e-10 * 5
    assert hopf.details["omega"] == pytest.approx(2.0, rel=1e-10)
    q = hopf.details["eigenvector"]
    qxy2 = float(np.vdot(q[:2], q[:2]).real)
    _, l1 = brusselator_oracle(hopf_l1, a)  # −1/6
    assert hopf.details["first_lyapunov"] == pytest.approx(float(l1) * qxy2, rel=L1_RTOL)


# ---------------------------------------------------------------- refusals
def test_stability_refused_without_a_vector_field():
    prob = Problem(lambda u, p: [u[0] ** 2 - p["b"]], ["x"], {"b": 1.0})
    with pytest.raises(ProblemDefinitionError, match="mass=True"):
        trace(prob, [1.0], free="b", bounds={"b": (0.5, 2.0)}, stability=True)


def test_mass_matrix_checked():
    with pytest.raises(ProblemDefinitionError, match="mass must be 2×2"):
        Problem(lambda u, p: u, ["x", "y"], {}, mass=np.eye(3))
    with pytest.raises(ProblemDefinitionError, match="finite"):
        Problem(lambda u, p: u, ["x", "y"], {}, mass=np.full((2, 2), np.nan))


def test_dense_output_leaves_n_unstable_out():
    br = trace(brusselator(2.0, "analytic"), [2.0, 0.5], free="b", bounds={"b": (1.0, 7.0)},
               stability=True)  # fmt: skip
    mid = br.interpolate([0.5 * (br.s[0] + br.s[-1])])
    assert "n_unstable" not in mid and mid["a"][0] == 2.0  # fixed parameters kept
