"""References for ``scripts/pleat_closure.py``: the quantities of one contact-loss path
(the widths g_A − g_B, F_A − F_B, the drop F_A − F_D, the jump g_C − g_A and the energies
ABD, ABC), independent of the traced path.

* exponential heights: the sympy closed forms of :func:`cusp.verification.contact_loss_path`
  (differences formed symbolically, evaluated at the exact binary inputs), and their series
  in d = ΔF_N/F_N0 (the exact exponents);
* Gaussian heights and the sphere: the path written out from the physics with mpmath
  (docs/physics.md §7: the stick level frozen along AB, the energies as loop integrals of
  F_T dg_T).
"""

from __future__ import annotations

import functools
import math

from cusp.models.registry import build_body

#: digits of the mpmath references (the energies at d = 1e-12 cancel about 24)
REF_DPS = 70


@functools.lru_cache(maxsize=1)
def exponential_closed_forms() -> dict:
    """The sympy closed forms of the quantities (differences formed symbolically, so that
    evaluating them at high precision does not cancel) and the symbols they take."""
    from cusp.verification import SYMBOLS as S
    from cusp.verification import contact_loss_path

    P = contact_loss_path()
    exprs = {
        "dg": S["g_A"] - P["g_B"],
        "dF": P["F_A"] - P["F_B"],
        "drop": P["F_A"] - P["F_D"],
        "jump": P["g_C"] - S["g_A"],
        "ABD": P["snap_back"],
        "ABC": P["snap_through"],
    }
    syms = tuple(S[k] for k in ("sigma", "mu", "lambda", "F_N0", "g_A", "Fp_N"))
    return {"exprs": exprs, "symbols": syms}


def reference(case: dict, F_Np: float, mu: float | None = None) -> dict[str, float]:
    """The quantities of one path from an independent reference (see the module docstring);
    NaN where the point they need does not exist."""
    p = dict(case["params"], **({} if mu is None else {"mu": mu}))
    if case["model"] == "rough-exponential":
        from cusp.verification import exact_value

        cf = exponential_closed_forms()
        lam = build_body(case["model"], **p).lam  # the float λ the model uses
        vals = (p["sigma"], p["mu"], lam, case["F_N0"], case["g_A"], F_Np)
        c_exists = (1.0 - math.exp(-case["g_A"] / (p["mu"] * lam))) * case["F_N0"] < F_Np
        return {
            k: float(exact_value(e, cf["symbols"], vals))
            if c_exists or k not in ("jump", "ABC")
            else math.nan
            for k, e in cf["exprs"].items()
        }
    import mpmath as mp  # optional (the test extra): imported where it is used

    with mp.workdps(REF_DPS):
        if case["model"] == "sphere":
            return _sphere_reference(p, case["F_N0"], case["g_A"], F_Np)
        return _gaussian_reference(p, case["F_N0"], case["g_A"], F_Np)


def _gw(n, t):
    """F_n(t) = ∫_t^∞ (s − t)^n φ(s) ds by parabolic-cylinder functions."""
    import mpmath as mp

    return mp.gamma(n + 1) * mp.exp(-t * t / 4) * mp.pcfd(-n - 1, t) / mp.sqrt(2 * mp.pi)


def _gaussian_reference(p, F_N0, g_A, F_Np) -> dict[str, float]:
    """Gaussian heights: d0 = d + g_N0 frozen along AB, g_T = (μλ/σ*)(d0 − d),
    F_T = μK[J(d) − J(d0)], loop integrals with ∫J = (2/5)ΔJ_{5/2}."""
    import mpmath as mp

    s, nu, mu = mp.mpf(p["sigma"]), mp.mpf(p["nu"]), mp.mpf(p["mu"])
    E_star = mp.mpf(p["E"]) / (2 * (1 - nu**2))
    K = 4 * E_star * mp.sqrt(mp.mpf(p["radius"])) * mp.mpf(p["density"]) * p["nominal_area"] / 3
    c = mu * (2 - nu) / (2 * (1 - nu))  # μλ/σ*: g_T = c (d0 − d)
    F_N0, g_A, F_Np = mp.mpf(F_N0), mp.mpf(g_A), mp.mpf(F_Np)

    def J(h, n=None):
        n = mp.mpf(3) / 2 if n is None else n
        return s**n * _gw(n, h / s)

    def sep(load):
        return mp.findroot(lambda h: mp.log(K * J(h)) - mp.log(load), 0)

    d_A, d_B = sep(F_N0), sep(F_Np)
    d0_A, d0_D = d_A + g_A / c, d_B + g_A / c
    F_A = mu * K * (J(d_A) - J(d0_A))
    F_D = mu * K * (J(d_B) - J(d0_D))
    five2 = mp.mpf(5) / 2
    pref = mu * c * K
    along_ab = -pref * (2 * (J(d_A, five2) - J(d_B, five2)) / 5 - J(d0_A) * (d_B - d_A))

    def reload(d0):  # ∫ F_T dg_T along BC from B to the level d0
        return pref * (J(d_B) * (d0 - d0_A) - 2 * (J(d0_A, five2) - J(d0, five2)) / 5)

    out = {"dg": c * (d_B - d_A), "dF": mu * (F_N0 - F_Np), "drop": F_A - F_D}
    out["ABD"] = -(along_ab + reload(d0_D))
    out["jump"] = out["ABC"] = mp.nan
    if F_A < mu * F_Np:
        target = J(d_B) - F_A / (mu * K)
        d0_C = mp.findroot(lambda h: mp.log(J(h)) - mp.log(target), d0_D)
        g_C = c * (d0_C - d_B)
        out["jump"] = g_C - g_A
        out["ABC"] = -(along_ab + reload(d0_C) - F_A * (g_C - g_A))
    return {k: float(v) for k, v in out.items()}


def _sphere_reference(p, F_N0, g_A, F_Np) -> dict[str, float]:
    """Two spheres: F_N = k a³, F_T = μk(a³ − c³), g_T = μκ(a² − c²) with k = 4E*/(3R*),
    κ = (2 − ν)E*/(2GR*), R* = R/2; c frozen along AB; the loop integrals in closed form."""
    import mpmath as mp

    R, E, nu, mu = (mp.mpf(p[k]) for k in ("radius", "E", "nu", "mu"))
    E_star, G, Rs = E / (2 * (1 - nu**2)), E / (2 * (1 + nu)), R / 2
    k, kap = 4 * E_star / (3 * Rs), (2 - nu) * E_star / (2 * G * Rs)
    F_N0, g_A, F_Np = mp.mpf(F_N0), mp.mpf(g_A), mp.mpf(F_Np)
    a0, a1 = mp.cbrt(F_N0 / k), mp.cbrt(F_Np / k)
    cA = mp.sqrt(a0**2 - g_A / (mu * kap))
    F_A = mu * k * (a0**3 - cA**3)
    m2 = 2 * mu * mu * k * kap
    along_ab = m2 * ((a1**5 - a0**5) / 5 - cA**3 * (a1**2 - a0**2) / 2)

    def reload(c):  # ∫ F_T dg_T along BC from B to the stick radius c
        return -m2 * (a1**3 * (c**2 - cA**2) / 2 - (c**5 - cA**5) / 5)

    out = {"dg": mu * kap * (a0**2 - a1**2), "dF": mu * (F_N0 - F_Np)}
    out["drop"] = out["ABD"] = out["jump"] = out["ABC"] = mp.nan
    if a1**2 > g_A / (mu * kap):  # D exists
        cD = mp.sqrt(a1**2 - g_A / (mu * kap))
        out["drop"] = F_A - mu * k * (a1**3 - cD**3)
        out["ABD"] = -(along_ab + reload(cD))
    if F_A < mu * F_Np:
        cC = mp.cbrt(a1**3 - F_A / (mu * k))
        g_C = mu * kap * (a1**2 - cC**2)
        out["jump"] = g_C - g_A
        out["ABC"] = -(along_ab + reload(cC) - F_A * (g_C - g_A))
    return {k: float(v) for k, v in out.items()}


def rel_error(got: float, want: float) -> float:
    """|got − want|/|want| (0 where both are missing, inf where only one is)."""
    if math.isnan(want) and math.isnan(got):
        return 0.0
    if math.isnan(want) or math.isnan(got):
        return math.inf
    return abs(got - want) / abs(want)


# ------------------------------------------------------------------------------------------
# the exact exponents: series of the exponential closed forms in d


def exponential_series(case: dict, terms: int = 2) -> dict[str, dict]:
    """Each quantity's series in d (F'_N = F_N0(1 − d), g_A = x_A λ μ) from the sympy closed
    forms: the exponent of its first term, the first ``terms`` terms (text) and the leading
    coefficient at the scene's parameters."""
    import sympy as sp

    from cusp.verification import SYMBOLS as S

    cf = exponential_closed_forms()
    d, x_A = sp.symbols("d x_A", positive=True)
    sub = {S["Fp_N"]: S["F_N0"] * (1 - d), S["g_A"]: x_A * S["lambda"] * S["mu"]}
    p = case["params"]
    lam = build_body(case["model"], **p).lam
    scene = {S["sigma"]: p["sigma"], S["mu"]: p["mu"], S["lambda"]: lam, S["F_N0"]: case["F_N0"]}
    scene[x_A] = case["g_A"] / (p["mu"] * lam)
    out = {}
    for key, expr in cf["exprs"].items():
        e = sp.expand_log(expr.subs(sub), force=True)
        ser = sp.series(e, d, 0, 5).removeO()
        coeffs = [(k, sp.factor(sp.simplify(ser.coeff(d, k)))) for k in range(5)]
        nonzero = [(k, c) for k, c in coeffs if c != 0]
        out[key] = {
            "exponent": nonzero[0][0],
            "terms": " + ".join(f"({sp.sstr(c)})·d^{k}" for k, c in nonzero[:terms]),
            "leading": float(nonzero[0][1].subs(scene)),
        }
    return out
