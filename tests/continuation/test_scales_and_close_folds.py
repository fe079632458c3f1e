"""Badly scaled unknowns and close folds: a problem whose unknowns are of size 1e-9 and 1e6
at once, traced with finite differences and no ``scales=``; two folds 1e-6 apart in the
parameter; a fold where an unknown is far smaller than at the start.

Every problem here is built on the cusp x³ − a·x − b, whose folds are at x = ±√(a/3),
b = ∓2(a/3)^{3/2} (∂/∂x: 3x² − a = 0; closed form), with its unknowns rescaled or offset
so that those folds stay known exactly.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from cusp.continuation import Problem, trace

# --- 1. unknowns of size 1e-9 and 1e6 at once, no user scales

EPS = float(np.finfo(float).eps)
C0 = 1e-9  # a concentration: c = C0·x (mol)
N0 = 1e6  # a population: N = N0·(2 + x)² (individuals)

#: tolerance on a fold's state relative to its own magnitude, by derivative strategy: the
#: differenced Jacobian's error moves the zero of det J (central ~ε^{2/3}, forward ~ε^{1/2},
#: of the components' sizes); the parameter is stationary there, exact to 1e-10 with any.
SCALED_STATE_RTOL = {"complex": 1e-12, "central": 1e-9, "forward": 1e-7}


def _concentration_population(derivatives: str, a: float = 1.0) -> Problem:
    """R = [C0·(x³ − a·x − b), N0·((N/N0) − (2 + x)²)] with x = c/C0: the equations in the
    units of their unknowns (mol, individuals). Folds (closed form, above): c = ±C0·√(a/3),
    b = ∓2(a/3)^{3/2}, N = N0·(2 ± √(a/3))²."""

    def residual(u, p):
        x = u[0] / C0
        return np.array([C0 * (x**3 - p["a"] * x - p["b"]), N0 * (u[1] / N0 - (2.0 + x) ** 2)])

    return Problem(residual, ["c", "N"], {"a": a, "b": 0.0}, derivatives=derivatives)


def _check_scaled_folds(br, derivatives: str, a: float = 1.0, count: int = 1) -> None:
    xf = math.sqrt(a / 3.0)  # the folds' x (closed form)
    bf = 2.0 * (a / 3.0) ** 1.5  # and |b| there
    folds = br.special("fold")
    assert br.status == "bound" and len(folds) == count, (br.status, folds)
    for sp in folds:
        s = math.copysign(1.0, sp.values["c"])
        assert sp.status == "converged", sp.details
        assert sp.values["b"] == pytest.approx(-s * bf, rel=1e-10, abs=0)
        tol = SCALED_STATE_RTOL[derivatives]
        assert sp.values["c"] == pytest.approx(s * xf * C0, rel=tol, abs=0)
        assert sp.values["N"] == pytest.approx(N0 * (2.0 + s * xf) ** 2, rel=tol, abs=0)


@pytest.mark.parametrize("derivatives", ["central", "forward"])
@pytest.mark.parametrize("direction", [1, -1])
def test_fd_start_at_zero_learns_a_size_of_1e_9(derivatives, direction):
    # c = 0 and b = 0 at the start (x = 0 solves x³ − x = 0): their sizes come from the start
    # tangent, dc/db = C0/(3x² − a) = −1e-9 beside dN/db = −4e6. Before, the tangent
    # component of c (1e-15 of N's) counted as not moving (size 1), and the tangent that sizes
    # the components was differenced with steps of 6e-6 in c (1e3 of its range): central
    # differences traced past the fold without seeing it, forward ones stalled for 5000 steps
    prob = _concentration_population(derivatives)
    br = trace(
        prob,
        [0.0, 4.0 * N0],
        free="b",
        bounds={"N": (0.2 * N0, 9.0 * N0)},
        direction=direction,
        throw=False,
    )
    _check_scaled_folds(br, derivatives)
    # the size of c is of the order of its values on the branch (|x| ≤ 2), not 1
    assert 1e-10 < br.info["scales"]["c"] < 1e-8


@pytest.mark.parametrize("derivatives", ["complex", "central", "forward"])
@pytest.mark.parametrize("x0", [-1.5, 1.5])
def test_both_folds_converged_with_sizes_1e_9_and_1e6(derivatives, x0):
    # R = [x³ − a·x − b, N/N0 − (2 + x)] (x = c/C0): from either outer sheet across both
    # folds. The fold locator's bordering vectors were Euclidean unit vectors: the null
    # vector (1e-15, 1) in (c, N) lost its c component to cancellation, Newton diverged and
    # the fold was reported as a regula-falsi "guess" (even with complex-step derivatives)
    def residual(u, p):
        x = u[0] / C0
        return np.array([x**3 - p["a"] * x - p["b"], u[1] / N0 - (2.0 + x)])

    b0 = x0**3 - x0  # the start solves x0³ − x0 − b0 = 0
    prob = Problem(residual, ["c", "N"], {"a": 1.0, "b": b0}, derivatives=derivatives)
    br = trace(
        prob,
        [x0 * C0, (2.0 + x0) * N0],
        free="b",
        bounds={"b": (-2.0, 2.0)},
        direction=1 if x0 < 0 else -1,
        throw=False,
    )
    xf = 1.0 / math.sqrt(3.0)  # √(a/3) at a = 1
    folds = br.special("fold")
    assert br.status == "bound" and len(folds) == 2
    for sp in folds:
        s = math.copysign(1.0, sp.values["c"])
        assert sp.status == "converged", sp.details
        assert sp.values["b"] == pytest.approx(-s * 2.0 * xf**3, rel=1e-10, abs=0)
        tol = SCALED_STATE_RTOL[derivatives]
        assert sp.values["c"] == pytest.approx(s * xf * C0, rel=tol, abs=0)
        assert sp.values["N"] == pytest.approx((2.0 + s * xf) * N0, rel=tol, abs=0)


@pytest.mark.parametrize("derivatives", ["central", "forward"])
@pytest.mark.parametrize("scale_b", [1e-9, 1e7])
def test_parameter_of_any_size_starting_at_zero(derivatives, scale_b):
    # the free parameter in other units (b·scale_b) and 0 at the start, as c: both sized by
    # the start tangent (before: c sized 1 and the parameter 0.08 or 8e7)
    def residual(u, p):
        x = u[0] / C0
        b = p["b"] / scale_b
        return np.array([C0 * (x**3 - x - b), N0 * (u[1] / N0 - (2.0 + x) ** 2)])

    prob = Problem(residual, ["c", "N"], {"b": 0.0}, derivatives=derivatives)
    br = trace(prob, [0.0, 4.0 * N0], free="b", bounds={"N": (0.2 * N0, 9.0 * N0)})
    (sp,) = br.special("fold")
    s = math.copysign(1.0, sp.values["c"])
    xf = 1.0 / math.sqrt(3.0)
    assert sp.status == "converged"
    assert sp.values["b"] == pytest.approx(-s * 2.0 * xf**3 * scale_b, rel=1e-10, abs=0)
    assert sp.values["c"] == pytest.approx(s * xf * C0, rel=SCALED_STATE_RTOL[derivatives])
    assert 0.1 < br.info["scales"]["b"] / scale_b < 10.0


# --- 2. two folds 1e-6 apart (relative) in the parameter and 1e-2 apart in the state

CLOSE_A = 7.5e-5
"""a of x³ − a·x − (b − b0): folds at x = ±√(a/3) = ±0.005 (1e-2 apart), where b − b0 =
∓2(a/3)^{3/2} = ∓2.5e-7 (5e-7 apart: 5e-7 relative at b0 = 1, 5e-10 at b0 = 1e3)."""


def _close_folds(n: int, b0: float, x0: float, derivatives: str) -> Problem:
    """R_0 = X³ − a·X − (b − b0) with X = x_0 + x0 (the state offset by x0), and for n > 1
    R_i = x_i − (i + 1)·x_0 − x_0²/2 (i = 1 … n−1): unknowns that bend with x_0, so that
    the pseudo-arclength is not linear in X. Folds: X = ±√(a/3), b = b0 ∓ 2(a/3)^{3/2},
    x_i = (i + 1)·x_0 + x_0²/2 there (closed form)."""

    def residual(u, p):
        x = u[0] + x0
        r = [x**3 - p["a"] * x - (p["b"] - b0)]
        r += [u[i] - (i + 1.0) * u[0] - 0.5 * u[0] ** 2 for i in range(1, n)]
        return np.array(r)

    def jacobian(u, p):
        j = np.eye(n)
        j[0, 0] = 3.0 * (u[0] + x0) ** 2 - p["a"]
        for i in range(1, n):
            j[i, 0] = -(i + 1.0) - u[0]
        return j

    def param_jacobian(u, p, name):
        out = np.zeros(n)
        out[0] = -1.0 if name == "b" else -(u[0] + x0)
        return out

    names = [f"x{i}" for i in range(n)]
    if derivatives == "analytic":
        return Problem(
            residual, names, {"a": CLOSE_A, "b": b0}, jacobian=jacobian,
            param_jacobian=param_jacobian,
        )  # fmt: skip
    return Problem(residual, names, {"a": CLOSE_A, "b": b0}, derivatives=derivatives)


@pytest.mark.parametrize("derivatives", ["analytic", "central"])
@pytest.mark.parametrize(
    ("n", "b0", "x0", "start", "direction"),
    [
        (3, 1.0, 0.0, -1.0, 1),  # the step from x = −0.11 to 0.15 spans both folds
        (3, 1.0, 0.0, 0.7, -1),
        (3, 1e3, 0.0, -1.0, 1),  # the parameter sized 1e3: its dip is 5e-10 of it
        (3, 1.0, 10.0, -1.0, 1),  # the state offset: x_0 ≈ −10 at the folds
        (5, 1e3, 10.0, 1.0, -1),  # a step begins 1e-3 before the first fold
        (4, -50.0, 0.5, -0.9242, 1),  # a step begins 0.01 before the first fold
    ],
)
def test_two_close_folds_both_located(n, b0, x0, start, direction, derivatives):
    # The fold test's sign is the same at both ends of the step that holds them; the cubic
    # Hermite interpolant's derivative, which shows two folds one step spans, is in error by
    # ~5e-4 there (the pseudo-arclength is not linear in x), ten times the dip of the
    # tangent's b component (−7.5e-5), and its vertex is 0.06 of the step off. Before, both
    # folds were missed; now the point at the interpolant's dip is corrected and the dip
    # searched from the true values (successive parabolas, closer to an end whose value is
    # far below its neighbour's)
    prob = _close_folds(n, b0, x0, derivatives)
    xs = start - x0  # the unknown x_0 at the start, on the sheet of X = start
    u0 = [xs] + [(i + 1.0) * xs + 0.5 * xs * xs for i in range(1, n)]
    b_start = b0 + start**3 - CLOSE_A * start  # R_0 = 0 there
    br = trace(
        prob.with_params(b=b_start),
        u0,
        free="b",
        bounds={"b": (b0 - 2.0, b0 + 2.0)},
        direction=direction,
    )
    folds = br.special("fold")
    assert br.status == "bound" and len(folds) == 2, folds
    xf = math.sqrt(CLOSE_A / 3.0)  # 0.005
    gap = 2.0 * (CLOSE_A / 3.0) ** 1.5  # 2.5e-7
    for sp, s in zip(sorted(folds, key=lambda sp: sp.values["x0"]), (-1.0, 1.0)):
        assert sp.status == "converged", sp.details
        assert sp.values["b"] == pytest.approx(b0 - s * gap, rel=1e-10, abs=0)
        u = s * xf - x0  # the unknown x_0 at the fold
        if derivatives == "analytic":  # the state to rounding, relative to its magnitude
            tol = 1e-10 * max(xf, abs(u))
        else:
            # central differences of X³ with step h err by h² (the third derivative is 6),
            # which moves the zero of 3X² − a by h²/(6X): h = ε^{1/3}·max(size, |x_0|)
            h = EPS ** (1.0 / 3.0) * max(br.info["scales"]["x0"], abs(u))
            tol = 2.0 * h * h / (6.0 * xf)
        assert sp.values["x0"] == pytest.approx(u, abs=tol)
        for i in range(1, n):
            xi = (i + 1.0) * u + 0.5 * u * u
            # (its error is x_0's times ∂x_i/∂x_0 = i + 1 + x_0, and its own rounding)
            assert sp.values[f"x{i}"] == pytest.approx(xi, abs=tol * (abs(i + 2.0 + u) + 1.0))


# --- 3. a fold where an unknown is far smaller than at the start

X_START = -1.3  # the start: x³ − x − b = 0 at b = x³ − x = −0.897
C_START = 1e7  # c at the start; c = C_START·exp(−κ(x − X_START)) on the curve
X_FOLDS = (-1.0 / math.sqrt(3.0), 1.0 / math.sqrt(3.0))  # 3x² − 1 = 0 (closed form)
KAPPA = math.log(C_START / 1e-4) / (X_FOLDS[0] - X_START)
"""c falls from 1e7 at the start to 1e-4 at the first fold, and to 2.7e-22 at the second:
c_f = C_START·exp(−κ(x_f − X_START)) (closed form)."""


def _decaying(derivatives: str) -> Problem:
    """R = [x³ − x − b, c·e^{κ(x − X_START)}/C_START − 1]: a quantity that decays
    exponentially along the branch (a concentration), in an equation relative to it."""

    def residual(u, p):
        x, c = u
        return np.array([x**3 - x - p["b"], c * np.exp(KAPPA * (x - X_START)) / C_START - 1.0])

    def jacobian(u, p):
        x, c = u
        e = math.exp(KAPPA * (x - X_START)) / C_START
        return np.array([[3.0 * x * x - 1.0, 0.0], [KAPPA * c * e, e]])

    def param_jacobian(u, p, name):
        return np.array([-1.0, 0.0])

    params = {"b": X_START**3 - X_START}
    if derivatives == "analytic":
        return Problem(
            residual, ["x", "c"], params, jacobian=jacobian, param_jacobian=param_jacobian
        )
    return Problem(residual, ["x", "c"], params, derivatives=derivatives)


@pytest.mark.parametrize("derivatives", ["analytic", "complex"])
def test_fold_state_relative_to_itself_after_decay(derivatives):
    # c is sized 1e7 where the branch starts (sizes only grow) and is 1e-4 and 2.7e-22 at the
    # folds. The fold Newton measured its updates against max(1e7, |c|) and stopped with
    # c off by 2e-7 of itself at the second fold, at a residual of 2e-7 that the rounding
    # floor, reckoned with 1e7, let pass; it now measures them against the components'
    # magnitudes in the step (foldlocate.local_magnitudes)
    br = trace(_decaying(derivatives), [X_START, C_START], free="b", bounds={"b": (-1.0, 1.0)})
    folds = br.special("fold")
    assert br.status == "bound" and len(folds) == 2
    assert br.info["scales"]["c"] == C_START
    for sp, xf in zip(folds, X_FOLDS):
        cf = C_START * math.exp(-KAPPA * (xf - X_START))  # 1e-4, then 2.7e-22
        assert sp.status == "converged", sp.details
        assert sp.values["b"] == pytest.approx(-2.0 * xf**3, rel=1e-12, abs=0)
        assert sp.values["x"] == pytest.approx(xf, rel=1e-12, abs=0)
        assert sp.values["c"] == pytest.approx(cf, rel=1e-12, abs=0)
