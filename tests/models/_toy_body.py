"""A toy body for the contact-loss protocol (cusp.models.protocol), registered by the tests.

Not a model of the paper: a "brush" invented so that the whole path O-A-B-C-D and its energies
have closed forms a reader can check by hand. Contact radius a [µm] and stick radius c ≤ a:

* normal load       F_N = k a²                    (k [N/µm²], ``stiffness``)
* tangential load   F_T = μ k (a² − c²) = μ F_N [1 − (c/a)²]
* compliance        g_T = μ β (a − c)             (β dimensionless, ``compliance``)
* areas             A_r ∝ a², A_ST ∝ c²

so the body slides as a whole at g_T = μβa (c = 0). Levels p = a/a0, q = c/a0 with
a0 = √(F_N0/k) [µm]. On the path, with G = μβa0 [µm], K = μF_N0 [N], x_A = g_A/G,
q_A = 1 − x_A and p_B = √(F'_N/F_N0) (see :func:`path_closed_forms`):

* A: F_A = K(1 − q_A²)
* AB (q = q_A): g_T = G(p − q_A), F_T = K(p² − q_A²), so F'_T = F_A − μ(F_N0 − F'_N)
* BC (p = p_B): g_T = G(p_B − q), F_T = K(p_B² − q²)
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np

from cusp.models.errors import check_positive
from cusp.models.registry import MU, Parameter

#: the toy's parameters as a scene gives them (k > 0, 0 < β ≤ 1)
STIFFNESS = Parameter("stiffness", "N/µm²", description="k in F_N = k a²")
COMPLIANCE = Parameter("compliance", "", 0.0, 1.0, upper_inclusive=True, description="β")
REQUIRED = (MU, STIFFNESS, COMPLIANCE)


class BrushLevels:
    """p = a/a0, q = c/a0; each method returns the value and its partial derivatives."""

    names = ("a", "c")
    p0 = 1.0  # a = a0 under F_N0

    def __init__(self, body: BrushBody, F_N0: float, g_A: float) -> None:
        self.scale = math.sqrt(F_N0 / body.stiffness)  # a0 [µm]
        self.beta_a0 = body.compliance * self.scale  # β a0 [µm]

    def log_normal_load(self, p: float) -> tuple[float, float]:
        return 2.0 * math.log(p), 2.0 / p  # log(F_N/F_N0) = log(a²/a0²)

    def tangential_ratio(self, p: float, q: float) -> tuple[float, float, float]:
        return 1.0 - (q / p) ** 2, 2.0 * q * q / p**3, -2.0 * q / (p * p)

    def slip(self, p: float, q: float) -> tuple[float, float, float]:
        return self.beta_a0 * (p - q), self.beta_a0, -self.beta_a0  # g_T/μ [µm]

    def stick_area(self, p: float, q: float) -> tuple[float, float, float]:
        return (q / p) ** 2, -2.0 * q * q / p**3, 2.0 * q / (p * p)

    def area_ratio(self, p: float) -> tuple[float, float]:
        return p * p, 2.0 * p

    def slip_limit(self, p: float) -> float:
        return self.beta_a0 * p  # s(p, 0)


class BrushBody:
    """``BrushBody(mu, stiffness, compliance)``: μ, k [N/µm²], β (module docstring)."""

    def __init__(self, mu: float, stiffness: float, compliance: float) -> None:
        self.mu = check_positive("mu", mu)
        self.stiffness = check_positive("stiffness", stiffness, "N/µm²")
        self.compliance = check_positive("compliance", compliance)

    def contact_levels(self, normal_load: float, max_slip: float) -> BrushLevels:
        return BrushLevels(self, normal_load, max_slip)

    def tangential_force(self, g_T, F_N):
        """F_T [N] = μF_N[1 − (1 − g_T/(μβa))²], μF_N beyond the slip limit μβa."""
        a = np.sqrt(np.asarray(F_N, dtype=float) / self.stiffness)
        r = np.minimum(np.asarray(g_T, dtype=float) / (self.mu * self.compliance * a), 1.0)
        return self.mu * F_N * (1.0 - (1.0 - r) ** 2)


def path_closed_forms(mu, stiffness, compliance, F_N0, g_A, F_Np, dps: int = 30):
    """Points A, B, C, D ({g_T, F_T, F_N, A_SL (printed reading)}, C None if F_A ≥ μF'_N)
    and the energies ABD, ABC [N·µm] of the toy's path, in mpmath at ``dps`` digits.

    With u = g_T/G: on AB F_T = K((q_A + u)² − q_A²), on BC F_T = K(p_B² − (p_B − u)²), so
    ABD = KG ∫_{u_B}^{x_A} [2u² + 2u(q_A − p_B)] du and
    ABC = ABD + KG ∫_{x_A}^{u_C} [1 − q_A² − p_B² + (p_B − u)²] du.
    """
    with mp.workdps(dps):
        mu, k, beta = mp.mpf(mu), mp.mpf(stiffness), mp.mpf(compliance)
        F_N0, g_A, F_Np = mp.mpf(F_N0), mp.mpf(g_A), mp.mpf(F_Np)
        a0 = mp.sqrt(F_N0 / k)
        G, K = mu * beta * a0, mu * F_N0
        x_A = g_A / G
        q_A, p_B = 1 - x_A, mp.sqrt(F_Np / F_N0)

        def point(p, q, F_N):
            return {
                "g_T": G * (p - q),
                "F_T": K * (p * p - q * q),
                "F_N": F_N,
                "A_SL": (1 - (q / p) ** 2) + (1 - p * p),  # Eq 32 as printed, A_r ∝ a²
            }

        pts = {"A": point(1, q_A, F_N0), "B": point(p_B, q_A, F_Np)}
        pts["D"] = point(p_B, p_B - x_A, F_Np)
        u_B = p_B - q_A
        abd = K * G * (mp.mpf(2) / 3 * (x_A**3 - u_B**3) + (q_A - p_B) * (x_A**2 - u_B**2))
        energy = {"snap_back": abd, "snap_through": None}
        pts["C"] = None
        if pts["A"]["F_T"] < mu * F_Np:
            q_C = mp.sqrt(p_B**2 - 1 + q_A**2)  # F_T = F_A on BC
            pts["C"] = point(p_B, q_C, F_Np)
            u_C = p_B - q_C
            extra = (1 - q_A**2 - p_B**2) * (u_C - x_A) + ((p_B - x_A) ** 3 - (p_B - u_C) ** 3) / 3
            energy["snap_through"] = abd + K * G * extra
        return pts, energy
