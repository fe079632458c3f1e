"""Problems for whole diagrams and deflation (:func:`cusp.continuation.diagram`,
:func:`cusp.continuation.deflate`), each with its closed forms in its docstring:

- :func:`two_modes`: two interacting modes, a secondary branch point on the first mode's
  branch;
- :func:`isola`: a circle of solutions disjoint from the trivial line, reachable only by
  deflation;
- :func:`painleve`: the first Painlevé transcendent's boundary-value problem by finite
  differences, two solutions (Farrell, Birkisson & Funke 2015's first example).

Each returns a plain :class:`~cusp.continuation.Problem` with its analytic Jacobian.
"""

from __future__ import annotations

import math

import numpy as np
import scipy.sparse as sps

from cusp.continuation import Problem


def two_modes() -> Problem:
    """x(λ − 1 − x² − y²/2) = 0, y(λ − 2 − y² − x²/2) = 0.

    Closed forms: the trivial branch x = y = 0 has branch points at λ = 1 (mode x) and λ = 2
    (mode y); the x-branch y = 0, x² = λ − 1 carries a secondary branch point where
    λ − 2 − x²/2 = (λ − 3)/2 = 0: λ = 3, x = ±√2; the y-branch x = 0, y² = λ − 2 none
    (λ − 1 − y²/2 = λ/2 ≠ 0 for λ ≥ 2); the mixed branches x² + y²/2 = λ − 1,
    y² + x²/2 = λ − 2, i.e. x² = 2λ/3, y² = (2λ − 6)/3 (from λ = 3), one for x > 0 and one for
    x < 0, with det J = 3x²y² ≠ 0 off y = 0: none either."""

    def residual(u, p):
        x, y, lam = u[0], u[1], p["lam"]
        return np.array([x * (lam - 1 - x * x - y * y / 2), y * (lam - 2 - y * y - x * x / 2)])

    def jacobian(u, p):
        x, y, lam = u[0], u[1], p["lam"]
        return np.array(
            [
                [lam - 1 - 3 * x * x - y * y / 2, -x * y],
                [-x * y, lam - 2 - 3 * y * y - x * x / 2],
            ]
        )

    def param_jacobian(u, p, name):
        return np.array([u[0], u[1]])

    return Problem(residual, ["x", "y"], {"lam": 0.0}, jacobian=jacobian,
                   param_jacobian=param_jacobian)  # fmt: skip


def isola() -> Problem:
    """x·((x − 3)² + (λ − 2)² − 1) = 0: the line x = 0 (∂R/∂x = (9 + (λ − 2)² − 1) > 0 on it:
    no branch point) and the circle of radius 1 about (x, λ) = (3, 2), regular (∇R = x·∇ of
    the circle, x ∈ [2, 4]): an isola, reachable from x = 0 only by deflation. At λ = 2 the
    solutions are x = 0, 2, 4."""
    return Problem(
        lambda u, p: [u[0] * ((u[0] - 3.0) ** 2 + (p["lam"] - 2.0) ** 2 - 1.0)],
        ["x"],
        {"lam": 0.0},
        jacobian=lambda u, p: [[3 * u[0] ** 2 - 12 * u[0] + 8 + (p["lam"] - 2.0) ** 2]],
        param_jacobian=lambda u, p, name: [2 * u[0] * (p["lam"] - 2.0)],
    )


def painleve(n: int) -> tuple[Problem, np.ndarray]:
    """y'' = y² − x on (0, 10), y(0) = 0, y(10) = √10 (the first Painlevé transcendent's
    boundary-value problem, y ~ √x at infinity cut at x = 10), by central differences on n
    interior nodes; sparse analytic Jacobian."""
    h = 10.0 / (n + 1)
    x = h * np.arange(1, n + 1)

    def residual(u, p):
        full = np.concatenate([[0.0], u, [math.sqrt(10.0)]])
        return (full[:-2] - 2 * full[1:-1] + full[2:]) / h**2 - full[1:-1] ** 2 + x

    def jacobian(u, p):
        off = np.full(n - 1, 1 / h**2)
        return sps.diags([off, -2 / h**2 - 2 * u, off], [-1, 0, 1], format="csc")

    return Problem(residual, [f"y{i}" for i in range(n)], {}, jacobian=jacobian), x


__all__ = ["isola", "painleve", "two_modes"]
