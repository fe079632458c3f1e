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

import numpy as np

from .._errors import ProblemDefinitionError
from .._options import KEEP, ContinuationOptions, Keep, with_overrides
from .._outcomes import Kind
from ..problem._events import Event
from ..problem._problem import ContinuationProblem, as_problem
from ..results._branch import Branch, SpecialPoint
from ..stepping._state import TracerState
from ..stepping._tracer import DEFAULT_OPTIONS, Tracer
from ._chain import ChainPoint, PointChain, _Renamed
from ._directions import trace_directions
from ._foldcurve import FOLD_OPTIONS, fold_curve


def locus(
    chain: PointChain | Sequence[ChainPoint],
    start: Mapping[str, Mapping[str, float]],
    *,
    free: str,
    params: Mapping[str, float] | None = None,
    direction: str | int = "both",
    bounds: Mapping[str, Sequence[float]] | None = None,
    targets: Mapping[str, Sequence[float]] | None = None,
    events: Sequence[Event] = (),
    monitor: Sequence[str] = (),
    scales: Mapping[str, float] | None = None,
    options: ContinuationOptions | None = None,
    throw: bool = True,
    rtol: float | Keep = KEEP,
    ds: float | Keep = KEEP,
    ds_min: float | Keep = KEEP,
    ds_max: float | Keep = KEEP,
    max_steps: int | Keep = KEEP,
    tol: float | Keep = KEEP,
    step_tol: float | Keep = KEEP,
    max_step_solves: int | Keep = KEEP,
    max_newton_iterations: int | Keep = KEEP,
    target_newton_iterations: int | Keep = KEEP,
    max_angle: float | Keep = KEEP,
    target_angle: float | Keep = KEEP,
    target_contraction: float | Keep = KEEP,
    target_distance: float | Keep = KEEP,
    curve_tol: float | Keep = KEEP,
    growth: float | Keep = KEEP,
    predictor: str | Keep = KEEP,
    state_weight: float | None | Keep = KEEP,
    detect_folds: bool | Keep = KEEP,
    detect_branch_points: bool | Keep = KEEP,
    locate_tol: float | Keep = KEEP,
    max_locate_iterations: int | Keep = KEEP,
) -> Branch:
    """The locus of a chain of points as the parameter ``free`` varies.

    Parameters
    ----------
    chain : PointChain or sequence of ChainPoint
        The points (built into a :class:`PointChain` with ``params`` if a sequence).
    start : mapping of str to mapping of str to float
        Each point's values, ``{point: {variable: value}}``, at the chain's parameter values
        (corrected by Newton first).
    free : str
        The parameter of the chain that varies; a turning point of it along the locus is
        reported as a fold.
    params : mapping of str to float, optional
        The chain's parameter values (only with a sequence of points).
    direction : {"both", 1, -1}, optional
        ``"both"`` (default; the two halves joined at the start, ``info["start_index"]``),
        +1 or −1.
    bounds, targets, events, monitor, scales, options, throw : optional
        As for :func:`~cusp.continuation.trace`, on the chain's names (``"B.g"``) and
        parameters.

    Returns
    -------
    Branch
        The locus: a column per chain variable (``"B.g"``) and parameter, its folds in
        ``free`` among the special points.

    Other Parameters
    ----------------
    rtol, ds, ds_min, ds_max, max_steps, tol, step_tol, max_step_solves, \
max_newton_iterations, target_newton_iterations, max_angle, target_angle, \
target_contraction, target_distance, curve_tol, growth, predictor, state_weight, \
detect_folds, detect_branch_points, locate_tol, max_locate_iterations : optional
        The field of the same name of ``options``, overridden.

    Raises
    ------
    ProblemDefinitionError
        ``free`` not a parameter of the chain, ``params`` given with a built chain, a bad
        ``direction`` or start.
    ContinuationError
        A failure of the continuation (with ``throw=True``).
    """
    options = with_overrides(options, DEFAULT_OPTIONS, locals())
    chain, u0 = _chain_start(chain, start, free, params, direction)
    curve: dict[str, Any] = dict(
        bounds=bounds, targets=targets, events=events, monitor=monitor, scales=scales
    )

    def begin(d: int) -> tuple[Tracer, TracerState]:
        tracer = Tracer(chain, free=free, direction=d, options=options, throw=throw, **curve)
        return tracer, tracer.init(u0)

    return trace_directions(begin, direction)


def _chain_start(
    chain: PointChain | Sequence[ChainPoint],
    start: Mapping[str, Mapping[str, float]],
    free: str,
    params: Mapping[str, float] | None,
    direction: str | int,
) -> tuple[PointChain, np.ndarray]:
    """The chain of :func:`locus` (checked) and its start's unknowns."""
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
    return chain, chain.start(start)


def point_locus(
    problem: ContinuationProblem,
    point: SpecialPoint,
    *,
    free: tuple[str, str],
    direction: str | int = "both",
    bounds: Mapping[str, Sequence[float]] | None = None,
    targets: Mapping[str, Sequence[float]] | None = None,
    events: Sequence[Event] = (),
    monitor: Sequence[str] = (),
    scales: Mapping[str, float] | None = None,
    options: ContinuationOptions | None = None,
    throw: bool = True,
    rtol: float | Keep = KEEP,
    ds: float | Keep = KEEP,
    ds_min: float | Keep = KEEP,
    ds_max: float | Keep = KEEP,
    max_steps: int | Keep = KEEP,
    tol: float | Keep = KEEP,
    step_tol: float | Keep = KEEP,
    max_step_solves: int | Keep = KEEP,
    max_newton_iterations: int | Keep = KEEP,
    target_newton_iterations: int | Keep = KEEP,
    max_angle: float | Keep = KEEP,
    target_angle: float | Keep = KEEP,
    target_contraction: float | Keep = KEEP,
    target_distance: float | Keep = KEEP,
    curve_tol: float | Keep = KEEP,
    growth: float | Keep = KEEP,
    predictor: str | Keep = KEEP,
    state_weight: float | None | Keep = KEEP,
    detect_folds: bool | Keep = KEEP,
    detect_branch_points: bool | Keep = KEEP,
    locate_tol: float | Keep = KEEP,
    max_locate_iterations: int | Keep = KEEP,
) -> Branch:
    """The locus of a located point of a branch as a second parameter varies.

    ``free = (p1, p2)``: ``p1`` is the branch's free parameter, ``p2`` the one that varies
    along the locus. A fold is continued by :func:`~cusp.continuation.fold_curve`; a bound
    hit or target by holding its variable at its value (:func:`locus` of a one-point chain,
    whose variables keep their problem's names).

    Parameters
    ----------
    problem : Problem or ContinuationProblem
        The problem of the branch the point lies on.
    point : SpecialPoint
        A fold, a target or a bound hit (``"endpoint"`` with ``with_respect_to``).
    free : (str, str)
        ``(p1, p2)``.
    direction, bounds, targets, events, monitor, scales, options, throw : optional
        As for :func:`locus` (for a fold, :func:`~cusp.continuation.fold_curve`, whose
        default options detect no branch points).

    Returns
    -------
    Branch
        The locus in ``(p1, p2)`` and the unknowns.

    Other Parameters
    ----------------
    rtol, ds, ds_min, ds_max, max_steps, tol, step_tol, max_step_solves, \
max_newton_iterations, target_newton_iterations, max_angle, target_angle, \
target_contraction, target_distance, curve_tol, growth, predictor, state_weight, \
detect_folds, detect_branch_points, locate_tol, max_locate_iterations : optional
        The field of the same name of ``options``, overridden.

    Raises
    ------
    ProblemDefinitionError
        ``point`` not a fold, target or bound hit of a branch, or ``p2`` not a parameter.
    ContinuationError
        A failure of the continuation (with ``throw=True``).
    """
    if not isinstance(point, SpecialPoint):
        raise ProblemDefinitionError(f"point must be a SpecialPoint of a branch, got {point!r}")
    fold = point.kind == Kind.FOLD
    options = with_overrides(options, FOLD_OPTIONS if fold else DEFAULT_OPTIONS, locals())
    curve: dict[str, Any] = dict(
        direction=direction, bounds=bounds, targets=targets, events=events, monitor=monitor,
        scales=scales, options=options, throw=throw,
    )  # fmt: skip
    if fold:
        return fold_curve(problem, point, free=free, **curve)
    return _held_locus(problem, point, free, curve)


def _held_locus(
    problem: ContinuationProblem, point: SpecialPoint, free: tuple[str, str], curve: dict
) -> Branch:
    """:func:`point_locus` of a target or bound hit: the locus of a one-point chain that
    holds the point's variable at its value (``curve``: the arguments of :func:`locus`)."""
    var = point.with_respect_to
    if point.kind not in (Kind.TARGET, Kind.ENDPOINT) or var is None:
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
    return locus(chain, start, free=p2, **curve)


__all__ = ["locus", "point_locus"]
