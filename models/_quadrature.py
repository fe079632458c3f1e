"""Adaptive quadrature of the rough-surface integrals over a summit-height pdf.

Used by densities without closed forms (general Φ, and the Gaussian stick part). Imported
lazily: the exponential surface never loads it. A surface provides ``pdf(z)`` [1/µm],
``support`` (lo, hi) [µm] and ``breakpoints`` (points where Φ is not smooth, e.g. histogram
edges), and ``sigma`` (the length scale used to split infinite intervals).

The algebraic end-point behaviour (z − h)^k is put into QUADPACK's QAWS weight, so the
integrands that QAGS/QAGI see are as smooth as Φ itself. All integrals are of nonnegative
integrands, so the relative accuracy requested (1.2e-14, QUADPACK's floor) is what it aims
for; where it cannot, it returns its best estimate (the message is suppressed, not ignored:
the returned error estimate is checked and a loose one raises).
"""

from __future__ import annotations

import math
from itertools import pairwise

import numpy as np
from scipy import integrate

from .errors import ModelParameterError

_EPSREL = 1.2e-14  # QUADPACK refuses less than 50 ulp
_LIMIT = 200
#: an error estimate this much above the request means quadrature failed
_FAIL = 1e-8


def _quad(f, a, b, *, epsabs: float = 0.0, scale: float | None = None, **kw):
    """∫_a^b f by QUADPACK; over a half-infinite interval in units of ``scale`` (z = a +
    scale·u: QAGI maps u ∈ [0, ∞) to (0, 1] with the unit 1, so a density of width 1e-6 µm
    lived in 1e-6 of the mapped interval and its tail was missed: the Weibull density of
    σ* = 1e-6 µm integrated to 0.968, and σ* = 1e6 µm failed)."""
    if not a < b:
        return 0.0
    g, lo, hi, unit = f, a, b, 1.0
    if scale is not None and math.isfinite(a) and math.isinf(b):
        g, lo, hi, unit = (lambda u: f(a + scale * u)), 0.0, math.inf, scale
    elif scale is not None and math.isinf(a) and math.isfinite(b):
        g, lo, hi, unit = (lambda u: f(b - scale * u)), 0.0, math.inf, scale
    res = integrate.quad(
        g, lo, hi, epsabs=epsabs / unit, epsrel=_EPSREL, limit=_LIMIT, full_output=1, **kw
    )
    val, err = unit * res[0], unit * res[1]
    if not math.isfinite(val) or err > _FAIL * abs(val) + max(1e-300, 1e6 * epsabs):
        raise ModelParameterError(
            f"quadrature over [{a!r}, {b!r}] failed: value {val!r}, error estimate {err!r}; "
            f"is the density pdf finite and integrable there?"
        )
    return val


def _segments(surface, a: float, b: float) -> list[float]:
    """Split [a, b] at the density's breakpoints (and at a + sigma·k near an infinite end)."""
    pts = [a] + [p for p in surface.breakpoints if a < p < b] + [b]
    return pts


def _weighted(surface, k: float, h: float, a: float, b: float) -> float:
    """∫_a^b (z − h)^k Φ(z) dz for h ≤ a < b (b may be inf), with Φ possibly non-smooth."""
    pdf = surface.pdf
    if not a < b:
        return 0.0
    if math.isinf(b):
        lo, hi = surface.support
        split = a + 4.0 * surface.sigma
        if not math.isinf(hi):
            raise ModelParameterError("internal: infinite upper limit on finite support")
        return _weighted(surface, k, h, a, split) + _quad(
            lambda z: (z - h) ** k * pdf(z), split, math.inf, scale=surface.sigma
        )
    pts = _segments(surface, a, b)
    total = 0.0
    for i, (u, v) in enumerate(pairwise(pts)):
        if i == 0 and u == h and k != 0.0:
            total += _quad(pdf, u, v, weight="alg", wvar=(k, 0.0))
        else:
            total += _quad(lambda z: (z - h) ** k * pdf(z), u, v)
    return total


def _moment_scalar(surface, k: float, h: float) -> float:
    lo, hi = surface.support
    a = max(h, lo)
    return _weighted(surface, k, h, a, hi)


def moment(surface, k: float, h: np.ndarray) -> np.ndarray:
    """∫_h^∞ (z − h)^k Φ(z) dz elementwise [µm^k]."""
    h = np.asarray(h, dtype=float)
    out = np.array([_moment_scalar(surface, k, float(x)) for x in h.ravel()])
    return out.reshape(h.shape)


def _gauss_jacobi(m: int, k: float):
    from scipy.special import roots_jacobi

    if k == 0.0:
        x, w = np.polynomial.legendre.leggauss(m)
    else:
        x, w = roots_jacobi(m, 0.0, k)  # weight (1 + x)^k on [−1, 1]
    return 0.5 * (1.0 + x), w * 2.0 ** (-k - 1.0)  # ∫_0^1 v^k f(v) dv ≈ Σ w f(v)


_GJ: dict[tuple[int, float], tuple[np.ndarray, np.ndarray]] = {}


def _pdf_values(pdf, z: np.ndarray) -> np.ndarray:
    """pdf at an array of points (user pdfs may accept scalars only)."""
    try:
        out = np.asarray(pdf(z), dtype=float)
        if out.shape == z.shape:
            return out
    except (TypeError, ValueError):
        pass
    return np.array([float(pdf(float(x))) for x in z])


def _slip_short(surface, h: float, g: float, k: float = 1.5) -> float | None:
    """∫_h^{h+g} (z − h)^k Φ dz on a short interval by Gauss–Jacobi (weight v^k); None if 20
    and 30 nodes disagree.

    QUADPACK's QAWS returns poor error estimates on intervals of a few ulp, where this rule
    is exact to rounding for any Φ smooth across [h, h + g].
    """
    vals = []
    for m in (20, 30):
        if (m, k) not in _GJ:
            _GJ[m, k] = _gauss_jacobi(m, k)
        v, w = _GJ[m, k]
        vals.append(float(np.dot(w, _pdf_values(surface.pdf, h + g * v))))
    a, b = vals
    if not (math.isfinite(a) and abs(a - b) <= 2e-15 * abs(b)):
        return None
    return g ** (k + 1.0) * b


def slip_integral(surface, h: np.ndarray, g: np.ndarray, k: float = 1.5) -> np.ndarray:
    """∫_h^{h+g} (z − h)^k Φ dz elementwise [µm^{k+1}] (k = 3/2: S of Eq 10; k = 1: the
    slipping summits' share of the real contact area; k = 0: their share of the summits)."""
    lo, hi = surface.support
    out = np.empty(h.shape)
    for i, (x, y) in enumerate(zip(h.ravel(), g.ravel(), strict=True)):
        a, b = max(x, lo), min(x + y, hi)
        if not (y > 0.0 and a < b):
            out.flat[i] = 0.0
            continue
        smooth = a == x and b == x + y and not any(a < p < b for p in surface.breakpoints)
        short = _slip_short(surface, float(x), float(y), k) if smooth else None
        out.flat[i] = short if short is not None else _weighted(surface, k, x, a, b)
    return out


def _stick_scalar(surface, h: float, g: float) -> float:
    lo, hi = surface.support
    d0 = h + g
    a = max(d0, lo)
    if not a < hi:
        return 0.0
    pdf = surface.pdf

    def bracket(z):
        # (z − h)^{3/2} − (z − d0)^{3/2} written without cancellation
        u = np.maximum(z - d0, 0.0)
        return g * (3.0 * u * u + 3.0 * u * g + g * g) / ((u + g) ** 1.5 + u**1.5)

    def f(z):
        return bracket(z) * pdf(z)

    if math.isinf(hi):
        split = a + 4.0 * surface.sigma
        pts = _segments(surface, a, split)
        total = _quad(f, split, math.inf, scale=surface.sigma)
    else:
        pts = _segments(surface, a, hi)
        total = 0.0
    for u, v in pairwise(pts):
        total += _quad(f, u, v)
    return total


def stick_integral(surface, h: np.ndarray, g: np.ndarray) -> np.ndarray:
    """T = ∫_{h+g}^∞ [(z − h)^{3/2} − (z − h − g)^{3/2}] Φ dz elementwise [µm^{3/2}]."""
    out = np.empty(h.shape)
    for i, (x, y) in enumerate(zip(h.ravel(), g.ravel(), strict=True)):
        out.flat[i] = _stick_scalar(surface, float(x), float(y)) if y > 0.0 else 0.0
    return out


def integrate_pdf(pdf, support, breakpoints, sigma, epsabs: float = 0.0) -> float:
    """∫ pdf over the support (the normalisation check; moments with ``epsabs`` > 0, since a
    mean can be 0)."""
    lo, hi = support
    finite_lo = lo if math.isfinite(lo) else min([p for p in breakpoints] + [0.0]) - 4 * sigma
    finite_hi = hi if math.isfinite(hi) else max([p for p in breakpoints] + [0.0]) + 4 * sigma
    pts = [finite_lo] + [p for p in breakpoints if finite_lo < p < finite_hi] + [finite_hi]
    total = 0.0
    if not math.isfinite(lo):
        total += _quad(pdf, -math.inf, finite_lo, epsabs=epsabs, scale=sigma)
    if not math.isfinite(hi):
        total += _quad(pdf, finite_hi, math.inf, epsabs=epsabs, scale=sigma)
    for u, v in pairwise(pts):
        total += _quad(pdf, u, v, epsabs=epsabs)
    return total
