"""The released energies of a rough surface as integrals of positive integrands (the optional
``leg_areas`` of :mod:`cusp.models.protocol`, for :class:`~cusp.models.rough_levels.RoughLevels`
and :class:`~cusp.models.exponential.ExponentialLevels`).

On the legs of the path (docs/physics.md §7) the tangential force over μF_N0 is
T = [J(d) − J(d0)]/J(d_A) and the slip over μ is s = (λ/σ*)(d0 − d): AB has d0 = d0_A, BC has
d = d_B, and D is on BC at the slip of A. The area between AB and BC at one slip is a
difference of two differences of J (the legs agree to ~g_A/σ* at small slips); written as
an integral of J'' = d²J/dh² > 0 over the triangle of (d, d0) between them and integrated
once in closed form,

  ABD = (λ/σ*)/(2J(d_A)) ∫ J''(y) W(y) dy,
  W = (y − d_A)² on [d_A, d_B],  δ² on [d_B, d0_A],  (d0_D − y)² on [d0_A, d0_D],

with δ = d_B − d_A and d0_D = d0_A + δ, and the rest of the snap-through area

  ABC − ABD = (λ/σ*)/J(d_A) ∫_{d0_D}^{d0_C} [−J'(y)] (y − d0_D) dy.

Both integrands are positive and their weights are formed from the differences between the
levels (kept to rounding by the levels, which are measured from d_A): nothing cancels,
however small the slip or the reduction (the quadrature of the gap between the legs lost
~ε over the relative gap: 4.6 relative at g_A = 1e-9 µm on the Gaussian scene). In the
levels' units (y = d_A + u Y) the factors are λc = λu/σ* and the levels' ``curvature``
u²J''/J(d_A) and ``slope`` −uJ'/J(d_A).

The integrals are adaptive Gauss–Legendre (16 and 32 nodes per interval, the worst interval
halved until the estimates agree to the tolerance); the error bound adds the quadrature's
estimate, the integrands' own error (the levels' ``relative_error``) and each level's error
times the area's derivative in it (the same integrals with the derivatives of the weights).
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Callable

import numpy as np

_EPS = float(np.finfo(float).eps)
_X16, _W16 = np.polynomial.legendre.leggauss(16)
_X32, _W32 = np.polynomial.legendre.leggauss(32)
#: intervals an integral may be split into before its estimate is returned as it is
_MAX_INTERVALS = 400

__all__ = ["adaptive_gauss_legendre", "rough_leg_areas"]


def _panel(f, a: float, width: float) -> tuple[np.ndarray, float]:
    """Both rules on [a, a + width]: the 32-node values (every row of f) and the first row's
    difference to the 16-node rule."""
    half = 0.5 * width
    fine = half * (f(a + half * (1.0 + _X32)) @ _W32)
    coarse = half * (f(a + half * (1.0 + _X16)) @ _W16)
    return fine, float(abs(fine[0] - coarse[0]))


def adaptive_gauss_legendre(
    f: Callable[[np.ndarray], np.ndarray], a: float, width: float, rtol: float
) -> tuple[np.ndarray, float]:
    """∫ over [a, a + width] of every row of ``f`` (nodes in, ``(rows, nodes)`` out; the
    first row a nonnegative integrand), halving the interval of the largest error until the
    errors sum to ``rtol`` of the first row's integral (at most 400 intervals). Returns the
    integrals and the first row's error estimate (the sum of the two rules' differences,
    which bounds the finer rule's error on smooth integrands by a wide margin)."""
    if not width > 0.0:
        return np.zeros(np.asarray(f(np.array([a]))).shape[0]), 0.0
    fine, err = _panel(f, a, width)
    heap = [(-err, a, width, fine)]
    total, errsum = fine.copy(), err
    while errsum > rtol * abs(total[0]) and len(heap) < _MAX_INTERVALS:
        e, x, w, val = heapq.heappop(heap)
        total -= val
        errsum += e  # (e is −err)
        for start in (x, x + 0.5 * w):
            v, d = _panel(f, start, 0.5 * w)
            heapq.heappush(heap, (-d, start, 0.5 * w, v))
            total += v
            errsum += d
    return total, errsum


def rough_leg_areas(levels, p_A, q_A, p_B, q_C, level_rtol, quad_tol, errors=None):
    """``((ABD, error), (ABC − ABD, error))`` [µm] for levels with ``lam`` (λc), ``curvature``
    and ``slope`` (module docstring), the second (NaN, NaN) without C (``q_C`` NaN).
    ``errors``: absolute errors of (p_A, q_A, p_B, q_C), else ``level_rtol`` times each."""
    levels_in = (p_A, q_A, p_B, q_C)
    if errors is None:
        errors = [level_rtol * abs(v) if math.isfinite(v) else 0.0 for v in levels_in]
    e_pA, e_qA, e_pB, e_qC = (e + _EPS * abs(v) for e, v in zip(errors, levels_in))
    lam = levels.lam
    eta = float(getattr(levels, "relative_error", 16.0 * _EPS)) + 16.0 * _EPS
    delta = p_B - p_A
    w_B = max(q_A - p_B, 0.0)
    tol = 0.25 * quad_tol
    curv = levels.curvature

    def first(tau):  # W = τ², its sensitivity weight 2τ
        c = curv(p_A + tau)
        return np.array([c * tau * tau, 2.0 * c * tau])

    def middle(tau):
        c = curv(p_B + tau)
        return np.array([c * delta * delta, 2.0 * c * delta])

    def last(tau):
        c = curv(q_A + tau)
        r = delta - tau
        return np.array([c * r * r, 2.0 * c * np.abs(r)])

    value = sens = quad = 0.0
    for f, width in ((first, delta), (middle, w_B), (last, delta)):
        (v, s), e = adaptive_gauss_legendre(f, 0.0, width, tol)
        value, sens, quad = value + v, sens + s, quad + e
    abd = 0.5 * lam * value
    abd_err = 0.5 * lam * (quad + sens * (e_pA + e_qA + e_pB)) + eta * abd
    if not math.isfinite(q_C):
        return (abd, abd_err), (math.nan, math.nan)
    q_D = q_A + delta
    h = q_C - q_D
    slope = levels.slope

    def rest(tau):
        s = slope(q_D + tau)
        return np.array([s * tau, s])

    (v, s0), e = adaptive_gauss_legendre(rest, 0.0, max(h, 0.0), tol)
    dc = lam * v
    at_c = float(slope(np.array([q_C]))[0]) * max(h, 0.0)
    dc_err = lam * (e + at_c * e_qC + s0 * (e_qA + e_pA + e_pB)) + eta * dc
    return (abd, abd_err), (dc, dc_err)
