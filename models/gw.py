"""Greenwood–Williamson integrals F_n(t) = ∫_t^∞ (s − t)^n φ(s) ds, φ the standard normal density.

For a Gaussian summit-height density of standard deviation σ* [µm], the load integral is
J(h) = σ*^{3/2} F_{3/2}(h/σ*) and the area integral σ* F_1(h/σ*). All functions take and
return dimensionless numbers (t = h/σ*), accept numpy arrays and broadcast.

Method (accuracy and speed measured in ``docs/benchmarks/gw.md``):

* n = 0: φ(t) √(π/2) erfcx(t/√2) for t > 1, ``scipy.special.ndtr(−t)`` otherwise.
* n = 1: F_1 = φ(t) + |t| Φ(|t|) for t < 0 (two positive terms). For t ≥ 0,
  F_1 = φ(t) G_1(t), G_1 = 1 − t G_0 with G_0 = √(π/2) erfcx(t/√2) for t < 2, and the
  continued fraction G_1/G_0 = 1/(t + 2/(t + 3/(t + …))) for t ≥ 2, where 1 − t G_0 cancels.
* n = −1/2, 1/2, 3/2: substituting s = t + x² gives an entire, even integrand,
  F_n(t) = ∫_ℝ x^{2n+1} φ(t + x²) dx, for which the trapezoidal rule converges geometrically.
  A fixed number of nodes spans the region where the integrand exceeds e^{-50} of its peak
  (the peak sits at x = 0 for t ≥ 0 and near x = √−t for t < 0), and the peak factor is taken
  out analytically, so the log form never underflows or overflows.
* φ(t) = exp(−t²/2)/√(2π) is evaluated with t² split exactly (Dekker), because rounding t²
  alone costs t² × 1.1e-16 relative (1.6e-13 at t = 38).

Relative accuracy ≤ 1e-14 on t ∈ [−10, 38] wherever F_n is a normal double (tested against
mpmath). F_{3/2}(t) falls into the subnormal range for t ≳ 37.6 and underflows for t ≳ 38.6;
use ``log_gw_integral`` there: it is finite for every finite t, with an error of a few ulp of
log F_n (as an absolute error, that is a relative error of F_n of ~1e-16 × |log F_n|).
"""

from __future__ import annotations

import math

import numpy as np
from scipy import special as sc

__all__ = ["gw_integral", "log_gw_integral", "gw_difference", "normal_pdf", "mills_ratios"]

_LOG_SQRT_2PI = 0.5 * math.log(2.0 * math.pi)
_SQRT_PI_2 = math.sqrt(math.pi / 2.0)
_INV_SQRT2 = 1.0 / math.sqrt(2.0)
_INV_SQRT_2PI = 1.0 / math.sqrt(2.0 * math.pi)
#: integrand dropped below e^{-_L} of its peak
_L = 50.0
#: trapezoid intervals on the covered part of the half line
_M = 48
#: continued fraction for F_1: switch point and depth (depth 160 is exact to 3e-16 at t = 2)
_T_CF = 2.0
_K_CF = 160
#: Gauss–Legendre rule for gw_difference
_GL_X, _GL_W = np.polynomial.legendre.leggauss(20)
#: values per block (bounds the (block, M+1) work arrays to ~0.4 MB, cache friendly)
_BLOCK = 1024
#: below this t, F_n (n half-integer) by its expansion in 1/t² (:func:`_far_left`): the
#: trapezoid forms x² + t there, which rounds to ε|t| (1.3e-11 relative at t = −3.4e5)
_T_LEFT = -20.0
_K_LEFT = 14


def _check_order(n: float, allowed=(-0.5, 0, 0.5, 1, 1.5)) -> float:
    if n not in allowed:
        from .errors import ModelParameterError

        raise ModelParameterError(f"n must be one of {allowed}, got {n!r}")
    return float(n)


def _finite(t) -> np.ndarray:
    t = np.asarray(t, dtype=float)
    if not (math.isfinite(t.flat[0]) if t.size == 1 else np.all(np.isfinite(t))):
        from .errors import ModelParameterError

        bad = t[~np.isfinite(t)].ravel()[0] if t.ndim else t
        raise ModelParameterError(f"t must be finite, got {bad!r}")
    return t


def _square(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """t² = hi + lo exactly (Veltkamp/Dekker): hi the rounded square, lo its error."""
    hi = t * t
    a = t * 134217729.0  # 2^27 + 1
    th = a - (a - t)
    tl = t - th
    return hi, ((th * th - hi) + 2.0 * th * tl) + tl * tl


def _exp_minus_half_square(t: np.ndarray) -> np.ndarray:
    """exp(−t²/2) with t² = hi + lo split exactly (Veltkamp/Dekker)."""
    hi, lo = _square(t)
    return np.exp(-0.5 * hi) * (1.0 - 0.5 * lo)


def _grid(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Trapezoid nodes x, shape t.shape + (M+1,), and steps h, shape t.shape + (1,)."""
    tp = np.maximum(t, 0.0)
    hi2 = -t + np.sqrt(tp * tp + 2.0 * _L)
    lo2 = np.maximum(-t - math.sqrt(2.0 * _L), 0.0)
    lo, hi = np.sqrt(lo2), np.sqrt(hi2)
    h = ((hi - lo) / _M)[..., None]
    x = lo[..., None] + h * np.arange(_M + 1)
    return x, h


def _blocked(func, t: np.ndarray, *args) -> np.ndarray:
    flat = t.ravel()
    out = np.empty(flat.shape)
    for i in range(0, flat.size, _BLOCK):
        out[i : i + _BLOCK] = func(flat[i : i + _BLOCK], *args)
    return out.reshape(t.shape)


def _trapezoid_sum(t: np.ndarray, p: int) -> np.ndarray:
    """∫_ℝ x^p w(x) dx with w = exp(E), E = −t x² − x⁴/2 (t ≥ 0) or −(x² + t)²/2 (t < 0)."""
    if t.size > _BLOCK:
        return _blocked(_trapezoid_sum, t, p)
    x, h = _grid(t)
    x2 = x * x
    tt = t[..., None]
    # t < 0: x² + t about the peak at x² ≈ −t, formed from the grid's start x_0 as
    # (x_0² + t) + y(2x_0 + y), y = x − x_0 = h·k, with x_0² split exactly (x_0² + t then
    # exact by Sterbenz): x² + t rounded directly errs by ε|t| (1.5e-12 relative in F_n
    # at t = −3.6e5, 2.5e-8 at t = −1e9)
    if np.all(t >= 0.0):  # (the usual case of a scalar call: no work for t < 0)
        e = -x2 * (tt + 0.5 * x2)
    else:
        x0 = x[..., :1]
        sq_hi, sq_lo = _square(x0)
        y = h * np.arange(_M + 1)
        w = ((sq_hi + tt) + sq_lo) + y * (2.0 * x0 + y)
        e = np.where(tt >= 0.0, -x2 * (tt + 0.5 * x2), -0.5 * w * w)
    f = np.exp(e)
    for _ in range(p // 2):
        f *= x2
    return (2.0 * f[..., 1:].sum(axis=-1) + f[..., 0]) * h[..., 0]


def _far_left_series(n: float, t: np.ndarray) -> np.ndarray:
    """Σ_k C(n, 2k) (2k − 1)!! t^{−2k}, so that F_n(t) = |t|^n Σ for t ≤ −20.

    F_n(t) = E[(S + |t|)^n; S > t] for a standard normal S; for t ≤ −20 the mass of S below
    t is < 1e-87, and the binomial series of (1 + S/|t|)^n averaged over S (odd moments
    vanish, E S^{2k} = (2k − 1)!!) is asymptotic with terms below 1e-18 by k = 14."""
    if t.size <= 4:  # (one level at a time: Python floats, the same IEEE operations)
        return np.array([_far_left_sum(n, x) for x in t.tolist()]).reshape(t.shape)
    return _far_left_sum(n, t)


def _far_left_sum(n: float, t):
    """The sum of :func:`_far_left_series` for a float or an array ``t`` (the one recurrence)."""
    inv2 = 1.0 / (t * t)
    total = term = coef = 1.0  # coef: C(n, 2k) (2k − 1)!!, from the previous one
    for k in range(1, _K_LEFT):
        coef *= (n - 2 * k + 2) * (n - 2 * k + 1) / ((2 * k) * (2 * k - 1)) * (2 * k - 1)
        term = term * inv2
        total = total + coef * term
    return total


def _g1(t: np.ndarray, g0: np.ndarray) -> np.ndarray:
    """G_1 = F_1/φ = 1 − t G_0, by a continued fraction where that cancels (t ≥ 2)."""
    g1 = 1.0 - t * g0
    big = t >= _T_CF
    if np.any(big):
        tb = t[big]
        if tb.size <= 4:
            # a few values (the contact levels ask for one at a time): the recurrence in
            # Python floats, the same IEEE operations as numpy's on arrays of one element
            # but 40 times faster (15 µs instead of 600: it was a third of a Gaussian
            # locus's energies)
            r = np.array([_cf_tail(x) for x in tb.tolist()])
        else:
            r = np.zeros_like(tb)
            for k in range(_K_CF, 1, -1):
                r = k / (tb + r)
        g1[big] = g0[big] / (tb + r)
    return g1


def normal_pdf(t) -> np.ndarray:
    """φ(t) = exp(−t²/2)/√(2π), with t² split exactly (no ε t² relative error)."""
    t = np.asarray(t, dtype=float)
    return _exp_minus_half_square(t) * _INV_SQRT_2PI


def mills_ratios(z) -> tuple[np.ndarray, np.ndarray]:
    """(G_0, G_1) at z ≥ 0: G_0 = Q(z)/φ(z) = √(π/2) erfcx(z/√2) (the Mills ratio) and
    G_1 = F_1(z)/φ(z) = 1 − z G_0, the latter by a continued fraction where it cancels."""
    z = np.atleast_1d(np.asarray(z, dtype=float))
    g0 = _SQRT_PI_2 * sc.erfcx(z * _INV_SQRT2)
    return g0, _g1(z, g0)


def _cf_tail(x: float) -> float:
    """The tail 2/(x + 3/(x + …)) of the continued fraction of :func:`_g1` at one x."""
    r = 0.0
    for k in range(_K_CF, 1, -1):
        r = k / (x + r)
    return r


def log_gw_integral(n: float, t) -> np.ndarray:
    """Return log F_n(t), finite for every finite t (no underflow).

    F_{−1/2} = −2 dF_{1/2}/dt is (4/3)σ*^{1/2} J'' of a Gaussian surface.

    Parameters
    ----------
    n : {-0.5, 0, 0.5, 1, 1.5}
        The order.
    t : array_like
        The level, in units of the rms height (dimensionless).

    Returns
    -------
    numpy.ndarray
        log F_n(t), the shape of ``t``.

    Raises
    ------
    ModelParameterError
        Another order, or a ``t`` that is not finite.
    """
    n = _check_order(n)
    t = _finite(t)
    if n == 0:
        return sc.log_ndtr(-t)
    t1 = np.atleast_1d(t)
    if n == 1:
        tp = np.maximum(t1, 0.0)
        g0 = _SQRT_PI_2 * sc.erfcx(tp * _INV_SQRT2)
        out = np.log(_g1(tp, g0)) - _LOG_SQRT_2PI - 0.5 * tp * tp
        neg = t1 < 0.0
        tn = t1[neg]
        out[neg] = np.log(np.exp(-0.5 * tn * tn - _LOG_SQRT_2PI) - tn * sc.ndtr(-tn))
    else:
        tp = np.maximum(t1, 0.0)
        far = t1 <= _T_LEFT
        out = np.empty(t1.shape)
        near = ~far
        out[near] = (
            np.log(_trapezoid_sum(t1[near], int(2 * n + 1))) - _LOG_SQRT_2PI - 0.5 * tp[near] ** 2
        )
        tf = t1[far]
        out[far] = n * np.log(-tf) + np.log(_far_left_series(n, tf))
    return out.reshape(t.shape)


def gw_integral(n: float, t) -> np.ndarray:
    """Return F_n(t) = ∫_t^∞ (s − t)^n φ(s) ds, φ the standard normal density.

    Parameters
    ----------
    n : {-0.5, 0, 0.5, 1, 1.5}
        The order.
    t : array_like
        The level, in units of the rms height (dimensionless).

    Returns
    -------
    numpy.ndarray
        F_n(t) (dimensionless), the shape of ``t``.

    Raises
    ------
    ModelParameterError
        Another order, or a ``t`` that is not finite.

    Examples
    --------
    >>> float(gw_integral(0, 0.0)), float(gw_integral(1, 0.0))  # 1/2 and φ(0) = 1/√(2π)
    (0.5, 0.3989422804014327)
    """
    n = _check_order(n)
    t = _finite(t)
    t1 = np.atleast_1d(t)
    if n == 0:
        out = sc.ndtr(-t1)
        right = t1 > 1.0  # (erfcx overflows far left: evaluated right of 1 only)
        tr = t1[right]
        out[right] = (
            _exp_minus_half_square(tr) * (_INV_SQRT_2PI * _SQRT_PI_2) * sc.erfcx(tr * _INV_SQRT2)
        )
    elif n == 1:
        # t < 0: φ(t) + |t| Φ(|t|), two positive terms (erfcx(t/√2) would carry e^{t²/2})
        phi = _exp_minus_half_square(t1) * _INV_SQRT_2PI
        g0 = _SQRT_PI_2 * sc.erfcx(np.maximum(t1, 0.0) * _INV_SQRT2)
        out = np.where(t1 < 0.0, phi - t1 * sc.ndtr(-t1), phi * _g1(np.maximum(t1, 0.0), g0))
    else:
        out = _half_integer(n, t1)
    return out.reshape(t.shape)


def _half_integer(n: float, t: np.ndarray) -> np.ndarray:
    """F_n(t) for n ∈ {−1/2, 1/2, 3/2}: the trapezoid, or the expansion far left."""
    far = t <= _T_LEFT
    out = np.empty(t.shape)
    near = ~far
    tn = t[near]
    scale = np.where(tn > 0.0, _exp_minus_half_square(tn), 1.0) * _INV_SQRT_2PI
    out[near] = _trapezoid_sum(tn, int(2 * n + 1)) * scale
    tf = t[far]
    out[far] = (-tf) ** n * _far_left_series(n, tf)
    return out


def gw_difference(n: float, t, delta) -> np.ndarray:
    """Return F_n(t) − F_n(t + δ) for δ ≥ 0, without cancellation for small δ.

    For δ (max(t, 0) + δ + 1) ≤ 4, or t < 0 and δ ≤ 3|t|/4, it is n ∫_t^{t+δ} F_{n−1}(τ) dτ by
    20-point Gauss–Legendre (F_{n−1} is smooth on that interval: F_{−1/2} and F_{1/2} from the
    same trapezoidal rule); otherwise F_n(t + δ) is well below F_n(t) and the plain difference
    loses < 1 digit.

    Parameters
    ----------
    n : {0.5, 1, 1.5}
        The order.
    t : array_like
        The level, in units of the rms height (dimensionless).
    delta : array_like
        The increment δ ≥ 0 (dimensionless), broadcast against ``t``.

    Returns
    -------
    numpy.ndarray
        The difference (dimensionless), the broadcast shape.

    Raises
    ------
    ModelParameterError
        Another order, a value that is not finite, or δ < 0.
    """
    n = _check_order(n, (0.5, 1, 1.5))
    t, delta = np.broadcast_arrays(_finite(t), _finite(delta))
    if np.any(delta < 0):
        from .errors import ModelParameterError

        raise ModelParameterError(f"delta must be >= 0, got {delta[delta < 0].ravel()[0]!r}")
    t1, d1 = np.atleast_1d(t).astype(float), np.atleast_1d(delta).astype(float)
    # (far left, F_n ~ |t|^n: the difference cancels while t + δ < t/4, where F_{n−1} is
    # smooth on the interval: its singularity-free region reaches a third of its length)
    small = (d1 * (np.maximum(t1, 0.0) + d1 + 1.0) <= 4.0) | ((t1 < 0.0) & (d1 <= -0.75 * t1))
    out = np.empty(t1.shape)
    if np.any(~small):
        tl, dl = t1[~small], d1[~small]
        out[~small] = gw_integral(n, tl) - gw_integral(n, tl + dl)
    if np.any(small):
        ts, ds = t1[small], d1[small]
        tau = ts[:, None] + 0.5 * ds[:, None] * (1.0 + _GL_X)
        integrand = _f_minus_one(n, tau.ravel()).reshape(tau.shape)
        out[small] = n * 0.5 * ds * (integrand @ _GL_W)
    return out.reshape(t.shape)


def _f_minus_one(n: float, t: np.ndarray) -> np.ndarray:
    """F_{n−1}(t) for n = 1/2 (F_{−1/2}), 1 (F_0) or 3/2 (F_{1/2})."""
    if n == 1:
        return gw_integral(0, t)
    return _half_integer(n - 1.0, t)
