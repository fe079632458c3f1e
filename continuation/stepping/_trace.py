"""The entry point of a branch: :func:`trace` (a :class:`~._tracer.Tracer` run to the end)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from numpy.typing import ArrayLike

from .._errors import ProblemDefinitionError
from .._options import KEEP, ContinuationOptions, Keep, StabilityOptions, with_overrides
from ..detection._eigen import vector_field_mass
from ..problem._events import Event
from ..problem._problem import ContinuationProblem
from ..results._branch import Branch, SpecialPoint
from ..results._stability import with_stability
from ._state import TracerState
from ._tracer import DEFAULT_OPTIONS, Tracer


def trace(
    problem: ContinuationProblem,
    u0: ArrayLike | SpecialPoint,
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
    stability: bool | StabilityOptions = False,
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
    u0 : array_like, shape (n,), or SpecialPoint
        A guess of the unknowns at the problem's parameter values (corrected by Newton), or
        a special point of a branch: a ``"branch_point"`` starts on the other branch through
        it (``direction`` choosing the half-branch).
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
        The sign of the free parameter's initial change.
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
    tracer = Tracer(
        problem,
        free=free,
        params=params,
        bounds=bounds,
        targets=targets,
        events=events,
        monitor=monitor,
        scales=scales,
        direction=direction,
        options=with_overrides(options, DEFAULT_OPTIONS, locals()),
        throw=throw,
    )
    branch = tracer.result(run(tracer, tracer.init(u0)))
    if wanted is None:
        return branch
    return with_stability(tracer.system.problem, branch, wanted)


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


def run(tracer: Tracer, state: TracerState) -> TracerState:
    """Step ``tracer`` from ``state`` until the curve ends.

    numpy's floating-point warnings are silenced once for all the steps (see
    :meth:`Tracer.step`).
    """
    with np.errstate(all="ignore"):
        while state.status is None:
            state = tracer._step(state)
    return state


__all__ = ["run", "stability_options", "trace"]
