"""The regime map over (μ, F'_N) (cusp.models.regimes): for exponential heights the
boundaries and the regimes against their closed forms, the energies on the grid against the
sympy closed forms of :func:`cusp.verification.contact_loss_path`; for a sphere the boundary
where D disappears against the body's own slip limit (Eq 2 with Hertz).

Closed forms (exponential heights, F_A = μF_N0(1 − e^{−g_A/(λμ)}), derived in
``cusp.verification``): C boundary F'_N = F_A/μ = F_N0(1 − e^{−g_A/(λμ)}); deepest reduction
F'_N = F_N0 − F_A/μ = F_N0 e^{−g_A/(λμ)}.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from cusp.models import ContactLoss, ExponentialRoughSurface, Sphere
from cusp.models.errors import ModelParameterError
from cusp.models.manifold import DEFAULT_OPTIONS
from cusp.models.regimes import REGIMES, regime_boundaries, regime_map
from cusp.verification.oracles import exponential_closed_form as closed_form

pytest.importorskip("cusp.verification")  # (sympy: the closed forms)

SIGMA, NU, F_N0, G_A = 2.0, 0.3, 1000.0, 0.34
LAM = SIGMA * (2.0 - NU) / (2.0 * (1.0 - NU))


def _closed(key, mu, F_Np):
    return closed_form(key, mu, F_Np)


@pytest.fixture(scope="module")
def exp_map():
    model = ContactLoss(ExponentialRoughSurface(SIGMA, NU, 0.1), F_N0, G_A, 850.0)
    return regime_map(model, (0.02, 1.0), (100.0, 1000.0), mus=8, loads=10)


def test_boundaries_follow_the_closed_forms(exp_map):
    mu, load = exp_map.boundaries["C boundary"]
    assert mu.size > 10 and mu[0] == pytest.approx(0.02) and mu[-1] == pytest.approx(1.0)
    x = np.exp(-G_A / (LAM * mu))
    assert np.allclose(load, F_N0 * (1.0 - x), rtol=1e-10, atol=0.0)
    mu, load = exp_map.boundaries["F'_T = 0"]
    x = np.exp(-G_A / (LAM * mu))
    assert np.allclose(load, F_N0 * x, rtol=1e-10, atol=0.0)
    assert "D disappears" not in exp_map.boundaries  # a rough surface never slides whole


def test_boundaries_alone_follow_the_closed_forms_along_the_dense_output():
    # regime_boundaries (the regime-map figure's polygons): the locus of A in μ alone,
    # sampled along its dense output; the arcs are within rtol of the locus in its weighted
    # norm, t = F_A/(μ0·F_N0) of size 1, so F_A to rtol·μ0·F_N0 and F'_N = F_A/μ (or
    # F_N0 − F_A/μ) to rtol·μ0·F_N0/μ
    model = ContactLoss(ExponentialRoughSurface(SIGMA, NU, 0.1), F_N0, G_A, 850.0)
    rb = regime_boundaries(model, (0.02, 1.0), (100.0, 1000.0))
    mu = rb.mu
    assert mu.size > 100 and mu[0] == pytest.approx(0.02) and mu[-1] == pytest.approx(1.0)
    assert np.all(np.diff(mu) > 0)
    x = np.exp(-G_A / (LAM * mu))
    bound = DEFAULT_OPTIONS.rtol * 0.1 * F_N0 / mu
    m, load = rb.boundaries["C boundary"]
    assert np.array_equal(m, mu) and np.all(np.abs(load - F_N0 * (1.0 - x)) <= bound)
    m, load = rb.boundaries["F'_T = 0"]
    assert np.array_equal(m, mu) and np.all(np.abs(load - F_N0 * x) <= bound)
    assert np.allclose(rb.F_A, mu * F_N0 * (1.0 - x), rtol=0.0, atol=DEFAULT_OPTIONS.rtol * 100)
    assert set(rb.boundaries) == {"C boundary", "F'_T = 0"}  # no D boundary: never slides
    with pytest.raises(ModelParameterError, match="mu_span"):
        regime_boundaries(model, (1.0, 0.02), (100.0, 1000.0))


def test_regimes_and_energies_on_the_grid(exp_map):
    rm = exp_map
    for j, mu in enumerate(rm.mu):
        x = math.exp(-G_A / (LAM * mu))
        for k, load in enumerate(rm.loads):
            want = 3 if load < F_N0 * x else (0 if load > F_N0 * (1.0 - x) else 1)
            assert REGIMES[rm.regimes[k, j]] == REGIMES[want], (mu, load)
            if want == 3 or load > F_N0 * (1.0 - 1e-3):  # (above the spine: not traced)
                assert math.isnan(rm.snap_back[k, j]) and math.isnan(rm.snap_through[k, j])
                continue
            assert rm.snap_back[k, j] == pytest.approx(_closed("snap_back", mu, load), rel=1e-9)
            if want == 0:
                assert rm.snap_through[k, j] == pytest.approx(
                    _closed("snap_through", mu, load), rel=1e-9
                )
            else:
                assert math.isnan(rm.snap_through[k, j])


def test_sphere_boundary_where_d_disappears():
    sphere = Sphere(1000.0, 0.2, 0.3, 0.1)
    model = ContactLoss(sphere, F_N0, 2.0, 850.0)
    rm = regime_map(model, (0.02, 1.0), (100.0, 1000.0), mus=6, loads=8)
    mu, load = rm.boundaries["D disappears"]
    assert mu.size > 5
    # D disappears where g_A is the slip at which the sphere slides under F'_N:
    # g_A = (μ/μ0)·slip_limit(F'_N), slip_limit the body's closed form at μ0 = 0.1
    g = [m / 0.1 * sphere.slip_limit(f) for m, f in zip(mu, load)]
    assert np.allclose(g, 2.0, rtol=1e-10, atol=0.0)
    assert 2 in rm.regimes  # gross sliding under both controls below that load
    # the figure's boundaries alone: the same curve where D disappears
    rb = regime_boundaries(model, (0.02, 1.0), (100.0, 1000.0))
    mu_b, load_b = rb.boundaries["D disappears"]
    g = [m / 0.1 * sphere.slip_limit(f) for m, f in zip(mu_b, load_b)]
    assert mu_b.size > 5 and np.allclose(g, 2.0, rtol=1e-10, atol=0.0)


def test_bad_spans_are_refused():
    model = ContactLoss(ExponentialRoughSurface(SIGMA, NU, 0.1), F_N0, G_A, 850.0)
    with pytest.raises(ModelParameterError, match="load_span"):
        regime_map(model, (0.02, 1.0), (900.0, 100.0))
    with pytest.raises(ModelParameterError, match="mus"):
        regime_map(model, (0.02, 1.0), (100.0, 1000.0), mus=1)
