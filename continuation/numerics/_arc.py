"""The arc of a step: the cubic Hermite curve between two points of a curve with given end
derivatives, the one model of the curve inside a step that the engine uses.

    z(θ) = h00(θ)·z0 + h10(θ)·L·d0 + h01(θ)·z1 + h11(θ)·L·d1,    θ ∈ [0, 1],

with ``h00 = 2θ³ − 3θ² + 1``, ``h10 = θ³ − 2θ² + θ``, ``h01 = 3θ² − 2θ³``, ``h11 = θ³ − θ²``;
``s = θ·L`` is the arc's parameter and ``d0``, ``d1`` are ``dz/ds`` at its ends. Two
parametrisations use it:

- a step's *bracket* (:class:`~..detection._bracket.Bracket`, where special points are
  located): ``s`` the pseudo-arclength along the first tangent, ``L = h`` the step's, and
  ``d = t/(W t_a·t)`` (the unit tangents divided by their component along the first);
- the branch's *dense output* (:mod:`~..results._dense`) and the step's accuracy check
  (:meth:`HermiteArc.error`): ``s`` the arclength of the circular arc with the same chord
  and tangents (:func:`arc_from`: exact on a circle), ``d`` the unit tangents.

The class gives its points (:meth:`~HermiteArc.at`, vectorised :meth:`~HermiteArc.sample`),
its derivative, the turning point of a component and a pair of them, the root of a
component, its midpoint and how far that lies from the curve (:meth:`~HermiteArc.error`,
which the step control holds within ``rtol``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from ._linalg import weighted_square

DIP_MARGIN = 0.25
"""How far outside the step (as a fraction of it) the vertex of a dip may lie: its position
is as uncertain as its value (on two folds 1e-2 apart in the state, 0.06 of the step)."""

DIP_INSET = 0.05
"""A dip's vertex outside or next to the step's ends is sampled this far inside."""


class HermiteArc:
    """The cubic Hermite arc from ``z0`` to ``z1`` with end derivatives ``d0``, ``d1``
    (``dz/ds``) over the parameter length ``length`` (see the module docstring). Immutable;
    the stacked data of :meth:`at` is made when first needed.

    >>> arc = HermiteArc(np.array([0.0, 0.0]), np.array([1.0, 0.0]),
    ...                  np.array([1.0, 1.0]), np.array([0.0, 1.0]), 1.5)
    >>> arc.at(0.0).tolist(), arc.at(1.0).tolist(), arc.midpoint().tolist()
    ([0.0, 0.0], [1.0, 1.0], [0.6875, 0.3125])
    """

    __slots__ = ("z0", "d0", "z1", "d1", "length", "_basis")

    def __init__(
        self, z0: np.ndarray, d0: np.ndarray, z1: np.ndarray, d1: np.ndarray, length: float
    ) -> None:
        self.z0, self.d0, self.z1, self.d1, self.length = z0, d0, z1, d1, length
        self._basis: np.ndarray | None = None

    # --- points and derivatives

    def _stacked(self, coefficients: Any) -> np.ndarray:
        """``c0·z0 + c1·L·d0 + c2·z1 + c3·L·d1`` by one product with the stacked data (a row
        of coefficients per result)."""
        basis = self._basis
        if basis is None:
            h = self.length
            basis = self._basis = np.array((self.z0, h * self.d0, self.z1, h * self.d1))
        return np.array(coefficients).dot(basis)

    def at(self, theta: float) -> np.ndarray:
        """The point at the fraction ``theta`` of the arc."""
        return self._stacked(_weights(theta))

    def derivative(self, theta: float) -> np.ndarray:
        """``dz/ds`` at the fraction ``theta``."""
        return self._stacked(self._derivative_weights(theta))

    def at_and_derivative(self, theta: float) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`at` and :meth:`derivative` at ``theta``, in one product."""
        both = self._stacked((_weights(theta), self._derivative_weights(theta)))
        return both[0], both[1]

    def _derivative_weights(self, s: float) -> tuple[float, float, float, float]:
        s2 = s * s
        h = self.length
        return (
            (6 * s2 - 6 * s) / h,
            (3 * s2 - 4 * s + 1) / h,
            (-6 * s2 + 6 * s) / h,
            (3 * s2 - 2 * s) / h,
        )

    def sample(self, thetas: np.ndarray) -> np.ndarray:
        """The points at the fractions ``thetas`` (an array), one row each: the polynomial
        evaluated for all of them at once (the dense output's many points)."""
        th = thetas[:, None]
        th2 = th * th
        th3 = th2 * th
        length = self.length
        return (
            (2 * th3 - 3 * th2 + 1) * self.z0
            + (th3 - 2 * th2 + th) * (length * self.d0)
            + (3 * th2 - 2 * th3) * self.z1
            + (th3 - th2) * (length * self.d1)
        )

    def midpoint(self) -> np.ndarray:
        """The point at θ = ½ in closed form, ``(z0 + z1)/2 + L/8·(d0 − d1)``."""
        return self.midpoint_of(self.z0, self.d0, self.z1, self.d1, self.length)

    @staticmethod
    def midpoint_of(
        z0: np.ndarray, d0: np.ndarray, z1: np.ndarray, d1: np.ndarray, length: float
    ) -> np.ndarray:
        """:meth:`midpoint` of the arc of these data (plain Python for the two components of
        a problem of one unknown: a third of numpy's cost)."""
        c = 0.125 * length
        if z0.size == 2:
            (a, b), (p, q) = z0.tolist(), z1.tolist()
            (u, v), (x, y) = d0.tolist(), d1.tolist()
            return np.array(((a + p) * 0.5 + (u - x) * c, (b + q) * 0.5 + (v - y) * c))
        return (z0 + z1) * 0.5 + (d0 - d1) * c

    # --- where a component turns or takes a value

    def turning(self, k: int) -> float:
        """θ ∈ [0, 1] where component ``k`` is stationary: the root of its derivative, a
        quadratic in θ that changes sign on [0, 1] when ``d0[k]`` and ``d1[k]`` do (the
        root nearest the zero of the linear interpolation of the derivative). On the
        benchmark folds (cusp, truss) the arc there is 1e-5 to 3e-3 off the fold, against
        1e-3 to 1e-1 at the zero of the linearly interpolated tangent component: the fold
        Newton needs 2–3 iterations, not 3–5."""
        ta, tb = float(self.d0[k]), float(self.d1[k])
        if ta == tb:
            return 0.5
        linear = min(1.0, max(0.0, ta / (ta - tb)))
        delta = float(self.z1[k] - self.z0[k]) / self.length
        a = 3.0 * (ta + tb) - 6.0 * delta
        b = 6.0 * delta - 4.0 * ta - 2.0 * tb
        disc = b * b - 4.0 * a * ta
        if ta * tb > 0 or disc < 0 or not math.isfinite(disc):
            return linear
        q = -0.5 * (b + math.copysign(math.sqrt(disc), b))
        roots = [
            r
            for r in ((q / a) if a != 0 else math.nan, (ta / q) if q != 0 else math.nan)
            if 0.0 <= r <= 1.0
        ]
        return min(roots, key=lambda r: abs(r - linear)) if roots else linear

    @staticmethod
    def turning_pair(ta: float, tb: float, delta: float, dip: bool = False) -> float | None:
        """Two turning points of one component inside an arc: ``ta``, ``tb`` its derivatives
        ``dz_k/ds`` at the ends, ``delta`` its change over the arc divided by the length.
        The arc's derivative ``ta + bθ + aθ²`` (a = 3(ta + tb) − 6δ, b = 6δ − 4ta − 2tb) has
        the same sign at both ends but two roots inside when its vertex lies in (0, 1) with
        the other sign; the vertex θ is returned (else None): a tight S-curve whose two
        folds one step spans, which the end values alone cannot show. With ``dip``, also
        when the vertex has the ends' sign but a smaller magnitude than both (a dip towards
        zero, where the arc's error may hide the other sign), moved inside by
        :data:`DIP_INSET`.

        >>> # x³ − a x at a = 0.03 over x ∈ [−0.4, 0.4]: folds at x = ±0.1
        >>> round(HermiteArc.turning_pair(3 * 0.16 - 0.03, 3 * 0.16 - 0.03, 0.16 - 0.03), 12)
        0.5
        """
        if not ta * tb > 0.0:
            return None
        a = 3.0 * (ta + tb) - 6.0 * delta
        if a == 0.0:
            return None
        b = 6.0 * delta - 4.0 * ta - 2.0 * tb
        theta = -b / (2.0 * a)
        vertex = ta - b * b / (4.0 * a)
        if 0.0 < theta < 1.0 and vertex * ta < 0.0:
            return theta
        if not (dip and -DIP_MARGIN < theta < 1.0 + DIP_MARGIN):
            return None
        # a dip: the vertex has the other sign, or is closer to 0 than both ends by more than
        # the arc's rounding (a constant component's vertex is its value up to it)
        if vertex * ta < 0.0 or abs(vertex) < (1.0 - 1e-6) * min(abs(ta), abs(tb)):
            return min(max(theta, DIP_INSET), 1.0 - DIP_INSET)
        return None

    def root(self, k: int, value: float) -> float:
        """θ ∈ [0, 1] where component ``k`` equals ``value`` (its end values bracket it): the
        real root in [0, 1] nearest to the linear interpolation's."""
        length = self.length
        x0, m0 = float(self.z0[k]), length * float(self.d0[k])
        x1, m1 = float(self.z1[k]), length * float(self.d1[k])
        # p(θ) = a θ³ + b θ² + m0 θ + x0
        a = 2 * x0 + m0 - 2 * x1 + m1
        b = -3 * x0 - 2 * m0 + 3 * x1 - m1
        roots = np.roots([a, b, m0, x0 - value])
        real = roots[np.abs(roots.imag) <= 1e-9 * (1.0 + np.abs(roots.real))].real
        inside = real[(real >= -1e-12) & (real <= 1.0 + 1e-12)]
        lin = (x0 - value) / (x0 - x1) if x0 != x1 else 0.5
        if inside.size == 0:
            return min(1.0, max(0.0, lin))
        return float(min(1.0, max(0.0, inside[np.argmin(np.abs(inside - lin))])))

    # --- how far the arc is from the curve

    def error(
        self,
        residual: Callable[[np.ndarray], np.ndarray],
        lu: Any,
        weights: np.ndarray | None,
    ) -> float:
        """The distance from the arc to the curve ``G = 0`` (``residual``: G): its midpoint
        (:meth:`midpoint`) projected onto the curve by one Newton update with the step's
        last factorization ``lu`` (of ``[∂G/∂z; row]`` near ``z1``),
        ``|lu⁻¹·[G(z_m); 0]|`` in the weighted norm (``weights`` None: all 1). The arc's
        error is largest near its middle (it grows like ``θ²(1−θ)²`` for a smooth curve),
        O(h⁴); one residual and one solve with a factorization at hand. Infinite where the
        residual is not finite at the midpoint."""
        return self.error_of(self.z0, self.d0, self.z1, self.d1, self.length, residual, lu, weights)

    @staticmethod
    def error_of(
        z0: np.ndarray,
        d0: np.ndarray,
        z1: np.ndarray,
        d1: np.ndarray,
        length: float,
        residual: Callable[[np.ndarray], np.ndarray],
        lu: Any,
        weights: np.ndarray | None,
    ) -> float:
        """:meth:`error` of the arc of these data, without making it (once a step)."""
        g = residual(HermiteArc.midpoint_of(z0, d0, z1, d1, length))
        rhs = np.empty(g.size + 1)
        rhs[:-1] = g
        rhs[-1] = 0.0
        d = lu.solve(rhs)
        e = math.sqrt(d.dot(d) if weights is None else weighted_square(d, weights))
        return e if e == e else math.inf


def _weights(s: float) -> tuple[float, float, float, float]:
    """The Hermite basis ``(h00, h10, h01, h11)`` at ``s``."""
    s2 = s * s
    s3 = s2 * s
    return (2 * s3 - 3 * s2 + 1, s3 - 2 * s2 + s, -2 * s3 + 3 * s2, s3 - s2)


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


ZOOM = 0.25
"""A search whose smallest sample is an end, below this fraction of the nearest sample,
samples this fraction of the way from the end to it: two folds may sit just inside the step
(on two folds 1e-2 apart in the state, a step began 1e-3 before the first)."""


def parabola_minimum(samples: Sequence[tuple[float, float]]) -> float | None:
    """The next point of a search for a zero of a function that is positive at every
    sample so far: ``samples`` are (θ, g) ascending in θ. The vertex of the parabola
    through the smallest interior sample and its two neighbours (successive parabolic
    interpolation: superlinear towards a smooth minimum), if the parabola opens upwards,
    its vertex lies strictly between them and it predicts a value below half the smallest
    sample — the minimum may then be ≤ 0; else None (the samples show the minimum, above
    zero, or no minimum inside).

    >>> # g = (θ − 0.3)² − 0.01 sampled at 0, 0.5 and 1: the vertex θ = 0.3 (g = −0.01)
    >>> round(parabola_minimum([(0.0, 0.08), (0.5, 0.03), (1.0, 0.48)]), 12)
    0.3
    >>> parabola_minimum([(0.0, 0.08), (0.3, 0.01), (0.5, 0.03)]) is None  # g = (θ−0.3)²+0.01
    True
    """
    if len(samples) < 3:
        return None
    i = min(range(len(samples)), key=lambda j: samples[j][1])
    if i == 0 or i == len(samples) - 1:  # smallest at an end, far below its neighbour:
        (x0, g0), (x1, g1) = samples[i], samples[1 if i == 0 else i - 1]
        return x0 + ZOOM * (x1 - x0) if g0 < ZOOM * g1 else None  # closer to it
    (x0, g0), (x1, g1), (x2, g2) = samples[i - 1 : i + 2]
    if not (g1 > 0.0 and g1 <= g0 and g1 <= g2):
        return None
    d0, d2 = (g0 - g1) / (x0 - x1), (g2 - g1) / (x2 - x1)
    curvature = (d2 - d0) / (x2 - x0)  # the parabola's second derivative / 2
    if not curvature > 0.0:
        return None
    slope = d0 - curvature * (x0 - x1)  # its derivative at x1
    x = x1 - slope / (2.0 * curvature)
    predicted = g1 - slope * slope / (4.0 * curvature)
    if not (x0 < x < x2 and x != x1 and predicted < 0.5 * g1):
        return None
    return x


__all__ = ["HermiteArc", "arc_from", "arc_length", "parabola_minimum"]
