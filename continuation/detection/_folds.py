"""The fold locator (:func:`locate_fold`): a turning point of any component ``z_k`` inside an
accepted step, by Newton on the minimally augmented system ``[G(z); g_k(z)] = 0``, with
``g_k`` from the bordered system of ``∂G/∂z`` without column ``k`` (Govaerts, *Numerical methods for
bifurcations of dynamical equilibria*, 2000) — quadratic convergence, bordering vectors
updated every iteration.

The bordering vectors are chosen in relative terms, so that the iteration does not depend on
the units of the unknowns: the row ``c`` is the null vector measured relative to the
components' magnitudes ``max(s_i, |z_i|)`` (:func:`_relative_border`), and the first column
``b``, before a left null vector is known, is ``∂G/∂z_k``, outside the range of the matrix
wherever the curve is regular (:func:`minimally_augmented`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._errors import SingularMatrixError
from .._outcomes import PointStatus
from ..numerics._differences import _CBRT_EPS, _SQRT_EPS, second_derivative_row
from ..numerics._linalg import (
    PairLU,
    bordered,
    bordered_square,
    delete_column,
    dense_solve,
    factor,
    inverse_magnitudes,
    max_abs,
    scaled_max,
    unit_last,
)
from ..problem._problem import has_exact_jacobian
from ..systems._curve import CurveSystem
from ._bracket import (
    Bracket,
    Located,
    accept_located,
    newton_done,
    oriented_tangent,
    tangent_at,
)
from ._regula import locate_on_arc

FOLD_SLACK = 1e-6
"""How far outside its step (as a fraction of it) a located fold may lie: the tangent's
sign at the step's ends is exact to about that (√step_tol). The 5% of other located points
took the neighbour of two folds 4% of a step apart, twice, for both."""

# relative error of the fold Newton's matrix when the Jacobian is exact: its last row is a
# forward difference of the Jacobian (√ε ≈ 1.5e-8, with a margin for its truncation error)
_FORWARD_D2_ERROR = 1e-7


def minimally_augmented(
    system: CurveSystem,
    z: np.ndarray,
    k: int,
    b: np.ndarray | None,
    c: np.ndarray,
    e: np.ndarray | None = None,
):
    """Test function ``g`` of the fold in component ``k``, its right/left null vectors and the
    Jacobian ``dg`` of G at ``z``: ``[[M, b], [c^T, 0]] [v; g] = [0; 1]`` with ``M = ∂G/∂z``
    without column ``k`` (``e``: that right-hand side, if the caller holds one). ``b`` None:
    the column ``∂G/∂z_k`` (unit), which lies outside the range of ``M`` wherever the curve
    is regular — at a fold it is the transversality condition — so that the bordered matrix
    is regular before a left null vector is known (the test function is then the tangent's
    component ``k``, up to a factor)."""
    dg = system.jacobian(z)
    if b is None:
        col = dg[:, k]
        b = np.ravel(col.toarray()) if type(col) is not np.ndarray else col.copy()
        b /= math.sqrt(b.dot(b))
    a = bordered_square(delete_column(dg, k), b, c)
    if e is None:
        e = unit_last(b.size + 1)
    if type(a) is np.ndarray:
        lu, x = dense_solve(a, e)
    else:
        lu = factor(a)
        x = lu.solve(e)
    y = lu.solve(e, trans=True)
    return x[-1], x[:-1], y[:-1], dg


def locate_fold(br: Bracket, k: int, f_a: float, f_b: float) -> Located:
    """The fold (turning point of component ``k``) inside the step ``br`` whose tangent
    component ``t_k`` changed sign from ``f_a`` to ``f_b``: the one fold locator.

    Newton on the minimally augmented system from the turning point of the step's arc
    (:func:`fold_newton`); from a poor start (a long step, two folds close together) the
    fold is first bracketed coarsely by regula falsi on ``t_k`` and Newton restarted there;
    where Newton fails (the fold system has no regular solution: a kink, or derivatives too
    rough to locate it) the point is a regula-falsi estimate only, a guess. With
    finite-difference derivatives a fold whose radius of curvature is within 100 difference
    steps is a guess too (:func:`_resolved`)."""
    found = fold_newton(br, k)
    if found is not None:
        return _resolved(found, br)

    def tangent_k(z: np.ndarray) -> float:
        return float(tangent_at(br.system, z, br.row, br.weights)[k])

    rough = locate_on_arc(br, tangent_k, f_a, f_b, rtol=1e-3)
    start_tangent = tangent_at(br.system, rough.z, br.row, br.weights)
    found = fold_newton(br, k, start=rough.z, tangent=start_tangent)
    if found is not None:
        method = "minimally augmented Newton (after regula falsi)"
        return _resolved(found._replace(details={**found.details, "method": method}), br)
    found = locate_on_arc(br, tangent_k, f_a, f_b)
    details = {**found.details, "method": "Illinois on the tangent component (Newton failed)"}
    ends = details.get("test_values", (0.0, 0.0))
    if min(abs(ends[0]), abs(ends[1])) > 1e-6:
        # the tangent component jumps instead of passing through zero
        details["non_smooth"] = True
    return _resolved(found._replace(status=PointStatus.GUESS, details=details), br)


def _resolved(found: Located, br: Bracket) -> Located:
    """``found``, a guess where, with finite-difference derivatives, the fold's radius of
    curvature is within 100 difference steps: it cannot be told from a kink smoothed by
    the stencil."""
    problem = br.system.problem
    if problem is None or has_exact_jacobian(problem):
        return found
    method = getattr(problem, "derivatives", "central")
    # the difference step, relative to the components' magnitudes; arclength is measured
    # in the same relative terms (the weights are 1/scale²)
    h_fd = np.finfo(float).eps ** (1 / 3 if method == "central" else 1 / 2)
    cos = float(br.t_a @ (br.weights * br.t_b))
    turn = math.acos(max(-1.0, min(1.0, cos)))
    if turn > 0 and abs(br.h) / turn < 100 * h_fd:
        reason = (
            f"radius of curvature {abs(br.h) / turn:.2g} is within 100 finite-difference "
            f"steps ({h_fd:.2g}): possibly a kink; supply a jacobian to decide"
        )
        details = {**found.details, "non_smooth": True, "reason": reason}
        return found._replace(status=PointStatus.GUESS, details=details)
    return found


def fold_newton(
    br: Bracket, k: int, start: np.ndarray | None = None, tangent: np.ndarray | None = None
) -> Located | None:
    """Newton on ``[G(z); g_k(z)] = 0`` from the turning point of the step's arc (or from
    ``start`` with its ``tangent``); None if it fails or leaves the step. A curve of two
    components is iterated in plain floats (:func:`_on_floats`), with the same stopping test
    and acceptance; what that cannot decide, on arrays (:func:`_on_arrays`)."""
    if start is None or tangent is None:
        z, tangent = br.arc.at_and_derivative(br.arc.turning(k))
    if start is not None:
        z = start.copy()
    if br.system.scalar:
        found = _on_floats(br, k, z, tangent)
        if found is not _UNDECIDED:
            return found
    return _on_arrays(br, k, z, tangent)


def _on_arrays(br: Bracket, k: int, z: np.ndarray, tangent: np.ndarray) -> Located | None:
    """:func:`fold_newton` on arrays (any size, dense or sparse)."""
    o, system = br.options, br.system
    # the components other than k (a slice for the usual fold in the last one)
    keep = slice(None, -1) if k == z.size - 1 else np.arange(z.size) != k
    # the bordering row in relative terms: c = v̂/m with v̂ = v/m of unit length and m
    # (mags) the components' magnitudes max(s_i, |z_i|) (a Euclidean unit v of components
    # 1e-9 and 1e6 leaves the small one to cancellation, and the null vector with it);
    # the updates are measured against the magnitudes in this step (local_magnitudes)
    scales, local = system.scales, local_magnitudes(br, z)
    mags = 1.0 / np.asarray(inverse_magnitudes(scales, z), dtype=float)[keep]
    b, c = None, _relative_border(tangent[keep], mags)
    rhs, vt, e = np.empty(z.size), np.zeros(z.size), unit_last(z.size)
    exact = system.exact_jacobian
    converged, it, sizes = False, 0, (math.inf, math.inf)
    for it in range(1, o.max_locate_iterations + 1):
        try:
            g, v, w, dg = minimally_augmented(system, z, k, b, c, e)
        except SingularMatrixError:
            return None
        vt[keep] = v
        # the Newton system [∂G/∂z; ∇g] dz = −[G; g] with ∇g = −w·D²G[v, ·], solved for
        # d = −dz with that row negated (sign flips are exact: bitwise the same update)
        rhs[:-1] = system.residual(z)
        rhs[-1] = -g
        second = second_derivative_row(system.jacobian, z, vt, w, dg if exact else None, scales)
        a = bordered(dg, second)
        try:
            d = dense_solve(a, rhs)[1] if type(a) is np.ndarray else factor(a).solve(rhs)
        except SingularMatrixError:
            return None
        update = (scaled_max(d, inverse_magnitudes(local, z)), scaled_max(d, 1.0 / scales))
        if not math.isfinite(update[0]):
            return None
        z = z - d
        nb = math.sqrt(w.dot(w))
        if nb > 0 and max_abs(v) > 0:
            b, c = w / nb, _relative_border(v, mags)
        zk, mk, sk = abs(float(z[k])), float(local[k]), float(scales[k])
        if _fold_newton_done(o, it, update, sizes, zk, mk, sk, exact):
            converged = True
            break
        sizes = update
    if not converged:
        return None
    # the tangent at a fold in z_k spans the kernel of ∂G/∂z, which has no k component: v
    # (from the last iterate, one update of ≤ locate_tol away)
    details = {"method": "minimally augmented Newton", "test_function": float(g)}
    t_fold = oriented_tangent(vt, br.row, br.weights)
    return accept_located(br, z, dg, it, update[0], details, t_fold, FOLD_SLACK, local)


def local_magnitudes(br: Bracket, z: np.ndarray) -> np.ndarray:
    """The components' magnitudes where a point is located in the step ``br``:
    ``max(|z_i|, min(s_i, max(|z_a,i|, |z_b,i|)))`` (``s_i`` where that is 0) — what they
    are in this step, not the typical size ``s_i`` they got where the curve began, which
    only grows. A concentration sized 1e7 at the start and 2.7e-22 at a fold was located to
    1e-12 of 1e7 (2e-7 of itself, at a residual of 2e-7 that a rounding floor reckoned
    with 1e7 let pass); a component crossing 0 in the step keeps the size of its ends."""
    s = br.system.scales
    ends = np.maximum(np.abs(br.z_a), np.abs(br.z_b))
    m = np.maximum(np.abs(z), np.minimum(s, ends))
    return np.where(m > 0.0, m, s)


def _fold_newton_done(
    o: Any,
    it: int,
    update: tuple[float, float],
    previous: tuple[float, float],
    zk: float,
    mk: float,
    sk: float,
    exact: bool,
) -> bool:
    """The fold Newton's stopping test (:func:`~._bracket.newton_done`) on the update relative
    to the local magnitudes (``update[0]``), the fold's component ``zk`` to the tolerance
    relative to itself even where it is far below its magnitude ``mk``; an early stop (on
    the estimated next update) needs the same of the update relative to the typical sizes
    (``update[1]``), whose estimate is the more cautious where the fold's component is far
    below its size ``sk``. Or stagnation below 1e-6 of the typical sizes: ill-conditioned
    systems (cond ~ N² for discretised operators), forward differences and components that
    rounding in the terms of their equations limits relative to themselves stall there; the
    fold's parameter is still exact to second order, its state to the accuracy of the
    derivatives."""
    tol, d2 = o.locate_tol, _FORWARD_D2_ERROR if exact else None
    if update[0] <= tol:
        return True
    if newton_done(it, update[0], previous[0], tol, 0.0, d2, zk / max(mk, zk)) and newton_done(
        it, update[1], previous[1], tol, 0.0, d2, zk / max(sk, zk)
    ):
        return True
    return it >= 4 and update[1] > 0.5 * previous[1] and update[1] <= 1e-6


def _relative_border(v: np.ndarray, d: np.ndarray) -> np.ndarray:
    """``v̂/(|v̂|·d)`` with ``v̂ = v/d``: a bordering row ``c`` for the null vector ``v``
    whose product ``c·v = |v̂|`` weighs every component relative to its magnitude ``d``."""
    u = v / d
    return u / (math.sqrt(u.dot(u)) * d)


_UNDECIDED = object()


def _on_floats(br: Bracket, k: int, z: np.ndarray, tangent: np.ndarray) -> Any:
    """:func:`fold_newton` on a curve of two components in plain floats (``system.scalar``):
    with one unknown the minimally augmented system has a closed form — ``M = ∂G/∂z_j``
    (j ≠ k) is a number, ``v = 1/c``, ``w = 1/b``, ``g = −M/(bc)`` — and the Newton matrix
    ``[∂G/∂z; w·D²G[v, ·]]`` is 2×2 (:class:`~..numerics._linalg.PairLU`); the second
    derivatives are differenced as :func:`second_derivative_row` does, and the stopping test
    is the same.
    The located point, or None if Newton fails; ``_UNDECIDED`` where a value is not finite,
    a callback returns another type or a matrix is singular (the array path then runs)."""
    o, system = br.options, br.system
    j = 1 - k
    if not abs(tangent[j]) > 0.0:
        return _UNDECIDED
    x = z.tolist()
    s = system.scales.tolist()
    local = local_magnitudes(br, z)  # (the updates' measure, as on arrays)
    b = c = 1.0 if tangent[j] > 0 else -1.0
    exact = system.exact_jacobian
    jac_row, res = system.scalar_jacobian, system.scalar_residual
    converged, it, sizes, update = False, 0, (math.inf, math.inf), (math.inf, math.inf)
    for it in range(1, o.max_locate_iterations + 1):
        zz = np.array(x)
        row0 = jac_row(zz)
        G = res(zz)
        if row0 is None or G is None:
            return _UNDECIDED
        v, w = 1.0 / c, 1.0 / b
        g = -row0[j] * v / b
        # w·D²G[v·e_j, ·] by differences of the Jacobian row along e_j (the step of
        # second_derivative_row: forward for exact derivatives, central otherwise)
        scale = 1.0 / (abs(v) * (1.0 / max(s[j], abs(x[j]))))
        up: tuple[float, float] | None
        down: tuple[float, float] | None
        if exact:
            z1 = list(x)
            z1[j] = x[j] + (_SQRT_EPS * scale) * v
            h = abs(z1[j] - x[j]) / abs(v)
            up, down = jac_row(np.array(z1)), row0
        else:
            h = _CBRT_EPS * scale
            zp, zm = list(x), list(x)
            zp[j], zm[j] = x[j] + h * v, x[j] - h * v
            up, down, h = jac_row(np.array(zp)), jac_row(np.array(zm)), 2.0 * h
        if up is None or down is None:
            return _UNDECIDED
        try:
            lu = PairLU(row0[0], row0[1], (up[0] - down[0]) * w / h, (up[1] - down[1]) * w / h)
        except SingularMatrixError:
            return None
        d0, d1 = lu.solve_pair(G, -g)
        i0, i1 = inverse_magnitudes(local, zz)
        update = (max(abs(d0) * i0, abs(d1) * i1), max(abs(d0) / s[0], abs(d1) / s[1]))
        if not update[0] < math.inf:
            return None
        x = [x[0] - d0, x[1] - d1]
        b, c = (1.0 if w > 0 else -1.0), (1.0 if v > 0 else -1.0)
        if _fold_newton_done(o, it, update, sizes, abs(x[k]), float(local[k]), s[k], exact):
            converged = True
            break
        sizes = update
    if not converged:
        return None
    vt = np.zeros(2)
    vt[j] = v
    details = {"method": "minimally augmented Newton", "test_function": float(g)}
    dg, zf = np.array([row0]), np.array(x)
    t = oriented_tangent(vt, br.row, br.weights)
    return accept_located(br, zf, dg, it, update[0], details, t, FOLD_SLACK, local)
