"""A published Hopf point (AUTO-07p's tutorial demo ``ab``) and a sparse reaction–diffusion
problem of 10⁴ unknowns (issue 29)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sp
import sympy as sy

from cusp.continuation import Problem, trace
from cusp.examples import ab_reactor


def test_auto_ab_demo_hopf_point(hopf_l1):
    """AUTO 97 tutorial, demo ab, first run (p2 = 14, p3 = 2; ``doc/tutorial.tex`` of the
    auto-07p repository) prints ``HB 4 PAR(1) = 1.308998E-01, U(1) = 8.950803E-01,
    U(2) = 4.177042E+00``. Closed form: on the branch u1 = 3θ/14 (θ = u2), p1 = u1e^{−θ}/(1−u1),
    the trace of the Jacobian, −4 − u1/(1 − u1) + 14u1, vanishes at 14u1² − 17u1 + 4 = 0:
    u1 = (17 + √65)/28 (the other root, (17 − √65)/28 on the saddle branch between the
    folds, is a neutral saddle: det < 0)."""
    base = ab_reactor().problem
    prob = Problem(base._residual, base.unknowns, base.params, jacobian=base._jacobian,
                   param_jacobian=base._param_jacobian, mass=True)  # fmt: skip
    br = trace(prob, [0.0, 0.0], free="p1", bounds={"p1": (0.0, 0.15)}, stability=True)
    assert len(br.special("fold")) == 2
    (hopf,) = br.special("hopf")  # the neutral saddle at u1 = 0.3192 is not reported
    u1 = (17 + math.sqrt(65)) / 28  # 0.8950802...
    theta = 14 * u1 / 3
    p1 = u1 * math.exp(-theta) / (1 - u1)
    assert hopf.values["u1"] == pytest.approx(u1, rel=1e-10)
    assert hopf.values["u2"] == pytest.approx(theta, rel=1e-10)
    assert hopf.values["p1"] == pytest.approx(p1, rel=1e-10)
    # the published values: AUTO located its Hopf point to its step tolerance (EPSS = 1e-4
    # in r.ab), 1.9e-6 relative off in p1 (exact 0.13090004482), as its cusp (docs/test-
    # problems.md); its state (exact u1 = 0.89508063, u2 = 4.17704296) 4e-7 and 2.3e-7 off
    assert hopf.values["p1"] == pytest.approx(1.308998e-01, rel=2e-6)
    assert hopf.values["u1"] == pytest.approx(8.950803e-01, rel=1e-6)
    assert hopf.values["u2"] == pytest.approx(4.177042e00, rel=1e-6)
    x, y, P1 = sy.symbols("x y p1")
    U1 = (17 + sy.sqrt(65)) / 28
    TH = 14 * U1 / 3
    f = [-x + P1 * (1 - x) * sy.exp(y), -y + P1 * 14 * (1 - x) * sy.exp(y) - 2 * y]
    omega, l1 = hopf_l1(f, [x, y], {x: U1, y: TH, P1: U1 * sy.exp(-TH) / (1 - U1)})
    assert hopf.details["omega"] == pytest.approx(float(omega), rel=1e-9)
    assert hopf.details["first_lyapunov"] == pytest.approx(float(l1), rel=1e-6)
    # stable from p1 = 0 to the first fold, a saddle between the folds, then the upper
    # branch: unstable focus (2) until the Hopf point, stable after it
    n = br["n_unstable"]
    assert n[0] == 0 and n[hopf.index - 1] == 2 and n[-1] == 0


def brusselator_rd(n_cells: int, a: float = 2.0, d: float = 0.01) -> Problem:
    """The Brusselator with equal diffusion d on [0, 1], Neumann ends, finite differences on
    ``n_cells`` points (2·n_cells unknowns, interleaved x, y; sparse analytic Jacobian)."""
    h = 1.0 / (n_cells - 1)
    main = -2.0 * np.ones(n_cells)
    lap = sp.diags([np.ones(n_cells - 1), main, np.ones(n_cells - 1)], [-1, 0, 1]).tolil()
    lap[0, 1] = 2.0
    lap[n_cells - 1, n_cells - 2] = 2.0
    lap = (lap.tocsc() * (d / (h * h))).tocsc()
    perm = np.arange(2 * n_cells).reshape(2, n_cells).T.ravel()  # (x0, y0, x1, y1, ...)
    big_lap = sp.block_diag([lap, lap]).tocsc()[perm][:, perm]

    def residual(u, p):
        x, y = u[0::2], u[1::2]
        b = p["b"]
        out = np.empty_like(u)
        out[0::2] = a - (b + 1) * x + x * x * y
        out[1::2] = b * x - x * x * y
        return out + big_lap @ u

    def jacobian(u, p):
        x, y = u[0::2], u[1::2]
        b = p["b"]
        jxx, jxy, jyx, jyy = -(b + 1) + 2 * x * y, x * x, b - 2 * x * y, -x * x
        n2 = 2 * n_cells
        diag = np.empty(n2)
        diag[0::2], diag[1::2] = jxx, jyy
        up = np.zeros(n2 - 1)
        up[0::2] = jxy
        lo = np.zeros(n2 - 1)
        lo[0::2] = jyx
        return (sp.diags([lo, diag, up], [-1, 0, 1], format="csc") + big_lap).tocsc()

    def param_jacobian(u, p, name):
        x = u[0::2]
        out = np.empty_like(u)
        out[0::2], out[1::2] = -x, x
        return out

    names = [f"{c}{i}" for i in range(n_cells) for c in "xy"]
    return Problem(residual, names, {"b": 4.5}, jacobian=jacobian,
                   param_jacobian=param_jacobian, mass=True)  # fmt: skip


def test_sparse_reaction_diffusion_hopf():
    """10⁴ unknowns. The homogeneous state x = a, y = b/a solves every cell; its Fourier
    mode k has the Jacobian [[b − 1 − dκ, a²], [−b, −a² − dκ]], so the uniform mode (κ = 0)
    has the Brusselator's Hopf point b = 1 + a² = 5, ω = a = 2 and every other mode is more
    stable (trace smaller by 2dκ; no Turing point with equal diffusion). In the ⟨q, q⟩ = 1
    normalisation q is the ODE's eigenvector spread over N cells (each part 1/√N), the
    adjoint likewise, so l1 = l1_ODE/N with l1_ODE = −(a² + 2)/(2a(2a² + 1)) = −1/6."""
    n_cells = 5000
    a = 2.0
    prob = brusselator_rd(n_cells, a)
    u0 = np.tile([a, 4.5 / a], n_cells)
    br = trace(prob, u0, free="b", bounds={"b": (4.5, 5.5)}, stability=True)
    assert br.info["stability"]["method"].startswith("shift-invert")
    hopf, hopf1 = br.special("hopf")
    # the second: mode 1, whose Laplacian eigenvalue is −κ1 = −(4/h²)sin²(π/(2(N − 1)))
    # (Neumann, h = 1/(N − 1)): b = 1 + a² + 2dκ1 = 5.197...
    h = 1.0 / (n_cells - 1)
    kappa1 = 4.0 / h**2 * math.sin(math.pi / (2 * (n_cells - 1))) ** 2
    assert abs(hopf1.values["b"] - (5.0 + 2 * 0.01 * kappa1)) <= 1e-9 * 5.2
    assert abs(hopf.values["b"] - 5.0) <= 1e-10 * 5
    assert hopf.details["omega"] == pytest.approx(a, rel=1e-10)
    l1_ode = -(a * a + 2) / (2 * a * (2 * a * a + 1))
    assert hopf.details["first_lyapunov"] * n_cells == pytest.approx(l1_ode, rel=1e-6)
    assert br["n_unstable"][0] == 0 and br["n_unstable"][-1] == 4
