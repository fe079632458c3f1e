"""Two identical parallel elastic cylinders in partial slip, per unit length (Sec. 3.2, Eqs 23–29).

With F̂_T = F_T/(μ F_N) and k = c/a the stick half-width over the contact half-width:

* c/a = √(1 − F̂_T)                                                      (Eq 26)
* F̂_ST = (2/π)[√(F̂_T(1 − F̂_T)) + arctan√((1 − F̂_T)/F̂_T)] + F̂_T − 1     (Eq 28)
* Â_ST = c/a                                                             (Eq 29)

Numerics: Eq 28 loses every digit as F̂_T → 0 (the bracket tends to π/2). With w = arcsin√F̂_T
it is F̂_ST = F̂_T − (2w − sin 2w)/π, and u − sin u is summed as a series for u < 2; for
F̂_T > 1/2, with v = arcsin√(1 − F̂_T), F̂_ST = (2v + sin 2v)/π − (1 − F̂_T).

No compliance law: the paper gives none (the 2-D elastic displacement of a line contact is
defined only up to a datum), so a cylinder cannot follow a load–displacement path; the methods
that would need one raise :class:`cusp.models.errors.NoComplianceLawError`.
"""

from __future__ import annotations

import math
from typing import NoReturn

import numpy as np

from .errors import NoComplianceLawError, check_ratio
from .protocol import no_compliance_law

__all__ = ["Cylinder", "u_minus_sin_u"]

# u − sin u = Σ_{j≥1} (−1)^{j+1} u^{2j+1}/(2j+1)!; 14 terms reach 1e-17 relative at u = 2
_SERIES = [(-1.0) ** (j + 1) / math.factorial(2 * j + 1) for j in range(1, 15)]


def u_minus_sin_u(u):
    """u − sin u without cancellation (series below u = 2, direct above)."""
    u = np.asarray(u, dtype=float)
    u2 = u * u
    acc = np.zeros_like(u)
    for c in reversed(_SERIES):
        acc = acc * u2 + c
    series = acc * u2 * u
    return np.where(np.abs(u) < 2.0, series, u - np.sin(u))


_MESSAGE = (
    "Cylinder has no compliance (load-displacement) law: the paper gives none, because the "
    "2-D elastic displacement of a line contact is defined only up to an arbitrary datum. "
    "Only the stick ratios (Eqs 26-29) are available; use Sphere for a loading path."
)


class Cylinder:
    """Two identical parallel cylinders (per unit length).

    Parameters
    ----------
    nu : float, optional
        Poisson's ratio ν, in (−1, 0.5].
    mu : float, optional
        The friction coefficient μ > 0 (the stick ratios do not depend on it).
    """

    def __init__(self, nu=None, mu=None) -> None:
        from .errors import check_poisson, check_positive

        self.nu = None if nu is None else check_poisson(nu)
        self.mu = None if mu is None else check_positive("mu", mu)

    @staticmethod
    def stick_zone_ratio(FT_hat):
        """Return the stick-zone ratio c/a = √(1 − F̂_T) (Eq 26).

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
        return np.sqrt(1.0 - check_ratio(FT_hat))

    @staticmethod
    def stick_force_ratio(FT_hat):
        """Return F̂_ST(F̂_T) (Eq 28), without cancellation at both ends.

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
        m = 1.0 - F
        w = np.arcsin(np.sqrt(F))
        low = F - u_minus_sin_u(2.0 * w) / math.pi
        v = np.arcsin(np.sqrt(m))
        high = (2.0 * v + np.sin(2.0 * v)) / math.pi - m
        return np.where(F <= 0.5, low, high)

    @staticmethod
    def stick_area_ratio(FT_hat):
        """Return Â_ST(F̂_T) = c/a = √(1 − F̂_T) (Eq 29).

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
        return np.sqrt(1.0 - check_ratio(FT_hat))

    def tangential_slip(self, F_T, F_N):
        """Not available: the paper gives no compliance law for cylinders.

        Parameters
        ----------
        F_T : array_like
            Tangential force [N].
        F_N : array_like
            Normal load [N].

        Raises
        ------
        NoComplianceLawError
            Always: the body has no compliance law (see the module docstring).
        """
        raise NoComplianceLawError(_MESSAGE)

    def tangential_force(self, g_T, F_N):
        """Not available: the paper gives no compliance law for cylinders.

        Parameters
        ----------
        g_T : array_like
            Tangential slip [µm].
        F_N : array_like
            Normal load [N].

        Raises
        ------
        NoComplianceLawError
            Always: the body has no compliance law (see the module docstring).
        """
        raise NoComplianceLawError(_MESSAGE)

    compliance = tangential_slip

    def contact_levels(self, normal_load: float, max_slip: float) -> NoReturn:
        """Not available: no compliance law, so no contact-loss path.

        Parameters
        ----------
        normal_load : float
            F_N0 [N].
        max_slip : float
            g_A [µm].

        Raises
        ------
        NoComplianceLawError
            Always: the body has no compliance law (see the module docstring).
        """
        raise no_compliance_law(type(self).__name__)

    def __repr__(self) -> str:
        return f"Cylinder(nu={self.nu!r}, mu={self.mu!r})"
