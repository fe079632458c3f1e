"""Two-parameter continuation of folds (limit points) and the cusps on them.

The fold curve is traced by the ordinary tracer on the minimally augmented system
(Govaerts 2000; as in MatCont and BifurcationKit)

    G(u, p1, p2) = [F(u, p1, p2); g(u, p1, p2)],   [[M, b], [cᵀ, 0]] [v; g] = [0; 1],

where ``M`` is ``∂F/∂(u, p1)`` without the column of the variable that turns (``p1`` for an
ordinary fold, a monitored unknown for the fold of a snap-back): the curve system
:class:`~..systems._fold.FoldSystem`, ``n + 1`` equations in ``n + 2`` unknowns, whose
bordering vectors are replaced by the current null vectors after every accepted point.

On the curve:

- **cusp**: the normal-form coefficient ``a = ½⟨w, D²F[v, v]⟩`` changes sign; located by
  Newton on ``[F; g; a] = 0`` (n + 2 equations and unknowns), cross-checked by the parameter
  components of the fold curve's tangent (both vanish at a cusp);
- **second zero eigenvalue** (codimension 2, e.g. a limit point meeting a branch point): the
  determinant of the bordered matrix ``[[M, b], [cᵀ, 0]]`` changes sign (it is
  ``−cᵀ adj(M) b``, proportional to the product of the non-zero eigenvalues of ``M``);
- bounds, targets, events and monitored folds exactly as on ordinary branches.

:func:`fold_curve` gives the tracer the fold curve's own two test functions
(:class:`~..detection._cusp.CuspTest`, :class:`~..detection._cusp.Codim2Test`) besides the
generic ones.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import Any, NamedTuple

import numpy as np

from .._errors import ProblemDefinitionError
from .._options import KEEP, ContinuationOptions, Keep, StabilityOptions, with_overrides
from .._outcomes import Kind
from ..detection._cusp import Codim2Test, CuspTest
from ..detection._eigen import vector_field_mass
from ..detection._foldhopf import BogdanovTakensTest, ZeroHopfTest
from ..detection._tests import TestFunction
from ..problem._events import Event
from ..problem._problem import ContinuationProblem, as_problem
from ..results._branch import Branch, SpecialPoint
from ..stepping._state import TracerState
from ..stepping._trace import stability_options
from ..stepping._tracer import Tracer
from ..systems._fold import FoldSystem
from ._directions import trace_directions


def fold_curve(
    problem: ContinuationProblem,
    fold_point: SpecialPoint,
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
    """Continue a fold in two parameters.

    Parameters
    ----------
    problem : Problem or ContinuationProblem
        The problem the fold was found on.
    fold_point : SpecialPoint
        A special point of kind ``"fold"`` returned by :func:`trace` (a fold in the free
        parameter, or in a monitored unknown: the fold curve of a snap-back).
    free : (str, str)
        ``(p1, p2)``: the branch's free parameter and the second parameter.
    direction : {"both", 1, -1}, optional
        ``"both"`` (default: the two halves joined at the starting fold), ``+1`` or ``-1``
        (the sign of the initial change of ``p2``).
    bounds, targets, events, monitor, scales : optional
        As for :func:`~cusp.continuation.trace`; they apply to the fold curve (bounds may
        name any unknown or either parameter). An unknown whose value at the fold is far
        below its typical size on the branch (0, or 0 up to rounding) takes that size
        unless ``scales`` gives one.
    options : ContinuationOptions, optional
        Default: ``ContinuationOptions(detect_branch_points=False)``.
    throw : bool, optional
        If False, a failure returns the partial curve with its status instead of raising.
    stability : bool or StabilityOptions, optional
        For a problem declared a vector field (``Problem(..., mass=...)``) and a fold in
        the free parameter: also detect and locate ``"bogdanov_takens"`` and
        ``"zero_hopf"`` points (:mod:`~..detection._foldhopf`).

    Returns
    -------
    Branch
        The fold curve; its special points include ``"cusp"`` (details: the coefficient on
        each side, the tangent's parameter components, the fold branches that meet) and
        ``"codim2"`` (a second zero eigenvalue); with ``stability``, ``"bogdanov_takens"``
        and ``"zero_hopf"`` (``details["omega"]``). ``info["direction"]`` says which way(s)
        were traced and ``info["start_index"]`` where the starting fold is.

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
        ``fold_point`` not a fold, ``free`` not a pair of the problem's parameters, a bad
        ``direction``, or ``stability`` on a problem that is no vector field.
    ContinuationError
        A failure of the continuation (with ``throw=True``).
    """
    problem = as_problem(problem)
    start = _fold_setup(problem, fold_point, free)
    dynamic = _dynamic_tests(problem, start, stability_options(stability))
    options = with_overrides(options, FOLD_OPTIONS, locals())
    if direction not in ("both", 1, -1):
        raise ProblemDefinitionError(f"direction must be 'both', +1 or -1, got {direction!r}")
    system = FoldSystem.through(
        problem, start.p1, start.p2, start.k, start.params, options.state_weight, start.z0
    )
    curve: dict[str, Any] = dict(
        bounds=bounds, targets=targets, events=events, monitor=monitor, scales=scales,
        options=options, throw=throw,
    )  # fmt: skip
    label = "start (fold)"

    def begin(d: int) -> tuple[Tracer, TracerState]:
        tests = (CuspTest(), Codim2Test(), *dynamic())
        tracer = Tracer.for_system(system, direction=d, tests=tests, **curve)
        return tracer, tracer.init_at(start.z0, start_label=label, scales=fold_point.scales)

    return trace_directions(begin, direction, start_kind="fold", start_label=label)


def _dynamic_tests(
    problem: ContinuationProblem, start: _FoldStart, wanted: StabilityOptions | None
) -> Callable[[], tuple[TestFunction, ...]]:
    """A maker of the Bogdanov–Takens and zero-Hopf tests (none without ``wanted``),
    checked: the problem is a vector field, the fold one of the free parameter."""
    if wanted is None:
        return tuple
    mass = vector_field_mass(problem)
    if start.k != len(problem.unknowns):
        raise ProblemDefinitionError(
            "stability on a fold curve needs a fold of the free parameter; this fold is a "
            "turning point of a monitored unknown (a snap-back), whose matrix is not ∂R/∂u"
        )
    return lambda: (BogdanovTakensTest(mass), ZeroHopfTest(mass, wanted))


FOLD_OPTIONS = ContinuationOptions(detect_branch_points=False)
"""The default options of a fold curve: no branch points (its matrix is singular along it)."""


class _FoldStart(NamedTuple):
    """The start of a fold curve (:func:`_fold_setup`): the two parameters, the index of
    the variable that turns (in the unknowns and ``p1``), the parameter values at the fold
    and the fold's curve vector ``(u, p1, p2)``."""

    p1: str
    p2: str
    k: int
    params: dict[str, float]
    z0: np.ndarray


def _fold_setup(
    problem: ContinuationProblem, fold_point: SpecialPoint, free: tuple[str, str]
) -> _FoldStart:
    """Check the arguments of :func:`fold_curve` and the start they give."""
    if not isinstance(fold_point, SpecialPoint) or fold_point.kind != Kind.FOLD:
        raise ProblemDefinitionError(
            f"fold_point must be a SpecialPoint of kind 'fold' returned by trace, "
            f"got {fold_point!r}"
        )
    try:
        p1, p2 = free
    except (TypeError, ValueError):
        raise ProblemDefinitionError(
            f"free must be a pair (branch parameter, second parameter), got {free!r}"
        ) from None
    params = dict(problem.params)
    for name in (p1, p2):
        if name not in params:
            raise ProblemDefinitionError(
                f"{name!r} is not a parameter of the problem; parameters are {sorted(params)}"
            )
    if p1 == p2:
        raise ProblemDefinitionError(f"the two free parameters must differ, got {free!r}")
    for key in params:
        if key in fold_point.values:
            params[key] = float(fold_point.values[key])
    turns = fold_point.with_respect_to or p1
    names_y = list(problem.unknowns) + [p1]
    if turns not in names_y:
        raise ProblemDefinitionError(
            f"the fold is a turning point of {turns!r}, which is neither an unknown nor "
            f"{p1!r}: was it traced with free={turns!r}? Pass free=({turns!r}, second "
            "parameter)"
        )
    values = fold_point.values
    z0 = np.array([values[nm] for nm in problem.unknowns] + [values[p1], values[p2]], dtype=float)
    return _FoldStart(p1=p1, p2=p2, k=names_y.index(turns), params=params, z0=z0)


__all__ = ["fold_curve"]
