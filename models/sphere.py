"""Two identical elastic spheres under partial slip (Cattaneo–Mindlin; Sec. 3.1, Eqs 16–22).

With F̂_T = F_T/(μ F_N) and k = c/a the stick-circle radius over the contact radius:

* c/a = (1 − F̂_T)^{1/3}                               (Eq 19)
* F̂_ST = F̂_T − [1 − (1 − F̂_T)^{2/3}]^{3/2}            (Eq 21)
* Â_ST = (1 − F̂_T)^{2/3}                               (Eq 22)
* g_T = 3 (2 − ν) μ F_N / (8 G a) [1 − (1 − F̂_T)^{2/3}] (Eq 2), Hertz a = [3 F_N R*/(4 E*)]^{1/3}

Composite conventions (two identical spheres of radius R [µm], modulus E [N/µm²], Poisson
ratio ν): R* = R/2, E* = E/[2(1 − ν²)], G = E/[2(1 + ν)] (the shear modulus of each body, as
in Johnson 1985 Eq 7.42 with G1 = G2). Units: lengths µm, forces N, moduli N/µm².

Numerics: Eq 21 cancels as F̂_T → 1 (two numbers near 1); for F̂_T > 1/2 it is evaluated as
−expm1(3/2 log1p(−k²)) − (1 − F̂_T), where 1 − F̂_T is exact and the first term
≈ 3k²/2 ≫ 1 − F̂_T.
"""

from __future__ import annotations

import math
from typing import cast

import numpy as np

from .errors import (
    GrossSlidingError,
    ModelParameterError,
    check_finite_array,
    check_poisson,
    check_positive,
    check_ratio,
)

__all__ = ["Sphere", "SphereLevels"]


class Sphere:
    """Two identical elastic spheres in contact (per pair).

    None of the parameters is needed for the stick ratios; all four are needed for the
    compliance law (Eq 2) and the contact-loss path.

    Parameters
    ----------
    radius : float, optional
        Radius R of each sphere [µm].
    E : float, optional
        Young's modulus of each sphere [N/µm²].
    nu : float, optional
        Poisson's ratio ν, in (−1, 0.5].
    mu : float, optional
        Friction coefficient μ > 0.

    Examples
    --------
    >>> round(float(Sphere.stick_zone_ratio(0.875)), 12)  # c/a = (1 − 7/8)^{1/3} = 1/2
    0.5
    """

    def __init__(self, radius=None, E=None, nu=None, mu=None) -> None:
        self.radius = None if radius is None else check_positive("radius", radius, "µm")
        self.E = None if E is None else check_positive("E", E, "N/µm²")
        self.nu = None if nu is None else check_poisson(nu)
        self.mu = None if mu is None else check_positive("mu", mu)

    # ------------------------------------------------------------------ ratios
    @staticmethod
    def stick_zone_ratio(FT_hat):
        """Return the stick-zone ratio c/a = (1 − F̂_T)^{1/3} (Eq 19).

        Parameters
        ----------
        FT_hat : array_like
            F̂_T = F_T/(μ F_N) in [0, 1] (dimensionless).

        Returns
        -------
        numpy.ndarray
            c/a (dimensionless), the shape of ``FT_hat``.

        Raises
        ------
        ModelParameterError
            A ratio outside [0, 1] or not finite.
        """
        F = check_ratio(FT_hat)
        with np.errstate(divide="ignore"):
            return np.where(F <= 0.5, np.exp(np.log1p(-F) / 3.0), np.cbrt(1.0 - F))

    @staticmethod
    def stick_force_ratio(FT_hat):
        """Return F̂_ST(F̂_T) = F̂_T − [1 − (1 − F̂_T)^{2/3}]^{3/2} (Eq 21).

        Parameters
        ----------
        FT_hat : array_like
            F̂_T = F_T/(μ F_N) in [0, 1] (dimensionless).

        Returns
        -------
        numpy.ndarray
            F̂_ST (dimensionless), the shape of ``FT_hat``.

        Raises
        ------
        ModelParameterError
            A ratio outside [0, 1] or not finite.
        """
        F = check_ratio(FT_hat)
        m = 1.0 - F  # exact for F ≥ 1/2
        with np.errstate(divide="ignore"):
            one_minus_k2_low = -np.expm1(np.log1p(-F) * (2.0 / 3.0))
            low = F - one_minus_k2_low**1.5
        # the high branch is used for F > 1/2 only (k² < 0.63 there); at F ≤ 1 ulp the
        # platform cbrt may round (1 − F)^{1/3} above 1 (glibc: cbrt(1 − 2⁻⁵²) = 1 + 2⁻⁵²),
        # and log1p(−k²) of the unused entry is then NaN
        with np.errstate(divide="ignore", invalid="ignore"):
            k2 = np.cbrt(m) ** 2
            high = -np.expm1(1.5 * np.log1p(-k2)) - m
        return np.where(F <= 0.5, low, np.where(F == 1.0, 0.0, high))

    @staticmethod
    def stick_area_ratio(FT_hat):
        """Return Â_ST(F̂_T) = (c/a)² = (1 − F̂_T)^{2/3} (Eq 22).

        Parameters
        ----------
        FT_hat : array_like
            F̂_T = F_T/(μ F_N) in [0, 1] (dimensionless).

        Returns
        -------
        numpy.ndarray
            Â_ST (dimensionless), the shape of ``FT_hat``.

        Raises
        ------
        ModelParameterError
            A ratio outside [0, 1] or not finite.
        """
        F = check_ratio(FT_hat)
        with np.errstate(divide="ignore"):
            low = np.exp(np.log1p(-F) * (2.0 / 3.0))
        return np.where(F <= 0.5, low, np.cbrt(1.0 - F) ** 2)

    # ------------------------------------------------------------------ compliance (Eq 2)
    def _require(self, what: str) -> None:
        missing = [k for k in ("radius", "E", "nu", "mu") if getattr(self, k) is None]
        if missing:
            raise ModelParameterError(
                f"{what} needs Sphere(radius=..., E=..., nu=..., mu=...); missing: "
                f"{', '.join(missing)}"
            )

    def _values(self, what: str) -> tuple[float, float, float, float]:
        """``(radius, E, nu, mu)``, all given (else a ModelParameterError naming ``what``)."""
        self._require(what)
        return (
            cast(float, self.radius),
            cast(float, self.E),
            cast(float, self.nu),
            cast(float, self.mu),
        )

    @property
    def E_star(self) -> float:
        """E* = E/[2(1 − ν²)]  [N/µm²]."""
        _, E, nu, _ = self._values("E_star")
        return E / (2.0 * (1.0 - nu**2))

    @property
    def G(self) -> float:
        """G = E/[2(1 + ν)]  [N/µm²], shear modulus of each sphere."""
        _, E, nu, _ = self._values("G")
        return E / (2.0 * (1.0 + nu))

    def contact_radius(self, F_N):
        """Return the Hertz contact radius a = [3 F_N R*/(4 E*)]^{1/3}, R* = R/2.

        Parameters
        ----------
        F_N : array_like
            Normal load [N], > 0.

        Returns
        -------
        numpy.ndarray
            a [µm], the shape of ``F_N``.

        Raises
        ------
        ModelParameterError
            A parameter of the sphere missing (all four are needed), or a load ≤ 0.
        """
        radius = self._values("contact_radius")[0]
        F_N = _positive_load(F_N)
        return np.cbrt(3.0 * F_N * (0.5 * radius) / (4.0 * self.E_star))

    def slip_limit(self, F_N):
        """Return the slip at the onset of gross sliding, g_lim = 3 (2 − ν) μ F_N / (8 G a).

        Parameters
        ----------
        F_N : array_like
            Normal load [N], > 0.

        Returns
        -------
        numpy.ndarray
            g_lim [µm], the shape of ``F_N``.

        Raises
        ------
        ModelParameterError
            A parameter of the sphere missing (all four are needed), or a load ≤ 0.
        """
        _, _, nu, mu = self._values("slip_limit")
        F_N = _positive_load(F_N)
        return 3.0 * (2.0 - nu) * mu * F_N / (8.0 * self.G * self.contact_radius(F_N))

    def tangential_slip(self, F_T, F_N):
        """Return the slip g_T(F_T; F_N) by Eq 2.

        Parameters
        ----------
        F_T : array_like
            Tangential force [N], 0 ≤ F_T < μ F_N.
        F_N : array_like
            Normal load [N], > 0 (broadcast against ``F_T``).

        Returns
        -------
        numpy.ndarray
            g_T [µm].

        Raises
        ------
        GrossSlidingError
            F_T ≥ μ F_N (gross sliding).
        ModelParameterError
            A parameter of the sphere missing, or a force out of range.
        """
        mu = self._values("tangential_slip")[3]
        F_T = check_finite_array("F_T", F_T, lower=0.0, unit="N")
        F_N = _positive_load(F_N)
        F_T, F_N = np.broadcast_arrays(F_T, F_N)
        ratio = F_T / (mu * F_N)
        if np.any(ratio >= 1.0):
            i = int(np.flatnonzero(np.ravel(ratio >= 1.0))[0])
            raise GrossSlidingError(
                f"F_T must be < mu*F_N (gross sliding otherwise): F_T = {np.ravel(F_T)[i]!r} N, "
                f"mu*F_N = {mu * np.ravel(F_N)[i]!r} N"
            )
        return self.slip_limit(F_N) * -np.expm1(np.log1p(-ratio) * (2.0 / 3.0))

    def tangential_force(self, g_T, F_N):
        """Return F_T(g_T; F_N), the inverse of Eq 2: μ F_N [1 − (1 − g_T/g_lim)^{3/2}].

        For g_T ≥ g_lim (:meth:`slip_limit`) the spheres slide: F_T = μ F_N.

        Parameters
        ----------
        g_T : array_like
            Tangential slip [µm], ≥ 0.
        F_N : array_like
            Normal load [N], > 0 (broadcast against ``g_T``).

        Returns
        -------
        numpy.ndarray
            F_T [N].

        Raises
        ------
        ModelParameterError
            A parameter of the sphere missing (all four are needed), or a load ≤ 0.
        """
        mu = self._values("tangential_force")[3]
        g_T = check_finite_array("g_T", g_T, lower=0.0, unit="µm")
        F_N = _positive_load(F_N)
        g_T, F_N = np.broadcast_arrays(g_T, F_N)
        r = np.minimum(g_T / self.slip_limit(F_N), 1.0)
        with np.errstate(divide="ignore"):
            return mu * F_N * -np.expm1(1.5 * np.log1p(-r))

    # ------------------------------------------------------------------ contact-loss path
    def contact_levels(self, normal_load: float, max_slip: float) -> SphereLevels:
        """Return the levels of this sphere for the contact-loss path.

        Parameters
        ----------
        normal_load : float
            F_N0 [N].
        max_slip : float
            g_A [µm].

        Returns
        -------
        SphereLevels
            The sphere's :class:`~cusp.models.ContactLevels`.

        Raises
        ------
        ModelParameterError
            A parameter of the sphere missing (all four are needed), or a load ≤ 0.
        """
        return SphereLevels(self, normal_load, max_slip)

    def __repr__(self) -> str:
        return f"Sphere(radius={self.radius!r}, E={self.E!r}, nu={self.nu!r}, mu={self.mu!r})"


class SphereLevels:
    """Contact levels of the Hertz–Mindlin sphere (:class:`cusp.models.protocol.ContactLevels`),
    measured from the Hertz radius a0 under F_N0: p = 1 − a/a0, q = 1 − c/a0, so that at
    small slips, where a, c and a0 agree to many digits, a − c = a0(q − p) keeps them all.
    With r = 1 − c/a = (q − p)/(1 − p):

    * log(F_N/F_N0) = 3 log(1 − p)                 (Hertz, F_N ∝ a³)
    * F̂_T = 1 − (c/a)³ = r(3 − 3r + r²)            (Eq 19)
    * g_T = μκ(a² − c²)/a0² = μκ(q − p)(2 − p − q)  (Eq 2 with Hertz)
    * Â_ST = (c/a)² = (1 − r)²,  A_r/A_r(F_N0) = (1 − p)²  (A_ST ∝ c², A_r ∝ a²), and
      the slipped shares 1 − Â_ST = (q − p)(2 − p − q)/(1 − p)² (``slip_area``) and
      1 − A_r/A_r(F_N0) = p(2 − p) (``area_loss``), which keep their digits at small slips

    with κ = (2 − ν) E* a0² / (2 G R*) [µm]. The spheres slide as a whole when the stick zone
    vanishes, c = 0, i.e. q = 1 (``stick_bounds``), at g_T = μκ(1 − p)² (``slip_limit``). The
    path reports a = a0(1 − p) and c = a0(1 − q) [µm] (``lengths``).
    """

    names = ("a", "c")
    p0 = 0.0  # a = a0 under F_N0
    #: the stick zone exists for q < 1 (c > 0); q = 1 is gross sliding
    stick_bounds = (-math.inf, 1.0)

    def __init__(self, sphere: Sphere, F_N0: float, g_A: float) -> None:
        sphere._require("the contact-loss path (compliance law, Eq 2)")
        nu, radius = cast(float, sphere.nu), cast(float, sphere.radius)  # checked just above
        with np.errstate(over="ignore", under="ignore", divide="ignore", invalid="ignore"):
            a0 = float(sphere.contact_radius(F_N0))
            den = 2.0 * sphere.G * 0.5 * radius
            kappa = (2.0 - nu) * sphere.E_star * a0**2 / den if den > 0.0 else math.inf
        if not (0.0 < a0 < math.inf and 0.0 < kappa < math.inf):
            raise ModelParameterError(
                f"radius = {radius!r} µm and E = {sphere.E!r} N/µm² under F_N0 = {F_N0!r} N "
                f"give a Hertz radius a0 = {a0!r} µm and a compliance κ = {kappa!r} µm outside "
                f"the float range: choose radius and E whose a0 = (3 F_N0 R/(8 E*))^(1/3) and "
                f"κ are finite and > 0"
            )
        #: a0 [µm]
        self.scale = a0
        #: κ [µm]
        self.kappa = kappa

    def lengths(self, p, q):
        """a = a0(1 − p), c = a0(1 − q) [µm]."""
        return self.scale * (1.0 - p), self.scale * (1.0 - q)

    def log_normal_load(self, p: float) -> tuple[float, float]:
        """log(F_N/F_N0) = 3 log(1 − p) and its derivative (Hertz); NaN where a ≤ 0 (a trial
        point of the path may land there: a non-finite residual shortens its step)."""
        if not p < 1.0:
            return math.nan, math.nan
        return 3.0 * math.log1p(-p), -3.0 / (1.0 - p)

    def tangential_ratio(self, p: float, q: float) -> tuple[float, float, float]:
        """F̂_T = 1 − (c/a)³ = r(3 − 3r + r²), r = (q − p)/(1 − p), and its derivatives
        (Eq 19)."""
        w = 1.0 - p
        r = (q - p) / w
        dF = 3.0 * (1.0 - r) ** 2  # dF̂/dr
        # near gross sliding (r -> 1) from c/a, so that F̂_T <= 1 (F_T <= μF_N) to the last bit
        F = r * (3.0 - 3.0 * r + r * r) if r < 0.5 else 1.0 - ((1.0 - q) / w) ** 3
        return F, -dF * (1.0 - q) / (w * w), dF / w

    def slip(self, p: float, q: float) -> tuple[float, float, float]:
        """g_T/μ = κ(q − p)(2 − p − q) [µm] and its derivatives (Eq 2)."""
        k = self.kappa
        return k * (q - p) * (2.0 - p - q), -2.0 * k * (1.0 - p), 2.0 * k * (1.0 - q)

    def stick_area(self, p: float, q: float) -> tuple[float, float, float]:
        """Â_ST = (c/a)² = (1 − r)² and its derivatives (Eq 22)."""
        w = 1.0 - p
        k = (1.0 - q) / w  # c/a
        return k * k, 2.0 * k * k / w, -2.0 * k / w

    def area_ratio(self, p: float) -> tuple[float, float]:
        """A_r/A_r(F_N0) = (1 − p)² and its derivative."""
        return (1.0 - p) ** 2, -2.0 * (1.0 - p)

    def slip_area(self, p: float, q: float) -> tuple[float, float, float]:
        """1 − Â_ST = (a² − c²)/a² = (q − p)(2 − p − q)/(1 − p)² and its derivatives: at small
        slips Â_ST ≈ 1 − g_T/g_lim, and 1 − Â_ST formed from it would keep only ~ε/f of its
        digits; from q − p it keeps them all."""
        w = 1.0 - p
        k = (1.0 - q) / w  # c/a
        return (q - p) * (2.0 - p - q) / (w * w), -2.0 * k * k / w, 2.0 * k / w

    def area_loss(self, p: float) -> tuple[float, float]:
        """1 − A_r/A_r(F_N0) = 1 − (1 − p)² = p(2 − p) and its derivative."""
        return p * (2.0 - p), 2.0 * (1.0 - p)

    def slip_limit(self, p: float) -> float:
        """κ(1 − p)² [µm]: the stick zone vanishes (gross sliding) at g_T = μκ(a/a0)²."""
        return self.kappa * (1.0 - p) ** 2

    def leg_areas(self, p_A, q_A, p_B, q_D, q_C, level_rtol, *, errors=None):
        """The released areas in closed form, ∫ T ds between the legs [µm] with T = F_T/(μF_N0)
        and s = g_T/μ: ``((ABD, error), (ABC − ABD, error))``, the second (NaN, NaN) when
        ``q_C`` is NaN (no C). ``level_rtol``: each level's own error relative to itself.

        With x = 1 − p and y = 1 − q, T = x³ − y³ and s = κ(x² − y²) on every leg, so the areas
        are integrals of polynomials; written in the differences the path keeps
        (:mod:`cusp.verification.sphere_energy` derives them) they are polynomials with
        positive coefficients in positive variables, evaluated without cancellation:

        * ABD = κ[AB(x_B, w, δ) + BD(y_D, e_D)],  ABC − ABD = κ DC(y_C, h_D),

        x_B = 1 − p_B, w = q_A − p_B, δ = p_B − p_A, y_D = 1 − q_D, e_D = q_D − q_A,
        y_C = 1 − q_C, h_D = q_C − q_D. The error: 16ε of the sum of the terms (their
        rounding), plus each variable's error (its rounding, and the errors of the levels it
        is formed from: ``errors``, the absolute errors of (p_A, q_A, p_B, q_D, q_C), else
        ``level_rtol`` times each level) times the polynomial's derivative in it, taken at
        the variables' upper bounds (a bound, the coefficients being positive). Near gross
        sliding the stick levels are resolved only to the chain's bounds (c known to 1e-11
        relative at g_A = (1 − 1e-6) g_lim), not to ``level_rtol``: an energy bound of
        8.1e-14 stood against an error of 2.4e-13 there (1.1e-11 at 1 − 1e-9)."""
        values = (p_A, q_A, p_B, q_D, q_C)
        if errors is None:
            errors = tuple(level_rtol * abs(z) if math.isfinite(z) else 0.0 for z in values)
        e_A, e_qA, e_B, e_D, e_C = errors

        def base(z, ez):  # 1 − z and its error
            return 1.0 - z, _EPS * abs(1.0 - z) + ez

        def diff(hi, ehi, lo, elo):  # hi − lo and its error
            return hi - lo, _EPS * abs(hi - lo) + ehi + elo

        ab = _released(
            _AREA_AB, base(p_B, e_B), diff(q_A, e_qA, p_B, e_B), diff(p_B, e_B, p_A, e_A)
        )
        bd = _released(_AREA_BD, base(q_D, e_D), diff(q_D, e_D, q_A, e_qA))
        abd = (self.kappa * (ab[0] + bd[0]), self.kappa * (ab[1] + bd[1]))
        if not math.isfinite(q_C):
            return abd, (math.nan, math.nan)
        dc = _released(_AREA_DC, base(q_C, e_C), diff(q_C, e_C, q_D, e_D))
        return abd, (self.kappa * dc[0], self.kappa * dc[1])


_EPS = float(np.finfo(float).eps)
#: the closed forms of :meth:`SphereLevels.leg_areas` as monomials (numerator, denominator,
#: exponents), derived by :func:`cusp.verification.sphere_energy.sphere_released_areas`
#: (a test checks they agree): AB in (x_B, w, δ), BD in (y_D, e_D), DC in (y_C, h_D)
_AREA_AB = (
    (2, 5, (0, 0, 5)),
    (3, 4, (0, 1, 4)),
    (1, 1, (2, 0, 3)),
    (5, 4, (1, 0, 4)),
    (3, 1, (1, 1, 3)),
    (3, 1, (2, 1, 2)),
)
_AREA_BD = ((3, 20, (0, 5)), (3, 4, (1, 4)), (1, 1, (2, 3)))
_AREA_DC = ((2, 5, (0, 5)), (2, 1, (1, 4)), (3, 1, (3, 2)), (4, 1, (2, 3)))


def _released(table, *variables: tuple[float, float]) -> tuple[float, float]:
    """Σ c Π zⱼ^kⱼ over the monomials of ``table`` at the (value, error) ``variables``, and a
    bound on its error: 16ε Σ|terms| (the evaluation) plus Σⱼ ∂/∂zⱼ(|z| + Δz) Δzⱼ (the
    variables' errors, by the mean-value theorem: every coefficient is positive)."""
    z = [v for v, _ in variables]
    dz = [e for _, e in variables]
    top = [abs(v) + e for v, e in variables]
    value = size = spread = 0.0
    for num, den, ks in table:
        term = num / den * math.prod(v**k for v, k in zip(z, ks))
        value += term
        size += abs(term)
        for j, kj in enumerate(ks):
            if kj:
                rest = math.prod(t**k for i, (t, k) in enumerate(zip(top, ks)) if i != j)
                spread += num / den * kj * top[j] ** (kj - 1) * rest * dz[j]
    return value, 16.0 * _EPS * size + spread


def _positive_load(F_N):
    F_N = check_finite_array("F_N", F_N, unit="N")
    if np.any(F_N <= 0.0):
        raise ModelParameterError(f"F_N must be > 0 [N], got {F_N!r}")
    return F_N
