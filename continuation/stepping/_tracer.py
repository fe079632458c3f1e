"""Pseudo-arclength continuation: the step-level API (:class:`Tracer`).

A step (docs/continuation.md) has five phases: 1. predict and correct (:func:`~._step.advance`:
predictor, Newton corrector, the three guards of :func:`~._control.guard_factor`, a shorter
step on rejection; the corner step and the step aimed at a bound are variants, :mod:`._advance`);
2. accept and adapt (the curve system refreshed, :func:`~._control.next_step_size`);
3. evaluate the test functions (:func:`~._crossings.evaluate`; a sign change of a test of the
curve's geometry is confirmed by the half step, :func:`~._confirm.confirm_step`: one it does
not reproduce was a jump, and the step is redone shorter; a fold is confirmed where it lies on
the step's arc, :func:`~._confirm.located_on_arc`); 4. locate and insert the zeros inside the
step (:func:`~._crossings.splits`, :func:`~._crossings.locate_crossings`), in arclength order;
5. terminate (a bound, a terminal event, or ``max_steps`` with a
:class:`~.._errors.MaxStepsWarning`: the branch is incomplete, not a success).

The solver state (:class:`~._state.TracerState`) is an immutable record replaced at every step;
it holds the curve system valid at its last point: stepping twice from a state gives the same
points, bit for bit.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Mapping, Sequence

import numpy as np
from numpy.typing import ArrayLike

from .._errors import NonFiniteResidualError, ProblemDefinitionError
from .._options import KEEP, ContinuationOptions, Keep, with_overrides
from .._outcomes import Kind, PointStatus, Status
from ..detection._tests import BoundTest, ComponentTest, Record, TestFunction, generic_tests
from ..numerics._linalg import max_abs
from ..numerics._scaling import diverged, given_scales, grown_scales, out_of_range
from ..problem._events import Event
from ..problem._problem import ContinuationProblem, as_problem
from ..results._branch import Branch, SpecialPoint
from ..systems._branch import BranchSystem
from ..systems._consistency import check_consistent
from ..systems._curve import CurveSystem
from ._advance import advance
from ._begin import Beginning, StartAt, as_array, by_index, start_state
from ._confirm import confirm_step, located_on_arc
from ._control import next_step_size
from ._crossings import (
    Evaluation,
    Found,
    corner_folds,
    evaluate,
    locate_crossings,
    splits,
    step_bracket,
)
from ._insert import endpoint_record, link_located
from ._state import Point, TracerState, assemble_branch, resume_record
from ._step import STALL_FACTOR, Failure, StepRules, Trial, wnorm
from ._work import OutOfWork, StepWork, max_steps_message, stalled

logger = logging.getLogger(__name__)

DEFAULT_OPTIONS = ContinuationOptions()  # frozen: shared (validation costs 20 µs a call)


class Tracer:
    """Step-level continuation of one curve.

    The tracer holds only configuration; all that changes, the curve system included, lives
    in the :class:`~cusp.continuation.TracerState` records.

    Parameters
    ----------
    problem : Problem or ContinuationProblem
        The equations ``R(u, p) = 0``.
    free : str
        The parameter that varies along the branch.
    params, bounds, targets, events, monitor, scales, direction, options, throw, rtol, ds, \
ds_min, ds_max, max_steps, tol, step_tol, max_step_solves, max_newton_iterations, \
target_newton_iterations, max_angle, target_angle, target_contraction, target_distance, \
curve_tol, growth, predictor, state_weight, detect_folds, detect_branch_points, \
locate_tol, max_locate_iterations : optional
        As for :func:`~cusp.continuation.trace`, which documents them and what is raised.

    Examples
    --------
    >>> from cusp.continuation import Problem, Tracer
    >>> problem = Problem(lambda u, p: [u[0]**3 - u[0] - p["b"]], ["x"], {"b": -1.0})
    >>> tracer = Tracer(problem, free="b", bounds={"b": (-1, 1)})
    >>> state = tracer.init([-1.3247])
    >>> while not tracer.done(state):
    ...     state = tracer.step(state)
    >>> branch = tracer.result(state)
    >>> branch.status, [round(sp.values["b"], 10) for sp in branch.special("fold")]
    ('bound', [0.3849001795, -0.3849001795])
    """

    def __init__(
        self,
        problem: ContinuationProblem,
        *,
        free: str,
        params: Mapping[str, float] | None = None,
        bounds: Mapping[str, Sequence[float]] | None = None,
        targets: Mapping[str, Sequence[float]] | None = None,
        events: Sequence[Event] = (),
        monitor: Sequence[str] = (),
        scales: Mapping[str, float] | None = None,
        direction: int = 1,
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
    ) -> None:
        problem = as_problem(problem)
        if not isinstance(free, str):
            raise ProblemDefinitionError(f"free must be a parameter name, got {free!r}")
        options = with_overrides(options, DEFAULT_OPTIONS, locals())
        self._configure(
            branch_system(problem, free, params, options),
            options,
            bounds=bounds,
            targets=targets,
            events=events,
            monitor=monitor,
            scales=scales,
            direction=direction,
            throw=throw,
            tests=(),
        )

    @classmethod
    def for_system(
        cls,
        system: CurveSystem,
        *,
        options: ContinuationOptions,
        bounds: Mapping[str, Sequence[float]] | None = None,
        targets: Mapping[str, Sequence[float]] | None = None,
        events: Sequence[Event] = (),
        monitor: Sequence[str] = (),
        scales: Mapping[str, float] | None = None,
        direction: int = 1,
        throw: bool = True,
        tests: Sequence[TestFunction] = (),
    ) -> Tracer:
        """Build a tracer for any curve system (fold curves and other augmented systems).

        Parameters
        ----------
        system : CurveSystem
            The curve (its start system).
        options : ContinuationOptions
            The numerical settings.
        bounds, targets, events, monitor, scales, direction, throw : optional
            As for :func:`~cusp.continuation.trace`, on the curve's components.
        tests : sequence of TestFunction, optional
            Test functions evaluated besides the generic ones of the curve (folds of its
            ``fold_components`` and of the monitored components, branch points, targets,
            bounds, events; :func:`~..detection._tests.generic_tests`), after them: the
            cusp and codimension-2 tests of a fold curve, or tests of one's own.

        Returns
        -------
        Tracer
            The tracer (start it with :meth:`init_at`).
        """
        self = object.__new__(cls)
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
            tests=tests,
        )
        return self

    def _configure(
        self,
        system: CurveSystem,
        options: ContinuationOptions,
        *,
        bounds: Mapping[str, Sequence[float]] | None,
        targets: Mapping[str, Sequence[float]] | None,
        events: Sequence[Event],
        monitor: Sequence[str],
        scales: Mapping[str, float] | None,
        direction: int,
        throw: bool,
        tests: Sequence[TestFunction],
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
        self.tests: tuple[TestFunction, ...] = (*generic, *tests)
        branch_point = Kind.BRANCH_POINT
        self._has_bp = any(t.kind == branch_point for t in self.tests)
        # the tests that can see several zeros inside one step
        self._split_tests = tuple((i, t) for i, t in enumerate(self.tests) if t.splits_on(system))
        bound_tests = tuple((i, t) for i, t in enumerate(self.tests) if isinstance(t, BoundTest))
        self._rules = StepRules(options, system.dim, bound_tests)
        self._scales = given_scales(system.names, scales)

    # ------------------------------------------------------------------ start

    def init(
        self, u0: ArrayLike | SpecialPoint, *, tangent: ArrayLike | None = None
    ) -> TracerState:
        """Correct the starting point and compute the first tangent.

        Parameters
        ----------
        u0 : array_like, shape (n,), or SpecialPoint
            Initial guess of the unknowns (at the problem's parameter values), or a special
            point of a branch (a ``"branch_point"`` starts on the other branch).
        tangent : array_like, shape (n + 1,), optional
            The start's tangent, if known (the start is then not corrected).

        Returns
        -------
        TracerState
            The state at the start.

        Raises
        ------
        ProblemDefinitionError
            A ``u0`` of the wrong shape or not finite, or a branch point without switching data.
        ContinuationError
            The start could not be corrected (with ``throw=True``).
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
        z0 = system.start_vector(u)
        return self._start(
            StartAt(system=system, z0=z0, tangent=as_array(tangent), from_guess=True)
        )

    def _init_at_special(self, sp: SpecialPoint, tangent: ArrayLike | None) -> TracerState:
        system = self.system.with_values(sp.values)
        z0 = np.array([sp.values[name] for name in system.names], dtype=float)
        label = "start"
        skip_bp = False
        t0 = as_array(tangent)
        if sp.kind == Kind.BRANCH_POINT and t0 is None:
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
            t0 = other * (np.sign(other[k]) * self.direction)
            label = "start (branch switch)"
            skip_bp = True
        elif sp.kind == Kind.FOLD:
            skip_bp = True
        inherited = by_index(system, sp.scales)
        at = StartAt(
            system=system, z0=z0, tangent=t0, label=label, skip_bp=skip_bp, inherited=inherited
        )
        return self._start(at)

    def init_at(
        self,
        z0: ArrayLike,
        *,
        start_label: str = "start",
        scales: Mapping[str, float] | None = None,
    ) -> TracerState:
        """Start from a full curve vector ``z0``, corrected with its last component fixed.

        Parameters
        ----------
        z0 : array_like, shape (dim,)
            The curve's components (``system.names``).
        start_label : str, optional
            The label of the start's special point.
        scales : mapping of str to float, optional
            Typical sizes on a curve the start lies on (whose fold this curve continues).

        Returns
        -------
        TracerState
            The state at the start.

        Raises
        ------
        ProblemDefinitionError
            A ``z0`` of the wrong shape.
        """
        z = np.asarray(z0, dtype=float)
        if z.shape != (self.system.dim,):
            raise ProblemDefinitionError(
                f"z0 must hold {self.system.dim} values {list(self.system.names)}, "
                f"got shape {z.shape}"
            )
        inherited = by_index(self.system, scales)
        return self._start(
            StartAt(system=self.system, z0=z, label=start_label, inherited=inherited)
        )

    def _start(self, at: StartAt) -> TracerState:
        begin = Beginning(
            options=self.options, tests=self.tests, given=self._scales, direction=self.direction
        )
        return start_state(begin, at)

    # ------------------------------------------------------------------ step

    def done(self, state: TracerState) -> bool:
        """Return whether the curve of ``state`` has ended.

        Parameters
        ----------
        state : TracerState
            A state of this tracer.

        Returns
        -------
        bool
            True once the state has a status.
        """
        return state.status is not None

    def step(self, state: TracerState) -> TracerState:
        """Take one accepted continuation step (with its special points), or end the curve.

        numpy's floating-point warnings are silenced inside it: a trial point where the user's
        functions overflow or take the square root of a negative number gives a non-finite
        value, which the step rejects like any other (and reports if it persists).

        Parameters
        ----------
        state : TracerState
            The state to step from (not changed).

        Returns
        -------
        TracerState
            The state after the step.
        """
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
            error = stalled(out, state.system.values(state.last.z), state.ds)
            return self._fail(
                state, Failure(status=Status.STALLED, message=str(error), error=error)
            )

    def _work(self, state: TracerState, work: StepWork) -> TracerState:
        # 1. predict and correct
        trial = advance(self._rules, state, work)
        if isinstance(trial, Failure):
            return self._fail(state, trial)
        while True:
            # 2.-3. accept, evaluate the test functions and confirm a sign change
            judged = self._evaluate(state, trial, work)
            trial = judged.trial
            # 4. locate the crossings inside the step (a corner's folds are only bracketed)
            special, located = self._locate(state, judged)
            if not located or self._confirmed(state, judged, located):
                break
            # a fold not located on the step's arc: the half step decides
            shorter = confirm_step(self._rules, state, trial, judged.bracket, work)
            if shorter is None:
                break
            trial = shorter
        # 5. insert the located points, adapt the step size, terminate
        return self._finish(state, judged, special, located)

    def _confirmed(self, state: TracerState, judged: Evaluation, located: Sequence[Found]) -> bool:
        """Whether the step needs no half step: a component's value that Newton with it
        fixed cannot reach inside the step (a bound located only by regula falsi) says the
        step jumped (across a pole, say), unless it was confirmed already; a fold is
        confirmed where it was located on the step's arc."""
        br = judged.bracket
        doubtful = br is None and any(
            isinstance(f.test, ComponentTest) and f.located.status is not PointStatus.CONVERGED
            for f in located
        )
        if doubtful:
            return False
        if not judged.deferred:
            return True
        assert br is not None
        points = [f.located for f in located if f.test.confirm]
        return located_on_arc(self._rules, state, judged.trial, br, points)

    def _evaluate(self, state: TracerState, trial: Trial, work: StepWork) -> Evaluation:
        """The trial evaluated by the tests (:class:`~._crossings.Evaluation`), confirmed by
        the half step where a test of the curve's geometry (not a fold) changed sign."""
        while True:
            judged = ev = evaluate(self.tests, self._has_bp, state, trial)
            if not ev.crossings or trial.corner or trial.aimed is not None:
                return judged
            confirm = [c.test for c in ev.crossings if c.test.confirm]
            if not confirm:
                return judged
            br = step_bracket(self.options, state.system, state.last, trial)
            if all(tt.kind == Kind.FOLD for tt in confirm):
                return judged.with_bracket(br, deferred=True)
            shorter = confirm_step(self._rules, state, trial, br, work)
            if shorter is None:
                return judged.with_bracket(br)
            trial = shorter

    def _locate(
        self, state: TracerState, judged: Evaluation
    ) -> tuple[tuple[Record, ...] | None, list[Found]]:
        """The records of a corner's folds (else None) and the crossings located inside the
        step (a sign change through a pole dropped; what the user's derivatives locate,
        checked against the residual there)."""
        system, trial, crossings = judged.system, judged.trial, judged.crossings
        br = None if system is not state.system else judged.bracket  # (refreshed: not on it)
        special = None
        if trial.corner:
            special, crossings = corner_folds(crossings, state.last.s, trial.h)
        elif self._split_tests:
            replaced, parts = splits(
                self._split_tests, self.options, state, system, trial, judged.values
            )
            if replaced:
                crossings = [c for c in crossings if c.test not in replaced] + parts
        located = (
            locate_crossings(self.options, state, system, trial, crossings, br) if crossings else []
        )
        kept = []
        for f in located:
            if f.located.status is PointStatus.POLE:  # a sign change through infinity
                logger.info("%r changed sign through a pole, not a zero: not reported", f.test)
                continue
            if (
                f.test.kind in (Kind.FOLD, Kind.BRANCH_POINT)
                and f.located.status is PointStatus.CONVERGED
            ):
                check_consistent(system, f.located.z, f"the located {f.test.label}")
            kept.append(f)
        return special, kept

    def _finish(
        self,
        state: TracerState,
        judged: Evaluation,
        special: tuple[Record, ...] | None,
        located: Sequence[Found],
    ) -> TracerState:
        """Link the located points between the last point and the step's end, and end the
        branch on a terminal test, ``max_steps`` or a diverging component."""
        o, system, trial = self.options, judged.system, judged.trial
        end, n_points = state.last, state.n_points
        status: Status | None = None
        message, end_special, inside = "", special, False
        if located:  # (most steps locate nothing)
            linked = link_located(state, system, trial, located, special)
            end, n_points, status, message = (
                linked.prev,
                linked.n_points,
                linked.status,
                linked.message,
            )
            end_special, inside = linked.end_special, linked.inside
        steps = state.steps + 1
        values = judged.values if status is None else state.test_values  # (irrelevant once ended)
        if not inside:
            if status is None and steps >= o.max_steps:
                status, message = Status.MAX_STEPS, max_steps_message(o, state, system, trial)
                end_special = (*(end_special or ()), endpoint_record("max_steps"))
            grown = grown_scales(system.scales, trial.res.z, self._scales)
            t1 = trial.t
            if grown is not None:  # the step's end is in the new scales' metric
                k = out_of_range(grown)
                if k is not None:  # a component diverges: stop before the metric overflows
                    return self._diverged(state, system, trial, k)
                system = system.with_scales(grown)
                t1 = t1 / wnorm(t1, system.weights)
            res = trial.res
            end = Point.of(
                z=res.z,
                t=t1,
                s=state.last.s + trial.h,
                iterations=res.iterations,
                rejected=trial.rejected,
                residual_norm=res.residual_norm,
                ds=trial.ds,
                special=end_special,
                prev=end,
                interpolation_error=trial.interpolation_error,
            )
            n_points += 1
        return TracerState.of(
            last=end,
            system=system,
            ds=next_step_size(o, trial.factor, trial.rejected, trial.ds),
            test_values=values,
            steps=steps,
            status=status,
            message=message,
            n_points=n_points,
            stalled=state.stalled + 1 if trial.ds < STALL_FACTOR * o.ds_min else 0,
        )

    def _diverged(
        self, state: TracerState, system: CurveSystem, trial: Trial, k: int
    ) -> TracerState:
        """The end of a branch whose component ``k`` outgrew the largest scale."""
        msg = diverged(system.names, trial.res.z, k)
        error = NonFiniteResidualError(msg, values=system.values(trial.res.z))
        return self._fail(
            state, Failure(status=Status.NONFINITE_RESIDUAL, message=msg, error=error)
        )

    def _fail(self, state: TracerState, failure: Failure) -> TracerState:
        if self.throw:
            raise failure.error
        logger.warning("continuation stopped: %s", failure.message)
        return state.replaced(status=failure.status, message=failure.message)

    # ------------------------------------------------------------------ result

    def result(self, state: TracerState) -> Branch:
        """Assemble the branch of a state (finished or not).

        Parameters
        ----------
        state : TracerState
            A state of this tracer.

        Returns
        -------
        Branch
            Its column arrays and special points.
        """
        info = {
            "direction": self.direction,
            "rtol": self.options.rtol,
            "options": self.options.as_dict(),
            "resume": {**resume_record(state, self.tests), "given_scales": dict(self._scales)},
        }
        kinds = frozenset(t.kind for t in self.tests)
        return assemble_branch(state, info, kinds)


def branch_system(
    problem: ContinuationProblem,
    free: str,
    params: Mapping[str, float] | None,
    options: ContinuationOptions,
) -> BranchSystem:
    """The curve system of the branch of ``problem`` in ``free`` (``params`` overriding its
    parameters): a :class:`Tracer`'s, which :func:`~._trace.trace` makes itself, its option
    keywords merged once (:func:`~.._options.with_overrides` reads an entry point's
    ``locals()``: a dict of its fifty arguments, a few µs a trace)."""
    problem = as_problem(problem)
    if not isinstance(free, str):
        raise ProblemDefinitionError(f"free must be a parameter name, got {free!r}")
    return BranchSystem(problem, free, params, options.state_weight)


__all__ = ["Tracer", "TracerState", "branch_system"]
