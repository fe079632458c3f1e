"""Locating special points inside an accepted step ``z_a -> z_b``.

- folds (turning points of any component ``z_k``): Newton on the minimally augmented system
  (:mod:`.foldlocate`), with the stopping test and the second-derivative rows written here
  (:func:`newton_done`, :func:`second_derivative_row`);
- component targets and bounds: the corrector with the constraint ``z_k = value`` (exact);
- events and branch points: the Illinois variant of regula falsi on the pseudo-arclength,
  each evaluation a corrected point on the curve.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from .._errors import SingularMatrixError
from ..numerics._linalg import (
    bordered,
    factor,
    max_abs,
    unit_last,
)
from ..systems._newton import correct

if TYPE_CHECKING:
    from .._options import ContinuationOptions

_EPS = float(np.finfo(float).eps)


@dataclass
class Bracket:
    """An accepted step: end points, unit tangents and the pseudo-arclength ``h`` of ``z_b``."""

    system: Any
    """The curve system (a :class:`~..systems._curve.CurveSystem`)."""
    z_a: np.ndarray
    t_a: np.ndarray
    z_b: np.ndarray
    t_b: np.ndarray
    weights: np.ndarray
    options: ContinuationOptions
    row: np.ndarray = field(init=False)
    h: float = field(init=False)
    d_a: np.ndarray = field(init=False)
    d_b: np.ndarray = field(init=False)
    _basis: np.ndarray | None = field(init=False, default=None, repr=False)

    def __post_init__(self) -> None:
        self.row = self.weights * self.t_a
        self.h = float(self.row.dot(self.z_b - self.z_a))
        # the interpolant is parametrised by σ, not by arclength: its end derivatives are
        # dz/dσ = t/(row·t) (t_b is tilted by the step's turn, up to max_angle)
        self.d_a = self.t_a / float(self.row.dot(self.t_a))
        cos_b = float(self.row.dot(self.t_b))
        self.d_b = self.t_b / cos_b if cos_b > 0.1 else self.t_b

    def sigma(self, z: np.ndarray) -> float:
        return float(self.row.dot(z - self.z_a))

    def _hermite(self, coefficients) -> np.ndarray:
        """``c0·z_a + c1·h·d_a + c2·z_b + c3·h·d_b`` (one product with the stacked data; a
        row of coefficients per result)."""
        basis = self._basis
        if basis is None:
            basis = self._basis = np.array(
                (self.z_a, self.h * self.d_a, self.z_b, self.h * self.d_b)
            )
        return np.array(coefficients).dot(basis)

    def guess(self, theta: float) -> np.ndarray:
        """Cubic Hermite interpolation between the end points (θ ∈ [0, 1])."""
        return self._hermite(self._weights(theta))

    def guess_derivative(self, theta: float) -> np.ndarray:
        """``dz/dσ`` of the interpolant at θ."""
        return self._hermite(self._derivative_weights(theta))

    def guess_and_derivative(self, theta: float) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`guess` and :meth:`guess_derivative` at θ, in one product."""
        both = self._hermite((self._weights(theta), self._derivative_weights(theta)))
        return both[0], both[1]

    @staticmethod
    def _weights(s: float) -> tuple[float, float, float, float]:
        s2 = s * s
        s3 = s2 * s
        return (2 * s3 - 3 * s2 + 1, s3 - 2 * s2 + s, -2 * s3 + 3 * s2, s3 - s2)

    def _derivative_weights(self, s: float) -> tuple[float, float, float, float]:
        s2 = s * s
        h = self.h
        return (
            (6 * s2 - 6 * s) / h,
            (3 * s2 - 4 * s + 1) / h,
            (-6 * s2 + 6 * s) / h,
            (3 * s2 - 2 * s) / h,
        )

    def turning_theta(self, k: int) -> float:
        """θ ∈ [0, 1] where component ``k`` of the Hermite interpolant is stationary: the
        root of its derivative, a quadratic in θ that changes sign on [0, 1] when
        ``t_a[k]`` and ``t_b[k]`` do. On the benchmark folds (cusp, truss) the interpolant
        there is 1e-5 to 3e-3 off the fold, against 1e-3 to 1e-1 at the zero of the linearly
        interpolated tangent component: the fold Newton needs 2–3 iterations, not 3–5."""
        ta, tb = float(self.d_a[k]), float(self.d_b[k])
        if ta == tb:
            return 0.5
        linear = min(1.0, max(0.0, ta / (ta - tb)))
        delta = float(self.z_b[k] - self.z_a[k]) / self.h
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

    def pair_theta(self, k: int) -> float | None:
        """θ ∈ (0, 1) between two turning points of component ``k`` of the interpolant that
        leave no net sign change of its derivative (see :func:`hermite_turning_pair`)."""
        delta = float(self.z_b[k] - self.z_a[k]) / self.h
        return hermite_turning_pair(float(self.d_a[k]), float(self.d_b[k]), delta)

    def point_at(self, sigma: float, strict: bool = False, start=None):
        """The curve point whose pseudo-arclength from ``z_a`` (along ``t_a``) is ``sigma``."""
        o = self.options
        theta = sigma / self.h if self.h != 0 else 0.0
        z0 = self.guess(theta) if start is None else start
        c = self.row.dot(self.z_a) + sigma
        return correct(self.system, z0, self.row, c, o, budget=2, strict=strict)

    def polish(self, z: np.ndarray, sigma: float) -> np.ndarray:
        """Newton to the update tolerance (not just the residual tolerance) at ``sigma``."""
        res = self.point_at(sigma, strict=True, start=z)
        return res.z if res.converged else z


class Located(NamedTuple):
    """A special point located inside a step (immutable).

    ``sigma``: its pseudo-arclength from the step's start; ``status``: ``"converged"`` or
    ``"guess"`` (only bracketed); ``details``: what the locating method reports."""

    z: np.ndarray
    sigma: float
    status: str
    iterations: int
    details: Mapping = MappingProxyType({})
    tangent: np.ndarray | None = None
    """Unit tangent at ``z`` oriented like the step, when the locating iteration gave it."""
    residual_norm: float | None = None
    """Max-norm of the residual at ``z``, when the locating iteration computed it."""


def hermite_turning_pair(ta: float, tb: float, delta: float, dip: bool = False) -> float | None:
    """Two turning points of one component inside a step, seen by its cubic Hermite
    interpolant: ``ta``, ``tb`` the component's derivatives with respect to θ ∈ [0, 1]
    (divided by the step's length ``h``) at the ends, ``delta`` its change over the step
    divided by ``h``. The interpolant's derivative ``ta + bθ + aθ²`` (a = 3(ta + tb) − 6δ,
    b = 6δ − 4ta − 2tb) has the same sign at both ends but two roots inside when its vertex
    lies in (0, 1) with the other sign; the vertex θ is returned (else None): a tight S-curve
    whose two folds one step spans, which the end values alone cannot show. With ``dip``,
    also when the vertex has the ends' sign but a smaller magnitude than both (a dip towards
    zero, where the interpolant's error may hide the other sign).

    >>> # x³ − a x at a = 0.03 over x ∈ [−0.4, 0.4]: folds at x = ±0.1
    >>> round(hermite_turning_pair(3 * 0.16 - 0.03, 3 * 0.16 - 0.03, 0.16 - 0.03), 12)
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
    # the interpolant's rounding (a constant component's vertex is its value up to it)
    if vertex * ta < 0.0 or abs(vertex) < (1.0 - 1e-6) * min(abs(ta), abs(tb)):
        return min(max(theta, DIP_INSET), 1.0 - DIP_INSET)
    return None


DIP_MARGIN = 0.25
"""How far outside the step (as a fraction of it) the vertex of a dip may lie: its position
is as uncertain as its value (on two folds 1e-2 apart in the state, 0.06 of the step)."""
DIP_INSET = 0.05
"""A dip's vertex outside or next to the step's ends is sampled this far inside."""


ZOOM = 0.25
"""A search whose smallest sample is a step's end, below this fraction of the nearest
sample, samples this fraction of the way from the end to it: two folds may sit just inside
the step (on two folds 1e-2 apart in the state, a step began 1e-3 before the first)."""


def parabola_minimum(samples: list[tuple[float, float]]) -> float | None:
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


def oriented_tangent(t: np.ndarray, row: np.ndarray, weights: np.ndarray) -> np.ndarray | None:
    """``t`` scaled to unit weighted norm with ``row·t > 0``; None if ``t`` is not finite or
    too close to orthogonal to ``row`` for the orientation to be trusted."""
    nt = math.sqrt(t.dot(weights * t))
    if not (math.isfinite(nt) and nt > 0.0):
        return None
    rt = row.dot(t) / nt
    if abs(rt) < 1e-3 * math.sqrt(row.dot(row / weights)):
        return None
    return t / (nt if rt > 0 else -nt)


def tangent_at(
    system, z: np.ndarray, row: np.ndarray, weights: np.ndarray, br: Bracket | None = None
) -> np.ndarray:
    """Unit tangent at ``z`` oriented so that ``row·t > 0``.

    Exactly at a branch point ``[∂G/∂z; row]`` is singular whatever the border: the tangent of
    the branch is then the limit of its tangents, taken from the step's Hermite interpolant."""
    dg = system.jacobian(z)
    try:
        t = factor(bordered(dg, row)).solve(unit_last(z.size))
    except SingularMatrixError:
        if br is None:
            raise
        t = br.guess_derivative(min(1.0, max(0.0, br.sigma(z) / br.h)))
    return t / math.sqrt(t.dot(weights * t))


def newton_done(
    it: int,
    size: float,
    previous: float,
    tol: float,
    stall: float,
    perturbation: float | None = None,
    k_ratio: float | None = None,
) -> bool:
    """Stopping test of the locating Newton iterations, with update ``size`` (max-norm of the
    update relative to the components' magnitudes ``max(scale_i, |z_i|)``).

    Once quadratic convergence is under way (the update shrank by 100 or more), the next
    update is estimated and the iteration stops if it would be below the tolerance. With
    ``perturbation`` None the estimate is the linear one, ``size²/previous`` (safe whatever
    the Newton matrix's error). Given the relative error δ of the Newton matrix, it is
    ``C·size² + δ·size`` with ``C = size/previous²`` from the last contraction: Newton's
    quadratic term plus the linear one that the matrix error adds. Given ``k_ratio`` =
    ``|z_k|/max(scale_k, |z_k|)`` for the component the point is located in (such as a
    fold's parameter), an early stop also needs the estimate below ``tol·k_ratio``: that
    component is then exact to ``tol`` relative to itself even when it is much smaller than
    its typical size."""
    if size <= tol:
        return True
    if math.isfinite(previous) and size <= 1e-2 * previous:
        if perturbation is None:
            estimate = size * size / previous
        else:
            estimate = size * (size * size / (previous * previous) + perturbation)
        if estimate <= tol and (k_ratio is None or estimate <= tol * k_ratio):
            return True
    # stagnation: the updates stopped shrinking, at a level below ``stall``
    return it >= 4 and size > 0.5 * previous and size <= stall


def accept_located(
    br: Bracket,
    z: np.ndarray,
    dg: Any,
    iterations: int,
    last_update: float,
    details: dict,
    tangent: np.ndarray | None = None,
    slack: float = 0.05,
    magnitudes: np.ndarray | None = None,
) -> Located | None:
    """A point a locating Newton converged to, as :class:`Located` — if it solves ``G = 0``
    to tolerance (or to its rounding floor, reckoned with the components' ``magnitudes`` if
    given, else their typical sizes) and lies in the step (within ``slack`` of it, 5% by
    default); else None (it converged to a point of another step, or off the curve)."""
    system = br.system
    rn = max_abs(system.residual(z))
    if not (rn <= br.options.tol or rn <= system.residual_floor(dg, z, magnitudes)):  # NaN too
        return None
    sigma = br.sigma(z)
    if not (-slack * abs(br.h) <= (sigma if br.h >= 0 else -sigma) <= (1 + slack) * abs(br.h)):
        return None
    details = {**details, "last_update": float(last_update)}
    return Located(z, sigma, "converged", iterations, details, tangent, rn)


def locate_component(br: Bracket, k: int, value: float) -> Located | None:
    """The curve point with ``z_k = value`` exactly (corrector with constraint row ``e_k``)."""
    o = br.options
    za, zb = br.z_a[k], br.z_b[k]
    theta = min(1.0, max(0.0, float((value - za) / (zb - za)))) if zb != za else 0.5
    row = np.zeros(br.z_a.size)
    row[k] = 1.0
    res = correct(br.system, br.guess(theta), row, value, o, budget=2)
    if not res.converged:
        return None
    z = res.z.copy()
    z[k] = value  # the constraint is linear: snap away the last rounding
    # the corrector's last factorization is [∂G/∂z; e_k] (at z up to its last update or
    # two): its solution t of [∂G/∂z; e_k] t = e_last has ∂G/∂z t = 0, a tangent
    return Located(
        z,
        br.sigma(z),
        "converged",
        res.iterations,
        {"method": "Newton with the component fixed"},
        tangent=oriented_tangent(res.lu.solve(unit_last(z.size)), br.row, br.weights),
    )
