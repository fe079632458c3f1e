"""The points located inside a step as points of the branch (:func:`located_point`), linked
in order (:class:`Linked`, see :func:`link_located`)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

from .._outcomes import Kind, PointStatus, Status
from ..detection._bracket import Bracket, Located, tangent_at
from ..detection._tests import Record
from ..numerics._linalg import max_abs
from ..systems._curve import CurveSystem
from ._crossings import Found
from ._state import Point, TracerState
from ._step import Trial


class Linked(NamedTuple):
    """The located points of a step linked in (:func:`link_located`): the last of them
    (``prev``), the branch's point count, the status and message of a terminal test, the
    records of the step's own end point and whether the branch ended inside the step."""

    prev: Point
    n_points: int
    status: Status | None
    message: str
    end_special: tuple[Record, ...] | None
    inside: bool

    @classmethod
    def of(
        cls,
        *,
        prev: Point,
        n_points: int,
        status: Status | None,
        message: str,
        end_special: tuple[Record, ...] | None,
        inside: bool,
    ) -> Linked:
        """Built by keyword, fast: a class called with keywords first gathers them in a
        dict (three times the cost of this call, on every step)."""
        return cls(prev, n_points, status, message, end_special, inside)


def endpoint_record(label: str) -> Record:
    return Record(
        kind=Kind.ENDPOINT,
        label=label,
        with_respect_to=None,
        status=PointStatus.CONVERGED,
        interval=None,
        details={},
    )


def located_point(
    system: CurveSystem,
    last: Point,
    loc: Located,
    records: tuple[Record, ...],
    br: Bracket | None,
    prev: Point,
    trial: Trial,
) -> Point:
    """A point located inside the step as a point of the branch (``ds`` 0: no step of its
    own; the step's interpolation error)."""
    tan = loc.tangent
    if tan is None:
        assert br is not None  # only the aimed end point is located without a bracket
        tan = tangent_at(system, loc.z, br.row, system.weights, br)
    rn = loc.residual_norm
    if rn is None:
        rn = max_abs(system.residual(loc.z))
    return Point.of(
        z=loc.z,
        t=tan,
        s=last.s + loc.sigma,
        iterations=loc.iterations,
        rejected=0,
        residual_norm=rn,
        ds=0.0,
        special=records,
        prev=prev,
        interpolation_error=trial.interpolation_error,
    )


def link_located(
    state: TracerState,
    system: CurveSystem,
    trial: Trial,
    located: Sequence[Found],
    special: tuple[Record, ...] | None,
) -> Linked:
    """The located points of a step linked in after the last point, in order, up to a
    terminal one (the step's end, for a step aimed at a bound)."""
    last = state.last
    prev, n_points = last, state.n_points
    status: Status | None = None
    message, end_special, inside = "", special, False
    for f in located:
        tt, loc = f.test, f.located
        records: tuple[Record, ...] = (tt.record(system, loc, (last.s, last.s + trial.h)),)
        if tt.terminal:
            ending = tt.ending(loc)
            status, message = ending.status, ending.message
            records += ending.records
        if tt is trial.aimed:  # the step's own end point
            end_special = records
            break
        prev = located_point(system, last, loc, records, f.bracket, prev, trial)
        n_points += 1
        if tt.terminal:
            inside = True  # a terminal point located inside the step, before its end
            break
    return Linked.of(
        prev=prev,
        n_points=n_points,
        status=status,
        message=message,
        end_special=end_special,
        inside=inside,
    )


__all__ = ["Linked", "endpoint_record", "link_located", "located_point"]
