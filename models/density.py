"""Rough surface over a general, user-supplied summit-height density Φ(z) [1/µm].

The same code path as every other density (:mod:`cusp.models.rough`), with all integrals by
adaptive quadrature (:mod:`cusp.models._quadrature`, QUADPACK with the (z − h)^k end-point weight
put into QAWS). Slower than the closed forms (~1 ms per integral) but exact to ~1e-13 for
smooth or piecewise-smooth Φ; give the points where Φ is not smooth as ``breakpoints``
(histogram edges are set for you).

>>> heights = HeightDensity.weibull(shape=2.0, scale=3.0, loc=-2.5)
>>> surface = GeneralRoughSurface(heights, nu=0.3, mu=0.1, sigma=2.0)
>>> surface.stick_force_ratio(0.5, separation=1.0)  # doctest: +SKIP
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np

from .errors import ModelParameterError, check_positive
from .rough import RoughSurface

__all__ = ["HeightDensity", "GeneralRoughSurface", "weibull_surface"]


class HeightDensity:
    """A summit-height probability density Φ(z) [1/µm] on ``support`` = (lo, hi) [µm].

    The density is checked to integrate to 1 within ``rtol``.

    Parameters
    ----------
    pdf : callable
        Φ(z) [1/µm] of a height z [µm]: accepts a float (and preferably an array) and
        returns Φ ≥ 0.
    support : tuple of (float, float), optional
        ``(lo, hi)`` [µm], ``lo < hi`` (default the whole line).
    breakpoints : sequence of float, optional
        Heights [µm] where Φ or its derivatives jump (the quadratures split there).
    scale : float, optional
        Length scale [µm] used to split infinite intervals (≈ the standard deviation;
        default from the support and breakpoints).
    name : str, optional
        A label shown by ``repr``.
    rtol : float, optional
        The tolerance of the check that Φ integrates to 1 (default 1e-6).

    Raises
    ------
    ModelParameterError
        ``pdf`` not callable, a bad support or breakpoint, or an integral other than 1 (the
        message names the integral found).
    """

    def __init__(
        self,
        pdf: Callable,
        support: tuple[float, float] = (-math.inf, math.inf),
        breakpoints: Sequence[float] = (),
        *,
        scale: float | None = None,
        name: str = "custom",
        rtol: float = 1e-6,
    ) -> None:
        if not callable(pdf):
            raise ModelParameterError(f"pdf must be callable, got {pdf!r}")
        lo, hi = (float(v) for v in support)
        if math.isnan(lo) or math.isnan(hi) or not lo < hi:
            raise ModelParameterError(
                f"support must be (lo, hi) with lo < hi [µm], got {support!r}"
            )
        bps = sorted(float(p) for p in breakpoints)
        if not all(math.isfinite(p) for p in bps):
            raise ModelParameterError(f"breakpoints must be finite [µm], got {breakpoints!r}")
        self.pdf = pdf
        self.support = (lo, hi)
        self.breakpoints = tuple(p for p in bps if lo < p < hi)
        self.name = name
        finite = [v for v in (lo, hi, *bps) if math.isfinite(v)]
        default_scale = (max(finite) - min(finite)) / 4 if len(finite) > 1 else 1.0
        #: length scale [µm] used to split infinite intervals (≈ the standard deviation)
        self.scale = check_positive("scale", scale if scale is not None else default_scale, "µm")
        from ._quadrature import integrate_pdf

        total = integrate_pdf(pdf, self.support, self.breakpoints, self.scale)
        if not (math.isfinite(total) and abs(total - 1.0) <= rtol):
            raise ModelParameterError(
                f"pdf must integrate to 1 over support {self.support!r} (within rtol={rtol:g}), "
                f"got integral {total!r}"
            )

    @classmethod
    def weibull(cls, shape: float, scale: float, loc: float = 0.0) -> HeightDensity:
        """Return Weibull heights: Φ(z) = (k/λ)((z−loc)/λ)^{k−1} exp(−((z−loc)/λ)^k).

        The density is zero at and below ``loc``.

        Parameters
        ----------
        shape : float
            The shape k > 0.
        scale : float
            The scale λ > 0 [µm].
        loc : float, optional
            The lowest height [µm] (default 0).

        Returns
        -------
        HeightDensity
            The density.
        """
        k = check_positive("shape", shape)
        lam = check_positive("scale", scale, "µm")
        if not math.isfinite(loc):
            raise ModelParameterError(f"loc must be finite [µm], got {loc!r}")

        def pdf(z):
            if type(z) is float:  # (QUADPACK's calls, one value each: 3 µs, not 28)
                v = (z - loc) / lam
                return (k / lam) * v ** (k - 1.0) * math.exp(-(v**k)) if v > 0.0 else 0.0
            u = np.maximum((np.asarray(z, dtype=float) - loc) / lam, 0.0)
            with np.errstate(divide="ignore", invalid="ignore"):
                val = (k / lam) * u ** (k - 1.0) * np.exp(-(u**k))
            return np.where(u > 0.0, val, 0.0)

        std = lam * math.sqrt(math.gamma(1 + 2 / k) - math.gamma(1 + 1 / k) ** 2)
        return cls(pdf, (loc, math.inf), scale=std, name=f"weibull(k={k:g}, scale={lam:g})")

    @classmethod
    def histogram(cls, edges: Sequence[float], counts: Sequence[float]) -> HeightDensity:
        """Return a piecewise-constant Φ from a histogram of measured summit heights.

        Parameters
        ----------
        edges : sequence of float, shape (b + 1,)
            Bin edges [µm], strictly increasing.
        counts : sequence of float, shape (b,)
            Counts per bin (≥ 0, not all zero).

        Returns
        -------
        HeightDensity
            The normalised density.

        Raises
        ------
        ModelParameterError
            Edges or counts malformed.
        """
        e = np.asarray(edges, dtype=float)
        n = np.asarray(counts, dtype=float)
        if e.ndim != 1 or e.size < 2 or not np.all(np.isfinite(e)):
            raise ModelParameterError(f"edges must be >= 2 finite values [µm], got {e!r}")
        if np.any(np.diff(e) <= 0):
            raise ModelParameterError(f"edges must be strictly increasing, got {e!r}")
        if n.shape != (e.size - 1,) or np.any(~np.isfinite(n)) or np.any(n < 0):
            raise ModelParameterError(f"counts must be {e.size - 1} finite values >= 0, got {n!r}")
        if n.sum() <= 0:
            raise ModelParameterError(f"counts must not all be zero, got {n!r}")
        heights = n / (n.sum() * np.diff(e))

        def pdf(z):
            z = np.asarray(z, dtype=float)
            i = np.clip(np.searchsorted(e, z, side="right") - 1, 0, heights.size - 1)
            return np.where((z >= e[0]) & (z < e[-1]), heights[i], 0.0)

        centers = 0.5 * (e[1:] + e[:-1])
        w = n / n.sum()
        mean = float(np.sum(w * centers))
        std = math.sqrt(float(np.sum(w * ((centers - mean) ** 2 + np.diff(e) ** 2 / 12))))
        return cls(pdf, (e[0], e[-1]), tuple(e[1:-1]), scale=max(std, 1e-12), name="histogram")

    def moments(self) -> tuple[float, float]:
        """Return the mean and standard deviation of the heights, by quadrature.

        Returns
        -------
        mean : float
            The mean height [µm].
        std : float
            The standard deviation [µm].
        """
        from ._quadrature import integrate_pdf

        args = (self.support, self.breakpoints, self.scale)
        tol = 1e-14 * self.scale
        m = integrate_pdf(lambda z: z * self.pdf(z), *args, epsabs=tol)
        m2 = integrate_pdf(lambda z: (z - m) ** 2 * self.pdf(z), *args, epsabs=tol * self.scale)
        return m, math.sqrt(m2)

    def __repr__(self) -> str:
        return f"HeightDensity({self.name}, support={self.support})"


class GeneralRoughSurface(RoughSurface):
    """Rough surface over any :class:`HeightDensity` (all integrals by quadrature).

    The methods are those of :class:`~cusp.models.RoughSurface`.

    Parameters
    ----------
    heights : HeightDensity
        The summit-height density.
    nu : float
        Poisson's ratio ν, in (−1, 0.5].
    mu : float
        Friction coefficient μ > 0.
    sigma : float, optional
        σ* [µm]; it only enters λ (default: the standard deviation of the heights).
    E : float, optional
        Young's modulus of each body [N/µm²] (E* = E/[2(1 − ν²)]).
    radius : float, optional
        Composite summit radius ρ* [µm].
    density : float, optional
        Summit density η [1/µm²].
    nominal_area : float, optional
        Nominal contact area A_n [µm²].

    Raises
    ------
    ModelParameterError
        ``heights`` not a HeightDensity, or a parameter out of its range.
    """

    load_dependent = True

    def __init__(
        self,
        heights: HeightDensity,
        nu: float,
        mu: float,
        sigma: float | None = None,
        E: float | None = None,
        radius: float | None = None,
        density: float | None = None,
        nominal_area: float | None = None,
    ) -> None:
        if not isinstance(heights, HeightDensity):
            raise ModelParameterError(
                f"heights must be a HeightDensity (wrap your pdf in HeightDensity(pdf, support))"
                f", got {heights!r}"
            )
        self.heights = heights
        self._mean, std = heights.moments()
        super().__init__(std if sigma is None else sigma, nu, mu, E, radius, density, nominal_area)

    @property
    def support(self):
        """The support ``(lo, hi)`` [µm] of the heights."""
        return self.heights.support

    @property
    def breakpoints(self):
        """The heights [µm] where Φ or its derivatives jump."""
        return self.heights.breakpoints

    def pdf(self, z):
        return self.heights.pdf(z)

    def _center(self) -> float:
        return self._mean


def weibull_surface(
    sigma: float,
    nu: float,
    mu: float,
    shape: float,
    E: float | None = None,
    radius: float | None = None,
    density: float | None = None,
    nominal_area: float | None = None,
) -> GeneralRoughSurface:
    """Build a rough surface over Weibull summit heights (the scene model ``rough-weibull``).

    The Weibull scale is σ*/√(Γ(1 + 2/k) − Γ(1 + 1/k)²) [µm], so that the heights have
    standard deviation σ*.

    Parameters
    ----------
    sigma : float
        The heights' standard deviation σ* [µm].
    nu : float
        Poisson's ratio ν, in (−1, 0.5].
    mu : float
        Friction coefficient μ > 0.
    shape : float
        The Weibull shape k, 0.0117 < k < 1e15.
    E : float, optional
        Young's modulus of each body [N/µm²] (E* = E/[2(1 − ν²)]).
    radius : float, optional
        Composite summit radius ρ* [µm].
    density : float, optional
        Summit density η [1/µm²].
    nominal_area : float, optional
        Nominal contact area A_n [µm²].

    Returns
    -------
    GeneralRoughSurface
        The surface.

    Raises
    ------
    ModelParameterError
        A parameter out of its range.
    """
    k = check_positive("shape", shape)
    sigma = check_positive("sigma", sigma, "µm")
    # Weibull scale such that the heights have standard deviation sigma
    try:
        spread = math.sqrt(math.gamma(1 + 2 / k) - math.gamma(1 + 1 / k) ** 2)
    except (OverflowError, ValueError):  # Γ(1 + 2/k) beyond the float range (k < 0.0117)
        spread = math.nan
    if not (math.isfinite(spread) and spread > 0.0):  # k > ~1e15: Γ(1 + 2/k) rounds to 1
        raise ModelParameterError(
            f"shape = {shape!r}: the Weibull heights have no finite, nonzero spread in floating "
            "point (sqrt(Γ(1 + 2/k) − Γ(1 + 1/k)²)); allowed: a shape k with 0.0117 < k < 1e15"
        )
    heights = HeightDensity.weibull(k, sigma / spread)
    return GeneralRoughSurface(
        heights,
        nu,
        mu,
        sigma=sigma,
        E=E,
        radius=radius,
        density=density,
        nominal_area=nominal_area,
    )
