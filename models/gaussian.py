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
from .gw import gw_difference, gw_integral, log_gw_integral
from .rough import RoughSurface

__all__ = ["GaussianRoughSurface"]


class GaussianRoughSurface(RoughSurface):
    """Composite rough surface with Gaussian summit heights (std σ* [µm], mean 0).

    ``GaussianRoughSurface(sigma, nu, mu, E=None, radius=None, density=None,
    nominal_area=None)``; see :class:`cusp.models.rough.RoughSurface` for the parameters.
    """

    load_dependent = True
    support = (-math.inf, math.inf)
    breakpoints = ()

    def pdf(self, z):
        s = self.sigma
        return np.exp(-0.5 * (np.asarray(z, dtype=float) / s) ** 2) / (s * math.sqrt(2 * math.pi))

    def load_integral(self, h):
        """J(h) = σ*^{3/2} F_{3/2}(h/σ*)  [µm^{3/2}]."""
        h = check_finite_array("h", h, unit="µm")
        return self.sigma**1.5 * gw_integral(1.5, h / self.sigma)

    def log_load_integral(self, h):
        h = check_finite_array("h", h, unit="µm")
        return 1.5 * math.log(self.sigma) + log_gw_integral(1.5, h / self.sigma)

    def load_integral_derivative(self, h):
        """dJ/dh = −(3/2) σ*^{1/2} F_{1/2}(h/σ*)  [µm^{1/2}]."""
        h = check_finite_array("h", h, unit="µm")
        return -1.5 * math.sqrt(self.sigma) * gw_integral(0.5, h / self.sigma)

    def log_load_integral_derivative(self, h):
        """d log J/dh = −(3/2) F_{1/2}/(σ* F_{3/2}) at h/σ*  [1/µm], from the logs (finite
        far in the tail, where J and dJ/dh both underflow)."""
        h = check_finite_array("h", h, unit="µm")
        t = h / self.sigma
        return -1.5 / self.sigma * np.exp(log_gw_integral(0.5, t) - log_gw_integral(1.5, t))

    def area_integral(self, h):
        """A(h) = σ* F_1(h/σ*)  [µm]."""
        h = check_finite_array("h", h, unit="µm")
        return self.sigma * gw_integral(1, h / self.sigma)

    def tail_probability(self, h):
        h = check_finite_array("h", h, unit="µm")
        return sc.ndtr(-h / self.sigma)

    def load_integral_difference(self, h, g):
        h, g = self._hg(h, g)
        return self.sigma**1.5 * gw_difference(1.5, h / self.sigma, g / self.sigma)

    def slip_load_integral(self, h, g):
        """S = ∫_h^{h+g} (z − h)^{3/2} Φ dz  [µm^{3/2}], by quadrature with the (z − h)^{3/2}
        end-point weight (QAWS)."""
        return super().slip_load_integral(h, g)

    def stick_load_integral(self, h, g):
        """T (Eq 7) [µm^{3/2}]: [J(h) − J(h + g)] − S while S is at most half the difference
        (no cancellation, and T ≤ J(h) − J(h + g) exactly), else by direct quadrature."""
        h, g = self._hg(h, g)
        diff = self.load_integral_difference(h, g)
        slip = super().slip_load_integral(h, g)
        out = diff - slip
        direct = slip > 0.5 * diff
        if np.any(direct):
            out[direct] = super().stick_load_integral(h[direct], g[direct])
        return out
