"""Locating the zero of a test function along a step's arc by the Illinois variant of
regula falsi (events, branch points before their Newton, and anything without a Newton of
its own), each evaluation a corrected point of the curve."""

from __future__ import annotations

import math

import numpy as np

from ..numerics._linalg import max_abs
from ._bracket import _EPS, Bracket, Located


def locate_on_arc(br: Bracket, f, f_a: float, f_b: float, rtol: float | None = None) -> Located:
    """Zero of ``f(z)`` along the arc by Illinois regula falsi on the pseudo-arclength, to
    ``rtol`` (default ``locate_tol``) relative to the step. A trial point where the
    corrector's matrix is exactly singular, on the curve already (residual within
    tolerance), is taken as the zero itself: it is the singular point the test function
    looks for (a branch point).

    A sign change through infinity (a pole: a test function or event with a denominator
    that crosses zero along the curve) is not a zero: where the values at both ends of the
    closed bracket exceed those at the step's ends in magnitude, the result has status
    ``"pole"`` and marks no special point."""
    o = br.options
    lo, hi, flo, fhi = 0.0, br.h, f_a, f_b
    raw = [abs(f_a), abs(f_b)]  # |f| at the bracket's ends (flo and fhi are Illinois-scaled)
    xtol = (o.locate_tol if rtol is None else rtol) * abs(br.h) + 4 * _EPS * abs(br.h)
    side = 0
    best = None
    it = 0
    widths = [math.inf, math.inf, math.inf]  # the bracket's width before each try
    for it in range(1, o.max_locate_iterations + 1):
        sigma = (lo * fhi - hi * flo) / (fhi - flo)
        width = abs(hi - lo)
        if width > 0.5 * widths[-3] or not min(lo, hi) < sigma < max(lo, hi):
            # the bracket did not halve in three tries (one end's value is tiny next to the
            # other's, as the determinant's a rounding away from a branch point, and the
            # Illinois halving needs a hundred tries to catch up): bisect
            sigma = 0.5 * (lo + hi)
        widths.append(width)
        res = br.point_at(sigma)
        if not res.converged and res.reason == "singular" and res.residual_norm <= o.tol:
            details = {"method": "Illinois", "test_values": (0.0, 0.0), "singular_trial": True}
            return Located(res.z, sigma, "converged", it, details)
        z = res.z
        if not res.converged:
            # next to a branch point the corrector's matrix is singular to rounding and its
            # update is noise (a residual at rounding level over σ_min ~ ε): the arc's own
            # point serves if it lies on the curve to tolerance
            z = br.guess(sigma / br.h)
            if not max_abs(br.system.residual(z)) <= o.tol:
                break
        fz = f(z)
        best = (z, sigma)
        if fz == 0.0:
            return Located(
                br.polish(z, sigma),
                sigma,
                "converged",
                it,
                {"method": "Illinois", "test_values": (0.0, 0.0)},
            )
        if np.sign(fz) == np.sign(flo):
            lo, flo, raw[0] = sigma, fz, abs(fz)
            if side == -1:
                fhi *= 0.5
            side = -1
        else:
            hi, fhi, raw[1] = sigma, fz, abs(fz)
            if side == 1:
                flo *= 0.5
            side = 1
        ends = max(abs(f_a), abs(f_b))
        closing = abs(hi - lo) <= 1e-3 * abs(br.h)  # (a pole needs no closer bracket)
        if (closing and min(raw) > 10.0 * ends) or (abs(hi - lo) <= xtol and min(raw) > ends):
            details = {"method": "Illinois", "interval": (lo, hi), "pole": True}
            return Located(z, sigma, "pole", it, details)
        if abs(hi - lo) <= xtol:
            return Located(
                br.polish(z, sigma),
                sigma,
                "converged",
                it,
                {
                    "method": "Illinois",
                    "interval": (lo, hi),
                    "test_values": (float(flo), float(fhi)),
                },
            )
    if best is not None and min(raw) > max(abs(f_a), abs(f_b)):
        return Located(best[0], best[1], "pole", it, {"interval": (lo, hi), "pole": True})
    if best is None:
        sigma = 0.5 * (lo + hi)
        return Located(br.guess(sigma / br.h), sigma, "guess", it, {"interval": (lo, hi)})
    return Located(best[0], best[1], "guess", it, {"method": "Illinois", "interval": (lo, hi)})


__all__ = ["locate_on_arc"]
