"""Tracing one branch of a diagram: both ways from its start, each half stepped by the
:class:`~..stepping._tracer.Tracer` and watched for a return to the start (a closed branch:
an isola, or a loop through a branch point), which ends it.

After every step the arcs of the new rows (the cubic Hermite arcs of the dense output) are
compared with the start: once the half has been farther than ``2·tol`` from it, an arc that
passes within ``tol`` of the start with its tangent along the start's (cosine above
:data:`CLOSING_COSINE`, same orientation) closes the branch. The half then ends there with
status ``terminal_event`` (a normal end) and its message says it closed; the other half is
not traced (it would be the same loop run backwards).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np

from .._outcomes import Status
from ..numerics._arc import HermiteArc, arc_length
from ..results._branch import Branch, join_halves
from ..stepping._state import Point, TracerState
from ..stepping._tracer import Tracer
from ._geometry import _nearest_on_arc, unit

CLOSING_COSINE = 0.9
"""How parallel (and same way) the returning arc must run to the start's tangent."""


class Walked(NamedTuple):
    """A traced branch of a diagram: the ``branch``, whether it ``closed`` on itself, how
    each half ended (``ends``: the statuses, minus half first; one entry if closed) and the
    ``halves`` as traced (minus, plus; the one half if closed)."""

    branch: Branch
    closed: bool
    ends: tuple[str, ...]
    halves: tuple[Branch, ...]


def walk(begin: Callable[[int], tuple[Tracer, TracerState]], tol: float) -> Walked:
    """Trace a branch both ways from one start (``begin(d)``: the tracer and initial state of
    the half in direction ``d``), ending a half that returns to the start (see the module)."""
    plus, closed = _half(*begin(1), tol)
    if closed:
        return Walked(branch=plus, closed=True, ends=("closed",), halves=(plus,))
    minus, closed = _half(*begin(-1), tol)
    if closed:  # only a loop traced the other way round could close here
        return Walked(branch=minus, closed=True, ends=("closed",), halves=(minus,))
    both = join_halves(minus, plus)
    ends = (str(minus.status), str(plus.status))
    return Walked(branch=both, closed=False, ends=ends, halves=(minus, plus))


def _half(tracer: Tracer, state: TracerState, tol: float) -> tuple[Branch, bool]:
    """Step one half to its end or back to its start; (branch, closed)."""
    start = state.last
    seen = start
    left = False
    while state.status is None:
        state = tracer.step(state)
        new = _new_rows(state.last, seen)
        seen = state.last
        w = state.system.weights
        for a, b in zip(new[:-1], new[1:]):
            if not left:
                left = _distance(b.z, start.z, w) > 2.0 * tol
                continue
            if _returns(a, b, start, w, tol):
                message = (
                    f"closed: the branch returned to its start (within {tol:.3g}, weighted) "
                    f"at s = {b.s:.6g}"
                )
                state = state.replaced(status=Status.TERMINAL_EVENT, message=message)
                return tracer.result(state), True
    return tracer.result(state), False


def _new_rows(last: Point, seen: Point) -> list[Point]:
    """The rows from ``seen`` (included) to ``last``, in order."""
    rows = []
    p: Point | None = last
    while p is not None and p is not seen:
        rows.append(p)
        p = p.prev
    rows.append(seen)
    return rows[::-1]


def _returns(a: Point, b: Point, start: Point, w: np.ndarray, tol: float) -> bool:
    """Whether the arc from row ``a`` to row ``b`` passes the start (see the module)."""
    length = arc_length(b.z - a.z, a.t, b.t, w)
    if length <= 0.0:
        return False
    chord = _distance(a.z, b.z, w)
    if min(_distance(a.z, start.z, w), _distance(b.z, start.z, w)) > tol + chord:
        return False
    distance, tangent, _ = _nearest_on_arc(HermiteArc(a.z, a.t, b.z, b.t, length), start.z, w)
    return distance <= tol and float(tangent.dot(w * unit(start.t, w))) >= CLOSING_COSINE


def _distance(x: np.ndarray, y: np.ndarray, w: np.ndarray) -> float:
    d = x - y
    return float(np.sqrt(d.dot(w * d)))


__all__ = ["CLOSING_COSINE", "Walked", "walk"]
