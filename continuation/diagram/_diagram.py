"""A whole bifurcation diagram in one call: :func:`diagram` traces the branch through the
start, then from every located simple branch point the other branch through it, recursively,
each branch once; deflation (:func:`~._deflation.deflate`) at chosen parameter values starts
branches not connected to the start.

Each branch once (``tol = DUPLICATE_FACTOR·rtol``, distances in the weighted metric of
:mod:`~._geometry`, relative to the typical sizes):

- *before* tracing from a branch point P in its other branch's direction ``t_o``: a known
  branch that passes within ``tol`` of P (its dense output, not only its rows) with its
  tangent there within ``min(MAX_ANGLE, ∠(t_o, t_this)/4)`` of ``t_o`` (``t_this`` the
  tangent of the branch that located P) is that branch: P is linked to it, nothing is traced.
  Two distinct branches crossing at P have the tangents ``t_this`` and ``t_o`` there, so the
  branch P lies on is never taken for the other one; the quarter of their angle keeps a
  transcritical point with nearly equal slopes apart too.
- *after* tracing a branch: it is a duplicate of a known branch when :data:`CHECKS` points of
  its dense output, spread over it at the middle of arcs (between rows), all lie within
  ``tol`` of the known branch's dense output. Two distinct branches are within ``tol`` of each
  other only near where they cross or touch (a curve through a point is locally unique where
  the Jacobian has full rank); points spread over the whole branch are not all there.
  Branches closer than ``tol`` along their whole length are the same curve at the accuracy
  asked: a smaller ``rtol`` separates them.
- a closed branch stops when it returns to its start (:mod:`~._walk`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .._errors import AccuracyError, ContinuationError, ProblemDefinitionError
from .._options import KEEP, ContinuationOptions, Keep
from .._outcomes import Kind, PointStatus
from ..problem._problem import ContinuationProblem, as_problem
from ..results._branch import Branch, SpecialPoint
from ..stepping._state import TracerState
from ..stepping._tracer import DEFAULT_OPTIONS, Tracer
from ._deflation import Deflation, deflate, polished
from ._geometry import cosine, curve_of, nearest, pair_weights, samples, unit
from ._records import Diagram, DiagramBranch, DiagramPoint
from ._walk import Walked, walk

DUPLICATE_FACTOR = 4.0
"""``tol = DUPLICATE_FACTOR·rtol``: two dense outputs of one curve, each within ``rtol`` of
it, are within ``2·rtol`` of each other; twice that is the margin."""

MAX_ANGLE = 8.0
"""Degrees: a known branch through a branch point is its other branch only if its tangent
there is this close to the other branch's direction (and see the module)."""

CHECKS = 9
"""Points of a traced branch compared with the known ones."""


@dataclass(frozen=True)
class DeflationStarts:
    """Where :func:`diagram` looks for branches by deflation.

    At each value of the free parameter in ``at``, :func:`~cusp.continuation.deflate` runs
    from ``guesses`` (the known branches' points there deflated first).

    Parameters
    ----------
    at : tuple of float
        Values of the free parameter.
    guesses : tuple of tuple of float, each of length n
        Starting points of deflated Newton (unknowns).
    max_solutions : int, optional
        At most this many new solutions per value (default 10).
    """

    at: tuple[float, ...]
    guesses: tuple[tuple[float, ...], ...]
    max_solutions: int = 10


@dataclass
class _Book:
    """The diagram being built (mutable; frozen into a :class:`Diagram` at the end)."""

    begin: Callable[[Any, Mapping[str, float] | None], Callable[[int], Any]]
    free: str
    tol: float
    max_depth: int
    max_branches: int
    branches: list[DiagramBranch] = field(default_factory=list)
    points: list[dict[str, Any]] = field(default_factory=list)
    queue: list[tuple[int, int, SpecialPoint]] = field(default_factory=list)
    recognised: list[str] = field(default_factory=list)
    deflation: list[Deflation] = field(default_factory=list)
    traces: int = 0


def diagram(
    problem: ContinuationProblem,
    u0: ArrayLike,
    *,
    free: str,
    bounds: Mapping[str, Sequence[float]],
    params: Mapping[str, float] | None = None,
    max_depth: int = 3,
    max_branches: int = 50,
    monitor: Sequence[str] = (),
    scales: Mapping[str, float] | None = None,
    options: ContinuationOptions | None = None,
    rtol: float | Keep = KEEP,
    deflation: DeflationStarts | Mapping[str, Any] | None = None,
) -> Diagram:
    """The whole bifurcation diagram of ``problem`` in ``free`` within ``bounds``.

    Traces the branch through ``u0`` both ways; from every simple branch point located on a
    branch of depth below ``max_depth``, the other branch through it, both ways; each branch
    once (see the module: a branch found again — from its other end, another branch point,
    or by symmetry — is recognised and not kept; a closed branch stops on returning to its
    start). With ``deflation``, distinct solutions found by deflated Newton at given values
    of ``free`` that lie on no known branch start branches of depth 0 (with their own
    branch points).

    Parameters
    ----------
    problem : Problem or ContinuationProblem
        The equations ``R(u, p) = 0``.
    u0 : array_like, shape (n,)
        A guess of the unknowns at the problem's parameter values (corrected by Newton).
    free : str
        The parameter that varies along every branch.
    bounds : mapping of str to (float, float)
        ``{name: (low, high)}``: every branch ends on them (a diagram needs a window; give
        the free parameter's at least).
    params : mapping of str to float, optional
        Parameter values overriding ``problem.params``.
    max_depth : int, optional
        Branch switching recurses this deep (0: the start's branch only).
    max_branches : int, optional
        At most this many branches are kept; branch points beyond say so in their notes.
    monitor, scales : optional
        As for :func:`~cusp.continuation.trace`, for every branch.
    options : ContinuationOptions, optional
        The numerical settings of every branch.
    rtol : float, optional
        Overrides ``options.rtol``; also sets ``tol = DUPLICATE_FACTOR·rtol``.
    deflation : DeflationStarts or mapping, optional
        ``{"at": [values of free], "guesses": [[u…], …], "max_solutions": k}``.

    Returns
    -------
    Diagram
        The distinct branches and the branch points linking them.

    Raises
    ------
    ProblemDefinitionError
        A bad ``max_depth``, ``max_branches`` or ``deflation``, or ``bounds`` without the
        free parameter.

    Examples
    --------
    >>> from cusp.continuation import Problem, diagram
    >>> prob = Problem(lambda u, p: [u[0] * (p["p"] - u[0] ** 2)], ["x"], {"p": -1.0})
    >>> d = diagram(prob, [0.0], free="p", bounds={"p": (-1.0, 1.0)})
    >>> len(d.branches), round(d.points[0].point.values["p"], 12)  # x = 0 and p = x²
    (2, 0.0)
    """
    if not isinstance(max_depth, int) or max_depth < 0:
        raise ProblemDefinitionError(f"max_depth must be an int >= 0, got {max_depth!r}")
    if not isinstance(max_branches, int) or max_branches < 1:
        raise ProblemDefinitionError(f"max_branches must be an int >= 1, got {max_branches!r}")
    if free not in bounds:
        raise ProblemDefinitionError(
            f"bounds must bound the free parameter {free!r} (a diagram needs a window), got "
            f"bounds for {sorted(bounds)}"
        )
    starts = _deflation_starts(deflation)
    opts = options if options is not None else DEFAULT_OPTIONS
    if rtol is not KEEP:
        opts = opts.replace(rtol=rtol)

    base = dict(as_problem(problem).params)

    def begin(start: Any, at: Mapping[str, float] | None) -> Callable[[int], Any]:
        def half(d: int) -> tuple[Tracer, TracerState]:
            merged = {**base, **(params or {}), **(at or {})}
            tracer = Tracer(problem, free=free, params=merged,
                            bounds=bounds, monitor=monitor, scales=scales, direction=d,
                            options=opts, throw=False)  # fmt: skip
            return tracer, tracer.init(start)

        return half

    book = _Book(begin, free, DUPLICATE_FACTOR * opts.rtol, max_depth, max_branches)
    _add(book, walk(begin(u0, None), book.tol), depth=0, origin="start", source=None)
    _switch_all(book)
    if starts is not None:
        _deflate_all(book, problem, params, starts)
        _switch_all(book)
    return _frozen(book)


def _deflation_starts(value: DeflationStarts | Mapping[str, Any] | None) -> DeflationStarts | None:
    """``deflation`` as a :class:`DeflationStarts` (a mapping's keys checked)."""
    if value is None or isinstance(value, DeflationStarts):
        return value
    allowed = {"at", "guesses", "max_solutions"}
    unknown = set(value) - allowed
    if unknown or not {"at", "guesses"} <= set(value):
        raise ProblemDefinitionError(
            f"deflation must map 'at' and 'guesses' (and optionally 'max_solutions'), got "
            f"keys {sorted(value)}"
        )
    at = tuple(float(v) for v in np.atleast_1d(np.asarray(value["at"], dtype=float)))
    guesses = tuple(tuple(float(x) for x in np.atleast_1d(g)) for g in value["guesses"])
    return DeflationStarts(
        at=at, guesses=guesses, max_solutions=int(value.get("max_solutions", 10))
    )


def _add(book: _Book, walked: Walked, *, depth: int, origin: str, source: int | None) -> int:
    """Keep a traced branch, register its branch points and queue them; its index."""
    index = len(book.branches)
    book.branches.append(
        DiagramBranch(
            branch=walked.branch,
            depth=depth,
            origin=origin,
            source=source,
            closed=walked.closed,
            ends=walked.ends,
        )  # fmt: skip
    )
    book.traces += 1
    if source is not None:
        entry = book.points[source]
        entry["on"].append(index)
        entry["leaving"].append(index)
    for sp in walked.branch.special(Kind.BRANCH_POINT):
        k = _register(book, index, sp)
        book.queue.append((k, index, sp))
    return index


def _register(book: _Book, index: int, sp: SpecialPoint) -> int:
    """The index of the diagram point ``sp`` (on branch ``index``) is, added if new."""
    branch = book.branches[index].branch
    z = _vector(sp, branch.variables)
    for k, entry in enumerate(book.points):
        other = book.branches[entry["on"][0]].branch
        w = pair_weights(branch, other)
        d = z - _vector(entry["point"], branch.variables)
        if math.sqrt(float(d.dot(w * d))) <= book.tol:
            if index not in entry["on"]:
                entry["on"].append(index)
            return k
    book.points.append({"point": sp, "on": [index], "leaving": [], "notes": []})
    return len(book.points) - 1


def _switch_all(book: _Book) -> None:
    """Switch at every queued branch point (breadth first: the queue grows as branches are
    added)."""
    while book.queue:
        k, index, sp = book.queue.pop(0)
        book.points[k]["notes"].append(_switch(book, k, index, sp))


def _switch(book: _Book, k: int, index: int, sp: SpecialPoint) -> str:
    """Switch at point ``k`` as located on branch ``index``; a sentence saying what was done."""
    where = f"located on branch {index}"
    if sp.status != PointStatus.CONVERGED or "other_tangent" not in sp.details:
        return f"{where}: not switched (not located to tolerance, or no switching data)"
    depth = book.branches[index].depth
    if depth >= book.max_depth:
        return f"{where}: not switched (depth {depth} = max_depth)"
    known = _known_through(book, index, sp)
    if known is not None:
        _link(book, k, known)
        book.recognised.append(f"point {k} {where}: its other branch is branch {known}")
        return f"{where}: its other branch is branch {known}, already traced"
    if len(book.branches) >= book.max_branches:
        return f"{where}: not switched (max_branches = {book.max_branches} reached)"
    try:
        walked = walk(book.begin(sp, None), book.tol)
    except ContinuationError as exc:
        return f"{where}: switching failed ({exc})"
    book.traces += 1
    dup = _duplicate_of(book, walked.branch)
    if dup is not None and _along_other(book, index, sp, dup):
        _link(book, k, dup)
        book.recognised.append(f"point {k} {where}: the branch traced is branch {dup}")
        return f"{where}: the branch traced from it is branch {dup}, already traced"
    if dup is not None:  # a trace that jumped back, or failed at the point: not a branch
        return (
            f"{where}: switching failed: the trace from it (ends {walked.ends}) lies on "
            f"branch {dup}, which does not leave the point along the other branch's direction"
        )
    walked, jumped = _drop_jumped_half(book, index, sp, walked)
    book.traces -= 1  # counted by _add
    new = _add(book, walked, depth=depth + 1, origin="branch_point", source=k)
    return f"{where}: switched into branch {new}{jumped}"


def _drop_jumped_half(book: _Book, index: int, sp: SpecialPoint, walked: Walked) -> tuple:
    """(walked, note): a half of a switch that lies on a known branch not leaving the point
    along the other direction (the tracer jumped back onto it) is dropped, the other half
    kept alone, and the note says so; otherwise ``walked`` as it is and no note."""
    if walked.closed:
        return walked, ""
    for h, half in enumerate(walked.halves):
        dup = _duplicate_of(book, half)
        if dup is not None and not _along_other(book, index, sp, dup):
            keep = walked.halves[1 - h]
            ends = (f"jumped onto branch {dup}", str(keep.status))
            kept = Walked(branch=keep, closed=False, ends=ends, halves=(keep,))
            return kept, f" (one half only: the other jumped onto branch {dup}, dropped)"
    return walked, ""


def _link(book: _Book, k: int, branch: int) -> None:
    """Branch ``branch`` passes through point ``k``; it leaves it unless the point was first
    located on it."""
    entry = book.points[k]
    if branch not in entry["on"]:
        entry["on"].append(branch)
    if branch != entry["on"][0] and branch not in entry["leaving"]:
        entry["leaving"].append(branch)


def _known_through(book: _Book, index: int, sp: SpecialPoint) -> int | None:
    """A known branch through ``sp`` along its other branch's direction (see the module)."""
    this = book.branches[index].branch
    if tuple(sp.details.get("names", this.variables)) != tuple(this.variables):
        return None
    for j in range(len(book.branches)):
        if _along_other(book, index, sp, j):
            return j
    return None


def _along_other(book: _Book, index: int, sp: SpecialPoint, j: int) -> bool:
    """Whether branch ``j`` passes within tol of ``sp`` (located on branch ``index``) with its
    tangent there within ``min(MAX_ANGLE, ∠(t_o, t_this)/4)`` of the other branch's ``t_o``."""
    this, item = book.branches[index].branch, book.branches[j].branch
    w = pair_weights(this, item)
    t_other = np.asarray(sp.details["other_tangent"], dtype=float)
    spread = math.degrees(math.acos(min(1.0, cosine(t_other, np.asarray(sp.tangent), w))))
    limit = math.cos(math.radians(min(MAX_ANGLE, spread / 4.0)))
    hit = nearest(curve_of(item), _vector(sp, this.variables), w, reach=book.tol)
    if hit is None or hit.distance > book.tol:
        return False
    return cosine(hit.tangent, unit(t_other, w), w) >= limit


def _duplicate_of(book: _Book, branch: Branch) -> int | None:
    """The known branch a traced one lies on (every checked point within tol), or None."""
    points = samples(curve_of(branch), CHECKS)
    for j, item in enumerate(book.branches):
        w = pair_weights(branch, item.branch)
        curve = curve_of(item.branch)
        if all(_within(curve, q, w, book.tol) for q in points):
            return j
    return None


def _within(curve: Any, q: np.ndarray, w: np.ndarray, tol: float) -> bool:
    hit = nearest(curve, q, w, reach=tol)
    return hit is not None and hit.distance <= tol


def _deflate_all(
    book: _Book, problem: ContinuationProblem, params: Mapping[str, float] | None,
    starts: DeflationStarts,
) -> None:  # fmt: skip
    """Deflated solutions at each value of ``starts.at``; a branch from each one on no known
    branch."""
    for value in starts.at:
        at = {book.free: value}
        known = [polished(problem, {**(params or {}), **at}, u) for u in _known_at(book, value)]
        found = deflate(problem, list(starts.guesses), params={**(params or {}), **at},
                        max_solutions=starts.max_solutions, known=known)  # fmt: skip
        book.deflation.append(found)
        for u in found.solutions:
            _start_from(book, u, value)


def _known_at(book: _Book, value: float) -> list[np.ndarray]:
    """The unknowns of the known branches' rows where the free parameter equals ``value``
    (the branches' dense output there): deflated before the search starts."""
    out = []
    for item in book.branches:
        br = item.branch
        x = br[book.free]
        for i in np.flatnonzero((x[:-1] - value) * (x[1:] - value) <= 0.0).tolist():
            try:
                part = br.interpolate([_crossing_s(br, i, value)])
            except AccuracyError:  # an arc off the curve (a kink): not deflated
                continue
            out.append(np.array([part[v][0] for v in br.variables[:-1]]))
    return out


def _crossing_s(br: Branch, i: int, value: float) -> float:
    """The arclength on segment ``i`` where the free parameter is ``value`` (linear)."""
    x0, x1 = float(br[br.variables[-1]][i]), float(br[br.variables[-1]][i + 1])
    f = 0.5 if x1 == x0 else (value - x0) / (x1 - x0)
    return float(br.s[i] + min(1.0, max(0.0, f)) * (br.s[i + 1] - br.s[i]))


def _start_from(book: _Book, u: np.ndarray, value: float) -> None:
    """A branch from the deflated solution ``u`` at ``free = value``, unless on a known one."""
    z = np.append(u, value)
    for j, item in enumerate(book.branches):
        curve = curve_of(item.branch)
        if _within(curve, z, curve.w, book.tol):
            book.recognised.append(
                f"deflated solution at {book.free} = {value:g}: on branch {j}, not traced"
            )
            return
    if len(book.branches) >= book.max_branches:
        book.recognised.append(f"deflated solution at {book.free} = {value:g}: max_branches")
        return
    try:
        walked = walk(book.begin(u, {book.free: value}), book.tol)
    except ContinuationError as exc:
        book.recognised.append(f"deflated solution at {book.free} = {value:g}: failed ({exc})")
        return
    book.traces += 1
    dup = _duplicate_of(book, walked.branch)
    if dup is not None:
        book.recognised.append(
            f"deflated solution at {book.free} = {value:g}: on branch {dup}, already traced"
        )
        return
    book.traces -= 1
    _add(book, walked, depth=0, origin="deflation", source=None)


def _vector(sp: SpecialPoint, names: Sequence[str]) -> np.ndarray:
    return np.array([sp.values[v] for v in names], dtype=float)


def _frozen(book: _Book) -> Diagram:
    points = tuple(
        DiagramPoint(
            point=e["point"],
            on=tuple(e["on"]),
            leaving=tuple(e["leaving"]),
            notes=tuple(e["notes"]),
        )  # fmt: skip
        for e in book.points
    )
    return Diagram(branches=tuple(book.branches), points=points, free=book.free, tol=book.tol,
                   recognised=tuple(book.recognised), deflation=tuple(book.deflation),
                   traces=book.traces)  # fmt: skip


__all__ = ["CHECKS", "DUPLICATE_FACTOR", "MAX_ANGLE", "DeflationStarts", "diagram"]
