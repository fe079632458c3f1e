"""Smooth bodies: sphere compliance (Eq 2 with Hertz), cylinder and flat have no compliance law."""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from cusp.models import Cylinder, FlatPlane, Sphere
from cusp.models.cylinder import u_minus_sin_u
from cusp.models.errors import GrossSlidingError, ModelParameterError, NoComplianceLawError

STEEL = dict(radius=5000.0, E=0.21, nu=0.3, mu=0.1)  # R = 5 mm, E = 210 GPa = 0.21 N/µm²


def test_hertz_contact_radius():
    s = Sphere(**STEEL)
    # two identical spheres: R* = R/2, E* = E/(2(1 − ν²)); a³ = 3 F R*/(4 E*)
    E_star = 0.21 / (2 * (1 - 0.09))
    a = (3 * 10.0 * 2500.0 / (4 * E_star)) ** (1 / 3)
    assert s.contact_radius(10.0) == pytest.approx(a, rel=1e-15)
    assert s.G == pytest.approx(0.21 / 2.6, rel=1e-15)


def test_compliance_law_eq2():
    s = Sphere(**STEEL)
    F_N = 10.0
    with mp.workdps(40):
        a = mp.cbrt(3 * mp.mpf(F_N) * 2500 / (4 * (mp.mpf(0.21) / (2 * (1 - mp.mpf(0.3) ** 2)))))
        G = mp.mpf(0.21) / (2 * (1 + mp.mpf(0.3)))
        for F_T in (1e-12, 0.1, 0.5, 0.999):
            ratio = mp.mpf(F_T) / (mp.mpf(0.1) * F_N)
            ref = (
                3
                * (2 - mp.mpf(0.3))
                * mp.mpf(0.1)
                * F_N
                / (8 * G * a)
                * (1 - (1 - ratio) ** (mp.mpf(2) / 3))
            )
            assert float(abs(s.tangential_slip(F_T, F_N) - ref) / ref) <= 1e-14
    g = s.tangential_slip(0.5, F_N)
    assert s.tangential_force(g, F_N) == pytest.approx(0.5, rel=1e-14)
    # beyond the slip limit the spheres slide at μ F_N
    assert s.tangential_force(2 * s.slip_limit(F_N), F_N) == pytest.approx(0.1 * F_N)
    g = np.linspace(0, s.slip_limit(F_N), 50)
    assert np.all(np.diff(s.tangential_force(g, F_N)) > 0)


def test_sphere_gross_sliding_and_missing_parameters():
    s = Sphere(**STEEL)
    with pytest.raises(GrossSlidingError, match="mu\\*F_N"):
        s.tangential_slip(1.0, 10.0)
    with pytest.raises(ModelParameterError, match="missing: radius, E"):
        Sphere(nu=0.3, mu=0.1).tangential_slip(0.1, 10.0)
    with pytest.raises(ModelParameterError, match="radius must be a finite number > 0"):
        Sphere(radius=-1.0)
    with pytest.raises(ModelParameterError, match="nu"):
        Sphere(nu=0.7)


@pytest.mark.parametrize("body", [Cylinder(), FlatPlane()])
def test_no_compliance_law(body):
    with pytest.raises(NoComplianceLawError, match="no compliance"):
        body.tangential_slip(0.1, 1.0)
    with pytest.raises(NoComplianceLawError):
        body.tangential_force(0.1, 1.0)


def test_cylinder_message_says_why():
    with pytest.raises(NoComplianceLawError, match="paper gives none"):
        Cylinder().tangential_slip(0.1, 1.0)


def test_u_minus_sin_u_series():
    with mp.workdps(400):  # u − sin u ≈ u³/6 needs ~3|log10 u| digits
        for u in (1e-100, 1e-8, 1e-3, 0.5, 1.999, 2.0, 3.0):
            ref = mp.mpf(u) - mp.sin(mp.mpf(u))
            assert float(abs(u_minus_sin_u(u) - ref) / ref) <= 3e-16


def test_stick_zone_ratios():
    F = np.array([0.0, 0.2, 0.875, 1.0])
    assert Sphere.stick_zone_ratio(F) == pytest.approx((1 - F) ** (1 / 3))
    assert Cylinder.stick_zone_ratio(F) == pytest.approx(np.sqrt(1 - F))
    assert math.isclose(Sphere.stick_area_ratio(0.875), 0.25, rel_tol=1e-15)


@pytest.mark.parametrize("F", [2.0**-52, 2.0**-53, 3 * 2.0**-53])
def test_sphere_stick_force_ratio_one_ulp_above_zero(F):
    """Found by hypothesis: at F̂_T = 2⁻⁵² the platform cbrt rounds (1 − F̂_T)^{1/3} above 1,
    which made the unused F̂_T > 1/2 branch warn (an error under the test settings). The value
    is Eq 21 in mpmath at 50 digits: F − [1 − (1 − F)^{2/3}]^{3/2}."""
    with mp.workdps(50):
        f = mp.mpf(F)
        ref = f - (1 - (1 - f) ** (mp.mpf(2) / 3)) ** (mp.mpf(3) / 2)
    got = float(Sphere.stick_force_ratio(F))
    assert abs(got - float(ref)) <= 1e-15 * float(ref)
