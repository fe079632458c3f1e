"""The contact-loss path and the loci at another ``rtol`` (the options' accuracy knob): the
points and energies within 10·rtol of the exponential closed forms, honest error estimates,
the quadrature following ``quad_tol``, and the defaults unchanged."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cusp.continuation import quadrature_tol
from cusp.models import ContactLoss, ExponentialRoughSurface
from cusp.models._loci_energy import ENERGY_RTOL, QUAD_RTOL, flag_rtol, gauss_legendre
from cusp.models.contact_loss import DEFAULT_OPTIONS
from cusp.models.manifold import DEFAULT_OPTIONS as LOCI_OPTIONS
from cusp.models.manifold import point_loci
from cusp.verification.oracles import exponential_closed_form as closed_form

# the Fig 6 scene: σ* = 2 µm, ν = 0.3, μ = 0.1, F_N0 = 1000 N, g_A = 0.34 µm, F'_N = 850 N
FIG6 = (2.0, 0.3, 0.1, 1000.0, 0.34, 850.0)
KEYS = ("g_T", "F_T", "F_N", "A_SL")


def _model() -> ContactLoss:
    sigma, nu, mu, F_N0, g_A, F_Np = FIG6
    return ContactLoss(ExponentialRoughSurface(sigma, nu, mu), F_N0, g_A, F_Np)


def _fig6_closed() -> tuple[dict, dict]:
    """Points A-D and the energies of Fig 6: the sympy closed forms of
    cusp.verification.contact_loss_path() (docs/physics.md §7), at the exact binary inputs;
    F_N is F_N0 on OA and F'_N after the reduction, g_T = g_A at A and D, F_T = F_A at C."""
    mu, F_Np = FIG6[2], FIG6[5]

    def cf(key):
        return closed_form(key, mu, F_Np)

    F_A = cf("F_A")
    pts = {
        "A": {"g_T": 0.34, "F_T": F_A, "F_N": 1000.0, "A_SL": cf("A_SL_A")},
        "B": {"g_T": cf("g_B"), "F_T": cf("F_B"), "F_N": F_Np, "A_SL": cf("A_SL_B")},
        "C": {"g_T": cf("g_C"), "F_T": F_A, "F_N": F_Np, "A_SL": cf("A_SL_C")},
        "D": {"g_T": 0.34, "F_T": cf("F_D"), "F_N": F_Np, "A_SL": cf("A_SL_D")},
    }
    return pts, {"snap_back": cf("snap_back"), "snap_through": cf("snap_through")}


@pytest.fixture(scope="module")
def fig6_closed():
    return _fig6_closed()


@pytest.mark.parametrize("rtol", [1e-3, 3e-3, 1e-2])
def test_fig6_at_a_loose_rtol_is_within_ten_rtol_of_the_closed_forms(fig6_closed, rtol):
    pts, energy = fig6_closed
    res = _model().run(DEFAULT_OPTIONS.replace(rtol=rtol))
    for key, want in pts.items():
        for q in KEYS:
            got = res.points[key][q]
            assert abs(got - want[q]) <= 10 * rtol * abs(want[q]), (key, q, got, want[q])
    for kind, want in energy.items():
        got, bound = res.energy[kind], res.energy_error[kind]
        assert abs(got - want) <= 10 * rtol * want, (kind, got, want)
        # the error estimate is an honest bound: at least the actual error (the points are
        # polished on their legs, the energies' rows to rounding, at any rtol) ...
        assert abs(got - want) <= bound, (kind, got, want, bound)
        # ... and within the quadrature tolerance asked for, so no message
        assert bound <= flag_rtol(quadrature_tol(rtol)) * got
    assert res.messages == []


def test_fig6_at_the_default_rtol_is_as_accurate_as_before(fig6_closed):
    # test_contact_loss.py's demands: points 1e-10, energies 1e-8, the estimate below 1e-12
    pts, energy = fig6_closed
    res = _model().run(DEFAULT_OPTIONS.replace(rtol=1e-3))
    assert res.points == _model().run().points  # the explicit default is the default
    for key, want in pts.items():
        for q in KEYS:
            assert res.points[key][q] == pytest.approx(want[q], rel=1e-10), (key, q)
    for kind, want in energy.items():
        assert res.energy[kind] == pytest.approx(want, rel=1e-8), kind
        assert res.energy_error[kind] < 1e-12 * res.energy[kind]


def test_the_default_quadrature_and_flag_are_unchanged():
    assert QUAD_RTOL == quadrature_tol(1e-3) == 1e-13 == DEFAULT_OPTIONS.quad_tol
    assert DEFAULT_OPTIONS.rtol == 1e-3  # ContinuationOptions' default
    assert flag_rtol() == ENERGY_RTOL == 1e-8
    assert flag_rtol(quadrature_tol(1e-2)) == 1e-8  # quad_tol 1e-11: the flag stays
    assert flag_rtol(quadrature_tol(0.1)) == pytest.approx(1e-7)  # 100·(0.1/1000)²/10


def test_gauss_legendre_stops_at_its_tolerance_with_an_honest_estimate():
    # Runge's function: ∫_{-1}^{1} dx/(1 + 25x²) = (2/5)·atan(5) (elementary), needing many
    # nodes at 1e-13
    exact = 0.4 * math.atan(5.0)
    nodes = {}
    for rtol in (1e-13, 1e-3):
        count = []

        def f(x, count=count):
            count.append(x.size)
            return 1.0 / (1.0 + 25.0 * x * x)

        value, err = gauss_legendre(f, -1.0, 1.0, rtol=rtol)
        assert abs(value - exact) <= err <= max(rtol * exact, 1e-15), (rtol, value, err)
        nodes[rtol] = sum(count)
    assert nodes[1e-3] < nodes[1e-13] / 4, nodes


def test_the_loci_at_a_loose_rtol_are_within_ten_rtol_of_the_closed_forms():
    rtol = 1e-2
    model = _model()
    loci = point_loci(model, "mu", (0.05, 0.5), options=LOCI_OPTIONS.replace(rtol=rtol))
    cols = loci.columns
    rows = np.flatnonzero(np.isfinite(cols["snap_through_energy"]))
    assert rows.size >= 5
    for i in rows[:: max(1, rows.size // 5)]:
        mu = float(cols["mu"][i])
        for column, key in (("F_A", "F_A"), ("g_B", "g_B"), ("g_C", "g_C"), ("F_D", "F_D")):
            want = closed_form(key, mu, 850.0)  # cusp.verification.contact_loss_path()
            assert abs(cols[column][i] - want) <= 10 * rtol * abs(want), (mu, column)
        for kind in ("snap_back", "snap_through"):
            want = closed_form(kind, mu, 850.0)
            got, bound = cols[f"{kind}_energy"][i], cols[f"{kind}_error"][i]
            assert abs(got - want) <= min(10 * rtol * want, bound), (mu, kind, got, want)


def test_loci_given_the_default_options_are_the_default_loci():
    # point_loci traces its path with the path's own options at the loci's rtol: at the
    # default rtol, exactly what it traces without options
    model = _model()
    plain = point_loci(model, "mu", (0.05, 0.5))
    given = point_loci(model, "mu", (0.05, 0.5), options=LOCI_OPTIONS.replace(rtol=1e-3))
    for key, column in plain.columns.items():
        np.testing.assert_array_equal(given.columns[key], column, err_msg=key)
