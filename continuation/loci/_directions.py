"""Tracing a curve from one start in one direction or both (fold curves, loci)."""

from __future__ import annotations

from collections.abc import Callable

from ..results._branch import Branch, join_halves
from ..stepping._state import TracerState
from ..stepping._trace import run
from ..stepping._tracer import Tracer


def trace_directions(
    begin: Callable[[int], tuple[Tracer, TracerState]],
    direction: str | int,
    *,
    start_kind: str | None = None,
    start_label: str = "",
) -> Branch:
    """Trace a curve from one start in ``direction`` (+1 or −1) or ``"both"``: ``begin(d)``
    gives the tracer and its initial state for direction ``d``. Both halves are joined at the
    start (:func:`~..results._branch.join_halves`, which records it as ``start_kind``); one
    half gets ``info`` ``direction`` and ``start_index`` 0."""
    halves = []
    for d in (1, -1) if direction == "both" else (int(direction),):
        tracer, state = begin(d)
        halves.append(tracer.result(run(tracer, state)))
    if len(halves) == 1:
        halves[0].info.update(direction=direction, start_index=0)
        return halves[0]
    return join_halves(halves[1], halves[0], start_kind=start_kind, start_label=start_label)


__all__ = ["trace_directions"]
