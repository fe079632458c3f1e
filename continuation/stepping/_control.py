"""Step-size control: each guard of an accepted or rejected step compares what the step
measured with its nominal value and says by how much ``ds`` should change
(Allgower & Georg §6.1; COCO's atlas does the same with its own measures), and the next
step size is the most restrictive of them.

The guards: Newton's first contraction (Deuflhard), the predictor–corrector distance (a
fraction of ``ds`` and the curve tolerance ``curve_tol``), the tangent's turn, Newton's
iteration count (:func:`guard_factor`), and the distance of the step's interpolant from the
curve, held within ``rtol`` (:func:`interpolation_factor`).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, NamedTuple

from .._outcomes import Guard

if TYPE_CHECKING:
    from .._options import ContinuationOptions


class Rejection(NamedTuple):
    """Why a guard rejects a step (built by keyword): the ``guard`` and what it measured
    (``detail``); ``str()`` gives ``"guard: detail"``."""

    guard: Guard
    detail: str

    def __str__(self) -> str:
        return f"{self.guard}: {self.detail}"


#: a guard that asks for less than this fraction of ds rejects the step
REJECT_BELOW = 0.5


def guard_factor(
    o: ContinuationOptions,
    contraction: float,
    distance: float,
    ds: float,
    angle: float,
    iterations: int,
) -> tuple[float, Rejection | None]:
    """The factor by which the step's guards would scale ``ds``, and why the step is
    rejected (None when it is accepted).

    Each guard compares what the step measured with its nominal value and gives the factor
    that would bring it there, from how the measure grows with ds (Allgower & Georg §6.1):

    - Newton's first contraction κ = |Δz₂|/|Δz₁| grows like ds²: ``√(κ̄/κ)``, κ̄ =
      ``target_contraction``;
    - the predictor–corrector distance δ grows like ds²: ``target_distance·ds/δ`` (δ/ds, the
      curve's bending within the step, grows like ds) and ``√(curve_tol/δ)``;
    - the tangent's turn α grows like ds: ``target_angle/α``;
    - the Newton count: ``target_newton_iterations/iterations``.

    The step is rejected when one of the first three asks for less than half of ``ds`` (κ over
    4κ̄, δ over 2·target_distance·ds or 4·curve_tol, α over 2·target_angle) or the turn
    exceeds ``max_angle``; the next ``ds`` is the accepted one times the smallest factor (see
    :func:`next_step_size`)."""
    f_kappa = math.sqrt(o.target_contraction / contraction) if contraction > 0.0 else math.inf
    if distance > 0.0:
        f_delta = min(o.target_distance * ds / distance, math.sqrt(o.curve_tol / distance))
    else:
        f_delta = math.inf
    f_angle = o.target_angle / angle if angle > 0.0 else math.inf
    worst = min(f_kappa, f_delta, f_angle)
    if worst < REJECT_BELOW or angle > o.max_angle:
        if angle > o.max_angle or worst == f_angle:
            detail = f"the tangent turned {angle:.3g} degrees"
            return worst, Rejection(guard=Guard.ANGLE, detail=detail)
        if worst == f_kappa:
            detail = f"Newton's first contraction was {contraction:.3g}"
            return worst, Rejection(guard=Guard.CONTRACTION, detail=detail)
        detail = f"the corrector moved {distance:.3g} from the predictor"
        return worst, Rejection(guard=Guard.DISTANCE, detail=detail)
    return min(worst, o.target_newton_iterations / max(iterations, 1)), None


#: a step's interpolant is accepted within this fraction of rtol, and the next step aims at
#: the second (it grows like ds⁴: the factor is the fourth root of the ratio)
_INTERP_ACCEPT = 0.5
_INTERP_AIM = 0.25


def interpolation_factor(o: ContinuationOptions, error: float) -> tuple[float, Rejection | None]:
    """The factor by which the step's interpolation error (its arc's distance from the
    curve) would scale ``ds`` (``(rtol/4 / error)^(1/4)``), and why the step is rejected
    (None when the error is within ``rtol/2``)."""
    if error <= 0.0:
        return math.inf, None
    factor = (_INTERP_AIM * o.rtol / error) ** 0.25
    if error > _INTERP_ACCEPT * o.rtol:
        detail = f"the step's cubic arc is {error:.3g} off the curve (rtol {o.rtol:g})"
        return factor, Rejection(guard=Guard.INTERPOLATION, detail=detail)
    return factor, None


def next_step_size(options: ContinuationOptions, factor: float, rejected: int, ds: float) -> float:
    """The ``ds`` after an accepted step of size ``ds`` whose guards ask for ``factor``
    (:func:`guard_factor`): scaled by it within ``[0.5, growth]`` (not above 1 after
    ``rejected`` tries) and ``[ds_min, ds_max]``."""
    o = options
    factor = min(o.growth, max(0.5, factor))
    if rejected:
        factor = min(factor, 1.0)
    return min(o.ds_max, max(o.ds_min, ds * factor))


__all__ = ["Rejection", "guard_factor", "interpolation_factor", "next_step_size"]
