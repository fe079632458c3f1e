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
from typing import TYPE_CHECKING, Any

import numpy as np
import scipy.sparse as sp

from .._errors import SingularMatrixError
from .._outcomes import PointStatus
from ..numerics._differences import second_derivative_row
from ..numerics._linalg import (
    bordered,
    dense_solve,
    factor,
    inverse_magnitudes,
    max_abs,
    scaled_max,
)
from ..problem._derivatives import column_groups
from ..systems._curve import CurveSystem
from ._bracket import (
    Bracket,
    Located,
    accept_located,
    newton_done,
)
from ._regula import locate_on_arc

if TYPE_CHECKING:
    from .._options import ContinuationOptions

#: largest curve dimension for which the extended system is built and solved densely
MAX_DENSE = 200


def locate_branch_point(br: Bracket, f_a: float, f_b: float) -> Located:
    """The branch point inside the step ``br`` where the determinant's sign changed from
    ``f_a`` to ``f_b``: bracketed by regula falsi to 1e-3 of the step, then Newton on the
    extended system; if that fails, regula falsi to the location tolerance (a bracketed
    estimate: status ``"guess"`` unless the bracket closed on a zero). The result carries
    the two branches' tangents there (:func:`branch_point_directions`): its ``tangent`` is
    this branch's, its details the other's (``other_tangent``), for branch switching."""
    found = _locate(br, f_a, f_b)
    if found.status is PointStatus.POLE:  # the determinant changed sign through infinity
        return found
    theta = min(1.0, max(0.0, br.sigma(found.z) / br.h))
    estimate = br.arc.derivative(theta)  # this branch's tangent, from the step's arc
    directions = branch_point_directions(br.system, found.z, estimate, br.weights)
    tangent = directions.pop("tangent")
    if float(tangent @ br.row) < 0:
        tangent = -tangent
    return found._replace(tangent=tangent, details={**found.details, **directions})


def _locate(br: Bracket, f_a: float, f_b: float) -> Located:
    rough = _regula_falsi(br, f_a, f_b, rtol=1e-3)
    if rough.status is PointStatus.CONVERGED:
        found = _newton_extended(br, rough.z)
        if found is not None:
            return found
    found = _regula_falsi(br, f_a, f_b)
    if found.status is PointStatus.POLE:
        return found
    if found.status is PointStatus.CONVERGED and not found.details.get("exact_zero"):
        # the sign change is bracketed, but the points next to a branch point are corrected
        # only to about √tol (the corrector's matrix is singular there): not converged
        details = {**found.details, "reason": "extended-system Newton failed; bracketed only"}
        return found._replace(status=PointStatus.GUESS, details=details)
    return found


def branch_point_directions(
    system: CurveSystem, z: np.ndarray, estimate: np.ndarray, weights: np.ndarray, seed: int = 0
) -> dict[str, Any]:
    """The tangents of the two branches that cross at the simple branch point ``z``.

    ``estimate``: an approximation of this branch's tangent there (the step's interpolant:
    exactly at the branch point no bordered system gives it). The kernel of ``∂G/∂z`` is
    two-dimensional: it is computed (dense SVD up to :data:`MAX_DENSE` components, else
    inverse iteration on the bordered matrix) with the left null vector ``ψ``; ``t`` is the
    estimate projected onto the kernel, ``φ`` the kernel vector W-orthogonal to it. The
    branches' tangents ``α t + β φ`` solve the algebraic bifurcation equation

        ψ·D²G[α t + β φ]² = a11 α² + 2 a12 α β + a22 β² = 0,

    whose two roots are taken in full (not assuming β = 0 for this branch: ``t`` is only an
    estimate): the root nearer ``t`` is this branch (returned as ``tangent``, refined), the
    other is ``other_tangent``. Where the equation has no two distinct real roots (not a
    simple branch point) ``other_tangent`` is ``φ`` and ``details["abe_degenerate"]`` is
    set. All tangents have unit weighted norm.
    """
    dg = system.jacobian(z)
    t = estimate / math.sqrt(estimate @ (weights * estimate))
    if z.size <= MAX_DENSE + 1:
        dense = dg.toarray() if hasattr(dg, "toarray") else np.asarray(dg, dtype=float)
        u_, _, vt_ = np.linalg.svd(dense)
        psi, kernel = u_[:, -1], vt_[-2:]
        t = kernel.T @ (kernel @ t)  # onto the kernel
        t /= math.sqrt(t @ (weights * t))
        v = max(kernel, key=lambda k: _off(k, t, weights))
        phi = v - (v @ (weights * t)) * t
    else:
        phi, psi = _kernel_by_inverse_iteration(dg, weights * t, seed)
        phi = phi - (phi @ (weights * t)) * t
    phi /= math.sqrt(phi @ (weights * phi))

    def d2(v1: np.ndarray, v2: np.ndarray) -> float:
        row = second_derivative_row(system.jacobian, z, v1, psi, None, system.scales)
        return float(row @ v2)

    a11, a12, a22 = d2(t, t), d2(t, phi), d2(phi, phi)
    disc = a12 * a12 - a11 * a22
    scale = max(abs(a11), abs(a12), abs(a22), 1e-300)
    out: dict[str, Any] = {"null_vector": phi, "left_null_vector": psi}
    out["abe_coefficients"] = (a11, a12, a22)
    if disc <= 1e-16 * scale * scale:
        # no two distinct real roots: the orthogonal direction, flagged
        this, other = t, phi
        out["abe_degenerate"] = True
    else:
        q = -(a12 + math.copysign(math.sqrt(disc), a12))
        first = a22 * t + q * phi  # the root β/α = q/a22 (homogeneous: no division)
        second = q * t + a11 * phi  # the root β/α = a11/q
        first /= math.sqrt(first @ (weights * first))
        second /= math.sqrt(second @ (weights * second))
        near_first = abs(float(first @ (weights * t))) >= abs(float(second @ (weights * t)))
        this, other = (first, second) if near_first else (second, first)
        if float(this @ (weights * t)) < 0:
            this = -this
    out["tangent"] = this
    out["other_tangent"] = other
    return out


def _off(k: np.ndarray, t: np.ndarray, weights: np.ndarray) -> float:
    """How much of the kernel vector ``k`` is W-orthogonal to ``t``."""
    r = k - (k @ (weights * t)) * t
    return float(r @ (weights * r))


def _kernel_by_inverse_iteration(
    dg: Any, row: np.ndarray, seed: int
) -> tuple[np.ndarray, np.ndarray]:
    """The kernel vector of the nearly singular ``[∂G/∂z; rowᵀ]`` and the left null vector of
    ``∂G/∂z``, by four steps of inverse iteration from random vectors (for systems too large
    for a dense SVD)."""
    rng = np.random.default_rng(seed)
    try:
        lu = factor(bordered(dg, row))
    except SingularMatrixError:  # exactly singular: the dense SVD after all
        dense = dg.toarray() if hasattr(dg, "toarray") else np.asarray(dg, dtype=float)
        u_, _, vt_ = np.linalg.svd(dense)
        return vt_[-2] - (vt_[-2] @ row) / (vt_[-1] @ row) * vt_[-1], u_[:, -1]
    phi = rng.standard_normal(row.size)
    psi = rng.standard_normal(row.size)
    for _ in range(4):
        phi = lu.solve(phi)
        phi /= np.linalg.norm(phi)
        psi = lu.solve(psi, trans=True)
        psi /= np.linalg.norm(psi)
    return phi, psi[:-1]


def _bordered_det(system: CurveSystem, z: np.ndarray, row: np.ndarray) -> tuple[float, float]:
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
    outside the step. Dense for dense Jacobians of up to :data:`MAX_DENSE` components (the
    second derivatives column by column), sparse for sparse ones of any size (grouped
    columns: :func:`_hessian_plan`); dense ones above :data:`MAX_DENSE`: None."""
    system, o = br.system, br.options
    z = z0.copy()
    dg = system.jacobian(z)
    plan = None
    if sp.issparse(dg):
        plan = _hessian_plan(dg)
        psi = _kernel_by_inverse_iteration(dg, br.row, 0)[1]
        psi /= np.linalg.norm(psi)
    elif z.size <= MAX_DENSE:
        psi = _left_null_vector(dg)
    else:
        return None
    found = _extended_loop(system, o, z, psi, 0.0, dg, plan, system.jacobian)
    if not system.derivatives_exact and hasattr(system, "accurate_jacobian"):
        # differenced derivatives: the point solves G + μψ = 0, Gzᵀψ = 0 with the Jacobian
        # the differences give, off by their error to first order in the free parameter;
        # polished (or, where the plain ones did not converge, located) with the Jacobian
        # extrapolated to a higher order (the second-derivative block, which only steers
        # Newton, stays as it is)
        if found is not None:
            z, psi, mu = found[:3]
        else:
            mu = 0.0
        accurate = system.accurate_jacobian
        polished = _extended_loop(system, o, z, psi, mu, accurate(z), plan, accurate)
        if polished is not None:
            found = polished
    if found is None:
        return None
    z, psi, mu, dg, it, size = found
    method = "Newton on the extended system [G + mu psi; G_z^T psi; psi.psi - 1]"
    return accept_located(br, z, dg, it, size, {"method": method, "mu": float(mu)})


def _extended_loop(
    system: CurveSystem,
    o: ContinuationOptions,
    z: np.ndarray,
    psi: np.ndarray,
    mu: float,
    dg: Any,
    plan: Any,
    jac: Any,
) -> tuple | None:
    """Newton's iterations on the extended system from ``(z, ψ, μ)`` (``dg = jac(z)``) with
    the Jacobian ``jac``: ``(z, ψ, μ, jac(z), iterations, last update)``, or None if they
    fail."""
    m, n = psi.size, z.size
    previous, it, size = math.inf, 0, math.inf
    for it in range(1, o.max_locate_iterations + 1):
        try:
            if plan is None:
                d = dense_solve(*_extended_system(system, z, psi, mu, dg))[1]
            else:
                a, rhs = _extended_sparse(system, z, psi, mu, dg, plan)
                d = factor(a).solve(rhs)
        except SingularMatrixError:
            return None
        dz = d[:n]
        size = max(scaled_max(dz, inverse_magnitudes(system.scales, z)), max_abs(d[n : n + m]))
        if not math.isfinite(size):
            return None
        z, psi, mu = z - dz, psi - d[n : n + m], mu - float(d[-1])
        dg = jac(z)
        if newton_done(it, size, previous, o.locate_tol, stall=1e-8):
            return z, psi, mu, dg, it, size
        previous = size
    return None


def _hessian_plan(dg: Any) -> tuple[np.ndarray, np.ndarray, Any, list[np.ndarray]]:
    """How to difference ``H = Σ ψ_i ∇²G_i`` of a sparse ``G``: ``H_kj`` can be nonzero only
    where an equation depends on both ``z_k`` and ``z_j`` (the pattern ``SᵀS`` of the
    Jacobian's pattern ``S``). Columns of ``S`` with many entries (the free parameter's,
    ``wide``) are differenced one by one, giving their rows too (``H`` is symmetric); the
    others (``narrow``) in structurally orthogonal groups of ``SᵀS`` among themselves
    (:func:`~..problem._derivatives.column_groups`), one difference a group. Returns
    ``(narrow, wide, the narrow columns' pattern, the groups)``."""
    s = sp.csc_matrix(dg, dtype=float, copy=True)
    s.data[:] = 1.0
    m, n = s.shape
    wide = np.flatnonzero(np.diff(s.indptr) > max(8, m // 4))
    narrow = np.setdiff1d(np.arange(n), wide)
    sn = s[:, narrow]
    pattern = (sn.T @ sn).tocsc()
    return narrow, wide, pattern, column_groups(pattern)


def _sparse_hessian(system: CurveSystem, z: np.ndarray, psi: np.ndarray, plan: tuple) -> Any:
    """``H = Σ ψ_i ∇²G_i`` at ``z`` (CSC) by the grouped differences of ``plan``."""
    narrow, wide, pattern, groups = plan
    n = z.size
    rows: list[np.ndarray] = []
    cols: list[np.ndarray] = []
    vals: list[np.ndarray] = []
    d = np.zeros(n)
    for g in groups:
        d[narrow[g]] = 1.0
        hv = second_derivative_row(system.jacobian, z, d, psi, None, system.scales)
        d[narrow[g]] = 0.0
        part = pattern[:, g].tocoo()
        k = narrow[part.row]
        rows.append(k)
        cols.append(narrow[g[part.col]])
        vals.append(hv[k])
    for j in wide.tolist():  # column j, and row j where the groups left it out
        d[j] = 1.0
        hv = second_derivative_row(system.jacobian, z, d, psi, None, system.scales)
        d[j] = 0.0
        rows += [np.arange(n), np.full(narrow.size, j)]
        cols += [np.full(n, j), narrow]
        vals += [hv, hv[narrow]]
    data = (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols)))
    return sp.csc_matrix(data, shape=(n, n))


def _extended_sparse(
    system: CurveSystem, z: np.ndarray, psi: np.ndarray, mu: float, dg: Any, plan: tuple
) -> tuple[Any, np.ndarray]:
    """:func:`_extended_system` for a sparse Jacobian (the second derivatives by
    :func:`_sparse_hessian`)."""
    n, m = z.size, psi.size
    a = sp.bmat(
        [
            [dg, sp.diags(np.full(m, mu)), sp.csc_matrix(psi[:, None])],
            [_sparse_hessian(system, z, psi, plan), dg.T, None],
            [None, sp.csr_matrix(2.0 * psi[None, :]), None],
        ],
        format="csc",
    )
    rhs = np.empty(m + n + 1)
    rhs[:m] = system.residual(z) + mu * psi
    rhs[m : m + n] = dg.T @ psi
    rhs[-1] = psi @ psi - 1.0
    return a, rhs


def _extended_system(
    system: CurveSystem, z: np.ndarray, psi: np.ndarray, mu: float, dg: Any
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


__all__ = ["MAX_DENSE", "branch_point_directions", "locate_branch_point"]
