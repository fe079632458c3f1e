"""Self-checks of the oracles (no solver involved): the hand-written Jacobians and parameter
derivatives in `oracles.py` agree with central differences of the hand-written residuals, and
with complex-step derivatives where the residual is analytic."""

from __future__ import annotations

import numpy as np
import pytest

from tests.continuation import oracles as orc

CASES = {
    "cusp": (lambda: orc.cusp_problem(None), [0.3]),
    "bratu5": (lambda: orc.bratu_problem(5, None), [0.1, 0.3, 0.4, 0.2, 0.05]),
    "bratu5_sparse": (lambda: orc.bratu_problem(5, None, sparse=True), [0.1, 0.3, 0.4, 0.2, 0.05]),
    "truss_green": (lambda: orc.truss_green_problem(None), [0.3]),
    "truss_rotated": (lambda: orc.truss_rotated_problem(None), [0.3]),
    "truss_2dof": (lambda: orc.truss_2dof_problem(None), [0.2, 0.7]),
    "snap_monitor": (lambda: orc.snapback_monitor_problem(None), [0.05, 0.3]),
    "snap_control": (lambda: orc.snapback_control_problem(None), [0.05]),
    "arch6": (lambda: orc.arch_problem(6.0, None), [1.3, 0.4]),
    "cohesive_exp": (lambda: orc.cohesive_exp_problem(2.0, None), [0.4]),
    "cohesive_lin_pre": (lambda: orc.cohesive_linear_problem(2.0, 0.01, None), [0.004]),
    "cohesive_lin_post": (lambda: orc.cohesive_linear_problem(2.0, 0.01, None), [0.5]),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_oracle_derivatives(name):
    make, u = CASES[name]
    case = make()
    u = np.asarray(u, dtype=float)
    p = {k: v + 0.37 for k, v in case.params.items()}
    jac = case.jacobian(u, p)
    jac = jac.toarray() if hasattr(jac, "toarray") else np.asarray(jac)
    h = 1e-6
    fd = np.column_stack(
        [
            (case.residual(u + h * e, p) - case.residual(u - h * e, p)) / (2 * h)
            for e in np.eye(u.size)
        ]
    )
    assert np.allclose(jac, fd, rtol=1e-6, atol=1e-6 * max(1.0, np.abs(jac).max()))
    cs = np.column_stack([case.residual(u + 1e-30j * e, p).imag / 1e-30 for e in np.eye(u.size)])
    assert np.allclose(jac, cs, rtol=1e-12, atol=1e-12 * max(1.0, np.abs(jac).max()))
    for k in case.params:
        try:
            dp = case.param_jacobian(u, p, k)
        except KeyError:
            continue
        pp, pm = dict(p), dict(p)
        pp[k] += h
        pm[k] -= h
        fdp = (case.residual(u, pp) - case.residual(u, pm)) / (2 * h)
        assert np.allclose(dp, fdp, rtol=1e-6, atol=1e-6), k
