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
_MAX_INTERVALS = 600
#: the first interval of the geometric split [levels]
_FIRST = 2.0**-6

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
    which bounds the finer rule's error on smooth integrands by a wide margin).

    The interval is first split geometrically from ``a`` (widths 2⁻⁶, 2⁻⁵, ... levels): the
    integrands here decay away from ``a`` on a scale of a level or less, and a first rule
    over a long interval would put no node where they live (the snap-back energy of Fig 9's
    locus in μ came out 19 times too small below μ = 1e-7, where q_A is 1e7 levels)."""
    if not width > 0.0:
        return np.zeros(np.asarray(f(np.array([a]))).shape[0]), 0.0
    edges = [0.0]
    step = _FIRST
    while edges[-1] + step < width:
        edges.append(edges[-1] + step)
        step *= 2.0
    edges.append(width)
    heap = []  # (−error, tie-breaker, start, width, values): tuples never compare arrays
    total, errsum = None, 0.0
    for k, (lo, hi) in enumerate(zip(edges[:-1], edges[1:])):
        v, d = _panel(f, a + lo, hi - lo)
        heap.append((-d, k, a + lo, hi - lo, v))
        total = v.copy() if total is None else total + v
        errsum += d
    heapq.heapify(heap)
    assert total is not None
    count = len(heap)
    while heap and errsum > rtol * abs(total[0]) and count < _MAX_INTERVALS:
        e, _, x, w, val = heapq.heappop(heap)
        half = 0.5 * w
        if not x < x + half < x + w:  # (an interval of a few ulps: kept as it is, its
            continue  # error estimate in errsum; a Weibull path at F'_N = F_N0 − 1 ulp)
        total -= val
        errsum += e  # (e is −err)
        for start in (x, x + half):
            v, d = _panel(f, start, half)
            count += 1
            heapq.heappush(heap, (-d, count, start, half, v))
            total += v
            errsum += d
    return total, errsum


def rough_leg_areas(levels, p_A, q_A, p_B, q_C, level_rtol, quad_tol, errors=None):
    """``((ABD, error), (ABC − ABD, error))`` [µm] for levels with ``lam`` (λc), ``curvature``
    and ``slope`` (module docstring), the second (NaN, NaN) without C (``q_C`` NaN).
    ``errors``: absolute errors of (p_A, q_A, p_B, q_D, q_C), else ``level_rtol`` times each
    (q_D's is not used: D lies on BC at q_D = q_A + p_B − p_A, at the slip of A)."""
    levels_in = (p_A, q_A, p_B, q_C)
    if errors is None:
        errors = [level_rtol * abs(v) if math.isfinite(v) else 0.0 for v in levels_in]
    else:
        errors = [errors[0], errors[1], errors[2], errors[4]]
    e_pA, e_qA, e_pB, e_qC = (e + _EPS * abs(v) for e, v in zip(errors, levels_in))
    lam = levels.lam
    eta = float(getattr(levels, "relative_error", 16.0 * _EPS)) + 16.0 * _EPS
    delta = p_B - p_A
    w_B = max(q_A - p_B, 0.0)
    tol = 0.25 * quad_tol
    curv = levels.curvature

    def first(tau):  # W = τ², and |∂W/∂level| = 2τ
        c = curv(p_A + tau)
        return np.array([c * tau * tau, 2.0 * c * tau])

    def middle(tau):
        c = curv(p_B + tau)
        return np.array([c * delta * delta, 2.0 * c * delta])

    def last(tau):
        c = curv(q_A + tau)
        r = delta - tau
        return np.array([c * r * r, 2.0 * c * np.abs(r)])

    value = quad = 0.0
    sens = []  # per piece: ∫ curvature |∂W/∂level| (W moves with p_A on every piece, with
    # p_B on the last two, with q_A on the last; its ends move with W continuous)
    for f, width in ((first, delta), (middle, w_B), (last, delta)):
        (v, s), e = adaptive_gauss_legendre(f, 0.0, width, tol)
        value, quad = value + v, quad + e
        sens.append(s)
    abd = 0.5 * lam * value
    spread = sum(sens) * e_pA + (sens[1] + sens[2]) * e_pB + sens[2] * e_qA
    abd_err = 0.5 * lam * (quad + spread) + eta * abd
    if not math.isfinite(q_C):
        return (abd, abd_err), (math.nan, math.nan)
    q_D = q_A + delta
    h, e_h = _c_beyond_d(levels, p_A, q_A, p_B, q_C, (e_pA, e_qA, e_pB, e_qC), eta, tol)
    slope = levels.slope

    def rest(tau):  # and the derivative in q_D at fixed h: −∫ curvature·τ
        return np.array([slope(q_D + tau) * tau, curv(q_D + tau) * tau])

    (v, s0), e = adaptive_gauss_legendre(rest, 0.0, h, tol)
    dc = lam * v
    at_c = float(slope(np.array([q_D + h]))[0]) * h
    dc_err = lam * (e + at_c * e_h + s0 * (e_qA + e_pA + e_pB)) + eta * dc
    return (abd, abd_err), (dc, dc_err)


def _c_beyond_d(levels, p_A, q_A, p_B, q_C, errors, eta, tol):
    """h = q_C − q_D (C beyond D on the reloading leg, in levels) and its error bound.

    Not from the chain's q_C (at a tiny reduction C and D are a rounding of their levels
    apart): from T_A − T_D, the drop of the force from A to D, integrated without
    cancellation as ∫ curvature(p_A + y) K(y) dy with K(y) = min(y, δ, w_A, δ + w_A − y)
    (δ = p_B − p_A, w_A = q_A − p_A), h solving ∫_0^h slope(q_D + s) ds = T_A − T_D by
    Newton's method from the chain's q_C − q_D."""
    e_pA, e_qA, e_pB, e_qC = errors
    delta, w_A = p_B - p_A, q_A - p_A
    q_D = q_A + delta
    h = q_C - q_D
    lo, hi = sorted((delta, w_A))
    curv = levels.curvature

    def drop(y):  # the measure of {τ ∈ [0, δ], σ ∈ [0, w_A]: τ + σ = y}, and 1
        c = curv(p_A + y)
        return np.array([c * np.minimum(np.minimum(y, lo), delta + w_A - y), c])

    value = err = 0.0
    pieces = []  # ∫ curvature on each piece: K moves with the smaller of δ, w_A on the last
    # two, with the larger on the last
    for a, b in ((0.0, lo), (lo, hi), (hi, delta + w_A)):
        (v, c0), e = adaptive_gauss_legendre(drop, a, b - a, tol)
        value, err = value + v, err + e
        pieces.append(c0)
    e_delta, e_w = e_pA + e_pB, e_qA + e_pA
    e_lo, e_hi = (e_delta, e_w) if delta <= w_A else (e_w, e_delta)
    e_drop = err + (pieces[1] + pieces[2]) * e_lo + pieces[2] * e_hi + eta * value
    slope = levels.slope
    x = max(h, value / float(slope(np.array([q_D]))[0]))
    for _ in range(50):
        (reached,), _ = adaptive_gauss_legendre(lambda s: slope(q_D + s)[None, :], 0.0, x, tol)
        step = (reached - value) / float(slope(np.array([q_D + x]))[0])
        x = max(x - step, 0.5 * x)
        if abs(step) <= 4.0 * _EPS * x:
            break
    return x, (e_drop + 4.0 * _EPS * value) / float(slope(np.array([q_D + x]))[0]) + 4 * _EPS * x
