"""The regular Hopf system and Newton's method on it.

A Hopf point of ``M u' = R(u, p)`` is a solution of the standard extended system
(Kuznetsov, *Elements of Applied Bifurcation Theory*, 3rd ed., §10.2.2; Griewank & Reddien
1983; AUTO's and pde2path's Hopf systems)

    R(u, p) = 0,
    A qr + ω M qi = 0,      A qi − ω M qr = 0,        (``(A − iωM) q = 0``, ``q = qr + i qi``)
    Re(cᴴq) = 1,  Im(cᴴq) = 0,

``3n + 2`` real equations in ``(u, p, qr, qi, ω)``: regular at a Hopf point where the pair
``±iω`` is simple, no other eigenvalue is zero and the pair crosses with non-zero speed
(``c`` a fixed reference vector with ``cᴴq ≠ 0``: the eigenvector at the start). It is
chosen over the minimally augmented system (Govaerts 2000) because it is the one that stays
sparse and square with the problem's own Jacobian in its blocks (a sparse LU solves it at
``10⁴`` unknowns), because its unknowns carry ``ω`` and ``q``, which the first Lyapunov
coefficient needs anyway, and because it passes through a Bogdanov–Takens point (``ω`` then
changes sign: the Hopf curve continues as the same points with ``q̄``), which makes
``ω = 0`` a plain test function on Hopf curves.

The blocks ``∂(Aq)/∂u = D²R[q, ·]`` and ``∂(Aq)/∂p`` are central differences of the
Jacobian along ``qr``, ``qi`` and ``p``: they enter only Newton's matrix, not the residual,
so they set the rate of convergence, not the point.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp

from .._errors import ConvergenceError, SingularMatrixError, format_values
from ..problem._problem import as_matrix, extrapolated_derivatives, has_exact_jacobian
from ._lyapunov import Factored


@dataclass(frozen=True, kw_only=True)
class HopfPoint:
    """A solution of the Hopf system: state, parameters (all, by name), ``ω``, the
    eigenvector ``q`` (``cᴴq = 1``), Newton's iterations, ``max|R|`` and ``∂R/∂u`` there."""

    u: np.ndarray
    params: dict[str, float]
    omega: float
    q: np.ndarray
    iterations: int
    residual_norm: float
    jacobian: Any


class HopfSystem:
    """The Hopf system of ``problem`` (mass matrix ``mass``, None for ``I``) with reference
    vector ``c``."""

    def __init__(self, problem: Any, mass: Any, c: np.ndarray) -> None:
        self.problem = problem
        self.mass = mass
        self.n = len(problem.unknowns)
        self.c = np.asarray(c, dtype=complex)
        self.exact = has_exact_jacobian(problem)
        self.sparse = getattr(problem, "sparsity", None) is not None or sp.issparse(mass)

    def _m(self, x: np.ndarray) -> np.ndarray:
        return x if self.mass is None else self.mass @ x

    def derivatives(self, u: np.ndarray, p: Mapping[str, float], name: str) -> tuple:
        """``(A, ∂R/∂name)`` accurate to rounding (extrapolated differences if not exact)."""
        jac, dp = extrapolated_derivatives(self.problem, u, p, name)
        jac = as_matrix(jac)
        self.sparse = self.sparse or sp.issparse(jac)
        return jac, np.asarray(dp, dtype=float)

    def residual(
        self, u: np.ndarray, p: Mapping[str, float], q: np.ndarray, omega: float, jac: Any
    ) -> np.ndarray:
        """The ``3n + 2`` equations (``jac``: ``A`` at ``(u, p)``)."""
        qr, qi = q.real, q.imag
        r = np.asarray(self.problem.residual(u, p), dtype=float)
        cq = np.vdot(self.c, q)
        return np.concatenate(
            [
                r,
                jac @ qr + omega * self._m(qi),
                jac @ qi - omega * self._m(qr),
                [cq.real - 1.0, cq.imag],
            ]
        )

    def _djac(self, u: np.ndarray, p: Mapping[str, float], v: np.ndarray) -> Any:
        """``D²R[v, ·]`` as a matrix: a central difference of the Jacobian along ``v``."""
        nv = float(np.max(np.abs(v)))
        if nv == 0.0:
            return sp.csc_matrix((self.n, self.n)) if self.sparse else np.zeros((self.n,) * 2)
        h = (1e-5 if self.exact else 1e-4) * max(1.0, float(np.max(np.abs(u)))) / nv
        jp = as_matrix(self.problem.jacobian(u + h * v, p))
        jm = as_matrix(self.problem.jacobian(u - h * v, p))
        return (jp - jm) / (2.0 * h)

    def param_column(
        self, u: np.ndarray, p: Mapping[str, float], q: np.ndarray, name: str, dp: np.ndarray
    ) -> np.ndarray:
        """``∂/∂p[name]`` of the equations (``dp``: ``∂R/∂p[name]``)."""
        h = (1e-5 if self.exact else 1e-4) * max(1.0, abs(float(p[name])))
        hi, lo = dict(p), dict(p)
        hi[name] += h
        lo[name] -= h
        dj = (as_matrix(self.problem.jacobian(u, hi)) - as_matrix(self.problem.jacobian(u, lo))) / (
            2.0 * h
        )
        return np.concatenate([dp, dj @ q.real, dj @ q.imag, [0.0, 0.0]])

    def state_jacobian(
        self, u: np.ndarray, p: Mapping[str, float], q: np.ndarray, omega: float, jac: Any
    ) -> Any:
        """``∂/∂(u, qr, qi, ω)`` of the equations, ``(3n + 2) × (3n + 1)``."""
        n, qr, qi = self.n, q.real, q.imag
        hr, hi = self._djac(u, p, qr), self._djac(u, p, qi)
        mqr, mqi = self._m(qr), self._m(qi)
        cr, ci = self.c.real, self.c.imag
        if self.sparse:
            m = sp.identity(n, format="csc") if self.mass is None else sp.csc_matrix(self.mass)
            a = sp.csc_matrix(jac)
            col = lambda x: sp.csc_matrix(x.reshape(-1, 1))  # noqa: E731
            row = lambda x: sp.csc_matrix(x.reshape(1, -1))  # noqa: E731
            return sp.bmat(
                [
                    [a, None, None, sp.csc_matrix((n, 1))],
                    [sp.csc_matrix(hr), a, omega * m, col(mqi)],
                    [sp.csc_matrix(hi), -omega * m, a, col(-mqr)],
                    [sp.csc_matrix((1, n)), row(cr), row(ci), None],
                    [sp.csc_matrix((1, n)), row(-ci), row(cr), None],
                ],
                format="csc",
            )
        m = np.eye(n) if self.mass is None else np.asarray(self.mass, dtype=float)
        a = np.asarray(jac)
        z, zc, zr = np.zeros((n, n)), np.zeros((n, 1)), np.zeros((1, n))
        return np.block(
            [
                [a, z, z, zc],
                [np.asarray(hr), a, omega * m, mqi[:, None]],
                [np.asarray(hi), -omega * m, a, -mqr[:, None]],
                [zr, cr[None], ci[None], np.zeros((1, 1))],
                [zr, -ci[None], cr[None], np.zeros((1, 1))],
            ]
        )


def _with_column(mat: Any, column: np.ndarray, at: int) -> Any:
    """``mat`` with ``column`` inserted before column ``at``."""
    if sp.issparse(mat):
        mat = sp.csc_matrix(mat)
        col = sp.csc_matrix(column.reshape(-1, 1))
        return sp.hstack([mat[:, :at], col, mat[:, at:]], format="csc")
    return np.insert(np.asarray(mat), at, column, axis=1)


def locate_hopf(
    problem: Any,
    *,
    mass: Any,
    u0: np.ndarray,
    params: Mapping[str, float],
    free: str,
    omega0: float,
    q0: np.ndarray,
    tol: float = 1e-11,
    max_iter: int = 30,
) -> HopfPoint:
    """Newton's method on the Hopf system in ``(u, params[free], q, ω)`` from a guess; ``q0``
    (the guess's eigenvector) is also the reference ``c``. Converged when a step changes no
    component by more than ``tol`` relative (``max(1, |x|)``), which leaves the point
    accurate to rounding (the next step would be ``~tol²``), or when steps below 1e-7 stop
    shrinking (the floor of a differenced Jacobian's rounding: such a point is accurate to
    about that floor, ~1e-9, not to rounding). An update that contracts by less than 10
    is followed by a fresh factorization, else the last one is reused (a chord step: a
    sparse factorization of the ``3n + 2`` system costs as much as 20 solves). Raises
    :class:`~.._errors.ConvergenceError` if not converged in ``max_iter`` steps, or if ``ω``
    collapses to 0 (a Bogdanov–Takens point or a neutral saddle, not a Hopf point), or
    as soon as Newton's own updates grow twice after the second (a singular system: the
    double pair of a symmetric problem)."""
    q0 = np.asarray(q0, dtype=complex)
    c = q0 / np.linalg.norm(q0)
    system = HopfSystem(problem, mass, c)
    n = system.n
    u, p = np.array(u0, dtype=float), {k: float(v) for k, v in params.items()}
    q, omega = c / np.vdot(c, c), float(omega0)
    previous, lu, grew = np.inf, None, 0
    f = np.zeros(1)
    for it in range(1, max_iter + 1):
        fresh = lu is None
        f, dx, lu = _newton_step(system, u, p, q, omega, free, lu)
        if dx is None:
            break
        x_old = np.concatenate([u, [p[free]], q.real, q.imag, [omega]])
        u = u + dx[:n]
        p[free] = float(p[free] + dx[n])
        q = q + dx[n + 1 : 2 * n + 1] + 1j * dx[2 * n + 1 : 3 * n + 1]
        omega = float(omega + dx[3 * n + 1])
        change = float(np.max(np.abs(dx) / np.maximum(1.0, np.abs(x_old))))
        # converged; or stalled at the floor of a differenced Jacobian's rounding (steps of
        # 1e-9 that no longer shrink: the point is as accurate as the Jacobian)
        floor = fresh and change <= 1e-7 and change > 0.5 * previous
        grew += int(fresh and it > 2 and change > previous)
        if change > 0.1 * previous:  # a chord step contracting poorly: factor again
            lu = None
        previous = change
        if change <= tol or floor:
            if not omega > 1e3 * tol * max(1.0, abs(omega0)):
                break
            jac, _ = system.derivatives(u, p, free)
            rn = float(np.max(np.abs(problem.residual(u, p))))
            return HopfPoint(
                u=u, params=p, omega=omega, q=q, iterations=it, residual_norm=rn, jacobian=jac
            )
        if grew >= 2:  # Newton's own steps grow: a singular system (a double pair)
            break
    raise _failed(
        f"Newton on the Hopf system from {format_values(dict(params))} (omega guess "
        f"{omega0:.6g}) did not converge (last omega {omega:.6g}): no Hopf point there",
        p,
        it,
        f,
    )


def _newton_step(
    system: HopfSystem,
    u: np.ndarray,
    p: dict[str, float],
    q: np.ndarray,
    omega: float,
    free: str,
    lu: Factored | None,
) -> tuple[np.ndarray, np.ndarray | None, Factored]:
    """The Hopf system's residual, the update (None if not finite) and the factors used:
    ``lu`` (a chord step) or, if None, the Jacobian's at this point (Newton's step)."""
    jac, dp = system.derivatives(u, p, free)
    f = system.residual(u, p, q, omega, jac)
    try:
        if lu is None:
            mat = _with_column(
                system.state_jacobian(u, p, q, omega, jac),
                system.param_column(u, p, q, free, dp),
                system.n,
            )
            lu = Factored(mat)
        dx = -lu.solve(f)
    except SingularMatrixError as exc:
        raise _failed(f"the Hopf system is singular (omega={omega:.6g}; {exc})", p, 0, f) from None
    return f, (dx if np.all(np.isfinite(dx)) else None), lu


def _failed(what: str, p: Mapping[str, float], it: int, f: np.ndarray) -> ConvergenceError:
    rn = float(np.max(np.abs(f))) if np.all(np.isfinite(f)) else float("inf")
    return ConvergenceError(
        what,
        values=p,
        ds=0.0,
        iterations=it,
        residual_norm=rn,
        remedy="A pair that only approaches the imaginary axis, or a real pair (a neutral "
        "saddle), has no Hopf point.",
    )


__all__ = ["HopfPoint", "HopfSystem", "locate_hopf"]
