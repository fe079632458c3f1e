"""Exponential rough surface: loading curve, normal contact, errors (Eqs 1, 9, 11, 13)."""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cusp.models import ExponentialRoughSurface
from cusp.models.errors import GrossSlidingError, MissingLoadScaleError, ModelParameterError

SCALE = dict(E=210.0e-6 * 1e6, radius=100.0, density=1e-4, nominal_area=1e6)


def surface(**kw):
    return ExponentialRoughSurface(sigma=2.0, nu=0.3, mu=0.1, **kw)


def test_lambda_and_threshold():
    s = surface()
    assert s.lam == pytest.approx(2.0 * 1.7 / 1.4, rel=1e-15)
    # g_N0 = 2(1 − ν) g_T / (μ(2 − ν)), independent of σ*
    assert s.stick_threshold(0.34) == pytest.approx(2 * 0.7 * 0.34 / (0.1 * 1.7), rel=1e-15)


def test_loading_curve_against_mpmath():
    # Eq 9 from its definition: F_T/(μF_N) = (S + T)/J(d) with Φ = e^{−z/σ}/σ, v = (z − d0)/σ:
    # T/J = e^{−x} ∫_0^∞ [(v + x)^{3/2} − v^{3/2}] e^{−v} dv / Γ(5/2),
    # S/J = ∫_0^x v^{3/2} e^{−v} dv / Γ(5/2)  (summits with d < z < d0 slide)
    s = surface()
    with mp.workdps(50):
        for g_T in (1e-12, 0.01, 0.34, 2.0, 8.0):
            x = mp.mpf(g_T) / (mp.mpf(0.1) * mp.mpf(s.lam))

            def stick(v, x=x):
                return ((v + x) ** 1.5 - v**1.5) * mp.exp(-v)

            ref = mp.exp(-x) * mp.quad(stick, [0, 1, mp.inf])
            ref += mp.quad(lambda v: v**1.5 * mp.exp(-v), [0, x])
            ref /= mp.gamma(2.5)
            got = s.tangential_force(g_T, 1000.0) / (0.1 * 1000.0)
            assert abs(got - ref) <= 2e-15 * ref, g_T


@settings(max_examples=100, deadline=None)
@given(
    g=st.floats(1e-200, 30.0),
    FN=st.floats(1e-3, 1e6),
)
def test_slip_is_inverse_of_force(g, FN):
    s = surface()
    FT = s.tangential_force(g, FN)
    if FT < s.mu * FN:
        g_back = s.tangential_slip(FT, FN)
        assert s.tangential_force(g_back, FN) == pytest.approx(FT, rel=4e-16, abs=0)
        # the inverse is ill-conditioned near gross slip: cond = (e^x − 1)/x, x = g/(μλ)
        x = g / (s.mu * s.lam)
        cond = math.expm1(x) / x
        assert g_back == pytest.approx(g, rel=4e-16 * cond + 1e-15)


def test_gross_sliding_is_an_error():
    s = surface()
    with pytest.raises(GrossSlidingError, match="mu\\*F_N"):
        s.tangential_slip(100.0, 1000.0)
    with pytest.raises(GrossSlidingError):
        s.tangential_slip([10.0, 150.0], 1000.0)


def test_normal_contact_needs_load_scale():
    s = surface()
    with pytest.raises(MissingLoadScaleError, match="E, radius, density, nominal_area"):
        s.separation(1000.0)
    with pytest.raises(MissingLoadScaleError, match="radius"):
        surface(E=1.0).real_contact_area(0.0)


def test_normal_contact_closed_form():
    s = surface(**SCALE)
    E_star = SCALE["E"] / (2 * (1 - 0.3**2))
    K = 4 / 3 * E_star * math.sqrt(SCALE["radius"]) * SCALE["density"] * SCALE["nominal_area"]
    assert s.load_scale == pytest.approx(K, rel=1e-15)
    d = s.separation([100.0, 1000.0])
    assert s.normal_load(d) == pytest.approx([100.0, 1000.0], rel=1e-14)
    # F_N = K Γ(5/2) σ^{3/2} e^{−d/σ}
    assert s.normal_load(3.0) == pytest.approx(
        K * 0.75 * math.sqrt(math.pi) * 2**1.5 * math.exp(-1.5)
    )
    # A_r ∝ F_N for this density
    A = s.real_contact_area(d)
    assert A[1] / A[0] == pytest.approx(10.0, rel=1e-14)
    assert s.real_contact_area(3.0) == pytest.approx(
        math.pi * SCALE["radius"] * SCALE["density"] * SCALE["nominal_area"] * 2 * math.exp(-1.5)
    )
    assert s.normal_load_derivative(3.0) == pytest.approx(-s.normal_load(3.0) / 2.0)


def test_difference_without_cancellation():
    s = surface()
    g = 1e-250
    diff = s.load_integral_difference(0.0, g)
    assert diff == pytest.approx(s.load_integral(0.0) * g / 2.0, rel=1e-15)
    assert s.stick_load_integral(0.0, g) + s.slip_load_integral(0.0, g) == pytest.approx(diff)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(sigma=-1.0, nu=0.3, mu=0.1), "sigma must be a finite number > 0 \\[µm\\], got -1.0"),
        (dict(sigma=0.0, nu=0.3, mu=0.1), "sigma .* got 0.0"),
        (dict(sigma=float("nan"), nu=0.3, mu=0.1), "sigma .* got nan"),
        (dict(sigma=2.0, nu=0.6, mu=0.1), "nu .*\\(-1, 0.5\\], got 0.6"),
        (dict(sigma=2.0, nu=-1.0, mu=0.1), "nu .* got -1.0"),
        (dict(sigma=2.0, nu=0.3, mu=0.0), "mu must be .* > 0, got 0.0"),
        (dict(sigma=2.0, nu=0.3, mu=math.inf), "mu .* got inf"),
        (dict(sigma=2.0, nu=0.3, mu=0.1, E=-5.0), "E must be .* got -5.0"),
    ],
)
def test_bad_parameters(kwargs, match):
    with pytest.raises(ModelParameterError, match=match):
        ExponentialRoughSurface(**kwargs)
    assert issubclass(ModelParameterError, ValueError)


@pytest.mark.parametrize("bad", [-0.1, 1.5, float("nan"), float("inf"), [0.2, 1.01]])
def test_bad_ratio(bad):
    s = surface()
    with pytest.raises(ModelParameterError, match="FT_hat must be finite and in \\[0, 1\\]"):
        s.stick_force_ratio(bad)
    with pytest.raises(ModelParameterError, match="FT_hat"):
        s.stick_area_ratio(bad)


def test_bad_loads():
    s = surface()
    with pytest.raises(ModelParameterError, match="F_N must be > 0"):
        s.tangential_force(0.1, -5.0)
    with pytest.raises(ModelParameterError, match="g_T must be finite and >= 0"):
        s.tangential_force(float("nan"), 5.0)
    with pytest.raises(ModelParameterError, match="F_T"):
        s.tangential_slip(-1.0, 5.0)


def test_loading_curve_oracle_of_fig6():
    # docs/physics.md §7: along A→B, g'_T = g_A + μλ ln(F'_N/F_N0) keeps J(d0) fixed
    s = surface()
    F_N0, g_A, F_N1 = 1000.0, 0.34, 850.0
    F_A = s.tangential_force(g_A, F_N0)
    F_T1 = F_A - s.mu * (F_N0 - F_N1)
    g1 = s.tangential_slip(F_T1, F_N1)
    assert g1 == pytest.approx(g_A + s.mu * s.lam * math.log(F_N1 / F_N0), rel=1e-13)
    np.testing.assert_allclose(s.mu * F_N1 - F_T1, s.mu * F_N0 - F_A, rtol=1e-14)


def test_load_arguments_are_optional_but_checked():
    s = surface()
    assert s.stick_force_ratio(0.5, normal_load=10.0) == s.stick_force_ratio(0.5)
    with pytest.raises(ModelParameterError, match="normal_load must be > 0"):
        s.stick_force_ratio(0.5, normal_load=-1.0)
    with pytest.raises(ModelParameterError, match="separation must be finite"):
        s.stick_area_ratio(0.5, separation=float("nan"))
