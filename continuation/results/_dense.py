"""Dense output of a traced branch: the solver's own interpolant between its points.

Between two consecutive rows of a :class:`~._branch.Branch` the curve is the cubic Hermite
arc through both points with their unit tangents, parametrised by the fraction θ ∈ [0, 1]
of the segment's arclength ``L = c·(α/2)/sin(α/2)`` (``c`` the chord, ``α`` the angle
between the tangents, both in the branch's weighted norm: exact on a circle):

    z(θ) = h00(θ)·z0 + h10(θ)·L·t0 + h01(θ)·z1 + h11(θ)·L·t1.

The tracer measures, at every step, how far this arc's midpoint lies from the curve (one
Newton update from it, :meth:`~..numerics._arc.HermiteArc.error`) and rejects a step whose
arc is more than ``rtol/2`` off (:func:`~..stepping._control.interpolation_factor`), so that
evaluating the arcs costs no Newton at all and is within ``rtol`` of the curve (weighted
norm, relative to the typical sizes). A segment whose arc could not be brought within
``rtol`` (a kink passed at ``ds_min``, a corner step) is refused with an
:class:`~.._errors.AccuracyError` rather than evaluated.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .._errors import AccuracyError, ProblemDefinitionError
from ..numerics._arc import HermiteArc, arc_length


def arrays(branch: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, float]:
    """The branch's points, unit tangents, weights, per-segment errors and rtol, or an
    AccuracyError saying why it has no interpolant."""
    info = branch.info
    errors = branch.stats.get("interpolation_error")
    rtol = info.get("rtol")
    scales = info.get("scales")
    if errors is None or rtol is None or scales is None:
        raise AccuracyError(
            "this branch carries no interpolant (it was not traced by the tracer, or was "
            "assembled from pieces): use points_at (Newton) for points between its rows"
        )
    names = branch.variables
    Z = np.column_stack([branch[v] for v in names])
    sc = np.array([scales[v] for v in names], dtype=float)
    base = info.get("base_weights")
    w = (np.ones(len(names)) if base is None else np.asarray(base, dtype=float)) / (sc * sc)
    T = np.array(branch.tangents, dtype=float)
    norms = np.sqrt(np.einsum("ij,ij->i", T * w, T))
    T = T / np.where(norms > 0, norms, 1.0)[:, None]
    return Z, T, w, np.asarray(errors, dtype=float), float(rtol)


def interpolate(branch: Any, s: ArrayLike) -> dict[str, np.ndarray]:
    """The branch's interpolant at pseudo-arclengths ``s`` (see the module)."""
    Z, T, w, errors, rtol = arrays(branch)
    sv = np.atleast_1d(np.asarray(s, dtype=float))
    S = branch.s
    if sv.size and not (np.all(np.isfinite(sv)) and sv.min() >= S[0] and sv.max() <= S[-1]):
        raise ProblemDefinitionError(
            f"s must lie within the branch's arclength [{S[0]!r}, {S[-1]!r}], got "
            f"[{float(np.nanmin(sv))!r}, {float(np.nanmax(sv))!r}]"
        )
    out = np.empty((sv.size, Z.shape[1]))
    seg = np.clip(np.searchsorted(S, sv, side="right") - 1, 0, max(S.size - 2, 0))
    for i in np.unique(seg).tolist():
        pick = seg == i
        if S.size == 1 or S[i + 1] == S[i]:
            out[pick] = Z[min(i + 1, S.size - 1)]
            continue
        check_segment(branch, i, errors[i + 1], rtol)
        theta = (sv[pick] - S[i]) / (S[i + 1] - S[i])
        out[pick] = segment(Z, T, w, i).sample(theta)
    return _columns(branch, out)


def interpolate_at(branch: Any, name: str, values: ArrayLike) -> dict[str, np.ndarray]:
    """The branch's interpolant where component ``name`` takes each of ``values`` (the first
    crossing in branch order), by solving the segment's cubic for θ (no Newton on the
    problem)."""
    if name not in branch.variables:
        raise ProblemDefinitionError(
            f"name {name!r} is not traced on this branch; it must be one of "
            f"{list(branch.variables)}"
        )
    Z, T, w, errors, rtol = arrays(branch)
    k = branch.variables.index(name)
    x = Z[:, k]
    vals = np.atleast_1d(np.asarray(values, dtype=float))
    if not np.all(np.isfinite(vals)):
        raise ProblemDefinitionError(f"values must be finite, got {vals!r}")
    out = np.empty((vals.size, Z.shape[1]))
    for j, v in enumerate(vals.tolist()):
        i = crossing_segment(x, name, v)
        check_segment(branch, i, errors[i + 1], rtol)
        arc = segment(Z, T, w, i)
        out[j] = arc.sample(np.array([arc.root(k, v)]))[0]
        out[j, k] = v
    return _columns(branch, out)


def crossing_segment(x: np.ndarray, name: str, v: float) -> int:
    """The first segment (row index of its start) across which the column ``x`` of
    component ``name`` takes the value ``v``; a ProblemDefinitionError if none does."""
    d = x - v
    hits = np.flatnonzero(d[:-1] * d[1:] <= 0.0)
    if hits.size == 0:
        raise ProblemDefinitionError(
            f"{name} = {v!r} is not reached on this branch ({name} covers "
            f"[{float(x.min())!r}, {float(x.max())!r}])"
        )
    return int(hits[0])


def segment(Z: np.ndarray, T: np.ndarray, w: np.ndarray, i: int) -> HermiteArc:
    """The arc between rows ``i`` and ``i + 1`` (unit tangents, the circular arc's length)."""
    length = arc_length(Z[i + 1] - Z[i], T[i], T[i + 1], w)
    return HermiteArc(Z[i], T[i], Z[i + 1], T[i + 1], length)


def check_segment(branch: Any, i: int, error: float, rtol: float) -> None:
    """Refuse segment ``i`` unless its arc's measured ``error`` is within ``rtol`` (the step
    accepts half of it; a point located inside a step splits it, each part with the step's
    error)."""
    if not error <= rtol:
        raise AccuracyError(
            f"between rows {i} and {i + 1} of this branch (s in [{branch.s[i]:.6g}, "
            f"{branch.s[i + 1]:.6g}]) the interpolant is {error:.3g} off the curve, above "
            f"rtol = {rtol:g} (a kink passed at ds_min, or a corner): use points_at (Newton) "
            "there"
        )


def _columns(branch: Any, out: np.ndarray) -> dict[str, np.ndarray]:
    cols = {v: out[:, j].copy() for j, v in enumerate(branch.variables)}
    n = out.shape[0]
    for key in branch.keys():
        column = branch[key]
        # the fixed parameters; a column that varies but is not traced (n_unstable) has no
        # value between rows: left out rather than given row 0's
        if key not in cols and np.all(column == column[0]):
            cols[key] = np.full(n, float(column[0]))
    return cols


__all__ = [
    "arrays",
    "check_segment",
    "crossing_segment",
    "interpolate",
    "interpolate_at",
    "segment",
]
