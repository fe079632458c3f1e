"""The predictor–corrector phase of a continuation step.

From the last point ``z`` with unit tangent ``t`` and step size ``ds``:

- **predict**: ``z + ds·d`` along the tangent (or the secant through the last two points);
- **correct**: Newton on ``[G(z); row·z = row·z_pred]`` with ``row = W d``; the step is
  accepted when Newton converges and the guards pass (:mod:`._control`), and otherwise
  retried shorter down to ``ds_min`` (where a damped Newton is tried last);
- two variants replace the arclength step (:mod:`._advance`): a step whose tangent line
  crosses a bound with margin is **aimed at the bound**, and at a **corner** (a non-smooth
  turning point, or after many steps creeping at ``ds_min``) natural-parameter steps in one
  component are tried.

Here: one try of a step (:func:`try_step`), its outcome (:class:`Trial`, :class:`Rejected`,
:class:`Failure`) and the step's rules; :func:`~._advance.advance` takes the step.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from .._errors import (
    ContinuationError,
    ConvergenceError,
    NonFiniteResidualError,
    SingularMatrixError,
    StepGuardError,
    format_values,
)
from .._outcomes import Convergence, Guard, Status
from ..detection._tests import BoundTest
from ..numerics._arc import HermiteArc, arc_from
from ..numerics._linalg import max_abs, weighted_square
from ..systems._curve import CurveSystem
from ..systems._newton import (
    NewtonResult,
    NewtonSettings,
    damped_newton,
    factor_at,
    newton,
)
from ._control import Rejection, guard_factor, interpolation_factor
from ._work import Solve, StepWork

if TYPE_CHECKING:
    from .._options import ContinuationOptions

logger = logging.getLogger(__name__)

# records are made by a static method of() and this bound object.__new__: a class method's
# binding and the lookup of __new__ on object cost a third of a record (callgrind), and the
# stepper makes several records a step
_new = object.__new__

SINGULAR_CUT = 0.4
"""The cut of a step whose Newton matrix is singular: a trial point on a singular point of
the curve (a step of exactly the distance to a branch point); halving would land on it again
from every dyadic point before it, so the cut is not a power of 2."""

MIN_FACTOR = 0.1
"""A rejected step is retried at least this large (times ds)."""

STALL_STEPS = 10
"""Steps at ds < STALL_FACTOR·ds_min before a corner step is tried."""

STALL_FACTOR = 1e3

STALL_LIMIT = 100
"""Steps creeping below STALL_FACTOR·ds_min before the branch ends."""

_SINGULAR_RESULT = NewtonResult(
    z=np.zeros(0),
    converged=False,
    iterations=0,
    residual_norm=math.inf,
    lu=None,
    reason=Convergence.SINGULAR,
)

_REMEDY = (
    "Try a smaller ds_min or ds_max, a better starting point, an analytic jacobian, or "
    "check the residual for discontinuities; pass throw=False to keep the partial branch."
)

_KEEP = "; pass throw=False to keep the partial branch."
_GUARD_REMEDY = {
    Guard.ANGLE: "The tangent turns faster than max_angle allows even over ds_min: a corner "
    "or a kink of the curve, or a residual that is not smooth there. Lower ds_min, raise "
    "max_angle (and target_angle) if the curve really turns that fast, or check the "
    "residual for kinks" + _KEEP,
    Guard.CONTRACTION: "Newton contracts too weakly (first contraction above "
    "4*target_contraction), whatever the step: an inaccurate Jacobian (compare it with the "
    "residual's differences: check_jacobian), a nearly singular one, or badly scaled "
    "components. Fix or give an analytic jacobian, give typical sizes (scales=...), or "
    "raise target_contraction" + _KEEP,
    Guard.DISTANCE: "The corrector lands too far from the predictor even at ds_min: the "
    "curve bends more than curve_tol allows. Lower ds_min, raise curve_tol (a coarser curve) "
    "or target_distance" + _KEEP,
}


class StepRules:
    """What the step needs of the tracer's configuration (fixed while a curve is traced):
    the ``options``, the unit vector ``e_last``, ``bound_tests`` (the ``(index in the
    state's test values, test)`` of each bound) and the corrector's settings of a step,
    with and without the contraction test (``newton``, ``newton_at_ds_min``) and of the
    damped fallback (``damped``). The arclength weights belong to the curve system (they
    follow its scales)."""

    __slots__ = ("options", "e_last", "bound_tests", "newton", "newton_at_ds_min", "damped")

    def __init__(
        self,
        options: ContinuationOptions,
        dim: int,
        bound_tests: tuple[tuple[int, BoundTest], ...],
    ) -> None:
        self.options = options
        self.e_last = np.zeros(dim)
        self.e_last[-1] = 1.0
        self.bound_tests = bound_tests
        self.newton = NewtonSettings.of(options, contract=True)
        self.newton_at_ds_min = NewtonSettings.of(options)
        self.damped = NewtonSettings.of(options, budget=5)


def wnorm(x: np.ndarray, weights: np.ndarray) -> float:
    """The weighted (arclength) norm ``√(Σ w_i x_i²)``."""
    return math.sqrt(weighted_square(x, weights))


@dataclass(slots=True)
class Trial:
    """An accepted step (built by keyword; a new one replaces it where a value changes).

    ``res``: the corrector's result (its ``z`` is the new point); ``t``: the unit tangent
    there; ``factor``: by which its guards would scale the step size
    (:func:`~._control.guard_factor`); ``ds``: the step size used; ``h``: the new point's
    pseudo-arclength from the last one; ``rt``: det [∂G/∂z; (W t)ᵀ] has the sign of the
    corrector's determinant times the sign of ``rt``; ``rejected``: the tries rejected
    before it; ``corner``: a corner step; ``aimed``: the bound test it was aimed at (or
    None); ``interpolation_error``: the distance from its arc to the curve
    (:meth:`~..numerics._arc.HermiteArc.error`)."""

    res: NewtonResult
    t: np.ndarray
    factor: float
    ds: float
    h: float
    rt: float
    rejected: int = 0
    corner: bool = False
    aimed: BoundTest | None = None
    interpolation_error: float = 0.0

    @staticmethod
    def of(
        *,
        res: NewtonResult,
        t: np.ndarray,
        factor: float,
        ds: float,
        h: float,
        rt: float,
        rejected: int = 0,
        corner: bool = False,
        aimed: BoundTest | None = None,
        interpolation_error: float = 0.0,
    ) -> Trial:
        """Built by keyword, fast: a class called with keywords first gathers them in a
        dict (three times the cost of this call, on every step)."""
        self = _new(Trial)
        self.res = res
        self.t = t
        self.factor = factor
        self.ds = ds
        self.h = h
        self.rt = rt
        self.rejected = rejected
        self.corner = corner
        self.aimed = aimed
        self.interpolation_error = interpolation_error
        return self

    def with_rejected(self, rejected: int) -> Trial:
        """A copy that counts ``rejected`` tries before it; this one unchanged."""
        return Trial.of(
            res=self.res,
            t=self.t,
            factor=self.factor,
            ds=self.ds,
            h=self.h,
            rt=self.rt,
            rejected=rejected,
            corner=self.corner,
            aimed=self.aimed,
            interpolation_error=self.interpolation_error,
        )


@dataclass(slots=True)
class Rejected:
    """A try of a step that was not accepted: the corrector's result ``res``, why
    (``reason``: the corrector's, or a guard's :class:`~._control.Rejection`) and the
    ``factor`` by which the step should be cut."""

    res: NewtonResult
    reason: Convergence | Rejection
    factor: float


class Failure(NamedTuple):
    """A step that could not be taken: the branch's ``status``, the ``message`` and the
    typed ``error`` (raised, or logged when the tracer does not throw)."""

    status: Status
    message: str
    error: ContinuationError


@dataclass(slots=True, eq=False)
class Predictor:
    """The step's predictor: the unit ``secant`` through the last two points (None for the
    tangent predictor), the ``direction`` (the secant or the tangent) and the corrector's
    border ``row`` (the direction times the arclength weights); never changed after it is
    made."""

    secant: np.ndarray | None
    direction: np.ndarray
    row: np.ndarray

    @staticmethod
    def of(
        *,
        secant: np.ndarray | None,
        direction: np.ndarray,
        row: np.ndarray,
    ) -> Predictor:
        """Built by keyword, fast: a class called with keywords first gathers them in a
        dict (three times the cost of this call, on every step)."""
        self = _new(Predictor)
        self.secant = secant
        self.direction = direction
        self.row = row
        return self


def predictor(
    o: ContinuationOptions,
    system: CurveSystem,
    z: np.ndarray,
    t: np.ndarray,
    z_prev: np.ndarray | None,
) -> Predictor:
    """The step's predictor from ``z`` (unit tangent ``t``; ``z_prev`` the point before)."""
    secant = None
    if o.predictor == "secant" and z_prev is not None:
        d = z - z_prev
        nd = wnorm(d, system.weights)
        if nd > 0:
            secant = d / nd
    direction = t if secant is None else secant
    row = direction if system.unit_weights else system.weights * direction
    return Predictor.of(secant=secant, direction=direction, row=row)


def try_step(
    rules: StepRules,
    system: CurveSystem,
    z: np.ndarray,
    t: np.ndarray,
    ds: float,
    direction: np.ndarray,
    row: np.ndarray,
    secant: np.ndarray | None,
    work: StepWork,
    kind: Solve = Solve.TRY,
) -> Trial | Rejected:
    """One corrector solve at ``ds`` along the predictor's ``direction`` (its ``row``, its
    ``secant``: see :class:`Predictor`; counted in ``work`` as ``kind``): the trial if it is
    accepted, else why not."""
    work.charge(kind, ds)
    o = rules.options
    z_pred = z + ds * direction
    # above ds_min a wandering Newton gives up early (the step is cut anyway); the
    # hyperplane is the one through the predictor
    settings = rules.newton if ds > o.ds_min else rules.newton_at_ds_min
    res = newton(system, z_pred, row, None, settings, max_first=2.0 * ds)
    used_fallback = False
    if not res.converged and ds <= o.ds_min:
        res = damped_newton(system, z_pred, row, row.dot(z_pred), rules.damped)
        used_fallback = True
    if not res.converged:
        if res.reason is Convergence.NONFINITE:
            work.nonfinite += 1
        cut = SINGULAR_CUT if res.reason is Convergence.SINGULAR else 0.5
        return Rejected(res=res, reason=res.reason, factor=cut)
    lu = factor_at(system, res.z, row)  # (the factorization at the point itself)
    if lu is None:  # (the trial point is exactly singular: a branch point)
        return Rejected(res=_SINGULAR_RESULT, reason=Convergence.SINGULAR, factor=SINGULAR_CUT)
    res.lu = lu  # (the corrector's result, not yet seen by anything else)
    found = _judged(rules, system, z, t, ds, z_pred, res, row, secant)
    if used_fallback and isinstance(found, Trial):
        logger.info("step accepted by the damped fallback corrector at ds=%g", ds)
    return found


def _judged(
    rules: StepRules,
    system: CurveSystem,
    z: np.ndarray,
    t: np.ndarray,
    ds: float,
    z_pred: np.ndarray,
    res: NewtonResult,
    row: np.ndarray,
    secant: np.ndarray | None,
) -> Trial | Rejected:
    """The corrected point of a try under the step's guards (:func:`~._control.guard_factor`)
    and the accuracy of its arc (:func:`~._control.interpolation_factor`)."""
    o = rules.options
    W = system.weights
    unit_w = system.unit_weights
    t_new = res.lu.solve(rules.e_last)
    t_new /= math.sqrt(t_new.dot(t_new) if unit_w else weighted_square(t_new, W))
    rt = float(row.dot(t_new))  # (a float: the comparisons below cost less)
    cosang = rt if secant is None else float(t_new.dot(W * t))
    angle = math.degrees(math.acos(max(-1.0, min(1.0, cosang))))
    dc = res.z - z_pred
    distance = math.sqrt(dc.dot(dc) if unit_w else weighted_square(dc, W))
    factor, rejection = guard_factor(o, res.contraction, distance, ds, angle, res.iterations)
    if rejection is not None:
        return Rejected(res=res, reason=rejection, factor=factor)
    # the pseudo-arclength of the step: row·(z1 − z) = ds·(row·direction) = ds, as the
    # corrector satisfies the (linear) hyperplane equation to rounding; the chord is then
    # √(ds² + δ²) (the correction lies in the hyperplane, W-orthogonal to the direction)
    length = arc_from(math.sqrt(ds * ds + distance * distance), cosang)
    error = HermiteArc.error_of(
        z, t, res.z, t_new, length, system.residual, res.lu, None if unit_w else W
    )
    f_interp, rejection = interpolation_factor(o, error)
    if rejection is not None and ds > o.ds_min:  # (at ds_min, a kink: kept, its arc inexact)
        return Rejected(res=res, reason=rejection, factor=f_interp)
    return Trial.of(
        res=res,
        t=t_new,
        factor=min(factor, f_interp),
        ds=ds,
        h=ds,
        rt=rt,
        interpolation_error=error,
    )


def failure(
    system: CurveSystem,
    z: np.ndarray,
    t: np.ndarray,
    ds: float,
    res: NewtonResult,
    reason: Convergence | Rejection,
    o: ContinuationOptions,
    work: StepWork,
    crept: int = 0,
) -> Failure:
    """The failure of the step from ``z`` (unit tangent ``t``) at ``ds`` (after ``crept``
    steps creeping near ``ds_min``, if any), with the reason of the corrector or of a guard.
    Where the residual is not finite at some of the step's trial points, or a little ahead
    along the tangent (:func:`_nonfinite_ahead`), the branch has reached the edge of the
    residual's domain: the failure says so (status ``"nonfinite_residual"``), whatever the
    last try's reason (near that edge the derivatives of ``√`` or ``log`` grow without
    bound, and Newton fails by contraction first)."""
    values = system.values(z)
    text = str(reason)
    if crept:
        text += f"; the branch crept {crept} steps shorter than {STALL_FACTOR:g}*ds_min"
    # (a creeping branch's reason carries the creep: not a non-finite residual as such)
    nonfinite = (reason is Convergence.NONFINITE and not crept) or work.nonfinite > 0
    ahead = None if nonfinite else _nonfinite_ahead(system, z, t)
    if nonfinite or ahead is not None:
        return _edge_of_domain(values, ds, text, o, work, ahead)
    if isinstance(reason, Rejection) and reason.guard in _GUARD_REMEDY:
        _, _, detail = text.partition(": ")
        exc: ConvergenceError = StepGuardError(
            f"the step's {reason.guard} guard rejects the step ({detail}; Newton converged)",
            guard=reason.guard,
            values=values,
            ds=ds,
            iterations=res.iterations,
            residual_norm=res.residual_norm,
            remedy=_GUARD_REMEDY[reason.guard],
        )
        return Failure(status=Status.GUARD_FAILURE, message=str(exc), error=exc)
    exc = ConvergenceError(
        f"Newton's method and the damped fallback failed ({text})",
        values=values,
        ds=ds,
        iterations=res.iterations,
        residual_norm=res.residual_norm,
        remedy=_REMEDY,
    )
    return Failure(status=Status.CONVERGENCE_FAILURE, message=str(exc), error=exc)


def _edge_of_domain(
    values: dict[str, float],
    ds: float,
    text: str,
    o: ContinuationOptions,
    work: StepWork,
    ahead: float | None,
) -> Failure:
    """The failure of a step at the edge of the residual's domain (see :func:`failure`)."""
    where = (
        f"at {max(work.nonfinite, 1)} of the {work.solves} trial points within "
        f"ds={max(work.ds_hi, ds):.3g} of {format_values(values)}"
        if ahead is None
        else f"{ahead:.3g} ahead along the branch from {format_values(values)}"
    )
    msg = (
        f"the residual or its Jacobian is not finite (NaN or infinite) {where}, and no "
        f"step down to ds_min={o.ds_min:g} passes ({text}): the branch reaches the edge "
        "of the domain where the residual is defined (a square root or logarithm of a "
        "negative number, a division by zero, an overflow) and stops there"
    )
    error = NonFiniteResidualError(msg, values=values)
    return Failure(status=Status.NONFINITE_RESIDUAL, message=msg, error=error)


def _nonfinite_ahead(system: CurveSystem, z: np.ndarray, t: np.ndarray) -> float | None:
    """The shortest of the distances 1e-8, 1e-7, …, 0.1 (weighted, along the unit tangent
    ``t`` from ``z``) at which the residual is not finite, or None."""
    for k in range(8, 0, -1):
        s = 10.0**-k
        try:
            g = system.residual(z + s * t)
        except SingularMatrixError:
            continue
        if not math.isfinite(max_abs(g)):
            return s
    return None


__all__ = [
    "Failure",
    "Predictor",
    "Rejected",
    "StepRules",
    "Trial",
    "failure",
    "predictor",
    "try_step",
    "wnorm",
]
