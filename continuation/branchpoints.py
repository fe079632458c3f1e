"""Simple branch points: located by Newton on a regular extended system, and the tangents
of the branches that cross there.

At a simple branch point of ``G: R^{m+1} → R^m`` the Jacobian ``∂G/∂z`` loses rank by one:
it has a left null vector ``ψ`` and a two-dimensional kernel. The point solves the extended
system (Moore 1980; the branch-point locator of MatCont)

    G(z) + μ ψ = 0,    ∂G/∂z(z)ᵀ ψ = 0,    ψ·ψ = 1

in ``(z, ψ, μ)`` (2m + 2 equations and unknowns), which is regular there with μ = 0; Newton
on it converges quadratically, where a corrector on ``[G; border]`` (singular at the branch
point whatever the border) reaches only about the square root of its tolerance. The
second-derivative block ``∂(∂G/∂zᵀψ)/∂z = Σ ψ_i ∇²G_i`` is differenced from the Jacobian,
so the system is built densely: for more than :data:`MAX_DENSE` components the point is
only bracketed (regula falsi on the determinant's sign, each trial a corrected point).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .errors import SingularMatrixError
from .linalg import bordered, dense_solve, factor, inverse_magnitudes, max_abs, scaled_max
from .locate import (
    Bracket,
    Located,
    accept_located,
    locate_on_arc,
    newton_done,
    second_derivative_row,
)

#: largest curve dimension for which the extended system is built and solved densely
MAX_DENSE = 200


def locate_branch_point(br: Bracket, f_a: float, f_b: float) -> Located:
    """The branch point inside the step ``br`` where the determinant's sign changed from
    ``f_a`` to ``f_b``: bracketed by regula falsi to 1e-3 of the step, then Newton on the
    extended system; if that fails, regula falsi to the location tolerance (a bracketed
    estimate: status ``"guess"`` unless the bracket closed on a zero)."""
    rough = _regula_falsi(br, f_a, f_b, rtol=1e-3)
    if br.system.dim <= MAX_DENSE and rough.status == "converged":
        found = _newton_extended(br, rough.z)
        if found is not None:
            return found
    found = _regula_falsi(br, f_a, f_b)
    if found.status == "converged" and not found.details.get("exact_zero"):
        # the sign change is bracketed, but the points next to a branch point are corrected
        # only to about √tol (the corrector's matrix is singular there): not converged
        details = {**found.details, "reason": "extended-system Newton failed; bracketed only"}
        return found._replace(status="guess", details=details)
    return found


def _bordered_det(system: Any, z: np.ndarray, row: np.ndarray) -> tuple[float, float]:
    lu = factor(bordered(system.jacobian(z), row))
    return lu.sign_det(), lu.log_abs_det()


def _regula_falsi(br: Bracket, f_a: float, f_b: float, rtol: float | None = None) -> Located:
    """Illinois on the sign of det [∂G/∂z; border] along the arc (the ratio of determinants
    to the start's, so that it stays finite); a trial point where the matrix is singular is
    the zero itself."""
    system = br.system
    ref = _bordered_det(system, br.z_a, br.row)

    def f(z: np.ndarray) -> float:
        try:
            sgn, logdet = _bordered_det(system, z, br.row)
        except SingularMatrixError:  # landed exactly on the branch point
            return 0.0
        return sgn * math.exp(min(logdet - ref[1], 700.0))

    fa = ref[0]
    sb, lb = _bordered_det(system, br.z_b, br.row)
    fb = sb * math.exp(min(lb - ref[1], 700.0))
    if fa * fb > 0:  # the sign change was seen with a different border: bisect on it
        fb = -fa
    found = locate_on_arc(br, f, fa, fb, rtol=rtol)
    if found.details.get("test_values") == (0.0, 0.0):
        return found._replace(details={**found.details, "exact_zero": True})
    return found


def _left_null_vector(dg: Any) -> np.ndarray:
    """A unit left null vector of the nearly rank-deficient ``dg`` (m × (m+1)): its
    smallest left singular vector (dense SVD; used for at most :data:`MAX_DENSE`)."""
    dense = dg.toarray() if hasattr(dg, "toarray") else np.asarray(dg, dtype=float)
    u, _, _ = np.linalg.svd(dense)
    return u[:, -1]


def _newton_extended(br: Bracket, z0: np.ndarray) -> Located | None:
    """Newton on ``[G + μψ; ∂G/∂zᵀψ; ψ·ψ − 1] = 0`` from ``z0``; None if it fails or lands
    outside the step."""
    system, o = br.system, br.options
    z = z0.copy()
    dg = system.jacobian(z)
    psi = _left_null_vector(dg)
    mu = 0.0
    m, n = psi.size, z.size
    previous, it, converged = math.inf, 0, False
    for it in range(1, o.max_locate_iterations + 1):
        a, rhs = _extended_system(system, z, psi, mu, dg)
        try:
            d = dense_solve(a, rhs)[2]
        except SingularMatrixError:
            return None
        dz = d[:n]
        size = max(scaled_max(dz, inverse_magnitudes(system.scales, z)), max_abs(d[n : n + m]))
        if not math.isfinite(size):
            return None
        z, psi, mu = z - dz, psi - d[n : n + m], mu - float(d[-1])
        dg = system.jacobian(z)
        if newton_done(it, size, previous, o.locate_tol, stall=1e-8):
            converged = True
            break
        previous = size
    if not converged:
        return None
    method = "Newton on the extended system [G + mu psi; G_z^T psi; psi.psi - 1]"
    return accept_located(br, z, dg, it, size, {"method": method, "mu": float(mu)})


def _extended_system(
    system: Any, z: np.ndarray, psi: np.ndarray, mu: float, dg: Any
) -> tuple[np.ndarray, np.ndarray]:
    """The Newton matrix of the extended system at ``(z, ψ, μ)`` and its residual (the system
    for minus the update)."""
    n, m = z.size, psi.size
    dense = dg.toarray() if hasattr(dg, "toarray") else np.asarray(dg, dtype=float)
    size = m + n + 1
    a = np.zeros((size, size))
    a[:m, :n] = dense
    a[:m, n : n + m] = mu * np.eye(m)
    a[:m, -1] = psi
    e = np.zeros(n)
    for j in range(n):  # row j of Σ ψ_i ∇²G_i: ψ·D²G[e_j, ·]
        e[j] = 1.0
        a[m + j, :n] = second_derivative_row(system.jacobian, z, e, psi, None, system.scales)
        e[j] = 0.0
    a[m : m + n, n : n + m] = dense.T
    a[-1, n : n + m] = 2.0 * psi
    rhs = np.empty(size)
    rhs[:m] = system.residual(z) + mu * psi
    rhs[m : m + n] = dense.T @ psi
    rhs[-1] = psi @ psi - 1.0
    return a, rhs


__all__ = ["MAX_DENSE", "locate_branch_point"]
