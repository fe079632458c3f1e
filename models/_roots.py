"""Roots of increasing functions, elementwise over arrays: a bracket grown until it holds the
target (:func:`expand_bracket`) and Illinois regula falsi inside it (:func:`monotone_root`),
used by the rough surfaces to invert their integrals (:func:`gap_low`, :func:`gap_high`)."""

from __future__ import annotations

import numpy as np

from .errors import ModelParameterError

__all__ = ["expand_bracket", "gap_high", "gap_low", "monotone_root"]


def monotone_root(f, target, lo, hi, *, maxiter: int = 200, xtol: float = 0.0) -> np.ndarray:
    """Solve f(x) = target elementwise for an increasing f on a bracket [lo, hi].

    ``f(x, idx)`` maps the values x of the elements ``idx`` (an index array into the full
    problem) to f there; ``lo``/``hi`` must satisfy f(lo) ≤ target ≤ f(hi)
    (use :func:`expand_bracket`). Illinois regula falsi, with a bisection every third step so
    the bracket at least halves; stops when the bracket is a few ulp wide.
    """
    target, lo, hi = np.broadcast_arrays(target, lo, hi)
    shape = lo.shape
    target, lo, hi = (np.array(a, dtype=float).ravel() for a in (target, lo, hi))
    everything = np.arange(lo.size)
    flo = np.asarray(f(lo, everything), dtype=float).ravel() - target
    fhi = np.asarray(f(hi, everything), dtype=float).ravel() - target
    x = np.where(np.abs(flo) <= np.abs(fhi), lo, hi)
    done = (flo == 0.0) | (fhi == 0.0)
    x = np.where(flo == 0.0, lo, np.where(fhi == 0.0, hi, x))
    for it in range(maxiter):
        width = hi - lo
        active = ~done & (width > 4.0 * np.spacing(np.maximum(np.abs(lo), np.abs(hi))) + xtol)
        if not np.any(active):
            break
        a, b, fa, fb = lo[active], hi[active], flo[active], fhi[active]
        with np.errstate(invalid="ignore", divide="ignore"):
            xs = b - fb * (b - a) / (fb - fa)
        mid = a + 0.5 * (b - a)
        bad = ~np.isfinite(xs) | (xs <= a) | (xs >= b)
        xn = np.where(bad | (it % 3 == 2), mid, xs)
        fx = np.asarray(f(xn, everything[active]), dtype=float).ravel() - target[active]
        left = fx < 0.0  # root to the right of xn
        # Illinois-type: halve the function value kept at the end that did not move
        new_lo = np.where(left, xn, a)
        new_hi = np.where(left, b, xn)
        new_flo = np.where(left, fx, 0.5 * fa)
        new_fhi = np.where(left, 0.5 * fb, fx)
        lo[active], hi[active], flo[active], fhi[active] = new_lo, new_hi, new_flo, new_fhi
        x[active] = xn
        done[active] = fx == 0.0
    return x.reshape(shape)


def expand_bracket(f, target, lo, hi, *, step: float = 1.0, maxiter: int = 200):
    """Grow [lo, hi] until an increasing f brackets target (f(lo) ≤ target ≤ f(hi))."""
    target, lo, hi = np.broadcast_arrays(target, lo, hi)
    shape = lo.shape
    target, lo, hi = (np.array(a, dtype=float).ravel() for a in (target, lo, hi))
    everything = np.arange(lo.size)
    s = np.full(lo.shape, float(step))
    for _ in range(maxiter):
        below = np.asarray(f(lo, everything)).ravel() > target
        above = np.asarray(f(hi, everything)).ravel() < target
        if not (np.any(below) or np.any(above)):
            return lo.reshape(shape), hi.reshape(shape)
        lo = np.where(below, lo - s, lo)
        hi = np.where(above, hi + s, hi)
        s = np.where(below | above, 2.0 * s, s)
    raise ModelParameterError(
        f"could not bracket the root: target {target!r} not reached in [{lo!r}, {hi!r}]"
    )


def gap_low(surface, d, F):
    """g_N0 at which F̂_T = F (≤ 1/2) is reached at separations d, solved in log g."""
    # log[J(d) − J(d + e^u)] − log J(d) = log F̂_T, increasing in u = log g
    log_j = surface.log_load_integral(d)
    slope = -surface.load_integral_derivative(d) / surface.load_integral(d)

    def f(u, idx):
        with np.errstate(divide="ignore", over="ignore"):
            diff = surface.load_integral_difference(d[idx], np.exp(u))
            return np.log(diff) - log_j[idx]

    u0 = np.log(F) - np.log(slope)
    lo, hi = expand_bracket(f, np.log(F), u0 - 1.0, u0 + 1.0)
    return np.exp(monotone_root(f, np.log(F), lo, hi))


def gap_high(surface, d, F):
    """g_N0 at which F̂_T = F (> 1/2) is reached at separations d, solved in g."""
    # −log J(d + g) = −log J(d) − log(1 − F̂_T), increasing in g
    target = -surface.log_load_integral(d) - np.log1p(-F)

    def f(g, idx):
        return -surface.log_load_integral(d[idx] + g)

    lo, hi = expand_bracket(
        f, target, np.zeros_like(d), np.full_like(d, surface.sigma), step=surface.sigma
    )
    return monotone_root(f, target, lo, hi)
