"""Pseudo-arclength continuation: the step-level API (:class:`Tracer`) and :func:`trace`.

A step has five phases:

1. **predict and correct** (:func:`~._step.advance`): tangent (or secant) predictor,
   Newton corrector on the bordered system and the three guards (first contraction,
   predictor-corrector distance, tangent turn; :func:`~._control.guard_factor`), a shorter
   step on rejection; the corner step and the step aimed at a bound are variants of it;
2. **accept and adapt**: the curve system is refreshed at the new point (augmented systems
   update their borders) and the next step size is set (:func:`~._control.next_step_size`);
3. **evaluate** the test functions the curve system defines
   (:meth:`~..systems._curve.CurveSystem.test_functions`) at the new point
   (:func:`~._crossings.evaluate`); when a test of the curve's geometry changed sign the step
   is confirmed by its half step (:func:`~._confirm.confirm_step`), and a sign change
   that the half step does not reproduce was a jump: the step is redone shorter (a fold is
   located first, and the step confirmed when the fold lies on the step's arc:
   :func:`~._confirm.located_on_arc`; the half step decides otherwise);
4. **locate and insert**: a sign change between the two ends of the step, or two zeros of
   one test inside it (:func:`~._crossings.pairs`), is located inside it
   (:func:`~._crossings.locate_crossings`) and the located points are linked in, in
   arclength order;
5. **terminate**: a bound or a terminal event ends the branch (``max_steps`` too, with a
   :class:`~.._errors.MaxStepsWarning`: the branch is incomplete, not a success).

The solver state (:class:`~._state.TracerState`) is an immutable record replaced at every
step; it holds the curve system valid at its last point, so stepping twice from the same
state gives the same points, bit for bit.
"""

from __future__ import annotations

import logging
import math
import warnings
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from .._errors import (
    MaxStepsWarning,
    NonFiniteResidualError,
    ProblemDefinitionError,
    format_values,
)
from .._options import ContinuationOptions
from ..detection._bracket import Bracket, Located, tangent_at
from ..detection._tests import BoundTest, ComponentTest, Record, TestFunction, generic_tests
from ..numerics._linalg import max_abs
from ..numerics._scaling import (
    diverged,
    given_scales,
    grown_sizes,
    out_of_range,
)
from ..problem._events import Event
from ..problem._problem import as_problem
from ..results._branch import Branch, SpecialPoint
from ..systems._branch import BranchSystem
from ..systems._consistency import check_consistent
from ..systems._curve import CurveSystem
from ._begin import start_state
from ._confirm import confirm_step, located_on_arc
from ._control import next_step_size
from ._crossings import corner_folds, evaluate, locate_crossings, splits, step_bracket
from ._state import Point, TracerState, assemble_branch
from ._step import STALL_FACTOR, Failure, StepRules, Trial, advance, wnorm
from ._work import OutOfWork, StepWork, stalled

logger = logging.getLogger(__name__)

_new_tuple = tuple.__new__  # builds a NamedTuple without its Python-level constructor

_DEFAULT_OPTIONS = ContinuationOptions()  # frozen: shared (validation costs 20 µs a call)


class Tracer:
    """Step-level continuation of one branch.

    >>> from cusp.continuation import Problem, Tracer
    >>> problem = Problem(lambda u, p: [u[0]**3 - u[0] - p["b"]], ["x"], {"b": -1.0})
    >>> tracer = Tracer(problem, free="b", bounds={"b": (-1, 1)})
    >>> state = tracer.init([-1.3247])
    >>> while not tracer.done(state):
    ...     state = tracer.step(state)
    >>> branch = tracer.result(state)
    >>> branch.status, [round(sp.values["b"], 10) for sp in branch.special("fold")]
    ('bound', [0.3849001795, -0.3849001795])

    The arguments are those of :func:`trace`. The tracer holds only configuration; all that
    changes, the curve system included, lives in the :class:`~._state.TracerState` records.
    """

    def __init__(
        self,
        problem: Any,
        *,
        free: str,
        params: Mapping[str, float] | None = None,
        bounds: Mapping[str, tuple[float, float]] | None = None,
        targets: Mapping[str, Sequence[float]] | None = None,
        events: Sequence[Event] = (),
        monitor: Sequence[str] = (),
        scales: Mapping[str, float] | None = None,
        direction: int = 1,
        options: ContinuationOptions | None = None,
        throw: bool = True,
        **overrides: Any,
    ) -> None:
        problem = as_problem(problem)
        if not isinstance(free, str):
            raise ProblemDefinitionError(f"free must be a parameter name, got {free!r}")
        options = options or _DEFAULT_OPTIONS
        if overrides:
            options = options.replace(**overrides)
        system = BranchSystem(problem, free, params, options.state_weight)
        self._configure(
            system,
            options,
            bounds=bounds,
            targets=targets,
            events=events,
            monitor=monitor,
            scales=scales,
            direction=direction,
            throw=throw,
        )

    @classmethod
    def for_system(
        cls, system: CurveSystem, *, options: ContinuationOptions, **kwargs: Any
    ) -> Tracer:
        """A tracer for any curve system (fold curves and other augmented systems); the
        keyword arguments are those of :func:`trace` that apply to a curve: ``bounds``,
        ``targets``, ``events``, ``monitor``, ``scales``, ``direction``, ``throw``."""
        self = object.__new__(cls)
        self._configure(system, options, **kwargs)
        return self

    def _configure(
        self,
        system: CurveSystem,
        options: ContinuationOptions,
        *,
        bounds: Mapping[str, tuple[float, float]] | None = None,
        targets: Mapping[str, Sequence[float]] | None = None,
        events: Sequence[Event] = (),
        monitor: Sequence[str] = (),
        scales: Mapping[str, float] | None = None,
        direction: int = 1,
        throw: bool = True,
        tests: Sequence[TestFunction] = (),
    ) -> None:
        if direction not in (1, -1):
            raise ProblemDefinitionError(f"direction must be +1 or -1, got {direction!r}")
        self.system = system
        """The curve system at the start (a state carries the one valid at its point)."""
        self.problem = system.problem
        self.options = options
        self.throw = bool(throw)
        self.direction = direction
        generic = generic_tests(
            system,
            options,
            fold_components=system.fold_components,
            monitor=monitor,
            targets=targets,
            bounds=bounds,
            events=events,
        )
        self.tests = (*generic, *tests)
        self._has_bp = any(t.kind == "branch_point" for t in self.tests)
        # the tests that can see several zeros inside one step
        self._split_tests = tuple((i, t) for i, t in enumerate(self.tests) if t.splits_on(system))
        bound_tests = tuple((i, t) for i, t in enumerate(self.tests) if isinstance(t, BoundTest))
        self._rules = StepRules(options, system.dim, bound_tests)
        self._scales = given_scales(system, scales)

    # ------------------------------------------------------------------ start

    def init(self, u0: Any, *, tangent: Any = None) -> TracerState:
        """Correct the starting point and compute the first tangent.

        ``u0``: initial guess of the unknowns (at the problem's parameter values), or a
        :class:`~..results._branch.SpecialPoint` (a ``"branch_point"`` starts on the other branch).
        """
        if isinstance(u0, SpecialPoint):
            return self._init_at_special(u0, tangent)
        system = self.system
        u = np.array(u0, dtype=float, ndmin=1)
        n = len(self.problem.unknowns) if self.problem is not None else system.dim - 1
        if u.shape != (n,):
            raise ProblemDefinitionError(
                f"u0 must hold {n} values (one per unknown {list(system.names[:n])}), "
                f"got shape {u.shape}"
            )
        if not math.isfinite(max_abs(u)):
            raise ProblemDefinitionError(f"u0 must be finite, got {u}")
        return self._start(system, system.start_vector(u), tangent, "start", False, from_guess=True)

    def _init_at_special(self, sp: SpecialPoint, tangent: Any) -> TracerState:
        system = self.system.with_values(sp.values)
        z0 = np.array([sp.values[name] for name in system.names], dtype=float)
        start_label = "start"
        skip_bp = False
        if sp.kind == "branch_point" and tangent is None:
            if "other_tangent" not in sp.details:
                raise ProblemDefinitionError("this branch point carries no switching data")
            other = np.array(sp.details["other_tangent"], dtype=float)
            names = sp.details.get("names", system.names)
            if tuple(names) != tuple(system.names):
                raise ProblemDefinitionError(
                    f"branch switching needs the same free parameter as the branch the "
                    f"branch point came from ({names[-1]!r})"
                )
            k = int(np.argmax(np.abs(other)))
            tangent = other * (np.sign(other[k]) * self.direction)
            start_label = "start (branch switch)"
            skip_bp = True
        elif sp.kind == "fold":
            skip_bp = True
        inherited = _by_index(system, sp.scales)
        return self._start(system, z0, tangent, start_label, skip_bp, inherited)

    def init_at(
        self, z0: Any, *, start_label: str = "start", sizes: Mapping[str, float] | None = None
    ) -> TracerState:
        """Start from a full curve vector ``z0`` (corrected with its last component fixed).
        ``sizes``: the typical sizes on a curve the start lies on (a branch whose fold this
        curve continues), for the components whose value at ``z0`` is far below them."""
        z0 = np.asarray(z0, dtype=float)
        if z0.shape != (self.system.dim,):
            raise ProblemDefinitionError(
                f"z0 must hold {self.system.dim} values {list(self.system.names)}, "
                f"got shape {z0.shape}"
            )
        inherited = _by_index(self.system, sizes)
        return self._start(self.system, z0, None, start_label, False, inherited)

    def _start(
        self,
        system: CurveSystem,
        z0: np.ndarray,
        tangent: Any,
        start_label: str,
        skip_bp: bool,
        inherited: Mapping[int, float] | None = None,
        from_guess: bool = False,
    ) -> TracerState:
        return start_state(self, system, z0, tangent, start_label, skip_bp, inherited, from_guess)

    # ------------------------------------------------------------------ step

    def done(self, state: TracerState) -> bool:
        return state.status is not None

    def step(self, state: TracerState) -> TracerState:
        """One accepted continuation step (with its special points), or the end. numpy's
        floating-point warnings are silenced inside it: a trial point where the user's
        functions overflow or take the square root of a negative number gives a non-finite
        value, which the step rejects like any other (and reports if it persists)."""
        with np.errstate(all="ignore"):
            return self._step(state)

    def _step(self, state: TracerState) -> TracerState:
        """:meth:`step` (numpy's warnings silenced by the caller)."""
        if state.status is not None:
            return state
        work = StepWork(self.options.max_step_solves)
        try:
            return self._work(state, work)
        except OutOfWork as out:
            values = state.system.values(state.last.z)
            return self._fail(state, Failure("stalled", *stalled(out, values, state.ds)))

    def _work(self, state: TracerState, work: StepWork) -> TracerState:
        # 1. predict and correct
        trial = advance(self._rules, state, work)
        if isinstance(trial, Failure):
            return self._fail(state, trial)
        while True:
            # 2.-3. accept, evaluate the test functions and confirm a sign change
            trial, system, values, crossings, br, deferred = self._evaluate(state, trial, work)
            # 4. locate the crossings inside the step (a corner's folds are only bracketed)
            special, located = self._locate(state, system, trial, values, crossings, br)
            # a component's value that Newton with it fixed cannot reach inside the step (a
            # bound located only by regula falsi) says the step jumped (across a pole, say):
            # the half step decides, unless it was confirmed already
            doubtful = br is None and any(
                isinstance(tt, ComponentTest) and loc.status != "converged"
                for tt, loc, _ in located
            )
            if not doubtful and (
                not deferred
                or located_on_arc(
                    self._rules, state, trial, br, [loc for tt, loc, _ in located if tt.confirm]
                )
            ):
                break
            # a fold not located on the step's arc: the half step decides
            shorter = confirm_step(self._rules, state, trial, br, work)
            if shorter is None:
                break
            trial = shorter
        # 5. insert the located points, adapt the step size, terminate
        return self._finish(state, system, trial, values, special, located)

    def _evaluate(self, state: TracerState, trial: Trial, work: StepWork) -> tuple:
        """The trial (or the shorter one that replaces a jump), the curve system at its end,
        the test values there, the tests whose change counts (crossings), the step's bracket
        if a test of the curve's geometry changed sign (else None) and whether its
        confirmation is deferred until the crossings are located (folds only:
        :func:`~._confirm.located_on_arc`; others are confirmed by the half step first)."""
        while True:
            system, values, crossings = evaluate(self.tests, self._has_bp, state, trial)
            if not crossings or trial.corner or trial.aimed is not None:
                return trial, system, values, crossings, None, False
            confirm = [c[0] for c in crossings if c[0].confirm]
            if not confirm:
                return trial, system, values, crossings, None, False
            br = step_bracket(self.options, state.system, state.last, trial)
            if all(tt.kind == "fold" for tt in confirm):
                return trial, system, values, crossings, br, True
            shorter = confirm_step(self._rules, state, trial, br, work)
            if shorter is None:
                return trial, system, values, crossings, br, False
            trial = shorter

    def _locate(
        self,
        state: TracerState,
        system: CurveSystem,
        trial: Trial,
        values: tuple,
        crossings: list,
        br: Bracket | None,
    ) -> tuple[tuple[Record, ...] | None, Sequence[tuple[TestFunction, Located, Bracket | None]]]:
        """The records of a corner's folds (else None) and the crossings located inside the
        step (``br``: the step's bracket, if made)."""
        if system is not state.system:  # (refreshed: the bracket is on the old system)
            br = None
        special = None
        if trial.corner:
            special, crossings = corner_folds(crossings, state.last.s, trial.h)
        elif self._split_tests:
            replaced, parts = splits(self._split_tests, self.options, state, system, trial, values)
            if replaced:
                crossings = [c for c in crossings if c[0] not in replaced] + parts
        located = (
            locate_crossings(self.options, state, system, trial, crossings, br) if crossings else ()
        )
        kept = []
        for tt, loc, where in located:
            if loc.status == "pole":  # a sign change through infinity: no special point
                logger.info("%r changed sign through a pole, not a zero: not reported", tt)
                continue
            if tt.kind in ("fold", "branch_point") and loc.status == "converged":
                # (what the user's derivatives locate, they decide: they are checked there)
                check_consistent(system, loc.z, f"the located {tt.label}")
            kept.append((tt, loc, where))
        return special, kept

    def _finish(
        self,
        state: TracerState,
        system: CurveSystem,
        trial: Trial,
        values: tuple,
        special: tuple[Record, ...] | None,
        located: Sequence[tuple[TestFunction, Located, Bracket | None]],
    ) -> TracerState:
        """Link the located points between the last point and the step's end, and end the
        branch on a terminal test or ``max_steps``."""
        o = self.options
        res, t1, factor, ds, h, _, rejected, _, aimed, interp = trial
        last = state.last
        prev, n_points = last, state.n_points
        status, message = None, ""
        end_special = special
        ends_inside = False  # a terminal point located inside the step, before its end
        for tt, loc, br in located:
            interval = (last.s, last.s + h)
            records: tuple[Record, ...] = (tt.record(system, loc, br, system.weights, interval),)
            if tt.terminal:
                status, message, extra = tt.ending(loc)
                records += extra
            if tt is aimed:  # the step's own end point
                end_special = records
                break
            prev = self._located_point(system, last, loc, records, br, prev, interp)
            n_points += 1
            if tt.terminal:
                ends_inside = True
                break
        steps = state.steps + 1
        if status is not None:
            values = state.tests  # irrelevant once finished
        if ends_inside:  # (also in a step aimed at a bound beyond another one it crossed)
            end = prev
        else:
            if status is None and steps >= o.max_steps:
                status = "max_steps"
                message = (
                    f"the branch stopped after max_steps={o.max_steps} steps at "
                    f"{format_values(system.values(res.z))}, before reaching a bound or a "
                    f"terminal event: it is incomplete (the last step was ds={ds:.3g}). "
                    + (
                        "The steps were cut far below ds: the step's guards keep rejecting "
                        "longer steps (check the Jacobian against the residual: "
                        "check_jacobian; or give typical sizes, scales=...)"
                        if state.stalled or ds < 1e-3 * o.ds
                        else "Raise max_steps, or ds_max if the steps are at it, or give "
                        "bounds that end the branch"
                    )
                )
                warnings.warn(message, MaxStepsWarning, stacklevel=3)
                end_special = (
                    *(end_special or ()),
                    ("endpoint", "max_steps", None, "converged", None, {}),
                )
            grown = grown_sizes(system.scales, res.z, self._scales)
            if grown is not None:  # the step's end is in the new sizes' metric
                k = out_of_range(grown)
                if k is not None:  # a component diverges: stop before the metric overflows
                    msg = diverged(system.names, res.z, k)
                    error = NonFiniteResidualError(msg, values=system.values(res.z))
                    return self._fail(state, Failure("nonfinite_residual", msg, error))
                system = system.with_scales(grown)
                t1 = t1 / wnorm(t1, system.weights)
            end = _new_tuple(  # a Point (see stepping.Trial on tuple.__new__)
                Point,
                (
                    res.z, t1, last.s + h, res.iterations, rejected, res.residual_norm, ds,
                    end_special, prev, interp,
                ),
            )  # fmt: skip
            n_points += 1
        stalled = state.stalled + 1 if ds < STALL_FACTOR * o.ds_min else 0
        ds_next = next_step_size(o, factor, rejected, ds)
        return _new_tuple(
            TracerState,
            (end, system, ds_next, values, steps, status, message, n_points, stalled),
        )

    def _located_point(
        self,
        system: CurveSystem,
        last: Point,
        loc: Located,
        records: tuple[Record, ...],
        br: Bracket | None,
        prev: Point,
        interp: float,
    ) -> Point:
        tan = loc.tangent
        if tan is None:
            assert br is not None  # only the aimed end point is located without a bracket
            tan = tangent_at(system, loc.z, br.row, system.weights, br)
        rn = loc.residual_norm
        if rn is None:
            rn = max_abs(system.residual(loc.z))
        return Point(
            loc.z, tan, last.s + loc.sigma, loc.iterations, 0, rn, 0.0, records, prev, interp
        )

    def _fail(self, state: TracerState, failure: Failure) -> TracerState:
        if self.throw:
            raise failure.error
        logger.warning("continuation stopped: %s", failure.message)
        return state._replace(status=failure.status, message=failure.message)

    # ------------------------------------------------------------------ result

    def result(self, state: TracerState) -> Branch:
        """Assemble the :class:`~..results._branch.Branch` (column arrays and special points) of a
        state (finished or not)."""
        return assemble_branch(state, {"direction": self.direction, "rtol": self.options.rtol})


def _by_index(system: CurveSystem, sizes: Mapping[str, float] | None) -> dict[int, float]:
    """Typical sizes by name (of a curve a start lies on) as ``{component index: size}``, for
    the components of ``system`` they name."""
    out = {}
    for name, size in (sizes or {}).items():
        k = system.index(name)
        if k is not None and math.isfinite(size) and size > 0.0:
            out[k] = float(size)
    return out


def trace(problem: Any, u0: Any, *, free: str, **kwargs: Any) -> Branch:
    """Trace the branch of ``problem`` through ``u0`` with ``free`` as the continuation
    parameter.

    Parameters
    ----------
    problem:
        a :class:`~cusp.continuation.Problem` (or any object following its protocol).
    u0:
        guess of the unknowns at the problem's parameter values (corrected by Newton), or a
        :class:`SpecialPoint`; a ``"branch_point"`` starts on the other branch through it.
    free:
        name of the parameter that varies along the branch.

    Other parameters
    ----------------
    params:
        parameter values overriding ``problem.params`` for this computation.
    bounds:
        ``{name: (low, high)}`` for any unknown or the free parameter: the branch ends exactly
        on the bound it meets.
    targets:
        ``{name: [values]}``: points located exactly at these values and inserted.
    events:
        :class:`Event` objects, located and inserted (terminal ones end the branch).
    monitor:
        unknowns whose turning points are reported as folds too (``with_respect_to`` names
        them): a snap-back is a turning point of a controlled displacement.
    direction:
        +1 (default) or −1: the sign of the free parameter's initial change.
    options:
        a :class:`ContinuationOptions`; keyword arguments named like its fields override it.
    throw:
        if False, failures return the partial branch with a status instead of raising.
    """
    tracer = Tracer(problem, free=free, **kwargs)
    return tracer.result(run(tracer, tracer.init(u0)))


def run(tracer: Tracer, state: TracerState) -> TracerState:
    """Step ``tracer`` from ``state`` until the branch ends (numpy's floating-point warnings
    silenced once for all the steps: see :meth:`Tracer.step`)."""
    with np.errstate(all="ignore"):
        while state.status is None:
            state = tracer._step(state)
    return state


__all__ = ["Tracer", "TracerState", "run", "trace"]
