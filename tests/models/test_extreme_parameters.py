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
