"""A continuation step (:func:`advance`): the pseudo-arclength step, cut until it is accepted,
and the two variants that replace it: the step aimed at a bound (:func:`aim_at_bound`) and
the natural-parameter step across a corner (:func:`corner_step`)."""

from __future__ import annotations

import logging
import math
from typing import TYPE_CHECKING

import numpy as np

from .._outcomes import Guard
from ..detection._bracket import oriented_tangent
from ..detection._tests import BoundTest
from ..numerics._arc import HermiteArc, arc_length
from ..systems._consistency import check_consistent
from ..systems._curve import CurveSystem
from ..systems._newton import NewtonResult, correct
from ._control import Rejection, guard_factor, interpolation_factor
from ._step import (
    MIN_FACTOR,
    STALL_FACTOR,
    STALL_LIMIT,
    STALL_STEPS,
    Failure,
    Predictor,
    StepRules,
    Trial,
    failure,
    predictor,
    try_step,
    wnorm,
)
from ._work import Solve, StepWork

if TYPE_CHECKING:
    from .._options import ContinuationOptions
    from ._state import TracerState

logger = logging.getLogger(__name__)

AIM_REACH = 1.25
"""A bound within this many steps along the tangent is aimed at."""


def advance(rules: StepRules, state: TracerState, work: StepWork) -> Trial | Failure:
    """Predict and correct one step from the last point of ``state``: the corner step after
    many steps creeping at ``ds_min``, else the step aimed at a bound within reach, else the
    pseudo-arclength step, retried shorter until it is accepted; at ``ds_min`` the corner
    step and then failure. Each corrector solve counts against the step's ``work``."""
    o = rules.options
    system = state.system
    last = state.last
    z, t, prev = last.z, last.t, last.prev
    z_prev = None if prev is None else prev.z
    if o.predictor == "tangent":  # (predictor(), inline on the common path)
        secant, direction, row = None, t, t if system.unit_weights else system.weights * t
    else:
        pred = predictor(o, system, z, t, z_prev)
        secant, direction, row = pred.secant, pred.direction, pred.row
    if state.stalled >= STALL_STEPS:
        found = _creeping(
            rules, state, Predictor.of(secant=secant, direction=direction, row=row), work
        )
        if found is not None:
            return found
    elif secant is None and rules.bound_tests:
        aimed = aim_at_bound(rules, state, z, t, state.ds, work)
        if aimed is not None:
            return aimed
    ds = state.ds
    rejected = 0
    kappa = math.inf  # the first contraction of the last step rejected for it
    kept = 0  # how many times in a row it stayed put on a step half as long
    while True:
        tried = try_step(rules, system, z, t, ds, direction, row, secant, work)
        if isinstance(tried, Trial):
            return tried.with_rejected(rejected) if rejected else tried
        res, reason = tried.res, tried.reason
        if isinstance(reason, Rejection) and reason.guard is Guard.CONTRACTION:
            # κ falls like ds² when the step is too long; a κ that stays put while the
            # step shrinks eightfold (three rejections) is the Newton matrix's own error
            # (near a fold it may stay put for a halving or two): no step size cures it
            kept = kept + 1 if res.contraction >= 0.5 * kappa else 0
            if kept >= 3:
                return _not_smooth(system, z, t, ds, res, o, work)
            kappa = res.contraction
        if ds <= o.ds_min:
            corner = corner_step(rules, system, z, t, state.ds, z_prev, work)
            if corner is not None:
                return corner
            return failure(system, z, t, ds, res, reason, o, work)
        # a rejected guard says how much smaller the step should be: at least halved, but
        # for the interpolant alone (an accuracy, not a safety, guard: its error grows like
        # ds⁴, so its factor is reliable) its own factor
        interp = isinstance(reason, Rejection) and reason.guard is Guard.INTERPOLATION
        cut = tried.factor if interp else min(0.5, tried.factor)
        ds = max(ds * max(cut, MIN_FACTOR), o.ds_min)
        rejected += 1


def _creeping(
    rules: StepRules, state: TracerState, pred: Predictor, work: StepWork
) -> Trial | Failure | None:
    """A branch creeping at ds near ds_min (say, Newton with a Jacobian differenced across a
    kink): the corner step tried directly; still creeping after :data:`STALL_LIMIT` steps,
    a step of ``STALL_FACTOR·ds_min`` that the guards reject ends it. None: the step goes
    on as usual."""
    o, system, last = rules.options, state.system, state.last
    z_prev = None if last.prev is None else last.prev.z
    corner = corner_step(rules, system, last.z, last.t, state.ds, z_prev, work)
    if corner is not None:
        return corner
    if state.stalled < STALL_LIMIT:
        return None
    ds = STALL_FACTOR * o.ds_min
    tried = try_step(rules, system, last.z, last.t, ds, pred.direction, pred.row, pred.secant, work)
    if isinstance(tried, Trial):
        return tried
    return failure(system, last.z, last.t, ds, tried.res, tried.reason, o, work, state.stalled)


def _not_smooth(
    system: CurveSystem,
    z: np.ndarray,
    t: np.ndarray,
    ds: float,
    res: NewtonResult,
    o: ContinuationOptions,
    work: StepWork,
) -> Failure:
    """The failure of a step whose first contraction stays put on ever shorter steps: a
    supplied Jacobian that disagrees with the residual is refused here
    (:class:`~.._errors.JacobianError`); otherwise the residual is not smooth ahead."""
    check_consistent(system, z, "the last point")
    detail = (
        f"Newton's first contraction stays at {res.contraction:.3g} on ever shorter steps "
        f"(down to ds={ds:.3g}), with derivatives that agree with the residual's differences "
        "at the last point: the residual is not smooth ahead (a kink or a jump, or "
        "derivatives that grow without bound towards the edge of its domain)"
    )
    reason = Rejection(guard=Guard.CONTRACTION, detail=detail)
    return failure(system, z, t, ds, res, reason, o, work)


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
    natural-parameter steps in one component at a time, each moving the way it was moving.

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
    work.charge(Solve.CORNER, h)
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
    # past a corner the turn says nothing of the curve's bending (nor does the arc across
    # it say anything of the curve beyond): Newton's count decides
    length = arc_length(res.z - z, t, t_new, W)
    error = _arc_error(system, z, t, res.z, t_new, length, res)
    return Trial(
        res=res,
        t=t_new,
        factor=o.target_newton_iterations / max(res.iterations, 1),
        ds=wnorm(res.z - z, W),
        h=float(row.dot(res.z - z)),
        rt=row.dot(t_new),
        corner=True,
        interpolation_error=error,
    )


def _arc_error(
    system: CurveSystem,
    z: np.ndarray,
    t: np.ndarray,
    z1: np.ndarray,
    t1: np.ndarray,
    length: float,
    res: NewtonResult,
) -> float:
    """The distance from the step's arc to the curve (:meth:`~..numerics._arc.HermiteArc.error`
    with the corrector's factorization)."""
    weights = None if system.unit_weights else system.weights
    return HermiteArc.error_of(z, t, z1, t1, length, system.residual, res.lu, weights)


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
    values = state.test_values
    # within reach: the component moves by at most ds/√w_k along the unit tangent
    reach = AIM_REACH * ds
    w = W.tolist()
    for i, tt in rules.bound_tests:
        old = values[i]
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
        work.charge(Solve.AIMED, ds)
        return _aimed(rules, state.system, z, t, tt, sigma, tk)
    return None


def _aimed(
    rules: StepRules,
    system: CurveSystem,
    z: np.ndarray,
    t: np.ndarray,
    tt: BoundTest,
    sigma: float,
    tk: float,
) -> Trial | None:
    """The step from ``z`` onto the bound ``tt``, whose tangent line meets it at ``sigma``
    (``tk``: the tangent's component there), or None if its guards reject it."""
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
    res = NewtonResult(
        z=z1,
        converged=True,
        iterations=res.iterations,
        residual_norm=res.residual_norm,
        lu=res.lu,
        reason=res.reason,
    )
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
    factor, rejection = guard_factor(
        o, res.contraction, wnorm(z1 - z_pred, W), h, angle, res.iterations
    )
    if rejection is not None:
        return None
    error = _arc_error(system, z, t, z1, t_new, arc_length(z1 - z, t, t_new, W), res)
    f_interp, rejection = interpolation_factor(o, error)
    if rejection is not None:
        return None
    return Trial(
        res=res,
        t=t_new,
        factor=min(factor, f_interp),
        ds=h,
        h=h,
        rt=rt,
        aimed=tt,
        interpolation_error=error,
    )


__all__ = ["advance", "aim_at_bound", "corner_step"]
