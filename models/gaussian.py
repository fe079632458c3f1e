"""Rough surface with Gaussian summit heights, Φ(z) = φ(z/σ*)/σ* (Sec. 2; Greenwood–Williamson).

J(h) = σ*^{3/2} F_{3/2}(h/σ*), A(h) = σ* F_1(h/σ*), ∫_h^∞ Φ = F_0(h/σ*), with the GW integrals
of :mod:`cusp.models.gw` (≤ 1e-14 relative). J(d) − J(d0) uses ``gw_difference`` (no cancellation
for tiny slips). The slip and stick parts S, T (Eqs 10, 7) have no GW closed form: S is
integrated by adaptive quadrature (:mod:`cusp.models._quadrature`), and T = [J(d) − J(d0)] − S
while S is the smaller part, by direct quadrature of its cancellation-free bracket otherwise.

Here the stick/slip split depends on the load level (through t = d/σ*), so the ratio methods
take ``normal_load`` [N] (needs the load scale E, radius, density, nominal_area) or the mean
plane ``separation`` d [µm]. Units: lengths µm, forces N, moduli N/µm².
"""

from __future__ import annotations

import math

import numpy as np
from scipy import special as sc

from .errors import check_finite_array
from .gw import gw_difference, gw_integral, log_gw_integral, mills_ratios, normal_pdf
from .rough import RoughSurface

__all__ = ["GaussianRoughSurface"]

_EPS = float(np.finfo(float).eps)


class GaussianRoughSurface(RoughSurface):
    """Composite rough surface with Gaussian summit heights (std σ* [µm], mean 0).

    The integrals are the Greenwood–Williamson functions of :mod:`cusp.models.gw`; the
    ratios depend on the load level.

    Parameters
    ----------
    sigma : float
        Composite rms roughness σ* [µm], > 0 (the standard deviation of the heights).
    nu : float
        Poisson's ratio ν, in (−1, 0.5].
    mu : float
        Friction coefficient μ > 0.
    E, radius, density, nominal_area : float, optional
        The load scale, as for :class:`~cusp.models.RoughSurface`: E [N/µm²], ρ* [µm],
        η [1/µm²], A_n [µm²].
    """

    load_dependent = True
    support = (-math.inf, math.inf)
    breakpoints = ()

    def pdf(self, z):
        s = self.sigma
        return np.exp(-0.5 * (np.asarray(z, dtype=float) / s) ** 2) / (s * math.sqrt(2 * math.pi))

    def load_integral(self, h):
        """Return J(h) = σ*^{3/2} F_{3/2}(h/σ*).

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].

        Returns
        -------
        numpy.ndarray
            J(h) [µm^{3/2}].
        """
        h = check_finite_array("h", h, unit="µm")
        return self.sigma**1.5 * gw_integral(1.5, h / self.sigma)

    def log_load_integral(self, h):
        h = check_finite_array("h", h, unit="µm")
        return 1.5 * math.log(self.sigma) + log_gw_integral(1.5, h / self.sigma)

    def load_integral_derivative(self, h):
        """Return dJ/dh = −(3/2) σ*^{1/2} F_{1/2}(h/σ*).

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].

        Returns
        -------
        numpy.ndarray
            dJ/dh [µm^{1/2}].
        """
        h = check_finite_array("h", h, unit="µm")
        return -1.5 * math.sqrt(self.sigma) * gw_integral(0.5, h / self.sigma)

    def log_load_integral_derivative(self, h):
        """Return d log J/dh = −(3/2) F_{1/2}/(σ* F_{3/2}) at h/σ*.

        Computed from the logs: finite far in the tail, where J and dJ/dh both underflow.

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].

        Returns
        -------
        numpy.ndarray
            d log J/dh [1/µm].
        """
        h = check_finite_array("h", h, unit="µm")
        t = h / self.sigma
        return -1.5 / self.sigma * np.exp(log_gw_integral(0.5, t) - log_gw_integral(1.5, t))

    def integral_rtol(self) -> float:
        """Return the relative error bound of the GW integrals and their differences.

        Measured ≤ 2e-14 against mpmath at the exact binary t (docs/benchmarks/gw.md and
        tests/models/test_gw.py).

        Returns
        -------
        float
            The bound at given levels.
        """
        return 3e-14

    def load_integral_second_derivative(self, h):
        """Return d²J/dh² = (3/4) σ*^{−1/2} F_{−1/2}(h/σ*) (> 0).

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].

        Returns
        -------
        numpy.ndarray
            d²J/dh² [µm^{−1/2}].
        """
        h = check_finite_array("h", h, unit="µm")
        return 0.75 / math.sqrt(self.sigma) * gw_integral(-0.5, h / self.sigma)

    def log_load_integral_second_derivative(self, h):
        """Return log d²J/dh², finite far in the tail where J'' underflows.

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].

        Returns
        -------
        numpy.ndarray
            log(d²J/dh² / µm^{−1/2}).
        """
        h = check_finite_array("h", h, unit="µm")
        return math.log(0.75) - 0.5 * math.log(self.sigma) + log_gw_integral(-0.5, h / self.sigma)

    def area_integral(self, h):
        """Return A(h) = σ* F_1(h/σ*).

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].

        Returns
        -------
        numpy.ndarray
            A(h) [µm].
        """
        h = check_finite_array("h", h, unit="µm")
        return self.sigma * gw_integral(1, h / self.sigma)

    def tail_probability(self, h):
        h = check_finite_array("h", h, unit="µm")
        return sc.ndtr(-h / self.sigma)

    def load_integral_difference(self, h, g):
        h, g = self._hg(h, g)
        return self.sigma**1.5 * gw_difference(1.5, h / self.sigma, g / self.sigma)

    def area_integral_difference(self, h, g):
        """Return A(h) − A(h + g) = σ* [F_1(t) − F_1(t + x)], without cancellation.

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].
        g : array_like
            Gap ≥ 0 [µm], broadcast against ``h``.

        Returns
        -------
        numpy.ndarray
            The difference [µm].
        """
        h, g = self._hg(h, g)
        return self.sigma * gw_difference(1, h / self.sigma, g / self.sigma)

    def tail_difference(self, h, g):
        """Return ∫_h^{h+g} Φ dz = ∫_t^{t+x} φ, without cancellation.

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].
        g : array_like
            Gap ≥ 0 [µm], broadcast against ``h``.

        Returns
        -------
        numpy.ndarray
            The probability (dimensionless).
        """
        h, g = self._hg(h, g)
        return _phi_moment(0, h / self.sigma, g / self.sigma)

    def slip_area_integral(self, h, g):
        """Return ∫_h^{h+g} (z − h) Φ dz = σ* ∫_0^x v φ(t + v) dv, without cancellation.

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].
        g : array_like
            Gap ≥ 0 [µm], broadcast against ``h``.

        Returns
        -------
        numpy.ndarray
            The integral [µm]: the slipping summits' share of the real contact area (Eq 14).
        """
        h, g = self._hg(h, g)
        return self.sigma * _phi_moment(1, h / self.sigma, g / self.sigma)

    def slip_load_integral(self, h, g):
        """Return S = ∫_h^{h+g} (z − h)^{3/2} Φ dz (Eq 10), by weighted quadrature.

        The quadrature carries the (z − h)^{3/2} end-point weight (QAWS).

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].
        g : array_like
            Gap ≥ 0 [µm], broadcast against ``h``.

        Returns
        -------
        numpy.ndarray
            S [µm^{3/2}].
        """
        return super().slip_load_integral(h, g)

    def stick_load_integral(self, h, g):
        """Return the stick integral T of Eq 7.

        T = [J(h) − J(h + g)] − S while S is at most half the difference (no cancellation,
        and T ≤ J(h) − J(h + g) exactly), else by direct quadrature.

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].
        g : array_like
            Gap ≥ 0 [µm], broadcast against ``h``.

        Returns
        -------
        numpy.ndarray
            T [µm^{3/2}].
        """
        h, g = self._hg(h, g)
        diff = self.load_integral_difference(h, g)
        slip = super().slip_load_integral(h, g)
        out = diff - slip
        direct = slip > 0.5 * diff
        if np.any(direct):
            out[direct] = super().stick_load_integral(h[direct], g[direct])
        return out


#: Gauss–Legendre rule of the short φ-moments, and the exponent range it integrates exactly
_GL_X, _GL_W = np.polynomial.legendre.leggauss(20)
_GL_RANGE = 12.0


def _phi_moment(k: int, t, x) -> np.ndarray:
    """∫_0^x v^k φ(t + v) dv for k ∈ {0, 1} and x ≥ 0, to a few ulp wherever it is a normal
    number.

    φ(t + v) = φ(t) exp(E), E = −tv − v²/2: where E spans at most 12 on [0, x], 20-point
    Gauss–Legendre in v (exact to rounding); otherwise the closed forms, each taken where
    it does not cancel: k = 0, Φ(t + x) − Φ(t) left of 0, Q(t) − Q(t + x) otherwise; k = 1,
    F_1(t) − F_1(t + x) − x F_0(t + x) where t + x > 0, and left of 0 (where that cancels:
    both terms ≈ |t|) φ(t + x)[x G_0 − G_1](|t + x|) + φ(t) G_1(|t|) with the Mills ratio
    G_0 = Φ(−z)/φ(z) and G_1 = 1 − z G_0 (a continued fraction, as in :mod:`.gw`)."""
    t, x = np.broadcast_arrays(np.asarray(t, dtype=float), np.asarray(x, dtype=float))
    t1, x1 = np.atleast_1d(t).astype(float), np.atleast_1d(x).astype(float)
    e_end = -x1 * (t1 + 0.5 * x1)
    e_top = np.where((t1 < 0.0) & (-t1 < x1), 0.5 * t1 * t1, np.maximum(e_end, 0.0))
    span = e_top - np.minimum(e_end, 0.0)
    out = np.empty(t1.shape)
    short = span <= _GL_RANGE
    if np.any(short):
        ts, xs = t1[short], x1[short]
        v = 0.5 * xs[:, None] * (1.0 + _GL_X)
        f = np.exp(-v * (ts[:, None] + 0.5 * v)) * (v if k else 1.0)
        out[short] = normal_pdf(ts) * 0.5 * xs * (f @ _GL_W)
    long = ~short
    if np.any(long):
        out[long] = _phi_moment_long(k, t1[long], x1[long])
    return out.reshape(t.shape)


def _phi_moment_long(k: int, t: np.ndarray, x: np.ndarray) -> np.ndarray:
    """:func:`_phi_moment` where φ varies by more than e^12 on the interval."""
    top = t + x
    left = top <= 0.0
    if k == 0:  # (Q far right by erfcx; Φ far left by Q of the mirror image)
        q0 = gw_integral(0, np.where(left, -top, t))
        q1 = gw_integral(0, np.where(left, -t, top))
        return q0 - q1  # Φ(t + x) − Φ(t) = Q(−t − x) − Q(−t) left of 0
    out = gw_integral(1, t) - gw_integral(1, top) - x * gw_integral(0, top)
    out[left] = 0.0  # (φ(t + x) < 1e-323 beyond 38.6σ left: the moment is 0 in floats)
    near = left & (top > -38.6)
    if np.any(near):
        z1, z0 = -top[near], -t[near]
        g0_1, g1_1 = mills_ratios(z1)
        g1_0 = mills_ratios(z0)[1]
        out[near] = normal_pdf(z1) * (x[near] * g0_1 - g1_1) + normal_pdf(z0) * g1_0
    return out
