"""Two-parameter continuation of folds (limit points) and the cusps on them.

The fold curve is traced by the ordinary tracer on the minimally augmented system
(Govaerts 2000; as in MatCont and BifurcationKit)

    G(u, p1, p2) = [F(u, p1, p2); g(u, p1, p2)],   [[M, b], [cᵀ, 0]] [v; g] = [0; 1],

where ``M`` is ``∂F/∂(u, p1)`` without the column of the variable that turns (``p1`` for an
ordinary fold, a monitored unknown for the fold of a snap-back), so the system has ``n + 1``
equations in ``n + 2`` unknowns. The bordering vectors ``b, c`` are replaced by the current
left/right null vectors after every accepted point (a new, immutable :class:`FoldSystem` each
time, carried by the tracer's state). ``∇g = −wᵀ(∂M/∂z)v`` is a directional difference of the
Jacobian.

On the curve:

- **cusp**: the normal-form coefficient ``a = ½⟨w, D²F[v, v]⟩`` changes sign; located by
  Newton on ``[F; g; a] = 0`` (n + 2 equations and unknowns), cross-checked by the parameter
  components of the fold curve's tangent (both vanish at a cusp);
- **second zero eigenvalue** (codimension 2, e.g. a limit point meeting a branch point): the
  determinant of the bordered matrix ``[[M, b], [cᵀ, 0]]`` changes sign (it is
  ``−cᵀ adj(M) b``, proportional to the product of the non-zero eigenvalues of ``M``);
- bounds, targets, events and monitored folds exactly as on ordinary branches.

The fold-curve system brings its own two test functions (:class:`CuspTest`,
:class:`Codim2Test`); the tracer knows nothing of them.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from .._errors import ProblemDefinitionError
from .._options import ContinuationOptions
from ..detection._cusp import Codim2Test, CuspTest
from ..problem._problem import as_problem
from ..results._branch import Branch, SpecialPoint
from ..stepping._state import TracerState
from ..stepping._tracer import Tracer
from ..systems._fold import FoldSystem
from ._directions import trace_directions


def fold_curve(
    problem,
    fold_point: SpecialPoint,
    *,
    free: tuple[str, str],
    direction: str | int = "both",
    bounds: Mapping[str, tuple[float, float]] | None = None,
    targets: Mapping[str, Sequence[float]] | None = None,
    events: Sequence = (),
    monitor: Sequence[str] = (),
    scales: Mapping[str, float] | None = None,
    options: ContinuationOptions | None = None,
    throw: bool = True,
    **overrides: Any,
) -> Branch:
    """Continue a fold in two parameters.

    Parameters
    ----------
    problem:
        the problem the fold was found on.
    fold_point:
        a :class:`SpecialPoint` of kind ``"fold"`` returned by :func:`trace` (a fold in the
        free parameter, or in a monitored unknown: the fold curve of a snap-back).
    free:
        ``(p1, p2)``: the branch's free parameter and the second parameter.

    Other parameters
    ----------------
    direction:
        ``"both"`` (default: the two halves joined at the starting fold), ``+1`` or ``-1``
        (the sign of the initial change of ``p2``).
    bounds, targets, events, monitor, scales, options, throw:
        as for :func:`trace`; they apply to the fold curve (bounds may name any unknown or
        either parameter). An unknown whose value at the fold is far below its typical size
        on the branch (0, or 0 up to rounding) takes that size unless ``scales`` gives one.

    The result is a :class:`Branch` whose special points include ``"cusp"`` (details: the
    coefficient on each side, the tangent's parameter components, the fold branches that
    meet) and ``"codim2"`` (a second zero eigenvalue). ``info["direction"]`` says which way(s)
    were traced and ``info["start_index"]`` where the starting fold is.
    """
    problem = as_problem(problem)
    p1, p2, k, params = _fold_setup(problem, fold_point, free)
    options = options or ContinuationOptions(detect_branch_points=False)
    if overrides:
        options = options.replace(**overrides)
    if direction not in ("both", 1, -1):
        raise ProblemDefinitionError(f"direction must be 'both', +1 or -1, got {direction!r}")

    z0 = np.array(
        [fold_point.values[nm] for nm in problem.unknowns]
        + [fold_point.values[p1], fold_point.values[p2]],
        dtype=float,
    )
    system = FoldSystem.through(problem, p1, p2, k, params, options.state_weight, z0)

    def begin(d: int) -> tuple[Tracer, TracerState]:
        tracer = Tracer.for_system(
            system,
            options=options,
            bounds=bounds,
            targets=targets,
            events=events,
            monitor=monitor,
            scales=scales,
            direction=d,
            throw=throw,
            tests=(CuspTest(), Codim2Test()),
        )
        return tracer, tracer.init_at(z0, start_label="start (fold)", sizes=fold_point.scales)

    return trace_directions(begin, direction, start_kind="fold", start_label="start (fold)")


def _fold_setup(
    problem: Any, fold_point: SpecialPoint, free: tuple[str, str]
) -> tuple[str, str, int, dict[str, float]]:
    """Check the arguments of :func:`fold_curve`: the two parameters, the index of the
    variable that turns, and the parameter values at the fold."""
    if not isinstance(fold_point, SpecialPoint) or fold_point.kind != "fold":
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
    wrt = fold_point.with_respect_to or p1
    names_y = list(problem.unknowns) + [p1]
    if wrt not in names_y:
        raise ProblemDefinitionError(
            f"the fold is a turning point of {wrt!r}, which is neither an unknown nor {p1!r}: "
            f"was it traced with free={wrt!r}? Pass free=({wrt!r}, second parameter)"
        )
    return p1, p2, names_y.index(wrt), params


__all__ = ["Codim2Test", "CuspTest", "FoldSystem", "fold_curve"]
