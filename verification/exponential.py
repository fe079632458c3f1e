"""Rough surface with exponential heights: Sec. 2 (Eqs 9-15) and the contact-loss path (Sec. 4).

sympy integrates the Greenwood-Williamson integrals (Eqs 7, 8, 10, 11, 13, 14) with the
exponential density Phi = exp(-z/sigma*)/sigma* (Eq 1) and solves the resulting relations;
nothing is typed in as a result. :func:`exponential_derivations` gives the records of Eqs 9,
10, 12 (with the alternative readings of its garbled second line) and 15, and of the three
Section 4 ids ``"MD"`` (Mindlin-Deresiewicz force F'_T along AB), ``"AB"`` (the slip g'_T
along AB) and ``"32"`` (the total slipped area along AB); :func:`contact_loss_path` gives the
closed forms of the whole path O -> A -> B -> C/D.
"""

from __future__ import annotations

import functools

import sympy as sp

from .common import (
    F_N,
    F_N0,
    HALF3,
    Derivation,
    F_hat,
    F_Np,
    K,
    d,
    g_A,
    g_T,
    lam,
    mu,
    sigma,
    solve_unique,
    t,
    x,
    z,
)

PHI = sp.exp(-z / sigma) / sigma  # Eq 1

#: the Fhat_T-valued relations: domain, and the change of variable tried by the verdict
_F_DOM = ((F_hat, (0.0, 1.0)),)
_TO_X = ((F_hat, 1 - sp.exp(-x)),)
_X_DOM = ((x, (0.0, 40.0)),)


# --------------------------------------------------------------------------------------------
# The Greenwood-Williamson integrals


def _height_integral(integrand: sp.Expr, lower: sp.Expr, upper: sp.Expr, shift: sp.Expr):
    """int_lower^upper integrand(z) Phi(z) dz, computed by sympy after z = shift + sigma t.

    The change of variable (done by ``Integral.transform``) only moves and scales the
    integration variable; sympy does the integration itself.
    """
    integral = sp.Integral(integrand * PHI, (z, lower, upper))
    return sp.simplify(integral.transform(z, (shift + sigma * t, t)).doit())


@functools.lru_cache(maxsize=1)
def _rough() -> dict[str, sp.Expr]:
    """The Greenwood-Williamson integrals for the exponential density, in closed form."""
    g_N0 = g_T * sigma / (mu * lam)  # Eq 5
    d0 = d + g_N0
    # Eq 11: F_N = K int_d^oo (z-d)^{3/2} Phi dz
    J_d = _height_integral((z - d) ** HALF3, d, sp.oo, d)
    # Eq 7: stick part, asperities above d0
    stick = _height_integral((z - d) ** HALF3 - (z - d0) ** HALF3, d0, sp.oo, d0)
    # Eq 8 second integral / Eq 10: sliding asperities d < z < d0 carry mu F_N,i
    slip = _height_integral((z - d) ** HALF3, d, d0, d)
    # Eqs 13-14: area integrals
    area_all = _height_integral(z - d, d, sp.oo, d)
    area_slip = _height_integral(z - d, d, d0, d)
    normal = K * J_d
    tangential = mu * K * (stick + slip)  # Eq 8
    return {
        "g_N0": g_N0,
        "J_d": J_d,
        "stick": stick,
        "slip": slip,
        "area_all": area_all,
        "area_slip": area_slip,
        "F_N": normal,
        "F_T": tangential,
        "F_ST_eq7": mu * K * stick,
        "F_ST_eq10": tangential - mu * K * slip,
    }


def _in_x(expr: sp.Expr) -> sp.Expr:
    """Write an expression of g_T through x = g_T / (mu lambda)."""
    return sp.simplify(expr.subs(g_T, x * mu * lam))


def _loading_curve() -> sp.Expr:
    """Eq 9 as derived: F_T(g_T) at fixed F_N, Eq 8 over Eq 11 times F_N."""
    R = _rough()
    return sp.simplify((R["F_T"] / R["F_N"]) * F_N)


def _stick_area_in_x() -> sp.Expr:
    """Ahat_ST = 1 - (Eq 14 slip area)/(Eq 13 area), as a function of x."""
    R = _rough()
    return sp.simplify(_in_x(1 - R["area_slip"] / R["area_all"]))


# --------------------------------------------------------------------------------------------
# Sec. 2: Eqs 9, 10, 12, 15


def _loading_derivations(eq9: sp.Expr) -> list[Derivation]:
    """Eq 9 (the loading curve) and Eq 10 (the stick force, Eq 8 minus the slip integral)."""
    R = _rough()
    # Eq 10 = Eq 7: the stick part as F_T minus the slip part equals the stick integral
    eq10_derived = sp.simplify(_in_x(R["F_ST_eq7"] / (mu * R["F_N"])))
    eq10_printed = sp.simplify(_in_x(R["F_ST_eq10"] / (mu * R["F_N"])))
    dims = ((g_T, (0.0, 5.0)), (F_N, (0.0, 2000.0)), (mu, (0.0, 1.0)), (lam, (0.0, 5.0)))
    return [
        Derivation(
            "9",
            "F_T(g_T) at fixed F_N, exponential heights",
            mu * F_N * (1 - sp.exp(-g_T / (mu * lam))),
            eq9,
            dims,
            (
                "Eq 8 integrated with Phi = exp(-z/sigma)/sigma (stick integral over z > d0 plus",
                "slip integral over d < z < d0), divided by Eq 11; g_N0 = g_T sigma/(mu lambda).",
            ),
        ),
        Derivation(
            "10",
            "stick force: F_T - F_T^SL (Eq 10) equals the stick integral (Eq 7)",
            eq10_printed,
            eq10_derived,
            _X_DOM,
            ("Eq 10 (F_T from Eq 8 minus the slip integral) vs Eq 7, both over mu F_N, in x.",),
        ),
    ]


def _eq12_readings() -> dict[str, sp.Expr]:
    """The second line of Eq 12, garbled in the extracted text, in its three readings."""
    X = sp.sqrt(-sp.log(1 - F_hat))
    pref = (1 - F_hat) / (3 * sp.sqrt(sp.pi))
    poly = -4 * X**3 - 6 * X
    return {
        # (a) braces close before "- erf": the reading adopted (docs/verification.md)
        "a": F_hat - pref * poly - sp.erf(X),
        # (b) braces enclose the erf term: F - { pref [..] - erf }; identical to reading
        #     the braces as in (a) but with erf of the other sign
        "b": F_hat - (pref * poly - sp.erf(X)),
        # (c) the prefactor multiplies erf too: F - pref { [..] - erf }
        "c": F_hat - pref * (poly - sp.erf(X)),
    }


def _eq12_derivations(x_of_F: sp.Expr) -> list[Derivation]:
    """Eq 12: Fhat_ST in x (first line), in Fhat_T (second line, three readings), slip part."""
    R = _rough()
    fst_x = sp.simplify(_in_x(R["F_ST_eq7"] / (mu * R["F_N"])))
    eq12 = sp.simplify(fst_x.subs(x, x_of_F))
    readings = _eq12_readings()
    # the first line of Eq 12, in x = g_T/(mu lambda)
    eq12x_printed = (
        (1 - sp.exp(-x))
        - sp.exp(-x) / (3 * sp.sqrt(sp.pi)) * (-4 * x**HALF3 - 6 * sp.sqrt(x))
        - sp.erf(sp.sqrt(x))
    )
    out = [
        Derivation(
            "12 (x)",
            "Fhat_ST as a function of x = g_T/(mu lambda) (first line of Eq 12)",
            eq12x_printed,
            fst_x,
            _X_DOM,
            ("Eq 7 integrated, over Eq 11; Fhat_T = 1 - exp(-x) from Eq 9.",),
        ),
        Derivation(
            "12",
            "Fhat_ST(Fhat_T), exponential heights",
            readings["a"],
            eq12,
            _F_DOM,
            (
                "Eq 7 integrated, over mu F_N (Eq 11), with x = -ln(1 - Fhat_T) solved from the",
                "derived Eq 9. Printed reading: Fhat - (1-Fhat)/(3 sqrt(pi)) [-4X^3-6X] - erf(X),",
                "X = sqrt(-ln(1-Fhat)), i.e. Fhat_T - P(5/2, x).",
            ),
            change_of_variable=_TO_X,
        ),
        Derivation(
            "12 (slip)",
            "slip part Fhat_T - Fhat_ST = P(5/2, x) (Eq 10 second term over mu F_N)",
            sp.erf(sp.sqrt(x))
            - sp.exp(-x) * (4 * x**HALF3 + 6 * sp.sqrt(x)) / (3 * sp.sqrt(sp.pi)),
            _in_x(R["slip"] / R["J_d"]),
            _X_DOM,
            (
                "Slip integral over d < z < d0 (Eq 10) over Eq 11, in x; printed as",
                "docs/physics.md §4 reads P(5/2, x). This is the part that cancels",
                "catastrophically for small x.",
            ),
        ),
    ]
    for key, title in (
        ("b", "braces enclose erf, F - {pref [-4X^3-6X] - erf X} (= erf with + sign)"),
        ("c", "prefactor multiplies erf, F - pref {-4X^3-6X - erf X}"),
    ):
        out.append(
            Derivation(
                f"12 (reading {key})",
                f"alternative reading of garbled Eq 12: {title}",
                readings[key],
                eq12,
                _F_DOM,
                ("Same derivation as Eq 12; this reading of the extracted text is tested.",),
                role="alternative reading",
                change_of_variable=_TO_X,
            )
        )
    return out


def _eq15_derivation(x_of_F: sp.Expr) -> Derivation:
    """Eq 15: the stick-area ratio Ahat_ST(Fhat_T)."""
    eq15 = sp.simplify(_stick_area_in_x().subs(x, x_of_F))
    return Derivation(
        "15",
        "Ahat_ST(Fhat_T), exponential heights",
        (1 - F_hat) * (1 - sp.log(1 - F_hat)),
        eq15,
        _F_DOM,
        ("1 - (Eq 14 slip area)/(Eq 13 area), integrated; x = -ln(1 - Fhat_T) from Eq 9.",),
        change_of_variable=_TO_X,
    )


def exponential_derivations() -> list[Derivation]:
    """The exponential-surface records: Eqs 9, 10, 12 (and readings), 15, MD, AB, 32."""
    eq9 = _loading_curve()
    # the inverse of Eq 9 in the nondimensional variable: x(Fhat) solves Fhat = F_T/(mu F_N)
    x_of_F = solve_unique(_in_x(eq9 / (mu * F_N)) - F_hat, x)
    return [
        *_loading_derivations(eq9),
        *_eq12_derivations(x_of_F),
        _eq15_derivation(x_of_F),
        *_contact_loss_derivations(),
    ]


# --------------------------------------------------------------------------------------------
# Sec. 4: the contact-loss path


def _contact_loss_derivations() -> list[Derivation]:
    """Section 4 for the exponential density: the Mindlin-Deresiewicz path A -> B, as derived
    by :func:`contact_loss_path` (at B = any point of AB, the reduced load F'_N being free)."""
    cf = contact_loss_path()
    md, ab, asl = cf["F_B"], cf["g_B"], cf["A_SL_B"]
    md_printed = mu * F_N0 * (1 - sp.exp(-g_A / (mu * lam))) - mu * (F_N0 - F_Np)
    ab_printed = g_A + mu * lam * sp.log(F_Np / F_N0)
    xp = g_A / (mu * lam) + sp.log(F_Np / F_N0)
    asl_printed = (1 - sp.exp(-xp) * (1 + xp)) + (F_N0 - F_Np) / F_N0
    dom = (
        (F_Np, (500.0, 1000.0)),
        (F_N0, (1000.0, 1500.0)),
        (g_A, (0.0, 1.0)),
        (mu, (0.05, 1.0)),
        (lam, (0.5, 5.0)),
    )
    return [
        Derivation(
            "MD",
            "Mindlin-Deresiewicz force F'_T(F'_N) along AB, exponential heights",
            md_printed,
            md,
            dom,
            (
                "F_A from the derived Eq 9 at (g_A, F_N0); per-asperity MD rule summed over the",
                "heights: the load lost is K[J(d_A) - J(d_B)] (Eq 11), d solved from the load.",
            ),
        ),
        Derivation(
            "AB",
            "slip g'_T(F'_N) along AB, exponential heights",
            ab_printed,
            ab,
            dom,
            ("The derived Eq 9 at F'_N solved for g_T with F_T = F'_T (derived MD).",),
        ),
        Derivation(
            "32",
            "total slipped area Ahat_SL(F'_N) along AB, exponential heights",
            asl_printed,
            asl,
            dom,
            (
                "Eq 32 with Ahat_ST from the derived Eq 15 at x' = g'_T/(mu lambda) (derived AB)",
                "and dA_r/A_r from Eq 13 at d_A, d_B (derived, not assumed equal to dF_N/F_N0).",
            ),
        ),
    ]


@functools.lru_cache(maxsize=1)
def contact_loss_path() -> dict[str, sp.Expr]:
    """Closed forms of the whole contact-loss path (Sec. 4) for exponential heights.

    Keys: ``F_A``; ``g_B``, ``F_B``; ``g_C`` (F_T = F_A again on the reloading curve, needs
    F_A < mu F'_N), ``F_D`` (the reloading curve at g_A); ``A_SL_A`` ... ``A_SL_D`` (Eq 32
    as printed); ``snap_back`` (area ABD) and ``snap_through`` (area ABC) as the loop
    integrals of F_T dg_T. Every expression is derived from the GW integrals: the loading
    curve (Eq 9), its inverse, the MD rule summed over the asperities and Eq 32, then
    integrated by sympy; symbols are those of :data:`~cusp.verification.SYMBOLS` (``sigma``,
    ``mu``, ``lambda``, ``F_N0``, ``Fp_N``, ``g_A``). Used as test oracles for
    :mod:`cusp.models.contact_loss`, which traces the path from residuals instead.
    """
    R = _rough()
    d_of_load = solve_unique(R["F_N"] - F_N, d)
    eq9 = _loading_curve()
    ast_x = _stick_area_in_x()
    f = sp.Symbol("f", positive=True)  # the normal load along AB
    gp = sp.Symbol("gp", positive=True)
    F_A = eq9.subs({g_T: g_A, F_N: F_N0})
    d_A = d_of_load.subs(F_N, F_N0)
    # MD summed over the asperities, and the inverse loading curve, along AB at load f
    md = sp.simplify(F_A - mu * (R["F_N"].subs(d, d_A) - R["F_N"].subs(d, d_of_load.subs(F_N, f))))
    g_ab = sp.expand_log(sp.simplify(solve_unique(eq9.subs({g_T: gp, F_N: f}) - md, gp)))
    reload = eq9.subs(F_N, F_Np)  # F_T(g_T) at F'_N
    g_B = g_ab.subs(f, F_Np)
    F_B = md.subs(f, F_Np)
    g_C = sp.simplify(solve_unique(reload.subs(g_T, gp) - F_A, gp))
    F_D = reload.subs(g_T, g_A)
    # Eq 32 (printed): 1 - Ahat_ST(x) + dA_r/A_r, A_r from Eq 13 at the two separations
    A_r = R["area_all"]
    d_B = d_of_load.subs(F_N, F_Np)
    dA = sp.simplify((A_r.subs(d, d_A) - A_r.subs(d, d_B)) / A_r.subs(d, d_A))

    def asl(g, reduced):
        return sp.simplify(1 - ast_x.subs(x, g / (mu * lam)) + (dA if reduced else 0))

    # loop integrals of F_T dg_T: A -> B (parametrised by the load f), B -> D and B -> C
    # on the reloading curve, then back to A vertically (D) or horizontally (C)
    along_ab = sp.integrate(sp.simplify(md * sp.diff(g_ab, f)), (f, F_N0, F_Np))
    b_to_d = sp.integrate(reload, (g_T, g_B, g_A))
    b_to_c = sp.integrate(reload, (g_T, g_B, g_C))
    return {
        "F_A": F_A,
        "g_B": g_B,
        "F_B": F_B,
        "g_C": g_C,
        "F_D": F_D,
        "A_SL_A": asl(g_A, False),
        "A_SL_B": asl(g_B, True),
        "A_SL_C": asl(g_C, True),
        "A_SL_D": asl(g_A, True),
        "snap_back": sp.simplify(-(along_ab + b_to_d)),
        "snap_through": sp.simplify(-(along_ab + b_to_c - F_A * (g_C - g_A))),
    }


@functools.lru_cache(maxsize=1)
def manifold_events() -> dict[str, sp.Expr]:
    """Closed forms of the events of the catastrophe manifold for exponential heights, solved
    by sympy from :func:`contact_loss_path` (the loci of the points are its expressions read
    as functions of μ or of F'_N).

    Keys: ``C boundary, F'_N`` and ``C boundary, mu`` (F_A = μF'_N: where C appears, below
    it force control ends in gross sliding) and ``F'_T = 0, F'_N`` and ``F'_T = 0, mu`` (F_B
    = 0: the deepest admissible reduction), each the root in that parameter (sympy must find
    exactly one).
    """
    cf = contact_loss_path()
    boundary = cf["F_A"] - mu * F_Np
    return {
        "C boundary, F'_N": solve_unique(boundary, F_Np),
        "C boundary, mu": solve_unique(boundary, mu),
        "F'_T = 0, F'_N": solve_unique(cf["F_B"], F_Np),
        "F'_T = 0, mu": solve_unique(cf["F_B"], mu),
    }
