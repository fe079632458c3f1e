"""The first point of a curve: the start corrected, its scales (typical sizes) taken, its
tangent, the checks of a start, and its test functions' values (the work of
:meth:`~._tracer.Tracer.init` and its variants)."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from .._errors import NonFiniteResidualError, ProblemDefinitionError, SingularMatrixError
from .._outcomes import Kind, PointStatus
from ..detection._tests import BoundTest, Record, TestFunction
from ..numerics._linalg import bordered, factor, max_abs, unit_last
from ..numerics._scaling import start_scales
from ..systems._consistency import check_consistent
from ..systems._curve import CurveSystem
from ._start import Start, correct_start, refuse_singular
from ._state import Point, TracerState
from ._step import wnorm

if TYPE_CHECKING:
    from .._options import ContinuationOptions


@dataclass(slots=True)
class Beginning:
    """What a curve's start needs of the tracer: its ``options``, test functions
    (``tests``), the user's scales by component index (``given``) and the ``direction``
    (+1 or −1) of the last component's change."""

    options: ContinuationOptions
    tests: tuple[TestFunction, ...]
    given: Mapping[int, float]
    direction: int


@dataclass(slots=True)
class StartAt:
    """Where a curve starts: the point ``z0`` on ``system``, its ``tangent`` if known (a
    branch switch: then not corrected), the start's ``label``, whether the branch-point
    test is skipped there (``skip_bp``: starting on a special point), the scales of a curve
    the start lies on (``inherited``, by component index) and whether ``z0`` is a guess."""

    system: CurveSystem
    z0: np.ndarray
    tangent: np.ndarray | None = None
    label: str = "start"
    skip_bp: bool = False
    inherited: Mapping[int, float] | None = None
    from_guess: bool = False


def start_state(begin: Beginning, at: StartAt) -> TracerState:
    """The first state of a curve from ``at.z0`` on ``at.system``: the start corrected
    (unless the tangent is given: a branch switch), its scales, its tangent, the checks of a
    start (supplied derivatives, a branch point hidden by differences, bounds) and the test
    functions' values there (see :meth:`~._tracer.Tracer.init`)."""
    system, z0 = at.system, at.z0
    g0 = system.residual(z0)
    if not math.isfinite(max_abs(g0)):
        raise NonFiniteResidualError(
            f"the residual is not finite at the starting point {system.values(z0)}",
            values=system.values(z0),
        )
    system = system.checked(z0)  # (whether the float path can be taken)
    bounds = [(t.k, t.pair) for t in begin.tests if isinstance(t, BoundTest)]
    # (a component at rounding level, −1e-32 for an exact 0, must not set the scale the
    # start is corrected with: it is recognised by the Jacobian here too)
    provisional = start_scales(
        z0,
        begin.given,
        bounds,
        jacobian=lambda: system.jacobian(z0),
        inherited=at.inherited,
        guess=at.from_guess,
    )
    system = system.with_scales(provisional.scales)
    start = _corrected(begin, at, system, g0)
    on_fold = start.fold_oriented_by  # (on a fold of the free parameter: module _start)
    if not provisional.settled or np.any((start.z == 0.0) & (z0 != 0.0)):
        system, start = _scaled_by_motion(begin, at, system, start, bounds, provisional.scales)
    return _first_state(begin, at, system, start, on_fold)


def _corrected(begin: Beginning, at: StartAt, system: CurveSystem, g0: np.ndarray) -> Start:
    """The start corrected (:func:`~._start.correct_start`), or taken as it is with its
    given tangent (a branch switch)."""
    if at.tangent is None:
        return correct_start(system, at.z0, g0, begin.options, _e_last(at.z0), begin.direction)
    return Start(
        z=at.z0,
        t=np.asarray(at.tangent, dtype=float),
        sdet=None,
        residual_norm=float(np.max(np.abs(g0))),
        iterations=0,
        fold_oriented_by=None,
    )


def _scaled_by_motion(
    begin: Beginning,
    at: StartAt,
    system: CurveSystem,
    start: Start,
    bounds: Sequence[tuple[int, tuple[float, float]]],
    provisional: np.ndarray,
) -> tuple[CurveSystem, Start]:
    """Components of scale 0 take their scale from the tangent (:func:`scales_by_motion`;
    zeros set exactly by :func:`~._start.snap_zeros` take theirs as zeros do); a start
    corrected in scales far above the ones it has is corrected again in its own, to the
    accuracy its scales demand (a guess of 1e-9 for a genuine 1e-9, sized 1)."""
    system, t0, retangent = scales_by_motion(
        system, start.z, start.t, begin.given, bounds, at.inherited
    )
    sdet = None if retangent else start.sdet  # (with the differences' steps of the new scales)
    moved = Start(
        z=start.z,
        t=t0,
        sdet=sdet,
        residual_norm=start.residual_norm,
        iterations=start.iterations,
        fold_oriented_by=start.fold_oriented_by,
    )
    corrected_here = at.tangent is None and start.fold_oriented_by is None
    if not corrected_here or not np.any(system.scales < 1e-3 * provisional):
        return system, moved
    again = correct_start(
        system, moved.z, system.residual(moved.z), begin.options, _e_last(moved.z), begin.direction
    )
    more = Start(
        z=again.z,
        t=again.t,
        sdet=again.sdet,
        residual_norm=again.residual_norm,
        iterations=start.iterations + again.iterations,
        fold_oriented_by=again.fold_oriented_by,
    )
    return system, more


def _first_state(
    begin: Beginning, at: StartAt, system: CurveSystem, start: Start, on_fold: str | None
) -> TracerState:
    """The checks of a corrected start and the state at it: the test functions' values
    there (None, for the tests that vanish at a special point the curve starts on).
    ``on_fold``: the component that oriented the tangent where the first correction found
    the start on a fold of the free parameter (else None)."""
    z0 = start.z
    check_consistent(system, z0, "the starting point")
    if at.tangent is None and start.fold_oriented_by is None:
        refuse_singular(system, z0)  # (a branch point a differenced Jacobian hides)
    t0 = start.t / wnorm(start.t, system.weights)  # (a positive factor: sdet keeps its sign)
    system = system.refreshed(z0)
    skip_bp = at.skip_bp or on_fold is not None
    sdet = start.sdet
    if skip_bp:
        sdet = None
    elif sdet is None:
        sdet = factor(bordered(system.jacobian(z0), system.weights * t0)).sign_det()
    # starting on a special point, the test functions vanish there up to rounding: their
    # signs are taken after the first step instead
    values = tuple(
        None
        if (skip_bp and t.kind in (Kind.BRANCH_POINT, Kind.FOLD))
        else t.value(system, z0, t0, sdet)
        for t in begin.tests
    )
    details = {}
    if on_fold is not None:
        details = {"fold_of": system.names[-1], "oriented_by": on_fold}
    record = Record(
        kind=Kind.ENDPOINT,
        label=at.label,
        with_respect_to=None,
        status=PointStatus.CONVERGED,
        interval=None,
        details=details,
    )
    o = begin.options
    first = Point.of(
        z=z0,
        t=t0,
        s=0.0,
        iterations=start.iterations,
        rejected=0,
        residual_norm=start.residual_norm,
        ds=o.ds,
        special=(record,),
        prev=None,
        interpolation_error=0.0,
    )
    _check_start_in_bounds(begin.tests, z0)
    return TracerState.of(last=first, system=system, ds=o.ds, test_values=values, steps=0)


def _e_last(z: np.ndarray) -> np.ndarray:
    return unit_last(z.size)


def _check_start_in_bounds(tests: Sequence[TestFunction], z0: np.ndarray) -> None:
    for t in tests:
        if isinstance(t, BoundTest) and t.violated_by(z0):
            lo, hi = t.pair
            raise ProblemDefinitionError(
                f"the starting point has {t.with_respect_to}={z0[t.k]:.10g}, outside "
                f"bounds[{t.with_respect_to!r}] = ({lo:g}, {hi:g})"
            )


def scales_by_motion(
    system: CurveSystem,
    z0: np.ndarray,
    t0: np.ndarray,
    given: Mapping[int, float],
    bounds: Sequence[tuple[int, tuple[float, float]]],
    inherited: Mapping[int, float] | None,
) -> tuple[CurveSystem, np.ndarray, bool]:
    """The system with the scales of the start ``z0``
    (:func:`~..numerics._scaling.start_scales` with the start tangent ``t0``), the tangent,
    and whether the tangent was recomputed.

    A component of unknown scale is differenced with steps relative to its provisional
    scale 1 until its scale is known; for a concentration of 1e-9 that step is a million
    times its value and the differenced Jacobian, hence the tangent that sizes it, is
    garbage. With a differenced Jacobian the tangent is therefore recomputed with the steps
    of the new scales (``[∂G/∂z; (W t0)ᵀ] t = e``, the same orientation) and the scales
    taken again, until none changes by more than a factor 2 (at most three rounds)."""
    provisional = system.scales
    for rounds in range(4):
        scales = start_scales(
            z0, given, bounds, t0, lambda s=system: s.jacobian(z0), inherited=inherited
        ).scales
        close = bool(np.all(np.abs(np.log2(scales / system.scales)) <= 1.0))
        if not np.array_equal(scales, system.scales):
            system = system.with_scales(scales)
        if close or system.exact_jacobian or rounds == 3:
            break
        try:
            t = factor(bordered(system.jacobian(z0), system.weights * t0)).solve(unit_last(z0.size))
        except SingularMatrixError:
            break
        if not np.all(np.isfinite(t)):
            break
        t0 = t
    return system, t0, not np.array_equal(system.scales, provisional) and rounds > 0


def as_array(x: ArrayLike | None) -> np.ndarray | None:
    """``x`` as a float array, None kept."""
    return None if x is None else np.asarray(x, dtype=float)


def by_index(system: CurveSystem, scales: Mapping[str, float] | None) -> dict[int, float]:
    """Scales by name (of a curve a start lies on) as ``{component index: scale}``, for the
    components of ``system`` they name."""
    out = {}
    for name, size in (scales or {}).items():
        k = system.index(name)
        if k is not None and math.isfinite(size) and size > 0.0:
            out[k] = float(size)
    return out


__all__ = ["Beginning", "StartAt", "as_array", "by_index", "scales_by_motion", "start_state"]
