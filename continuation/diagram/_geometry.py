"""Where a point lies relative to a traced branch: the distance to its dense output (the
cubic Hermite arcs between its rows, :mod:`~..results._dense`) in a weighted metric, and the
branch's tangent there.

A diagram compares branches in one metric per pair: ``‖dz‖² = Σ b_i dz_i²/S_i²`` with ``b``
the branches' base arclength weights and ``S_i`` the larger of the two branches' typical
sizes of component ``i`` (each branch's dense output is within ``rtol`` of its curve in its
own metric, hence also in this one, whose sizes are no smaller).
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from .._errors import ProblemDefinitionError
from ..numerics._arc import HermiteArc, arc_length

SAMPLES = 17
"""Points of an arc sampled for its nearest point before the refinement."""

REFINE = 24
"""Golden-section iterations refining the nearest sample (to 1e-5 of the arc)."""


class Nearest(NamedTuple):
    """The point of a branch's dense output nearest to a given point: its ``distance``
    (weighted), the unit ``tangent`` there (weighted), and the ``segment`` and fraction
    ``theta`` of the arc it lies on."""

    distance: float
    tangent: np.ndarray
    segment: int
    theta: float


class Curve(NamedTuple):
    """A branch's rows ``Z``, unit tangents ``T`` (in its own metric ``w``), and the
    arclength of each segment's arc."""

    Z: np.ndarray
    T: np.ndarray
    w: np.ndarray
    lengths: np.ndarray


def base_and_scales(branch: Any) -> tuple[np.ndarray, np.ndarray]:
    """A branch's base arclength weights and typical sizes, in ``branch.variables`` order."""
    names = branch.variables
    scales = branch.info.get("scales")
    if scales is None:
        raise ProblemDefinitionError("this branch carries no typical sizes (info['scales'])")
    base = branch.info.get("base_weights")
    b = np.ones(len(names)) if base is None else np.asarray(base, dtype=float)
    return b, np.array([float(scales[v]) for v in names])


def pair_weights(first: Any, second: Any) -> np.ndarray:
    """The weights of the metric comparing two branches (see the module)."""
    if tuple(first.variables) != tuple(second.variables):
        raise ProblemDefinitionError(
            f"branches of different components cannot be compared: {first.variables} and "
            f"{second.variables}"
        )
    b, s1 = base_and_scales(first)
    _, s2 = base_and_scales(second)
    size = np.maximum(s1, s2)
    return b / (size * size)


def curve_of(branch: Any) -> Curve:
    """The rows, unit tangents and arc lengths of ``branch`` (its own metric)."""
    b, sizes = base_and_scales(branch)
    w = b / (sizes * sizes)
    Z = np.column_stack([np.asarray(branch[v], dtype=float) for v in branch.variables])
    T = np.array(branch.tangents, dtype=float)
    norms = np.sqrt(np.einsum("ij,ij->i", T * w, T))
    T = T / np.where(norms > 0, norms, 1.0)[:, None]
    lengths = np.array([arc_length(Z[i + 1] - Z[i], T[i], T[i + 1], w) for i in range(len(Z) - 1)])
    return Curve(Z=Z, T=T, w=w, lengths=lengths)


def arc(curve: Curve, i: int) -> HermiteArc:
    """The dense output's arc between rows ``i`` and ``i + 1``."""
    return HermiteArc(curve.Z[i], curve.T[i], curve.Z[i + 1], curve.T[i + 1], curve.lengths[i])


def nearest(curve: Curve, z: np.ndarray, w: np.ndarray, *, reach: float) -> Nearest | None:
    """The point of ``curve``'s arcs nearest to ``z`` in the metric ``w``, among the arcs that
    may come within ``reach`` of it (an arc lies within its chord of its ends, as its turn is
    held below 90°); None if none may."""
    Z = curve.Z
    d = Z - z
    node = np.sqrt(np.einsum("ij,ij->i", d * w, d))
    if len(Z) == 1:
        return Nearest(float(node[0]), unit(curve.T[0], w), 0, 0.0) if node[0] <= reach else None
    dz = np.diff(Z, axis=0)
    chord = np.sqrt(np.einsum("ij,ij->i", dz * w, dz))
    near = np.minimum(node[:-1], node[1:]) <= reach + chord
    best: Nearest | None = None
    for i in np.flatnonzero(near).tolist():
        found = _nearest_on_arc(arc(curve, i), z, w)
        if best is None or found[0] < best.distance:
            best = Nearest(found[0], found[1], i, found[2])
    return best


def _nearest_on_arc(a: HermiteArc, z: np.ndarray, w: np.ndarray) -> tuple[float, np.ndarray, float]:
    """(distance, unit tangent, θ) of the point of arc ``a`` nearest to ``z``: the best of
    :data:`SAMPLES` points, refined by golden sections between its neighbours."""
    thetas = np.linspace(0.0, 1.0, SAMPLES)
    pts = a.sample(thetas) - z
    dist = np.einsum("ij,ij->i", pts * w, pts)
    k = int(np.argmin(dist))
    lo, hi = thetas[max(k - 1, 0)], thetas[min(k + 1, SAMPLES - 1)]
    g = 0.5 * (np.sqrt(5.0) - 1.0)

    def f(th: float) -> float:
        p = a.at(th) - z
        return float(p.dot(w * p))

    for _ in range(REFINE):
        x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
        if f(x1) <= f(x2):
            hi = x2
        else:
            lo = x1
    theta = 0.5 * (lo + hi)
    best = min((f(theta), theta), (float(dist[k]), float(thetas[k])))
    return float(np.sqrt(best[0])), unit(a.derivative(best[1]), w), best[1]


def unit(t: np.ndarray, w: np.ndarray) -> np.ndarray:
    """``t`` normalised in the metric ``w``."""
    n = float(np.sqrt(t.dot(w * t)))
    return t / n if n > 0 else t


def cosine(a: np.ndarray, b: np.ndarray, w: np.ndarray) -> float:
    """|cos| of the angle between ``a`` and ``b`` in the metric ``w``."""
    return abs(float(unit(a, w).dot(w * unit(b, w))))


def samples(curve: Curve, count: int) -> np.ndarray:
    """``count`` points of the dense output at the middle of arcs spread over the branch
    (points between rows, not rows), or its rows if it has a single one."""
    n = len(curve.Z) - 1
    if n < 1:
        return curve.Z.copy()
    picks = sorted(set(np.round(np.linspace(0, n - 1, min(count, n))).astype(int).tolist()))
    return np.array([arc(curve, i).midpoint() for i in picks])


__all__ = [
    "Curve",
    "Nearest",
    "arc",
    "base_and_scales",
    "cosine",
    "curve_of",
    "nearest",
    "pair_weights",
    "samples",
    "unit",
]
