"""Independent oracles for the continuation tests: the published problems of
TEST-PROBLEMS.md written as residuals (with hand-derived derivatives), and their reference
special points recomputed here in mpmath at 40 digits, never with the solver under test.

Every reference value used by the tests is either computed by a function in this module or
printed beside its literal together with the snippet that produced it.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any, NamedTuple

import mpmath as mp
import numpy as np
import scipy.sparse as sps

#: Derivative strategies a test can be parametrised over: the hand-written Jacobian or one of
#: the solver's finite-difference fallbacks.
STRATEGIES = ("analytic", "central", "forward", "complex")

#: Tolerance on the *state* of a refined fold (its parameter is always compared to 1e-12
#: relative: at a fold the parameter is stationary, so a state error δ perturbs it by O(δ²)).
#: A forward-difference Jacobian is itself only accurate to ~sqrt(eps) ~ 1.5e-8, which moves
#: the zero of det J, hence the fold's state, by about that much.
STATE_RTOL = {"analytic": 1e-9, "complex": 1e-9, "central": 1e-8, "forward": 1e-6}

DPS = 40


class Case(NamedTuple):
    """A Problem together with the oracle's own residual and derivatives, which the tests use to
    check the solver's output independently of anything the solver computed."""

    problem: Any
    residual: Callable
    jacobian: Callable
    param_jacobian: Callable
    unknowns: list
    params: dict


def make_problem(residual, unknowns, params, jacobian, param_jacobian, strategy):
    """The Problem a user would write: analytic derivatives or a finite-difference fallback."""
    if strategy is not None:
        from cusp.continuation import Problem  # lazily, so the oracles' self-checks run without it
    if strategy == "analytic":
        prob = Problem(
            residual,
            unknowns=unknowns,
            params=params,
            jacobian=jacobian,
            param_jacobian=param_jacobian,
        )
    elif strategy in ("central", "forward", "complex"):
        prob = Problem(residual, unknowns=unknowns, params=params, derivatives=strategy)
    elif strategy is None:  # no Problem: the oracle's functions only
        prob = None
    else:
        raise ValueError(f"unknown strategy {strategy!r}")
    return Case(prob, residual, jacobian, param_jacobian, list(unknowns), dict(params))


def branch_residual_norms(case, br):
    """max-norm of the oracle's residual at every point of a branch (from br's columns)."""
    u = np.column_stack([np.asarray(br[name], dtype=float) for name in case.unknowns])
    out = np.empty(u.shape[0])
    for i in range(u.shape[0]):
        p = {name: float(br[name][i]) for name in case.params}
        out[i] = np.max(np.abs(case.residual(u[i].copy(), p)))
    return out


def special(br, kind, with_respect_to=None):
    """Special points of one kind (optionally a fold w.r.t. one variable), in branch order."""
    pts = [
        sp
        for sp in br.special_points
        if sp.kind == kind and (with_respect_to is None or sp.with_respect_to == with_respect_to)
    ]
    return sorted(pts, key=lambda sp: sp.index)


def assert_special_points_consistent(case, br):
    """Every special point's values are the branch's columns at its index, bit for bit."""
    n = len(br[case.unknowns[0]])
    for name in [*case.unknowns, *case.params]:
        assert len(br[name]) == n, name
    for sp in br.special_points:
        assert 0 <= sp.index < n, sp
        assert sp.status in ("converged", "guess"), sp
        for name in [*case.unknowns, *case.params]:
            assert br[name][sp.index] == sp.values[name], (sp.kind, sp.label, name)


# ---------------------------------------------------------------------------------------------
# 1. Cusp normal form x^3 - a x - b = 0
# ---------------------------------------------------------------------------------------------


def cusp_residual(u, p):
    x = u[0]
    return np.array([x**3 - p["a"] * x - p["b"]])


def cusp_jacobian(u, p):
    return np.array([[3.0 * u[0] ** 2 - p["a"]]])


def cusp_param_jacobian(u, p, name):
    if name == "b":
        return np.array([-1.0])
    if name == "a":
        return np.array([-u[0]])
    raise KeyError(name)


def cusp_problem(strategy="analytic", a=1.0, b=-1.0):
    return make_problem(
        cusp_residual, ["x"], {"a": a, "b": b}, cusp_jacobian, cusp_param_jacobian, strategy
    )


@functools.lru_cache
def cusp_start(a=1.0, b=-1.0):
    """The real root of x^3 - a x - b below the folds (b = -1: x = -1.324717957244746, minus
    the plastic number)."""
    with mp.workdps(DPS):
        return float(mp.findroot(lambda x: x**3 - a * x - b, -1.3))


@functools.lru_cache
def cusp_folds(a=1.0):
    """Folds of the cusp at fixed a > 0: 3x^2 = a, b = x^3 - a x = -2x^3 (exact)."""
    with mp.workdps(DPS):
        x = mp.sqrt(mp.mpf(a) / 3)
        # (x, b) pairs: x = -sqrt(a/3) gives b = +2/(3 sqrt 3) for a = 1, and vice versa.
        return tuple((float(s * x), float(-2 * (s * x) ** 3)) for s in (-1, 1))


# ---------------------------------------------------------------------------------------------
# 2. Finite-difference Bratu (u_{i-1} - 2u_i + u_{i+1})/h^2 + lam exp(u_i) = 0, u_0 = u_{N+1} = 0
# ---------------------------------------------------------------------------------------------


def bratu_names(n):
    return [f"u{i}" for i in range(n)]


def bratu_residual(u, p):
    n = u.shape[0]
    h2 = (1.0 / (n + 1)) ** 2
    lap = -2.0 * u
    lap[1:] += u[:-1]
    lap[:-1] += u[1:]
    return lap / h2 + p["lam"] * np.exp(u)


def bratu_jacobian_dense(u, p):
    n = u.shape[0]
    h2 = (1.0 / (n + 1)) ** 2
    jac = (
        np.diag(np.full(n - 1, 1.0), -1) + np.diag(np.full(n - 1, 1.0), 1) - 2.0 * np.eye(n)
    ) / h2
    return jac + np.diag(p["lam"] * np.exp(u))


def bratu_jacobian_sparse(u, p):
    n = u.shape[0]
    h2 = (1.0 / (n + 1)) ** 2
    off = np.full(n - 1, 1.0 / h2)
    return sps.diags([off, -2.0 / h2 + p["lam"] * np.exp(u), off], [-1, 0, 1], format="csc")


def bratu_param_jacobian(u, p, name):
    if name != "lam":
        raise KeyError(name)
    return np.exp(u)


def bratu_problem(n, strategy="analytic", sparse=False):
    jac = bratu_jacobian_sparse if sparse else bratu_jacobian_dense
    return make_problem(
        bratu_residual, bratu_names(n), {"lam": 0.0}, jac, bratu_param_jacobian, strategy
    )


def _bratu_shoot(a, mu, n):
    """Discrete shooting for the FD Bratu problem with mu = h^2 lam.

    u_0 = 0, u_1 = a, u_{i+1} = 2u_i - u_{i-1} - mu e^{u_i} (i = 1..n). Returns u_{n+1} and its
    derivatives w = du/da, z = du/dmu, wa = d2u/da2, wm = d2u/dadmu (variational recursions),
    so that Newton on (u_{n+1}, w_{n+1}) = (0, 0) has the exact Jacobian [[w, z], [wa, wm]].
    """
    zero = mp.mpf(0)
    um, u, wm_, w, zm, z, am, wa, bm, wb = (
        zero,
        a,
        zero,
        mp.mpf(1),
        zero,
        zero,
        zero,
        zero,
        zero,
        zero,
    )
    for _ in range(n):
        e = mp.exp(u)
        me = mu * e
        un = 2 * u - um - me
        wn = 2 * w - wm_ - me * w
        zn = 2 * z - zm - e - me * z
        an = 2 * wa - am - me * (w * w + wa)
        bn = 2 * wb - bm - e * w - me * (z * w + wb)
        um, u, wm_, w, zm, z, am, wa, bm, wb = u, un, w, wn, z, zn, wa, an, wb, bn
    return u, w, z, wa, wb


@functools.lru_cache
def bratu_fd_fold(n, dps=DPS):
    """Fold (lam*(N), u_1) of the N-point FD Bratu problem by discrete shooting in mpmath.

    Fold <=> u_{N+1}(a, mu) = 0 and du_{N+1}/da = 0 (then dmu/da = 0 along the solution
    curve a -> mu(a)). Newton from the continuum guess a = 4h (u'(0) = 4 at the fold since
    s tanh s = 1), lam = lam* - 1.83 h^2, with the exact 2x2 Jacobian, to 1e-(dps-4).
    """
    with mp.workdps(dps):
        h = mp.mpf(1) / (n + 1)
        a = 4 * h
        mu = (mp.mpf("3.513830719125161") - mp.mpf("1.8284") * h**2) * h**2
        for _ in range(50):
            u, w, z, wa, wb = _bratu_shoot(a, mu, n)
            da, dmu = mp.lu_solve(mp.matrix([[w, z], [wa, wb]]), mp.matrix([-u, -w]))
            a += da
            mu += dmu
            if abs(da) <= abs(a) * mp.mpf(10) ** (4 - dps) and abs(dmu) <= abs(mu) * mp.mpf(10) ** (
                4 - dps
            ):
                break
        else:  # pragma: no cover - the oracle itself failed
            raise RuntimeError(f"shooting Newton did not converge for N={n}")
        return float(mu / h**2), float(a)


@functools.lru_cache
def bratu_continuum_fold():
    """lam* = 8(s^2 - 1) with s tanh s = 1, and u(1/2) = 2 ln cosh s at the fold."""
    with mp.workdps(DPS):
        s = mp.findroot(lambda s: s * mp.tanh(s) - 1, 1.2)
        return float(8 * (s**2 - 1)), float(2 * mp.log(mp.cosh(s)))


#: lam*(N) for N = 99999 (h = 1e-5), too slow to recompute in every test run (~20 s). Produced
#: by `bratu_fd_fold(99999, dps=32)` and confirmed with dps=45 (both give
#: 3.51383071894235168460497410157945...); u_1 = 3.99998243040404708562089e-5.
#: Check against the continuum: lam* - lam*(N) = 1.8281e-10 = 1.8281 h^2.
BRATU_FOLD_N99999 = 3.5138307189423516846049741


# ---------------------------------------------------------------------------------------------
# 3. Von Mises truss: supports (+-L, 0), apex (0, H), load P downward, apex deflection v
# ---------------------------------------------------------------------------------------------


def truss_green_problem(strategy="analytic", EA=1.0, L=1.0, H=0.5):
    """1 dof, Green-Lagrange strain: P = (EA/l0^3) v (H - v)(2H - v). Unknown v, free P."""
    k = EA / (L**2 + H**2) ** 1.5

    def residual(u, p):
        v = u[0]
        return np.array([p["P"] - k * v * (H - v) * (2 * H - v)])

    def jacobian(u, p):
        v = u[0]
        return np.array([[-k * (2 * H**2 - 6 * H * v + 3 * v**2)]])

    def param_jacobian(u, p, name):
        return np.array([1.0])

    return make_problem(residual, ["v"], {"P": 0.0}, jacobian, param_jacobian, strategy)


def truss_green_limits(EA=1.0, L=1.0, H=0.5):
    """Limit points v = H(1 -+ 1/sqrt 3), P = +-(2/(3 sqrt 3)) EA H^3/l0^3, in mpmath."""
    with mp.workdps(DPS):
        EA, L, H = mp.mpf(EA), mp.mpf(L), mp.mpf(H)
        k = EA / (L**2 + H**2) ** mp.mpf(1.5)
        out = []
        for s in (-1, 1):
            v = H * (1 + s / mp.sqrt(3))
            out.append((float(v), float(k * v * (H - v) * (2 * H - v))))
        return tuple(out)


def truss_rotated_problem(strategy="analytic", EA=1.0, L=1.0, H=1.0):
    """1 dof, rotated engineering strain: P = 2EA y (1/l - 1/l0), y = H - v, l = sqrt(L^2+y^2)."""
    l0 = (L**2 + H**2) ** 0.5

    def residual(u, p):
        y = H - u[0]
        return np.array([p["P"] - 2 * EA * y * (1 / (L**2 + y**2) ** 0.5 - 1 / l0)])

    def jacobian(u, p):
        y = H - u[0]
        return np.array([[2 * EA * (L**2 / (L**2 + y**2) ** 1.5 - 1 / l0)]])

    def param_jacobian(u, p, name):
        return np.array([1.0])

    return make_problem(residual, ["v"], {"P": 0.0}, jacobian, param_jacobian, strategy)


def truss_rotated_limits(EA=1.0, L=1.0, H=1.0):
    """Limit where l^3 = L^2 l0, i.e. y = +-sqrt((L^2 l0)^(2/3) - L^2), in mpmath."""
    with mp.workdps(DPS):
        EA, L, H = mp.mpf(EA), mp.mpf(L), mp.mpf(H)
        l0 = mp.sqrt(L**2 + H**2)
        lc = mp.cbrt(L**2 * l0)
        out = []
        for y in (mp.sqrt(lc**2 - L**2), -mp.sqrt(lc**2 - L**2)):
            out.append((float(H - y), float(2 * EA * y * (1 / lc - 1 / l0))))
        return tuple(out)


def truss_2dof_residual_factory(EA=1.0, L=1.0, H=2.0):
    """Gradient of Pi = (EA l0/2)(e1^2 + e2^2) - P v in (u, v): apex free sideways (u)."""
    l02 = L**2 + H**2
    l0 = l02**0.5

    def strains(u, v):
        y = H - v
        e1 = ((L + u) ** 2 + y**2 - l02) / (2 * l02)
        e2 = ((L - u) ** 2 + y**2 - l02) / (2 * l02)
        return y, e1, e2

    def residual(q, p):
        u, v = q[0], q[1]
        y, e1, e2 = strains(u, v)
        return np.array(
            [EA * (e1 * (L + u) - e2 * (L - u)) / l0, -EA * y * (e1 + e2) / l0 - p["P"]]
        )

    def jacobian(q, p):
        u, v = q[0], q[1]
        y, e1, e2 = strains(u, v)
        juu = EA / l0 * ((L + u) ** 2 / l02 + e1 + (L - u) ** 2 / l02 + e2)
        juv = -EA * 2 * y * u / (l0 * l02)
        jvv = EA / l0 * (e1 + e2 + 2 * y**2 / l02)
        return np.array([[juu, juv], [juv, jvv]])

    def param_jacobian(q, p, name):
        return np.array([0.0, -1.0])

    return residual, jacobian, param_jacobian


def truss_2dof_problem(strategy="analytic", EA=1.0, L=1.0, H=2.0):
    res, jac, pjac = truss_2dof_residual_factory(EA, L, H)
    return make_problem(res, ["u", "v"], {"P": 0.0}, jac, pjac, strategy)


def truss_2dof_references(EA=1.0, L=1.0, H=2.0):
    """Branch point y^2 = H^2 - 2L^2 and limit point y^2 = H^2/3 on the symmetric path
    P = EA y (H^2 - y^2)/l0^3; on the asymmetric path u^2 + y^2 = H^2 - 2L^2 and
    P = 2 EA L^2 y / l0^3 (from dPi/du = u (A + 2L^2)/l0^2 with A = L^2 + u^2 + y^2 - l0^2)."""
    with mp.workdps(DPS):
        EA, L, H = mp.mpf(EA), mp.mpf(L), mp.mpf(H)
        l03 = (L**2 + H**2) ** mp.mpf(1.5)
        yb = mp.sqrt(H**2 - 2 * L**2)
        yl = H / mp.sqrt(3)
        return {
            "bp_v": float(H - yb),
            "bp_P": float(EA * yb * (H**2 - yb**2) / l03),
            "lp_v": float(H - yl),
            "lp_P": float(EA * yl * (H**2 - yl**2) / l03),
        }


# ---------------------------------------------------------------------------------------------
# 4. Snap-back: Green truss (EA = 1, L = 1, H = 0.1) in series with a spring k_s
# ---------------------------------------------------------------------------------------------

SNAP = {"EA": 1.0, "L": 1.0, "H": 0.1, "ks": 0.005}


def _truss_force(v, EA, L, H):
    return EA / (L**2 + H**2) ** 1.5 * v * (H - v) * (2 * H - v)


def _truss_stiffness(v, EA, L, H):
    return EA / (L**2 + H**2) ** 1.5 * (2 * H**2 - 6 * H * v + 3 * v**2)


def snapback_monitor_problem(strategy="analytic", EA=1.0, L=1.0, H=0.1, ks=0.005):
    """Unknowns (v, delta), free P: P = P_truss(v), delta = v + P/k_s. The delta-turning points
    are turning points with respect to the unknown `delta` (found with monitor=["delta"])."""

    def residual(q, p):
        v, d = q[0], q[1]
        return np.array([p["P"] - _truss_force(v, EA, L, H), d - v - p["P"] / ks])

    def jacobian(q, p):
        return np.array([[-_truss_stiffness(q[0], EA, L, H), 0.0], [-1.0, 1.0]])

    def param_jacobian(q, p, name):
        return np.array([1.0, -1.0 / ks])

    return make_problem(residual, ["v", "delta"], {"P": 0.0}, jacobian, param_jacobian, strategy)


def snapback_control_problem(strategy="analytic", EA=1.0, L=1.0, H=0.1, ks=0.005):
    """Unknown v, free parameter delta: v + P_truss(v)/k_s - delta = 0 (displacement control)."""

    def residual(q, p):
        v = q[0]
        return np.array([v + _truss_force(v, EA, L, H) / ks - p["delta"]])

    def jacobian(q, p):
        return np.array([[1.0 + _truss_stiffness(q[0], EA, L, H) / ks]])

    def param_jacobian(q, p, name):
        return np.array([-1.0])

    return make_problem(residual, ["v"], {"delta": 0.0}, jacobian, param_jacobian, strategy)


def snapback_turning_points(EA=1.0, L=1.0, H=0.1, ks=0.005):
    """delta-turning points t = -+sqrt((H^2 - k_s/K)/3), t = v - H, K = EA/l0^3, in mpmath.
    Returns ((v1, delta1, P1), (v2, delta2, P2)) in path order."""
    with mp.workdps(DPS):
        EA, L, H, ks = (mp.mpf(str(x)) for x in (EA, L, H, ks))
        K = EA / (L**2 + H**2) ** mp.mpf(1.5)
        out = []
        for s in (-1, 1):
            v = H + s * mp.sqrt((H**2 - ks / K) / 3)
            P = K * v * (H - v) * (2 * H - v)
            out.append((float(v), float(v + P / ks), float(P)))
        return tuple(out)


# ---------------------------------------------------------------------------------------------
# 5. Shallow arch, two-mode Ritz: Pi = (1/8)(x1^2 - 2e x1 + 4x2^2)^2 + x1^2 + 16x2^2 - p x1
# ---------------------------------------------------------------------------------------------


def arch_problem(e, strategy="analytic"):
    def residual(q, p):
        x1, x2 = q[0], q[1]
        Q = x1**2 - 2 * e * x1 + 4 * x2**2
        return np.array([Q * (x1 - e) / 2 + 2 * x1 - p["p"], 2 * Q * x2 + 32 * x2])

    def jacobian(q, p):
        x1, x2 = q[0], q[1]
        Q = x1**2 - 2 * e * x1 + 4 * x2**2
        j12 = 4 * x2 * (x1 - e)
        return np.array([[(x1 - e) ** 2 + Q / 2 + 2, j12], [j12, 2 * Q + 16 * x2**2 + 32]])

    def param_jacobian(q, p, name):
        return np.array([-1.0, 0.0])

    return make_problem(residual, ["xi1", "xi2"], {"p": 0.0}, jacobian, param_jacobian, strategy)


def arch_references(e):
    """On the symmetric path p = 2x + x(x - 2e)(x - e)/2: limit points where dp/dx = 0 (sympy
    roots, checked against e -+ sqrt((e^2 - 4)/3)); branch points where Q + 16 = 0, i.e.
    x = e -+ sqrt(e^2 - 16), p_B = 8e - 6x = 2e +- 6 sqrt(e^2 - 16) (only if e > 4)."""
    import sympy as sp

    x, ee = sp.symbols("x e", real=True)
    p = 2 * x + x * (x - 2 * ee) * (x - ee) / 2
    e_val = sp.nsimplify(e)
    lps = sorted(sp.solve(sp.diff(p, x).subs(ee, e_val), x), key=lambda r: float(r))
    closed = [e_val - sp.sqrt((e_val**2 - 4) / 3), e_val + sp.sqrt((e_val**2 - 4) / 3)]
    assert all(sp.simplify(a - b) == 0 for a, b in zip(lps, closed, strict=True))
    pe = p.subs(ee, e_val)
    out = {"lp": [(float(r.evalf(DPS)), float(pe.subs(x, r).evalf(DPS))) for r in lps]}
    Q16 = (x**2 - 2 * ee * x + 16).subs(ee, e_val)
    bps = sorted((r for r in sp.solve(Q16, x) if r.is_real), key=lambda r: float(r))
    out["bp"] = [(float(r.evalf(DPS)), float(pe.subs(x, r).evalf(DPS))) for r in bps]
    return out


# ---------------------------------------------------------------------------------------------
# 6. Cohesive bar, nondimensional: U = s l + W
# ---------------------------------------------------------------------------------------------


def cohesive_exp_problem(ell=2.0, strategy="analytic"):
    """Exponential softening s = exp(-W): unknown W, free U, residual U - l e^{-W} - W."""

    def residual(q, p):
        return np.array([p["U"] - ell * np.exp(-q[0]) - q[0]])

    def jacobian(q, p):
        return np.array([[ell * np.exp(-q[0]) - 1.0]])

    def param_jacobian(q, p, name):
        return np.array([1.0])

    return make_problem(residual, ["W"], {"U": ell}, jacobian, param_jacobian, strategy)


def cohesive_linear_problem(ell=2.0, w0=0.01, strategy="analytic"):
    """Bilinear (intrinsic) cohesive law, a continuous piecewise-linear s(W): s = W/w0 up to
    the peak s = 1 at W = w0, then linear softening s = (1 - W)/(1 - w0) to s = 0 at W = 1,
    then s = 0. Unknown W, free U, residual U - l s(W) - W. U(W) is continuous with slope
    l/w0 + 1 > 0 before the peak and 1 - l/(1 - w0) < 0 after it (l = 2): the peak
    U = l + w0 is a turning point of U with a kink (no smooth fold), and so is the minimum
    U = 1 at W = 1 where softening ends."""

    def s_and_slope(w):
        wr = np.real(w)
        if wr <= w0:
            return w / w0, 1.0 / w0
        if wr <= 1.0:
            return (1.0 - w) / (1.0 - w0), -1.0 / (1.0 - w0)
        return 0.0 * w, 0.0

    def residual(q, p):
        s, _ = s_and_slope(q[0])
        return np.array([p["U"] - ell * s - q[0]])

    def jacobian(q, p):
        _, ds = s_and_slope(q[0])
        return np.array([[-ell * ds - 1.0]])

    def param_jacobian(q, p, name):
        return np.array([1.0])

    return make_problem(residual, ["W"], {"U": 0.0}, jacobian, param_jacobian, strategy)
