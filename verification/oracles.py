"""Independent high-precision references for the contact-loss path (docs/physics.md §7): the
test oracles of :mod:`cusp.models.contact_loss` and :mod:`cusp.models.manifold`, also used by
the benchmark scripts.

- :func:`exponential_closed_form`: the sympy closed forms of the exponential path
  (:func:`~.exponential.contact_loss_path`) and of its manifold's events
  (:func:`~.exponential.manifold_events`), evaluated exactly at the binary inputs;
- :func:`gaussian_path` and :func:`sphere_path`: the path of a Gaussian rough surface and of
  a Hertz–Mindlin sphere in mpmath.

Written from the physics, not from ``models``: mpmath at 40 digits, with the stick-threshold
level d0 = d + g_N0 invariant along AB (the Mindlin–Deresiewicz rule keeps μF_N − F_T, hence
J(d0), fixed) and the released energies as loop integrals of F_T dg_T, using
∫_a^b J(h) dh = (2/5)[J_{5/2}(a) − J_{5/2}(b)] (since dJ_{5/2}/dh = −(5/2) J). The Gaussian
GW functions come from parabolic-cylinder functions, F_n(t) = Γ(n+1) e^{−t²/4} D_{−n−1}(t)
/ √(2π), cross-checked by quadrature in the tests.
"""

from __future__ import annotations

import mpmath as mp

from .common import SYMBOLS
from .exponential import contact_loss_path, manifold_events
from .implementation import exact_value

DPS = 40


def scaled_quad(f, points):
    """∫ f over the intervals between ``points`` by ``mp.quad``, with f divided by its
    largest magnitude at points inside the finite intervals: mp.quad's tolerance is absolute
    (10^−dps), so an integrand of 1e-283 was accepted after one level, 4e-9 off."""
    finite = [p for p in points if mp.isfinite(p)]
    inside = [a + (b - a) * k / 8 for a, b in zip(finite[:-1], finite[1:]) for k in (1, 4, 7)]
    values = [abs(f(p)) for p in inside]
    scale = max((v for v in values if mp.isfinite(v)), default=mp.mpf(0)) or mp.mpf(1)
    return scale * mp.quad(lambda z: f(z) / scale, points)


def gw(n, t):
    """F_n(t) = ∫_t^∞ (s − t)^n φ(s) ds."""
    t = mp.mpf(t)
    return mp.gamma(n + 1) * mp.exp(-t * t / 4) * mp.pcfd(-n - 1, t) / mp.sqrt(2 * mp.pi)


def gaussian_path(sigma, nu, mu, E, radius, density, nominal_area, F_N0, g_A, F_Np):
    """Points O, A, B, C, D ({g_T, F_T, F_N, A_SL, d, d0}, None if absent) and energies."""
    with mp.workdps(DPS):
        s, nu, mu = mp.mpf(sigma), mp.mpf(nu), mp.mpf(mu)
        E_star = mp.mpf(E) / (2 * (1 - nu**2))
        K = (
            mp.mpf(4)
            / 3
            * E_star
            * mp.sqrt(mp.mpf(radius))
            * mp.mpf(density)
            * mp.mpf(nominal_area)
        )
        lam = s * (2 - nu) / (2 * (1 - nu))
        F_N0, g_A, F_Np = mp.mpf(F_N0), mp.mpf(g_A), mp.mpf(F_Np)

        def J(h, n=None):
            n = mp.mpf(3) / 2 if n is None else n
            return s**n * gw(n, h / s)

        def area(h):
            return s * gw(1, h / s)

        def tail(h):
            return gw(0, h / s)

        def sep(load):
            return mp.findroot(lambda h: mp.log(K * J(h)) - mp.log(load), 0)

        def slip(d, d0):
            return mu * lam / s * (d0 - d)

        def force(d, d0):
            return mu * K * (J(d) - J(d0))

        d_A = sep(F_N0)

        def a_sl(d, d0):
            a_st = (area(d0) + (d0 - d) * tail(d0)) / area(d)
            return (1 - a_st) + (area(d_A) - area(d)) / area(d_A)

        def pt(d, d0, load):
            return {
                "g_T": slip(d, d0),
                "F_T": force(d, d0),
                "F_N": load,
                "A_SL": a_sl(d, d0),
                "d": d,
                "d0": d0,
            }

        d0_A = d_A + g_A * s / (mu * lam)
        F_A = force(d_A, d0_A)
        d_B = sep(F_Np)
        pts = {"O": pt(d_A, d_A, F_N0), "A": pt(d_A, d0_A, F_N0), "B": pt(d_B, d0_A, F_Np)}
        d0_D = d_B + g_A * s / (mu * lam)
        pts["D"] = pt(d_B, d0_D, F_Np)
        c_exists = F_A < mu * F_Np
        five2 = mp.mpf(5) / 2
        pref = mu**2 * lam * K / s
        # A -> B (d from d_A to d_B at d0 = d0_A), then B -> D along the reloading curve
        along_ab = -pref * (mp.mpf(2) / 5 * (J(d_A, five2) - J(d_B, five2)) - J(d0_A) * (d_B - d_A))

        def reload(d0_end):
            return pref * (
                J(d_B) * (d0_end - d0_A) - mp.mpf(2) / 5 * (J(d0_A, five2) - J(d0_end, five2))
            )

        energy = {"snap_back": -(along_ab + reload(d0_D)), "snap_through": None}
        if c_exists:
            target = J(d_B) - F_A / (mu * K)
            d0_C = mp.findroot(lambda h: mp.log(J(h)) - mp.log(target), d0_D)
            pts["C"] = pt(d_B, d0_C, F_Np)
            g_C = slip(d_B, d0_C)
            energy["snap_through"] = -(along_ab + reload(d0_C) - F_A * (g_C - g_A))
        else:
            pts["C"] = None
        return pts, energy


def sphere_path(radius, E, nu, mu, F_N0, g_A, F_Np, *, dps=DPS):
    """Hertz–Mindlin sphere: Eq 2 with Hertz, c invariant along AB (μF_N − F_T ∝ c³); at
    ``dps`` digits. No D (and no C, no energies) where g_A is beyond the gross-sliding slip
    under F'_N."""
    with mp.workdps(dps):
        R, E, nu, mu = (mp.mpf(v) for v in (radius, E, nu, mu))
        F_N0, g_A, F_Np = mp.mpf(F_N0), mp.mpf(g_A), mp.mpf(F_Np)
        E_star = E / (2 * (1 - nu**2))
        G = E / (2 * (1 + nu))

        def a_of(load):
            return mp.cbrt(3 * load * (R / 2) / (4 * E_star))

        def g_lim(load):
            return 3 * (2 - nu) * mu * load / (8 * G * a_of(load))

        def slip(F_T, load):
            return g_lim(load) * (1 - (1 - F_T / (mu * load)) ** (mp.mpf(2) / 3))

        def force(g, load):
            return mu * load * (1 - (1 - g / g_lim(load)) ** (mp.mpf(3) / 2))

        a0 = a_of(F_N0)

        def pt(F_T, load):
            a = a_of(load)
            c = a * mp.cbrt(1 - F_T / (mu * load))
            a_sl = 1 - (c / a) ** 2 + 1 - (a / a0) ** 2
            return {"g_T": slip(F_T, load), "F_T": F_T, "F_N": load, "A_SL": a_sl, "a": a, "c": c}

        F_A = force(g_A, F_N0)
        F_B = F_A - mu * (F_N0 - F_Np)
        pts = {"O": pt(mp.mpf(0), F_N0), "A": pt(F_A, F_N0), "B": pt(F_B, F_Np)}
        if g_A >= g_lim(F_Np):  # the spheres slide under F'_N before g_A: no D, no C
            pts["C"] = pts["D"] = None
            return pts, {"snap_back": None, "snap_through": None}
        pts["D"] = pt(force(g_A, F_Np), F_Np)
        g_B = pts["B"]["g_T"]
        # A -> B parametrised by the load f: F = F_A - mu (F_N0 - f), g = slip(F, f)
        along_ab = scaled_quad(
            lambda f: (
                (F_A - mu * (F_N0 - f)) * mp.diff(lambda ff: slip(F_A - mu * (F_N0 - ff), ff), f)
            ),
            [F_N0, F_Np],
        )
        b_to_d = scaled_quad(lambda g: force(g, F_Np), [g_B, g_A])
        energy = {"snap_back": -(along_ab + b_to_d), "snap_through": None}
        if F_A < mu * F_Np:
            pts["C"] = pt(F_A, F_Np)
            g_C = pts["C"]["g_T"]
            b_to_c = scaled_quad(lambda g: force(g, F_Np), [g_B, g_C])
            energy["snap_through"] = -(along_ab + b_to_c - F_A * (g_C - g_A))
        else:
            pts["C"] = None
        return pts, energy


def exponential_closed_form(
    key, mu, F_Np, *, sigma=2.0, nu=0.3, F_N0=1000.0, g_A=0.34, event=False
):
    """The closed form ``key`` (an event's if ``event``) at μ = ``mu``, F'_N = ``F_Np``,
    evaluated exactly at the binary inputs with λ = σ*(2 − ν)/(2(1 − ν)) as the model forms
    it in floats. Defaults: the Fig 6 scene (σ* = 2 µm, ν = 0.3, F_N0 = 1000 N,
    g_A = 0.34 µm)."""
    S = SYMBOLS
    syms = (S["sigma"], S["mu"], S["lambda"], S["F_N0"], S["g_A"], S["Fp_N"])
    lam = sigma * (2.0 - nu) / (2.0 * (1.0 - nu))
    forms = manifold_events() if event else contact_loss_path()
    return float(exact_value(forms[key], syms, (sigma, mu, lam, F_N0, g_A, F_Np)))
