"""Smooth bodies (Sec. 3): sphere (Eqs 18-22), cylinder (Eqs 25-29), flat planes (Eqs 30-31).

The Cattaneo-Mindlin tractions are integrated by sympy over the disk of a sphere (2 pi r dr,
Eqs 17-18, 20) or the strip of a cylinder (dx, Eqs 24-25, 27), with c = (c/a) a; c/a is
solved from the resultant, and the stick-area ratio is the area (width) of the stick zone
over that of the contact. Flat planes carry a uniform pressure and traction; a point sticks
while the traction is below mu times the pressure, and the stick set is integrated.
:func:`smooth_derivations` gives the records.
"""

from __future__ import annotations

import sympy as sp

from .common import F_N, HALF3, Derivation, F_hat, a, c, ca, mu, r, rho, solve_unique, w, xi

#: relations in c/a, and relations in Fhat_T with the change of variable Fhat_T = 1 - w
_RATIO_DOM = ((ca, (0.0, 1.0)), (F_N, (0.0, 2000.0)), (mu, (0.0, 1.0)))
_F_DOM = ((F_hat, (0.0, 1.0)),)
_TO_W = ((F_hat, 1 - w),)

_s = sp.Symbol("s", real=True)  # xi / a across the cylinder strip


def _stick_ratio(resultant: sp.Expr) -> sp.Expr:
    """c/a(Fhat_T), solved from resultant / (mu F_N) = Fhat_T (positive real root)."""
    return solve_unique(resultant / (mu * F_N) - (1 - w), ca).subs(w, 1 - F_hat)


# --------------------------------------------------------------------------------------------
# Sphere


def _disk(q: sp.Expr, upper: sp.Expr) -> sp.Expr:
    """int_0^upper 2 pi r q dr, after r = a rho, with c = (c/a) a."""
    integral = sp.Integral(2 * sp.pi * q * r, (r, 0, upper))
    scaled = integral.transform(r, (a * rho, rho)).doit()  # r = a rho
    return sp.simplify(scaled.subs(c, ca * a))


def _sphere_derivations() -> list[Derivation]:
    """Eqs 18-22: tractions over the disk, 2 pi r dr (Eqs 17-18, 20)."""
    pre = mu * 3 * F_N / (2 * sp.pi * a**2)
    q1 = pre * sp.sqrt(1 - (r / a) ** 2)  # Eq 17a
    q2 = -pre * (c / a) * sp.sqrt(1 - (r / c) ** 2)  # Eq 17b
    ft_sphere = sp.simplify(_disk(q1, a) + _disk(q2, c))  # Eq 18
    fst_sphere = sp.simplify(_disk(q1, c) + _disk(q2, c))  # Eq 20
    ca_sphere = _stick_ratio(ft_sphere)  # Eq 19
    eq21 = sp.simplify((fst_sphere / (mu * F_N)).subs(ca, ca_sphere))
    area_sphere = sp.integrate(2 * sp.pi * r, (r, 0, c)) / sp.integrate(2 * sp.pi * r, (r, 0, a))
    eq22 = sp.simplify(area_sphere.subs(c, ca * a).subs(ca, ca_sphere))
    return [
        Derivation(
            "18",
            "sphere: F_T as the resultant of q1 + q2",
            mu * F_N * (1 - ca**3),
            ft_sphere,
            _RATIO_DOM,
            ("int_0^a 2 pi r q1 dr + int_0^c 2 pi r q2 dr, with c = (c/a) a.",),
        ),
        Derivation(
            "19",
            "sphere: stick radius c/a(Fhat_T)",
            (1 - F_hat) ** sp.Rational(1, 3),
            ca_sphere,
            _F_DOM,
            ("Eq 18 / (mu F_N) = Fhat_T solved for c/a (positive real root).",),
            change_of_variable=_TO_W,
        ),
        Derivation(
            "20",
            "sphere: stick force F_T^ST(c/a)",
            mu * F_N * (1 - (1 - ca**2) ** HALF3 - ca**3),
            fst_sphere,
            _RATIO_DOM,
            ("int_0^c 2 pi r (q1 + q2) dr.",),
        ),
        Derivation(
            "21",
            "sphere: Fhat_ST(Fhat_T)",
            F_hat - (1 - (1 - F_hat) ** sp.Rational(2, 3)) ** HALF3,
            eq21,
            _F_DOM,
            ("Derived Eq 20 / (mu F_N) with the derived Eq 19 substituted.",),
            change_of_variable=_TO_W,
        ),
        Derivation(
            "22",
            "sphere: Ahat_ST(Fhat_T)",
            (1 - F_hat) ** sp.Rational(2, 3),
            eq22,
            _F_DOM,
            ("Area of the stick disk over the contact disk, with the derived Eq 19.",),
            change_of_variable=_TO_W,
        ),
    ]


# --------------------------------------------------------------------------------------------
# Cylinder


def _strip(q: sp.Expr, half: sp.Expr) -> sp.Expr:
    """int_-half^half q dxi, after xi = a s, with c = (c/a) a."""
    integral = sp.Integral(q, (xi, -half, half))
    scaled = integral.transform(xi, (a * _s, _s)).doit()  # xi = a s
    return sp.simplify(scaled.subs(c, ca * a))


def _cylinder_derivations() -> list[Derivation]:
    """Eqs 25-29: tractions over the strip, dx (Eqs 24-25, 27), per unit length."""
    pre = mu * 2 * F_N / (sp.pi * a)
    q1 = pre * sp.sqrt(1 - (xi / a) ** 2)  # Eq 24a
    q2 = -pre * (c / a) * sp.sqrt(1 - (xi / c) ** 2)  # Eq 24b
    ft_cyl = sp.simplify(_strip(q1, a) + _strip(q2, c))  # Eq 25
    fst_cyl = sp.simplify(_strip(q1, c) + _strip(q2, c))  # Eq 27
    ca_cyl = _stick_ratio(ft_cyl)  # Eq 26
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
    return [
        Derivation(
            "25",
            "cylinder: F_T as the resultant of q1 + q2 (per unit length)",
            mu * F_N * (1 - ca**2),
            ft_cyl,
            _RATIO_DOM,
            ("int_-a^a q1 dx + int_-c^c q2 dx, with c = (c/a) a.",),
        ),
        Derivation(
            "26",
            "cylinder: stick half-width c/a(Fhat_T)",
            sp.sqrt(1 - F_hat),
            ca_cyl,
            _F_DOM,
            ("Eq 25 / (mu F_N) = Fhat_T solved for c/a (positive real root).",),
            change_of_variable=_TO_W,
        ),
        Derivation(
            "27",
            "cylinder: stick force F_T^ST(c/a)",
            eq27_printed,
            fst_cyl,
            _RATIO_DOM,
            ("int_-c^c (q1 + q2) dx (sympy returns asin; the paper prints arctan).",),
        ),
        Derivation(
            "28",
            "cylinder: Fhat_ST(Fhat_T)",
            eq28_printed,
            eq28,
            _F_DOM,
            ("Derived Eq 27 / (mu F_N) with the derived Eq 26 substituted.",),
            change_of_variable=_TO_W,
        ),
        Derivation(
            "29",
            "cylinder: Ahat_ST(Fhat_T)",
            sp.sqrt(1 - F_hat),
            eq29,
            _F_DOM,
            ("Width of the stick strip over the contact strip, with the derived Eq 26.",),
            change_of_variable=_TO_W,
        ),
    ]


# --------------------------------------------------------------------------------------------
# Flat planes


def _flat_derivations() -> list[Derivation]:
    """Eqs 30-31: uniform pressure p = F_N/A and uniform traction q = F_T/A over the nominal
    area; a point sticks while q < mu p (Sec. 3.3). Integrate over the stick set."""
    A_n, s_ = sp.symbols("A_n s", positive=True)
    F_Tf = F_hat * mu * F_N
    utilisation = sp.simplify((F_Tf / A_n) / (mu * F_N / A_n))  # q / (mu p)
    sticks = sp.Piecewise((1, utilisation < 1), (0, True))
    fst_flat = sp.integrate(sticks * F_Tf / A_n, (s_, 0, A_n)) / (mu * F_N)
    ast_flat = sp.integrate(sticks, (s_, 0, A_n)) / A_n
    return [
        Derivation(
            "30",
            "flat planes: Fhat_ST(Fhat_T)",
            sp.Piecewise((F_hat, F_hat < 1), (0, True)),
            sp.piecewise_fold(sp.simplify(fst_flat)),
            _F_DOM,
            ("Uniform traction F_T/A integrated over the set where it is below mu F_N/A.",),
        ),
        Derivation(
            "31",
            "flat planes: Ahat_ST(Fhat_T)",
            sp.Piecewise((1, F_hat < 1), (0, True)),
            sp.piecewise_fold(sp.simplify(ast_flat)),
            _F_DOM,
            ("Measure of the set where the uniform traction is below mu F_N/A, over A.",),
        ),
    ]


def smooth_derivations() -> list[Derivation]:
    """The smooth-body records: sphere (18-22), cylinder (25-29), flat planes (30-31)."""
    return _sphere_derivations() + _cylinder_derivations() + _flat_derivations()
