"""The integrals of a summit-height density Φ over the contact (paper Eqs 7–14), by adaptive
quadrature over ``self.pdf`` (:mod:`cusp.models._quadrature`, imported when first used): the
defaults of every :class:`~cusp.models.RoughSurface`, which closed-form densities override.
Lengths in µm."""

from __future__ import annotations

import numpy as np

from .errors import check_finite_array

__all__ = ["HeightIntegrals"]


class HeightIntegrals:
    """The density integrals of a rough surface (a base of :class:`~cusp.models.RoughSurface`).

    A subclass defines ``pdf(z)``; the integrals here evaluate it by quadrature.
    """

    def load_integral(self, h):
        """Return the load integral J(h) = ∫_h^∞ (z − h)^{3/2} Φ(z) dz.

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].

        Returns
        -------
        numpy.ndarray
            J(h) [µm^{3/2}].
        """
        from ._quadrature import moment

        return moment(self, 1.5, check_finite_array("h", h, unit="µm"))

    def log_load_integral(self, h):
        """Return log J(h) (J in µm^{3/2}).

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].

        Returns
        -------
        numpy.ndarray
            log(J / µm^{3/2}).
        """
        with np.errstate(divide="ignore"):
            return np.log(self.load_integral(h))

    def load_integral_derivative(self, h):
        """Return dJ/dh = −(3/2) ∫_h^∞ (z − h)^{1/2} Φ dz.

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].

        Returns
        -------
        numpy.ndarray
            dJ/dh [µm^{1/2}].
        """
        from ._quadrature import moment

        return -1.5 * moment(self, 0.5, check_finite_array("h", h, unit="µm"))

    def area_integral(self, h):
        """Return the area integral A(h) = ∫_h^∞ (z − h) Φ(z) dz.

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].

        Returns
        -------
        numpy.ndarray
            A(h) [µm].
        """
        from ._quadrature import moment

        return moment(self, 1.0, check_finite_array("h", h, unit="µm"))

    def tail_probability(self, h):
        """Return the tail probability ∫_h^∞ Φ(z) dz.

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].

        Returns
        -------
        numpy.ndarray
            The probability (dimensionless).
        """
        from ._quadrature import moment

        return moment(self, 0.0, check_finite_array("h", h, unit="µm"))

    def slip_load_integral(self, h, g):
        """Return S(h, g) = ∫_h^{h+g} (z − h)^{3/2} Φ dz, the sliding summits (Eq 10).

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
        from ._quadrature import slip_integral

        return slip_integral(self, *self._hg(h, g))

    def stick_load_integral(self, h, g):
        """Return T(h, g) = ∫_{h+g}^∞ [(z − h)^{3/2} − (z − h − g)^{3/2}] Φ dz (Eq 7).

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
        from ._quadrature import stick_integral

        return stick_integral(self, *self._hg(h, g))

    def load_integral_difference(self, h, g):
        """Return J(h) − J(h + g) = S + T ≥ 0, without cancellation for tiny g.

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].
        g : array_like
            Gap ≥ 0 [µm], broadcast against ``h``.

        Returns
        -------
        numpy.ndarray
            The difference [µm^{3/2}].
        """
        h, g = self._hg(h, g)
        return self.slip_load_integral(h, g) + self.stick_load_integral(h, g)

    def load_integral_second_derivative(self, h):
        """Return d²J/dh² = (3/4) ∫_h^∞ (z − h)^{−1/2} Φ dz > 0.

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].

        Returns
        -------
        numpy.ndarray
            d²J/dh² [µm^{−1/2}].
        """
        from ._quadrature import moment

        return 0.75 * moment(self, -0.5, check_finite_array("h", h, unit="µm"))

    def log_load_integral_second_derivative(self, h):
        """Return log d²J/dh² (J'' in µm^{−1/2}).

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].

        Returns
        -------
        numpy.ndarray
            log(J'' / µm^{−1/2}).
        """
        with np.errstate(divide="ignore"):
            return np.log(self.load_integral_second_derivative(h))

    def slip_area_integral(self, h, g):
        """Return ∫_h^{h+g} (z − h) Φ dz, without cancellation.

        It is the slipping summits' share of the real contact area over π ρ* η A_n (A(h)
        minus the stick area of Eq 14).

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].
        g : array_like
            Gap ≥ 0 [µm], broadcast against ``h``.

        Returns
        -------
        numpy.ndarray
            The integral [µm].
        """
        from ._quadrature import slip_integral

        h, g = self._hg(h, g)
        return slip_integral(self, h, g, k=1.0)

    def tail_difference(self, h, g):
        """Return ∫_h^{h+g} Φ dz, without cancellation for tiny g.

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
        from ._quadrature import slip_integral

        h, g = self._hg(h, g)
        return slip_integral(self, h, g, k=0.0)

    def area_integral_difference(self, h, g):
        """Return A(h) − A(h + g) = ∫_h^{h+g} (z − h) Φ dz + g ∫_{h+g}^∞ Φ dz ≥ 0.

        The two terms are nonnegative: no cancellation.

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
        return self.slip_area_integral(h, g) + g * self.tail_probability(h + g)

    def integral_rtol(self) -> float:
        """Return a bound on the relative error of this surface's integrals.

        QUADPACK is asked for 1.2e-14, measured up to 1.4e-13 on Weibull densities; the
        bounds of the path's points and energies use it.

        Returns
        -------
        float
            The relative error bound.
        """
        return 2e-13

    @staticmethod
    def _hg(h, g):
        """``h`` and ``g`` [µm] checked (finite; g ≥ 0) and broadcast."""
        h = check_finite_array("h", h, unit="µm")
        g = check_finite_array("g", g, lower=0.0, unit="µm")
        h, g = np.broadcast_arrays(h, g)
        return np.array(h), np.array(g)
