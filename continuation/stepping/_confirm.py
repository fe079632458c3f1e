"""Confirming a step across which a test of the curve's geometry changed sign (a fold, a
branch point): the step may have jumped to a nearby branch instead of crossing a special
point of its own.

A step that jumped to a nearby branch (one whose tangent turned little and whose correction
was small, as when two branches pass close and parallel) passes every guard of the step
itself and changes the sign of the branch-point test: its arc joins the two branches. Two
confirmations: a fold located on the step's arc (:func:`located_on_arc`), else the half
step (:func:`confirm_step`).
"""

from __future__ import annotations

import logging
import math
from collections.abc import Sequence
from dataclasses import replace
from typing import TYPE_CHECKING

import numpy as np

from .._outcomes import PointStatus
from ..detection._bracket import Bracket, Located
from ..systems._newton import NewtonSettings, newton
from ._advance import advance
from ._step import StepRules, Trial, predictor, try_step, wnorm
from ._work import OutOfWork, Solve, StepWork

if TYPE_CHECKING:
    from ._state import TracerState

logger = logging.getLogger(__name__)


def confirm_step(
    rules: StepRules, state: TracerState, trial: Trial, br: Bracket | None, work: StepWork
) -> Trial | None:
    """Confirm a step across which a test function changed sign: None if the half step from
    the same point lies on the step's cubic Hermite arc, else the step to take instead (the
    half step, or a shorter one if the half step is rejected).

    A step that jumped to a nearby branch (one whose tangent turned little and whose
    correction was small, as when two branches pass close and parallel) passes every guard
    of the step itself, and changes the sign of the branch-point test: its arc joins the two
    branches. The half step stays on the first branch, off that arc by about half the
    distance between them, where a true step's arc is off the curve by its interpolation
    error, O(ds⁴) against the predictor's distance δ = O(ds²): the step is confirmed when the
    half step is within ``δ/10`` of the arc (on a circle turning 30° in the step, the arc is
    off by δ/160; :func:`arc_limit`). The half step is first corrected only to 1e-3·δ,
    which is all the comparison needs; only when that point is off the arc (or its corrector
    fails) is the half step taken as a step of its own, the one to take instead. ``br``: the
    step's bracket, if the caller made it. (A fold is confirmed more cheaply, after it is
    located: :func:`located_on_arc`.)

    A step of less than twice ``ds_min`` has no half step: one that needs confirming cannot
    make progress (:class:`~._work.OutOfWork`, the branch ends "stalled"); each solve counts
    against the step's ``work``."""
    o = rules.options
    system = state.system
    W = system.weights
    last = state.last
    z, t = last.z, last.t
    pred = predictor(o, system, z, t, None if last.prev is None else last.prev.z)
    direction, row = pred.direction, pred.row
    ds = trial.ds
    if not 0.5 * ds >= o.ds_min:
        raise OutOfWork(work, f"a sign change at ds={ds:.3g} cannot be confirmed by a half step")
    if br is None:
        br = Bracket(system, z, t, trial.res.z, trial.t, W, o)
    delta, limit = arc_limit(W, z, direction, trial)

    # First the half-step point alone, corrected only as far as the comparison needs: to
    # 1e-3·δ (an update that small, relative to the components' magnitudes, moves the point
    # by at most 1e-3·δ in the weighted norm). Most steps are confirmed by it.
    mags = np.maximum(system.scales, np.abs(z))
    loose = 1e-3 * delta / wnorm(mags, W)
    if loose > math.sqrt(o.step_tol):
        z_half = z + 0.5 * ds * direction
        work.charge(Solve.HALF, 0.5 * ds)
        settings = NewtonSettings(
            tol=math.inf,
            step_tol=loose * loose,
            max_iterations=o.max_newton_iterations,
            contract=True,
        )
        res = newton(system, z_half, row, row.dot(z_half), settings, max_first=ds)
        if res.converged and off_arc(br, W, res.z) <= limit:
            return None
    # else the half step as a step of its own: the step to take instead if it is off the arc
    half = try_step(rules, system, z, t, 0.5 * ds, direction, row, pred.secant, work, Solve.HALF)
    if not isinstance(half, Trial):  # the half step fails where the whole one passed
        shorter = advance(rules, state.replaced(ds=max(0.25 * ds, o.ds_min)), work)
        if isinstance(shorter, Trial):
            return replace(shorter, rejected=trial.rejected + 1)
        return None
    off = off_arc(br, W, half.res.z)
    if off <= limit:
        return None
    logger.info(
        "a step of %g whose half step is %.3g off its arc (predictor distance %.3g): a jump "
        "to another branch, retaken as the half step",
        ds, off, delta,
    )  # fmt: skip
    return replace(half, rejected=trial.rejected + 1)


def arc_limit(
    W: np.ndarray, z: np.ndarray, direction: np.ndarray, trial: Trial
) -> tuple[float, float]:
    """The step's predictor distance δ (from ``z`` along ``direction``) and how far a point
    of the curve inside the step may lie from the step's arc: ``δ/10`` (see
    :func:`confirm_step`)."""
    delta = wnorm(trial.res.z - (z + trial.ds * direction), W)
    return delta, 0.1 * delta + 1e-9 * trial.ds


def off_arc(br: Bracket, W: np.ndarray, zh: np.ndarray) -> float:
    """The distance of ``zh`` from the step's cubic Hermite arc, at its pseudo-arclength."""
    return wnorm(zh - br.arc.at(br.sigma(zh) / br.h), W)


def located_on_arc(
    rules: StepRules, state: TracerState, trial: Trial, br: Bracket, points: Sequence[Located]
) -> bool:
    """Whether each of ``points`` (the folds located inside the step) converged and lies on
    the step's arc within the limit of :func:`confirm_step`: the step is then confirmed
    without its half step. A fold is located by Newton from the turning point of the step's
    arc; on a step that jumped between two branches that arc runs between them, off the
    curve by about half their distance, and Newton fails or converges to a point of the
    curve away from it (a true step's arc is off the curve by its interpolation error only).
    Where a point is off the arc or not located, the half step decides."""
    last = state.last
    system = state.system
    W = system.weights
    pred = predictor(
        rules.options, system, last.z, last.t, None if last.prev is None else last.prev.z
    )
    limit = arc_limit(W, last.z, pred.direction, trial)[1]
    return all(
        loc.status is PointStatus.CONVERGED and off_arc(br, W, loc.z) <= limit for loc in points
    )


__all__ = ["arc_limit", "confirm_step", "located_on_arc", "off_arc"]
