"""mpmath references from the DEFINING integrals of the paper (not from the closed forms).

Every function takes the exact binary float the code receives (converted with mpmath.mpf)
and works at ``mp.dps`` ≥ 50. Provenance of each reference:

* exponential (Eqs 7, 9, 14 with Φ = e^{−z/σ*}/σ*): with v = (z − d)/σ*, x = g_N0/σ*,
  F̂_T = 1 − e^{−x}                 (so x = −log1p(−F̂_T), mpmath's accurate log1p)
  F̂_ST = ∫_x^∞ [v^{3/2} − (v − x)^{3/2}] e^{−v} dv / Γ(5/2)   (stick force, Eq 7 over Eq 11)
  Â_ST = ∫_x^∞ v e^{−v} dv / ∫_0^∞ v e^{−v} dv                 (Eq 14 over Eq 13)
  The bracket is written as x(3w² + 3wx + x²)/((w + x)^{3/2} + w^{3/2}), w = v − x, an exact
  identity that keeps F̂_T = 1e-300 meaningful at 50 digits.
* sphere (Mindlin traction, a = p0 = 1, F_N = 2π/3): in the stick circle r < k = c/a,
  q(r)/μ = √(1 − r²) − k√(1 − r²/k²) = (1 − k²)/(√(1 − r²) + √(k² − r²)), k³ = 1 − F̂_T
  (Eq 19, from ∫ q dA = F_T); F̂_ST = ∫_0^k 2πr q dr / (μ F_N); Â_ST = πk²/π.
* cylinder (per unit length, a = p0 = 1, F_N = π/2): q(x)/μ = (1 − k²)/(√(1 − x²) + √(k² − x²))
  on |x| < k, k² = 1 − F̂_T (Eq 26); F̂_ST = ∫_{−k}^{k} q dx / (μ F_N); Â_ST = 2k/2.
* flat: every point carries μ p F̂_T: F̂_ST = F̂_T and Â_ST = 1 for F̂_T < 1; both 0 at 1.
* Gaussian (φ the standard normal pdf, lengths in units of σ*, t = d/σ*):
  J(t) = ∫_t^∞ (s − t)^{3/2} φ ds, A(t) = ∫_t^∞ (s − t) φ ds; δ = g_N0/σ* solves
  J(t + δ) = (1 − F̂_T) J(t) (bisection to 35 digits);
  F̂_ST = ∫_{t+δ}^∞ [(s − t)^{3/2} − (s − t − δ)^{3/2}] φ ds / J(t);
  Â_ST = ∫_{t+δ}^∞ (s − t) φ ds / A(t).
"""

from __future__ import annotations

import mpmath as mp

DPS = 50


def exponential(F: float):
    with mp.workdps(DPS):
        F = mp.mpf(F)
        if F == 1:  # full slip
            return mp.mpf(0), mp.mpf(0)
        if F == 0:  # no tangential load: all stick
            return mp.mpf(0), mp.mpf(1)
        x = -mp.log1p(-F)

        def bracket(w):
            return x * (3 * w * w + 3 * w * x + x * x) / ((w + x) ** 1.5 + w**1.5)

        # w = u²: removes the √w end-point behaviour (mp.quad's tanh-sinh then converges)
        r = mp.sqrt(x)
        pts = sorted({mp.mpf(0), min(r, 1), min(10 * r, 2), mp.mpf(2), mp.mpf(5), mp.inf})
        # mp.quad's tolerance is absolute: integrate bracket/x (order 1), multiply back
        stick = mp.quad(lambda u: 2 * u * bracket(u * u) / x * mp.exp(-(u * u + x)), pts)
        stick *= x / mp.gamma(2.5)
        area = mp.quad(lambda v: v * mp.exp(-v), [x, x + 1, x + 10, mp.inf])
        return stick, area


def _dps(F) -> int:
    """Enough digits that k = c/a, a number 1 − O(F̂_T), still carries DPS of them."""
    return DPS + max(0, int(-mp.log10(mp.mpf(F)))) if F > 0 else DPS


def sphere(F: float):
    with mp.workdps(_dps(F)):
        F = mp.mpf(F)
        if F == 1:  # full slip
            return mp.mpf(0), mp.mpf(0)
        if F == 0:  # no tangential load: all stick
            return mp.mpf(0), mp.mpf(1)
        k = mp.cbrt(1 - F)
        one_minus_k2 = -mp.expm1(mp.log1p(-F) * 2 / 3)

        def q(r):
            return one_minus_k2 / (mp.sqrt(1 - r * r) + mp.sqrt(k * k - r * r))

        # r = k sin θ removes the 1/√(k − r) end-point behaviour
        def integrand(th):
            r = k * mp.sin(th)
            return 2 * mp.pi * r * q(r) / one_minus_k2 * k * mp.cos(th)

        # tolerance of mp.quad is absolute: integrate q/(1 − k²) (order 1), multiply back
        stick = mp.quad(integrand, [0, mp.pi / 4, mp.pi / 2]) * one_minus_k2 / (2 * mp.pi / 3)
        return stick, k * k


def cylinder(F: float):
    with mp.workdps(_dps(F)):
        F = mp.mpf(F)
        if F == 1:  # full slip
            return mp.mpf(0), mp.mpf(0)
        if F == 0:  # no tangential load: all stick
            return mp.mpf(0), mp.mpf(1)
        k = mp.sqrt(1 - F)

        def q(x):
            return F / (mp.sqrt(1 - x * x) + mp.sqrt(k * k - x * x))

        # x = k sin θ removes the 1/√(k − |x|) end-point behaviour
        # q/F̂_T is order 1 (mp.quad's tolerance is absolute)
        stick = mp.quad(
            lambda th: q(k * mp.sin(th)) / F * k * mp.cos(th), [0, mp.pi / 4, mp.pi / 2]
        )
        stick *= 2 * F / (mp.pi / 2)
        return stick, k


def flat(F: float):
    F = mp.mpf(F)
    return (F, mp.mpf(1)) if F < 1 else (mp.mpf(0), mp.mpf(0))


BODIES = {"exponential": exponential, "sphere": sphere, "cylinder": cylinder, "flat": flat}


def _phi(s):
    return mp.exp(-s * s / 2) / mp.sqrt(2 * mp.pi)


def gaussian_J(t):
    t = mp.mpf(t)
    return mp.quad(lambda s: (s - t) ** 1.5 * _phi(s), [t, t + 1, t + 4, t + 12, mp.inf])


def gaussian_A(t):
    t = mp.mpf(t)
    return mp.quad(lambda s: (s - t) * _phi(s), [t, t + 1, t + 4, t + 12, mp.inf])


def gaussian(t: float, F: float, dps: int = 40):
    """(F̂_ST, Â_ST) at t = d/σ*, F̂_T = F, from the defining integrals."""
    with mp.workdps(dps):
        t, F = mp.mpf(t), mp.mpf(F)
        target = (1 - F) * gaussian_J(t)
        lo, hi = mp.mpf(0), mp.mpf(1)
        while gaussian_J(t + hi) > target:
            hi *= 2
        for _ in range(160):
            mid = (lo + hi) / 2
            if gaussian_J(t + mid) > target:
                lo = mid
            else:
                hi = mid
            if hi - lo < mp.mpf(10) ** (-dps + 5) * hi:
                break
        t0 = t + (lo + hi) / 2
        d = t0 - t

        def bracket(s):
            w = s - t0
            return d * (3 * w * w + 3 * w * d + d * d) / ((w + d) ** 1.5 + w**1.5)

        stick = mp.quad(lambda s: bracket(s) * _phi(s), [t0, t0 + 1, t0 + 4, t0 + 12, mp.inf])
        a_st = mp.quad(lambda s: (s - t) * _phi(s), [t0, t0 + 1, t0 + 4, t0 + 12, mp.inf])
        return stick / gaussian_J(t), a_st / gaussian_A(t)


def gaussian_force_ratio(t: float, delta: float, dps: int = 40):
    """F̂_T = [J(t) − J(t + δ)]/J(t) (loading curve, Eq 9 general form), δ = g_N0/σ*."""
    with mp.workdps(dps):
        t, d = mp.mpf(t), mp.mpf(delta)

        # J(t) − J(t + δ) = (3/2) ∫_t^{t+δ} ∫_τ^∞ (s − τ)^{1/2} φ(s) ds dτ, no cancellation
        def inner(tau):
            return mp.quad(lambda s: (s - tau) ** 0.5 * _phi(s), [tau, tau + 1, tau + 4, mp.inf])

        return 1.5 * mp.quad(inner, [t, t + d]) / gaussian_J(t)
