"""The points located inside a step as points of the branch (:func:`located_point`), linked
in order (:class:`Linked`, see :meth:`~._tracer.Tracer._link`)."""

from __future__ import annotations

from typing import NamedTuple

from .._outcomes import Kind, PointStatus, Status
from ..detection._bracket import Bracket, Located, tangent_at
from ..detection._tests import Record
from ..numerics._linalg import max_abs
from ..systems._curve import CurveSystem
from ._state import Point
from ._step import Trial


class Linked(NamedTuple):
    """The located points of a step linked in (:meth:`Tracer._link`): the last of them
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


__all__ = ["Linked", "endpoint_record", "located_point"]
