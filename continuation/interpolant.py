"""The interpolant of a step: the cubic Hermite arc between two points of a curve with their
unit tangents, and the measure of how far it lies from the curve, which the step control
holds within ``rtol`` (:class:`~.options.ContinuationOptions`) and the branch's dense output
(:mod:`~.dense`) relies on."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from .system import CurveSystem


def arc_length(dz: np.ndarray, t0: np.ndarray, t1: np.ndarray, w: np.ndarray) -> float:
    """The arclength of the circular arc with chord ``dz`` and unit end tangents ``t0``,
    ``t1`` (weighted norm ``w``): ``c·(α/2)/sin(α/2)``."""
    c = math.sqrt(float(dz.dot(w * dz)))
    cos_a = max(-1.0, min(1.0, float(t0.dot(w * t1))))
    half = 0.5 * math.acos(cos_a)
    return c if half < 1e-8 else c * half / math.sin(half)


def hermite(z0, t0, z1, t1, length: float, theta: np.ndarray) -> np.ndarray:
    """Points of the cubic Hermite arc at fractions ``theta`` (rows)."""
    th = theta[:, None]
    th2 = th * th
    th3 = th2 * th
    return (
        (2 * th3 - 3 * th2 + 1) * z0
        + (th3 - 2 * th2 + th) * (length * t0)
        + (3 * th2 - 2 * th3) * z1
        + (th3 - th2) * (length * t1)
    )


def interpolation_error(
    system: CurveSystem,
    z: np.ndarray,
    t: np.ndarray,
    z1: np.ndarray,
    t1: np.ndarray,
    h: float,
    lu: Any,
) -> float:
    """The distance from the step's interpolant to the curve: the midpoint of the cubic
    Hermite arc from ``z`` (unit tangent ``t``) to ``z1`` (``t1``), the one the branch's
    dense output evaluates (:mod:`~.dense`: tangents scaled by the arc's length ``L``),
    ``z_m = (z + z1)/2 + L/8·(t − t1)``, is projected onto the curve by one Newton update
    with the step's last factorization ``lu`` (of ``[∂G/∂z; row]`` near ``z1``):
    ``|lu⁻¹·[G(z_m); 0]|`` in the weighted norm. The arc's error is largest near its middle
    (it grows like ``θ²(1−θ)²``, θ the fraction of the step, for a smooth curve), O(h⁴);
    one residual and one solve with a factorization at hand. Infinite where the residual is
    not finite at ``z_m``. (``h``, the step's pseudo-arclength, is unused: kept for the
    callers' symmetry.)"""
    W = system.weights
    zm = 0.5 * (z + z1) + (0.125 * arc_length(z1 - z, t, t1, W)) * (t - t1)
    g = system.residual(zm)
    rhs = np.empty(g.size + 1)
    rhs[:-1] = g
    rhs[-1] = 0.0
    d = lu.solve(rhs)
    e = math.sqrt(float(d.dot(W * d)))
    return e if e == e else math.inf


__all__ = ["arc_length", "hermite", "interpolation_error"]
