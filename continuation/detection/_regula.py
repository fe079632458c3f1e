"""Locating the zero of a test function along a step's arc by the Illinois variant of
regula falsi (events, branch points before their Newton, and anything without a Newton of
its own), each evaluation a corrected point of the curve."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from .._outcomes import Convergence, PointStatus
from ..numerics._linalg import max_abs
from ._bracket import _EPS, Bracket, Located

#: a bracket that did not halve in this many tries is bisected instead
_TRIES = 3

#: a bracket closed to this fraction of the step whose ends' values exceed ten times the
#: step's ends' is a pole (it needs no closer bracket)
_POLE_WIDTH = 1e-3


class _Illinois:
    """The bracket ``[lo, hi]`` of pseudo-arclengths with the (Illinois-scaled) values
    ``flo``, ``fhi`` at its ends, the unscaled magnitudes ``raw`` there, and which end moved
    last (``side``)."""

    __slots__ = ("lo", "hi", "flo", "fhi", "raw", "side", "widths")

    def __init__(self, h: float, f_a: float, f_b: float) -> None:
        self.lo, self.hi, self.flo, self.fhi = 0.0, h, f_a, f_b
        self.raw = [abs(f_a), abs(f_b)]
        self.side = 0
        self.widths = [math.inf] * _TRIES  # the bracket's width before each try

    def next(self) -> float:
        """The next trial: the secant's zero, or the midpoint where the bracket did not
        halve in three tries (one end's value is tiny next to the other's, as the
        determinant's a rounding away from a branch point, and the Illinois halving needs a
        hundred tries to catch up)."""
        lo, hi = self.lo, self.hi
        sigma = (lo * self.fhi - hi * self.flo) / (self.fhi - self.flo)
        width = abs(hi - lo)
        if width > 0.5 * self.widths[-_TRIES] or not min(lo, hi) < sigma < max(lo, hi):
            sigma = 0.5 * (lo + hi)
        self.widths.append(width)
        return sigma

    def update(self, sigma: float, fz: float) -> None:
        """The bracket after the value ``fz`` at ``sigma`` (the other end's value halved
        when the same end moves twice: Illinois)."""
        if np.sign(fz) == np.sign(self.flo):
            self.lo, self.flo, self.raw[0] = sigma, fz, abs(fz)
            if self.side == -1:
                self.fhi *= 0.5
            self.side = -1
        else:
            self.hi, self.fhi, self.raw[1] = sigma, fz, abs(fz)
            if self.side == 1:
                self.flo *= 0.5
            self.side = 1

    @property
    def interval(self) -> tuple[float, float]:
        return (self.lo, self.hi)


def locate_on_arc(
    br: Bracket,
    f: Callable[[np.ndarray], Any],
    f_a: float,
    f_b: float,
    rtol: float | None = None,
) -> Located:
    """The zero of ``f(z)`` along the arc of ``br`` (``f_a``, ``f_b``: its values at the
    step's ends) by Illinois regula falsi on the pseudo-arclength, to ``rtol`` (default
    ``locate_tol``) relative to the step. A trial point where the corrector's matrix is
    exactly singular, on the curve already (residual within tolerance), is taken as the
    zero itself: it is the singular point the test function looks for (a branch point).

    A sign change through infinity (a pole: a test function or event with a denominator
    that crosses zero along the curve) is not a zero: where the values at both ends of the
    closed bracket exceed those at the step's ends in magnitude, the result has status
    ``"pole"`` and marks no special point."""
    o = br.options
    xtol = (o.locate_tol if rtol is None else rtol) * abs(br.h) + 4 * _EPS * abs(br.h)
    ends = max(abs(f_a), abs(f_b))
    bracket = _Illinois(br.h, f_a, f_b)
    best = None
    it = 0
    for it in range(1, o.max_locate_iterations + 1):
        sigma = bracket.next()
        res = br.point_at(sigma)
        if not res.converged and res.reason == Convergence.SINGULAR and res.residual_norm <= o.tol:
            details = {"method": "Illinois", "test_values": (0.0, 0.0), "singular_trial": True}
            return _located(res.z, sigma, PointStatus.CONVERGED, it, details)
        z = res.z
        if not res.converged:
            # next to a branch point the corrector's matrix is singular to rounding and its
            # update is noise (a residual at rounding level over σ_min ~ ε): the arc's own
            # point serves if it lies on the curve to tolerance
            z = br.arc.at(sigma / br.h)
            if not max_abs(br.system.residual(z)) <= o.tol:
                break
        fz = f(z)
        best = (z, sigma)
        if fz == 0.0:
            details = {"method": "Illinois", "test_values": (0.0, 0.0)}
            return _located(br.polish(z, sigma), sigma, PointStatus.CONVERGED, it, details)
        bracket.update(sigma, fz)
        found = _closed(br, bracket, z, sigma, it, xtol, ends)
        if found is not None:
            return found
    return _unclosed(br, bracket, best, it, ends)


def _closed(
    br: Bracket,
    bracket: _Illinois,
    z: np.ndarray,
    sigma: float,
    it: int,
    xtol: float,
    ends: float,
) -> Located | None:
    """The located point once the bracket is closed (to ``xtol``, or closing on a pole);
    None while it is open."""
    width, raw = abs(bracket.hi - bracket.lo), min(bracket.raw)
    closing = width <= _POLE_WIDTH * abs(br.h)  # (a pole needs no closer bracket)
    if (closing and raw > 10.0 * ends) or (width <= xtol and raw > ends):
        details = {"method": "Illinois", "interval": bracket.interval, "pole": True}
        return _located(z, sigma, PointStatus.POLE, it, details)
    if width <= xtol:
        details = {
            "method": "Illinois",
            "interval": bracket.interval,
            "test_values": (float(bracket.flo), float(bracket.fhi)),
        }
        return _located(br.polish(z, sigma), sigma, PointStatus.CONVERGED, it, details)
    return None


def _unclosed(br: Bracket, bracket: _Illinois, best: tuple | None, it: int, ends: float) -> Located:
    """The estimate where the bracket did not close within the iterations (or a trial left
    the curve): a pole if its ends' values exceed the step's, else a guess."""
    interval = bracket.interval
    if best is not None and min(bracket.raw) > ends:
        details = {"interval": interval, "pole": True}
        return _located(best[0], best[1], PointStatus.POLE, it, details)
    if best is None:
        sigma = 0.5 * (bracket.lo + bracket.hi)
        z = br.arc.at(sigma / br.h)
        return _located(z, sigma, PointStatus.GUESS, it, {"interval": interval})
    details = {"method": "Illinois", "interval": interval}
    return _located(best[0], best[1], PointStatus.GUESS, it, details)


def _located(
    z: np.ndarray, sigma: float, status: PointStatus, it: int, details: dict[str, Any]
) -> Located:
    return Located(z=z, sigma=sigma, status=status, iterations=it, details=details)


__all__ = ["locate_on_arc"]
