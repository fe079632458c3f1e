"""The interpolant of a step: the cubic Hermite arc between two points of a curve with their
unit tangents, and the measure of how far it lies from the curve, which the step control
holds within ``rtol`` (:class:`~.._options.ContinuationOptions`) and the branch's dense output
(:mod:`~..results._dense`) relies on."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ._linalg import weighted_square


def arc_length(dz: np.ndarray, t0: np.ndarray, t1: np.ndarray, w: np.ndarray) -> float:
    """The arclength of the circular arc with chord ``dz`` and unit end tangents ``t0``,
    ``t1`` in the weighted norm ``w``: :func:`arc_from`."""
    return arc_from(math.sqrt(dz.dot(w * dz)), float(t0.dot(w * t1)))


def arc_from(chord: float, cos_a: float) -> float:
    """The arclength of a circular arc from its ``chord`` and the cosine of the angle α
    between its end tangents: ``c·(α/2)/sin(α/2)``."""
    s2 = 0.5 * (1.0 - max(-1.0, min(1.0, cos_a)))  # sin²(α/2)
    if s2 < 0.07:  # α < 30°: asin(x)/x = 1 + x²/6 + 3x⁴/40 + 5x⁶/112, to 1e-6
        return chord * (1.0 + s2 * (1.0 / 6.0 + s2 * (3.0 / 40.0 + s2 * (5.0 / 112.0))))
    x = math.sqrt(s2)
    return chord * math.asin(x) / x


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
    system: Any,
    z: np.ndarray,
    t: np.ndarray,
    z1: np.ndarray,
    t1: np.ndarray,
    length: float,
    lu: Any,
) -> float:
    """The distance from the step's interpolant to the curve: the midpoint of the cubic
    Hermite arc from ``z`` (unit tangent ``t``) to ``z1`` (``t1``), the one the branch's
    dense output evaluates (:mod:`~..results._dense`: tangents scaled by the arc's ``length``,
    :func:`arc_from`), ``z_m = (z + z1)/2 + L/8·(t − t1)``, is projected onto the curve by
    one Newton update with the step's last factorization ``lu`` (of ``[∂G/∂z; row]`` near
    ``z1``): ``|lu⁻¹·[G(z_m); 0]|`` in the weighted norm. The arc's error is largest near its
    middle (it grows like ``θ²(1−θ)²``, θ the fraction of the step, for a smooth curve),
    O(h⁴); one residual and one solve with a factorization at hand. Infinite where the
    residual is not finite at ``z_m``."""
    c = 0.125 * length
    if z.size == 2:  # (scalar problems: plain Python, a third of numpy's cost; the same bits)
        (a, b), (p, q), (u, v), (x, y) = z.tolist(), z1.tolist(), t.tolist(), t1.tolist()
        zm = np.array(((a + p) * 0.5 + (u - x) * c, (b + q) * 0.5 + (v - y) * c))
    else:
        zm = (z + z1) * 0.5 + (t - t1) * c
    g = system.residual(zm)
    rhs = np.empty(g.size + 1)
    rhs[:-1] = g
    rhs[-1] = 0.0
    d = lu.solve(rhs)
    e = math.sqrt(d.dot(d) if system.unit_weights else weighted_square(d, system.weights))
    return e if e == e else math.inf


__all__ = ["arc_from", "arc_length", "hermite", "interpolation_error"]
