"""The tracer's state and its assembly into a :class:`~..results._branch.Branch`.

The state is an immutable record replaced at every step. The branch so far is a linked list
of immutable points (each holds the one before), so a step costs O(1) whatever the length
of the branch, and an old state stays valid: stepping from it again gives the same points.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from ..results._branch import Branch, SpecialPoint

if TYPE_CHECKING:
    from ..detection._tests import Record
    from ..systems._curve import CurveSystem


class Point(NamedTuple):
    """One row of a branch, linked to the row before it (``prev``)."""

    z: np.ndarray
    """The curve vector (unknowns and free parameters)."""
    t: np.ndarray
    """Unit tangent (weighted norm), oriented along the direction of travel."""
    s: float
    """Pseudo-arclength from the start."""
    newton: int
    """Newton iterations of the corrector (or of the locating method)."""
    rejected: int
    """Step tries rejected before this point was accepted."""
    residual: float
    """Max-norm of the residual at ``z``."""
    ds: float
    """The step size that produced the point (0 for a point located inside a step)."""
    special: tuple[Record, ...] | None
    """Special-point records of this row."""
    prev: Point | None
    """The row before (None at the start)."""
    interp: float
    """The distance from the cubic Hermite arc of the step that reached this point to the
    curve (0 at the start; a point located inside a step carries that step's)."""


class TracerState(NamedTuple):
    """Immutable solver state: the last point (with the branch behind it), the curve system
    valid beyond it (augmented systems carry their bordering vectors here), the next step
    size, the test-function values at the last point, the step count and, once finished,
    the status and message."""

    last: Point
    system: CurveSystem
    ds: float
    tests: tuple
    steps: int
    status: str | None = None
    message: str = ""
    n_points: int = 1
    stalled: int = 0  # consecutive steps taken with ds near ds_min


def _rows(state: TracerState) -> list[Point]:
    points = []
    p: Point | None = state.last
    while p is not None:
        points.append(p)
        p = p.prev
    points.reverse()
    return points


def assemble_branch(state: TracerState, info: dict[str, Any]) -> Branch:
    """The :class:`~..results._branch.Branch` of a state: column arrays (the traced components, the
    fixed parameters as constant columns), tangents, special points and per-point stats."""
    points = _rows(state)
    system = state.system
    n_pts = len(points)
    zs, ts, ss, newton, rejected, residual, dss = list(zip(*points))[:7]  # the fields
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
    status = state.status or "running"
    if state.status is None:
        message = "the branch is still being traced (result of an unfinished state)"
    else:
        message = state.message
    if not any(sp.kind == "endpoint" for sp in specials if sp.index == n_pts - 1):
        specials.append(
            SpecialPoint(
                kind="endpoint",
                index=n_pts - 1,
                values=values_at(n_pts - 1),
                tangent=T[-1].copy(),
                status="converged",
                label=status,
                s=float(ss[-1]),
                scales=dict(scales),
            )
        )
    stats = {
        "newton_iterations": np.array(newton),
        "rejected_steps": np.array(rejected),
        "residual_norm": np.array(residual),
        "ds": np.array(dss),
        "interpolation_error": np.array([p.interp for p in points]),
    }
    return Branch(
        columns,
        variables=tuple(names),
        s=np.array(ss),
        tangents=T,
        special_points=specials,
        status=status,
        message=message,
        stats=stats,
        info={
            "steps": state.steps,
            **info,
            "scales": dict(scales),
            "base_weights": system.base_weights.tolist(),
        },
    )


def _special_points(points, T, ss, values_at, scales) -> list[SpecialPoint]:
    specials = []
    for i, pt in enumerate(points):
        for kind, label, wrt, status, interval, details in pt.special or ():
            specials.append(
                SpecialPoint(
                    kind=kind,
                    index=i,
                    values=values_at(i),
                    tangent=T[i].copy(),
                    status=status,
                    label=label,
                    with_respect_to=wrt,
                    s=float(ss[i]),
                    interval=interval,
                    details=dict(details),  # the state's record stays as it was
                    scales=dict(scales),
                )
            )
    return specials


__all__ = ["Point", "TracerState", "assemble_branch"]
