"""Pattern-forming and chaotic systems, their steady states: Gray–Scott, the Brusselator with
diffusion, the Lorenz equations.

- :func:`gray_scott`: spatially uniform steady states of the Gray–Scott model: a fold and a
  transcritical branch point, both in closed form;
- :func:`brusselator`: steady states of the Brusselator with diffusion on N grid points and
  Dirichlet ends: the uniform state for every length L, with a branch point wherever a
  discrete Fourier mode becomes neutral (closed form), two of them 0.012 apart;
- :func:`lorenz`: equilibria of the Lorenz equations (AUTO-07p demo ``lrz``): the pitchfork of
  the origin at ρ = 1.
"""

from __future__ import annotations

import functools

import numpy as np

from ._base import DPS, Example, Reference, make_example

# ---------------------------------------------------------------------------------------------
# Gray-Scott, uniform steady states
# ---------------------------------------------------------------------------------------------


def gray_scott(F: float = 0.04, *, derivatives: str = "analytic") -> Example:
    """Uniform steady states of the Gray–Scott model (Gray & Scott, Chem. Eng. Sci. 39, 1984;
    Pearson, Science 261, 1993, whose F = 0.04 is used here)::

        −u v² + F (1 − u)    = 0
        u v² − (F + k) v     = 0

    Unknowns ``u``, ``v``, parameters ``k`` (free) and ``F``. Besides the trivial state
    (u, v) = (1, 0), uv = F + k gives (F + k) v² − F v + F (F + k) = 0 and
    u = 1 − (F + k) v/F. Start: the upper root at k = 0
    (v = (F + √(F² − 4F (F + k)²))/(2 (F + k))); bounds k ∈ [−0.1, 0.1], v ∈ [−0.5, 2].

    Special points (:func:`gray_scott_references`, closed form): the fold where the two roots
    merge, F = 4 (F + k)², i.e. F + k = √F/2: k = √F/2 − F, v = √F, u = 1/2 (F = 0.04:
    k = 0.06, v = 0.2).
    The lower root reaches v = 0 at k = −F, where it crosses the trivial branch u = 1, v = 0
    in a transcritical branch point (the trivial state's Jacobian is diag(−F, −(F + k))).
    """

    def residual(q, p):
        u, v = q[0], q[1]
        return np.array([-u * v**2 + p["F"] * (1 - u), u * v**2 - (p["F"] + p["k"]) * v])

    def jacobian(q, p):
        u, v = q[0], q[1]
        return np.array([[-(v**2) - p["F"], -2 * u * v], [v**2, 2 * u * v - (p["F"] + p["k"])]])

    def param_jacobian(q, p, name):
        u, v = q[0], q[1]
        if name == "k":
            return np.array([0.0, -v])
        if name == "F":
            return np.array([1 - u, -v])
        raise KeyError(name)

    def references():
        return tuple(
            Reference(kind, {**values, "F": F}, ("k",)) for kind, values in gray_scott_references(F)
        )

    # the upper root at k = 0: F v² − F v + F² = 0, v = (1 + √(1 − 4F))/2, u = 1 − v
    v0 = (1 + (1 - 4 * F) ** 0.5) / 2
    return make_example(
        "Gray-Scott uniform steady states",
        residual,
        ["u", "v"],
        {"k": 0.0, "F": F},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[1 - v0, v0],
        free="k",
        bounds={"k": (-0.1, 0.1), "v": (-0.5, 2.0)},
        references=references,
    )


@functools.lru_cache
def gray_scott_references(F: float = 0.04) -> tuple[tuple[str, dict[str, float]], ...]:
    """The fold and the branch point of :func:`gray_scott`, in path order from the upper
    root at k = 0: the fold k = √F/2 − F (where the discriminant F² − 4F (F + k)² of
    (F + k) v² − F v + F (F + k) = 0 vanishes), v = F/(2 (F + k)) = √F,
    u = 1 − (F + k) v/F = 1/2; then the branch point k = −F, u = 1, v = 0. mpmath at 40
    digits, with F the binary value of the float given."""
    import mpmath as mp

    with mp.workdps(DPS):
        f = mp.mpf(F)
        k = mp.sqrt(f) / 2 - f
        v = f / (2 * (f + k))
        u = 1 - (f + k) * v / f
        return (
            ("fold", {"u": float(u), "v": float(v), "k": float(k)}),
            ("branch_point", {"u": 1.0, "v": 0.0, "k": float(-f)}),
        )


# ---------------------------------------------------------------------------------------------
# Brusselator with diffusion, finite differences, Dirichlet ends
# ---------------------------------------------------------------------------------------------

#: The Brusselator's constants here: a Turing-unstable set (Dx < Dy), B below the Hopf
#: value 1 + A².
BRUSSELATOR = {"A": 2.0, "B": 4.6, "Dx": 0.0016, "Dy": 0.008}


def brusselator_names(n: int) -> list[str]:
    """The unknowns ``x1 … xn, y1 … yn`` (node i of the grid holds x_i and y_i)."""
    return [f"x{i + 1}" for i in range(n)] + [f"y{i + 1}" for i in range(n)]


def _laplacian(w, left, right):
    lap = -2.0 * w
    lap[1:] += w[:-1]
    lap[:-1] += w[1:]
    lap[0] += left
    lap[-1] += right
    return lap


def brusselator(n: int = 4, *, derivatives: str = "analytic") -> Example:
    """Steady states of the Brusselator with diffusion (Prigogine & Lefever 1968) on (0, 1)
    with Dirichlet ends, in the form of AUTO-07p's demos ``bru``/``brf`` (diffusion
    coefficients divided by L², x = A and y = B/A at both ends), on n interior nodes
    (h = 1/(n + 1))::

        Dx/(L² h²) Δx_i + A − (B + 1) x_i + x_i² y_i = 0
        Dy/(L² h²) Δy_i + B x_i − x_i² y_i           = 0

    Unknowns ``x1 … xn, y1 … yn``; parameters ``L`` (free, the length) and
    :data:`BRUSSELATOR` (A = 2, B = 4.6, Dx = 0.0016, Dy = 0.008: Turing-unstable, below the
    Hopf value B = 1 + A² = 5). Start: the uniform state x = A, y = B/A at L = 0.1; bounds
    L ∈ [0.1, 1].

    The uniform state solves the equations for every L. It has a branch point where the
    discrete mode sin(kπ i h) becomes neutral (:func:`brusselator_branch_points`): with
    λ_k = (4/h²) sin²(kπh/2) and m = λ_k/L², det [[B − 1 − Dx m, A²], [−B, −A² − Dy m]] = 0,
    i.e. Dx Dy m² + (Dx A² − (B − 1) Dy) m + A² = 0. For n = 4 the window holds seven,
    L = 0.1494, 0.2056, 0.2175, 0.2417, 0.4137, 0.5694, 0.6694 (modes 2, 3, 1, 4, 2, 3, 4):
    the pair at 0.2056 and 0.2175 lies within one step of a trace.
    """
    c = BRUSSELATOR

    def residual(u, p):
        x, y = u[:n], u[n:]
        s = 1.0 / (p["L"] ** 2 * (1.0 / (n + 1)) ** 2)
        A, B = p["A"], p["B"]
        rx = p["Dx"] * s * _laplacian(x, A, A) + A - (B + 1) * x + x**2 * y
        ry = p["Dy"] * s * _laplacian(y, B / A, B / A) + B * x - x**2 * y
        return np.concatenate([rx, ry])

    def jacobian(u, p):
        x, y = u[:n], u[n:]
        s = 1.0 / (p["L"] ** 2 * (1.0 / (n + 1)) ** 2)
        lap = np.diag(np.full(n - 1, 1.0), -1) + np.diag(np.full(n - 1, 1.0), 1) - 2 * np.eye(n)
        jxx = p["Dx"] * s * lap + np.diag(-(p["B"] + 1) + 2 * x * y)
        jyy = p["Dy"] * s * lap + np.diag(-(x**2))
        return np.block([[jxx, np.diag(x**2)], [np.diag(p["B"] - 2 * x * y), jyy]])

    def param_jacobian(u, p, name):
        x, y = u[:n], u[n:]
        A, B = p["A"], p["B"]
        s = 1.0 / (p["L"] ** 2 * (1.0 / (n + 1)) ** 2)
        ends = np.zeros(n)
        ends[0] = ends[-1] = 1.0
        if name == "L":
            lx, ly = _laplacian(x, A, A), _laplacian(y, B / A, B / A)
            return np.concatenate([lx * p["Dx"], ly * p["Dy"]]) * (-2 * s / p["L"])
        if name == "Dx":
            return np.concatenate([s * _laplacian(x, A, A), np.zeros(n)])
        if name == "Dy":
            return np.concatenate([np.zeros(n), s * _laplacian(y, B / A, B / A)])
        if name == "A":
            return np.concatenate([p["Dx"] * s * ends + 1, -p["Dy"] * s * B / A**2 * ends])
        if name == "B":
            return np.concatenate([-x, p["Dy"] * s * ends / A + x])
        raise KeyError(name)

    uniform = [c["A"]] * n + [c["B"] / c["A"]] * n

    def references():
        return tuple(
            Reference("branch_point", dict(zip(brusselator_names(n), uniform), L=L, **c), ("L",))
            for L, _ in brusselator_branch_points(n)
            if 0.1 < L < 1.0
        )

    return make_example(
        f"Brusselator with diffusion, N = {n}",
        residual,
        brusselator_names(n),
        {"L": 0.1, **c},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=uniform,
        free="L",
        bounds={"L": (0.1, 1.0)},
        references=references,
    )


@functools.lru_cache
def brusselator_branch_points(n: int = 4) -> tuple[tuple[float, int], ...]:
    """(L, k) of every branch point of the uniform state of :func:`brusselator` with n nodes,
    ascending in L: for each mode k = 1 … n, λ_k = (4/h²) sin²(kπh/2) (the eigenvalues of
    the Dirichlet second difference, eigenvectors sin(kπ i h)), the two roots m of
    Dx Dy m² + (Dx A² − (B − 1) Dy) m + A² = 0 (the 2 × 2 block of mode k singular), and
    L = √(λ_k/m). mpmath at 40 digits with the binary values of :data:`BRUSSELATOR`."""
    import mpmath as mp

    out = []
    with mp.workdps(DPS):
        A, B, Dx, Dy = (mp.mpf(BRUSSELATOR[k]) for k in ("A", "B", "Dx", "Dy"))
        h = mp.mpf(1) / (n + 1)
        qa, qb, qc = Dx * Dy, Dx * A**2 - (B - 1) * Dy, A**2
        disc = qb**2 - 4 * qa * qc
        for k in range(1, n + 1):
            lam = 4 / h**2 * mp.sin(k * mp.pi * h / 2) ** 2
            for sign in (-1, 1):
                m = (-qb + sign * mp.sqrt(disc)) / (2 * qa)
                out.append((float(mp.sqrt(lam / m)), k))
    return tuple(sorted(out))


# ---------------------------------------------------------------------------------------------
# Lorenz equilibria
# ---------------------------------------------------------------------------------------------


def lorenz(*, derivatives: str = "analytic") -> Example:
    """Equilibria of the Lorenz equations (AUTO-07p demo ``lrz``, its file ``lrz.f90``)::

        σ (y − x) = 0,   ρ x − y − x z = 0,   x y − β z = 0

    Unknowns ``x``, ``y``, ``z``, parameters ``rho`` (free), ``beta`` = 8/3, ``sigma`` = 10
    (the demo's). Start: the demo's origin at ρ = 0; bounds ρ ∈ [0, 30] (its UZSTOP).

    Special point (exact): the origin's Jacobian has det = σβ(ρ − 1), so a branch point at
    ρ = 1, a symmetric pitchfork: the branches x = y = ±√(β (ρ − 1)),
    z = ρ − 1 leave it. The Hopf points of those branches (ρ = σ(σ + β + 3)/(σ − β − 1))
    are not steady-state bifurcations.
    """

    def residual(u, p):
        x, y, z = u[0], u[1], u[2]
        return np.array([p["sigma"] * (y - x), p["rho"] * x - y - x * z, x * y - p["beta"] * z])

    def jacobian(u, p):
        x, y, z = u[0], u[1], u[2]
        s = p["sigma"]
        return np.array([[-s, s, 0.0], [p["rho"] - z, -1.0, -x], [y, x, -p["beta"]]])

    def param_jacobian(u, p, name):
        x, y, z = u[0], u[1], u[2]
        return {
            "rho": np.array([0.0, x, 0.0]),
            "beta": np.array([0.0, 0.0, -z]),
            "sigma": np.array([y - x, 0.0, 0.0]),
        }[name]

    fixed = {"beta": 8.0 / 3.0, "sigma": 10.0}
    return make_example(
        "Lorenz equilibria (AUTO-07p lrz)",
        residual,
        ["x", "y", "z"],
        {"rho": 0.0, **fixed},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[0.0, 0.0, 0.0],
        free="rho",
        bounds={"rho": (0.0, 30.0)},
        references=lambda: (
            Reference(
                "branch_point", {"x": 0.0, "y": 0.0, "z": 0.0, "rho": 1.0, **fixed}, ("rho",)
            ),
        ),
    )
