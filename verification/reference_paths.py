"""Self-checking high-precision references of the contact-loss path for every body that has
one (docs/physics.md §7): rough surfaces with exponential, Gaussian or Weibull heights, and
the Hertz–Mindlin sphere. The references of the extremes grid (``scripts/bench_extremes.py``,
``tests/models/test_extremes.py``).

Written from the physics in mpmath, independently of :mod:`cusp.models`: the plain formulas
of the paper (the loading curve, the Mindlin–Deresiewicz rule as an invariant stick-threshold
level d0 along AB, Eq 32 as printed, the energies as loop integrals of F_T dg_T with
∫_a^b J = (2/5)[J_{5/2}(a) − J_{5/2}(b)]), differences of nearly equal numbers included.
Those lose digits at tiny slips and reductions, so every value is computed twice, at a
working precision and 30 digits above it, and the precision is raised until the two agree
to ``digits`` (default 30) in every value; what is returned is the second evaluation.

The height densities (σ* the standard deviation, heights in µm):

* ``"exponential"``: Φ = e^{−z/σ*}/σ* (Eq 1): M_n(h) = Γ(n + 1) σ*^n e^{−h/σ*};
* ``"gaussian"``: M_n(h) = σ*^n F_n(h/σ*), F_n(t) = Γ(n + 1) e^{−t²/4} D_{−n−1}(t)/√(2π)
  (parabolic-cylinder functions), and for t < −30 (where mpmath's D_ν loses its digits)
  E[(|t| + S)^n] over a standard normal S, by its binomial series in the moments of S while
  that converges to the working precision, else by quadrature;
* ``("weibull", k)``: Φ = (k/s)(z/s)^{k−1} e^{−(z/s)^k}, z > 0, s = σ*/√(Γ(1 + 2/k) −
  Γ(1 + 1/k)²): Q and A by incomplete gamma functions, M_{3/2} and M_{5/2} by tanh-sinh
  quadrature,

with M_n(h) = ∫_h^∞ (z − h)^n Φ dz (Q = M_0, A = M_1, J = M_{3/2}), and the slipping
summits' share of the contact area, 1 − Â_ST, by quadrature of its definition
∫_d^{d0} (z − d) Φ dz / A(d) (as 1 − Â_ST it cancels to exactly 0 at every precision where
it is below 10^−dps: two zeros agree, and the self-check cannot see it).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import mpmath as mp

from .oracles import scaled_quad

__all__ = ["rough_path", "sphere_path", "self_checked"]

#: the working precision is raised up to this many digits before giving up
MAX_DPS = 400


def self_checked(compute: Callable[[int], dict], digits: int = 30, dps: int = 50) -> dict:
    """``compute(dps)`` (a nested dict of mpf or None) at ``dps`` and ``dps + 30`` digits,
    the precision doubled until both agree to ``digits`` in every value; returns the second.
    Raises ArithmeticError beyond :data:`MAX_DPS`."""
    while dps <= MAX_DPS:
        a, b = compute(dps), compute(dps + 30)
        with mp.workdps(dps + 30):
            if _agree(a, b, mp.mpf(10) ** -digits):
                return b
        dps *= 2
    raise ArithmeticError(f"the reference did not settle to {digits} digits by {MAX_DPS} digits")


def _agree(a: Any, b: Any, tol) -> bool:
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(_agree(a[k], b[k], tol) for k in a)
    if a is None or b is None:
        return a is None and b is None
    if isinstance(a, bool):
        return a == b
    return abs(a - b) <= tol * abs(b) or a == b


def _pdf(heights, s):
    """The height density Φ(z) [1/µm] (module docstring)."""
    if heights == "exponential":
        return lambda z: mp.exp(-z / s) / s
    if heights == "gaussian":
        return lambda z: mp.npdf(z / s) / s
    k = mp.mpf(heights[1])
    scale = s / mp.sqrt(mp.gamma(1 + 2 / k) - mp.gamma(1 + 1 / k) ** 2)
    return lambda z: (
        (k / scale) * (z / scale) ** (k - 1) * mp.exp(-((z / scale) ** k)) if z > 0 else 0
    )


def _slipping(heights, s, d, d0):
    """∫_d^{d0} (z − d) Φ(z) dz [µm]: A_r − A_ST over π ρ* η A_n, the contact area of the
    summits that slide (w < g_N0), by its definition (1 − Â_ST = this over A(d) would
    cancel to 0 at every working precision where it is below 10^−dps)."""
    if heights == "gaussian" and d < d0:
        return _slipping_gaussian(s, d, d0)
    pdf = _pdf(heights, s)
    lo = max(d, mp.mpf(0)) if heights not in ("exponential", "gaussian") else d
    if not lo < d0:
        return mp.mpf(0)
    # (split where the density lives: a rule over [d, d0] 8000 σ* wide saw none of it)
    inner = [lo + k * s for k in (1, 4, 16)] + [k * s for k in (-40, -10, -3, 0, 3, 10, 40)]
    points = [lo, *sorted({x for x in inner if lo < x < d0}), d0]
    return sum(scaled_quad(lambda z: (z - d) * pdf(z), [a, b]) for a, b in zip(points, points[1:]))


def _slipping_gaussian(s, d, d0):
    """:func:`_slipping` of the Gaussian density in closed form, s ∫_t^{t0} (u − t) φ(u) du =
    s [φ(t) − φ(t0) − t (Φ(t0) − Φ(t))] (t = d/s, t0 = d0/s; Φ(t0) − Φ(t) as Q(t) − Q(t0)
    right of the mean), evaluated with as many digits beyond the working precision as its
    terms cancel (measured on the terms, raised until the value keeps 15 of them)."""
    extra = 20
    while extra <= 4000:
        with mp.extradps(extra):
            t, t0 = d / s, d0 / s
            dP = mp.ncdf(-t) - mp.ncdf(-t0) if t > 0 else mp.ncdf(t0) - mp.ncdf(t)
            terms = (mp.npdf(t), mp.npdf(t0), t * dP)
            value = terms[0] - terms[1] - terms[2]
            big = max(abs(x) for x in terms)
            if value > 0 and big < value * mp.mpf(10) ** (extra - 15):
                return +(s * value)
            lost = int(mp.log10(big / value)) if value > 0 else 2 * extra
        extra = max(2 * extra, lost + 30)
    raise ArithmeticError("the Gaussian slipping area did not settle")


def _moments(heights, s):
    """M(n, h) for the density ``heights`` of standard deviation s (module docstring),
    each (n, h) computed once."""
    moment = _moment(heights, s)
    cache: dict[tuple, Any] = {}

    def cached(n, h):
        key = (n, h, mp.mp.prec)
        if key not in cache:
            cache[key] = moment(n, h)
        return cache[key]

    return cached


def _moment(heights, s):
    if heights == "exponential":
        return lambda n, h: mp.gamma(n + 1) * s**n * mp.exp(-h / s)
    if heights == "gaussian":

        def gauss(n, h):
            t = h / s
            if t < -30:  # (pcfd loses its digits there)
                f = _far_left(n, t)
            else:
                f = mp.gamma(n + 1) * mp.exp(-t * t / 4) * mp.pcfd(-n - 1, t)
                f /= mp.sqrt(2 * mp.pi)
            return s**n * f

        return gauss
    name, k = heights
    if name != "weibull":
        raise ValueError(f"unknown heights {heights!r}")
    k = mp.mpf(k)
    scale = s / mp.sqrt(mp.gamma(1 + 2 / k) - mp.gamma(1 + 1 / k) ** 2)

    def weibull(n, h):
        a = max(h, mp.mpf(0))
        if n == 0:
            return mp.exp(-((a / scale) ** k))
        if n == 1:  # ∫_h^∞ Q: (−h)+ plus (s/k) Γ(1/k, (a/s)^k)
            return (a - h) + scale / k * mp.gammainc(1 / k, (a / scale) ** k)

        def f(z):
            return (z - h) ** n * (k / scale) * (z / scale) ** (k - 1) * mp.exp(-((z / scale) ** k))

        return scaled_quad(f, [a, a + scale / 4, a + scale, a + 4 * scale, mp.inf])

    return weibull


def _far_left(n, t):
    """F_n(t) = ∫ (x − t)^n φ(x) dx for t < −30: E[(|t| + S)^n] over a standard normal S
    summed as Σ_k C(n, 2k) E[S^{2k}] |t|^{n−2k} (E S^{2k} = (2k − 1)!!) while its terms fall
    below the working precision, which they do before the series turns (near k = t²/2) for
    t² > 9.2 digits; otherwise the integral by quadrature over |x| ≤ 50 (the rest is below
    φ(50) ~ 1e-544 of it)."""
    tol = mp.mpf(10) ** (-mp.mp.dps - 5)
    if t * t > 9.2 * (mp.mp.dps + 10):
        a = -t
        total, term, k = mp.mpf(1), mp.mpf(1), 0
        while abs(term) > tol * abs(total):
            k += 1
            term *= (n - 2 * k + 2) * (n - 2 * k + 1) / ((2 * k) * (2 * k - 1)) * (2 * k - 1)
            term /= a * a
            total += term
        return a**n * total
    cut = mp.mpf(50)
    pts = [max(t, -cut)] + [x for x in (-10, -3, 0, 3, 10) if x > t] + [cut]
    return scaled_quad(lambda x: (x - t) ** n * mp.npdf(x), pts)


def _root(f, df, lo, hi, guess=None):
    """The root of an increasing f (derivative df) in a bracket grown from [lo, hi], by
    Newton's method from ``guess`` (the root at a lower precision) or from a bisected
    bracket, bisecting whenever a step leaves the bracket."""
    if guess is None:  # (the bracket at 20 digits: a Weibull moment by quadrature at the
        # working precision is 0.4 s, and the bracket needs dozens of them)
        with mp.workdps(20):
            step = hi - lo
            while f(lo) > 0:
                lo, step = lo - step, 2 * step
            while f(hi) < 0:
                hi, step = hi + step, 2 * step
            for _ in range(40):
                mid = (lo + hi) / 2
                lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
        # (widened well beyond the 20-digit root's error, which may leave the root just
        # outside the bisected bracket: Newton's steps then fell back to bisection)
        margin = mp.mpf(10) ** -9 * (1 + abs(lo) + abs(hi))
        lo, hi = lo - margin, hi + margin
        x = (lo + hi) / 2
    else:
        x, lo, hi = guess, None, None
    tol = mp.mpf(10) ** (-mp.mp.dps + 3)
    for _ in range(200):
        fx = f(x)
        if lo is not None:
            lo, hi = (x, hi) if fx < 0 else (lo, x)
        new = x - fx / df(x)
        if lo is not None and not lo <= new <= hi:  # (a root hit exactly is its bound)
            new = (lo + hi) / 2
        if abs(new - x) <= tol * (1 + abs(x)):
            return new
        x = new
    raise ArithmeticError("the reference's root did not converge")


def rough_path(heights, sigma, nu, mu, E, radius, density, nominal_area, F_N0, g_A, F_Np, *,
               reading="printed", digits=30):  # fmt: skip
    """Points O, A, B, C, D (``{g_T, F_T, F_N, A_SL, d, d0}``, None where absent) and the
    energies (``snap_back``, ``snap_through``; None without D or C) of the path of a rough
    surface (module docstring), self-checked to ``digits``."""
    args = (heights, sigma, nu, mu, E, radius, density, nominal_area, F_N0, g_A, F_Np, reading)
    roots: dict[str, Any] = {}  # each root at the last precision: the next one's start
    return self_checked(lambda dps: _rough(dps, roots, *args), digits)


def _rough(dps, roots, heights, sigma, nu, mu, E, radius, density, nominal_area, F_N0, g_A,
           F_Np, reading):  # fmt: skip
    with mp.workdps(dps):
        s, nu, mu = mp.mpf(sigma), mp.mpf(nu), mp.mpf(mu)
        E_star = mp.mpf(E) / (2 * (1 - nu**2))
        K = mp.mpf(4) / 3 * E_star * mp.sqrt(mp.mpf(radius)) * mp.mpf(density)
        K *= mp.mpf(nominal_area)
        lam = s * (2 - nu) / (2 * (1 - nu))
        F_N0, g_A, F_Np = mp.mpf(F_N0), mp.mpf(g_A), mp.mpf(F_Np)
        M = _moments(heights, s)
        half3, half5 = mp.mpf(3) / 2, mp.mpf(5) / 2

        def J(h):
            return M(half3, h)

        def dlog(h):  # −d log J/dh
            return half3 * M(mp.mpf(1) / 2, h) / J(h)

        def root(key, f, lo, hi):
            roots[key] = _root(f, dlog, lo, hi, roots.get(key))
            return roots[key]

        def sep(key, load):
            return root(key, lambda h: mp.log(load) - mp.log(K * J(h)), -s, s)

        d_A, d_B = sep("d_A", F_N0), sep("d_B", F_Np)
        A_A = M(1, d_A)

        def point(d, d0, load):
            slipping = _slipping(heights, s, d, d0) / M(1, d)  # 1 − Â_ST (Eqs 13, 14)
            if reading == "printed":
                a_sl = slipping + (A_A - M(1, d)) / A_A
            else:
                a_sl = 1 - (1 - slipping) * M(1, d) / A_A
            g_T = mu * lam / s * (d0 - d)
            return {"g_T": g_T, "F_T": mu * K * (J(d) - J(d0)), "F_N": load, "A_SL": a_sl,
                    "d": d, "d0": d0}  # fmt: skip

        gap = g_A * s / (mu * lam)
        d0_A = d_A + gap
        pts: dict[str, Any] = {"O": point(d_A, d_A, F_N0), "A": point(d_A, d0_A, F_N0)}
        pts["B"] = point(d_B, d0_A, F_Np)
        pts["D"] = point(d_B, d_B + gap, F_Np)
        F_A = pts["A"]["F_T"]
        pref = mu * K * mu * lam / s

        def along_ab():  # ∫ F dg from A to B (d from d_A to d_B at d0 = d0_A)
            return -pref * (2 / mp.mpf(5) * (M(half5, d_A) - M(half5, d_B)) - J(d0_A) * (d_B - d_A))

        def reload(d0_end):  # ∫ F dg from B along BC to d0 = d0_end
            return pref * (
                J(d_B) * (d0_end - d0_A) - 2 / mp.mpf(5) * (M(half5, d0_A) - M(half5, d0_end))
            )

        ab = along_ab()
        energy: dict[str, Any] = {"snap_back": -(ab + reload(d_B + gap)), "snap_through": None}
        pts["C"] = None
        if F_A < mu * F_Np:
            target = J(d_B) - F_A / (mu * K)
            d0_C = root("d0_C", lambda h: mp.log(target) - mp.log(J(h)), d_B + gap, d_B + gap + s)
            pts["C"] = point(d_B, d0_C, F_Np)
            g_C = pts["C"]["g_T"]
            energy["snap_through"] = -(ab + reload(d0_C) - F_A * (g_C - g_A))
        return {"points": pts, "energy": energy}


def sphere_path(radius, E, nu, mu, F_N0, g_A, F_Np, *, digits=30):
    """The sphere's points (``{g_T, F_T, F_N, A_SL, a, c}``) and energies, the Hertz–Mindlin
    path of :func:`cusp.verification.oracles.sphere_path` self-checked to ``digits``."""
    from .oracles import sphere_path as path

    def compute(dps):
        pts, energy = path(radius, E, nu, mu, F_N0, g_A, F_Np, dps=dps)
        return {"points": pts, "energy": energy}

    return self_checked(compute, digits)
