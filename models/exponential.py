"""Rough surface with exponential summit heights, Φ(z) = e^{−z/σ*}/σ* (paper Eqs 1, 9, 12, 15).

Everything is closed form. With x := g_N0/σ* = g_T/(μλ):

* J(h) = Γ(5/2) σ*^{3/2} e^{−h/σ*}, A(h) = σ* e^{−h/σ*}, ∫_h^∞ Φ = e^{−h/σ*};
* F̂_T = 1 − e^{−x}                      (Eq 9), so x = −log1p(−F̂_T);
* F̂_ST = F̂_T − P(5/2, x) = Q(5/2, x) − e^{−x}  (Eq 12; P, Q regularised incomplete gamma);
* Â_ST = e^{−x}(1 + x) = Q(2, x)           (Eq 15).

None of these depends on the load level, so ratios and the loading curve need no load scale;
A_r ∝ F_N. Numerics: the erf form of P printed in the paper cancels for small x (and
1 − P for large x), so F̂_T − P is used for F̂_T ≤ 1/2 and Q − (1 − F̂_T) above (1 − F̂_T is
exact there) written as e^{−x}[erfcx(√x) + (4x^{3/2} + 6x^{1/2})/(3√π) − 1], a bracket ≥ 0.85
with no cancellation. No quadrature is imported.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import special as sc

from ._leg_areas import rough_leg_areas
from .errors import ModelParameterError, check_finite_array, check_ratio
from .rough import RoughSurface
from .rough_levels import slip_in_mu_lambda

__all__ = ["ExponentialRoughSurface", "ExponentialLevels"]

_GAMMA_5_2 = 0.75 * math.sqrt(math.pi)
_LOG_GAMMA_5_2 = math.log(_GAMMA_5_2)


class ExponentialRoughSurface(RoughSurface):
    """Composite rough surface with exponentially distributed summit heights.

    Heights z [µm] are measured from the mean plane of the exponential law (Φ = 0 for z < 0
    is not imposed: the paper's Eq 1 density is used on the whole line where it matters,
    z > d). Every integral is in closed form, and the ratios do not depend on the load.

    Parameters
    ----------
    sigma : float
        Composite rms roughness σ* [µm], > 0 (the decay length of the heights).
    nu : float
        Poisson's ratio ν, in (−1, 0.5].
    mu : float
        Friction coefficient μ > 0.
    E, radius, density, nominal_area : float, optional
        The load scale, as for :class:`~cusp.models.RoughSurface`: E [N/µm²], ρ* [µm],
        η [1/µm²], A_n [µm²]; only for absolute d [µm], F_N [N], A_r [µm²].

    Examples
    --------
    >>> s = ExponentialRoughSurface(sigma=2.0, nu=0.3, mu=0.1)
    >>> round(float(s.stick_threshold(0.34)), 12)  # g_T σ*/(μλ) = 0.34·2/(0.1·17/7) µm
    2.8
    """

    load_dependent = False

    def contact_levels(self, normal_load: float, max_slip: float) -> ExponentialLevels:
        """Return the closed-form levels of this surface for the contact-loss path.

        Parameters
        ----------
        normal_load : float
            F_N0 [N].
        max_slip : float
            g_A [µm].

        Returns
        -------
        ExponentialLevels
            The surface's :class:`~cusp.models.ContactLevels`.
        """
        return ExponentialLevels(self, normal_load, max_slip)

    # ---------------------------------------------------------------- integrals (closed form)
    def pdf(self, z):
        z = np.asarray(z, dtype=float)
        return np.exp(-z / self.sigma) / self.sigma

    def load_integral(self, h):
        """Return J(h) = Γ(5/2) σ*^{3/2} e^{−h/σ*}.

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
        return _GAMMA_5_2 * self.sigma**1.5 * np.exp(-h / self.sigma)

    def log_load_integral(self, h):
        h = check_finite_array("h", h, unit="µm")
        return _LOG_GAMMA_5_2 + 1.5 * math.log(self.sigma) - h / self.sigma

    def load_integral_derivative(self, h):
        """Return dJ/dh = −J/σ*.

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].

        Returns
        -------
        numpy.ndarray
            dJ/dh [µm^{1/2}].
        """
        return -self.load_integral(h) / self.sigma

    def area_integral(self, h):
        h = check_finite_array("h", h, unit="µm")
        return self.sigma * np.exp(-h / self.sigma)

    def tail_probability(self, h):
        h = check_finite_array("h", h, unit="µm")
        return np.exp(-h / self.sigma)

    def load_integral_difference(self, h, g):
        h, g = self._hg(h, g)
        return self.load_integral(h) * -np.expm1(-g / self.sigma)

    def load_integral_second_derivative(self, h):
        """Return d²J/dh² = J/σ*².

        Parameters
        ----------
        h : array_like
            Level above the mean plane [µm].

        Returns
        -------
        numpy.ndarray
            d²J/dh² [µm^{−1/2}].
        """
        return self.load_integral(h) / self.sigma**2

    def log_load_integral_second_derivative(self, h):
        return self.log_load_integral(h) - 2.0 * math.log(self.sigma)

    def area_integral_difference(self, h, g):
        h, g = self._hg(h, g)
        return self.area_integral(h) * -np.expm1(-g / self.sigma)

    def tail_difference(self, h, g):
        h, g = self._hg(h, g)
        return self.tail_probability(h) * -np.expm1(-g / self.sigma)

    def slip_area_integral(self, h, g):
        """Return ∫_h^{h+g} (z − h) Φ dz = A(h) P(2, g/σ*), P the regularized gamma function.

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
        h, g = self._hg(h, g)
        return self.area_integral(h) * sc.gammainc(2.0, g / self.sigma)

    def integral_rtol(self) -> float:
        """Return the relative error bound of the closed forms: a few ulp.

        Returns
        -------
        float
            16 machine epsilons.
        """
        return 16.0 * float(np.finfo(float).eps)

    def slip_load_integral(self, h, g):
        h, g = self._hg(h, g)
        return self.load_integral(h) * sc.gammainc(2.5, g / self.sigma)

    def stick_load_integral(self, h, g):
        h, g = self._hg(h, g)
        x = g / self.sigma
        return self.load_integral(h) * _stick_force_ratio(-np.expm1(-x), x, np.exp(-x))

    def separation(self, F_N):
        """Return the separation d = −σ* ln(F_N / (K Γ(5/2) σ*^{3/2})).

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
        """
        F_N = check_finite_array("F_N", F_N, unit="N")
        if np.any(F_N <= 0.0):
            raise ModelParameterError(f"F_N must be > 0 [N], got {F_N!r}")
        return -self.sigma * (
            np.log(F_N / self.load_scale) - _LOG_GAMMA_5_2 - 1.5 * math.log(self.sigma)
        )

    # ---------------------------------------------------------------- ratios (load independent)
    def force_ratio(self, g_T, normal_load=None, *, separation=None):
        """Return F̂_T = 1 − exp(−g_T/(μλ)) (Eq 9), independent of the load.

        Parameters
        ----------
        g_T : array_like
            Tangential slip [µm], ≥ 0.
        normal_load, separation : optional
            Ignored: the ratios of the exponential density do not depend on the load.

        Returns
        -------
        numpy.ndarray
            F̂_T (dimensionless, in [0, 1]).
        """
        _check_unused_load(normal_load, separation)
        with np.errstate(over="ignore"):  # x = g_T/(μλ) beyond the float range: F̂_T = 1
            return -np.expm1(-self.stick_threshold(g_T) / self.sigma)

    def tangential_force(self, g_T, F_N):
        """Return F_T = μF_N(1 − e^{−x}), x = g_T/(μλ) (Eq 9).

        Computed as F_N (g_T/λ)(1 − e^{−x})/x: the same number, but finite and exact where x
        underflows (a huge μλ).

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
        g_T = check_finite_array("g_T", g_T, lower=0.0, unit="µm")
        # (the branch np.where does not take may overflow or be inf·0: masked, not used)
        with np.errstate(over="ignore", under="ignore", invalid="ignore"):
            slope = (g_T / self.sigma) * self._sigma_over_lam  # g_T/λ = μx (0 at g_T = 0)
            x = slope / self.mu
            small = x < 1e-8
            ratio = np.where(small, 1.0 - 0.5 * x, -np.expm1(-x) / np.where(small, 1.0, x))
            big = np.isinf(x) | (x > 1e8)  # (1 − e^{−x})/x ⋅ μx = μ: F_T = μF_N
            out = np.where(big, self.mu * F_N, F_N * slope * ratio)
        return out[()] if out.ndim == 0 else out

    def stick_gap(self, FT_hat, normal_load=None, *, separation=None):
        """Return g_N0 = −σ* log(1 − F̂_T) (inverse of Eq 9).

        Parameters
        ----------
        FT_hat : array_like
            F̂_T = F_T/(μ F_N) in [0, 1] (dimensionless).
        normal_load, separation : optional
            Ignored: the ratios of the exponential density do not depend on the load.

        Returns
        -------
        numpy.ndarray
            g_N0 [µm]; inf at F̂_T = 1.
        """
        _check_unused_load(normal_load, separation)
        F = check_ratio(FT_hat)
        with np.errstate(divide="ignore"):
            return -self.sigma * np.log1p(-F)

    def stick_force_ratio(self, FT_hat, normal_load=None, *, separation=None):
        """Return F̂_ST(F̂_T) = F̂_T − P(5/2, x), x = −ln(1 − F̂_T) (Eq 12); exact to ~1e-15.

        Parameters
        ----------
        FT_hat : array_like
            F̂_T = F_T/(μ F_N) in [0, 1] (dimensionless).
        normal_load, separation : optional
            Ignored: the ratios of the exponential density do not depend on the load.

        Returns
        -------
        numpy.ndarray
            F̂_ST (dimensionless).
        """
        _check_unused_load(normal_load, separation)
        F = check_ratio(FT_hat)
        with np.errstate(divide="ignore"):
            x = -np.log1p(-F)
        return _stick_force_ratio(F, x, 1.0 - F)

    def stick_area_ratio(self, FT_hat, normal_load=None, *, separation=None):
        """Return Â_ST(F̂_T) = (1 − F̂_T)(1 − ln(1 − F̂_T)) = Q(2, x) (Eq 15); 0 at F̂_T = 1.

        Below F̂_T = 1/2 it is 1 − P(2, x) (monotone after rounding: 1 − x²/2 + …); above,
        (1 − F̂_T)(1 + x) with 1 − F̂_T exact.

        Parameters
        ----------
        FT_hat : array_like
            F̂_T = F_T/(μ F_N) in [0, 1] (dimensionless).
        normal_load, separation : optional
            Ignored: the ratios of the exponential density do not depend on the load.

        Returns
        -------
        numpy.ndarray
            Â_ST (dimensionless, in [0, 1]).
        """
        _check_unused_load(normal_load, separation)
        F = check_ratio(FT_hat)
        with np.errstate(divide="ignore", invalid="ignore"):
            x = -np.log1p(-F)
            out = np.where(F <= 0.5, 1.0 - sc.gammainc(2.0, x), (1.0 - F) * (1.0 + x))
        return np.where(F == 1.0, 0.0, out)


class ExponentialLevels:
    """Contact levels of the exponential surface (:class:`cusp.models.protocol.ContactLevels`):
    p = d/u, q = d0/u, every relation in closed form.

    The unit u = σ*·c [µm], c = max(1, x_A) with x_A = g_A/(μλ) the stick-threshold gap at A
    over σ*, keeps q − p of order one at A however large x_A is (small μ or σ*), and the levels
    are measured from d_A, the separation under F_N0 (the datum d_A = 0 without a load
    scale), so that small differences keep their digits. With x = c(q − p) = g_N0/σ* and
    J ∝ e^{−d/σ*}:

    * log(F_N/F_N0) = −cp                    (Eq 11)
    * F̂_T = 1 − e^{−x}                       (Eq 9)
    * g_T = μλ(d0 − d)/σ* = μ (λc)(q − p)    (Eqs 4–5)
    * Â_ST = e^{−x}(1 + x)                   (Eq 15)
    * A_r/A_r(F_N0) = e^{−cp}                (Eq 13, A_r ∝ F_N)

    and the surface never slides as a whole at finite slip (``slip_limit`` = inf). The path
    reports d = d_A + up and d0 = d_A + uq [µm] (``lengths``).
    """

    names = ("d", "d0")
    p0 = 0.0
    #: the closed forms' relative error (the bounds of the path's points and energies)
    relative_error = 16.0 * float(np.finfo(float).eps)

    def __init__(self, surf: ExponentialRoughSurface, F_N0: float, g_A: float) -> None:
        x_A = slip_in_mu_lambda(surf, g_A)
        self.c = max(1.0, x_A)
        #: u [µm]
        self.scale = surf.sigma * self.c
        #: λc [µm]: g_T = μ λc (q − p)
        self.lam = surf.lam * self.c
        # the response is invariant under shifts of the mean plane: without a load scale the
        # datum is put at d = 0 under F_N0
        self.d_A = float(surf.separation(F_N0)) if surf.has_load_scale else 0.0
        #: a bound on the error of d_A [µm] (its closed form, a few ulp of its terms; the
        #: datum d_A = 0 is exact)
        eps = float(np.finfo(float).eps)
        self.origin_error = 8.0 * eps * (abs(self.d_A) + surf.sigma) if surf.has_load_scale else 0.0

    def lengths(self, p, q):
        """d = d_A + u p and d0 = d_A + u q [µm]."""
        return self.d_A + self.scale * p, self.d_A + self.scale * q

    def log_normal_load(self, p: float) -> tuple[float, float]:
        """log(F_N/F_N0) = −cp and its derivative (Eq 11)."""
        return -self.c * p, -self.c

    def tangential_ratio(self, p: float, q: float) -> tuple[float, float, float]:
        """F̂_T = 1 − e^{−c(q − p)} and its derivatives (Eq 9)."""
        c = self.c
        e = math.exp(-c * (q - p))
        return -math.expm1(-c * (q - p)), -c * e, c * e

    def slip(self, p: float, q: float) -> tuple[float, float, float]:
        """g_T/μ = λc (q − p) [µm] and its derivatives (Eqs 4–5)."""
        return self.lam * (q - p), -self.lam, self.lam

    def stick_area(self, p: float, q: float) -> tuple[float, float, float]:
        """Â_ST = e^{−x}(1 + x), x = c(q − p), and its derivatives (Eq 15)."""
        c = self.c
        x = c * (q - p)
        e = math.exp(-x)
        return e * (1.0 + x), c * x * e, -c * x * e

    def slip_area(self, p: float, q: float) -> tuple[float, float, float]:
        """1 − Â_ST = 1 − e^{−x}(1 + x) = P(2, x), x = c(q − p) (the regularized lower
        incomplete gamma function), and its derivatives: ≈ x²/2 at small slips, where forming
        it from Â_ST would keep only ~ε/x² of its digits."""
        c = self.c
        x = c * (q - p)
        e = math.exp(-x)
        # (x < 0 only at a trial point off the path: the formula as written, defined there)
        value = float(sc.gammainc(2.0, x)) if x >= 0.0 else 1.0 - e * (1.0 + x)
        return value, -c * x * e, c * x * e

    def area_loss(self, p: float) -> tuple[float, float]:
        """1 − A_r/A_r(F_N0) = −expm1(−cp) and its derivative."""
        d = -self.c * p
        return -math.expm1(d), self.c * math.exp(d)

    def area_ratio(self, p: float) -> tuple[float, float]:
        """A_r/A_r(F_N0) = e^{−cp} and its derivative (Eq 13)."""
        r = math.exp(-self.c * p)
        return r, -self.c * r

    def slip_limit(self, p: float) -> float:
        """inf: a rough surface does not slide as a whole at finite slip."""
        return math.inf

    def curvature(self, y: np.ndarray) -> np.ndarray:
        """u² J''(d_A + u y)/J(d_A) = c² e^{−cy} (the integrand of :meth:`leg_areas`)."""
        return self.c**2 * np.exp(-self.c * np.asarray(y, dtype=float))

    def slope(self, y: np.ndarray) -> np.ndarray:
        """−u J'(d_A + u y)/J(d_A) = c e^{−cy} (the integrand of :meth:`leg_areas`)."""
        return self.c * np.exp(-self.c * np.asarray(y, dtype=float))

    def leg_areas(self, p_A, q_A, p_B, q_D, q_C, level_rtol, *, quad_tol=1e-13, errors=None):
        """The released areas ABD and ABC − ABD as ∫ T ds between the legs [µm], with error
        bounds (:func:`cusp.models._leg_areas.rough_leg_areas`: positive integrands in the
        differences between the levels; the gap between the legs, integrated before, lost
        its digits at small μ: the snap-back energy of Fig 9's locus was 0.0 below
        μ = 1.2e-16, where it is 28.8 μ² N·µm)."""
        return rough_leg_areas(self, p_A, q_A, p_B, q_C, level_rtol, quad_tol, errors)


def _check_unused_load(normal_load, separation) -> None:
    """The exponential ratios do not depend on the load; still reject nonsense if given."""
    if normal_load is not None:
        F_N = check_finite_array("normal_load", normal_load, unit="N")
        if np.any(F_N <= 0.0):
            raise ModelParameterError(f"normal_load must be > 0 [N], got {normal_load!r}")
    if separation is not None:
        check_finite_array("separation", separation, unit="µm")


def _stick_force_ratio(F: np.ndarray, x: np.ndarray, m: np.ndarray) -> np.ndarray:
    """F̂_ST from F̂_T = F, x = −ln(1 − F) and m = 1 − F = e^{−x} (each given accurately)."""
    F, x, m = np.broadcast_arrays(F, x, m)
    with np.errstate(invalid="ignore"):
        low = F - sc.gammainc(2.5, x)
        # Q(5/2, x) − e^{−x} = e^{−x} [erfcx(√x) + (4x^{3/2} + 6x^{1/2})/(3√π) − 1], m = e^{−x}
        r = np.sqrt(x)
        high = m * (sc.erfcx(r) + (4.0 * x + 6.0) * r / (3.0 * math.sqrt(math.pi)) - 1.0)
    out = np.where(F <= 0.5, low, high)
    return np.where(F == 1.0, 0.0, out)
