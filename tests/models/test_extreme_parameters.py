"""Extreme but valid parameters give finite, accurate numbers (issue 17, point 5): the
exponential surface's loading curve F_T = μF_N(1 − e^{−g_T/(μλ)}) (Eq 9) at σ*, μ from the
smallest subnormal to 1e300, against mpmath at 50 digits, with no floating-point warning
(pytest turns warnings into errors)."""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

from cusp.models import ExponentialRoughSurface

CASES = [
    (1e-300, 0.3, 1e-300),
    (2.8e299, 0.0, 2.8e299),
    (5e-324, 0.5, 5e-324),
    (1e300, 0.3, 1e-300),
    (2.0, 0.3, 1e300),
    (2.0, 0.3, 0.1),
]
SLIPS = [0.0, 1e-12, 0.1, 1.0, 1e10]


def _oracle(sigma, nu, mu, g):
    with mp.workdps(50):
        s, n, m = mp.mpf(sigma), mp.mpf(nu), mp.mpf(mu)
        lam = s * (2 - n) / (2 * (1 - n))
        x = mp.mpf(g) / (m * lam)
        return float(-mp.expm1(-x)), float(m * 1000 * -mp.expm1(-x))


@pytest.mark.parametrize("sigma,nu,mu", CASES)
def test_loading_curve_at_extreme_parameters(sigma, nu, mu):
    surf = ExponentialRoughSurface(sigma, nu, mu)
    ratio = surf.force_ratio(SLIPS)
    force = surf.tangential_force(SLIPS, 1000.0)
    for g, r, f in zip(SLIPS, ratio, force):
        want_r, want_f = _oracle(sigma, nu, mu, g)
        assert np.isfinite(r) and np.isfinite(f)
        assert abs(r - want_r) <= 1e-15 * abs(want_r) + 1e-300
        # (1e-12 relative: results in the subnormal range keep fewer digits)
        assert abs(f - want_f) <= 1e-12 * abs(want_f) + 5e-324, (g, f, want_f)


def test_sphere_path_with_the_consistent_area_reading():
    # a trial point of the tracer reached a ≤ 0 (log of a non-positive load): a math domain
    # error ended the run; it is now a non-finite residual whose step is shortened. The
    # energies do not depend on the reading of Eq 32; the consistent reading of Â_SL at a
    # point is 1 − A_ST/A_r(F_N0) = 1 − (c/a0)²
    from cusp.models import ContactLoss, Sphere

    sphere = Sphere(1000.0, 0.2, 0.3, 0.1)
    cons = ContactLoss(sphere, 1000.0, 2.0, 850.0, area_reading="consistent").run()
    printed = ContactLoss(sphere, 1000.0, 2.0, 850.0).run()
    for kind in ("snap_back", "snap_through"):
        assert cons.energy[kind] == pytest.approx(printed.energy[kind], rel=1e-12)
    a0 = float(sphere.contact_radius(1000.0))
    for key in "ABCD":
        c = cons.points[key]["c"]
        assert cons.points[key]["A_SL"] == pytest.approx(1.0 - (c / a0) ** 2, rel=1e-12)


@pytest.mark.parametrize(
    "make",
    [
        lambda: __import__("cusp.models", fromlist=["Sphere"]).Sphere(1000.0, 5e-324, 0.3, 0.1),
        lambda: __import__("cusp.models", fromlist=["Sphere"]).Sphere(5e-324, 0.2, 0.3, 0.1),
        lambda: ExponentialRoughSurface(5e-324, 0.3, 0.1),
    ],
    ids=["sphere E subnormal", "sphere radius subnormal", "exponential sigma subnormal"],
)
def test_bodies_whose_path_cannot_be_scaled_are_refused_by_name(make):
    # (a ZeroDivisionError before): the refusal names the parameters and the range
    from cusp.models import ContactLoss
    from cusp.models.errors import ModelParameterError

    with pytest.raises(ModelParameterError, match=r"float range"):
        ContactLoss(make(), 1000.0, 0.34, 850.0).run()
