"""The entry point of a branch: :func:`trace` (a :class:`~._tracer.Tracer` run to the end)."""

from __future__ import annotations

import logging
import os
import sys
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .._errors import ProblemDefinitionError
from .._options import KEEP, ContinuationOptions, Keep, StabilityOptions, with_overrides
from ..detection._eigen import vector_field_mass
from ..problem._events import Event
from ..problem._problem import ContinuationProblem, as_problem
from ..results._branch import Branch, SpecialPoint
from ..results._stability import with_stability
from ._state import TracerState, resumed_state
from ._tracer import DEFAULT_OPTIONS, Tracer, branch_system

logger = logging.getLogger("cusp.continuation")


def trace(
    problem: ContinuationProblem,
    u0: ArrayLike | SpecialPoint | Mapping[str, float] | Branch,
    *,
    free: str,
    params: Mapping[str, float] | None = None,
    bounds: Mapping[str, Sequence[float]] | None = None,
    targets: Mapping[str, Sequence[float]] | None = None,
    events: Sequence[Event] = (),
    monitor: Sequence[str] = (),
    scales: Mapping[str, float] | None = None,
    direction: int | None = None,
    options: ContinuationOptions | None = None,
    throw: bool = True,
    stability: bool | StabilityOptions = False,
    checkpoint: str | os.PathLike[str] | None = None,
    checkpoint_every: int = 100,
    progress: bool = False,
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
    """Trace the branch of ``problem`` through ``u0`` with ``free`` as the parameter.

    The branch is a curve of solutions of ``R(u, p) = 0`` followed by pseudo-arclength
    continuation in the unknowns and the free parameter, its folds, branch points, events
    and targets located on the way.

    Parameters
    ----------
    problem : Problem or ContinuationProblem
        The equations ``R(u, p) = 0`` (a :class:`~cusp.continuation.Problem`, or any object
        following its protocol).
    u0 : array_like, shape (n,), mapping, SpecialPoint or Branch
        A guess of the unknowns at the problem's parameter values (corrected by Newton); a
        point ``{name: value}`` holding every unknown and any parameters (a row of a branch,
        ``branch.point(i)``: its parameter values are used, and ``params`` may not
        contradict them); a special point of a branch (a ``"branch_point"`` starts on the
        other branch through it, ``direction`` choosing the half-branch); or a branch to
        continue from its last point (one that stopped at ``max_steps`` or failed, or a
        checkpoint loaded with :func:`~cusp.continuation.load`): with its tangent, step size
        and options (``options`` and the option keywords override them; ``max_steps``
        counts the branch's steps too), the same ``free``, bounds, targets, events and
        monitor, it gives the points the uninterrupted trace gives, bit for bit.
    free : str
        The parameter that varies along the branch.
    params : mapping of str to float, optional
        Parameter values overriding ``problem.params`` for this computation.
    bounds : mapping of str to (float, float), optional
        ``{name: (low, high)}`` for any unknown or the free parameter: the branch ends
        exactly on the bound it meets.
    targets : mapping of str to sequence of float, optional
        ``{name: [values]}``: points located exactly at these values and inserted.
    events : sequence of Event, optional
        Zeros of user functions located and inserted (terminal ones end the branch).
    monitor : sequence of str, optional
        Unknowns whose turning points are reported as folds too (``with_respect_to`` names
        them): a snap-back is a turning point of a controlled displacement.
    scales : mapping of str to float, optional
        Typical sizes of components (otherwise taken at the start and grown along).
    direction : {1, -1}, optional
        The sign of the free parameter's initial change (default 1; continuing a branch,
        its own direction).
    options : ContinuationOptions, optional
        The numerical settings (default: ``ContinuationOptions()``).
    throw : bool, optional
        If False, a failure returns the partial branch with its status instead of raising.
    stability : bool or StabilityOptions, optional
        For a problem declared a vector field (``Problem(..., mass=...)``): the eigenvalues
        of every point (``branch.eigenvalues``), the column ``"n_unstable"`` (the number
        with positive real part) and the Hopf points located (``"hopf"`` special points
        with ``details["omega"]`` and ``details["first_lyapunov"]``). ``True`` is
        ``StabilityOptions()``; see docs/continuation.md, "Stability and Hopf".
    checkpoint : path, optional
        A file to which the branch so far is saved (:meth:`Branch.save`, atomically) every
        ``checkpoint_every`` steps, when the trace ends or is interrupted (an exception,
        Ctrl-C), without stability; ``trace(problem, load(checkpoint), ...)`` continues it.
    checkpoint_every : int
        Steps between checkpoints (>= 1).
    progress : bool
        Show a progress bar (tqdm, ``pip install 'cusp[progress]'``) on a terminal, for a
        trace that lasts over a second: steps taken, their rate, the free parameter. Nothing
        is shown when standard error is not a terminal.

    Returns
    -------
    Branch
        The traced curve: columns, arclength, tangents, special points, status.

    Other Parameters
    ----------------
    rtol, ds, ds_min, ds_max, max_steps, tol, step_tol, max_step_solves, \
max_newton_iterations, target_newton_iterations, max_angle, target_angle, \
target_contraction, target_distance, curve_tol, growth, predictor, state_weight, \
detect_folds, detect_branch_points, locate_tol, max_locate_iterations : optional
        The field of the same name of ``options``, overridden for this computation
        (documented and validated by :class:`~cusp.continuation.ContinuationOptions`).

    Raises
    ------
    ProblemDefinitionError
        A malformed problem, start or argument (the message names it).
    OptionsError
        An option outside its allowed range.
    ContinuationError
        A failure of the continuation (with ``throw=True``): :class:`ConvergenceError`,
        :class:`StepGuardError`, :class:`NonFiniteResidualError`, :class:`StalledError`.
    """
    wanted = stability_options(stability)
    if wanted is not None:
        vector_field_mass(problem)  # (refused before tracing: no vector field, no stability)
    watch = Watch.of(checkpoint, checkpoint_every, progress)
    if isinstance(u0, Branch):
        options, params, scales, direction = continued(u0, options, params, scales, direction)
    elif isinstance(u0, Mapping):
        u0, params = point_start(as_problem(problem), u0, params)
    options = with_overrides(options, DEFAULT_OPTIONS, locals())
    tracer = Tracer.for_system(
        branch_system(problem, free, params, options), options=options, bounds=bounds,
        targets=targets, events=events, monitor=monitor, scales=scales,
        direction=1 if direction is None else direction, throw=throw,
    )  # fmt: skip
    branch = tracer.result(run(tracer, first_state(tracer, u0), watch))
    if wanted is None:
        return branch
    return with_stability(tracer.system.problem, branch, wanted)


def first_state(tracer: Tracer, u0: Any) -> TracerState:
    """The state a trace starts from: a branch's last (continued), or ``u0`` corrected."""
    if isinstance(u0, Branch):
        return resumed_state(u0, tracer.system, tracer.tests, tracer.options.max_steps)
    return tracer.init(u0)


def stability_options(stability: bool | StabilityOptions) -> StabilityOptions | None:
    """The ``stability`` argument of an entry point as options (None: no stability)."""
    if stability is False:
        return None
    if stability is True:
        return StabilityOptions()
    if not isinstance(stability, StabilityOptions):
        raise ProblemDefinitionError(
            f"stability must be True, False or a StabilityOptions, got {stability!r}"
        )
    return stability


def run(tracer: Tracer, state: TracerState, watch: Watch | None = None) -> TracerState:
    """Step ``tracer`` from ``state`` until the curve ends.

    numpy's floating-point warnings are silenced once for all the steps (see
    :meth:`Tracer.step`); ``watch``: checkpoints and progress (None: none, and no cost per
    step).
    """
    if watch is not None:
        return watch.run(tracer, state)
    with np.errstate(all="ignore"):
        while state.status is None:
            state = tracer._step(state)
    return state


def continued(
    branch: Branch,
    options: ContinuationOptions | None,
    params: Mapping[str, float] | None,
    scales: Mapping[str, float] | None,
    direction: int | None,
) -> tuple[ContinuationOptions | None, Mapping[str, float] | None, Any, int]:
    """The options, parameters, scales and direction of a trace that continues ``branch``:
    its own where not given (the given ones checked against it)."""
    info = branch.info
    record = info.get("resume")
    if record is None or "options" not in info:
        raise ProblemDefinitionError(
            "cannot continue this branch: it carries no resume data (only branches made by "
            "trace() do); start from its last point instead: trace(problem, "
            "branch.point(-1), ...)"
        )
    if options is None:
        options = ContinuationOptions(**info["options"])
    fixed = {k: float(branch[k][-1]) for k in branch.keys() if k not in branch.variables}
    clash = {k: (v, fixed[k]) for k, v in (params or {}).items() if k in fixed and v != fixed[k]}
    if clash:
        raise ProblemDefinitionError(
            f"params contradict the branch being continued (given, on the branch): {clash}"
        )
    own = int(info.get("direction", 1))
    if direction is not None and direction != own:
        raise ProblemDefinitionError(
            f"direction={direction!r}, but the branch being continued was traced with "
            f"direction={own} (its last tangent sets the way on)"
        )
    if scales is None and record.get("given_scales"):
        scales = {branch.variables[k]: v for k, v in record["given_scales"].items()}
    return options, params, scales, own


#: columns a branch's row may hold besides unknowns and parameters (``branch.point(i)``)
DERIVED_COLUMNS = frozenset({"n_unstable"})


def point_start(
    problem: ContinuationProblem, point: Mapping[str, float], params: Mapping[str, float] | None
) -> tuple[np.ndarray, dict[str, float]]:
    """The unknowns and the parameters of a start given as a point ``{name: value}`` (a row
    of a branch, ``branch.point(i)``): its parameters, unless ``params`` contradicts them."""
    unknowns, names = list(problem.unknowns), dict(problem.params)
    missing = [n for n in unknowns if n not in point]
    if missing:
        raise ProblemDefinitionError(
            f"u0 given as a point must hold every unknown {unknowns}; it lacks {missing}"
        )
    extra = [k for k in point if k not in unknowns and k not in names and k not in DERIVED_COLUMNS]
    if extra:
        raise ProblemDefinitionError(
            f"u0 names {extra}, neither unknowns {unknowns} nor parameters {sorted(names)}"
        )
    given = {k: float(point[k]) for k in names if k in point}
    clash = {k: (v, given[k]) for k, v in (params or {}).items() if k in given and v != given[k]}
    if clash:
        raise ProblemDefinitionError(f"params contradict the point u0 (given, in u0): {clash}")
    u = np.array([point[n] for n in unknowns], dtype=float)
    return u, {**names, **(params or {}), **given}


@dataclass
class Watch:
    """What a trace does between its steps when asked: save a checkpoint every ``every``
    steps (and at the end, or when interrupted) and show a progress bar (tqdm, on a
    terminal)."""

    checkpoint: Path | None
    every: int
    progress: bool

    @staticmethod
    def of(checkpoint: Any, every: Any, progress: Any) -> Watch | None:
        """The watch of a trace's arguments (checked), or None when there is nothing to do
        (no checkpoint, and no progress or no terminal)."""
        if type(every) is not int or every < 1:
            raise ProblemDefinitionError(f"checkpoint_every must be an integer >= 1, got {every!r}")
        if not isinstance(progress, bool):
            raise ProblemDefinitionError(f"progress must be True or False, got {progress!r}")
        show = progress and _is_terminal()
        if checkpoint is None:
            return Watch(None, every, True) if show else None
        path = Path(checkpoint)
        if not path.parent.is_dir():
            raise ProblemDefinitionError(
                f"checkpoint={str(path)!r}: its directory {str(path.parent)!r} does not exist"
            )
        return Watch(path, every, show)

    def run(self, tracer: Tracer, state: TracerState) -> TracerState:
        """:func:`run` with checkpoints and progress."""
        bar = _bar(tracer) if self.progress else None
        try:
            with np.errstate(all="ignore"):
                while state.status is None:
                    state = tracer._step(state)
                    if bar is not None:
                        at = f"{tracer.system.names[-1]}={state.last.z[-1]:.6g}"
                        bar.set_postfix_str(at, refresh=False)
                        bar.update(1)
                    if self.checkpoint is not None and state.steps % self.every == 0:
                        self.save(tracer, state)
        except BaseException:
            if self.checkpoint is not None:  # the last state completed, resumable
                self.save(tracer, state)
            raise
        finally:
            if bar is not None:
                bar.close()
        if self.checkpoint is not None:
            self.save(tracer, state)
        return state

    def save(self, tracer: Tracer, state: TracerState) -> None:
        assert self.checkpoint is not None
        tracer.result(state).save(self.checkpoint)
        logger.debug("checkpoint: %d points saved to %s", state.n_points, self.checkpoint)


def _is_terminal() -> bool:
    isatty = getattr(sys.stderr, "isatty", None)
    return bool(isatty is not None and isatty())


def _bar(tracer: Tracer) -> Any:
    """A tqdm bar of steps on standard error, shown once the trace lasts a second."""
    try:
        from tqdm import tqdm
    except ImportError:
        raise ImportError(
            "progress=True needs tqdm: pip install 'cusp[progress]' (or pip install tqdm)"
        ) from None
    free = tracer.system.names[-1]
    return tqdm(desc=f"trace {free}", unit=" steps", delay=1.0, leave=False, file=sys.stderr)


__all__ = ["Watch", "continued", "first_state", "point_start", "run", "stability_options", "trace"]
