"""The predictor–corrector phase of a continuation step, and the step-size rule.

From the last point ``z`` with unit tangent ``t`` and step size ``ds``:

- **predict**: ``z + ds·d`` along the tangent (or the secant through the last two points);
- **correct**: Newton on ``[G(z); row·z = row·z_pred]`` with ``row = W d``; the step is
  accepted when Newton converges, the tangent turns by at most ``max_angle`` and the
  correction is at most ``ds``, and otherwise halved down to ``ds_min`` (where a damped
  Newton is tried last);
- two variants replace the arclength step: a step whose tangent line crosses a bound with
  margin is **aimed at the bound** (Newton with that component fixed), and at a **corner**
  (a non-smooth turning point, where no arclength hyperplane meets the curve beyond, or after
  many steps creeping at ``ds_min``) natural-parameter steps in one component are tried;
- **adapt**: the next ``ds`` from the Newton iteration count and the tangent's turn.

:func:`advance` returns a :class:`Trial` (the accepted step) or a :class:`Failure`.
"""

from __future__ import annotations

import logging
import math
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from .._errors import (
    ContinuationError,
    ConvergenceError,
    NonFiniteResidualError,
    SingularMatrixError,
    StepGuardError,
    format_values,
)
from ..detection._bracket import oriented_tangent
from ..numerics._arc import arc_from, arc_length, interpolation_error
from ..numerics._linalg import max_abs, weighted_square
from ..systems._consistency import check_consistent
from ..systems._newton import NewtonResult, correct, damped_newton, factor_at, newton
from ._control import guard_factor, interpolation_factor
from ._work import AIMED, CORNER, TRY, StepWork

if TYPE_CHECKING:
    from .._options import ContinuationOptions
    from ..detection._tests import BoundTest
    from ..systems._curve import CurveSystem
    from ._state import TracerState

logger = logging.getLogger(__name__)

#: the cut of a step whose Newton matrix is singular: a trial point on a singular point of
#: the curve (a step of exactly the distance to a branch point); halving would land on it
#: again from every dyadic point before it, so the cut is not a power of 2
_SINGULAR_CUT = 0.4

_new_tuple = tuple.__new__  # builds a NamedTuple without its Python-level constructor

_SINGULAR_RESULT = NewtonResult(np.zeros(0), False, 0, math.inf, None, "singular")

_AIM_REACH = 1.25  # a bound within this many steps along the tangent is aimed at
_MIN_FACTOR = 0.1  # a rejected step is retried at least this large (times ds)
_STALL_STEPS = 10  # steps at ds < STALL_FACTOR·ds_min before a corner step is tried
STALL_FACTOR = 1e3
_STALL_LIMIT = 100  # steps creeping below STALL_FACTOR·ds_min before the branch ends

_REMEDY = (
    "Try a smaller ds_min or ds_max, a better starting point, an analytic jacobian, or "
    "check the residual for discontinuities; pass throw=False to keep the partial branch."
)


_KEEP = "; pass throw=False to keep the partial branch."
_GUARD_REMEDY = {
    "angle": "The tangent turns faster than max_angle allows even over ds_min: a corner or "
    "a kink of the curve, or a residual that is not smooth there. Lower ds_min, raise "
    "max_angle (and target_angle) if the curve really turns that fast, or check the "
    "residual for kinks" + _KEEP,
    "contraction": "Newton contracts too weakly (first contraction above "
    "4*target_contraction), whatever the step: an inaccurate Jacobian (compare it with the "
    "residual's differences: check_jacobian), a nearly singular one, or badly scaled "
    "components. Fix or give an analytic jacobian, give typical sizes (scales=...), or "
    "raise target_contraction" + _KEEP,
    "distance": "The corrector lands too far from the predictor even at ds_min: the curve "
    "bends more than curve_tol allows. Lower ds_min, raise curve_tol (a coarser curve) or "
    "target_distance" + _KEEP,
}


class StepRules:
    """What the step needs of the tracer's configuration (fixed while a curve is traced):
    the options, the unit vector ``e_last`` and ``bound_tests``, the ``(index in the state's
    test values, test)`` of each bound. The arclength weights belong to the curve system
    (they follow its typical sizes)."""

    __slots__ = ("options", "e_last", "bound_tests")

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


def wnorm(x: np.ndarray, weights: np.ndarray) -> float:
    """The weighted (arclength) norm ``√(Σ w_i x_i²)``."""
    return math.sqrt(weighted_square(x, weights))


class Trial(NamedTuple):
    """An accepted step: the corrector's result ``res`` (its ``z`` is the new point), the
    unit tangent ``t`` there, ``factor`` (by which its guards would scale the step size:
    :func:`~._control.guard_factor`), the step size ``ds``
    used and the new point's pseudo-arclength ``h`` from the last one, ``rt`` (det
    [∂G/∂z; (W t)ᵀ] has the sign of the corrector's determinant times the sign of ``rt``),
    the number of rejected tries, whether it was a corner step, the bound test it was
    aimed at (or None) and ``interp``, the distance from its cubic Hermite arc to the curve
    (:func:`interpolation_error`).

    Built once per step with ``tuple.__new__`` (all ten fields, in order): half the cost
    of the NamedTuple constructor, which shows in the step's time on small problems."""

    res: NewtonResult
    t: np.ndarray
    factor: float
    ds: float
    h: float
    rt: float
    rejected: int
    corner: bool
    aimed: BoundTest | None
    interp: float


class Failure(NamedTuple):
    """A step that could not be taken: the branch's status, the message and the typed
    error (raised, or logged when the tracer does not throw)."""

    status: str
    message: str
    error: ContinuationError


def advance(rules: StepRules, state: TracerState, work: StepWork) -> Trial | Failure:
    """Predict and correct one step from the last point of ``state``: the corner step after
    many steps creeping at ``ds_min``, else the step aimed at a bound within reach, else the
    pseudo-arclength step, halved until it is accepted; at ``ds_min`` the corner step and
    then failure. Each corrector solve counts against the step's ``work``."""
    o = rules.options
    system = state.system
    last = state.last
    z, t, prev = last.z, last.t, last.prev
    z_prev = None if prev is None else prev.z
    if o.predictor == "tangent":  # (_predictor, inline on the common path)
        secant, direction, row = None, t, t if system.unit_weights else system.weights * t
    else:
        secant, direction, row = _predictor(o, system, z, t, z_prev)
    if state.stalled >= _STALL_STEPS:
        # creeping at ds near ds_min (say, Newton with a Jacobian differenced across a
        # kink): try to pass the corner directly
        corner = corner_step(rules, system, z, t, state.ds, z_prev, work)
        if corner is not None:
            return corner
        if state.stalled >= _STALL_LIMIT:
            # still creeping: a step of STALL_FACTOR·ds_min that the guards reject ends it
            ds = STALL_FACTOR * o.ds_min
            tried = _try(rules, system, z, t, ds, direction, row, secant, work)
            if isinstance(tried, Trial):
                return tried
            res, reason, _ = tried
            return _failure(system, z, t, ds, res, reason, o, work, crept=state.stalled)
    elif secant is None and rules.bound_tests:
        aimed = aim_at_bound(rules, state, z, t, state.ds, work)
        if aimed is not None:
            return aimed
    ds = state.ds
    rejected = 0
    kappa = math.inf  # the first contraction of the last step rejected for it
    kept = 0  # how many times in a row it stayed put on a step half as long
    while True:
        tried = _try(rules, system, z, t, ds, direction, row, secant, work)
        if isinstance(tried, Trial):
            return tried._replace(rejected=rejected) if rejected else tried
        res, reason, factor = tried
        if reason.startswith("contraction:"):
            # κ falls like ds² when the step is too long; a κ that stays put while the
            # step shrinks eightfold (three rejections) is the Newton matrix's own error
            # (near a fold it may stay put for a halving or two): no step size cures it
            kept = kept + 1 if res.contraction >= 0.5 * kappa else 0
            if kept >= 3:
                # (a supplied Jacobian that disagrees with the residual is refused here)
                check_consistent(system, z, "the last point")
                reason = (
                    f"contraction: Newton's first contraction stays at {res.contraction:.3g} "
                    f"on ever shorter steps (down to ds={ds:.3g}), with derivatives that "
                    "agree with the residual's differences at the last point: the residual "
                    "is not smooth ahead (a kink or a jump, or derivatives that grow without "
                    "bound towards the edge of its domain)"
                )
                return _failure(system, z, t, ds, res, reason, o, work)
            kappa = res.contraction
        if ds <= o.ds_min:
            corner = corner_step(rules, system, z, t, state.ds, z_prev, work)
            if corner is not None:
                return corner
            return _failure(system, z, t, ds, res, reason, o, work)
        # a rejected guard says how much smaller the step should be: at least halved, but
        # for the interpolant alone (an accuracy, not a safety, guard: its error grows like
        # ds⁴, so its factor is reliable) its own factor
        cut = factor if reason.startswith("interpolation") else min(0.5, factor)
        ds = max(ds * max(cut, _MIN_FACTOR), o.ds_min)
        rejected += 1


def _predictor(
    o: ContinuationOptions,
    system: CurveSystem,
    z: np.ndarray,
    t: np.ndarray,
    z_prev: np.ndarray | None,
) -> tuple[np.ndarray | None, np.ndarray, np.ndarray]:
    """The step's predictor from ``z`` (unit tangent ``t``): the unit secant through the
    last two points for the secant predictor (else None), the direction (the secant or
    ``t``) and the corrector's border row (the direction times the arclength weights)."""
    secant = None
    if o.predictor == "secant" and z_prev is not None:
        d = z - z_prev
        nd = wnorm(d, system.weights)
        if nd > 0:
            secant = d / nd
    direction = t if secant is None else secant
    return secant, direction, direction if system.unit_weights else system.weights * direction


def _try(
    rules: StepRules,
    system: CurveSystem,
    z: np.ndarray,
    t: np.ndarray,
    ds: float,
    direction: np.ndarray,
    row: np.ndarray,
    secant: np.ndarray | None,
    work: StepWork,
    kind: int = TRY,
) -> Trial | tuple[NewtonResult, str, float]:
    """One corrector solve at ``ds`` (counted in ``work`` as ``kind``): the trial if it is
    accepted, else the corrector's result, the reason it is not and the factor its guards
    ask for."""
    work.charge(kind, ds)
    o = rules.options
    W = system.weights
    unit_w = system.unit_weights
    z_pred = z + ds * direction
    # above ds_min a wandering Newton gives up early (the step is halved anyway); the
    # hyperplane is the one through the predictor
    res = newton(
        system,
        z_pred,
        row,
        None,
        tol=o.tol,
        step_tol=o.step_tol,
        max_iter=o.max_newton_iterations,
        contract=ds > o.ds_min,
        max_first=2.0 * ds,
    )
    used_fallback = False
    if not res.converged and ds <= o.ds_min:
        res = damped_newton(
            system,
            z_pred,
            row,
            row.dot(z_pred),
            tol=o.tol,
            step_tol=o.step_tol,
            max_iter=5 * o.max_newton_iterations,
        )
        used_fallback = True
    if not res.converged:
        if res.reason == "nonfinite":
            work.nonfinite += 1
        return res, res.reason, _SINGULAR_CUT if res.reason == "singular" else 0.5
    fresh = _at_point(system, res, row)
    if fresh is None:  # (the trial point is exactly singular: a branch point)
        return _SINGULAR_RESULT, "singular", _SINGULAR_CUT
    res = fresh
    t_new = res.lu.solve(rules.e_last)
    t_new /= math.sqrt(t_new.dot(t_new) if unit_w else weighted_square(t_new, W))
    rt = float(row.dot(t_new))  # (a float: the comparisons below cost less)
    cosang = rt if secant is None else float(t_new.dot(W * t))
    angle = math.degrees(math.acos(max(-1.0, min(1.0, cosang))))
    dc = res.z - z_pred
    distance = math.sqrt(dc.dot(dc) if unit_w else weighted_square(dc, W))
    factor, guard = guard_factor(o, res.contraction, distance, ds, angle, res.iterations)
    if guard:
        return res, guard, factor
    # the pseudo-arclength of the step: row·(z1 − z) = ds·(row·direction) = ds, as the
    # corrector satisfies the (linear) hyperplane equation to rounding; the chord is then
    # √(ds² + δ²) (the correction lies in the hyperplane, W-orthogonal to the direction)
    length = arc_from(math.sqrt(ds * ds + distance * distance), cosang)
    interp = interpolation_error(system, z, t, res.z, t_new, length, res.lu)
    f_interp, guard = interpolation_factor(o, interp)
    if guard and ds > o.ds_min:  # (at ds_min, a kink: kept, its arc marked inexact)
        return res, guard, f_interp
    if used_fallback:
        logger.info("step accepted by the damped fallback corrector at ds=%g", ds)
    factor = min(factor, f_interp)
    return _new_tuple(Trial, (res, t_new, factor, ds, ds, rt, 0, False, None, interp))


def _at_point(system: CurveSystem, res: NewtonResult, row: np.ndarray) -> NewtonResult | None:
    """The corrector's result with the factorization of ``[∂G/∂z; row]`` at its point
    itself (:func:`~..systems._newton.factor_at`), None where that matrix is singular. (The result
    is the corrector's, not yet seen by anything else: its factorization is replaced in
    place rather than in a copy.)"""
    lu = factor_at(system, res.z, row)
    if lu is None:
        return None
    res.lu = lu
    return res


def _failure(
    system: CurveSystem,
    z: np.ndarray,
    t: np.ndarray,
    ds: float,
    res: NewtonResult,
    reason: str,
    o: Any,
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
    if crept:
        reason += f"; the branch crept {crept} steps shorter than {STALL_FACTOR:g}*ds_min"
    ahead = None if reason == "nonfinite" or work.nonfinite else _nonfinite_ahead(system, z, t)
    if reason == "nonfinite" or work.nonfinite or ahead is not None:
        where = (
            f"at {max(work.nonfinite, 1)} of the {work.solves} trial points within "
            f"ds={max(work.ds_hi, ds):.3g} of {format_values(values)}"
            if ahead is None
            else f"{ahead:.3g} ahead along the branch from {format_values(values)}"
        )
        msg = (
            f"the residual or its Jacobian is not finite (NaN or infinite) {where}, and no "
            f"step down to ds_min={o.ds_min:g} passes ({reason}): the branch reaches the edge "
            "of the domain where the residual is defined (a square root or logarithm of a "
            "negative number, a division by zero, an overflow) and stops there"
        )
        return Failure("nonfinite_residual", msg, NonFiniteResidualError(msg, values=values))
    guard, _, detail = reason.partition(": ")
    if guard in _GUARD_REMEDY:
        exc: ConvergenceError = StepGuardError(
            f"the step's {guard} guard rejects the step ({detail}; Newton converged)",
            guard=guard,
            values=values,
            ds=ds,
            iterations=res.iterations,
            residual_norm=res.residual_norm,
            remedy=_GUARD_REMEDY[guard],
        )
        return Failure("guard_failure", str(exc), exc)
    exc = ConvergenceError(
        f"Newton's method and the damped fallback failed ({reason})",
        values=values,
        ds=ds,
        iterations=res.iterations,
        residual_norm=res.residual_norm,
        remedy=_REMEDY,
    )
    return Failure("convergence_failure", str(exc), exc)


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


def corner_step(
    rules: StepRules,
    system: CurveSystem,
    z: np.ndarray,
    t: np.ndarray,
    ds_hint: float,
    z_prev: np.ndarray | None,
    work: StepWork,
) -> Trial | None:
    """Fallback at a corner of the curve (a non-smooth turning point, where the tangent
    turns by more than 90° so no pseudo-arclength hyperplane meets the curve beyond):
    natural-parameter steps in one component at a time, largest tangent components
    first, each moving the way it was moving.

    The variable that turns at a corner is the one with the large tangent component before
    it: the smaller components are tried first (the "control component", as in contique);
    the approach to a corner halves ds at every step, so the trial sizes start higher, and
    at each size every component is tried."""
    o = rules.options
    W = system.weights
    incoming = None
    if z_prev is not None and wnorm(z - z_prev, W) > 0:
        incoming = (z - z_prev) / wnorm(z - z_prev, W)
    mags = np.abs(t) * np.sqrt(W)
    order = [j for j in np.argsort(mags) if mags[j] > 1e-6 * mags.max()][:4]
    h0 = max(ds_hint, 1e-4 * o.ds_max)
    sizes = [h for h in (h0 * 0.25**k for k in range(12)) if h >= 10 * o.ds_min]
    for h in sizes:
        for j in order:
            found = _natural_step(rules, system, z, t, int(j), h, incoming, work)
            if found is not None:
                logger.info("corner passed by a natural-parameter step in %s", system.names[j])
                return found
    return None


def _natural_step(
    rules: StepRules,
    system: CurveSystem,
    z: np.ndarray,
    t: np.ndarray,
    j: int,
    h: float,
    incoming: np.ndarray | None,
    work: StepWork,
) -> Trial | None:
    """A step of ``h`` (weighted) in component ``j`` alone, the way it was moving."""
    work.charge(CORNER, h)
    o = rules.options
    W = system.weights
    sign = 1.0 if t[j] > 0 else -1.0
    row = np.zeros(system.dim)
    row[j] = 1.0
    target = z[j] + sign * h / math.sqrt(W[j])
    z0 = z.copy()
    z0[j] = target
    res = correct(system, z0, row, target, o, budget=2)
    # the other components move by (slope)·h: a looser guard than for arclength steps,
    # still against jumping to a distant branch
    if not res.converged or wnorm(res.z - z, W) > 20.0 * h:
        return None
    if incoming is not None:  # never back along the way we came
        chord = res.z - z
        along = float(chord @ (W * incoming))
        if along < 0 and wnorm(chord - along * incoming, W) < 0.1 * wnorm(chord, W):
            return None
    # oriented by the stepped component (the chord through the corner is not aligned with
    # the tangent beyond it)
    t_new = res.lu.solve(rules.e_last)
    if t_new[j] == 0.0:
        return None
    t_new *= sign / t_new[j]
    t_new /= wnorm(t_new, W)
    row = W * t_new
    ds = wnorm(res.z - z, W)
    h = float(row.dot(res.z - z))
    # past a corner the turn says nothing of the curve's bending (nor does the arc across
    # it say anything of the curve beyond): Newton's count decides
    factor = o.target_newton_iterations / max(res.iterations, 1)
    length = arc_length(res.z - z, t, t_new, W)
    interp = interpolation_error(system, z, t, res.z, t_new, length, res.lu)
    return _new_tuple(Trial, (res, t_new, factor, ds, h, row.dot(t_new), 0, True, None, interp))


def aim_at_bound(
    rules: StepRules, state: TracerState, z: np.ndarray, t: np.ndarray, ds: float, work: StepWork
) -> Trial | None:
    """A step that would cross a bound, or come within a quarter step of it, ends on it
    instead: from the tangent predictor's crossing of the bound, Newton with that component
    fixed (one solve, where a step past the bound and locating it would take two). Used only
    where the bound is transversal with margin — the tangent within 90° − ``max_angle`` of
    the bound's normal (in the weighted metric), so that the curve, turning by at most
    ``max_angle``, still crosses it — and accepted under the same guards as any step;
    otherwise None (a normal step).

    The trial's ``h`` is the pseudo-arclength of the end point along ``t`` (also its ``ds``),
    ``rt`` the factor by which det [∂G/∂z; (W t_new)ᵀ] differs in sign from the corrector's
    determinant."""
    o = rules.options
    W = state.system.weights
    tests = state.tests
    # within reach: the component moves by at most ds/√w_k along the unit tangent
    reach = _AIM_REACH * ds
    w = W.tolist()
    for i, tt in rules.bound_tests:
        old = tests[i]
        if old is None or old == 0.0 or abs(old) * math.sqrt(w[tt.k]) > reach:
            continue
        k = tt.k
        tk = float(t[k])
        if tk == 0.0:
            continue
        sigma = -old / tk  # where the tangent line meets the bound
        if not 0.0 < sigma <= reach or not tt.crossed(old, old + reach * tk):
            continue
        if math.sqrt(W[k]) * abs(tk) < math.sin(math.radians(o.max_angle)):
            return None  # grazing: a normal step, then locating
        work.charge(AIMED, ds)
        return _aimed(rules, state.system, z, t, ds, tt, sigma, tk)
    return None


def _aimed(
    rules: StepRules,
    system: CurveSystem,
    z: np.ndarray,
    t: np.ndarray,
    ds: float,
    tt: BoundTest,
    sigma: float,
    tk: float,
) -> Trial | None:
    o = rules.options
    W = system.weights
    k = tt.k
    z_pred = z + sigma * t
    z_pred[k] = tt.value_at
    row = np.zeros(z.size)
    row[k] = 1.0
    res = correct(system, z_pred, row, tt.value_at, o, contract=True)
    if not res.converged:
        return None
    z1 = res.z.copy()
    z1[k] = tt.value_at  # the constraint is linear: snap away the last rounding
    res = NewtonResult(z1, True, res.iterations, res.residual_norm, res.lu)
    # [∂G/∂z; e_kᵀ] tan = e_last gives a tangent (with tan_k = 1), oriented like t
    tan = res.lu.solve(rules.e_last)
    wt = W * t
    t_new = oriented_tangent(tan, wt, W)
    if t_new is None:
        return None
    rt = float(t_new.dot(tan))  # the sign factor of det [∂G/∂z; (W t_new)ᵀ]
    angle = math.degrees(math.acos(max(-1.0, min(1.0, float(t_new.dot(wt))))))
    h = float(wt.dot(z1 - z))
    if t_new[k] * tk <= 0.0 or h <= 0.0:
        return None
    factor, guard = guard_factor(
        o, res.contraction, wnorm(z1 - z_pred, W), h, angle, res.iterations
    )
    if guard:
        return None
    length = arc_length(z1 - z, t, t_new, W)
    interp = interpolation_error(system, z, t, z1, t_new, length, res.lu)
    f_interp, guard = interpolation_factor(o, interp)
    if guard:
        return None
    return _new_tuple(Trial, (res, t_new, min(factor, f_interp), h, h, rt, 0, False, tt, interp))


__all__ = ["Failure", "StepRules", "Trial", "advance"]
