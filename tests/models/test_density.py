"""General summit-height densities through the quadrature code path."""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from cusp.models import ExponentialRoughSurface, GeneralRoughSurface, HeightDensity
from cusp.models.errors import ModelParameterError


def exp_heights(sigma=2.0):
    return HeightDensity(lambda z: math.exp(-z / sigma) / sigma, (0.0, math.inf), scale=sigma)


def test_general_path_matches_exponential_closed_form():
    # for d ≥ 0 the exponential law truncated at z = 0 gives exactly the closed forms
    general = GeneralRoughSurface(exp_heights(), nu=0.3, mu=0.1, sigma=2.0)
    closed = ExponentialRoughSurface(sigma=2.0, nu=0.3, mu=0.1)
    d = 1.0
    for F in (1e-9, 0.3, 0.9, 1 - 1e-9):
        assert general.stick_force_ratio(F, separation=d) == pytest.approx(
            closed.stick_force_ratio(F), rel=1e-12
        )
        assert general.stick_area_ratio(F, separation=d) == pytest.approx(
            closed.stick_area_ratio(F), rel=1e-12
        )
    for h in (0.0, 1.0, 5.0):
        assert general.load_integral(h) == pytest.approx(closed.load_integral(h), rel=1e-13)
        assert general.area_integral(h) == pytest.approx(closed.area_integral(h), rel=1e-13)
    assert general.force_ratio(0.3, separation=d) == pytest.approx(closed.force_ratio(0.3))


def test_weibull_against_mpmath():
    heights = HeightDensity.weibull(shape=2.0, scale=3.0, loc=-2.5)
    s = GeneralRoughSurface(heights, nu=0.3, mu=0.1, E=0.2, radius=100.0, density=1e-4,
                            nominal_area=1e6)  # fmt: skip
    d = 0.7
    with mp.workdps(30):

        def pdf(z):
            u = (z + mp.mpf(2.5)) / 3
            return mp.mpf(2) / 3 * u * mp.exp(-(u**2))

        J = mp.quad(lambda z: (z - d) ** 1.5 * pdf(z), [d, d + 3, mp.inf])
        A = mp.quad(lambda z: (z - d) * pdf(z), [d, d + 3, mp.inf])
    assert s.load_integral(d) == pytest.approx(float(J), rel=1e-13)
    assert s.area_integral(d) == pytest.approx(float(A), rel=1e-13)
    F_N = s.normal_load(d)
    assert s.separation(F_N) == pytest.approx(d, rel=1e-13)
    # below the lowest summit the integrand has no end-point singularity
    assert s.load_integral(-3.0) > s.load_integral(-2.5) > 0
    f = s.stick_force_ratio([0.2, 0.6], normal_load=F_N)
    assert np.all((f > 0) & (f < [0.2, 0.6]))


def test_histogram_density():
    edges = np.linspace(-3.0, 3.0, 13)
    counts = np.exp(-0.5 * (0.5 * (edges[1:] + edges[:-1])) ** 2)
    heights = HeightDensity.histogram(edges, counts)
    s = GeneralRoughSurface(heights, nu=0.3, mu=0.1)
    # J for piecewise-constant Φ in closed form: Σ c_i (2/5)[(b − h)^{5/2} − (a − h)^{5/2}]
    c = counts / (counts.sum() * 0.5)
    h = 0.2
    exact = sum(
        ci * 0.4 * (max(b - h, 0) ** 2.5 - max(a - h, 0) ** 2.5)
        for a, b, ci in zip(edges[:-1], edges[1:], c, strict=True)
    )
    assert s.load_integral(h) == pytest.approx(exact, rel=1e-13)
    ar = s.stick_area_ratio([0.1, 0.5, 0.9], separation=0.0)
    assert np.all(np.diff(ar) < 0)


def test_density_must_integrate_to_one():
    with pytest.raises(ModelParameterError, match="integrate to 1 .* got integral 2.0"):
        HeightDensity(lambda z: 2 * math.exp(-z), (0.0, math.inf))
    with pytest.raises(ModelParameterError, match="support"):
        HeightDensity(lambda z: 1.0, (1.0, 0.0))
    with pytest.raises(ModelParameterError, match="counts"):
        HeightDensity.histogram([0, 1, 2], [1, -1])
    with pytest.raises(ModelParameterError, match="heights must be a HeightDensity"):
        GeneralRoughSurface(lambda z: z, nu=0.3, mu=0.1)


def test_load_dependent_ratio_needs_a_load():
    s = GeneralRoughSurface(exp_heights(), nu=0.3, mu=0.1)
    with pytest.raises(ModelParameterError, match="normal_load .* or separation"):
        s.stick_force_ratio(0.5)
