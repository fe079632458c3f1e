"""The contact-loss legs evaluate the model once per point (issue 27, point 5: bounded work).

The engine asks a leg's problem for its residual, Jacobian and a parameter column at the same
point, and a locus's chain evaluates C and D on the one reloading leg in turn; the leg keeps
its latest evaluations, so that a Gaussian or general-density model (about 1 ms an
evaluation) is evaluated once per point. The numbers are the same, bit for bit; the fast
scalar paths of the Greenwood–Williamson integrals are the array paths' IEEE operations.
"""

from __future__ import annotations

import numpy as np
import pytest

from cusp.models import ContactLoss, ExponentialRoughSurface, gw
from cusp.models.errors import ModelParameterError, check_finite_array


def _counted(monkeypatch, model):
    calls = []
    real = type(model)._equations

    def counting(self, x, mu, leg, c):
        calls.append((tuple(x), mu, leg, c))
        return real(self, x, mu, leg, c)

    monkeypatch.setattr(type(model), "_equations", counting)
    return calls, real


def test_one_evaluation_per_point_and_the_same_numbers(monkeypatch):
    model = ContactLoss(ExponentialRoughSurface(2.0, 0.3, 0.1), 1000.0, 0.34, 850.0)
    bc = model.problem("BC", start=1.0, constant=0.15)
    calls, real = _counted(monkeypatch, model)
    u_c = np.array([2.5, 0.15, 0.3, 0.01, 0.2])  # (t, m, A_SL, p, q): two points of the leg
    u_d = np.array([2.9, 0.15, 0.2, 0.01, 0.3])
    p = {"g": 1.0, "mu": 0.1, "m_B": 0.15}
    for _ in range(3):  # C and D in turn, as a chain asks
        for u in (u_c, u_d):
            r, j = bc.residual(u, p), bc.jacobian(u, p)
            col, mu_col = bc.param_jacobian(u, p, "g"), bc.param_jacobian(u, p, "mu")
            x = [1.0, *u]  # (the leg's control g first: the order of the model's variables)
            R, J = real(model, x, 0.1, "BC", 0.15)
            assert r.tobytes() == R.tobytes() and j.tobytes() == J[:, 1:6].tobytes()
            assert col.tobytes() == J[:, 0].tobytes() and mu_col.tobytes() == J[:, 6].tobytes()
            r[:] = 7.0  # a caller's change does not reach the kept evaluation
    assert len(calls) == 2
    assert bc.residual(u_c, p).tobytes() == real(model, [1.0, *u_c], 0.1, "BC", 0.15)[0].tobytes()
    bc.residual(u_c, {**p, "mu": 0.2})  # another parameter value: evaluated again
    assert len(calls) == 3


@pytest.mark.parametrize("n", [-0.5, 0.5, 1.5])
def test_far_left_series_of_one_value_is_the_array_path_bit_for_bit(n):
    rng = np.random.default_rng(5)
    t = -np.exp(rng.uniform(np.log(20.0), np.log(1e12), 200))
    many = gw._far_left_series(n, t)  # (200 values: the array recurrence)
    one = np.array([gw._far_left_series(n, np.array([x]))[0] for x in t])
    assert one.tobytes() == many.tobytes()


def test_finite_checks_of_one_value_refuse_as_before():
    assert check_finite_array("h", 2.5).shape == () and check_finite_array("h", [2.5]).shape == (1,)
    for bad in (np.nan, np.inf, -np.inf, [np.nan]):
        with pytest.raises(ModelParameterError, match="h must be finite"):
            check_finite_array("h", bad, unit="µm")
    with pytest.raises(ModelParameterError, match=r"g_T must be finite and >= 0 \[µm\]"):
        check_finite_array("g_T", -1e-300, lower=0.0, unit="µm")
    with pytest.raises(ModelParameterError, match="t must be finite"):
        gw.gw_integral(1.5, np.nan)
