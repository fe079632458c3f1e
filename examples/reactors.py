"""Reactors: a two-compartment enzyme model and a stirred tank with Arrhenius kinetics.

- :func:`enz`: the two-compartment enzyme model of AUTO-07p demo ``enz`` (Kernévez): the
  symmetric branch has two folds and two symmetry-breaking branch points (roots of two
  quartics);
- :func:`cstr`: the first-order exothermic reaction in a CSTR with the full Arrhenius factor
  (Uppal, Ray & Poore 1974); AUTO's ``ab``
  (:func:`~cusp.examples.chemistry.ab_reactor`) is its limit γ → ∞. Its folds are the roots
  of a quadratic.
"""

from __future__ import annotations

import functools

import numpy as np

from ._base import DPS, Example, Reference, make_example

# ---------------------------------------------------------------------------------------------
# enz: two-compartment enzyme model
# ---------------------------------------------------------------------------------------------


def _enz_rate(s, kappa):
    """R(s) = s/(1 + s + κ s²) and R′(s) = (1 − κ s²)/(1 + s + κ s²)²."""
    d = 1 + s + kappa * s**2
    return s / d, (1 - kappa * s**2) / d**2


def enz(rho: float = 100.0, kappa: float = 1.0, *, derivatives: str = "analytic") -> Example:
    """AUTO-07p demo ``enz``: a two-compartment enzyme model (Kernévez et al.; AUTO's manual,
    section "enz: Stationary Solutions of an Enzyme Model"), with R(s) = s/(1 + s + κ s²)::

        (s0 − s1) + (s2 − s1) − ρ R(s1)      = 0
        (s0 + μ − s2) + (s1 − s2) − ρ R(s2) = 0

    Unknowns ``s1``, ``s2``; parameters ``s0`` (free), ``mu`` (0: the demo's start), ``rho``
    and ``kappa`` (the demo's ρ = 100, κ = 1). Start: the demo's s = 0 at s0 = 0; bounds
    s0 ∈ [0, 40].

    With μ = 0 the branch is symmetric, s1 = s2 = s, s0 = s + ρ R(s). Its
    Jacobian has the eigenvalue −1 − ρR′(s) on (1, 1) and −3 − ρR′(s) on (1, −1): folds where
    ρR′ = −1, symmetry-breaking branch points where ρR′ = −3 (:func:`enz_symmetric_points`).
    With ρ = 100, κ = 1, in path order: fold s = 1.0484, branch point s = 1.1742, branch
    point s = 4.3945, fold s = 8.8222. The asymmetric branch through the branch points is
    3 (s1 − s2) + ρ (R(s1) − R(s2)) = 0, s1 ≠ s2 (the difference of the two equations), with
    s0 = 2 s1 − s2 + ρ R(s1).
    """

    def residual(u, p):
        s1, s2 = u[0], u[1]
        r1, _ = _enz_rate(s1, p["kappa"])
        r2, _ = _enz_rate(s2, p["kappa"])
        s0 = p["s0"]
        return np.array(
            [(s0 - s1) + (s2 - s1) - p["rho"] * r1, (s0 + p["mu"] - s2) + (s1 - s2) - p["rho"] * r2]
        )

    def jacobian(u, p):
        _, d1 = _enz_rate(u[0], p["kappa"])
        _, d2 = _enz_rate(u[1], p["kappa"])
        return np.array([[-2 - p["rho"] * d1, 1.0], [1.0, -2 - p["rho"] * d2]])

    def param_jacobian(u, p, name):
        if name == "s0":
            return np.array([1.0, 1.0])
        if name == "mu":
            return np.array([0.0, 1.0])
        r1, _ = _enz_rate(u[0], p["kappa"])
        r2, _ = _enz_rate(u[1], p["kappa"])
        if name == "rho":
            return np.array([-r1, -r2])
        if name == "kappa":  # dR/dκ = −s³/(1 + s + κ s²)²
            return np.array([p["rho"] * r1**2 * u[0], p["rho"] * r2**2 * u[1]])
        raise KeyError(name)

    fixed = {"mu": 0.0, "rho": rho, "kappa": kappa}

    def references():
        return tuple(
            Reference(kind, {"s1": s, "s2": s, "s0": s0, **fixed}, ("s0",))
            for kind, s, s0 in enz_symmetric_points(rho, kappa)
        )

    return make_example(
        "two-compartment enzyme model (AUTO-07p enz)",
        residual,
        ["s1", "s2"],
        {"s0": 0.0, **fixed},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[0.0, 0.0],
        free="s0",
        bounds={"s0": (0.0, 40.0)},
        references=references,
    )


@functools.lru_cache
def enz_symmetric_points(
    rho: float = 100.0, kappa: float = 1.0
) -> tuple[tuple[str, float, float], ...]:
    """Folds (ρR′(s) = −1) and branch points (ρR′(s) = −3) of the symmetric branch of
    :func:`enz` with μ = 0, as (kind, s, s0) in path order (ascending s > 0).

    ρR′(s) = −c is the quartic c (1 + s + κ s²)² + ρ (1 − κ s²) = 0, i.e.
    c κ² s⁴ + 2cκ s³ + (c (1 + 2κ) − ρκ) s² + 2c s + c + ρ = 0; its positive real roots by
    mpmath ``polyroots`` at 40 digits, s0 = s + ρ R(s).
    """
    import mpmath as mp

    out = []
    with mp.workdps(DPS):
        r, k = mp.mpf(rho), mp.mpf(kappa)
        for kind, c in (("fold", 1), ("branch_point", 3)):
            coeffs = [c * k**2, 2 * c * k, c * (1 + 2 * k) - r * k, 2 * c, c + r]
            for root in mp.polyroots(coeffs, maxsteps=200, extraprec=100):
                if abs(mp.im(root)) < mp.mpf(10) ** -30 and mp.re(root) > 0:
                    s = mp.re(root)
                    out.append((kind, s, s + r * s / (1 + s + k * s**2)))
        return tuple((kind, float(s), float(s0)) for kind, s, s0 in sorted(out, key=lambda t: t[1]))


# ---------------------------------------------------------------------------------------------
# CSTR with the full Arrhenius factor
# ---------------------------------------------------------------------------------------------


def cstr(
    B: float = 16.0, beta: float = 2.0, gamma: float = 20.0, *, derivatives: str = "analytic"
) -> Example:
    """A first-order exothermic reaction in a continuous stirred tank (Uppal, Ray & Poore,
    Chem. Eng. Sci. 29, 1974), with the Arrhenius factor a(x2) = exp(x2/(1 + x2/γ))::

        −x1 + Da (1 − x1) a(x2)            = 0
        −x2 + B Da (1 − x1) a(x2) − β x2   = 0

    Unknowns ``x1`` (conversion), ``x2`` (temperature); parameters ``Da`` (free, the Damköhler
    number), ``B``, ``beta``, ``gamma`` (B = 16, β = 2, γ = 20 here: an S-shaped branch).
    AUTO's demo ``ab`` is the limit γ → ∞. Start x = 0 at Da = 0; bounds Da ∈ [0, 0.2].

    Special points (:func:`cstr_folds`): x2 = k x1 with k = B/(1 + β), and
    Da = x1/(1 − x1) · exp(−x2/(1 + x2/γ)); d ln Da/dx1 = 0 is the quadratic
    (a² + k) x1² + (2a − k) x1 + 1 = 0 with a = k/γ: two folds, Da = 0.09770526276403087 at
    x1 = 0.3337466458470499 and Da = 0.09465618881889497 at x1 = 0.5544112488897923.
    """

    def arrhenius(x2, g):
        d = 1 + x2 / g
        e = np.exp(x2 / d)
        return e, e / d**2  # a and da/dx2

    def residual(u, p):
        x1, x2 = u[0], u[1]
        e, _ = arrhenius(x2, p["gamma"])
        r = p["Da"] * (1 - x1) * e
        return np.array([-x1 + r, -x2 + p["B"] * r - p["beta"] * x2])

    def jacobian(u, p):
        x1, x2 = u[0], u[1]
        e, de = arrhenius(x2, p["gamma"])
        r1, r2 = -p["Da"] * e, p["Da"] * (1 - x1) * de
        return np.array([[-1 + r1, r2], [p["B"] * r1, -1 + p["B"] * r2 - p["beta"]]])

    def param_jacobian(u, p, name):
        x1, x2 = u[0], u[1]
        g = p["gamma"]
        e, _ = arrhenius(x2, g)
        r = p["Da"] * (1 - x1) * e
        if name == "Da":
            return np.array([(1 - x1) * e, p["B"] * (1 - x1) * e])
        if name == "B":
            return np.array([0.0, r])
        if name == "beta":
            return np.array([0.0, -x2])
        if name == "gamma":  # d/dγ of x2/(1 + x2/γ) = (x2/(γ + x2))²
            dr = r * (x2 / (g + x2)) ** 2
            return np.array([dr, p["B"] * dr])
        raise KeyError(name)

    fixed = {"B": B, "beta": beta, "gamma": gamma}

    def references():
        return tuple(Reference("fold", {**f, **fixed}, ("Da",)) for f in cstr_folds(B, beta, gamma))

    return make_example(
        "CSTR, Arrhenius kinetics (Uppal-Ray-Poore)",
        residual,
        ["x1", "x2"],
        {"Da": 0.0, **fixed},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[0.0, 0.0],
        free="Da",
        bounds={"Da": (0.0, 0.2)},
        references=references,
    )


@functools.lru_cache
def cstr_folds(
    B: float = 16.0, beta: float = 2.0, gamma: float = 20.0
) -> tuple[dict[str, float], ...]:
    """Folds in Da of :func:`cstr`, in path order (ascending x1): the roots of
    (a² + k) x² + (2a − k) x + 1 = 0 (k = B/(1 + β), a = k/γ) in closed form, mpmath at 40
    digits; x2 = k x1, Da = x1/(1 − x1) exp(−x2/(1 + x2/γ)). Keys x1, x2, Da.

    Derivation: ln Da = ln x1 − ln(1 − x1) − k x1/(1 + a x1), whose x1-derivative
    1/(x1 (1 − x1)) − k/(1 + a x1)² vanishes where (1 + a x1)² = k x1 (1 − x1).
    """
    import mpmath as mp

    with mp.workdps(DPS):
        k = mp.mpf(B) / (1 + mp.mpf(beta))
        a = k / mp.mpf(gamma)
        qa, qb, qc = a**2 + k, 2 * a - k, mp.mpf(1)
        disc = qb**2 - 4 * qa * qc
        if disc <= 0:
            return ()
        out = []
        for sign in (-1, 1):
            x1 = (-qb + sign * mp.sqrt(disc)) / (2 * qa)
            x2 = k * x1
            da = x1 / (1 - x1) * mp.exp(-x2 / (1 + x2 / mp.mpf(gamma)))
            out.append({"x1": float(x1), "x2": float(x2), "Da": float(da)})
        return tuple(out)
