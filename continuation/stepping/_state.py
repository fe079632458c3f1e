"""The tracer's state and its assembly into a :class:`~..results._branch.Branch`.

The state is an immutable record replaced at every step. The branch so far is a linked list
of immutable points (each holds the one before), so a step costs O(1) whatever the length
of the branch, and an old state stays valid: stepping from it again gives the same points.
Both are built by keyword.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._errors import ProblemDefinitionError
from .._outcomes import Kind, PointStatus, Status
from ..detection._spectrum import PartialSign, SignWithSpectrum
from ..detection._tests import Record, TestFunction
from ..results._branch import Branch, SpecialPoint
from ..systems._curve import CurveSystem

# records are made by a static method of() and this bound object.__new__: a class method's
# binding and the lookup of __new__ on object cost a third of a record (callgrind), and the
# stepper makes several records a step
_new = object.__new__


@dataclass(slots=True, eq=False)
class Point:
    """One row of a branch, linked to the row before it (``prev``); built by keyword
    (:meth:`of`) and never changed after it is made."""

    z: np.ndarray
    """The curve vector (unknowns and free parameters)."""
    t: np.ndarray
    """Unit tangent (weighted norm), oriented along the direction of travel."""
    s: float
    """Pseudo-arclength from the start."""
    iterations: int
    """Newton iterations of the corrector (or of the locating method)."""
    rejected: int
    """Step tries rejected before this point was accepted."""
    residual_norm: float
    """Max-norm of the residual at ``z``."""
    ds: float
    """The step size that produced the point (0 for a point located inside a step)."""
    special: tuple[Record, ...] | None
    """Special-point records of this row."""
    prev: Point | None
    """The row before (None at the start)."""
    interpolation_error: float
    """The distance from the arc of the step that reached this point to the curve (0 at the
    start; a point located inside a step carries that step's)."""

    @staticmethod
    def of(
        *,
        z: np.ndarray,
        t: np.ndarray,
        s: float,
        iterations: int,
        rejected: int,
        residual_norm: float,
        ds: float,
        special: tuple[Record, ...] | None,
        prev: Point | None,
        interpolation_error: float,
    ) -> Point:
        """Built by keyword, fast: a class called with keywords first gathers them in a
        dict (three times the cost of this call, on every step)."""
        self = _new(Point)
        self.z = z
        self.t = t
        self.s = s
        self.iterations = iterations
        self.rejected = rejected
        self.residual_norm = residual_norm
        self.ds = ds
        self.special = special
        self.prev = prev
        self.interpolation_error = interpolation_error
        return self


@dataclass(slots=True, eq=False)
class TracerState:
    """Immutable solver state of a :class:`~cusp.continuation.Tracer`.

    Built by keyword (:meth:`of`) and never changed after it is made.

    Parameters
    ----------
    last : Point
        The last point, with the branch behind it (linked rows).
    system : CurveSystem
        The curve system valid beyond it (augmented systems carry their bordering vectors
        here).
    ds : float
        The next step size.
    test_values : tuple
        The value of each of the tracer's test functions at ``last`` (None: not yet known).
    steps : int
        The accepted steps so far.
    status : Status or None, optional
        How the curve ended (None while it goes on).
    message : str, optional
        The same, as a sentence.
    n_points : int, optional
        The number of points of the branch so far.
    stalled : int, optional
        Consecutive steps taken with ``ds`` near ``ds_min``.
    """

    last: Point
    system: CurveSystem
    ds: float
    test_values: tuple[Any, ...]
    """The value of each of the tracer's test functions at ``last`` (None: not yet known)."""
    steps: int
    status: Status | None = None
    message: str = ""
    n_points: int = 1
    stalled: int = 0
    """Consecutive steps taken with ds near ds_min."""

    @staticmethod
    def of(
        *,
        last: Point,
        system: CurveSystem,
        ds: float,
        test_values: tuple[Any, ...],
        steps: int,
        status: Status | None = None,
        message: str = "",
        n_points: int = 1,
        stalled: int = 0,
    ) -> TracerState:
        """Build a state by keyword, fast.

        A class called with keywords first gathers them in a dict (three times the cost of
        this call, on every step).

        Parameters
        ----------
        last : Point
            The last point, with the branch behind it (linked rows).
        system : CurveSystem
            The curve system valid beyond it (augmented systems carry their bordering vectors
            here).
        ds : float
            The next step size.
        test_values : tuple
            The value of each of the tracer's test functions at ``last`` (None: not yet known).
        steps : int
            The accepted steps so far.
        status : Status or None, optional
            How the curve ended (None while it goes on).
        message : str, optional
            The same, as a sentence.
        n_points : int, optional
            The number of points of the branch so far.
        stalled : int, optional
            Consecutive steps taken with ``ds`` near ``ds_min``.

        Returns
        -------
        TracerState
            The new state.
        """
        self = _new(TracerState)
        self.last = last
        self.system = system
        self.ds = ds
        self.test_values = test_values
        self.steps = steps
        self.status = status
        self.message = message
        self.n_points = n_points
        self.stalled = stalled
        return self

    def replaced(self, **changes: Any) -> TracerState:
        """Return a copy with the fields given by keyword changed.

        Parameters
        ----------
        **changes
            New values of fields, by name.

        Returns
        -------
        TracerState
            The copy (this state is left as it is).
        """
        fields = {name: getattr(self, name) for name in self.__slots__}
        fields.update(changes)
        return TracerState.of(**fields)


def _rows(state: TracerState) -> list[Point]:
    points = []
    p: Point | None = state.last
    while p is not None:
        points.append(p)
        p = p.prev
    points.reverse()
    return points


def assemble_branch(
    state: TracerState, info: dict[str, Any], kinds: frozenset[str] = frozenset()
) -> Branch:
    """The :class:`~..results._branch.Branch` of a state: column arrays (the traced
    components, the fixed parameters as constant columns), tangents, special points and
    per-point statistics; ``kinds``: those the tracer's test functions report."""
    points = _rows(state)
    system = state.system
    n_pts = len(points)
    zs, ts, ss, iterations, rejected, residual_norm, ds, errors = _columns(points)
    Z = np.concatenate(zs).reshape(n_pts, -1)
    T = np.concatenate(ts).reshape(n_pts, -1)
    names = system.names
    columns = {name: Z[:, i].copy() for i, name in enumerate(names)}
    fixed = {
        name: float(value) for name, value in system.fixed_values().items() if name not in columns
    }
    for name, value in fixed.items():
        columns[name] = np.full(n_pts, value)

    def values_at(i: int) -> dict[str, float]:  # every column at row i
        values = dict(zip(names, zs[i].tolist()))
        values.update(fixed)
        return values

    scales = dict(zip(names, system.scales.tolist()))
    specials = _special_points(points, T, ss, values_at, scales)
    status = Status.RUNNING if state.status is None else state.status
    if state.status is None:
        message = "the branch is still being traced (result of an unfinished state)"
    else:
        message = state.message
    _add_end(specials, n_pts, T, ss, values_at, scales, status)
    return Branch(
        columns,
        variables=tuple(names),
        s=np.array(ss),
        tangents=T,
        special_points=specials,
        status=status,
        message=message,
        stats=_statistics(iterations, rejected, residual_norm, ds, errors),
        info={
            "steps": state.steps,
            **info,
            "scales": dict(scales),
            "base_weights": system.base_weights.tolist(),
        },
        kinds=kinds,
    )


def _columns(points: Sequence[Point]) -> list[tuple[Any, ...]]:
    """The points' fields as columns: z, t, s, iterations, rejected, residual_norm, ds and
    interpolation_error."""
    # (one comprehension of rows, transposed by zip in C: cheaper than a comprehension per
    # column, and those than map(attrgetter(name), points), a generic lookup per row)
    return list(
        zip(
            *[
                (p.z, p.t, p.s, p.iterations, p.rejected, p.residual_norm, p.ds,
                 p.interpolation_error)
                for p in points
            ]
        )
    )  # fmt: skip


def _statistics(
    iterations: Sequence[int],
    rejected: Sequence[int],
    residual_norm: Sequence[float],
    ds: Sequence[float],
    interpolation_error: Sequence[float],
) -> dict[str, np.ndarray]:
    """The per-point arrays of a branch's ``stats``, from the points' columns."""
    return {
        "newton_iterations": np.array(iterations),
        "rejected_steps": np.array(rejected),
        "residual_norm": np.array(residual_norm),
        "ds": np.array(ds),
        "interpolation_error": np.array(interpolation_error),
    }


def _add_end(
    specials: list[SpecialPoint],
    n_pts: int,
    T: np.ndarray,
    ss: Sequence[float],
    values_at: Callable[[int], dict[str, float]],
    scales: dict[str, float],
    status: Status,
) -> None:
    """An end point at the last row, unless one is recorded there already."""
    if any(sp.kind == Kind.ENDPOINT for sp in specials if sp.index == n_pts - 1):
        return
    specials.append(
        SpecialPoint(
            kind=Kind.ENDPOINT,
            index=n_pts - 1,
            values=values_at(n_pts - 1),
            tangent=T[-1].copy(),
            status=PointStatus.CONVERGED,
            label=str(status),
            s=float(ss[-1]),
            scales=dict(scales),
        )
    )


def _special_points(
    points: Sequence[Point],
    T: np.ndarray,
    ss: Sequence[float],
    values_at: Callable[[int], dict[str, float]],
    scales: dict[str, float],
) -> list[SpecialPoint]:
    specials = []
    for i, pt in enumerate(points):
        for record in pt.special or ():
            specials.append(
                SpecialPoint(
                    kind=record.kind,
                    index=i,
                    values=values_at(i),
                    tangent=T[i].copy(),
                    status=record.status,
                    label=record.label,
                    with_respect_to=record.with_respect_to,
                    s=float(ss[i]),
                    interval=record.interval,
                    details=dict(record.details),  # the state's record stays as it was
                    scales=dict(scales),
                )
            )
    return specials


# ---------------------------------------------------------------- resume

#: the statuses of a branch that can be continued: unfinished, or stopped short (a failure
#: may pass with other options); a bound or a terminal event ended it for good
RESUMABLE = frozenset(Status) - {Status.BOUND, Status.TERMINAL_EVENT}


def resume_record(state: TracerState, tests: Sequence[TestFunction]) -> dict[str, Any]:
    """What a state holds beyond its branch's rows, for ``branch.info["resume"]``: the next
    step size, the step counts and the test functions' values at the last point (their
    labels, to check that a continuation has the same tests)."""
    return {
        "ds": state.ds,
        "steps": state.steps,
        "stalled": state.stalled,
        "tests": test_signatures(tests),
        "values": [_saved_value(v) for v in state.test_values],
    }


def test_signatures(tests: Sequence[TestFunction]) -> list[list[Any]]:
    """What tells test functions apart: type, label, value (a bound's, a target's),
    direction and whether terminal."""
    out = []
    for t in tests:
        at = getattr(t, "value_at", None)
        value = None if at is None else float(at)
        out.append([type(t).__name__, t.label, value, t.direction, t.terminal])
    return out


def _saved_value(v: Any) -> Any:
    """A test function's value as plain data (the branch-point test's sign carries the
    spectrum of its matrix, or the means to compute a partial one)."""
    if v is None or type(v) in (float, int):
        return v
    if type(v) is SignWithSpectrum:
        return {"sign": float(v), "spectrum": v.spectrum}
    if type(v) is PartialSign:
        return {"sign": float(v), "partial": True}
    if isinstance(v, float):
        return float(v)
    return {"unsupported": type(v).__name__}


def _restored_value(saved: Any, system: CurveSystem, last: Point) -> Any:
    """The test function value :func:`_saved_value` saved."""
    if saved is None or type(saved) in (float, int):
        return saved
    if "spectrum" in saved:
        value = float.__new__(SignWithSpectrum, saved["sign"])
        spectrum = saved["spectrum"]
        value.spectrum = None if spectrum is None else tuple(spectrum)
        return value
    if saved.get("partial"):
        return PartialSign(saved["sign"], system, last.z, last.t, None)
    raise ProblemDefinitionError(
        f"the branch's last point holds a test function value of type "
        f"{saved.get('unsupported')!r}, which cannot be restored: start from its last point "
        f"instead, trace(problem, branch.point(-1), ...)"
    )


def resumable(branch: Branch, names: Sequence[str], max_steps: int) -> dict[str, Any]:
    """The resume record of a branch that ``trace(problem, branch, ...)`` can continue with
    curve components ``names``; ProblemDefinitionError saying why not otherwise."""
    record = branch.info.get("resume")
    why = None
    if record is None:
        why = (
            "it carries no resume data (only branches made by trace() do; a curve traced "
            "both ways, a fold curve or a locus does not)"
        )
    elif branch.eigenvalues is not None:
        why = (
            "it was analysed for stability (its Hopf rows are inserted): continue the "
            "branch traced without stability= (a checkpoint holds it), then add stability"
        )
    elif branch.status not in RESUMABLE:
        why = (
            f"it ended for good (status {str(branch.status)!r}); to go further, start from "
            f"its last point with other bounds: trace(problem, branch.point(-1), ...)"
        )
    elif tuple(branch.variables) != tuple(names):
        why = (
            f"its components are {list(branch.variables)}, this trace's are {list(names)} "
            f"(the same free parameter is needed)"
        )
    elif record["steps"] >= max_steps:
        why = (
            f"it has taken {record['steps']} steps and max_steps={max_steps}: raise "
            f"max_steps to continue it"
        )
    if why is not None or record is None:
        raise ProblemDefinitionError(f"cannot continue this branch: {why}")
    return dict(record)


def resumed_state(
    branch: Branch, system: CurveSystem, tests: Sequence[TestFunction], max_steps: int
) -> TracerState:
    """The state a trace left ``branch`` in (:func:`resume_record`, the rows, the typical
    sizes), so that stepping on from it gives the points the uninterrupted trace gave, bit
    for bit. ``system``: the curve system of the continuing tracer at its start."""
    record = resumable(branch, system.names, max_steps)
    labels = test_signatures(tests)
    if [list(t) for t in record["tests"]] != labels:
        raise ProblemDefinitionError(
            f"cannot continue this branch with other test functions: it was traced with "
            f"{record['tests']}, this trace has {labels} (give the same bounds, targets, "
            f"events, monitor and detect_* options)"
        )
    last_row = branch.point(-1)
    z = np.column_stack([branch[name] for name in system.names])
    system = system.with_values(last_row).checked(z[0].copy())
    scales = branch.info["scales"]
    system = system.with_scales(np.array([scales[name] for name in system.names]))
    last = _rows_of(branch, z)
    values = tuple(_restored_value(v, system, last) for v in record["values"])
    return TracerState.of(
        last=last,
        system=system,
        ds=float(record["ds"]),
        test_values=values,
        steps=int(record["steps"]),
        n_points=len(branch),
        stalled=int(record["stalled"]),
    )


def _rows_of(branch: Branch, z: np.ndarray) -> Point:
    """The linked points of a branch's rows (their special records as the tracer made
    them: the end point that assembling the branch added is left out); the last one."""
    n = len(branch)
    records: list[list[Record]] = [[] for _ in range(n)]
    for sp in branch.special_points:
        if sp.kind == Kind.ENDPOINT and sp.index == n - 1 and sp.label in _STATUSES:
            continue
        records[sp.index].append(
            Record(
                kind=sp.kind,
                label=sp.label,
                with_respect_to=sp.with_respect_to,
                status=sp.status,
                interval=sp.interval,
                details=dict(sp.details),
            )
        )
    st = branch.stats
    columns = [st[k].tolist() for k in _STAT_ORDER]
    prev = None
    for i in range(n):
        it, rej, res, ds, err = (c[i] for c in columns)
        prev = Point.of(
            z=z[i].copy(), t=branch.tangents[i].copy(), s=float(branch.s[i]), iterations=it,
            rejected=rej, residual_norm=res, ds=ds, special=tuple(records[i]) or None,
            prev=prev, interpolation_error=err,
        )  # fmt: skip
    assert prev is not None
    return prev


_STATUSES = frozenset(s.value for s in Status)
_STAT_ORDER = ("newton_iterations", "rejected_steps", "residual_norm", "ds", "interpolation_error")


__all__ = ["Point", "TracerState", "assemble_branch", "resume_record", "resumed_state"]
