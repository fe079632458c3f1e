"""The work limit of one continuation step.

Every loop of a step ends: the corrector after ``max_newton_iterations``, a locating
iteration after ``max_locate_iterations``, the halving of a rejected step at ``ds_min``; the
loops that retake a step (a rejected try, a half step confirming a sign change, a corner
step) are counted here, and a step that needs more than ``max_step_solves`` corrector solves
ends the branch with status ``"stalled"`` (:class:`~.._errors.StalledError`), its message
naming the point, the step sizes tried and what was tried. A step's residual and Jacobian
evaluations are thereby at most ``max_step_solves × max_newton_iterations`` each (plus the
location of its special points, bounded by their own iteration limits).
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from enum import IntEnum
from typing import Any

from .._errors import MaxStepsWarning, StalledError, format_values


class Solve(IntEnum):
    """What a corrector solve of a step was for (an index into :attr:`StepWork.counts`);
    ``words`` name it in the message of a stalled step."""

    TRY = 0
    HALF = 1
    CORNER = 2
    AIMED = 3

    @property
    def words(self) -> str:
        return _WORDS[self]


_WORDS = (
    "pseudo-arclength tries",
    "half steps confirming a sign change",
    "natural-parameter (corner) tries",
    "steps aimed at a bound",
)


class OutOfWork(Exception):
    """Raised inside a step that cannot make progress (caught by the tracer): its work limit
    is reached, or ``reason`` says why else."""

    def __init__(self, work: StepWork, reason: str = "") -> None:
        super().__init__(reason or "step work limit reached")
        self.work = work
        self.reason = reason


class StepWork:
    """The corrector solves of one step, by kind (:class:`Solve`), against ``limit``;
    ``ds_lo`` and ``ds_hi`` the smallest and largest step size tried; ``nonfinite`` how many
    solves met a residual or Jacobian that was not finite (the step's failure then says
    so). Made once per step, charged once per solve: kept to a few attribute updates."""

    __slots__ = ("limit", "solves", "counts", "ds_lo", "ds_hi", "nonfinite")

    def __init__(self, limit: int) -> None:
        self.limit = limit
        self.solves = self.nonfinite = 0
        self.counts = [0, 0, 0, 0]
        self.ds_lo, self.ds_hi = math.inf, 0.0

    def charge(self, kind: Solve, ds: float) -> None:
        """Count one corrector solve of ``kind`` at step size ``ds``; :class:`OutOfWork` past
        the limit (or for a step size that is not a positive number)."""
        self.solves += 1
        self.counts[kind] += 1
        if ds < self.ds_lo:
            self.ds_lo = ds
        if ds > self.ds_hi:
            self.ds_hi = ds
        if self.solves > self.limit or not ds > 0.0:
            raise OutOfWork(self)

    def describe(self) -> str:
        """What was tried, in words."""
        parts = [f"{n} {_WORDS[k]}" for k, n in enumerate(self.counts) if n]
        sizes = (
            f"step sizes from {self.ds_hi:.3g} down to {self.ds_lo:.3g}"
            if self.ds_hi > 0.0
            else "no step size"
        )
        return f"{self.solves} corrector solves ({', '.join(parts)}; {sizes})"


def stalled(out: OutOfWork, values: Mapping[str, float], ds: float) -> StalledError:
    """The error of a step from the point ``values`` (next step size ``ds``) that could not
    make progress (its message names the point, the step sizes tried and what was tried)."""
    work = out.work
    why = out.reason or f"the step's work limit (max_step_solves={work.limit}) was reached"
    message = (
        f"the branch stalled at {format_values(values)}: {why} after {work.describe()}. "
        "The curve cannot be followed from here at any step size the options allow: check "
        "the residual and its Jacobian near this point (check_jacobian), give typical sizes "
        "(scales=...), or end the branch before it with a bound"
    )
    ds = work.ds_lo if math.isfinite(work.ds_lo) else ds
    return StalledError(message, values=values, ds=ds, tried=work.describe())


def max_steps_message(options: Any, state: Any, system: Any, trial: Any) -> str:
    """The message (and warning) of a branch ended by ``max_steps`` (``options``: the
    tracer's; ``state``, ``system``, ``trial``: the step's)."""
    max_steps, ds0, ds = options.max_steps, options.ds, trial.ds
    values, stalled_steps = system.values(trial.res.z), state.stalled
    message = (
        f"the branch stopped after max_steps={max_steps} steps at "
        f"{format_values(values)}, before reaching a bound or a "
        f"terminal event: it is incomplete (the last step was ds={ds:.3g}). "
        + (
            "The steps were cut far below ds: the step's guards keep rejecting "
            "longer steps (check the Jacobian against the residual: "
            "check_jacobian; or give typical sizes, scales=...)"
            if stalled_steps or ds < 1e-3 * ds0
            else "Raise max_steps, or ds_max if the steps are at it, or give "
            "bounds that end the branch"
        )
    )
    warnings.warn(message, MaxStepsWarning, stacklevel=4)
    return message


__all__ = ["OutOfWork", "Solve", "StepWork", "max_steps_message", "stalled"]
