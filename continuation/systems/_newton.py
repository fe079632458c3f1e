"""Newton correctors on the bordered system ``[G(z); r·z − c] = 0``."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .._errors import SingularMatrixError
from ..numerics._linalg import (
    _EPS,
    DenseLU,
    PairLU,
    _gesv,
    _getrf,
    _getrs,
    factor,
    inverse_magnitudes,
    scaled_max,
    weighted_square,
)
from ..numerics._linalg import max_abs as _norm


class NewtonResult:
    """The outcome of a corrector: the point ``z``, whether it ``converged``, the
    ``iterations``, the max-norm of the residual, ``lu`` (the factorization of the last
    bordered matrix factored, at ``z`` minus the last update, or the last two when the last
    step was a simplified (chord) one; None if none was completed) and, on failure, the
    ``reason``; ``contraction`` is Deuflhard's first contraction ‖Δz₂‖/‖Δz₁‖ (0 if it
    converged in one iteration) and ``first_update`` the relative size of the first update
    (both relative to the components' magnitudes).

    A record that is never changed after it is made (a new one replaces it where a value
    changes); a slotted class rather than a NamedTuple because the step reads its fields
    often (a NamedTuple field costs twice a slot to read in CPython 3.11)."""

    __slots__ = (
        "z", "converged", "iterations", "residual_norm", "lu", "reason", "contraction",
        "first_update",
    )  # fmt: skip

    def __init__(
        self,
        z: np.ndarray,
        converged: bool,
        iterations: int,
        residual_norm: float,
        lu: Any,
        reason: str = "",
        contraction: float = 0.0,
        first_update: float = math.inf,
    ) -> None:
        self.z, self.converged, self.iterations = z, converged, iterations
        self.residual_norm, self.lu, self.reason = residual_norm, lu, reason
        self.contraction, self.first_update = contraction, first_update


#: the smallest update tolerance with differenced derivatives (they keep the updates from
#: getting much smaller); the two update tolerances are √step_tol (the error left is then
#: about step_tol) and step_tol itself (AUTO's test, see :func:`newton`)
_FD_STEP_TOL = 1e-10


def _floor_step_tol(system: Any, step_tol: float) -> float:
    """The update tolerance of AUTO's test: ``step_tol``, at least :data:`_FD_STEP_TOL`
    with differenced derivatives."""
    return step_tol if system.derivatives_exact else max(step_tol, _FD_STEP_TOL)


def _verdict(
    k: int, sn: float, rn_new: float, rn: float, sn_prev: float, floor: Any, tol: float,
    sq_step_tol: float, rel_step_tol: float, strict: bool, contract: bool,
) -> str:  # fmt: skip
    """Newton's tests after update ``k`` (see :func:`newton`), for both of its paths:
    ``"converged"``, the reason to give up, or ``""`` to go on. ``sn``: the update relative
    to the components' magnitudes and ``sn_prev`` the one before; ``rn_new`` (``rn``): the
    residual's max-norm after (before) it; ``floor()``: the residual's rounding level at the
    new point, as small as it gets in floating point (called only when a test needs it)."""
    if sn <= sq_step_tol and not strict and (rn_new <= tol or rn_new <= floor()):
        return "converged"
    if sn <= rel_step_tol and rn_new <= max(tol, floor()):  # AUTO's test
        return "converged"
    if k >= 3 and rn_new > 1e3 * max(rn, tol):
        return "diverging"
    if contract and sn > 0.5 * sn_prev and sn > sq_step_tol:
        return "not_contracting"
    return ""


def _sparse_step(a: Any, rhs: np.ndarray) -> tuple[Any, Any, str]:
    """A sparse Newton matrix factored and solved for ``rhs``: ``(LU, solution, "")``, or the
    reason it failed last."""
    try:
        lu = factor(a)
    except SingularMatrixError:
        return None, None, _singular_reason(a)
    return lu, lu.solve(rhs), ""


def _singular_reason(a) -> str:
    data = a.data if hasattr(a, "tocsr") else a
    return "singular" if np.all(np.isfinite(data)) else "nonfinite"


def newton(
    system, z0: np.ndarray, row: np.ndarray, c: float | None, *, tol: float, step_tol: float,
    max_iter: int, g0: np.ndarray | None = None, strict: bool = False, contract: bool = False,
    max_first: float | None = None,
) -> NewtonResult:  # fmt: skip
    """Solve ``G(z) = 0``, ``row·z = c`` by Newton's method from ``z0`` (``c`` None: the
    hyperplane through ``z0``, ``c = row·z0``).

    Converged when the max-norm of ``G`` is ≤ ``tol`` (or at the rounding level of its own
    terms, ``system.residual_floor``: a tight ``tol`` cannot be met by a residual whose terms
    are large, as on fine discretisations) and the last update is
    ≤ ``sqrt(step_tol)·(1 + |z|)``: under Newton's quadratic convergence the error left is
    then of order ``step_tol`` (the next update would be about the square of the last); or,
    whatever the residual, when the update is ≤ ``step_tol·(1 + |z|)`` (AUTO's test:
    residuals with large terms, such as finite differences on fine grids, cannot get below
    ``tol`` in floating point) and the residual is at the rounding level of its own terms
    (``system.residual_floor``; a wrong Jacobian, say differenced across a kink, also gives
    tiny updates but leaves the residual above that floor). ``strict`` requires the latter
    (used to polish located special points to rounding).

    Once an update is ≤ ``sqrt(step_tol)·(1 + |z|)`` (Newton's quadratic regime) but the
    residual is still above ``tol``, the next iteration is a simplified (chord) step with the
    last factorization: it contracts the error by a factor of order that update, as a full
    step would, without a Jacobian evaluation and factorization (a sparse LU of the bordered
    system, on large discretisations). Full and simplified steps alternate from there.

    ``contract``: give up (reason ``"not_contracting"``) as soon as an update, still above
    ``sqrt(step_tol)·(1 + |z|)``, is more than half the one before. Well inside its region of
    convergence Newton's updates shrink fast (contraction θ = |Δz_k|/|Δz_{k−1}| ≪ 1; on the
    cusp and truss benchmarks every accepted step has θ ≤ 0.06), and θ > 1/2 is Deuflhard's
    sign of a start outside that region (typically a predictor beyond a fold, whose
    hyperplane misses the curve, where θ reaches 0.9–1.3); the continuation step uses this to
    halve the step at once instead of spending the whole iteration budget first.

    ``max_first``: give up (reason ``"too_far"``) when the first update is longer than this
    in the system's weighted (arclength) norm, before the residual is evaluated there: a
    continuation step rejects corrections longer than its step anyway, and a first update
    of more than twice that (with a contraction below 1/2 the correction is at least half
    the first update) lands where the residual may not even be defined.

    A curve of two components whose equation comes in plain floats (``system.scalar``: a
    branch of one unknown) is corrected in floats (:func:`scalar_newton`), with the same
    tests and results to rounding, for three quarters of the time (the cusp's corrector:
    20 µs against 27 µs, most of the rest the user's functions); anything that path cannot
    decide is taken from the start by the general one.

    Implementation notes: dense matrices are factored and solved by one LAPACK gesv (the
    factors are wrapped in a DenseLU only for the result), sparse ones through ``factor``;
    the system is solved for minus the update (saves negating the residual; bitwise the
    same), and the bordering equation, being linear, holds to rounding after the first
    update, so its residual is computed once.
    """
    if system.scalar:
        found = scalar_newton(
            system, z0, row, c, tol, step_tol, max_iter, g0, strict, contract, max_first
        )
        if found is not None:
            return found
    return _newton_arrays(
        system, z0, row, c, tol, step_tol, max_iter, g0, strict, contract, max_first
    )


def _newton_arrays(
    system, z0, row, c, tol, step_tol, max_iter, g0, strict, contract, max_first
) -> NewtonResult:  # fmt: skip
    """:func:`newton` on arrays (any size, dense or sparse)."""
    z = z0  # never changed in place: each update makes a new array
    g = system.residual(z) if g0 is None else g0
    rn = _norm(g)
    if rn != rn:
        return NewtonResult(z, False, 0, rn, None, "nonfinite")
    m = g.size
    rhs = np.empty(m + 1)
    inv = inverse_magnitudes(system.scales, z)
    sq_step_tol = math.sqrt(step_tol)
    rel_step_tol = step_tol if system.derivatives_exact else max(step_tol, _FD_STEP_TOL)
    # the first update's weighted length is compared squared (no root on the common path)
    max_first_sq = math.inf if max_first is None else max_first * max_first
    weights = None if system.unit_weights else system.weights
    bordered_jacobian, residual = system.bordered_jacobian, system.residual
    sn_prev = sn_first = math.inf
    lu: Any = None
    f: Any = None
    piv: Any = None
    reason, converged, chord, k, theta = "max_iterations", False, False, 0, 0.0
    rhs[m] = 0.0 if c is None else row.dot(z) - c  # (None: z0 lies on the hyperplane)
    for k in range(1, max_iter + 1):
        rhs[:m] = g
        if k == 2:
            rhs[m] = 0.0
        if chord:  # a simplified step with the last factorization (see above)
            dz = _getrs(f, piv, rhs)[0] if f is not None else lu.solve(rhs)
        else:
            try:
                a = bordered_jacobian(z, row)
            except SingularMatrixError:  # an augmented system's own matrix
                return NewtonResult(z, False, k, rn, None, "singular")
            if type(a) is np.ndarray:  # dense: one LAPACK gesv (see dense_solve)
                f, piv, dz, info = _gesv(a, rhs)
                if info > 0 or not math.isfinite(f[-1, -1]):
                    return NewtonResult(z, False, k, rn, None, _singular_reason(a))
            else:
                lu, dz, why = _sparse_step(a, rhs)
                if why:
                    return NewtonResult(z, False, k, rn, None, why)
        if k == 1 and weighted_square(dz, weights) > max_first_sq:
            rn, reason = math.inf, "too_far"
            break
        z = z - dz
        try:
            g = residual(z)
        except SingularMatrixError:  # an augmented system's matrix, singular at the new z
            rn, reason = math.inf, "singular"
            break
        rn_new, sn = _norm(g), scaled_max(dz, inv)
        if k == 1:
            sn_first = sn
        elif k == 2:
            theta = sn / sn_first if sn_first > 0.0 else 0.0
        if rn_new != rn_new or sn != sn:
            rn, reason = rn_new, "nonfinite"
            break
        # (the floor is the terms' rounding at z itself, |∂G/∂z|·|z|: reckoned with a typical
        # size far above |z| it let y + 1e-8/y = b pass at y = 5e-9 with a residual of 2e-6)
        verdict = _verdict(
            k, sn, rn_new, rn, sn_prev,
            lambda a=a, z=z: system.residual_floor(a[:-1], z, np.abs(z)),
            tol, sq_step_tol, rel_step_tol, strict, contract,
        )  # fmt: skip
        if verdict:
            rn, converged, reason = rn_new, verdict == "converged", verdict
            break
        rn = rn_new
        chord = not chord and sn <= sq_step_tol
        sn_prev = sn
    lu = lu if f is None else DenseLU.from_factors(f, piv)
    return NewtonResult(z, converged, k, rn, lu, "" if converged else reason, theta, sn_first)


def scalar_newton(
    system, z0, row, c, tol, step_tol, max_iter, g0, strict, contract, max_first
) -> NewtonResult | None:  # fmt: skip
    """:func:`newton` for a curve of two components in plain floats: the residual and the
    Jacobian row come from ``system.scalar_residual`` and ``system.scalar_jacobian``, the
    2×2 bordered matrix is factored by :class:`~..numerics._linalg.PairLU`, and the tests are
    :func:`newton`'s, the rounding floor ``100·eps·|∂G/∂u|·max(scale, |u|)`` included.
    None where a value is not finite, a callback returns anything but a float array of the
    right shape, or a matrix is singular: the general path then decides (and says why)."""
    # (g0, given, is the system's residual: a float array of one value)
    g = system.scalar_residual(z0) if g0 is None else g0.item()
    if g is None or not abs(g) < math.inf:
        return None
    x, lam = z0.tolist()
    r0, r1 = row.tolist()
    w0, w1 = system.weights.tolist()
    i0, i1 = inverse_magnitudes(system.scales, z0)
    sq_step_tol = math.sqrt(step_tol)
    rel_step_tol = _floor_step_tol(system, step_tol)
    max_first_sq = math.inf if max_first is None else max_first * max_first
    b2 = 0.0 if c is None else r0 * x + r1 * lam - c  # the border's residual, then 0
    z, rn, a11, lu = z0, abs(g), 0.0, None
    sn_prev = sn_first = math.inf
    reason, converged, chord, k, theta = "max_iterations", False, False, 0, 0.0
    for k in range(1, max_iter + 1):
        if not chord:
            jac = system.scalar_jacobian(z)
            if jac is None:
                return None
            a11 = jac[0]
            try:
                lu = PairLU(a11, jac[1], r0, r1)
            except SingularMatrixError:
                return None
        d0, d1 = lu.solve_pair(g, b2)  # type: ignore[union-attr]
        b2 = 0.0
        if k == 1 and w0 * d0 * d0 + w1 * d1 * d1 > max_first_sq:
            rn, reason = math.inf, "too_far"
            break
        x, lam = x - d0, lam - d1
        z = np.array((x, lam))
        g_new = system.scalar_residual(z)
        if g_new is None:
            return None
        rn_new, sn = abs(g_new), max(abs(d0) * i0, abs(d1) * i1)
        if not sn < math.inf:
            return None
        if k == 1:
            sn_first = sn
        elif k == 2:
            theta = sn / sn_first if sn_first > 0.0 else 0.0
        verdict = _verdict(
            k, sn, rn_new, rn, sn_prev,
            # (CurveSystem.residual_floor of the Jacobian row at the new point)
            lambda a11=a11, x=x: 100 * _EPS * abs(a11) * abs(x),
            tol, sq_step_tol, rel_step_tol, strict, contract,
        )  # fmt: skip
        if verdict:
            rn, converged, reason = rn_new, verdict == "converged", verdict
            break
        rn, g = rn_new, g_new
        chord = not chord and sn <= sq_step_tol
        sn_prev = sn
    return NewtonResult(z, converged, k, rn, lu, "" if converged else reason, theta, sn_first)


def factor_at(system: Any, z: np.ndarray, row: np.ndarray) -> Any:
    """The factorization of ``[∂G/∂z(z); row]`` with the Jacobian evaluated at ``z`` itself,
    or None where that matrix is singular or not finite.

    A corrector's own last factorization is of the matrix at the iterate before its last
    update: a tangent solved with it is off by about that update times ``|D²G|/σ_min``,
    ``σ_min`` the smallest singular value of ``∂G/∂z``. Near a simple branch point
    ``σ_min`` tends to 0, and on a branch that is symmetric up to rounding (the trivial
    equilibrium of a pitchfork, reached from a guess) that error points along the other
    branch: the predictor moves off the symmetric branch by ``ds`` times it, every step, and
    the trace drifts onto the crossing branch. The tangent, the sign of the determinant and
    the interpolant's projection of an accepted point are therefore taken from the matrix at
    the point itself (one Jacobian and one factorization per accepted step)."""
    if system.scalar:
        jac = system.scalar_jacobian(z)
        if jac is not None:
            r0, r1 = row.tolist()
            try:
                return PairLU(jac[0], jac[1], r0, r1)
            except SingularMatrixError:
                return None
    try:
        a = system.bordered_jacobian(z, row)
        if type(a) is np.ndarray:
            f, piv, info = _getrf(a)
            if info > 0 or not math.isfinite(f[-1, -1]):
                return None
            return DenseLU.from_factors(f, piv)
        return factor(a)
    except SingularMatrixError:
        return None


def correct(
    system: Any,
    z0: np.ndarray,
    row: np.ndarray,
    c: float | None,
    options: Any,
    *,
    budget: int = 1,
    **kwargs: Any,
) -> NewtonResult:
    """:func:`newton` with the tolerances of ``options`` (a
    :class:`~.._options.ContinuationOptions`) and ``budget`` times its
    ``max_newton_iterations``; other keywords are passed on."""
    return newton(
        system, z0, row, c, tol=options.tol, step_tol=options.step_tol,
        max_iter=budget * options.max_newton_iterations, **kwargs,
    )  # fmt: skip


def damped_newton(
    system, z0: np.ndarray, row: np.ndarray, c: float, *, tol: float, step_tol: float, max_iter: int
) -> NewtonResult:
    """Fallback corrector: Newton with Armijo backtracking on ``||[G; r·z − c]||²``."""
    z = z0.copy()
    g = system.residual(z)
    if not np.all(np.isfinite(g)):
        return NewtonResult(z, False, 0, float("inf"), None, "nonfinite")
    m = g.size
    rhs = np.empty(m + 1)
    floor_tol = _floor_step_tol(system, step_tol)

    def merit(zz, gg):
        return float(gg @ gg + (row @ zz - c) ** 2)

    phi = merit(z, g)
    lu = None
    for k in range(1, max_iter + 1):
        a = system.bordered_jacobian(z, row)
        try:
            lu = factor(a)
        except SingularMatrixError:
            return NewtonResult(z, False, k, _norm(g), None, _singular_reason(a))
        rhs[:m] = -g
        rhs[m] = c - row @ z
        dz = lu.solve(rhs)
        inv = inverse_magnitudes(system.scales, z)
        if scaled_max(dz, inv) <= floor_tol and _norm(g) <= max(
            tol, system.residual_floor(a[:-1], z)
        ):
            return NewtonResult(z + dz, True, k, _norm(g), lu)
        lam = 1.0
        while lam > 1e-6:
            zt = z + lam * dz
            try:
                gt = system.residual(zt)
            except SingularMatrixError:
                gt = np.full(m, math.inf)
            if np.all(np.isfinite(gt)):
                phit = merit(zt, gt)
                if phit <= (1.0 - 1e-4 * lam) * phi or phit == 0.0:
                    break
            lam *= 0.5
        else:
            return NewtonResult(z, False, k, _norm(g), lu, "line_search")
        z, g, phi = zt, gt, phit
        rn = _norm(g)
        if rn <= tol and scaled_max(lam * dz, inverse_magnitudes(system.scales, z)) <= step_tol:
            return NewtonResult(z, True, k, rn, lu)
    return NewtonResult(z, False, max_iter, _norm(g), lu, "max_iterations")
