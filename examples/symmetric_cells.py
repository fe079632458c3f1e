"""Symmetric branch points of two identical coupled cells, whose symmetric (homogeneous)
branch is not u = 0: it moves with the parameter, and the symmetry-breaking pitchfork is
where the antisymmetric mode (φ, −φ) of the cell exchange (1 ↔ 2) becomes neutral.

- :func:`brusselator_cells`: Turing's two-cell model with Brusselator kinetics (Prigogine &
  Lefever), the homogeneous state (A, B/A) in both cells, one symmetry-breaking pitchfork in
  B in closed form, and the other branch in closed form;
- :func:`cstr_pair`: two identical exothermic stirred tanks (the Uppal–Ray–Poore reactor in
  the scaling of AUTO-07p's ``ab``) exchanging heat through a common wall: the symmetric
  branch is the single tank's S-curve, with two folds and two symmetry-breaking pitchforks
  between them, all in closed form.

The :class:`~cusp.examples.symmetric.Pitchfork` records give the point, the mode and (for
the Brusselator) the other branch.
"""

from __future__ import annotations

import functools

import numpy as np

from ._base import DPS, Example, Reference, make_example
from .symmetric import Pitchfork

# ---------------------------------------------------------------------------------------------
# Two coupled Brusselator cells
# ---------------------------------------------------------------------------------------------

#: The constants of :func:`brusselator_cells` (B is free): the inhibitor y diffuses ten
#: times faster than the activator x, the condition of a Turing instability.
BRUSSELATOR_CELLS = {"A": 2.0, "Dx": 0.4, "Dy": 4.0}


def brusselator_cells(*, derivatives: str = "analytic") -> Example:
    """Steady states of two identical cells with Brusselator kinetics coupled by diffusion:
    the two-cell model of A. M. Turing ("The chemical basis of morphogenesis", Phil. Trans.
    R. Soc. B 237, 37–72, 1952) with the trimolecular model of I. Prigogine and R. Lefever
    ("Symmetry breaking instabilities in dissipative systems II", J. Chem. Phys. 48,
    1695–1700, 1968, whose two-box system this is)::

        A − (B + 1) x1 + x1² y1 + Dx (x2 − x1) = 0
        B x1 − x1² y1 + Dy (y2 − y1)           = 0
        (the same with 1 ↔ 2)

    Unknowns ``x1``, ``y1``, ``x2``, ``y2``; parameters ``B`` (free) and
    :data:`BRUSSELATOR_CELLS` (A = 2, Dx = 0.4, Dy = 4). Start: the homogeneous state
    x = A, y = B/A in both cells at B = 1; bounds B ∈ [1, 4] (below the Hopf point
    B = 1 + A² = 5 of the homogeneous state).

    With J0 = [[B − 1, A²], [−B, −A²]] the one cell's Jacobian at (A, B/A), the homogeneous
    state's Jacobian has the blocks J0 on (φ, φ) (det A² > 0) and J0 − 2 diag(Dx, Dy) on
    (φ, −φ): det = A² (1 + 2Dx) + 4 Dx Dy − 2Dy (B − 1) (sympy). One branch point,
    B_c = (1 + 2Dx)(1 + A²/(2Dy)) = 2.7, a pitchfork of the exchange symmetry, mode
    (A², −c, −A², c) with c = B_c − 1 − 2Dx.

    Other branch (exact; :func:`brusselator_cells_pitchforks`): the sum of all four
    equations gives x1 + x2 = 2A, the difference of the cells' sums
    (1 + 2Dx)(x1 − x2) = 2Dy (y2 − y1); with x1,2 = A ± ξ, η = y1 − y2 = −ξ (1 + 2Dx)/Dy
    the y-equations give y1 = (B x1 − Dy η)/x1², y2 = (B x2 + Dy η)/x2² and, from
    y1 − y2 = η, B(ξ) = (1 + 2Dx)(A² − ξ²)(1 + Dy (1/x1² + 1/x2²))/(2Dy), |ξ| < A.
    B(ξ) = B_c + (1 + 2Dx)(4Dy/A² − 1) ξ²/(2Dy) + O(ξ⁴): supercritical here.
    """

    def residual(u, p):
        x1, y1, x2, y2 = u[0], u[1], u[2], u[3]
        A, B, Dx, Dy = p["A"], p["B"], p["Dx"], p["Dy"]
        return np.array(
            [
                A - (B + 1) * x1 + x1**2 * y1 + Dx * (x2 - x1),
                B * x1 - x1**2 * y1 + Dy * (y2 - y1),
                A - (B + 1) * x2 + x2**2 * y2 + Dx * (x1 - x2),
                B * x2 - x2**2 * y2 + Dy * (y1 - y2),
            ]
        )

    def jacobian(u, p):
        x1, y1, x2, y2 = u[0], u[1], u[2], u[3]
        B, Dx, Dy = p["B"], p["Dx"], p["Dy"]
        return np.array(
            [
                [-(B + 1) + 2 * x1 * y1 - Dx, x1**2, Dx, 0.0],
                [B - 2 * x1 * y1, -(x1**2) - Dy, 0.0, Dy],
                [Dx, 0.0, -(B + 1) + 2 * x2 * y2 - Dx, x2**2],
                [0.0, Dy, B - 2 * x2 * y2, -(x2**2) - Dy],
            ]
        )

    def param_jacobian(u, p, name):
        x1, y1, x2, y2 = u[0], u[1], u[2], u[3]
        return {
            "B": np.array([-x1, x1, -x2, x2]),
            "A": np.array([1.0, 0.0, 1.0, 0.0]),
            "Dx": np.array([x2 - x1, 0.0, x1 - x2, 0.0]),
            "Dy": np.array([0.0, y2 - y1, 0.0, y1 - y2]),
        }[name]

    c = BRUSSELATOR_CELLS
    B0 = 1.0
    return make_example(
        "two coupled Brusselator cells",
        residual,
        ["x1", "y1", "x2", "y2"],
        {"B": B0, **c},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[c["A"], B0 / c["A"], c["A"], B0 / c["A"]],
        free="B",
        bounds={"B": (1.0, 4.0)},
        references=lambda: tuple(pf.reference("B") for pf in brusselator_cells_pitchforks()),
    )


@functools.lru_cache
def brusselator_cells_pitchforks() -> tuple[Pitchfork, ...]:
    """The branch point of :func:`brusselator_cells`' homogeneous state:
    B_c = (1 + 2Dx)(1 + A²/(2Dy)) (mpmath at 40 digits from the binary constants), state
    (A, B_c/A, A, B_c/A), mode (A², −c, −A², c), c = B_c − 1 − 2Dx; other branch the
    ξ-parametrisation of :func:`brusselator_cells` (amplitude a = ξ = (x1 − x2)/2)."""
    import mpmath as mp

    k = BRUSSELATOR_CELLS
    with mp.workdps(DPS):
        A, Dx, Dy = (mp.mpf(k[n]) for n in ("A", "Dx", "Dy"))
        Bc = (1 + 2 * Dx) * (1 + A**2 / (2 * Dy))
        c = Bc - 1 - 2 * Dx
        values = {"x1": k["A"], "y1": float(Bc / A), "x2": k["A"], "y2": float(Bc / A)}
        values.update(B=float(Bc), **k)
        mode = (float(A**2), float(-c), float(-(A**2)), float(c))
    return (Pitchfork(values, mode, _brusselator_cells_other, brusselator_cells_point),)


def brusselator_cells_point(xi: float) -> dict[str, float]:
    """The point of :func:`brusselator_cells`' asymmetric branch with x1,2 = A ± ξ (float;
    ξ = 0 is the branch point)."""
    k = BRUSSELATOR_CELLS
    A, Dx, Dy = k["A"], k["Dx"], k["Dy"]
    x1, x2 = A + xi, A - xi
    eta = -xi * (1 + 2 * Dx) / Dy
    B = (1 + 2 * Dx) * (A**2 - xi**2) * (1 + Dy * (1 / x1**2 + 1 / x2**2)) / (2 * Dy)
    y1, y2 = (B * x1 - Dy * eta) / x1**2, (B * x2 + Dy * eta) / x2**2
    return {"x1": x1, "y1": y1, "x2": x2, "y2": y2, "B": B, **k}


def _brusselator_cells_other(v):
    """Residuals of the asymmetric branch's closed form at ``v`` (floats or columns)."""
    k = BRUSSELATOR_CELLS
    A, Dx, Dy = k["A"], k["Dx"], k["Dy"]
    x1, x2 = v["x1"], v["x2"]
    xi = (x1 - x2) / 2
    eta = -xi * (1 + 2 * Dx) / Dy
    B = (1 + 2 * Dx) * (A**2 - xi**2) * (1 + Dy * (1 / x1**2 + 1 / x2**2)) / (2 * Dy)
    return [
        x1 + x2 - 2 * A,
        v["y1"] - v["y2"] - eta,
        v["B"] - B,
        v["y1"] - (B * x1 - Dy * eta) / x1**2,
    ]


# ---------------------------------------------------------------------------------------------
# Two exothermic stirred tanks exchanging heat
# ---------------------------------------------------------------------------------------------

#: The constants of :func:`cstr_pair` (Da is free): AUTO-07p ``ab``'s heat of reaction
#: B = 14 and heat-transfer coefficient β = 2, and the wall's coupling κ = 0.1.
CSTR_PAIR = {"B": 14.0, "beta": 2.0, "kappa": 0.1}


def cstr_pair(*, derivatives: str = "analytic") -> Example:
    """Steady states of two identical stirred tanks, each with the first-order exothermic
    reaction of A. Uppal, W. H. Ray and A. B. Poore ("On the dynamic behavior of continuous
    stirred tank reactors", Chem. Eng. Sci. 29, 967–985, 1974) in the large-activation-energy
    scaling of AUTO-07p's demo ``ab``, exchanging heat through a common wall (coefficient
    κ; thermally coupled identical reactors as in the coupled-CSTR literature, e.g. Mankin &
    Hudson, Chem. Eng. Sci. 41, 1986)::

        −x1 + Da (1 − x1) e^{θ1}                         = 0
        −θ1 + B Da (1 − x1) e^{θ1} − β θ1 + κ (θ2 − θ1) = 0
        (the same with 1 ↔ 2)

    Unknowns ``x1``, ``theta1``, ``x2``, ``theta2`` (conversion and temperature of each
    tank); parameters ``Da`` (free, the Damköhler number) and :data:`CSTR_PAIR` (B = 14,
    β = 2, κ = 0.1). Start: both tanks cold, x = θ = 0 at Da = 0; bounds Da ∈ [0, 0.2].

    The symmetric branch is the single tank's S-curve: θ = k x, k = B/(1 + β),
    Da = x e^{−kx}/(1 − x). There Da e^{θ} = x/(1 − x) and the Jacobian has the blocks
    J0 = [[−1/(1 − x), x], [−B x/(1 − x), −(1 + β) + B x]] on (φ, φ) and
    J0 − diag(0, 2κ) on (φ, −φ), with det = (B x² − B x + 1 + β (+ 2κ))/(1 − x) (sympy):
    folds where x (1 − x) = (1 + β)/B = 1/k, symmetry-breaking branch points where
    x (1 − x) = (1 + β + 2κ)/B. In path order (x ascending): fold x = 0.3110, branch point
    x = 0.3536, branch point x = 0.6464, fold x = 0.6890 (:func:`cstr_pair_references`);
    the branch points are on the middle (unstable) arm of the S, a fold and a branch point
    0.0008 apart in Da. Mode at a branch point: (x, 1/(1 − x), −x, −1/(1 − x)).

    The asymmetric branch has no closed form: with (θ1, θ2) given, x1 and x2 follow
    linearly from the energy balances, B x1 = (1 + β + κ) θ1 − κ θ2 (and 1 ↔ 2), and the
    branch is the curve ln(x1/(1 − x1)) − θ1 = ln(x2/(1 − x2)) − θ2, θ1 ≠ θ2 (Da is
    either side's exponential), a transcendental equation.
    """

    def residual(u, p):
        x1, t1, x2, t2 = u[0], u[1], u[2], u[3]
        Da, B, beta, kappa = p["Da"], p["B"], p["beta"], p["kappa"]
        r1, r2 = Da * (1 - x1) * np.exp(t1), Da * (1 - x2) * np.exp(t2)
        return np.array(
            [
                -x1 + r1,
                -t1 + B * r1 - beta * t1 + kappa * (t2 - t1),
                -x2 + r2,
                -t2 + B * r2 - beta * t2 + kappa * (t1 - t2),
            ]
        )

    def jacobian(u, p):
        x1, t1, x2, t2 = u[0], u[1], u[2], u[3]
        Da, B, beta, kappa = p["Da"], p["B"], p["beta"], p["kappa"]
        e1, e2 = Da * np.exp(t1), Da * np.exp(t2)
        d = -1 - beta - kappa
        return np.array(
            [
                [-1 - e1, e1 * (1 - x1), 0.0, 0.0],
                [-B * e1, d + B * e1 * (1 - x1), 0.0, kappa],
                [0.0, 0.0, -1 - e2, e2 * (1 - x2)],
                [0.0, kappa, -B * e2, d + B * e2 * (1 - x2)],
            ]
        )

    def param_jacobian(u, p, name):
        x1, t1, x2, t2 = u[0], u[1], u[2], u[3]
        Da, B = p["Da"], p["B"]
        q1, q2 = (1 - x1) * np.exp(t1), (1 - x2) * np.exp(t2)
        return {
            "Da": np.array([q1, B * q1, q2, B * q2]),
            "B": np.array([0.0, Da * q1, 0.0, Da * q2]),
            "beta": np.array([0.0, -t1, 0.0, -t2]),
            "kappa": np.array([0.0, t2 - t1, 0.0, t1 - t2]),
        }[name]

    return make_example(
        "two exothermic CSTRs exchanging heat",
        residual,
        ["x1", "theta1", "x2", "theta2"],
        {"Da": 0.0, **CSTR_PAIR},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=np.zeros(4),
        free="Da",
        bounds={"Da": (0.0, 0.2)},
        references=lambda: cstr_pair_references()[0],
    )


@functools.lru_cache
def cstr_pair_references() -> tuple[tuple[Reference, ...], tuple[Pitchfork, ...]]:
    """The folds and branch points of :func:`cstr_pair`'s symmetric branch in path order
    (x ascending), and its branch points as :class:`Pitchfork` s (mode
    (x, 1/(1 − x), −x, −1/(1 − x)), no closed-form other branch): the roots
    x = (1 ± √(1 − 4q/B))/2 of B x² − B x + q = 0, q = 1 + β for the folds and 1 + β + 2κ
    for the branch points; θ = k x, k = B/(1 + β), Da = x e^{−kx}/(1 − x). mpmath at 40
    digits from the binary constants."""
    import mpmath as mp

    c = CSTR_PAIR
    points = []
    with mp.workdps(DPS):
        B, beta, kappa = (mp.mpf(c[n]) for n in ("B", "beta", "kappa"))
        k = B / (1 + beta)
        for kind, q in (("fold", 1 + beta), ("branch_point", 1 + beta + 2 * kappa)):
            for sign in (-1, 1):
                x = (1 + sign * mp.sqrt(1 - 4 * q / B)) / 2
                Da = x * mp.exp(-k * x) / (1 - x)
                state = {"x1": x, "theta1": k * x, "x2": x, "theta2": k * x}
                values = {n: float(v) for n, v in state.items()}
                values.update(Da=float(Da), **c)
                mode = (float(x), float(1 / (1 - x)), float(-x), float(-1 / (1 - x)))
                points.append((float(x), kind, values, mode))
    points.sort(key=lambda t: t[0])
    refs = tuple(Reference(kind, values, ("Da",)) for _, kind, values, _ in points)
    forks = tuple(Pitchfork(v, mode) for _, kind, v, mode in points if kind == "branch_point")
    return refs, forks
