"""The contact levels of a rough surface over any height density, for the contact-loss path
(:class:`cusp.models.protocol.ContactLevels`; docs/physics.md §3 and §7).

The levels are measured from the separation d_A under F_N0, so that small differences keep
their digits: p = (d − d_A)/u, q = (d0 − d_A)/u, with u = σ*·c [µm] and c = max(1, g_A/(μλ))
(q − p of order one at A). At a slip g_A = 1e-9 µm on the Gaussian scene (σ* = 2 µm,
d_A = 2.5 µm), d0 − d is 4.1e-9 σ*: stored as absolute levels it kept ~8 digits, formed as
a difference of logs of J fewer (F_A was 2.6e-8 off). Here every relation is formed from
differences the surface evaluates without cancellation (:class:`~.rough.RoughSurface`):

* log(F_N/F_N0) = log1p(−[J(d_A) − J(d)]/J(d_A))                         (Eq 11)
* F̂_T = [J(d) − J(d0)]/J(d)                                              (Eq 9)
* g_T = μλ(d0 − d)/σ* = μ (λc)(q − p)                                    (Eqs 4–5)
* 1 − Â_ST = ∫_d^{d0} (z − d) Φ dz / A(d)  (the slipping summits' area)   (Eq 14 over 13)
* 1 − A_r/A_r(F_N0) = [A(d_A) − A(d)]/A(d_A)                              (Eq 13)

(J, A and Φ the load integral, the area integral and the height density), and the released
energies are integrals of positive integrands in the same differences (:meth:`leg_areas`,
:mod:`cusp.models._leg_areas`). The path reports d = d_A + u p and d0 = d_A + u q [µm]
(``lengths``). A rough surface never slides as a whole at finite slip (``slip_limit`` = inf).
"""

from __future__ import annotations

import functools
import math

import numpy as np

from ._leg_areas import rough_leg_areas
from .errors import ModelParameterError

__all__ = ["RoughLevels", "slip_in_mu_lambda"]

_EPS = float(np.finfo(float).eps)
#: below this J is not a normal float (far in a Gaussian tail): the ratios from logs
_TINY = 1e-290


class RoughLevels:
    """Contact levels of a rough surface over any height density (module docstring).

    ``relative_error``: a bound on the relative error of the surface's integrals at given
    levels (the GW functions' for a Gaussian surface, QUADPACK's for a general density),
    used by the error bounds of the points and the energies (which add the rounding of the
    absolute levels d = d_A + u·p through the relations' derivatives:
    :mod:`cusp.models._point_errors`). Needs the load scale (d_A is absolute).
    """

    names = ("d", "d0")
    p0 = 0.0

    def __init__(self, surf, F_N0: float, g_A: float) -> None:
        self.surf = surf
        x_A = slip_in_mu_lambda(surf, g_A)
        c = max(1.0, x_A)
        #: u [µm]
        self.scale = s = surf.sigma * c
        #: λc [µm]: g_T = μ λc (q − p)
        self.lam = surf.lam * c
        #: d_A [µm], the separation under F_N0 (raises MissingLoadScaleError without the scale)
        self.d_A = float(surf.separation(F_N0))
        self.log_jA = float(surf.log_load_integral(self.d_A))
        self.J_A = math.exp(self.log_jA)
        self.A0 = float(surf.area_integral(self.d_A))
        rtol = getattr(surf, "integral_rtol", None)
        self.relative_error = float(rtol()) if rtol is not None else 2e-13
        #: a bound on the error of d_A [µm] (the root of log J(d) = log(F_N0/K) to a few ulp,
        #: off by the error of J over d log J/dd)
        slope = abs(self._at(0.0)[1]) / s
        self.origin_error = 4.0 * _EPS * abs(self.d_A) + (
            (self.relative_error + 4.0 * _EPS) / slope if slope > 0.0 else math.inf
        )

    def lengths(self, p, q):
        """d = d_A + u p and d0 = d_A + u q [µm]."""
        return self.d_A + self.scale * p, self.d_A + self.scale * q

    def _h(self, p: float) -> float:
        return self.d_A + self.scale * p

    @functools.lru_cache(maxsize=16)  # noqa: B019 - levels live as long as their model
    def _at(self, p: float) -> tuple[float, float, float, float, float, float]:
        """(log J, d log J/dp, A, ∫_h^∞ Φ, Φ, J) at h = d_A + u·p: each integral once per
        level (a residual and its Jacobian need them at p and q, several times over)."""
        surf, h = self.surf, self._h(p)
        if hasattr(surf, "log_load_integral_derivative"):  # finite where J underflows
            dlog = float(surf.log_load_integral_derivative(h))
        else:
            J = float(surf.load_integral(h))
            dlog = float(surf.load_integral_derivative(h)) / J if J > 0.0 else math.nan
        log_j = float(surf.log_load_integral(h))
        return (
            log_j,
            self.scale * dlog,
            float(surf.area_integral(h)),
            float(surf.tail_probability(h)),
            float(surf.pdf(h)),
            math.exp(log_j),
        )

    @functools.lru_cache(maxsize=16)  # noqa: B019
    def _load_difference(self, h: float, w: float) -> float:
        """J(h) − J(h + w) for w of either sign (a trial point may have q < p)."""
        if w >= 0.0:
            return float(self.surf.load_integral_difference(h, w))
        return -float(self.surf.load_integral_difference(h + w, -w))

    def log_normal_load(self, p: float) -> tuple[float, float]:
        """log(F_N/F_N0) = log1p(−[J(d_A) − J(d)]/J(d_A)) and its derivative (Eq 11)."""
        j, dj = self._at(p)[:2]
        if self.J_A < _TINY:
            return j - self.log_jA, dj
        r = self._load_difference(self.d_A, self.scale * p) / self.J_A
        value = math.log1p(-r) if r < 0.5 else j - self.log_jA
        return value, dj

    def tangential_ratio(self, p: float, q: float) -> tuple[float, float, float]:
        """F̂_T = [J(d) − J(d0)]/J(d) and its derivatives (Eq 9)."""
        jp, djp, *_, Jp = self._at(p)
        jq, djq = self._at(q)[:2]
        if Jp < _TINY:
            value = -math.expm1(jq - jp)
        else:
            value = self._load_difference(self._h(p), self.scale * (q - p)) / Jp
        e = 1.0 - value if value < 0.5 else math.exp(jq - jp)  # J(d0)/J(d)
        # (J(d0) below the floats: its term is 0, and d log J/dh there is not computed, NaN,
        # for a density without log-space integrals: a Weibull surface at g_A = 1e3 μλ)
        return value, e * djp, -e * djq if e > 0.0 else 0.0

    def slip(self, p: float, q: float) -> tuple[float, float, float]:
        """g_T/μ = λc (q − p) [µm] and its derivatives (Eqs 4–5)."""
        return self.lam * (q - p), -self.lam, self.lam

    def stick_area(self, p: float, q: float) -> tuple[float, float, float]:
        """Â_ST = [A(d0) + (d0 − d) Q(d0)]/A(d) and its derivatives (Eqs 13–14)."""
        s = self.scale
        _, _, den, tail, *_ = self._at(p)
        _, _, area0, tail0, pdf0, _ = self._at(q)
        num = area0 + s * (q - p) * tail0
        val = num / den
        dnum_p = -s * tail0
        dnum_q = -s * s * (q - p) * pdf0
        return val, (dnum_p + val * s * tail) / den, dnum_q / den

    def slip_area(self, p: float, q: float) -> tuple[float, float, float]:
        """1 − Â_ST = ∫_d^{d0} (z − d) Φ dz / A(d) (the slipping summits' share of the real
        contact area) and its derivatives: ≈ x² at small slips x, where forming it from Â_ST
        kept only ~ε/x² of its digits (Â_SL at A was 6e-2 off at g_A = 1e-8 µm)."""
        s, h = self.scale, self._h(p)
        w = s * (q - p)
        _, _, den, tail, *_ = self._at(p)
        surf = self.surf
        if w < 0.0:  # a trial point off the path (d0 < d): ∫_{d0}^{d} (d − z) Φ dz / A(d), the
            # formula's continuation, also without cancellation (a start at O is not noisy)
            val = float(-w * surf.tail_difference(h + w, -w) - surf.slip_area_integral(h + w, -w))
            _, dp, dq = self.stick_area(p, q)
            return val / den, -dp, -dq
        num = float(surf.slip_area_integral(h, w))
        between = float(surf.tail_difference(h, w))  # ∫_d^{d0} Φ
        pdf0 = self._at(q)[4]
        val = num / den
        return val, s * (val * tail - between) / den, s * w * pdf0 / den

    def area_loss(self, p: float) -> tuple[float, float]:
        """1 − A_r/A_r(F_N0) = [A(d_A) − A(d)]/A(d_A) and its derivative."""
        s = self.scale
        delta = s * p
        surf = self.surf
        if delta >= 0.0:
            loss = float(surf.area_integral_difference(self.d_A, delta))
        else:
            loss = -float(surf.area_integral_difference(self.d_A + delta, -delta))
        return loss / self.A0, s * self._at(p)[3] / self.A0

    def area_ratio(self, p: float) -> tuple[float, float]:
        """A_r/A_r(F_N0) = A(d)/A(d_A) and its derivative (Eq 13)."""
        _, _, area, tail, *_ = self._at(p)
        return area / self.A0, -self.scale * tail / self.A0

    def slip_limit(self, p: float) -> float:
        """inf: a rough surface does not slide as a whole at finite slip."""
        return math.inf

    def curvature(self, y: np.ndarray) -> np.ndarray:
        """u² J''(d_A + u y)/J(d_A) at levels ``y`` (the integrand of :meth:`leg_areas`)."""
        h = self.d_A + self.scale * np.asarray(y, dtype=float)
        log_j2 = np.asarray(self.surf.log_load_integral_second_derivative(h), dtype=float)
        return self.scale**2 * np.exp(log_j2 - self.log_jA)

    def slope(self, y: np.ndarray) -> np.ndarray:
        """−u J'(d_A + u y)/J(d_A) at levels ``y`` (the integrand of :meth:`leg_areas`)."""
        h = self.d_A + self.scale * np.asarray(y, dtype=float)
        surf = self.surf
        log_j = np.asarray(surf.log_load_integral(h), dtype=float)
        if hasattr(surf, "log_load_integral_derivative"):
            dlog = np.asarray(surf.log_load_integral_derivative(h), dtype=float)
        elif self.J_A >= _TINY:  # (J' directly: J'/J is 0/0 where J underflows)
            return (
                -self.scale * np.asarray(surf.load_integral_derivative(h), dtype=float) / self.J_A
            )
        else:
            dlog = np.asarray(surf.load_integral_derivative(h), dtype=float) / np.exp(log_j)
        return -self.scale * dlog * np.exp(log_j - self.log_jA)

    def leg_areas(self, p_A, q_A, p_B, q_D, q_C, level_rtol, *, quad_tol=1e-13, errors=None):
        """The released areas ABD and ABC − ABD as ∫ T ds between the legs [µm], each with an
        error bound, by :func:`cusp.models._leg_areas.rough_leg_areas` (integrals of
        J''·(weights) and −J'·(weights), positive integrands in the differences between
        the levels). ``errors``: the absolute errors of (p_A, q_A, p_B, q_D, q_C), else
        ``level_rtol`` of each level's size."""
        return rough_leg_areas(self, p_A, q_A, p_B, q_C, level_rtol, quad_tol, errors)


def slip_in_mu_lambda(surf, g_A: float) -> float:
    """x_A = g_A/(μλ) (formed without μλ, which can underflow), or a ModelParameterError when
    it is beyond the float range (a σ* or μ so small that the levels cannot be scaled)."""
    with np.errstate(over="ignore"):
        x = float((g_A / surf.sigma) * surf._sigma_over_lam / surf.mu)
    if not math.isfinite(x):
        raise ModelParameterError(
            f"sigma = {surf.sigma!r} µm and mu = {surf.mu!r} with max_slip = {g_A!r} µm give "
            f"g_A/(mu lambda) beyond the float range: the contact-loss path cannot be scaled; "
            f"choose sigma and mu with max_slip/(mu sigma) < 1e300"
        )
    return x
