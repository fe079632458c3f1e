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

import functools
import math
from typing import TYPE_CHECKING, cast

import numpy as np

from .errors import (
    GrossSlidingError,
    MissingLoadScaleError,
    ModelParameterError,
    check_finite_array,
    check_poisson,
    check_positive,
    check_ratio,
)

if TYPE_CHECKING:
    from .protocol import ContactLevels

__all__ = ["RoughSurface", "RoughLevels", "monotone_root"]

_LOAD_SCALE_KEYS = ("E", "radius", "density", "nominal_area")


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


class RoughSurface:
    """A composite rough surface on a rigid flat (base class; see module docstring).

    Parameters
    ----------
    sigma : composite rms roughness σ* [µm], > 0.
    nu : Poisson's ratio ν in (−1, 0.5].
    mu : friction coefficient μ > 0.

    Other parameters (the load scale; needed only for absolute d, F_N, A_r)
    ----------------------------------------------------------------------
    E : Young's modulus of each body [N/µm²]; E* = E/[2(1 − ν²)].
    radius : composite summit radius ρ* [µm].
    density : summit density η [1/µm²].
    nominal_area : nominal contact area A_n [µm²].
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
        """π ρ* η A_n  [µm], so that A_r = area_scale · A(d)."""
        _, radius, density, nominal_area = self._load_scale_values("the real contact area")
        return math.pi * radius * density * nominal_area

    # ---------------------------------------------------------------- density integrals
    # Defaults by quadrature over self.pdf; closed-form subclasses override them.
    def pdf(self, z):
        """Φ(z) [1/µm], the summit-height density at heights z [µm] (each density defines
        it)."""
        raise NotImplementedError(f"{type(self).__name__} defines no height density pdf(z)")

    def load_integral(self, h):
        """J(h) = ∫_h^∞ (z − h)^{3/2} Φ(z) dz  [µm^{3/2}]."""
        from ._quadrature import moment

        return moment(self, 1.5, check_finite_array("h", h, unit="µm"))

    def log_load_integral(self, h):
        """log J(h) (J in µm^{3/2})."""
        with np.errstate(divide="ignore"):
            return np.log(self.load_integral(h))

    def load_integral_derivative(self, h):
        """dJ/dh = −(3/2) ∫_h^∞ (z − h)^{1/2} Φ dz  [µm^{1/2}]."""
        from ._quadrature import moment

        return -1.5 * moment(self, 0.5, check_finite_array("h", h, unit="µm"))

    def area_integral(self, h):
        """A(h) = ∫_h^∞ (z − h) Φ(z) dz  [µm]."""
        from ._quadrature import moment

        return moment(self, 1.0, check_finite_array("h", h, unit="µm"))

    def tail_probability(self, h):
        """∫_h^∞ Φ(z) dz (dimensionless)."""
        from ._quadrature import moment

        return moment(self, 0.0, check_finite_array("h", h, unit="µm"))

    def slip_load_integral(self, h, g):
        """S(h, g) = ∫_h^{h+g} (z − h)^{3/2} Φ dz  [µm^{3/2}] (sliding summits, Eq 10)."""
        from ._quadrature import slip_integral

        return slip_integral(self, *self._hg(h, g))

    def stick_load_integral(self, h, g):
        """T(h, g) = ∫_{h+g}^∞ [(z − h)^{3/2} − (z − h − g)^{3/2}] Φ dz  [µm^{3/2}] (Eq 7)."""
        from ._quadrature import stick_integral

        return stick_integral(self, *self._hg(h, g))

    def load_integral_difference(self, h, g):
        """J(h) − J(h + g) = S + T ≥ 0 [µm^{3/2}], without cancellation for tiny g."""
        h, g = self._hg(h, g)
        return self.slip_load_integral(h, g) + self.stick_load_integral(h, g)

    @staticmethod
    def _hg(h, g):
        h = check_finite_array("h", h, unit="µm")
        g = check_finite_array("g", g, lower=0.0, unit="µm")
        h, g = np.broadcast_arrays(h, g)
        return np.array(h), np.array(g)

    # ---------------------------------------------------------------- normal contact
    def normal_load(self, d):
        """F_N(d) = K J(d)  [N] at mean-plane separation d [µm] (Eq 11)."""
        return self.load_scale * self.load_integral(d)

    def normal_load_derivative(self, d):
        """dF_N/dd = K J'(d)  [N/µm] (negative)."""
        return self.load_scale * self.load_integral_derivative(d)

    def real_contact_area(self, d):
        """A_r(d) = π ρ* η A_n ∫_d^∞ (z − d) Φ dz  [µm²] (Eq 13)."""
        return self.area_scale * self.area_integral(d)

    def separation(self, F_N):
        """Mean-plane separation d [µm] carrying the normal load F_N [N] > 0 (root of Eq 11)."""
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
        """g_N0 = 2 (1 − ν) g_T / [μ (2 − ν)] = g_T σ*/(μ λ)  [µm] (Eq 5)."""
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
        """F̂_T = F_T/(μ F_N) = [J(d) − J(d + g_N0)]/J(d) at slip g_T [µm] (Eq 9)."""
        d = self._d_of(normal_load, separation)
        g = self.stick_threshold(g_T)
        d, g = np.broadcast_arrays(d, g)
        out = self.load_integral_difference(d, g) / self.load_integral(d)
        return np.where(g == 0.0, 0.0, out)

    def tangential_force(self, g_T, F_N):
        """F_T(g_T; F_N)  [N] on the loading curve at normal load F_N [N] (Eq 9)."""
        F_N = check_finite_array("F_N", F_N, unit="N")
        if np.any(F_N <= 0.0):
            raise ModelParameterError(f"F_N must be > 0 [N], got {F_N!r}")
        sep = None if not self.load_dependent else self.separation(F_N)
        if sep is None:
            return self.mu * F_N * self.force_ratio(g_T)
        return self.mu * F_N * self.force_ratio(g_T, separation=sep)

    def tangential_slip(self, F_T, F_N):
        """Inverse of :meth:`tangential_force`: the slip g_T [µm] at which F_T [N] is reached.

        Requires 0 ≤ F_T < μ F_N; F_T ≥ μ F_N is gross sliding and raises GrossSlidingError.
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
        """g_N0 [µm] at which F̂_T is reached (inverse of :meth:`force_ratio` in g_N0)."""
        FT_hat = check_ratio(FT_hat)
        d = self._d_of(normal_load, separation)
        d, F = np.broadcast_arrays(d, FT_hat)
        d, F = np.array(d, dtype=float), np.array(F, dtype=float)
        g = np.zeros(F.shape)
        g[F == 1.0] = np.inf
        low = (F > 0.0) & (F <= 0.5)
        high = (F > 0.5) & (F < 1.0)
        if np.any(low):
            g[low] = self._gap_low(d[low], F[low])
        if np.any(high):
            g[high] = self._gap_high(d[high], F[high])
        return g

    def _gap_low(self, d, F):
        # log[J(d) − J(d + e^u)] − log J(d) = log F̂_T, increasing in u = log g
        log_j = self.log_load_integral(d)
        slope = -self.load_integral_derivative(d) / self.load_integral(d)

        def f(u, idx):
            with np.errstate(divide="ignore", over="ignore"):
                diff = self.load_integral_difference(d[idx], np.exp(u))
                return np.log(diff) - log_j[idx]

        u0 = np.log(F) - np.log(slope)
        lo, hi = expand_bracket(f, np.log(F), u0 - 1.0, u0 + 1.0)
        return np.exp(monotone_root(f, np.log(F), lo, hi))

    def _gap_high(self, d, F):
        # −log J(d + g) = −log J(d) − log(1 − F̂_T), increasing in g
        target = -self.log_load_integral(d) - np.log1p(-F)

        def f(g, idx):
            return -self.log_load_integral(d[idx] + g)

        lo, hi = expand_bracket(
            f, target, np.zeros_like(d), np.full_like(d, self.sigma), step=self.sigma
        )
        return monotone_root(f, target, lo, hi)

    # ---------------------------------------------------------------- stick ratios
    def stick_force_ratio(self, FT_hat, normal_load=None, *, separation=None):
        """F̂_ST = T/J(d) as a function of F̂_T ∈ [0, 1] (Eq 12 in general form).

        For load-dependent densities give ``normal_load`` [N] (needs the load scale) or the
        mean-plane ``separation`` d [µm].
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
        """Â_ST = A_ST/A_r as a function of F̂_T ∈ [0, 1] (Eq 15 in general form)."""
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
        """The levels of this surface for the contact-loss path at F_N0 = ``normal_load`` [N]
        and g_A = ``max_slip`` [µm] (:class:`RoughLevels`; needs the load scale, else
        MissingLoadScaleError)."""
        return RoughLevels(self, normal_load, max_slip)

    def __repr__(self) -> str:
        keys = ["sigma", "nu", "mu", *_LOAD_SCALE_KEYS]
        args = ", ".join(f"{k}={getattr(self, k)!r}" for k in keys if getattr(self, k) is not None)
        return f"{type(self).__name__}({args})"


class RoughLevels:
    """Contact levels of a rough surface over any height density
    (:class:`cusp.models.protocol.ContactLevels`), from the surface's GW integrals.

    p = d/u, q = d0/u with u = σ*·c [µm], c = max(1, g_A/(μλ)) (as for the exponential
    surface: q − p of order one at A). With J, A, Q = ∫_h^∞ Φ the load, area and tail
    integrals of the surface (module docstring) and d_A the separation under F_N0:

    * log(F_N/F_N0) = log J(d) − log J(d_A)                  (Eq 11)
    * F̂_T = 1 − J(d0)/J(d)                                   (Eq 9)
    * g_T = μλ(d0 − d)/σ* = μ (λc)(q − p)                    (Eqs 4–5)
    * Â_ST = [A(d0) + (d0 − d) Q(d0)]/A(d)                    (Eq 14 over Eq 13)
    * A_r/A_r(F_N0) = A(d)/A(d_A)                            (Eq 13)

    and the surface never slides as a whole at finite slip (``slip_limit`` = inf). Needs the
    load scale (d_A is absolute).
    """

    names = ("d", "d0")

    def __init__(self, surf: RoughSurface, F_N0: float, g_A: float) -> None:
        self.surf = surf
        x_A = slip_in_mu_lambda(surf, g_A)
        c = max(1.0, x_A)
        #: u [µm]
        self.scale = s = surf.sigma * c
        #: λc [µm]: g_T = μ λc (q − p)
        self.lam = surf.lam * c
        d0 = float(surf.separation(F_N0))  # raises MissingLoadScaleError without the scale
        self.p0 = d0 / s
        # log J at the start level itself (not log(F_N0/K), which the inverted separation
        # meets only to rounding): ℓ(p0) = 0 exactly, so the path starts on its equations;
        # off by two ulps, Newton at O wandered in p (dℓ/dp small where σ* ≪ |d|) and never
        # settled t = A_SL = 0 (σ* = 1e-4 µm, g_A = 5e-6 µm: "the starting point did not
        # converge")
        self.j0 = float(surf.log_load_integral(self.scale * self.p0))
        self.A0 = float(surf.area_integral(d0))

    @functools.lru_cache(maxsize=16)  # noqa: B019 - levels live as long as their model
    def _at(self, p: float) -> tuple[float, float, float, float, float]:
        """(log J, d log J/dp, A, ∫Φ, Φ) at h = u·p: each GW integral once per level (a
        residual and its Jacobian need them at p and q, several times over)."""
        surf, h = self.surf, self.scale * p
        if hasattr(surf, "log_load_integral_derivative"):  # finite where J underflows
            dlog = float(surf.log_load_integral_derivative(h))
        else:
            J = float(surf.load_integral(h))
            dlog = float(surf.load_integral_derivative(h)) / J if J > 0.0 else math.nan
        return (
            float(surf.log_load_integral(h)),
            self.scale * dlog,
            float(surf.area_integral(h)),
            float(surf.tail_probability(h)),
            float(surf.pdf(h)),
        )

    def log_normal_load(self, p: float) -> tuple[float, float]:
        """log(F_N/F_N0) = log J(d) − log J(d_A) and its derivative (Eq 11)."""
        j, dj = self._at(p)[:2]
        return j - self.j0, dj

    def tangential_ratio(self, p: float, q: float) -> tuple[float, float, float]:
        """F̂_T = 1 − J(d0)/J(d) and its derivatives (Eq 9)."""
        jp, djp = self._at(p)[:2]
        jq, djq = self._at(q)[:2]
        e = math.exp(jq - jp)
        return -math.expm1(jq - jp), e * djp, -e * djq

    def slip(self, p: float, q: float) -> tuple[float, float, float]:
        """g_T/μ = λc (q − p) [µm] and its derivatives (Eqs 4–5)."""
        return self.lam * (q - p), -self.lam, self.lam

    def stick_area(self, p: float, q: float) -> tuple[float, float, float]:
        """Â_ST = [A(d0) + (d0 − d) Q(d0)]/A(d) and its derivatives (Eqs 13–14)."""
        s = self.scale
        _, _, den, tail, _ = self._at(p)
        _, _, area0, tail0, pdf0 = self._at(q)
        num = area0 + s * (q - p) * tail0
        val = num / den
        dnum_p = -s * tail0
        dnum_q = -s * s * (q - p) * pdf0
        return val, (dnum_p + val * s * tail) / den, dnum_q / den

    def area_ratio(self, p: float) -> tuple[float, float]:
        """A_r/A_r(F_N0) = A(d)/A(d_A) and its derivative (Eq 13)."""
        _, _, area, tail, _ = self._at(p)
        return area / self.A0, -self.scale * tail / self.A0

    def slip_limit(self, p: float) -> float:
        """inf: a rough surface does not slide as a whole at finite slip."""
        return math.inf


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
