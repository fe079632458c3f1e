"""Symbolic derivation of the paper's closed forms (sympy), and their verification.

Every closed form is *derived* here from the defining integrals and traction distributions,
never typed in: sympy integrates the Greenwood-Williamson integrals (Eqs 7, 8, 10, 11, 13, 14)
with the exponential density (Eq 1), the Cattaneo-Mindlin tractions of spheres (Eqs 17-18, 20)
and cylinders (Eqs 24-25, 27), and solves the resulting relations. Each result is a
:class:`Derivation` holding the paper's formula as we read it (``docs/verification.md``,
``PHYSICS.md``), the derived expression, and how they are to be compared;
:func:`check_printed` gives the verdict and :func:`check_implementation` compares the
derived expression, evaluated with mpmath at high precision, with the float code in
``models``.

This module imports sympy at import time; ``import cusp.models`` does not import it.
Equation ids are the paper's numbers ("9", "12", ...) plus three ids for Section 4:
``"MD"`` (Mindlin-Deresiewicz force F'_T along AB), ``"AB"`` (the slip g'_T along AB) and
``"32"`` (the total slipped area along AB). Ids of the form ``"12 (reading b)"`` are
alternative readings of a garbled printed formula; they are expected to disagree.
"""

from __future__ import annotations

import functools
import math
import random
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import mpmath
import sympy as sp

__all__ = [
    "Derivation",
    "PrintedVerdict",
    "ImplementationVerdict",
    "derive_all",
    "derivation",
    "check_printed",
    "check_implementation",
    "SYMBOLS",
    "FT_HAT_EXTREMES",
    "FT_HAT_INTERIOR",
    "IMPLEMENTATION_RTOL",
    "exact_value",
    "contact_loss_path",
]

# --------------------------------------------------------------------------------------------
# Symbols. All positive: sympy then picks the principal branches the physics needs.
z, d, t = sp.symbols("z d t", positive=True)
sigma = sp.Symbol("sigma", positive=True)  # composite rms roughness sigma*
g_T = sp.Symbol("g_T", positive=True)  # tangential slip
mu = sp.Symbol("mu", positive=True)  # friction coefficient
lam = sp.Symbol("lambda", positive=True)  # lambda = sigma* (2 - nu) / [2 (1 - nu)]
K = sp.Symbol("K", positive=True)  # (4/3) E* sqrt(rho*) n_s A_n
F_N = sp.Symbol("F_N", positive=True)
F_hat = sp.Symbol("Fhat_T", positive=True)  # F_T / (mu F_N), in (0, 1)
x = sp.Symbol("x", positive=True)  # g_T / (mu lambda) = g_N0 / sigma*
w = sp.Symbol("w", positive=True)  # 1 - Fhat_T, in (0, 1)
r, rho = sp.symbols("r rho", positive=True)
a, c = sp.symbols("a c", positive=True)  # contact radius / half-width, stick radius
ca = sp.Symbol("c_over_a", positive=True)  # c / a, in (0, 1)
xi = sp.Symbol("xi", real=True)  # coordinate across the cylinder strip
g_A = sp.Symbol("g_A", positive=True)  # slip at point A
F_N0 = sp.Symbol("F_N0", positive=True)  # normal load on O -> A
F_Np = sp.Symbol("Fp_N", positive=True)  # reduced normal load F'_N

#: name -> symbol, for users building their own printed forms
SYMBOLS: dict[str, sp.Symbol] = {
    s.name: s for s in (sigma, g_T, mu, lam, F_N, F_hat, x, w, ca, g_A, F_N0, F_Np)
}

HALF3 = sp.Rational(3, 2)

#: F_T-hat points where the implementation is compared (extremes of the open interval)
FT_HAT_EXTREMES: tuple[float, ...] = (
    1e-300,
    1e-100,
    1e-14,
    1e-9,
    1.0 - 1e-9,
    1.0 - 2.0**-40,
    1.0 - 2.0**-52,
)
FT_HAT_INTERIOR: tuple[float, ...] = (0.001, 0.05, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99, 0.999999)

#: relative tolerance of the implementation comparison for exactly-representable inputs
IMPLEMENTATION_RTOL = 1e-13


@dataclass(frozen=True)
class Derivation:
    """One closed form: the paper's formula as read, and the expression sympy derived.

    ``variables`` maps each free symbol to its open domain (lo, hi), used for the numeric
    fallback check. ``change_of_variable`` optionally maps a variable to an expression of a
    new positive symbol that is a bijection of the domain (e.g. Fhat_T = 1 - exp(-x)); the
    symbolic check is also attempted after it. ``steps`` says, in words, what was derived.
    """

    equation: str
    title: str
    printed: sp.Expr
    derived: sp.Expr
    variables: tuple[tuple[sp.Symbol, tuple[float, float]], ...]
    steps: tuple[str, ...] = ()
    role: str = "paper"  # "paper" or "alternative reading"
    change_of_variable: tuple[tuple[sp.Symbol, sp.Expr], ...] = ()

    @property
    def expected_agreement(self) -> bool:
        return self.role == "paper"


@dataclass(frozen=True)
class PrintedVerdict:
    equation: str
    agrees: bool
    method: str  # "symbolic" or "numeric, N points at D digits"
    detail: str


@dataclass(frozen=True)
class ImplementationVerdict:
    equation: str
    # e.g. "ExponentialRoughSurface.stick_force_ratio"; None: no counterpart in models/
    implementation: str | None
    agrees: bool
    points: int
    max_rel_error: float
    detail: str
    failures: tuple[str, ...] = field(default=())
    #: max over points of (relative error / tolerance at that point); <= 1 means agreement
    max_error_over_tolerance: float = math.nan


# --------------------------------------------------------------------------------------------
# Rough surface, exponential heights (Sec. 2)

PHI = sp.exp(-z / sigma) / sigma  # Eq 1


def _height_integral(integrand: sp.Expr, lower: sp.Expr, upper: sp.Expr, shift: sp.Expr):
    """int_lower^upper integrand(z) Phi(z) dz, computed by sympy after z = shift + sigma t.

    The change of variable (done by ``Integral.transform``) only moves and scales the
    integration variable; sympy does the integration itself.
    """
    integral = sp.Integral(integrand * PHI, (z, lower, upper))
    return sp.simplify(integral.transform(z, (shift + sigma * t, t)).doit())


def _solve_unique(equation: sp.Expr, unknown: sp.Symbol) -> sp.Expr:
    roots = sp.solve(equation, unknown)
    if len(roots) != 1:
        raise RuntimeError(f"expected one root for {unknown}, sympy found {roots}")
    return roots[0]


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


def _exponential_derivations() -> list[Derivation]:
    R = _rough()
    # Eq 9: F_T as a function of g_T at fixed F_N
    eq9 = sp.simplify((R["F_T"] / R["F_N"]) * F_N)
    eq9_printed = mu * F_N * (1 - sp.exp(-g_T / (mu * lam)))
    # and its inverse in the nondimensional variable: x(Fhat) solves Fhat = F_T/(mu F_N)
    x_of_F = _solve_unique(_in_x(eq9 / (mu * F_N)) - F_hat, x)

    # Eq 10 = Eq 7: the stick part as F_T minus the slip part equals the stick integral
    eq10_derived = sp.simplify(_in_x(R["F_ST_eq7"] / (mu * R["F_N"])))
    eq10_printed = sp.simplify(_in_x(R["F_ST_eq10"] / (mu * R["F_N"])))

    # Eq 12: Fhat_ST = F_ST / (mu F_N) as a function of Fhat_T
    fst_x = sp.simplify(_in_x(R["F_ST_eq7"] / (mu * R["F_N"])))
    eq12 = sp.simplify(fst_x.subs(x, x_of_F))
    X = sp.sqrt(-sp.log(1 - F_hat))
    pref = (1 - F_hat) / (3 * sp.sqrt(sp.pi))
    poly = -4 * X**3 - 6 * X
    readings = {
        # (a) braces close before "- erf": the reading PHYSICS.md adopts
        "a": F_hat - pref * poly - sp.erf(X),
        # (b) braces enclose the erf term: F - { pref [..] - erf }; identical to reading
        #     the braces as in (a) but with erf of the other sign
        "b": F_hat - (pref * poly - sp.erf(X)),
        # (c) the prefactor multiplies erf too: F - pref { [..] - erf }
        "c": F_hat - pref * (poly - sp.erf(X)),
    }
    # the first line of Eq 12, in x = g_T/(mu lambda)
    eq12x_printed = (
        (1 - sp.exp(-x))
        - sp.exp(-x) / (3 * sp.sqrt(sp.pi)) * (-4 * x**HALF3 - 6 * sp.sqrt(x))
        - sp.erf(sp.sqrt(x))
    )

    # Eq 15: A_ST / A_r
    ast_x = sp.simplify(_in_x(1 - R["area_slip"] / R["area_all"]))
    eq15 = sp.simplify(ast_x.subs(x, x_of_F))
    eq15_printed = (1 - F_hat) * (1 - sp.log(1 - F_hat))

    F_dom = ((F_hat, (0.0, 1.0)),)
    to_x = ((F_hat, 1 - sp.exp(-x)),)
    dims = ((g_T, (0.0, 5.0)), (F_N, (0.0, 2000.0)), (mu, (0.0, 1.0)), (lam, (0.0, 5.0)))
    out = [
        Derivation(
            "9",
            "F_T(g_T) at fixed F_N, exponential heights",
            eq9_printed,
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
            ((x, (0.0, 40.0)),),
            ("Eq 10 (F_T from Eq 8 minus the slip integral) vs Eq 7, both over mu F_N, in x.",),
        ),
        Derivation(
            "12 (x)",
            "Fhat_ST as a function of x = g_T/(mu lambda) (first line of Eq 12)",
            eq12x_printed,
            fst_x,
            ((x, (0.0, 40.0)),),
            ("Eq 7 integrated, over Eq 11; Fhat_T = 1 - exp(-x) from Eq 9.",),
        ),
        Derivation(
            "12",
            "Fhat_ST(Fhat_T), exponential heights",
            readings["a"],
            eq12,
            F_dom,
            (
                "Eq 7 integrated, over mu F_N (Eq 11), with x = -ln(1 - Fhat_T) solved from the",
                "derived Eq 9. Printed reading: Fhat - (1-Fhat)/(3 sqrt(pi)) [-4X^3-6X] - erf(X),",
                "X = sqrt(-ln(1-Fhat)), i.e. Fhat_T - P(5/2, x).",
            ),
            change_of_variable=to_x,
        ),
        Derivation(
            "12 (slip)",
            "slip part Fhat_T - Fhat_ST = P(5/2, x) (Eq 10 second term over mu F_N)",
            sp.erf(sp.sqrt(x))
            - sp.exp(-x) * (4 * x**HALF3 + 6 * sp.sqrt(x)) / (3 * sp.sqrt(sp.pi)),
            _in_x(R["slip"] / R["J_d"]),
            ((x, (0.0, 40.0)),),
            (
                "Slip integral over d < z < d0 (Eq 10) over Eq 11, in x; printed as PHYSICS.md",
                "reads P(5/2, x). This is the part that cancels catastrophically for small x.",
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
                F_dom,
                ("Same derivation as Eq 12; this reading of the extracted text is tested.",),
                role="alternative reading",
                change_of_variable=to_x,
            )
        )
    out.append(
        Derivation(
            "15",
            "Ahat_ST(Fhat_T), exponential heights",
            eq15_printed,
            eq15,
            F_dom,
            ("1 - (Eq 14 slip area)/(Eq 13 area), integrated; x = -ln(1 - Fhat_T) from Eq 9.",),
            change_of_variable=to_x,
        )
    )
    out.extend(_contact_loss())
    return out


def _contact_loss() -> list[Derivation]:
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
    integrated by sympy; symbols are those of :data:`SYMBOLS` (``sigma``, ``mu``, ``lambda``,
    ``F_N0``, ``Fp_N``, ``g_A``). Used as test oracles for :mod:`cusp.models.contact_loss`, which
    traces the path from residuals instead.
    """
    R = _rough()
    d_of_load = _solve_unique(R["F_N"] - F_N, d)
    eq9 = sp.simplify((R["F_T"] / R["F_N"]) * F_N)
    ast_x = sp.simplify(_in_x(1 - R["area_slip"] / R["area_all"]))
    f = sp.Symbol("f", positive=True)  # the normal load along AB
    gp = sp.Symbol("gp", positive=True)
    F_A = eq9.subs({g_T: g_A, F_N: F_N0})
    d_A = d_of_load.subs(F_N, F_N0)
    # MD summed over the asperities, and the inverse loading curve, along AB at load f
    md = sp.simplify(F_A - mu * (R["F_N"].subs(d, d_A) - R["F_N"].subs(d, d_of_load.subs(F_N, f))))
    g_ab = sp.expand_log(sp.simplify(_solve_unique(eq9.subs({g_T: gp, F_N: f}) - md, gp)))
    reload = eq9.subs(F_N, F_Np)  # F_T(g_T) at F'_N
    g_B = g_ab.subs(f, F_Np)
    F_B = md.subs(f, F_Np)
    g_C = sp.simplify(_solve_unique(reload.subs(g_T, gp) - F_A, gp))
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


# --------------------------------------------------------------------------------------------
# Smooth bodies (Sec. 3)


def _smooth_derivations() -> list[Derivation]:
    out: list[Derivation] = []
    ratio_dom = ((ca, (0.0, 1.0)), (F_N, (0.0, 2000.0)), (mu, (0.0, 1.0)))
    F_dom = ((F_hat, (0.0, 1.0)),)
    to_w = ((F_hat, 1 - w),)

    # ---- sphere: tractions over the disk, 2 pi r dr (Eqs 17-18, 20)
    pre = mu * 3 * F_N / (2 * sp.pi * a**2)
    q1 = pre * sp.sqrt(1 - (r / a) ** 2)  # Eq 17a
    q2 = -pre * (c / a) * sp.sqrt(1 - (r / c) ** 2)  # Eq 17b

    def disk(q, upper):
        integral = sp.Integral(2 * sp.pi * q * r, (r, 0, upper))
        scaled = integral.transform(r, (a * rho, rho)).doit()  # r = a rho
        return sp.simplify(scaled.subs(c, ca * a))

    ft_sphere = sp.simplify(disk(q1, a) + disk(q2, c))  # Eq 18
    fst_sphere = sp.simplify(disk(q1, c) + disk(q2, c))  # Eq 20
    ca_sphere = _solve_unique(ft_sphere / (mu * F_N) - (1 - w), ca).subs(w, 1 - F_hat)  # Eq 19
    eq21 = sp.simplify((fst_sphere / (mu * F_N)).subs(ca, ca_sphere))
    area_sphere = sp.integrate(2 * sp.pi * r, (r, 0, c)) / sp.integrate(2 * sp.pi * r, (r, 0, a))
    eq22 = sp.simplify(area_sphere.subs(c, ca * a).subs(ca, ca_sphere))
    out += [
        Derivation(
            "18",
            "sphere: F_T as the resultant of q1 + q2",
            mu * F_N * (1 - ca**3),
            ft_sphere,
            ratio_dom,
            ("int_0^a 2 pi r q1 dr + int_0^c 2 pi r q2 dr, with c = (c/a) a.",),
        ),
        Derivation(
            "19",
            "sphere: stick radius c/a(Fhat_T)",
            (1 - F_hat) ** sp.Rational(1, 3),
            ca_sphere,
            F_dom,
            ("Eq 18 / (mu F_N) = Fhat_T solved for c/a (positive real root).",),
            change_of_variable=to_w,
        ),
        Derivation(
            "20",
            "sphere: stick force F_T^ST(c/a)",
            mu * F_N * (1 - (1 - ca**2) ** HALF3 - ca**3),
            fst_sphere,
            ratio_dom,
            ("int_0^c 2 pi r (q1 + q2) dr.",),
        ),
        Derivation(
            "21",
            "sphere: Fhat_ST(Fhat_T)",
            F_hat - (1 - (1 - F_hat) ** sp.Rational(2, 3)) ** HALF3,
            eq21,
            F_dom,
            ("Derived Eq 20 / (mu F_N) with the derived Eq 19 substituted.",),
            change_of_variable=to_w,
        ),
        Derivation(
            "22",
            "sphere: Ahat_ST(Fhat_T)",
            (1 - F_hat) ** sp.Rational(2, 3),
            eq22,
            F_dom,
            ("Area of the stick disk over the contact disk, with the derived Eq 19.",),
            change_of_variable=to_w,
        ),
    ]

    # ---- cylinder: tractions over the strip, dx (Eqs 24-25, 27)
    pre = mu * 2 * F_N / (sp.pi * a)
    q1 = pre * sp.sqrt(1 - (xi / a) ** 2)  # Eq 24a
    q2 = -pre * (c / a) * sp.sqrt(1 - (xi / c) ** 2)  # Eq 24b
    s = sp.Symbol("s", real=True)

    def strip(q, half):
        integral = sp.Integral(q, (xi, -half, half))
        scaled = integral.transform(xi, (a * s, s)).doit()  # xi = a s
        return sp.simplify(scaled.subs(c, ca * a))

    ft_cyl = sp.simplify(strip(q1, a) + strip(q2, c))  # Eq 25
    fst_cyl = sp.simplify(strip(q1, c) + strip(q2, c))  # Eq 27
    ca_cyl = _solve_unique(ft_cyl / (mu * F_N) - (1 - w), ca).subs(w, 1 - F_hat)  # Eq 26
    eq28 = sp.simplify((fst_cyl / (mu * F_N)).subs(ca, ca_cyl))
    width = sp.integrate(1, (xi, -c, c)) / sp.integrate(1, (xi, -a, a))
    eq29 = sp.simplify(width.subs(c, ca * a).subs(ca, ca_cyl))
    eq27_printed = (
        2 / sp.pi * mu * F_N * (ca * sp.sqrt(1 - ca**2) + sp.atan(ca / sp.sqrt(1 - ca**2)))
        - mu * F_N * ca**2
    )
    eq28_printed = (
        2 / sp.pi * (sp.sqrt((1 - F_hat) * F_hat) + sp.atan(sp.sqrt((1 - F_hat) / F_hat)))
        + F_hat
        - 1
    )
    out += [
        Derivation(
            "25",
            "cylinder: F_T as the resultant of q1 + q2 (per unit length)",
            mu * F_N * (1 - ca**2),
            ft_cyl,
            ratio_dom,
            ("int_-a^a q1 dx + int_-c^c q2 dx, with c = (c/a) a.",),
        ),
        Derivation(
            "26",
            "cylinder: stick half-width c/a(Fhat_T)",
            sp.sqrt(1 - F_hat),
            ca_cyl,
            F_dom,
            ("Eq 25 / (mu F_N) = Fhat_T solved for c/a (positive real root).",),
            change_of_variable=to_w,
        ),
        Derivation(
            "27",
            "cylinder: stick force F_T^ST(c/a)",
            eq27_printed,
            fst_cyl,
            ratio_dom,
            ("int_-c^c (q1 + q2) dx (sympy returns asin; the paper prints arctan).",),
        ),
        Derivation(
            "28",
            "cylinder: Fhat_ST(Fhat_T)",
            eq28_printed,
            eq28,
            F_dom,
            ("Derived Eq 27 / (mu F_N) with the derived Eq 26 substituted.",),
            change_of_variable=to_w,
        ),
        Derivation(
            "29",
            "cylinder: Ahat_ST(Fhat_T)",
            sp.sqrt(1 - F_hat),
            eq29,
            F_dom,
            ("Width of the stick strip over the contact strip, with the derived Eq 26.",),
            change_of_variable=to_w,
        ),
    ]

    # ---- flat planes: uniform pressure p = F_N/A and uniform traction q = F_T/A over the
    # nominal area; a point sticks while q < mu p (Sec. 3.3). Integrate over the stick set.
    A_n, s_ = sp.symbols("A_n s", positive=True)
    F_Tf = F_hat * mu * F_N
    utilisation = sp.simplify((F_Tf / A_n) / (mu * F_N / A_n))  # q / (mu p)
    sticks = sp.Piecewise((1, utilisation < 1), (0, True))
    fst_flat = sp.integrate(sticks * F_Tf / A_n, (s_, 0, A_n)) / (mu * F_N)
    ast_flat = sp.integrate(sticks, (s_, 0, A_n)) / A_n
    F_dom_closed = ((F_hat, (0.0, 1.0)),)
    out += [
        Derivation(
            "30",
            "flat planes: Fhat_ST(Fhat_T)",
            sp.Piecewise((F_hat, F_hat < 1), (0, True)),
            sp.piecewise_fold(sp.simplify(fst_flat)),
            F_dom_closed,
            ("Uniform traction F_T/A integrated over the set where it is below mu F_N/A.",),
        ),
        Derivation(
            "31",
            "flat planes: Ahat_ST(Fhat_T)",
            sp.Piecewise((1, F_hat < 1), (0, True)),
            sp.piecewise_fold(sp.simplify(ast_flat)),
            F_dom_closed,
            ("Measure of the set where the uniform traction is below mu F_N/A, over A.",),
        ),
    ]
    return out


@functools.lru_cache(maxsize=1)
def _all() -> tuple[Derivation, ...]:
    return tuple(_exponential_derivations() + _smooth_derivations())


def derive_all() -> list[Derivation]:
    """All derivations, in paper order (computed once per process, ~seconds)."""
    order = ["9", "10", "12 (x)", "12 (slip)", "12", "15", "18", "19", "20", "21", "22"]
    order += ["25", "26", "27", "28", "29", "30", "31", "MD", "AB", "32"]
    recs = _all()
    key = {eq: i for i, eq in enumerate(order)}
    return sorted(
        recs, key=lambda rec: (key.get(rec.equation.split(" (reading")[0], 99), rec.equation)
    )


def derivation(equation: str) -> Derivation:
    """The derivation with this id (e.g. ``"12"``)."""
    for rec in _all():
        if rec.equation == equation:
            return rec
    known = ", ".join(rec.equation for rec in _all())
    raise KeyError(f"no derivation for equation {equation!r}; known: {known}")


# --------------------------------------------------------------------------------------------
# Verdict: printed vs derived


def _is_zero_symbolically(expr: sp.Expr) -> bool:
    for attempt in (
        lambda e: sp.simplify(e),
        lambda e: sp.simplify(sp.expand_func(e)),
        lambda e: sp.simplify(sp.expand_log(sp.expand_func(e), force=True)),
    ):
        if attempt(expr) == 0:
            return True
    return False


def _sample_points(
    variables: Sequence[tuple[sp.Symbol, tuple[float, float]]], n: int, seed: int = 5
) -> list[dict[sp.Symbol, mpmath.mpf]]:
    rng = random.Random(seed)
    pts = []
    for _ in range(n):
        pt = {}
        for sym, (lo, hi) in variables:
            # avoid the end points, where the closed forms are singular or 0/0
            u = 0.02 + 0.96 * rng.random()
            pt[sym] = mpmath.mpf(lo) + (mpmath.mpf(hi) - mpmath.mpf(lo)) * mpmath.mpf(u)
        pts.append(pt)
    return pts


def _lambdify(expr: sp.Expr, symbols: Sequence[sp.Symbol]) -> Callable:
    return sp.lambdify(list(symbols), expr, modules="mpmath")


def check_printed(der: Derivation, *, points: int = 40, dps: int = 50) -> PrintedVerdict:
    """Does the printed form equal the derived one?

    First ``simplify(printed - derived) == 0`` (also after expand_func, and after the
    derivation's change of variable); where simplification stalls, the difference is
    evaluated with mpmath at ``points`` points of the domain at ``dps`` digits and must be
    below 10^-(dps-10) relative. The verdict says which method decided.
    """
    if points < 1 or dps < 20:
        raise ValueError(f"need points >= 1 and dps >= 20, got points={points}, dps={dps}")
    return _check_printed(der, points, dps)


@functools.lru_cache(maxsize=128)
def _check_printed(der: Derivation, points: int, dps: int) -> PrintedVerdict:
    diff = der.printed - der.derived
    declared = {sym for sym, _ in der.variables}
    if not diff.free_symbols <= declared:
        extra = ", ".join(sorted(str(sym) for sym in diff.free_symbols - declared))
        raise ValueError(f"Eq {der.equation}: symbols {extra} have no declared domain")
    if _is_zero_symbolically(diff):
        return PrintedVerdict(der.equation, True, "symbolic", "simplify(printed - derived) == 0")
    if der.change_of_variable:
        sub = dict(der.change_of_variable)
        if _is_zero_symbolically(diff.subs(sub)):
            names = ", ".join(f"{k} = {v}" for k, v in der.change_of_variable)
            return PrintedVerdict(
                der.equation, True, "symbolic", f"simplify(printed - derived) == 0 after {names}"
            )
    syms = [sym for sym, _ in der.variables]
    f_p = _lambdify(der.printed, syms)
    f_d = _lambdify(der.derived, syms)
    worst = mpmath.mpf(0)
    worst_at = None
    with mpmath.workdps(dps):
        tol = mpmath.mpf(10) ** (-(dps - 10))
        for pt in _sample_points(der.variables, points):
            args = [pt[s] for s in syms]
            vp, vd = f_p(*args), f_d(*args)
            err = abs(vp - vd) / max(abs(vd), mpmath.mpf(1e-30))
            if err > worst or worst_at is None:
                worst, worst_at = err, (args, vp, vd)
        agrees = worst <= tol
    args, vp, vd = worst_at
    where = ", ".join(f"{s}={mpmath.nstr(v, 8)}" for s, v in zip(syms, args, strict=True))
    detail = (
        f"max relative difference {mpmath.nstr(worst, 3)} (tolerance 1e-{dps - 10}); "
        f"worst at {where}: printed {mpmath.nstr(vp, 12)}, derived {mpmath.nstr(vd, 12)}"
    )
    return PrintedVerdict(
        der.equation, bool(agrees), f"numeric, {points} points at {dps} digits", detail
    )


# --------------------------------------------------------------------------------------------
# Verdict: derived vs the float implementation in models/


def exact_value(
    expr: sp.Expr,
    symbols: Sequence[sp.Symbol],
    values: Sequence[float],
    *,
    min_dps: int = 50,
    max_dps: int = 6400,
) -> mpmath.mpf:
    """``expr`` at the exact binary values ``values``, to about 30 correct digits.

    The derived expressions are evaluated as derived (e.g. the erf form of Eq 12), which
    cancels catastrophically at the ends of the interval; the precision is therefore doubled
    until two successive evaluations agree to 1e-30 relative, starting high enough that
    1 - v is exact for every input v.
    """
    f = _compiled(expr, tuple(symbols))
    start = min_dps
    for v in values:
        if v != 0 and math.isfinite(v):
            start = max(start, min_dps + int(abs(math.log10(abs(v)))))
            if v != 1:
                start = max(start, min_dps + int(abs(math.log10(abs(1 - v)))) + 20)
    prev = None
    dps = start
    while dps <= max_dps:
        with mpmath.workdps(dps):
            val = f(*[mpmath.mpf(v) for v in values])
            if isinstance(val, mpmath.mpc):
                if abs(val.imag) > abs(val.real) * mpmath.mpf(10) ** (-dps // 2):
                    raise ArithmeticError(f"complex value {val} at {values}")
                val = val.real
            if prev is not None:
                scale = max(abs(val), abs(prev))
                if scale == 0 or abs(val - prev) <= scale * mpmath.mpf(10) ** -30:
                    return +val
            prev = val
        dps *= 2
    raise ArithmeticError(f"no convergence of {expr} at {values} up to {max_dps} digits")


@dataclass(frozen=True)
class _Check:
    """How one derived expression is compared with one model method."""

    equation: str
    name: str  # "ExponentialRoughSurface.stick_force_ratio"
    expr: sp.Expr  # derived, with model parameters substituted
    inputs: tuple[sp.Symbol, ...]
    points: tuple[tuple[float, ...], ...]
    call: Callable[..., float]
    # symbols whose float value the code must combine with rounding (ratios g_T/(mu lambda),
    # F_T/(mu F_N)); their condition numbers widen the tolerance. Empty: inputs are used as is.
    conditioned: tuple[sp.Symbol, ...] = ()
    n_params: int = 0  # trailing model parameters in each point (not shown in messages)


def _ft_hat_points() -> tuple[tuple[float, ...], ...]:
    return tuple((v,) for v in sorted(FT_HAT_INTERIOR + FT_HAT_EXTREMES))


def _model_checks(models) -> list[_Check]:
    """The comparisons, against ``models.ExponentialRoughSurface``, ``Sphere``, ``Cylinder``."""
    sig_f, nu_f, mu_f = 2.0, 0.3, 0.1
    surf = models.ExponentialRoughSurface(sigma=sig_f, nu=nu_f, mu=mu_f)
    sphere, cylinder, flat = models.Sphere(), models.Cylinder(), models.FlatPlane()
    # the parameters enter as the exact binary floats the float code holds
    nu_s = sp.Symbol("nu", positive=True)
    pars = {lam: sigma * (2 - nu_s) / (2 * (1 - nu_s))}
    par_syms, par_vals = (mu, sigma, nu_s), (mu_f, sig_f, nu_f)
    F = _ft_hat_points()
    checks = [
        _Check(
            "12",
            "ExponentialRoughSurface.stick_force_ratio",
            derivation("12").derived,
            (F_hat,),
            F,
            surf.stick_force_ratio,
        ),
        _Check(
            "15",
            "ExponentialRoughSurface.stick_area_ratio",
            derivation("15").derived,
            (F_hat,),
            F,
            surf.stick_area_ratio,
        ),
        _Check(
            "21",
            "Sphere.stick_force_ratio",
            derivation("21").derived,
            (F_hat,),
            F,
            sphere.stick_force_ratio,
        ),
        _Check(
            "22",
            "Sphere.stick_area_ratio",
            derivation("22").derived,
            (F_hat,),
            F,
            sphere.stick_area_ratio,
        ),
        _Check(
            "28",
            "Cylinder.stick_force_ratio",
            derivation("28").derived,
            (F_hat,),
            F,
            cylinder.stick_force_ratio,
        ),
        _Check(
            "29",
            "Cylinder.stick_area_ratio",
            derivation("29").derived,
            (F_hat,),
            F,
            cylinder.stick_area_ratio,
        ),
    ]
    F_closed = F + ((1.0,),)  # the flat plane's drop at Fhat_T = 1 is part of Eqs 30-31
    checks += [
        _Check(
            "30",
            "FlatPlane.stick_force_ratio",
            derivation("30").derived,
            (F_hat,),
            F_closed,
            flat.stick_force_ratio,
        ),
        _Check(
            "31",
            "FlatPlane.stick_area_ratio",
            derivation("31").derived,
            (F_hat,),
            F_closed,
            flat.stick_area_ratio,
        ),
    ]
    # the slip part P(5/2, x) of Eq 12 from the model's slip integral at h = 0
    xs = tuple(float(-mpmath.log1p(-mpmath.mpf(v))) for (v,) in F)
    slip_pts = tuple((float(mpmath.mpf(v) * mpmath.mpf(sig_f)), sig_f) for v in xs)
    checks.append(
        _Check(
            "12 (slip)",
            "ExponentialRoughSurface.slip_load_integral / load_integral",
            derivation("12 (slip)").derived.subs(x, g_T / sigma),
            (g_T, sigma),
            slip_pts,
            lambda g, _s: float(surf.slip_load_integral(0.0, g)) / float(surf.load_integral(0.0)),
            conditioned=(g_T,),
            n_params=1,
        )
    )
    # Eq 9 and its inverse at F_N = 1000 N, at slips/forces spanning the Fhat_T points
    FN_f = 1000.0
    mulam = mu_f * sig_f * (2 - nu_f) / (2 * (1 - nu_f))
    g_pts = tuple(
        (float(-mpmath.log1p(-mpmath.mpf(v)) * mpmath.mpf(mulam)), FN_f) + par_vals for (v,) in F
    )
    ft_pts = tuple((float(mpmath.mpf(v) * mu_f * FN_f), FN_f) + par_vals for (v,) in F)
    eq9 = derivation("9").derived.subs(pars)
    F_T = sp.Symbol("F_T", positive=True)
    g_inv = _solve_unique(derivation("9").derived - F_T, g_T).subs(pars)
    checks += [
        _Check(
            "9",
            "ExponentialRoughSurface.tangential_force",
            eq9,
            (g_T, F_N) + par_syms,
            g_pts,
            lambda g, fn, *_: surf.tangential_force(g, fn),
            conditioned=(g_T,),
            n_params=3,
        ),
        _Check(
            "9",
            "ExponentialRoughSurface.tangential_slip",
            g_inv,
            (F_T, F_N) + par_syms,
            ft_pts,
            lambda ft, fn, *_: surf.tangential_slip(ft, fn),
            conditioned=(F_T,),
            n_params=3,
        ),
    ]
    # Section 4 at the Fig 6 data: F_N0 = 1000 N, g_A = 0.34 um, F'_N from 1000 N down
    gA_f, FN0_f = 0.34, 1000.0
    fnp = (999.999, 990.0, 950.0, 900.0, 850.0, 800.0, 750.0, 700.0)
    sec4 = tuple((v, FN0_f, gA_f) + par_vals for v in fnp)

    def md_call(fnp_, fn0, ga, *_):
        return float(surf.tangential_force(ga, fn0)) - mu_f * (fn0 - fnp_)

    def ab_call(fnp_, fn0, ga, *_):
        return surf.tangential_slip(md_call(fnp_, fn0, ga), fnp_)

    def asl_call(fnp_, fn0, ga, *_):
        fhat = md_call(fnp_, fn0, ga) / (mu_f * fnp_)
        return 1.0 - float(surf.stick_area_ratio(fhat)) + (fn0 - fnp_) / fn0

    loads = (F_Np, F_N0, g_A)
    ins = loads + par_syms
    checks += [
        _Check(
            eq,
            what,
            derivation(eq).derived.subs(pars),
            ins,
            sec4,
            call,
            conditioned=loads,
            n_params=3,
        )
        for eq, what, call in (
            ("MD", "ExponentialRoughSurface.tangential_force - mu dF_N", md_call),
            ("AB", "ExponentialRoughSurface.tangential_slip at (F'_T, F'_N)", ab_call),
            ("32", "1 - ExponentialRoughSurface.stick_area_ratio + dF_N/F_N0", asl_call),
        )
    ]
    return checks


def _condition(expr, inputs, values, which) -> float:
    """Sum over ``which`` of |v df/dv / f| at ``values``: how much rounding the inputs costs."""
    total = 0.0
    for sym in which:
        dexpr = sp.diff(expr, sym) * sym / expr
        try:
            total += abs(float(exact_value(dexpr, inputs, values, min_dps=30)))
        except (ArithmeticError, ZeroDivisionError):
            return math.inf
    return total


@functools.lru_cache(maxsize=256)
def _compiled(expr: sp.Expr, symbols: tuple[sp.Symbol, ...]) -> Callable:
    return _lambdify(expr, symbols)


def _run_check(chk: _Check) -> ImplementationVerdict:
    eps = 2.0**-52
    worst, worst_note, worst_ratio = 0.0, "", 0.0
    failures = []
    for pt in chk.points:
        exact = exact_value(chk.expr, chk.inputs, pt)
        try:
            got = float(chk.call(*pt))
        except Exception as exc:  # the model's own error is the finding
            failures.append(f"at {pt}: raised {type(exc).__name__}: {exc}")
            continue
        tol = IMPLEMENTATION_RTOL
        if chk.conditioned:
            tol += 4 * eps * _condition(chk.expr, chk.inputs, pt, chk.conditioned)
        if exact == 0:
            err = 0.0 if got == 0 else math.inf
        else:
            err = float(abs((mpmath.mpf(got) - exact) / exact))
        worst_ratio = max(worst_ratio, err / tol)
        if err >= worst:
            worst, worst_note = err, f" at {pt[: len(pt) - chk.n_params]} (tolerance {tol:.3g})"
        if not err <= tol:
            failures.append(
                f"at {pt}: got {got!r}, exact {mpmath.nstr(exact, 17)}, "
                f"relative error {err:.3g} > tolerance {tol:.3g}"
            )
    ok = not failures
    rule = f"{IMPLEMENTATION_RTOL:g}" + (" + 4 eps x condition" if chk.conditioned else "")
    detail = f"{len(chk.points)} points, max relative error {worst:.3g}{worst_note}; rule {rule}"
    if failures:
        detail += f"; {len(failures)} failing, first: {failures[0]}"
    return ImplementationVerdict(
        chk.equation, chk.name, ok, len(chk.points), worst, detail, tuple(failures), worst_ratio
    )


def check_implementation(models=None) -> dict[str, list[ImplementationVerdict]]:
    """Compare the derived expressions with the float code; equation id -> verdicts.

    ``models`` is the package (default: :mod:`cusp.models`). If the model classes cannot be
    imported, a single verdict under key ``"*"`` says so.
    """
    if models is None:
        import cusp.models as models_pkg

        models = models_pkg
    try:
        checks = _model_checks(models)
    except (AttributeError, ImportError, TypeError) as exc:
        msg = f"models not available: {type(exc).__name__}: {exc}"
        return {"*": [ImplementationVerdict("*", None, False, 0, math.nan, msg)]}
    out: dict[str, list[ImplementationVerdict]] = {}
    for chk in checks:
        out.setdefault(chk.equation, []).append(_run_check(chk))
    return out
