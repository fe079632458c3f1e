"""Symmetric branch points (pitchforks) of applications, on a trivial branch u = 0: the
equations are odd in u (R(−u) = −R(u)), so u = 0 solves them for every parameter value and
each simple eigenvalue of ∂R/∂u crossing zero there is a symmetric pitchfork.

- :func:`lorenz_stenflo`: equilibria of the Lorenz–Stenflo equations (acoustic-gravity waves
  in a rotating atmosphere; four unknowns), a pitchfork at r = 1 + s/a²;
- :func:`chen`: equilibria of the Chen system (three unknowns), a pitchfork at c = a/2;
- :func:`hopfield`: equilibria of a Hopfield network of four graded-response neurons with
  Hebbian weights, pitchforks at gain λ = 1/μ for each positive eigenvalue μ of the weights;
- :func:`chafee_infante`: steady states of the Chafee–Infante (Allen–Cahn) equation by finite
  differences, dense or sparse, any N: a cascade of pitchforks at the eigenvalues of the
  discrete Laplacian.

Every branch point comes as a :class:`Pitchfork`: the point, the null vector (mode) of ∂R/∂u
there, and, where there is one, the closed form of the other branch (``other``: residuals
that vanish on it; ``point``: the point of amplitude a on it). The two-cell problems, whose
symmetric branch is not u = 0, are in :mod:`~cusp.examples.symmetric_cells`;
``cusp.examples.PITCHFORKS`` lists the pitchforks of every one of them.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np
import scipy.sparse as sps

from ._base import DPS, Example, Reference, make_example


class Pitchfork(NamedTuple):
    """A symmetric branch point of an example's trivial branch and what a branch-switching
    test needs.

    ``values``: every unknown and parameter at the point (closed form, mpmath at 40 digits,
    rounded once). ``mode``: the null vector of ∂R/∂u there, one entry per unknown in the
    example's order (not normalised); the other branch leaves along (mode, 0) — a pitchfork:
    the free parameter is stationary. ``other``: a function of a mapping of values (floats
    or a :class:`~cusp.continuation.Branch`'s columns) returning the residuals of the other
    branch's closed form, a list of arrays that vanish on it; ``point``: the point of the
    other branch at amplitude a (a = 0 is the branch point), every unknown and parameter.
    Both are ``None`` where no closed form is known.
    """

    values: dict[str, float]
    mode: tuple[float, ...]
    other: Callable[[Any], list[Any]] | None = None
    point: Callable[[float], dict[str, float]] | None = None

    def reference(self, free: str) -> Reference:
        """The point as a :class:`Reference` of kind ``"branch_point"``."""
        return Reference("branch_point", dict(self.values), (free,))


# ---------------------------------------------------------------------------------------------
# Lorenz-Stenflo equilibria
# ---------------------------------------------------------------------------------------------

#: The Lorenz–Stenflo constants used here (the chaotic set of the literature, with r free).
LORENZ_STENFLO = {"a": 1.0, "b": 0.7, "s": 1.5}


def lorenz_stenflo(*, derivatives: str = "analytic") -> Example:
    """Equilibria of the Lorenz–Stenflo equations (L. Stenflo, "Generalized Lorenz equations
    for acoustic-gravity waves in the atmosphere", Physica Scripta 53, 83–84, 1996): the
    Lorenz model with the rotation of the atmosphere (s, the rotation number), a the Prandtl
    number, r the generalised Rayleigh number, b a geometric factor::

        a (y − x) + s w = 0,   r x − x z − y = 0,   x y − b z = 0,   −x − a w = 0

    Unknowns ``x``, ``y``, ``z``, ``w``; parameters ``r`` (free) and :data:`LORENZ_STENFLO`
    (a = 1, b = 0.7, s = 1.5). Start: the origin at r = 0; bounds r ∈ [0, 30].

    The origin's Jacobian has det = −b (a² r − a² − s) (sympy), so one branch point,
    r_c = 1 + s/a² = 2.5, a pitchfork (the equations are odd in (x, y, w)). Mode
    (x, y, z, w) = (1, r_c, 0, −1/a). Other branch: w = −x/a, y = r_c x, z = r − r_c,
    x² = b (r − r_c)/r_c, i.e. x = ±√(b (r − r_c)/r_c) for r > r_c (supercritical);
    :func:`lorenz_stenflo_pitchforks`.
    """

    def residual(u, p):
        x, y, z, w = u[0], u[1], u[2], u[3]
        a = p["a"]
        return np.array(
            [a * (y - x) + p["s"] * w, p["r"] * x - x * z - y, x * y - p["b"] * z, -x - a * w]
        )

    def jacobian(u, p):
        x, y, z = u[0], u[1], u[2]
        a = p["a"]
        return np.array(
            [
                [-a, a, 0.0, p["s"]],
                [p["r"] - z, -1.0, -x, 0.0],
                [y, x, -p["b"], 0.0],
                [-1.0, 0.0, 0.0, -a],
            ]
        )

    def param_jacobian(u, p, name):
        x, y, z, w = u[0], u[1], u[2], u[3]
        return {
            "r": np.array([0.0, x, 0.0, 0.0]),
            "a": np.array([y - x, 0.0, 0.0, -w]),
            "b": np.array([0.0, 0.0, -z, 0.0]),
            "s": np.array([w, 0.0, 0.0, 0.0]),
        }[name]

    return make_example(
        "Lorenz-Stenflo equilibria",
        residual,
        ["x", "y", "z", "w"],
        {"r": 0.0, **LORENZ_STENFLO},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=np.zeros(4),
        free="r",
        bounds={"r": (0.0, 30.0)},
        references=lambda: tuple(pf.reference("r") for pf in lorenz_stenflo_pitchforks()),
    )


@functools.lru_cache
def lorenz_stenflo_pitchforks() -> tuple[Pitchfork, ...]:
    """The branch point of :func:`lorenz_stenflo`'s origin: r_c = 1 + s/a² (mpmath at 40
    digits from the binary constants), mode (1, r_c, 0, −1/a), other branch
    x = ±√(b (r − r_c)/r_c), y = r_c x, z = r − r_c, w = −x/a (amplitude a = x)."""
    import mpmath as mp

    c = LORENZ_STENFLO
    with mp.workdps(DPS):
        a, b, s = (mp.mpf(c[k]) for k in ("a", "b", "s"))
        rc_mp = 1 + s / a**2
        rc, mode = float(rc_mp), (1.0, float(rc_mp), 0.0, float(-1 / a))

    def other(v):
        x = v["x"]
        return [
            v["w"] + x / c["a"],
            v["y"] - rc * x,
            v["z"] - (v["r"] - rc),
            rc * x**2 - c["b"] * (v["r"] - rc),
        ]

    def point(amp):
        r = rc + rc * amp**2 / c["b"]
        return {"x": amp, "y": rc * amp, "z": r - rc, "w": -amp / c["a"], "r": r, **c}

    zero = {"x": 0.0, "y": 0.0, "z": 0.0, "w": 0.0, "r": rc, **c}
    return (Pitchfork(zero, mode, other, point),)


# ---------------------------------------------------------------------------------------------
# Chen system equilibria
# ---------------------------------------------------------------------------------------------

#: The Chen system's constants (Chen & Ueta's chaotic set, with c free).
CHEN = {"a": 35.0, "b": 3.0}


def chen(*, derivatives: str = "analytic") -> Example:
    """Equilibria of the Chen system (G. Chen and T. Ueta, "Yet another chaotic attractor",
    Int. J. Bifurcation and Chaos 9, 1465–1466, 1999; an anticontrolled Lorenz system, the
    electronic-circuit chaos generator of the chaos-control literature)::

        a (y − x) = 0,   (c − a) x − x z + c y = 0,   x y − b z = 0

    Unknowns ``x``, ``y``, ``z``; parameters ``c`` (free) and :data:`CHEN` (a = 35, b = 3,
    the paper's). Start: the origin at c = 0; bounds c ∈ [0, 30] (the paper's c = 28
    inside).

    The origin's Jacobian has det = −a b (a − 2c) (its (x, y) block [[−a, a], [c − a, c]]
    times −b), so one branch point, c = a/2 = 17.5, a pitchfork (odd in (x, y)). Mode
    (1, 1, 0). Other branch: x = y, z = 2c − a, x² = b (2c − a), i.e.
    x = y = ±√(b (2c − a)) for c > a/2 (:func:`chen_pitchforks`).
    """

    def residual(u, p):
        x, y, z = u[0], u[1], u[2]
        a, c = p["a"], p["c"]
        return np.array([a * (y - x), (c - a) * x - x * z + c * y, x * y - p["b"] * z])

    def jacobian(u, p):
        x, y, z = u[0], u[1], u[2]
        a, c = p["a"], p["c"]
        return np.array([[-a, a, 0.0], [c - a - z, c, -x], [y, x, -p["b"]]])

    def param_jacobian(u, p, name):
        x, y, z = u[0], u[1], u[2]
        return {
            "c": np.array([0.0, x + y, 0.0]),
            "a": np.array([y - x, -x, 0.0]),
            "b": np.array([0.0, 0.0, -z]),
        }[name]

    return make_example(
        "Chen system equilibria",
        residual,
        ["x", "y", "z"],
        {"c": 0.0, **CHEN},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=np.zeros(3),
        free="c",
        bounds={"c": (0.0, 30.0)},
        references=lambda: tuple(pf.reference("c") for pf in chen_pitchforks()),
    )


@functools.lru_cache
def chen_pitchforks() -> tuple[Pitchfork, ...]:
    """The branch point of :func:`chen`'s origin, c = a/2 (exact), mode (1, 1, 0); other
    branch x = y = ±√(b (2c − a)), z = 2c − a (amplitude a = x)."""
    a, b = CHEN["a"], CHEN["b"]
    cc = a / 2  # exact in binary

    def other(v):
        return [v["y"] - v["x"], v["z"] - (2 * v["c"] - a), v["x"] ** 2 - b * v["z"]]

    def point(amp):
        z = amp**2 / b
        return {"x": amp, "y": amp, "z": z, "c": (z + a) / 2, **CHEN}

    zero = {"x": 0.0, "y": 0.0, "z": 0.0, "c": cc, **CHEN}
    return (Pitchfork(zero, (1.0, 1.0, 0.0), other, point),)


# ---------------------------------------------------------------------------------------------
# Hopfield network of graded-response neurons
# ---------------------------------------------------------------------------------------------

#: The stored patterns of :func:`hopfield` (orthogonal, ±1) and their strengths.
HOPFIELD_PATTERNS = ((1, 1, 1, 1), (1, 1, -1, -1), (1, -1, 1, -1))
HOPFIELD_STRENGTHS = (3.0, 2.0, 1.0)


def hopfield_weights() -> np.ndarray:
    """The Hebbian weights W = (1/N) Σ_p c_p ξ^p ξ^pᵀ − (Σ_p c_p/N) I of
    :data:`HOPFIELD_PATTERNS` with strengths :data:`HOPFIELD_STRENGTHS` (N = 4; zero
    diagonal): W = [[0, 1, ½, 0], [1, 0, 0, ½], [½, 0, 0, 1], [0, ½, 1, 0]], a ring of four
    neurons with alternating couplings. Its eigenvalues are c_p − c̄ on ξ^p (c̄ = 3/2):
    3/2, 1/2, −1/2, and −3/2 on (1, −1, −1, 1)."""
    xi = np.array(HOPFIELD_PATTERNS, dtype=float)
    c = np.array(HOPFIELD_STRENGTHS)
    n = xi.shape[1]
    return (xi.T * c) @ xi / n - c.sum() / n * np.eye(n)


def hopfield(*, derivatives: str = "analytic") -> Example:
    """Equilibria of a Hopfield network of four graded-response neurons (J. J. Hopfield,
    "Neurons with graded response have collective computational properties like those of
    two-state neurons", PNAS 81, 3088–3092, 1984, with C = R = 1, no input currents and the
    output V = tanh(λ u) of gain λ)::

        −u_i + Σ_j W_ij tanh(λ u_j) = 0,   i = 1 … 4

    with the symmetric Hebbian weights of :func:`hopfield_weights` (Hopfield, PNAS 79, 2554,
    1982: three orthogonal ±1 patterns stored with strengths 3, 2, 1, zero diagonal).
    Unknowns ``u1`` … ``u4``; parameter ``lam`` (free, the gain). Start: u = 0 at λ = 0;
    bounds λ ∈ [0, 3].

    ∂R/∂u = −I + λ W at u = 0: a branch point at λ = 1/μ for each positive eigenvalue μ of
    W, all simple: λ = 2/3 (μ = 3/2, mode ξ¹ = (1, 1, 1, 1), the first, where the network
    starts to remember) and λ = 2 (μ = 1/2, mode ξ² = (1, 1, −1, −1)); both pitchforks
    (tanh is odd). Other branches (exact, since W tanh(λ a ξ) = μ tanh(λ a) ξ for a ±1
    eigenvector ξ): u = a ξ with a = μ tanh(λ a), i.e. λ = artanh(a/μ)/a, |a| < μ
    (supercritical; :func:`hopfield_pitchforks`).
    """
    W = hopfield_weights()

    def residual(u, p):
        return -u + W @ np.tanh(p["lam"] * u)

    def jacobian(u, p):
        lam = p["lam"]
        return -np.eye(4) + W * (lam / np.cosh(lam * u) ** 2)

    def param_jacobian(u, p, name):
        if name != "lam":
            raise KeyError(name)
        return W @ (u / np.cosh(p["lam"] * u) ** 2)

    return make_example(
        "Hopfield network, four neurons",
        residual,
        hopfield_names(),
        {"lam": 0.0},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=np.zeros(4),
        free="lam",
        bounds={"lam": (0.0, 3.0)},
        references=lambda: tuple(pf.reference("lam") for pf in hopfield_pitchforks()),
    )


def hopfield_names() -> list[str]:
    """The unknowns ``u1 … u4`` of :func:`hopfield`."""
    return [f"u{i + 1}" for i in range(4)]


@functools.lru_cache
def hopfield_pitchforks() -> tuple[Pitchfork, ...]:
    """The branch points of :func:`hopfield`'s u = 0 in λ ∈ [0, 3], ascending: λ = 1/μ for
    the eigenvalues μ = c_p − c̄ > 0 of the stored patterns (3/2 and 1/2; exact rationals,
    evaluated in mpmath at 40 digits), mode ξ^p; other branch u = a ξ^p,
    λ = artanh(a/μ)/a."""
    import mpmath as mp

    names = hopfield_names()
    c = HOPFIELD_STRENGTHS
    out = []
    with mp.workdps(DPS):
        mean = mp.fsum(mp.mpf(v) for v in c) / len(HOPFIELD_PATTERNS[0])
        for xi, strength in zip(HOPFIELD_PATTERNS, c):
            mu = mp.mpf(strength) - mean
            if mu > 0 and 1 / mu <= 3:
                out.append((float(1 / mu), float(mu), tuple(float(v) for v in xi)))
    return tuple(
        Pitchfork({**dict.fromkeys(names, 0.0), "lam": lam}, xi, *_hopfield_other(mu, xi))
        for lam, mu, xi in sorted(out)
    )


def _hopfield_other(mu: float, xi: tuple[float, ...]):
    """(other, point) of the branch u = a ξ, λ = artanh(a/μ)/a."""
    names = hopfield_names()

    def other(v):
        a = v["u1"] / xi[0]
        res = [v[name] - a * s for name, s in zip(names[1:], xi[1:])]
        # μ tanh(λ a)/a − 1 (μλ − 1 at a = 0): a = μ tanh(λ a) divided by a, which would
        # hold on u = 0 too
        a, lam = np.asarray(a, dtype=float), v["lam"]
        safe = np.where(a == 0, 1.0, a)
        return [*res, mu * np.where(a == 0, lam, np.tanh(lam * safe) / safe) - 1]

    def point(amp):
        lam = math.atanh(amp / mu) / amp if amp else 1 / mu
        return {**{name: amp * s for name, s in zip(names, xi)}, "lam": lam}

    return other, point


# ---------------------------------------------------------------------------------------------
# Chafee-Infante (Allen-Cahn) equation, finite differences
# ---------------------------------------------------------------------------------------------


def chafee_infante_names(n: int) -> list[str]:
    """The unknowns ``u1 … u{n}``: u at x_i = i h, h = π/(n + 1)."""
    return [f"u{i + 1}" for i in range(n)]


def _ci_residual(u, p):
    n = u.shape[0]
    h2 = (math.pi / (n + 1)) ** 2
    lap = -2.0 * u
    lap[1:] += u[:-1]
    lap[:-1] += u[1:]
    return lap / h2 + p["lam"] * (u - u**3)


def _ci_jacobian_dense(u, p):
    n = u.shape[0]
    h2 = (math.pi / (n + 1)) ** 2
    lap = np.diag(np.full(n - 1, 1.0), -1) + np.diag(np.full(n - 1, 1.0), 1) - 2.0 * np.eye(n)
    return lap / h2 + np.diag(p["lam"] * (1 - 3 * u**2))


def _ci_jacobian_sparse(u, p):
    n = u.shape[0]
    h2 = (math.pi / (n + 1)) ** 2
    off = np.full(n - 1, 1.0 / h2)
    diag = -2.0 / h2 + p["lam"] * (1 - 3 * u**2)
    return sps.diags([off, diag, off], [-1, 0, 1], format="csc")


def _ci_param_jacobian(u, p, name):
    if name != "lam":
        raise KeyError(name)
    return u - u**3


def chafee_infante(
    n: int = 5, *, sparse: bool = False, lam_max: float = 10.0, derivatives: str = "analytic"
) -> Example:
    """Steady states of the Chafee–Infante equation u_t = u_xx + λ (u − u³) on (0, π),
    u(0) = u(π) = 0 (N. Chafee and E. F. Infante, "A bifurcation problem for a nonlinear
    partial differential equation of parabolic type", Applicable Anal. 4, 17–37, 1974; the
    Allen–Cahn equation of phase separation, Allen & Cahn, Acta Metall. 27, 1979), by
    central differences on n interior nodes x_i = i h, h = π/(n + 1)::

        (u_{i−1} − 2u_i + u_{i+1})/h² + λ (u_i − u_i³) = 0,   u_0 = u_{n+1} = 0

    Unknowns ``u1 … u{n}``; parameter ``lam`` (free). ``sparse``: the analytic Jacobian as a
    ``scipy.sparse`` CSC matrix (with a finite-difference ``derivatives``, the tridiagonal
    pattern as ``sparsity``), for n in the hundreds or thousands. Start: u = 0 at λ = 0;
    bounds λ ∈ [0, lam_max] (default 10).

    u = 0 solves the equations for every λ; its Jacobian is Δ_h + λ I, singular where λ is an
    eigenvalue of −Δ_h, λ_k = (4/h²) sin²(k h/2), k = 1 … n (continuum k²), each simple with
    the mode sin(k x_i): a cascade of pitchforks (odd equations), all supercritical
    (Lyapunov–Schmidt: λ ≈ λ_k (1 + (3/4) a²) along u ≈ a sin(k x_i), since
    Σ sin⁴/Σ sin² = 3/4 over the nodes; 1 + a² where 2k = n + 1). Default n = 5:
    λ = 0.9774, 3.6476, 7.2951 in the window (:func:`chafee_infante_pitchforks`).

    Other branches in closed form where the mode takes only the values 0 and ±c: 2k = n + 1
    (pattern 1, 0, −1, 0, …) and 3k = n + 1 (pattern 1, 1, 0, −1, −1, 0, …). There
    u = a·pattern and λ = q/(h² (1 − a²)), q = 2 and 1: at a node u_i = ±a the neighbours
    are 0, 0 (q = 2) or 0, u_i (q = 1), so Δ_h u_i = −q u_i/h², and at a zero node they are
    +a and −a. For n = 5 the modes k = 2 (λ_2 = 1/h² = 36/π²) and k = 3 (λ_3 = 2/h² = 72/π²)
    have them; mode 1 has none.
    """
    if n < 1:
        raise ValueError(f"n must be >= 1, got {n}")
    sparsity = None
    if sparse and derivatives != "analytic":
        sparsity = sps.diags([np.ones(n - 1), np.ones(n), np.ones(n - 1)], [-1, 0, 1])

    def references():
        return tuple(pf.reference("lam") for pf in chafee_infante_pitchforks(n, lam_max))

    return make_example(
        f"Chafee-Infante, N = {n}" + (" (sparse)" if sparse else ""),
        _ci_residual,
        chafee_infante_names(n),
        {"lam": 0.0},
        _ci_jacobian_sparse if sparse else _ci_jacobian_dense,
        _ci_param_jacobian,
        derivatives=derivatives,
        u0=np.zeros(n),
        free="lam",
        bounds={"lam": (0.0, lam_max)},
        references=references,
        sparsity=sparsity,
    )


def chafee_infante_eigenvalue(n: int, k: int) -> float:
    """λ_k = (4/h²) sin²(k h/2), h = π/(n + 1): the k-th eigenvalue of −Δ_h (mpmath at 40
    digits)."""
    import mpmath as mp

    with mp.workdps(DPS):
        h = mp.pi / (n + 1)
        return float(4 / h**2 * mp.sin(k * h / 2) ** 2)


@functools.lru_cache
def chafee_infante_pitchforks(n: int = 5, lam_max: float = 10.0) -> tuple[Pitchfork, ...]:
    """The branch points of :func:`chafee_infante`'s u = 0 with λ ≤ lam_max, ascending:
    λ_k (:func:`chafee_infante_eigenvalue`), mode sin(k x_i) = sin(k i h); other branch in
    closed form where 2k = n + 1 or 3k = n + 1 (see :func:`chafee_infante`), else None."""
    out = []
    h = math.pi / (n + 1)
    names = chafee_infante_names(n)
    for k in range(1, n + 1):
        lam = chafee_infante_eigenvalue(n, k)
        if lam > lam_max:
            break
        mode = tuple(float(np.sin(k * h * i)) for i in range(1, n + 1))
        values = {**dict.fromkeys(names, 0.0), "lam": lam}
        out.append(Pitchfork(values, mode, *_ci_other(n, k)))
    return tuple(out)


def _ci_other(n: int, k: int):
    """(other, point) of the exact branch u = a·pattern, λ = q/(h² (1 − a²)) of mode k, when
    2k = n + 1 (q = 2) or 3k = n + 1 (q = 1); (None, None) otherwise."""
    period: tuple[int, ...]
    if 2 * k == n + 1:
        q, period = 2.0, (1, 0, -1, 0)
    elif 3 * k == n + 1:
        q, period = 1.0, (1, 1, 0, -1, -1, 0)
    else:
        return None, None
    pattern = [period[i % len(period)] for i in range(n)]
    h2 = (math.pi / (n + 1)) ** 2
    names = chafee_infante_names(n)

    def other(v):
        a = v["u1"]
        res = [v[name] - s * a for name, s in zip(names[1:], pattern[1:])]
        return [*res, v["lam"] * h2 * (1 - a**2) - q]

    def point(amp):
        lam = q / (h2 * (1 - amp**2))
        return {**{name: s * amp for name, s in zip(names, pattern)}, "lam": lam}

    return other, point
