"""The finite-difference Bratu problem: ``u'' + λ eᵘ = 0`` on (0, 1), ``u(0) = u(1) = 0``, on N
interior nodes (h = 1/(N + 1)):

    (u_{i−1} − 2u_i + u_{i+1})/h² + λ e^{u_i} = 0,  i = 1 … N,  u_0 = u_{N+1} = 0.

A banded problem of any size with one fold in λ (the continuum fold λ* = 3.513830719125161 is
approached like λ*(N) ≈ λ* − 1.828 h²). References: the discrete fold by shooting in mpmath
(:func:`bratu_fd_fold`), the continuum fold (:func:`bratu_continuum_fold`) and the stored fold
for N = 99 999 (:data:`BRATU_FOLD_N99999`).
"""

from __future__ import annotations

import functools

import numpy as np
import scipy.sparse as sps

from ._base import DPS, Example, Reference, make_example


def bratu_names(n: int) -> list[str]:
    """The unknowns ``u0 … u{n−1}`` (node i + 1 of the grid is unknown ``u{i}``)."""
    return [f"u{i}" for i in range(n)]


def _residual(u, p):
    n = u.shape[0]
    h2 = (1.0 / (n + 1)) ** 2
    lap = -2.0 * u
    lap[1:] += u[:-1]
    lap[:-1] += u[1:]
    return lap / h2 + p["lam"] * np.exp(u)


def _jacobian_dense(u, p):
    n = u.shape[0]
    h2 = (1.0 / (n + 1)) ** 2
    jac = (
        np.diag(np.full(n - 1, 1.0), -1) + np.diag(np.full(n - 1, 1.0), 1) - 2.0 * np.eye(n)
    ) / h2
    return jac + np.diag(p["lam"] * np.exp(u))


def _jacobian_sparse(u, p):
    n = u.shape[0]
    h2 = (1.0 / (n + 1)) ** 2
    off = np.full(n - 1, 1.0 / h2)
    return sps.diags([off, -2.0 / h2 + p["lam"] * np.exp(u), off], [-1, 0, 1], format="csc")


def _param_jacobian(u, p, name):
    if name != "lam":
        raise KeyError(name)
    return np.exp(u)


def bratu(n: int, *, derivatives: str = "analytic", sparse: bool = False) -> Example:
    """The FD Bratu problem with ``n`` interior nodes: unknowns ``u0 … u{n−1}``, parameter
    ``lam`` (λ).

    ``sparse``: the analytic Jacobian as a ``scipy.sparse`` CSC matrix (else dense); with a
    finite-difference ``derivatives`` strategy, the tridiagonal pattern is given as
    ``sparsity`` (grouped differences, sparse Jacobians). ∂R/∂λ = eᵘ.

    Start u = 0 at λ = 0; free ``lam``; bounds on the middle unknown ``u{n//2} ∈ [−1, 2]``
    (past the fold, where u(½) = 1.1868 in the continuum limit).

    Special points: one fold in λ (:func:`bratu_fd_fold`; N = 1: u = 1, λ = 8/e; N = 2:
    u = (1, 1), λ = 9/e, both exact).
    """
    if n < 1:
        raise ValueError(f"n must be >= 1, got {n}")
    sparsity = None
    if sparse and derivatives != "analytic":
        sparsity = sps.diags([np.ones(n - 1), np.ones(n), np.ones(n - 1)], [-1, 0, 1])

    def references():
        lam, u = bratu_fd_fold_state(n)
        values = {name: float(x) for name, x in zip(bratu_names(n), u, strict=True)}
        values["lam"] = lam
        return (Reference("fold", values, ("lam",)),)

    return make_example(
        f"FD Bratu, N = {n}",
        _residual,
        bratu_names(n),
        {"lam": 0.0},
        _jacobian_sparse if sparse else _jacobian_dense,
        _param_jacobian,
        derivatives=derivatives,
        u0=np.zeros(n),
        free="lam",
        bounds={f"u{n // 2}": (-1.0, 2.0)},
        references=references,
        sparsity=sparsity,
    )


def _bratu_shoot(a, mu, n):
    """Discrete shooting for the FD Bratu problem with mu = h^2 lam.

    u_0 = 0, u_1 = a, u_{i+1} = 2u_i - u_{i-1} - mu e^{u_i} (i = 1..n). Returns u_{n+1} and its
    derivatives w = du/da, z = du/dmu, wa = d2u/da2, wm = d2u/dadmu (variational recursions),
    so that Newton on (u_{n+1}, w_{n+1}) = (0, 0) has the exact Jacobian [[w, z], [wa, wm]].
    """
    import mpmath as mp

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
def _bratu_fold_mp(n, dps):
    """(mu, a) of the fold at ``dps`` digits (see :func:`bratu_fd_fold`), as mpmath numbers."""
    import mpmath as mp

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
        return mu, a


@functools.lru_cache
def bratu_fd_fold(n: int, dps: int = DPS) -> tuple[float, float]:
    """Fold (lam*(N), u_1) of the N-point FD Bratu problem by discrete shooting in mpmath.

    Fold <=> u_{N+1}(a, mu) = 0 and du_{N+1}/da = 0 (then dmu/da = 0 along the solution
    curve a -> mu(a)). Newton from the continuum guess a = 4h (u'(0) = 4 at the fold since
    s tanh s = 1), lam = lam* - 1.83 h^2, with the exact 2x2 Jacobian, to 1e-(dps-4).
    """
    import mpmath as mp

    mu, a = _bratu_fold_mp(n, dps)
    with mp.workdps(dps):
        h = mp.mpf(1) / (n + 1)
        return float(mu / h**2), float(a)


@functools.lru_cache
def bratu_fd_fold_state(n: int, dps: int = DPS) -> tuple[float, tuple[float, ...]]:
    """(lam*(N), (u_1, …, u_N)): the fold of :func:`bratu_fd_fold` with its whole state, the
    nodes recomputed by the shooting recursion u_{i+1} = 2u_i − u_{i−1} − h²λ e^{u_i} from the
    converged (u_1, h²λ), in mpmath at ``dps`` digits."""
    import mpmath as mp

    mu, a = _bratu_fold_mp(n, dps)
    with mp.workdps(dps):
        h = mp.mpf(1) / (n + 1)
        nodes = [mp.mpf(0), a]
        for _ in range(n - 1):
            nodes.append(2 * nodes[-1] - nodes[-2] - mu * mp.exp(nodes[-1]))
        return float(mu / h**2), tuple(float(x) for x in nodes[1:])


@functools.lru_cache
def bratu_continuum_fold() -> tuple[float, float]:
    """lam* = 8(s^2 - 1) with s tanh s = 1, and u(1/2) = 2 ln cosh s at the fold (mpmath,
    40 digits)."""
    import mpmath as mp

    with mp.workdps(DPS):
        s = mp.findroot(lambda s: s * mp.tanh(s) - 1, 1.2)
        return float(8 * (s**2 - 1)), float(2 * mp.log(mp.cosh(s)))


#: lam*(N) for N = 99999 (h = 1e-5), too slow to recompute in every test run (~20 s). Produced
#: by `bratu_fd_fold(99999, dps=32)` and confirmed with dps=45 (both give
#: 3.51383071894235168460497410157945...); u_1 = 3.99998243040404708562089e-5.
#: Check against the continuum: lam* - lam*(N) = 1.8281e-10 = 1.8281 h^2.
BRATU_FOLD_N99999 = 3.5138307189423516846049741
