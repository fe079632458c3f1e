"""Loci of located points: a point of a branch (a bound hit, a target, a smooth fold) or a
chain of such points across the legs of a loading program, continued in a second parameter.

A point located on a branch of ``R(u, p₁) = 0`` by a condition ``c(u, p₁) = 0`` (a bound or
target: ``z_k − value``) is a regular solution of ``[R; c] = 0`` in ``(u, p₁)``; with a second
parameter ``p₂`` free, that system has a curve of solutions: the point's locus. A loading
program is a sequence of legs, each a problem of its own whose end (a corner where the next
leg begins) is such a point; a leg may take parameters from points of earlier legs (say, a
quantity frozen at the end of the leg before). A :class:`PointChain` stacks the points'
systems, linked by those parameters, into one problem whose unknowns are every point's
unknowns and control; its branch in ``p₂`` is the locus of all of them together, traced by
the same tracer as any branch, so bounds, targets, events and monitored turning points work
along it unchanged. Smooth folds are continued by :func:`~._foldcurve.fold_curve` (their
condition is a test function; :func:`point_locus` sends them there).

>>> from cusp.continuation import Problem, trace
>>> prob = Problem(lambda u, p: [u[0]**2 - p["b"] * p["a"]], ["x"], {"a": 1.0, "b": 1.0})
>>> br = trace(prob, [1.0], free="b", bounds={"b": (0.5, 2.0)})
>>> end = br.special("endpoint")[-1]           # the bound hit b = 2, at x = √(2a)
>>> loc = point_locus(prob, end, free=("b", "a"), bounds={"a": (1.0, 8.0)})
>>> round(float(loc["x"][-1]), 12)             # at a = 8: x = √16
4.0
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from .._errors import ProblemDefinitionError
from .._options import ContinuationOptions
from ..problem._problem import as_problem
from ..results._branch import Branch, SpecialPoint
from ..stepping._state import TracerState
from ..stepping._tracer import Tracer
from ._chain import ChainPoint, PointChain, _Renamed
from ._directions import trace_directions
from ._foldcurve import fold_curve


def locus(
    chain: PointChain | Sequence[ChainPoint],
    start: Mapping[str, Mapping[str, float]],
    *,
    free: str,
    params: Mapping[str, float] | None = None,
    direction: str | int = "both",
    options: ContinuationOptions | None = None,
    **kwargs: Any,
) -> Branch:
    """The locus of a chain of points as the parameter ``free`` varies.

    ``start``: each point's values (``{point: {variable: value}}``) at the chain's parameter
    values (corrected by Newton first). ``direction``: ``"both"`` (default; the two halves
    joined at the start, ``info["start_index"]``), +1 or −1. Other keyword arguments
    (``bounds``, ``targets``, ``events``, ``monitor``, ``scales``, ``throw`` and option
    overrides) are those of :func:`~..stepping._tracer.trace`, on the chain's names (``"B.g"``) and
    parameters; a turning point of ``free`` along the locus is reported as a fold.
    """
    if not isinstance(chain, PointChain):
        chain = PointChain(chain, params)
    elif params:
        raise ProblemDefinitionError("params go to the PointChain when it is built")
    if free not in chain.params:
        raise ProblemDefinitionError(
            f"free parameter {free!r} is not a parameter of the chain; parameters are "
            f"{sorted(chain.params)}"
        )
    if direction not in ("both", 1, -1):
        raise ProblemDefinitionError(f"direction must be 'both', +1 or -1, got {direction!r}")
    u0 = chain.start(start)

    def begin(d: int) -> tuple[Tracer, TracerState]:
        tracer = Tracer(chain, free=free, direction=d, options=options, **kwargs)
        return tracer, tracer.init(u0)

    return trace_directions(begin, direction)


def point_locus(
    problem: Any, point: SpecialPoint, *, free: tuple[str, str], **kwargs: Any
) -> Branch:
    """The locus of a located point of a branch of ``problem`` as the second parameter of
    ``free = (p1, p2)`` varies (``p1``: the branch's free parameter): a fold by
    :func:`~._foldcurve.fold_curve`, a bound hit or target by holding its variable at its
    value (:func:`locus` of a one-point chain, whose variables keep their problem's names).
    Keyword arguments as for :func:`locus`."""
    if not isinstance(point, SpecialPoint):
        raise ProblemDefinitionError(f"point must be a SpecialPoint of a branch, got {point!r}")
    if point.kind == "fold":
        return fold_curve(problem, point, free=free, **kwargs)
    var = point.with_respect_to
    if point.kind not in ("target", "endpoint") or var is None:
        raise ProblemDefinitionError(
            f"point_locus continues folds, targets and bound hits; got a {point.kind!r} point "
            f"{point.label!r} (for an event or a corner between legs, build a PointChain)"
        )
    problem = as_problem(problem)
    p1, p2 = free
    values = point.values
    fixed = {k: float(values[k]) for k in problem.params if k != p1 and k in values}
    if p2 not in fixed:
        raise ProblemDefinitionError(f"{p2!r} is not a parameter of the problem")
    pt = ChainPoint("", problem, p1, (var, float(values[var])))
    chain = _Renamed(PointChain([pt], fixed))
    start = {"": {v: float(values[v]) for v in tuple(problem.unknowns) + (p1,)}}
    return locus(chain, start, free=p2, **kwargs)


__all__ = ["locus", "point_locus"]
