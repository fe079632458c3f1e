"""The sphere's released energies (Sec. 4 on Hertz–Mindlin spheres) in closed form, written in
the small differences between the levels of the points A, B, C, D so that they do not cancel.

The sphere's levels (:class:`cusp.models.sphere.SphereLevels`) are p = 1 − a/a0 and
q = 1 − c/a0; with x = 1 − p = a/a0 and y = 1 − q = c/a0 the force and the slip of every leg
are polynomials (Hertz F_N ∝ a³, Eq 19, Eq 2 with Hertz):

* T = (F_N/F_N0) F̂_T = x³ − y³ (F_T over μF_N0),   G = s/κ = x² − y² (g_T over μκ).

Along AB the stick level is frozen (y = y_A) and x falls from x_A to x_B; along BC the contact
level is frozen (x = x_B) and y falls from y_A through y_D (G = G_A) to y_C (T = T_A). The
areas ABD = ∫_{G_B}^{G_A} (T_AB − T_BC) dG and ABC − ABD = ∫_{G_A}^{G_C} (T_A − T_BC) dG are
line integrals of polynomials, but each leg's ∫ T dG is larger than the area by 1/f (f = g_A
over the gross-sliding slip: the legs' slopes dT/dG, 3x/2 on AB and 3y/2 on BC, differ by
3(x − y)/2 ~ f). Subtracting from T the line τ(G) = T_B + (3/2) y_A (G − G_B) through B, whose
slope lies between the two legs' (y ≤ y_A < x_B ≤ x), changes no loop integral (∮ τ(G) dG = 0)
and leaves on each leg a sign-definite integrand:

* AB, x = x_B + d, d from 0 to δ = p_B − p_A, with w = q_A − p_B = x_B − y_A:
  T − τ = d²(x_B + d + x_B/2) + (3/2) w d (2x_B + d) ≥ 0;
* BD, y = y_A − e, e from 0 to e_D = q_D − q_A:  τ − T = e²(y_A + 2y)/2 ≥ 0;
* DC, y = y_C + h, h from 0 to h_D = q_C − q_D:  T_C − T = y³ − y_C³ ≥ 0 (T_C = T_A).

Integrated and expanded (sympy, :func:`sphere_released_areas`), each is a polynomial with
positive coefficients in positive variables — (x_B, w, δ), (y_D, e_D) and (y_C, h_D), with
x_B = 1 − p_B, y_D = 1 − q_D, y_C = 1 − q_C — so it is evaluated to a few roundings, and an
error of each variable propagates through its (positive) derivative. ABD = κ(AB + BD) and
ABC − ABD = κ DC, in µm per unit of μF_N0 (the units of ``SphereLevels.slip``).
"""

from __future__ import annotations

import functools
from fractions import Fraction

import sympy as sp

#: the levels of the points (A's contact level p_A is 0 on the path; kept general)
p_A, q_A, p_B, q_D, q_C = sp.symbols("p_A q_A p_B q_D q_C", real=True)
#: the variables of the closed forms: the bases and the differences, all positive
x_B, y_D, y_C = sp.symbols("x_B y_D y_C", positive=True)
delta, w, e_D, h_D = sp.symbols("delta w e_D h_D", positive=True)
_d, _e, _h, _x, _y = sp.symbols("d e h x y", positive=True)

#: each closed form's variables, in the order of the monomial tables
VARIABLES: dict[str, tuple[sp.Symbol, ...]] = {
    "AB": (x_B, w, delta),
    "BD": (y_D, e_D),
    "DC": (y_C, h_D),
}
#: the variables as the levels' differences
IN_LEVELS: dict[sp.Symbol, sp.Expr] = {
    x_B: 1 - p_B,
    y_D: 1 - q_D,
    y_C: 1 - q_C,
    delta: p_B - p_A,
    w: q_A - p_B,
    e_D: q_D - q_A,
    h_D: q_C - q_D,
}


def leg_polynomials() -> tuple[sp.Expr, sp.Expr]:
    """T = (F_N/F_N0) F̂_T and G = s/κ of the sphere in x = 1 − p, y = 1 − q, derived from
    Hertz (F_N/F_N0 = (1 − p)³), Eq 19 (F̂_T = r(3 − 3r + r²), r = (q − p)/(1 − p)) and
    Eq 2 with Hertz (s = κ(q − p)(2 − p − q)), as ``SphereLevels`` writes them."""
    p, q = sp.symbols("p q", real=True)
    r = (q - p) / (1 - p)
    T = sp.factor(sp.simplify((1 - p) ** 3 * r * (3 - 3 * r + r**2)))
    G = (q - p) * (2 - p - q)
    to_xy = {p: 1 - _x, q: 1 - _y}
    return sp.expand(T.subs(to_xy)), sp.expand(G.subs(to_xy))


def _monomials(poly: sp.Expr, variables: tuple[sp.Symbol, ...]) -> tuple:
    """``poly`` as ((coefficient, exponents), ...), exact rational coefficients, sorted."""
    terms = sp.Poly(poly, *variables).terms()
    return tuple(sorted((Fraction(int(c.p), int(c.q)), tuple(k)) for k, c in terms))


def _tau(g: sp.Expr, xb: sp.Expr, ya: sp.Expr) -> sp.Expr:
    """τ(G) = T_B + (3/2) y_A (G − G_B): the line through B = (x_B, y_A) of slope 3y_A/2."""
    T, G = leg_polynomials()
    at_B = {_x: xb, _y: ya}
    return T.subs(at_B) + sp.Rational(3, 2) * ya * (g - G.subs(at_B))


def _leg_integral(integrand: sp.Expr, var: sp.Symbol, end: sp.Expr) -> sp.Expr:
    return sp.expand(sp.integrate(sp.expand(integrand), (var, 0, end)))


@functools.lru_cache(maxsize=1)
def sphere_released_areas() -> dict:
    """The closed forms of the module docstring, derived by sympy from :func:`leg_polynomials`.

    Keys: ``"AB"``, ``"BD"``, ``"DC"``, the polynomials in :data:`VARIABLES` (ABD = κ(AB + BD),
    ABC − ABD = κ DC); ``"tables"``, each as its monomials ((coefficient, exponents), ...),
    the form :class:`~cusp.models.sphere.SphereLevels` evaluates; ``"loop ABD"`` and
    ``"loop DC"``, the same areas as the plain line integrals of T dG along the legs, in the
    levels (:func:`identity_residuals` relates the two)."""
    T, G = leg_polynomials()
    # AB: y = y_A = x_B − w, x = x_B + d, d from 0 (B) to δ (A)
    at = {_x: x_B + _d, _y: x_B - w}
    g_ab = G.subs(at)
    ab = (T.subs(at) - _tau(g_ab, x_B, x_B - w)) * sp.diff(g_ab, _d)
    # BD: x = x_B, y = y_A − e, e from 0 (B) to e_D (D), y_A = y_D + e_D
    at = {_x: x_B, _y: y_D + e_D - _e}
    g_bd = G.subs(at)
    bd = (_tau(g_bd, x_B, y_D + e_D) - T.subs(at)) * sp.diff(g_bd, _e)
    # DC: x = x_B, y = y_C + h, h from 0 (C) to h_D (D); G rises as h falls
    at = {_x: x_B, _y: y_C + _h}
    dc = (T.subs({_x: x_B, _y: y_C}) - T.subs(at)) * -sp.diff(G.subs(at), _h)
    out: dict = {
        "AB": _leg_integral(ab, _d, delta),
        "BD": _leg_integral(bd, _e, e_D),
        "DC": _leg_integral(dc, _h, h_D),
    }
    out["tables"] = {k: _monomials(out[k], v) for k, v in VARIABLES.items()}
    out.update(_loops(T, G))
    return out


def _loops(T: sp.Expr, G: sp.Expr) -> dict[str, sp.Expr]:
    """ABD = −(∫_AB T dG + ∫_BD T dG) and ABC − ABD = ∫_DC (T_A − T) dG, as line integrals
    along the legs in the levels (A → B: x from x_A to x_B; B → D → C: y from y_A)."""
    s = sp.Symbol("s", real=True)
    xA, yA, xB, yD, yC = 1 - p_A, 1 - q_A, 1 - p_B, 1 - q_D, 1 - q_C

    def line(f_T, at, lo, hi):
        return sp.integrate(f_T * sp.diff(G.subs(at), s), (s, lo, hi))

    ab = line(T.subs({_x: s, _y: yA}), {_x: s, _y: yA}, xA, xB)
    bd = line(T.subs({_x: xB, _y: s}), {_x: xB, _y: s}, yA, yD)
    T_A = T.subs({_x: xA, _y: yA})
    dc = line(T_A - T.subs({_x: xB, _y: s}), {_x: xB, _y: s}, yD, yC)
    return {"loop ABD": sp.expand(-(ab + bd)), "loop DC": sp.expand(dc)}


def identity_residuals() -> dict[str, sp.Expr]:
    """closed form − loop integral − (what differs between them), for ABD and ABC − ABD, in
    the levels: zero as polynomials (sympy expands them to 0).

    ABD: the closed form integrates τ from G_B to G_A on AB and to G_D on BD, so it exceeds
    the loop integral by ∫_{G_A}^{G_D} τ dG, which vanishes on the path (G_D = G_A, D is where
    BC reaches g_A). ABC − ABD: the closed form takes T_C for T_A, so it exceeds the loop
    integral by (T_C − T_A)(G_C − G_D), which vanishes on the path (C is where BC reaches
    F_A)."""
    T, G = leg_polynomials()
    cf = sphere_released_areas()
    g = sp.Symbol("g", real=True)
    xA, yA, xB, yD, yC = 1 - p_A, 1 - q_A, 1 - p_B, 1 - q_D, 1 - q_C
    G_A, G_D, G_C = (G.subs({_x: xv, _y: yv}) for xv, yv in ((xA, yA), (xB, yD), (xB, yC)))
    T_A, T_C = T.subs({_x: xA, _y: yA}), T.subs({_x: xB, _y: yC})
    tau = _tau(g, xB, yA)
    abd = (cf["AB"] + cf["BD"]).subs(IN_LEVELS) - cf["loop ABD"]
    abd -= sp.integrate(tau, (g, G_A, G_D))
    dc = cf["DC"].subs(IN_LEVELS) - cf["loop DC"] - (T_C - T_A) * (G_C - G_D)
    return {"ABD": sp.expand(abd), "DC": sp.expand(dc)}
