"""The first point of a curve: the start corrected, sized, checked and its test functions
evaluated (the work of :meth:`~._tracer.Tracer.init` and its variants)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from .._errors import NonFiniteResidualError, ProblemDefinitionError
from ..detection._tests import BoundTest, Record
from ..numerics._linalg import bordered, factor, max_abs
from ..numerics._scaling import settled_by_motion, typical_sizes
from ..systems._consistency import check_consistent
from ._start import correct_start, refuse_singular
from ._state import Point, TracerState
from ._step import wnorm

if TYPE_CHECKING:
    from ..systems._curve import CurveSystem


def start_state(
    tracer: Any,
    system: CurveSystem,
    z0: np.ndarray,
    tangent: Any,
    start_label: str,
    skip_bp: bool,
    inherited: Mapping[int, float] | None = None,
    from_guess: bool = False,
) -> TracerState:
    """The first state of ``tracer``'s curve (a :class:`~._tracer.Tracer`: its tests, options,
    step rules, given sizes and direction) from ``z0`` on ``system``: the start corrected
    (unless ``tangent`` is given: a branch switch), its typical sizes, its tangent, the
    checks of a start (supplied derivatives, a branch point hidden by differences, bounds)
    and the test functions' values there (see :meth:`Tracer.init`)."""
    o = tracer.options
    g0 = system.residual(z0)
    if not math.isfinite(max_abs(g0)):
        raise NonFiniteResidualError(
            f"the residual is not finite at the starting point {system.values(z0)}",
            values=system.values(z0),
        )
    bounds = [t for t in tracer.tests if isinstance(t, BoundTest)]
    given = tracer._scales
    # (a component at rounding level, −1e-32 for an exact 0, must not set the size the
    # start is corrected with: it is recognised by the Jacobian here too)
    provisional, settled = typical_sizes(
        z0,
        given,
        bounds,
        jacobian=lambda: system.jacobian(z0),
        inherited=inherited,
        guess=from_guess,
    )
    system = system.with_scales(provisional)
    details: dict[str, Any] = {}
    oriented_by = None
    if tangent is None:
        guess = z0
        start = correct_start(system, z0, g0, o, tracer._rules.e_last, tracer.direction)
        z0, t0, sdet, residual, iters, oriented_by = start
        # (zeros set exactly by start.snap_zeros take their size as zeros do)
        settled = settled and not np.any((z0 == 0.0) & (guess != 0.0))
        if oriented_by is not None:  # on a fold of the free parameter (module start)
            skip_bp = True
            details = {"fold_of": system.names[-1], "oriented_by": oriented_by}
    else:
        t0 = np.asarray(tangent, dtype=float)
        residual = float(np.max(np.abs(g0)))
        iters = 0
        sdet = None
    if not settled:  # components of size 0 take their size from the tangent
        system, t0, retangent = settled_by_motion(system, z0, t0, given, bounds, inherited)
        if retangent:  # (with the differences' steps of the new sizes)
            sdet = None
        sizes = system.scales
        if tangent is None and oriented_by is None and np.any(sizes < 1e-3 * provisional):
            # corrected in sizes far above the ones it has: again in its own, to the
            # accuracy its sizes demand (a guess of 1e-9 for a genuine 1e-9, sized 1)
            again = correct_start(
                system, z0, system.residual(z0), o, tracer._rules.e_last, tracer.direction
            )
            z0, t0, sdet, residual, more, oriented_by = again
            iters += more
    check_consistent(system, z0, "the starting point")
    if tangent is None and oriented_by is None:
        refuse_singular(system, z0)  # (a branch point a differenced Jacobian hides)
    t0 = t0 / wnorm(t0, system.weights)  # (a positive factor: sdet keeps its sign)
    system = system.refreshed(z0)
    if skip_bp:
        sdet = None
    elif sdet is None:
        sdet = factor(bordered(system.jacobian(z0), system.weights * t0)).sign_det()
    # starting on a special point, the test functions vanish there up to rounding: their
    # signs are taken after the first step instead
    tests = tuple(
        None if (skip_bp and t.kind in ("branch_point", "fold")) else t.value(system, z0, t0, sdet)
        for t in tracer.tests
    )
    record: Record = ("endpoint", start_label, None, "converged", None, details)
    first = Point(z0, t0, 0.0, iters, 0, residual, o.ds, (record,), None, 0.0)
    _check_start_in_bounds(tracer, z0)
    return TracerState(first, system, o.ds, tests, 0)


def _check_start_in_bounds(tracer: Any, z0: np.ndarray) -> None:
    for t in tracer.tests:
        if isinstance(t, BoundTest) and t.violated_by(z0):
            lo, hi = t.pair
            raise ProblemDefinitionError(
                f"the starting point has {t.wrt}={z0[t.k]:.10g}, outside "
                f"bounds[{t.wrt!r}] = ({lo:g}, {hi:g})"
            )


__all__ = ["start_state"]
