"""Mechanics: the elastica and a rigid-bar model of imperfection sensitivity.

- :func:`elastica`: Euler's elastica, a cantilever under an axial end load, by finite
  differences: pitchfork branch points at the discrete buckling loads (closed form);
- :func:`rigid_bar`: a rigid bar held upright by a spring that stays horizontal (the
  unstable-symmetric model of Thompson & Hunt): a subcritical pitchfork when perfect, a limit
  point obeying Koiter's two-thirds power law when imperfect (closed form).

The von Mises trusses are in :mod:`~cusp.examples.trusses`, the shallow arch in
:mod:`~cusp.examples.structures`.
"""

from __future__ import annotations

import numpy as np

from ._base import DPS, Example, Reference, make_example

# ---------------------------------------------------------------------------------------------
# Elastica: cantilever under an axial end load, finite differences
# ---------------------------------------------------------------------------------------------


def elastica_names(n: int) -> list[str]:
    """The unknowns ``theta1 … theta{n}``: the rotation at s = i/n, i = 1 … n."""
    return [f"theta{i + 1}" for i in range(n)]


def elastica(n: int = 10, *, derivatives: str = "analytic") -> Example:
    """Euler's elastica: a cantilever of unit length, clamped at s = 0 and loaded at its free
    end s = 1 by an axial compressive force P (in units EI/ℓ²), ``θ″ + P sin θ = 0``,
    ``θ(0) = 0``, ``θ′(1) = 0`` (Euler 1744; Timoshenko & Gere, Theory of Elastic
    Stability). Central differences on the nodes s_i = i/n, i = 1 … n (h = 1/n), the
    free end by a mirror node θ_{n+1} = θ_{n−1}::

        (θ_{i−1} − 2θ_i + θ_{i+1})/h² + P sin θ_i = 0,   θ_0 = 0

    Unknowns ``theta1 … theta{n}``, parameter ``P`` (free). Start: the straight rod θ = 0 at
    P = 0; bounds P ∈ [0, 30].

    Special points (:func:`elastica_buckling_loads`): the straight rod θ = 0 has a pitchfork
    branch point (the rod buckles to either side) at each eigenvalue of the difference
    operator, P_k = 4n² sin²((2k − 1)π/(4n)) (eigenvector sin((2k − 1)π s_i/2); the continuum
    values are ((2k − 1)π/2)²). For n = 10 the window holds P_1 = 2.4623 and P_2 = 21.799
    (continuum 2.4674 and 22.207).
    """
    h2 = (1.0 / n) ** 2

    def second_difference(t):
        d = -2.0 * t
        d[1:] += t[:-1]
        d[:-1] += t[1:]
        d[-1] += t[-2]  # mirror node at the free end
        return d / h2

    def residual(u, p):
        return second_difference(u) + p["P"] * np.sin(u)

    def jacobian(u, p):
        m = np.diag(np.full(n - 1, 1.0), -1) + np.diag(np.full(n - 1, 1.0), 1) - 2 * np.eye(n)
        m[-1, -2] = 2.0
        return m / h2 + np.diag(p["P"] * np.cos(u))

    def param_jacobian(u, p, name):
        if name != "P":
            raise KeyError(name)
        return np.sin(u)

    def references():
        zero = dict.fromkeys(elastica_names(n), 0.0)
        return tuple(
            Reference("branch_point", {**zero, "P": P}, ("P",))
            for P in elastica_buckling_loads(n)
            if P < 30.0
        )

    return make_example(
        f"elastica (cantilever), N = {n}",
        residual,
        elastica_names(n),
        {"P": 0.0},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=np.zeros(n),
        free="P",
        bounds={"P": (0.0, 30.0)},
        references=references,
    )


def elastica_buckling_loads(n: int = 10) -> tuple[float, ...]:
    """The buckling loads of :func:`elastica` with n nodes, ascending: the eigenvalues
    P_k = 4n² sin²((2k − 1)π/(4n)), k = 1 … n, of minus the difference operator (with the
    mirror node; its eigenvectors sin((2k − 1)π i/(2n)) satisfy θ_{n+1} = θ_{n−1}), in
    mpmath at 40 digits."""
    import mpmath as mp

    with mp.workdps(DPS):
        return tuple(
            float(4 * n**2 * mp.sin((2 * k - 1) * mp.pi / (4 * n)) ** 2) for k in range(1, n + 1)
        )


# ---------------------------------------------------------------------------------------------
# Rigid bar with a horizontal spring: unstable-symmetric bifurcation
# ---------------------------------------------------------------------------------------------


def rigid_bar(theta0: float = 0.0, *, derivatives: str = "analytic") -> Example:
    """A rigid bar of length l, pinned at its foot, held upright at its top by a linear
    spring of stiffness k that stays horizontal, under a vertical load P; initial tilt θ0
    (the unstable-symmetric model of Thompson & Hunt, A General Theory of Elastic Stability,
    1973). With k = l = 1 the
    equilibrium (∂Π/∂θ of Π = ½ k l² (sin θ − sin θ0)² − P l (cos θ0 − cos θ)) is::

        (sin θ − sin θ0) cos θ − P sin θ = 0

    Unknown ``theta``, parameters ``P`` (free) and ``theta0``. Start: θ = θ0 at P = 0; bounds
    θ ∈ [−1, 1.4], P ∈ [−1, 1.5].

    Perfect (θ0 = 0): the upright bar θ = 0 has a subcritical pitchfork at P = k l = 1; the
    branches P = cos θ leave it downwards. Imperfect (sin θ0 = ε > 0): one branch,
    P = cos θ (1 − ε/sin θ), with a limit point where sin³θ = ε, at
    P_max = (1 − ε^{2/3})^{3/2} (Koiter's two-thirds power law, exact for this model;
    :func:`rigid_bar_limit`).
    """

    def residual(u, p):
        t = u[0]
        return np.array([(np.sin(t) - np.sin(p["theta0"])) * np.cos(t) - p["P"] * np.sin(t)])

    def jacobian(u, p):
        t = u[0]
        s0 = np.sin(p["theta0"])
        return np.array([[np.cos(2 * t) + s0 * np.sin(t) - p["P"] * np.cos(t)]])

    def param_jacobian(u, p, name):
        t = u[0]
        if name == "P":
            return np.array([-np.sin(t)])
        if name == "theta0":
            return np.array([-np.cos(p["theta0"]) * np.cos(t)])
        raise KeyError(name)

    def references():
        if theta0 == 0.0:
            return (Reference("branch_point", {"theta": 0.0, "P": 1.0, "theta0": 0.0}, ("P",)),)
        t, P = rigid_bar_limit(theta0)
        return (Reference("fold", {"theta": t, "P": P, "theta0": theta0}, ("P",)),)

    return make_example(
        "rigid bar, horizontal spring" + (" (imperfect)" if theta0 else ""),
        residual,
        ["theta"],
        {"P": 0.0, "theta0": theta0},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[theta0],
        free="P",
        bounds={"theta": (-1.0, 1.4), "P": (-1.0, 1.5)},
        references=references,
    )


def rigid_bar_limit(theta0: float) -> tuple[float, float]:
    """(θ, P) at the limit point of the imperfect :func:`rigid_bar` (sin θ0 = ε > 0): from
    P(θ) = cos θ (1 − ε/sin θ), dP/dθ = ε/sin²θ − sin θ = 0 gives sin θ = ε^{1/3} and
    P = (1 − ε^{2/3})^{3/2}; mpmath at 40 digits."""
    import mpmath as mp

    with mp.workdps(DPS):
        eps = mp.sin(mp.mpf(theta0))
        s = mp.cbrt(eps)
        return float(mp.asin(s)), float((1 - s**2) ** mp.mpf(1.5))
