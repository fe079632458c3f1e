"""Chemistry: two published models with a cusp.

- :func:`co_oxidation`: CO oxidation on a catalyst, the Bykov–Yablonskii–Kim model in the form
  of Govaerts (2000) and of BifurcationKit.jl (``test/hopf_codim_2/COModel.jl``,
  ``docs/.../tutorialCO.md``): two folds in q2, a fold curve in (q2, k) with a cusp.
- :func:`ab_reactor`: the A → B reaction in a CSTR (Uppal, Ray & Poore, Chem. Eng. Sci. 29,
  1974), AUTO-07p demo ``ab``: two folds in p1, a fold curve in (p1, p3) with a cusp, all in
  closed form.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from ._base import DPS, Example, Reference, make_example

# ---------------------------------------------------------------------------------------------
# 1. CO oxidation (Bykov–Yablonskii–Kim)
# ---------------------------------------------------------------------------------------------

#: The fixed rate constants of the CO model (BifurcationKit's values).
CO_Q = dict(q1=2.5, q3=10.0, q4=0.0675, q5=1.0, q6=0.1)

# The cusp on the fold curve in (q2, k), from co_cusp_reference() in
# tests/continuation/test_cusp_models.py (sympy elimination to a quartic, mpmath, 40 digits)
# and, independently, from co_cusp() below (the same elimination by hand, mpmath, 40 digits):
CO_CUSP = dict(
    x="0.03594063654889180824117868429550515955046",
    y="0.3520054309466026862549047942252525956342",
    s="0.4513701117384072927127328666980025165018",
    q2="1.006408329678317622669347937186045037361",
    k="0.3559912732086765499450759422546292503564",
)
# folds in q2 at k = 0.4, from the same quartic (P = ∂P/∂x = 0, mpmath 40 digits)
CO_FOLDS_K04 = (
    "1.052200287869954692495685086585288461649",
    "1.042048505378526659254108548428345232525",
)


def co_oxidation(q2: float = 1.0, k: float = 0.4, *, derivatives: str = "analytic") -> Example:
    """CO oxidation on a catalyst (Bykov–Yablonskii–Kim), with z = 1 − x − y − s::

        2 q1 z² − 2 q5 x² − q3 x y = 0
        q2 z − q6 y − q3 x y       = 0
        q4 (z − k s)               = 0

    Unknowns ``x``, ``y``, ``s`` (coverages), parameters ``q2`` and ``k``; the other rate
    constants fixed at :data:`CO_Q`. Start: BifurcationKit's (x, y, s) = (0.001137, 0.891483,
    0.062345) at q2 = 1, k = 0.4 (a guess Newton corrects); free ``q2``, bounds
    q2 ∈ [0.5, 2.3] (BifurcationKit's range; it traces with ds_max = 0.01).

    Special points: at k = 0.4 two folds in q2, :data:`CO_FOLDS_K04` (:func:`co_folds`); the
    fold curve in (q2, k) has one cusp, :data:`CO_CUSP` (:func:`co_cusp`). BifurcationKit's
    published cusp k ≈ 0.35665351 is 1.9e-3 too high; its folds are right to 9 digits.
    """
    q1, q3, q4, q5, q6 = (CO_Q[n] for n in ("q1", "q3", "q4", "q5", "q6"))

    def residual(u, p):
        x, y, s = u
        z = 1 - x - y - s
        return np.array(
            [
                2 * q1 * z**2 - 2 * q5 * x**2 - q3 * x * y,
                p["q2"] * z - q6 * y - q3 * x * y,
                q4 * (z - p["k"] * s),
            ]
        )

    def jacobian(u, p):
        x, y, s = u
        z = 1 - x - y - s
        a = -4 * q1 * z
        return np.array(
            [
                [a - 4 * q5 * x - q3 * y, a - q3 * x, a],
                [-p["q2"] - q3 * y, -p["q2"] - q6 - q3 * x, -p["q2"]],
                [-q4, -q4, -q4 * (1 + p["k"])],
            ]
        )

    def param_jacobian(u, p, name):
        z = 1 - u[0] - u[1] - u[2]
        return np.array([0.0, z, 0.0]) if name == "q2" else np.array([0.0, 0.0, -q4 * u[2]])

    def references():
        out = [Reference("fold", dict(f, k=0.4), ("q2",)) for f in co_folds(0.4)]
        out.append(Reference("cusp", {n: float(v) for n, v in CO_CUSP.items()}, ("q2", "k")))
        return out

    return make_example(
        "CO oxidation (Bykov–Yablonskii–Kim)",
        residual,
        ["x", "y", "s"],
        {"q2": q2, "k": k},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[0.001137, 0.891483, 0.062345],
        free="q2",
        bounds={"q2": (0.5, 2.3)},
        references=references,
    )


def _poly_mul(a, b):
    out = [0] * (len(a) + len(b) - 1)
    for i, ai in enumerate(a):
        for j, bj in enumerate(b):
            out[i + j] += ai * bj
    return out


def _poly_add(*polys):
    out = [0] * max(len(p) for p in polys)
    for p in polys:
        for i, c in enumerate(p):
            out[i] += c
    return out


def _poly_eval(coeffs, x, derivative=0):
    """Value of the ``derivative``-th derivative of sum c_i x^i at x."""
    total = 0
    for i in range(len(coeffs) - 1, derivative - 1, -1):
        factor = math.prod(range(i - derivative + 1, i + 1))
        total = total * x + factor * coeffs[i]
    return total


def co_quartic(q2: Any, k: Any, q: Mapping[str, Any] = CO_Q) -> list[Any]:
    """Coefficients (ascending in x) of the CO model's quartic P(x; q2, k) with the rate
    constants ``q`` (default :data:`CO_Q`), in the numbers given (mpmath numbers give mpmath
    coefficients).

    F3 gives z = c(1 − x − y) with c = k/(1 + k) (so s = z/k); F2 is then linear in y,
    y = q2 c (1 − x)/D with D = q2 c + q6 + q3 x, and 1 − x − y = (1 − x)(q6 + q3 x)/D. F1
    times D² > 0 is P(x) = 2 q1 c² (1 − x)² (q6 + q3 x)² − 2 q5 x² D² − q3 q2 c x (1 − x) D.
    A fold in q2 is a double root of P, a cusp a triple root.
    """
    q1, q3, q5, q6 = (q[n] for n in ("q1", "q3", "q5", "q6"))
    c = k / (1 + k)
    one_minus_x = [1, -1]
    lin = [q6, q3]  # q6 + q3 x
    D = [q2 * c + q6, q3]
    A = _poly_mul(_poly_mul(one_minus_x, one_minus_x), _poly_mul(lin, lin))
    B = _poly_mul([0, 0, 1], _poly_mul(D, D))
    C = _poly_mul(_poly_mul([0, 1], one_minus_x), D)
    return _poly_add(
        [2 * q1 * c**2 * a for a in A], [-2 * q5 * b for b in B], [-q3 * q2 * c * t for t in C]
    )


def _co_state(x, q2, k, q):
    """(y, s) from x by the elimination of :func:`co_quartic`."""
    q3, q6 = q["q3"], q["q6"]
    c = k / (1 + k)
    y = q2 * c * (1 - x) / (q2 * c + q6 + q3 * x)
    return y, (1 - x - y) / (1 + k)


def co_cusp(dps: int = DPS) -> dict:
    """The cusp of the CO model on its fold curve in (q2, k): the triple root
    P = P_x = P_xx = 0 of :func:`co_quartic` in (x, q2, k), by mpmath ``findroot`` at ``dps``
    digits from (0.036, 1.0, 0.36); y and s from the elimination. The rate constants are the
    decimals of :data:`CO_Q` (not their binary roundings: 0.1 is exactly 1/10). Returns mpmath
    numbers (keys x, y, s, q2, k); they agree with :data:`CO_CUSP`."""
    import mpmath as mp

    with mp.workdps(dps):
        q = {n: mp.mpf(str(v)) for n, v in CO_Q.items()}

        def equations(x, q2, k):
            P = co_quartic(q2, k, q)
            return [_poly_eval(P, x, d) for d in range(3)]

        x, q2, k = mp.findroot(equations, (mp.mpf("0.036"), mp.mpf(1), mp.mpf("0.36")))
        y, s = _co_state(x, q2, k, q)
        return dict(x=x, y=y, s=s, q2=q2, k=k)


def co_folds(k: float = 0.4, dps: int = DPS) -> tuple[dict[str, float], ...]:
    """The two folds in q2 of the CO model at fixed k: double roots P = P_x = 0 of
    :func:`co_quartic` in (x, q2), by mpmath ``findroot`` at ``dps`` digits from x = 0.054,
    q2 = 1.052 and x = 0.025, q2 = 1.042 (the folds at k = 0.4); y and s from the
    elimination; the decimals of :data:`CO_Q` and ``k``. Floats, keys x, y, s, q2, in
    BifurcationKit's path order (at k = 0.4 the q2 agree with :data:`CO_FOLDS_K04`)."""
    import mpmath as mp

    out = []
    with mp.workdps(dps):
        q = {n: mp.mpf(str(v)) for n, v in CO_Q.items()}
        km = mp.mpf(str(k))
        for guess in (("0.054", "1.052"), ("0.025", "1.042")):

            def equations(x, q2):
                P = co_quartic(q2, km, q)
                return [_poly_eval(P, x, d) for d in range(2)]

            x, q2 = mp.findroot(equations, tuple(mp.mpf(g) for g in guess))
            y, s = _co_state(x, q2, km, q)
            out.append({"x": float(x), "y": float(y), "s": float(s), "q2": float(q2)})
    return tuple(out)


# ---------------------------------------------------------------------------------------------
# 2. A -> B reaction in a CSTR (Uppal–Ray–Poore 1974; AUTO-07p demo ab)
# ---------------------------------------------------------------------------------------------


def ab_reactor(
    p1: float = 0.0, p2: float = 14.0, p3: float = 2.0, *, derivatives: str = "analytic"
) -> Example:
    """The A → B reaction in a CSTR (AUTO-07p demo ``ab``), with r = p1 (1 − u1) e^{u2}::

        −u1 + r             = 0
        −u2 + p2 r − p3 u2  = 0

    Unknowns ``u1`` (conversion), ``u2`` (temperature), parameters ``p1`` (Damköhler number),
    ``p2`` and ``p3``. Start: the AUTO 97 tutorial's STPNT, u = 0 at p1 = 0, p2 = 14, p3 = 2;
    free ``p1``, bounds p1 ∈ [0, 0.15].

    Special points (closed form): at fixed p2, p3 two folds in p1 (:func:`ab_folds`); the fold
    curve in (p1, p3) has its cusp at u = (1/2, 2), p1 = e^{−2}, p3 = p2/4 − 1
    (:func:`ab_cusp`). The AUTO 97 tutorial ("third run: a 2-parameter locus of folds")
    reports it as PAR(1) = 1.353352E-01, U = (4.996530E-01, 1.998613E+00),
    PAR(3) = 2.499998E+00.
    """

    def residual(u, p):
        u1, u2 = u
        r = p["p1"] * (1 - u1) * np.exp(u2)
        return np.array([-u1 + r, -u2 + p["p2"] * r - p["p3"] * u2])

    def jacobian(u, p):
        u1, u2 = u
        a = p["p1"] * np.exp(u2)
        return np.array(
            [[-1 - a, a * (1 - u1)], [-p["p2"] * a, -1 + p["p2"] * a * (1 - u1) - p["p3"]]]
        )

    def param_jacobian(u, p, name):
        u1, u2 = u
        e = (1 - u1) * np.exp(u2)
        return {
            "p1": np.array([e, p["p2"] * e]),
            "p2": np.array([0.0, p["p1"] * e]),
            "p3": np.array([0.0, -u2]),
        }[name]

    def references():
        out = [Reference("fold", dict(f, p2=p2, p3=p3), ("p1",)) for f in ab_folds(p2, p3)]
        out.append(Reference("cusp", ab_cusp(p2), ("p1", "p3")))
        return out

    return make_example(
        "A → B reactor (AUTO-07p ab)",
        residual,
        ["u1", "u2"],
        {"p1": p1, "p2": p2, "p3": p3},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[0.0, 0.0],
        free="p1",
        bounds={"p1": (0.0, 0.15)},
        references=references,
    )


def ab_folds(p2: float = 14.0, p3: float = 2.0) -> tuple[dict[str, float], ...]:
    """Folds in p1 at fixed p2, p3 (closed form, mpmath 40 digits): F1 = 0 gives
    p1 = u1 e^{−u2}/(1 − u1), F2 − p2 F1 = 0 gives u1 = (1 + p3) u2/p2; with θ = u2 a fold is
    d(ln p1)/dθ = 0, i.e. (1 + p3) θ² = p2 (θ − 1), and there u1 = (θ − 1)/θ,
    p1 = (θ − 1) e^{−θ}. p2 = 14, p3 = 2: θ = (7 ∓ √7)/3. Keys u1, u2, p1; ascending θ
    (the path order from p1 = 0)."""
    import mpmath as mp

    with mp.workdps(DPS):
        a, b = 1 + mp.mpf(p3), mp.mpf(p2)
        disc = b**2 - 4 * a * b
        if disc < 0:
            return ()
        out = []
        for sign in (-1, 1):
            th = (b + sign * mp.sqrt(disc)) / (2 * a)
            out.append(
                {"u1": float((th - 1) / th), "u2": float(th), "p1": float((th - 1) * mp.exp(-th))}
            )
        return tuple(out)


def ab_cusp(p2: float = 14.0) -> dict[str, float]:
    """The cusp of the fold curve in (p1, p3) at fixed p2 (closed form: the folds of
    :func:`ab_folds` merge, d²(ln p1)/dθ² = 0 too): θ = u2 = 2, u1 = 1/2, p1 = e^{−2},
    p3 = p2/4 − 1 (p2 = 14: 5/2); mpmath, 40 digits. Keys u1, u2, p1, p2, p3."""
    import mpmath as mp

    with mp.workdps(DPS):
        return {
            "u1": 0.5,
            "u2": 2.0,
            "p1": float(mp.exp(-2)),
            "p2": float(p2),
            "p3": float(mp.mpf(p2) / 4 - 1),
        }
