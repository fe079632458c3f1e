"""Two ideally flat (smooth, rigid-plane) surfaces (paper Sec. 3.3, Eqs 30–31).

Every point of the interface carries the same traction, so the whole contact sticks until
F_T = μ F_N and then slides at once:

* F̂_ST = F̂_T for 0 ≤ F̂_T < 1, and 0 at F̂_T = 1   (Eq 30)
* Â_ST = 1   for 0 ≤ F̂_T < 1, and 0 at F̂_T = 1   (Eq 31)

There is no compliance law either (the slip is 0 until gross sliding, then indeterminate).
"""

from __future__ import annotations

from typing import NoReturn

import numpy as np

from .errors import NoComplianceLawError, check_positive, check_ratio
from .protocol import no_compliance_law

__all__ = ["FlatPlane"]

_MESSAGE = (
    "FlatPlane has no compliance law: ideally flat planes do not slip at all for F_T < mu*F_N "
    "and slide as a whole at F_T = mu*F_N, so g_T(F_T) is not a function."
)


class FlatPlane:
    """Two ideally flat surfaces in contact.

    Parameters
    ----------
    mu : float, optional
        The friction coefficient μ > 0 (the stick ratios do not depend on it).
    """

    def __init__(self, mu=None) -> None:
        self.mu = None if mu is None else check_positive("mu", mu)

    @staticmethod
    def stick_force_ratio(FT_hat):
        """Return F̂_ST = F̂_T (F̂_T < 1), 0 at F̂_T = 1 (Eq 30).

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
        return np.where(F < 1.0, F, 0.0)

    @staticmethod
    def stick_area_ratio(FT_hat):
        """Return Â_ST = 1 (F̂_T < 1), 0 at F̂_T = 1 (Eq 31).

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
        return np.where(F < 1.0, 1.0, 0.0)

    def tangential_slip(self, F_T, F_N):
        """Not available: g_T(F_T) is not a function for flat planes.

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
        """Not available: F_T(g_T) is not a function for flat planes.

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
        return "FlatPlane()" if self.mu is None else f"FlatPlane(mu={self.mu!r})"
