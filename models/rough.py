"""Shared machinery of a rough surface over a summit-height density Φ (paper Sec. 2, Eqs 1–15).

A composite rough surface (rms roughness σ* [µm], Poisson ratio ν, friction coefficient μ)
presses on a rigid flat at mean-plane separation d [µm]. Summits of height z > d touch with
closure w = z − d (Hertz, Eq 3); under a tangential slip g_T [µm] a summit sticks iff
w ≥ g_N0 = 2(1 − ν) g_T / (μ (2 − ν)) (Eq 5). Summed over Φ (Eqs 7–14), with d0 = d + g_N0:

* load integral   J(h) = ∫_h^∞ (z − h)^{3/2} Φ(z) dz                [µm^{3/2}]
* area integral   A(h) = ∫_h^∞ (z − h) Φ(z) dz                      [µm]
* normal load     F_N = K J(d), K = (4/3) E* √ρ* η A_n              [N]
* real area       A_r = π ρ* η A_n A(d)                             [µm²]
* tangential load F_T = μ K [J(d) − J(d0)] = μ K (S + T)           [N]
* slip part       S = ∫_d^{d0} (z − d)^{3/2} Φ dz                    (Eq 10)
* stick part      T = ∫_{d0}^∞ [(z − d)^{3/2} − (z − d0)^{3/2}] Φ dz  (Eq 7)
* stick area      A_ST = π ρ* η A_n [A(d0) + g_N0 ∫_{d0}^∞ Φ dz]      (Eq 14)

so F̂_T = (S + T)/J(d), F̂_ST = T/J(d), Â_ST = A_ST/A_r. All three are sums of nonnegative
terms: nothing here subtracts nearly equal numbers.

Composite conventions (Johnson 1985, two identical bodies of modulus E [N/µm²]):
E* = E / [2(1 − ν²)], G = E / [2(1 + ν)], ρ* the composite summit radius [µm], η the summit
density [1/µm²] and A_n the nominal area [µm²]. With these, Eq 2 per summit reduces to Eq 4
with λ = σ* (2 − ν) / [2(1 − ν)] [µm].

Subclasses supply the density-specific integrals; the defaults here integrate a pdf by
adaptive quadrature (imported lazily, only when a default is actually used).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, cast

import numpy as np

from ._height_integrals import HeightIntegrals
from ._roots import expand_bracket, gap_high, gap_low, monotone_root
from .errors import (
    GrossSlidingError,
    MissingLoadScaleError,
    ModelParameterError,
    check_finite_array,
    check_poisson,
    check_positive,
    check_ratio,
)
from .rough_levels import RoughLevels, slip_in_mu_lambda

if TYPE_CHECKING:
    from .protocol import ContactLevels

__all__ = ["RoughSurface", "RoughLevels", "monotone_root", "slip_in_mu_lambda"]

_LOAD_SCALE_KEYS = ("E", "radius", "density", "nominal_area")


class RoughSurface(HeightIntegrals):
    """A composite rough surface on a rigid flat (base class; see module docstring).

    E, radius, density and nominal_area form the load scale K, needed only for absolute d,
    F_N and A_r (:class:`~cusp.models.MissingLoadScaleError` otherwise).

    Parameters
    ----------
    sigma : float
        Composite rms roughness σ* [µm], > 0.
    nu : float
        Poisson's ratio ν, in (−1, 0.5].
    mu : float
        Friction coefficient μ > 0.
    E : float, optional
        Young's modulus of each body [N/µm²]; E* = E/[2(1 − ν²)].
    radius : float, optional
        Composite summit radius ρ* [µm].
    density : float, optional
        Summit density η [1/µm²].
    nominal_area : float, optional
        Nominal contact area A_n [µm²].
    """

    #: does the stick/slip split depend on the load level (False only for the exponential)?
    load_dependent = True

    def __init__(
        self,
        sigma: float,
        nu: float,
        mu: float,
        E: float | None = None,
        radius: float | None = None,
        density: float | None = None,
        nominal_area: float | None = None,
    ) -> None:
        self.sigma = check_positive("sigma", sigma, "µm")
        self.nu = check_poisson(nu)
        self.mu = check_positive("mu", mu)
        #: λ = σ* (2 − ν) / [2 (1 − ν)]  [µm]  (Eq 4)
        self.lam = self.sigma * (2.0 - self.nu) / (2.0 * (1.0 - self.nu))
        # σ*/λ = 2(1 − ν)/(2 − ν), of order one: g_N0 = g_T (σ*/λ)/μ without forming μλ,
        # which underflows for tiny σ* and μ
        self._sigma_over_lam = 2.0 * (1.0 - self.nu) / (2.0 - self.nu)
        given = {"E": E, "radius": radius, "density": density, "nominal_area": nominal_area}
        units = {"E": "N/µm²", "radius": "µm", "density": "1/µm²", "nominal_area": "µm²"}
        for key, value in given.items():
            if value is not None:
                given[key] = check_positive(key, value, units[key])
        self.E = given["E"]
        self.radius = given["radius"]
        self.density = given["density"]
        self.nominal_area = given["nominal_area"]

    # ---------------------------------------------------------------- load scale
    @property
    def has_load_scale(self) -> bool:
        """Whether E, radius, density and nominal_area are all given."""
        return all(getattr(self, k) is not None for k in _LOAD_SCALE_KEYS)

    def _require_load_scale(self, what: str) -> None:
        missing = [k for k in _LOAD_SCALE_KEYS if getattr(self, k) is None]
        if missing:
            raise MissingLoadScaleError(
                f"{what} needs the load scale K = (4/3) E* sqrt(radius) density nominal_area; "
                f"missing parameter(s): {', '.join(missing)} (pass them to "
                f"{type(self).__name__}(...)). Ratios and the loading curve of the exponential "
                f"surface need none of them."
            )

    def _load_scale_values(self, what: str) -> tuple[float, float, float, float]:
        """``(E, radius, density, nominal_area)``, all given (else MissingLoadScaleError)."""
        self._require_load_scale(what)
        return (
            cast(float, self.E),
            cast(float, self.radius),
            cast(float, self.density),
            cast(float, self.nominal_area),
        )

    @property
    def E_star(self) -> float:
        """E* = E / [2 (1 − ν²)]  [N/µm²] (two identical bodies)."""
        E = self._load_scale_values("E_star")[0]
        return E / (2.0 * (1.0 - self.nu**2))

    @property
    def load_scale(self) -> float:
        """K = (4/3) E* √ρ* η A_n  [N/µm^{3/2}], so that F_N = K J(d)."""
        _, radius, density, nominal_area = self._load_scale_values("the load scale")
        return 4.0 / 3.0 * self.E_star * math.sqrt(radius) * density * nominal_area

    @property
    def area_scale(self) -> float:
        """The area scale π ρ* η A_n [µm], so that A_r = area_scale · A(d)."""
        _, radius, density, nominal_area = self._load_scale_values("the real contact area")
        return math.pi * radius * density * nominal_area

    # ---------------------------------------------------------------- density integrals
    # Defaults by quadrature over self.pdf (HeightIntegrals); closed-form subclasses override.
    def pdf(self, z):
        """Return Φ(z) [1/µm], the summit-height density (each density defines it).

        Parameters
        ----------
        z : array_like
            Heights [µm].

        Returns
        -------
        numpy.ndarray
            Φ(z) [1/µm].
        """
        raise NotImplementedError(f"{type(self).__name__} defines no height density pdf(z)")

    # ---------------------------------------------------------------- normal contact
    def normal_load(self, d):
        """Return the normal load F_N(d) = K J(d) (Eq 11).

        Parameters
        ----------
        d : array_like
            Mean-plane separation [µm].

        Returns
        -------
        numpy.ndarray
            F_N [N].

        Raises
        ------
        MissingLoadScaleError
            E, radius, density or nominal_area not given.
        """
        return self.load_scale * self.load_integral(d)

    def normal_load_derivative(self, d):
        """Return dF_N/dd = K J'(d) (negative).

        Parameters
        ----------
        d : array_like
            Mean-plane separation [µm].

        Returns
        -------
        numpy.ndarray
            dF_N/dd [N/µm].

        Raises
        ------
        MissingLoadScaleError
            E, radius, density or nominal_area not given.
        """
        return self.load_scale * self.load_integral_derivative(d)

    def real_contact_area(self, d):
        """Return the real contact area A_r(d) = π ρ* η A_n ∫_d^∞ (z − d) Φ dz (Eq 13).

        Parameters
        ----------
        d : array_like
            Mean-plane separation [µm].

        Returns
        -------
        numpy.ndarray
            A_r [µm²].

        Raises
        ------
        MissingLoadScaleError
            E, radius, density or nominal_area not given.
        """
        return self.area_scale * self.area_integral(d)

    def separation(self, F_N):
        """Return the mean-plane separation d carrying the normal load F_N (root of Eq 11).

        Parameters
        ----------
        F_N : array_like
            Normal load [N], > 0.

        Returns
        -------
        numpy.ndarray
            d [µm].

        Raises
        ------
        MissingLoadScaleError
            E, radius, density or nominal_area not given.
        ModelParameterError
            A load ≤ 0 or not finite.
        """
        F_N = check_finite_array("F_N", F_N, unit="N")
        if np.any(F_N <= 0.0):
            raise ModelParameterError(f"F_N must be > 0 [N], got {F_N!r}")
        target = np.log(F_N / self.load_scale)
        return self._separation_from_log_j(target)

    def _separation_from_log_j(self, log_j_target):
        # −log J is increasing in h
        def f(h, idx):
            return -self.log_load_integral(h)

        c0 = self._center()
        lo, hi = expand_bracket(f, -log_j_target, c0 - self.sigma, c0 + self.sigma, step=self.sigma)
        return monotone_root(f, -log_j_target, lo, hi)

    def _center(self) -> float:
        return 0.0

    # ---------------------------------------------------------------- tangential contact
    def stick_threshold(self, g_T):
        """Return the stick threshold g_N0 = 2 (1 − ν) g_T / [μ (2 − ν)] = g_T σ*/(μ λ) (Eq 5).

        Parameters
        ----------
        g_T : array_like
            Tangential slip [µm], ≥ 0.

        Returns
        -------
        numpy.ndarray
            g_N0 [µm].
        """
        g_T = check_finite_array("g_T", g_T, lower=0.0, unit="µm")
        return g_T * self._sigma_over_lam / self.mu

    def _d_of(self, normal_load=None, separation=None):
        if (normal_load is None) == (separation is None):
            if separation is None and not self.load_dependent:
                return np.zeros(())
            raise ModelParameterError(
                f"{type(self).__name__}: give exactly one of normal_load [N] or separation "
                f"[µm] (the stick/slip split of this density depends on the load level), got "
                f"normal_load={normal_load!r}, separation={separation!r}"
            )
        if separation is not None:
            return check_finite_array("separation", separation, unit="µm")
        return self.separation(normal_load)

    def force_ratio(self, g_T, normal_load=None, *, separation=None):
        """Return F̂_T = F_T/(μ F_N) = [J(d) − J(d + g_N0)]/J(d) at slip g_T (Eq 9).

        Parameters
        ----------
        g_T : array_like
            Tangential slip [µm], ≥ 0.
        normal_load : array_like, optional
            F_N [N] (needs the load scale), or give ``separation``.
        separation : array_like, optional
            Mean-plane separation d [µm] (the exponential density needs neither).

        Returns
        -------
        numpy.ndarray
            F̂_T (dimensionless, in [0, 1]).
        """
        d = self._d_of(normal_load, separation)
        g = self.stick_threshold(g_T)
        d, g = np.broadcast_arrays(d, g)
        out = self.load_integral_difference(d, g) / self.load_integral(d)
        return np.where(g == 0.0, 0.0, out)

    def tangential_force(self, g_T, F_N):
        """Return F_T(g_T; F_N) on the loading curve (Eq 9).

        Parameters
        ----------
        g_T : array_like
            Tangential slip [µm], ≥ 0.
        F_N : array_like
            Normal load [N], > 0.

        Returns
        -------
        numpy.ndarray
            F_T [N].
        """
        F_N = check_finite_array("F_N", F_N, unit="N")
        if np.any(F_N <= 0.0):
            raise ModelParameterError(f"F_N must be > 0 [N], got {F_N!r}")
        sep = None if not self.load_dependent else self.separation(F_N)
        if sep is None:
            return self.mu * F_N * self.force_ratio(g_T)
        return self.mu * F_N * self.force_ratio(g_T, separation=sep)

    def tangential_slip(self, F_T, F_N):
        """Return the slip g_T at which F_T is reached (inverse of :meth:`tangential_force`).

        Parameters
        ----------
        F_T : array_like
            Tangential force [N], 0 ≤ F_T < μ F_N.
        F_N : array_like
            Normal load [N], > 0.

        Returns
        -------
        numpy.ndarray
            g_T [µm].

        Raises
        ------
        GrossSlidingError
            F_T ≥ μ F_N (gross sliding).
        """
        F_T = check_finite_array("F_T", F_T, lower=0.0, unit="N")
        F_N = check_finite_array("F_N", F_N, unit="N")
        if np.any(F_N <= 0.0):
            raise ModelParameterError(f"F_N must be > 0 [N], got {F_N!r}")
        F_T, F_N = np.broadcast_arrays(F_T, F_N)
        ratio = F_T / (self.mu * F_N)
        if np.any(ratio >= 1.0):
            bad = np.flatnonzero(np.ravel(ratio >= 1.0))[0]
            raise GrossSlidingError(
                f"F_T must be < mu*F_N (gross sliding otherwise): F_T = {np.ravel(F_T)[bad]!r} N"
                f", mu*F_N = {self.mu * np.ravel(F_N)[bad]!r} N"
            )
        sep = self.separation(F_N) if self.load_dependent else None
        g = self.stick_gap(ratio, separation=sep) if sep is not None else self.stick_gap(ratio)
        return g * self.mu / self._sigma_over_lam

    def stick_gap(self, FT_hat, normal_load=None, *, separation=None):
        """Return the g_N0 at which F̂_T is reached (inverse of :meth:`force_ratio` in g_N0).

        Parameters
        ----------
        FT_hat : array_like
            F̂_T = F_T/(μ F_N) in [0, 1] (dimensionless).
        normal_load : array_like, optional
            F_N [N] (needs the load scale), or give ``separation``.
        separation : array_like, optional
            Mean-plane separation d [µm] (the exponential density needs neither).

        Returns
        -------
        numpy.ndarray
            g_N0 [µm] (inf at F̂_T = 1).
        """
        FT_hat = check_ratio(FT_hat)
        d = self._d_of(normal_load, separation)
        d, F = np.broadcast_arrays(d, FT_hat)
        d, F = np.array(d, dtype=float), np.array(F, dtype=float)
        g = np.zeros(F.shape)
        g[F == 1.0] = np.inf
        low = (F > 0.0) & (F <= 0.5)
        high = (F > 0.5) & (F < 1.0)
        if np.any(low):
            g[low] = gap_low(self, d[low], F[low])
        if np.any(high):
            g[high] = gap_high(self, d[high], F[high])
        return g

    # ---------------------------------------------------------------- stick ratios
    def stick_force_ratio(self, FT_hat, normal_load=None, *, separation=None):
        """Return F̂_ST = T/J(d) as a function of F̂_T ∈ [0, 1] (Eq 12 in general form).

        Parameters
        ----------
        FT_hat : array_like
            F̂_T = F_T/(μ F_N) in [0, 1] (dimensionless).
        normal_load : array_like, optional
            F_N [N] (needs the load scale), or give ``separation``.
        separation : array_like, optional
            Mean-plane separation d [µm] (the exponential density needs neither).

        Returns
        -------
        numpy.ndarray
            F̂_ST (dimensionless, ≤ F̂_T).
        """
        F = check_ratio(FT_hat)
        d = self._d_of(normal_load, separation)
        g = self.stick_gap(F, separation=d) if self.load_dependent else self.stick_gap(F)
        d, g = np.broadcast_arrays(d, g)
        out = np.zeros(g.shape)
        ok = (g > 0.0) & np.isfinite(g)
        if np.any(ok):
            dd, gg = d[ok], g[ok]
            out[ok] = self.stick_load_integral(dd, gg) / self.load_integral(dd)
        # F̂_ST ≤ F̂_T holds exactly; guard against a last-ulp excess from the root solve
        return np.minimum(out, F)

    def stick_area_ratio(self, FT_hat, normal_load=None, *, separation=None):
        """Return Â_ST = A_ST/A_r as a function of F̂_T ∈ [0, 1] (Eq 15 in general form).

        Parameters
        ----------
        FT_hat : array_like
            F̂_T = F_T/(μ F_N) in [0, 1] (dimensionless).
        normal_load : array_like, optional
            F_N [N] (needs the load scale), or give ``separation``.
        separation : array_like, optional
            Mean-plane separation d [µm] (the exponential density needs neither).

        Returns
        -------
        numpy.ndarray
            Â_ST (dimensionless, in [0, 1]).
        """
        F = check_ratio(FT_hat)
        d = self._d_of(normal_load, separation)
        g = self.stick_gap(F, separation=d) if self.load_dependent else self.stick_gap(F)
        d, g = np.broadcast_arrays(d, g)
        out = np.where(g == 0.0, 1.0, 0.0)
        ok = (g > 0.0) & np.isfinite(g)
        if np.any(ok):
            dd, gg = d[ok], g[ok]
            d0 = dd + gg
            a_st = self.area_integral(d0) + gg * self.tail_probability(d0)
            out[ok] = a_st / self.area_integral(dd)
        # A_ST ≤ A_r exactly; guard against a last-ulp excess at tiny slips
        return np.minimum(out, 1.0)

    # ---------------------------------------------------------------- contact-loss path
    def contact_levels(self, normal_load: float, max_slip: float) -> ContactLevels:
        """Return the levels of this surface for the contact-loss path.

        Parameters
        ----------
        normal_load : float
            F_N0 [N].
        max_slip : float
            g_A [µm].

        Returns
        -------
        RoughLevels
            The surface's :class:`~cusp.models.ContactLevels`.

        Raises
        ------
        MissingLoadScaleError
            E, radius, density or nominal_area not given.
        """
        return RoughLevels(self, normal_load, max_slip)

    def __repr__(self) -> str:
        keys = ["sigma", "nu", "mu", *_LOAD_SCALE_KEYS]
        args = ", ".join(f"{k}={getattr(self, k)!r}" for k in keys if getattr(self, k) is not None)
        return f"{type(self).__name__}({args})"
