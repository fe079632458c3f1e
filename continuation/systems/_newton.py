"""The corrector: Newton's method on the bordered system ``[G(z); row·z − c] = 0`` of a curve
system, and the Jacobian factored at a point.

One corrector, :func:`newton` (its settings a :class:`NewtonSettings` record, its outcome a
:class:`NewtonResult` with a :class:`~.._outcomes.Convergence`): on arrays, dense (LAPACK
``gesv``) or sparse (SuperLU), and, for a curve of one unknown and its parameter
(``system.scalar``), in plain floats with 2×2 factors (:class:`~..numerics._linalg.PairLU`),
where numpy's and LAPACK's per-call costs would dominate. Both iterate the same way and take
their decisions from one place (:func:`_verdict`: convergence, divergence, contraction; the
first update's length checked alike), so they agree to rounding. :func:`damped_newton` is the
fallback at ``ds_min`` (Armijo backtracking on the residual's norm).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from .._errors import SingularMatrixError
from .._outcomes import Convergence
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
from ._curve import CurveSystem

if TYPE_CHECKING:
    from .._options import ContinuationOptions

# records are made by a static method of() and this bound object.__new__: a class method's
# binding and the lookup of __new__ on object cost a third of a record (callgrind), and the
# stepper makes several records a step
_new = object.__new__

#: the smallest update tolerance with differenced derivatives (they keep the updates from
#: getting much smaller); the two update tolerances are √step_tol (the error left is then
#: about step_tol) and step_tol itself (AUTO's test, see :func:`newton`)
FD_STEP_TOL = 1e-10

#: a residual that grows this many times over the larger of the last one and ``tol`` (from
#: the third iteration on) means Newton diverges
DIVERGENCE = 1e3

#: an update larger than this fraction of the one before means Newton does not contract
#: (Deuflhard's θ > 1/2)
CONTRACTION_LIMIT = 0.5


@dataclass(slots=True)
class NewtonSettings:
    """How far and how long :func:`newton` iterates.

    ``tol`` bounds the residual's max-norm, ``step_tol`` the error left after the last
    update (relative to the components' magnitudes), ``max_iterations`` the iterations.
    ``strict``: converged only by AUTO's test (the update itself below ``step_tol``: used to
    polish located points). ``contract``: give up as soon as an update above
    ``√step_tol`` is more than half the one before."""

    tol: float
    step_tol: float
    max_iterations: int
    strict: bool = False
    contract: bool = False
    sq_step_tol: float = field(init=False)
    """``√step_tol``: the update below which Newton is in its quadratic regime."""
    fd_step_tol: float = field(init=False)
    """AUTO's update tolerance with differenced derivatives, at least :data:`FD_STEP_TOL`."""

    def __post_init__(self) -> None:
        self.sq_step_tol = math.sqrt(self.step_tol)
        self.fd_step_tol = max(self.step_tol, FD_STEP_TOL)

    @classmethod
    def of(
        cls,
        options: ContinuationOptions,
        *,
        budget: int = 1,
        strict: bool = False,
        contract: bool = False,
    ) -> NewtonSettings:
        """The settings of ``options`` (its ``tol``, ``step_tol`` and ``budget`` times its
        ``max_newton_iterations``)."""
        # (by position: the class called with keywords gathers them in a dict first)
        tol, step_tol = options.tol, options.step_tol
        return cls(tol, step_tol, budget * options.max_newton_iterations, strict, contract)


@dataclass(slots=True)
class NewtonResult:
    """The outcome of the corrector, never changed after it is made except that the stepper
    may replace ``lu`` by the factorization at ``z`` itself
    (:func:`~..stepping._step.at_point`).

    ``z``: the point; ``converged``; ``iterations``; ``residual_norm``: the residual's
    max-norm at ``z``; ``lu``: the factorization of the last bordered matrix factored (at
    ``z`` minus the last update, or the last two after a simplified (chord) step; None if
    none was completed); ``reason``: why it stopped; ``contraction``: Deuflhard's first
    contraction ‖Δz₂‖/‖Δz₁‖ (0 if it converged in one iteration); ``first_update``: the
    relative size of the first update (both relative to the components' magnitudes)."""

    z: np.ndarray
    converged: bool
    iterations: int
    residual_norm: float
    lu: Any
    reason: Convergence
    contraction: float = 0.0
    first_update: float = math.inf

    @staticmethod
    def of(
        *,
        z: np.ndarray,
        converged: bool,
        iterations: int,
        residual_norm: float,
        lu: Any,
        reason: Convergence,
        contraction: float = 0.0,
        first_update: float = math.inf,
    ) -> NewtonResult:
        """A result built by keyword, fast (a class called with keywords builds a dict of
        them first: 1.2 µs against 0.4 µs here, on the corrector's every call)."""
        self = _new(NewtonResult)
        self.z = z
        self.converged = converged
        self.iterations = iterations
        self.residual_norm = residual_norm
        self.lu = lu
        self.reason = reason
        self.contraction = contraction
        self.first_update = first_update
        return self


# the outcomes, bound once (an enumeration's member costs a class attribute lookup each time)
_CONVERGED = Convergence.CONVERGED
_DIVERGING = Convergence.DIVERGING
_NOT_CONTRACTING = Convergence.NOT_CONTRACTING
_MAX_ITERATIONS = Convergence.MAX_ITERATIONS
_TOO_FAR = Convergence.TOO_FAR
_NONFINITE = Convergence.NONFINITE
_SINGULAR = Convergence.SINGULAR


def _verdict(
    k: int,
    sn: float,
    rn_new: float,
    rn: float,
    sn_prev: float,
    floor: Any,
    settings: NewtonSettings,
    rel_step_tol: float,
) -> Convergence | None:
    """Newton's tests after update ``k``, for both of its paths: CONVERGED, the reason to give
    up, or None to go on. ``sn``: the update relative to the components' magnitudes and
    ``sn_prev`` the one before; ``rn_new`` (``rn``): the residual's max-norm after (before)
    it; ``floor()``: the residual's rounding level at the new point, as small as it gets in
    floating point (called only when a test needs it); ``rel_step_tol``: AUTO's update
    tolerance (:func:`floor_step_tol`)."""
    tol, sq_step_tol = settings.tol, settings.sq_step_tol
    if sn <= sq_step_tol and not settings.strict and (rn_new <= tol or rn_new <= floor()):
        return _CONVERGED
    if sn <= rel_step_tol and rn_new <= max(tol, floor()):  # AUTO's test
        return _CONVERGED
    if k >= 3 and rn_new > DIVERGENCE * max(rn, tol):
        return _DIVERGING
    if settings.contract and sn > CONTRACTION_LIMIT * sn_prev and sn > sq_step_tol:
        return _NOT_CONTRACTING
    return None


def floor_step_tol(system: CurveSystem, settings: NewtonSettings) -> float:
    """The update tolerance of AUTO's test: ``settings.step_tol``, at least
    :data:`FD_STEP_TOL` with differenced derivatives."""
    return settings.step_tol if system.derivatives_exact else settings.fd_step_tol


def newton(
    system: CurveSystem,
    z0: np.ndarray,
    row: np.ndarray,
    c: float | None,
    settings: NewtonSettings,
    *,
    g0: np.ndarray | None = None,
    max_first: float | None = None,
) -> NewtonResult:
    """Solve ``G(z) = 0``, ``row·z = c`` by Newton's method from ``z0``.

    Parameters
    ----------
    system : CurveSystem
        ``G`` (m equations in m + 1 components).
    z0 : ndarray, shape (m + 1,)
        The start.
    row : ndarray, shape (m + 1,)
        The border: the hyperplane's normal.
    c : float or None
        The hyperplane's offset (None: the hyperplane through ``z0``, ``c = row·z0``).
    settings : NewtonSettings
        Tolerances, iteration limit, and when to give up early.
    g0 : ndarray, shape (m,), optional
        ``G(z0)``, if known.
    max_first : float, optional
        Give up (TOO_FAR) when the first update is longer than this in the weighted norm.

    Returns
    -------
    NewtonResult

    Notes
    -----
    Converged when the max-norm of ``G`` is ≤ ``tol`` (or at the rounding level of its own
    terms, ``system.residual_floor``: a tight ``tol`` cannot be met by a residual whose
    terms are large, as on fine discretisations) and the last update is ≤ ``√step_tol``
    relative to the components' magnitudes ``max(scale_i, |z_i|)``: under Newton's
    quadratic convergence the error left is then of order ``step_tol``; or, whatever the
    residual, when the update is ≤ ``step_tol`` (AUTO's test: residuals with large terms,
    such as finite differences on fine grids, cannot get below ``tol`` in floating point)
    and the residual is at its rounding floor (a wrong Jacobian, say differenced across a
    kink, also gives tiny updates but leaves the residual above it). ``strict`` requires the
    latter.

    Once an update is ≤ ``√step_tol`` (the quadratic regime) but the residual is still above
    ``tol``, the next iteration is a simplified (chord) step with the last factorization: it
    contracts the error by a factor of order that update, as a full step would, without a
    Jacobian evaluation and factorization. Full and simplified steps alternate from there.

    ``contract`` gives up (NOT_CONTRACTING) as soon as an update, still above ``√step_tol``,
    is more than half the one before: well inside its region of convergence Newton's updates
    shrink fast (every accepted step of the cusp and truss benchmarks has θ ≤ 0.06), and
    θ > 1/2 is Deuflhard's sign of a start outside it (a predictor beyond a fold reaches
    0.9–1.3); the step is then halved at once instead of spending every iteration first.
    ``max_first`` gives up when the first update is longer than it, before the residual is
    evaluated there: a continuation step rejects corrections longer than its
    step anyway, and where it lands the residual may not even be defined.

    A curve of two components whose equation comes in plain floats (``system.scalar``) is
    corrected in floats, with the same tests and results to rounding, in three quarters of
    the time (the cusp's corrector: 20 µs against 27 µs); anything that path cannot decide
    (a value that is not finite, a singular matrix, callbacks returning other types) is
    taken from the start on arrays. Dense matrices are factored and solved by one LAPACK
    ``gesv`` (wrapped in a DenseLU only for the result); the system is solved for minus the
    update (bitwise the same), and the bordering equation, being linear, holds to rounding
    after the first update, so its residual is computed once.
    """
    # the first update's weighted length is compared squared (no root on the common path)
    max_first_sq = math.inf if max_first is None else max_first * max_first
    if system.scalar:
        found = _on_floats(system, z0, row, c, settings, g0, max_first_sq)
        if found is not None:
            return found
    return _on_arrays(system, z0, row, c, settings, g0, max_first_sq)


def correct(
    system: CurveSystem,
    z0: np.ndarray,
    row: np.ndarray,
    c: float | None,
    options: ContinuationOptions,
    *,
    budget: int = 1,
    strict: bool = False,
    contract: bool = False,
    g0: np.ndarray | None = None,
) -> NewtonResult:
    """:func:`newton` with the tolerances of ``options`` and ``budget`` times its
    ``max_newton_iterations`` (:meth:`NewtonSettings.of`)."""
    settings = NewtonSettings.of(options, budget=budget, strict=strict, contract=contract)
    return newton(system, z0, row, c, settings, g0=g0)


class _Factors:
    """The array path's last factorization of its Newton matrix: LAPACK's factors of a dense
    one (``f``, ``piv``: one ``gesv`` factors and solves) or a sparse LU (``lu``), and the
    matrix ``a`` they factor."""

    __slots__ = ("f", "piv", "lu", "a")

    def __init__(self) -> None:
        self.f: Any = None
        self.piv: Any = None
        self.lu: Any = None
        self.a: Any = None

    def solve_new(self, a: Any, rhs: np.ndarray) -> np.ndarray | Convergence:
        """The solution with the matrix ``a`` factored now, or why it cannot be."""
        if type(a) is np.ndarray:  # dense: one LAPACK gesv (see dense_solve)
            f, piv, dz, info = _gesv(a, rhs)
            if info > 0 or not math.isfinite(f[-1, -1]):
                return _singular_reason(a)
            self.f, self.piv = f, piv
        else:
            try:
                self.lu = factor(a)
            except SingularMatrixError:
                return _singular_reason(a)
            dz = self.lu.solve(rhs)
        self.a = a
        return dz

    def update(
        self, system: CurveSystem, z: np.ndarray, row: np.ndarray, rhs: np.ndarray, chord: bool
    ) -> np.ndarray | Convergence:
        """Newton's update: with the last factorization (a simplified, chord, step: see
        :func:`newton`) or with the bordered matrix at ``z`` factored now; or why not."""
        if chord:
            return self.solve_again(rhs)
        try:
            return self.solve_new(system.bordered_jacobian(z, row), rhs)
        except SingularMatrixError:  # an augmented system's own matrix
            return _SINGULAR

    def solve_again(self, rhs: np.ndarray) -> np.ndarray:
        """The solution with the last factorization (a simplified, chord, step)."""
        return _getrs(self.f, self.piv, rhs)[0] if self.f is not None else self.lu.solve(rhs)

    def factorization(self) -> Any:
        """The last factorization (a :class:`~..numerics._linalg.DenseLU` or sparse LU)."""
        return self.lu if self.f is None else DenseLU.from_factors(self.f, self.piv)


def _on_arrays(
    system: CurveSystem,
    z0: np.ndarray,
    row: np.ndarray,
    c: float | None,
    settings: NewtonSettings,
    g0: np.ndarray | None,
    max_first_sq: float,
) -> NewtonResult:
    """:func:`newton` on arrays (any size, dense or sparse)."""
    z = z0  # never changed in place: each update makes a new array
    g = system.residual(z) if g0 is None else g0
    rn = _norm(g)
    if rn != rn:
        return _failed(z, 0, rn, _NONFINITE)
    rel_step_tol = floor_step_tol(system, settings)
    m = g.size
    rhs = np.empty(m + 1)
    inv = inverse_magnitudes(system.scales, z)
    weights = None if system.unit_weights else system.weights
    factors = _Factors()
    sn_prev = sn_first = math.inf
    reason, chord, k, theta = _MAX_ITERATIONS, False, 0, 0.0
    rhs[m] = 0.0 if c is None else row.dot(z) - c  # (None: z0 lies on the hyperplane)
    for k in range(1, settings.max_iterations + 1):
        rhs[:m] = g
        if k == 2:
            rhs[m] = 0.0
        dz = factors.update(system, z, row, rhs, chord)
        if isinstance(dz, Convergence):
            return _failed(z, k, rn, dz)
        if k == 1 and weighted_square(dz, weights) > max_first_sq:
            rn, reason = math.inf, _TOO_FAR
            break
        z = z - dz
        try:
            g = system.residual(z)
        except SingularMatrixError:  # an augmented system's matrix, singular at the new z
            rn, reason = math.inf, _SINGULAR
            break
        rn_new, sn = _norm(g), scaled_max(dz, inv)
        if k == 1:
            sn_first = sn
        elif k == 2:
            theta = sn / sn_first if sn_first > 0.0 else 0.0
        if rn_new != rn_new or sn != sn:
            rn, reason = rn_new, _NONFINITE
            break
        # (the floor is the terms' rounding at z itself, |∂G/∂z|·|z|: reckoned with a typical
        # size far above |z| it let y + 1e-8/y = b pass at y = 5e-9 with a residual of 2e-6)
        floor = lambda a=factors.a, z=z: system.residual_floor(a[:-1], z, np.abs(z))  # noqa: E731
        verdict = _verdict(k, sn, rn_new, rn, sn_prev, floor, settings, rel_step_tol)
        if verdict is not None:
            rn, reason = rn_new, verdict
            break
        rn = rn_new
        chord = not chord and sn <= settings.sq_step_tol
        sn_prev = sn
    return _finished(z, k, rn, factors.factorization(), reason, theta, sn_first)


def _on_floats(
    system: CurveSystem,
    z0: np.ndarray,
    row: np.ndarray,
    c: float | None,
    settings: NewtonSettings,
    g0: np.ndarray | None,
    max_first_sq: float,
) -> NewtonResult | None:
    """:func:`newton` for a curve of two components in plain floats: the residual and the
    Jacobian row from ``system.scalar_residual`` and ``system.scalar_jacobian``, the 2×2
    bordered matrix factored by :class:`~..numerics._linalg.PairLU`, the same tests (the
    rounding floor ``100·eps·|∂G/∂u|·|u|`` included). None where a value is not finite, a
    callback returns anything but a float array of the right shape, or a matrix is
    singular: the array path then decides (and says why). Its result is made here rather
    than by :func:`_finished`: a call less for every corrector of a step."""
    # (g0, given, is the system's residual: a float array of one value)
    g = system.scalar_residual(z0) if g0 is None else g0.item()
    if g is None or not abs(g) < math.inf:
        return None
    x, lam = z0.tolist()
    (r0, r1), (w0, w1) = row.tolist(), system.weights.tolist()
    i0, i1 = inverse_magnitudes(system.scales, z0)
    rel_step_tol = floor_step_tol(system, settings)
    b2 = 0.0 if c is None else r0 * x + r1 * lam - c  # the border's residual, then 0
    z, rn, a11, lu = z0, abs(g), 0.0, None
    sn_prev = sn_first = math.inf
    reason, chord, k, theta = _MAX_ITERATIONS, False, 0, 0.0
    floor = lambda: 100 * _EPS * abs(a11) * abs(x)  # noqa: E731 (the row's residual_floor)
    for k in range(1, settings.max_iterations + 1):
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
            rn, reason = math.inf, _TOO_FAR
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
        verdict = _verdict(k, sn, rn_new, rn, sn_prev, floor, settings, rel_step_tol)
        if verdict is not None:
            rn, reason = rn_new, verdict
            break
        rn, g = rn_new, g_new
        chord = not chord and sn <= settings.sq_step_tol
        sn_prev = sn
    return NewtonResult.of(
        z=z, converged=reason is _CONVERGED, iterations=k, residual_norm=rn, lu=lu,
        reason=reason, contraction=theta, first_update=sn_first,
    )  # fmt: skip


def _finished(
    z: np.ndarray,
    k: int,
    rn: float,
    lu: Any,
    reason: Convergence,
    theta: float,
    sn_first: float,
) -> NewtonResult:
    """The result of iterations that stopped at update ``k`` for ``reason``."""
    return NewtonResult.of(
        z=z,
        converged=reason is _CONVERGED,
        iterations=k,
        residual_norm=rn,
        lu=lu,
        reason=reason,
        contraction=theta,
        first_update=sn_first,
    )


def _failed(z: np.ndarray, k: int, rn: float, reason: Convergence, lu: Any = None) -> NewtonResult:
    """A result that did not converge, without contraction data."""
    return NewtonResult(z=z, converged=False, iterations=k, residual_norm=rn, lu=lu, reason=reason)


def _singular_reason(a: Any) -> Convergence:
    data = a.data if hasattr(a, "tocsr") else a
    return _SINGULAR if np.all(np.isfinite(data)) else _NONFINITE


def factor_at(system: CurveSystem, z: np.ndarray, row: np.ndarray) -> Any:
    """The factorization of ``[∂G/∂z(z); row]`` with the Jacobian evaluated at ``z`` itself,
    or None where that matrix is singular or not finite.

    A corrector's own last factorization is of the matrix at the iterate before its last
    update: a tangent solved with it is off by about that update times ``|D²G|/σ_min``,
    ``σ_min`` the smallest singular value of ``∂G/∂z``. Near a simple branch point
    ``σ_min`` tends to 0, and on a branch that is symmetric up to rounding (the trivial
    equilibrium of a pitchfork, reached from a guess) that error points along the other
    branch: the predictor moves off the symmetric branch by ``ds`` times it, every step, and
    the trace drifts onto the crossing branch. The tangent, the sign of the determinant and
    the arc's projection of an accepted point are therefore taken from the matrix at the
    point itself (one Jacobian and one factorization per accepted step)."""
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


def damped_newton(
    system: CurveSystem, z0: np.ndarray, row: np.ndarray, c: float, settings: NewtonSettings
) -> NewtonResult:
    """The fallback corrector at ``ds_min``: Newton with Armijo backtracking on
    ``‖[G; row·z − c]‖²`` (``settings``: its tolerances and iteration limit)."""
    tol, step_tol = settings.tol, settings.step_tol
    z = z0.copy()
    g = system.residual(z)
    if not np.all(np.isfinite(g)):
        return _failed(z, 0, float("inf"), Convergence.NONFINITE)
    m = g.size
    rhs = np.empty(m + 1)
    floor_tol = floor_step_tol(system, settings)

    def merit(zz, gg):
        return float(gg @ gg + (row @ zz - c) ** 2)

    phi = merit(z, g)
    lu = None
    for k in range(1, settings.max_iterations + 1):
        a = system.bordered_jacobian(z, row)
        try:
            lu = factor(a)
        except SingularMatrixError:
            return _failed(z, k, _norm(g), _singular_reason(a))
        rhs[:m] = -g
        rhs[m] = c - row @ z
        dz = lu.solve(rhs)
        inv = inverse_magnitudes(system.scales, z)
        if scaled_max(dz, inv) <= floor_tol and _norm(g) <= max(
            tol, system.residual_floor(a[:-1], z)
        ):
            return _converged(z + dz, k, _norm(g), lu)
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
            return _failed(z, k, _norm(g), Convergence.LINE_SEARCH, lu)
        z, g, phi = zt, gt, phit
        rn = _norm(g)
        if rn <= tol and scaled_max(lam * dz, inverse_magnitudes(system.scales, z)) <= step_tol:
            return _converged(z, k, rn, lu)
    return _failed(z, settings.max_iterations, _norm(g), Convergence.MAX_ITERATIONS, lu)


def _converged(z: np.ndarray, k: int, rn: float, lu: Any) -> NewtonResult:
    return NewtonResult.of(
        z=z, converged=True, iterations=k, residual_norm=rn, lu=lu, reason=_CONVERGED
    )


__all__ = [
    "NewtonResult",
    "NewtonSettings",
    "correct",
    "damped_newton",
    "factor_at",
    "floor_step_tol",
    "newton",
]
