"""Gaussian rough surface from light (d/σ* = 6) to heavy (d/σ* = −3) loads against mpmath.

References: reference/mp_reference.py (defining integrals at 40 digits; see its docstring),
stored in reference_values.json at the exact binary inputs.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cusp.models import (
    ExponentialRoughSurface,
    GaussianRoughSurface,
    GeneralRoughSurface,
    HeightDensity,
)
from cusp.models.errors import GrossSlidingError, MissingLoadScaleError, ModelParameterError

SIGMA = 2.0
SCALE = dict(E=0.2, radius=100.0, density=1e-4, nominal_area=1e6)


def surface(**kw):
    return GaussianRoughSurface(SIGMA, 0.3, 0.1, **kw)


def test_stick_ratios_against_mpmath(reference_table, rel_err):
    s = surface()
    rows = reference_table["gaussian"]
    assert {r[0] for r in rows} == {6.0, 3.0, 0.0, -3.0}
    worst = 0.0
    for t, Fhex, stick, area in rows:
        F = float.fromhex(Fhex)
        d = SIGMA * t
        worst = max(
            worst,
            rel_err(s.stick_force_ratio(F, separation=d), stick),
            rel_err(s.stick_area_ratio(F, separation=d), area),
        )
    assert worst <= 5e-14


def test_loading_curve_against_mpmath(reference_table, rel_err):
    s = surface()
    for t, dhex, ref in reference_table["gaussian_loading"]:
        delta = float.fromhex(dhex)  # g_N0/σ*
        g_T = delta * SIGMA * s.mu * s.lam / SIGMA
        assert rel_err(s.force_ratio(g_T, separation=SIGMA * t), ref) <= 1e-14, (t, delta)


def test_load_and_area_integrals_against_mpmath(reference_table, rel_err):
    s = surface()
    for t, J, A in reference_table["gaussian_JA"]:
        assert rel_err(s.load_integral(SIGMA * t) / SIGMA**1.5, J) <= 1e-14
        assert rel_err(s.area_integral(SIGMA * t) / SIGMA, A) <= 1e-14


def test_separation_round_trip_over_the_load_range():
    s = surface(**SCALE)
    d = SIGMA * np.array([6.0, 3.0, 0.0, -3.0])
    F_N = s.normal_load(d)
    np.testing.assert_allclose(s.separation(F_N), d, rtol=1e-14, atol=1e-14)
    assert np.all(np.diff(F_N) > 0)
    # ΔA_r/A_r differs from ΔF_N/F_N for this density (docs/physics.md §5)
    A = s.real_contact_area(d)
    assert not math.isclose(A[1] / A[0], F_N[1] / F_N[0], rel_tol=1e-3)


def test_ratios_at_a_normal_load_need_the_load_scale():
    with pytest.raises(MissingLoadScaleError, match="missing parameter\\(s\\): E, radius"):
        surface().stick_force_ratio(0.5, normal_load=100.0)
    with pytest.raises(ModelParameterError, match="exactly one of normal_load"):
        surface().stick_area_ratio(0.5)
    s = surface(**SCALE)
    F_N = s.normal_load(0.0)
    assert s.stick_force_ratio(0.5, normal_load=F_N) == pytest.approx(
        s.stick_force_ratio(0.5, separation=0.0), rel=1e-14
    )


def test_tangential_slip_inverse_and_gross_sliding():
    s = surface(**SCALE)
    F_N = s.normal_load(SIGMA * 1.0)
    for g in (1e-9, 0.05, 0.4):
        F_T = s.tangential_force(g, F_N)
        assert s.tangential_slip(F_T, F_N) == pytest.approx(g, rel=1e-11)
    with pytest.raises(GrossSlidingError):
        s.tangential_slip(0.1 * F_N, F_N)


def test_same_as_general_density_path():
    heights = HeightDensity(
        lambda z: math.exp(-0.5 * (z / SIGMA) ** 2) / (SIGMA * math.sqrt(2 * math.pi)),
        scale=SIGMA,
    )
    general = GeneralRoughSurface(heights, 0.3, 0.1, sigma=SIGMA)
    s = surface()
    for F in (1e-6, 0.5, 0.99):
        assert general.stick_force_ratio(F, separation=1.0) == pytest.approx(
            s.stick_force_ratio(F, separation=1.0), rel=1e-11
        )


def test_heavy_load_approaches_exponential_shape_bounds():
    # sanity: the ratios stay between the flat and zero and are load dependent
    s = surface()
    a = s.stick_force_ratio(0.5, separation=SIGMA * 6.0)
    b = s.stick_force_ratio(0.5, separation=SIGMA * -3.0)
    assert 0 < a < 0.5 and 0 < b < 0.5 and abs(a - b) > 1e-3
    e = ExponentialRoughSurface(SIGMA, 0.3, 0.1).stick_force_ratio(0.5)
    assert abs(a - e) < 0.1


@settings(max_examples=25, deadline=None)
@given(
    F=st.lists(st.floats(0.0, 1.0), min_size=2, max_size=2),
    t=st.sampled_from([6.0, 1.0, -3.0]),
)
def test_properties(F, t):
    s = surface()
    F = np.sort(np.array(F))
    f = s.stick_force_ratio(F, separation=SIGMA * t)
    a = s.stick_area_ratio(F, separation=SIGMA * t)
    assert np.all(np.isfinite(f)) and np.all(np.isfinite(a))
    assert np.all((f >= 0) & (f <= F * (1 + 1e-15)))
    assert np.all((a >= 0) & (a <= 1))
    assert a[1] <= a[0] * (1 + 1e-15)


def test_log_load_derivative_far_in_the_tail():
    # d log J/dh = −(3/2) F_{1/2}/(σ* F_{3/2}) against the parabolic-cylinder closed form of
    # the GW integrals (cusp.verification.oracles, mpmath at 40 digits), out to
    # h = 500σ*, where J and dJ/dh underflow (the logs are differences of numbers ~ −t²/2:
    # relative accuracy ~ ε t², so 1e-11 there)
    import mpmath as mp

    from cusp.verification.oracles import gw

    s = surface()
    for t, tol in ((-2.5, 1e-14), (0.0, 1e-14), (10.0, 1e-14), (38.0, 1e-13), (500.0, 1e-11)):
        got = float(s.log_load_integral_derivative(SIGMA * t))
        with mp.workdps(40):
            want = float(-1.5 / SIGMA * gw(0.5, mp.mpf(t)) / gw(1.5, mp.mpf(t)))
        assert abs(got - want) <= tol * abs(want), (t, got, want)
    assert float(s.load_integral(SIGMA * 500.0)) == 0.0  # (underflowed: why the logs)
