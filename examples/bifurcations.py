"""Bifurcations in normal form, in the variants a tracer meets: a pitchfork crossed along its
parabola, imperfect transcritical and pitchfork bifurcations (whose broken branches pass close
to each other), and a transcritical crossing at a narrow angle. All special points are in
closed form (the normal forms and their imperfections: Strogatz, Nonlinear Dynamics and Chaos,
§3.2–3.6; Golubitsky & Schaeffer, Singularities and Groups in Bifurcation Theory I, 1985).

The plain transcritical x (p − x) and pitchfork x (p − x²), traced along x = 0, are in
:mod:`~cusp.examples.normal_forms`.
"""

from __future__ import annotations

from ._base import DPS, Example, Reference, one_unknown


def subcritical_pitchfork(*, derivatives: str = "analytic") -> Example:
    """The subcritical pitchfork ``x (p + x²) = 0`` traced along its parabola p = −x².

    Unknown ``x``, parameter ``p``. Start: x = −0.6 at p = −0.36 on the parabola; bounds
    p ∈ [−0.5, 1], x ∈ [−1, 1]. With p increasing the trace climbs the parabola to its vertex
    and down the other side, ending at p = −0.5, x = √0.5.

    Special point: the vertex x = p = 0 is where the parabola crosses the trivial branch
    x = 0, a branch point (exact). The free parameter turns there, but it is not a fold:
    [∂F/∂x, ∂F/∂p] = [p + 3x², x] vanishes.
    """
    return one_unknown(
        "subcritical pitchfork along its parabola",
        lambda x, p: x * (p["p"] + x**2),
        lambda x, p: p["p"] + 3 * x**2,
        lambda x, p, name: x,
        {"p": -0.36},
        derivatives=derivatives,
        x0=-0.6,
        free="p",
        bounds={"p": (-0.5, 1.0), "x": (-1.0, 1.0)},
        refs=lambda: (Reference("branch_point", {"x": 0.0, "p": 0.0}, ("p",)),),
    )


def imperfect_transcritical(eps: float = 5e-4, *, derivatives: str = "analytic") -> Example:
    """The imperfect transcritical bifurcation ``x (p − x) − ε = 0``: the hyperbola
    p = x + ε/x, whose two arms pass the broken crossing of x = 0 and x = p close to each
    other.

    Unknown ``x``, parameters ``p`` (free) and ``eps``; bounds p ∈ [−1, 1], x ∈ [−1, 1];
    start at p = −0.9.

    - ε > 0 (default 5·10⁻⁴): each arm turns. Start on the arm x < 0 at
      x = (p − √(p² − 4ε))/2 = −0.89944; the trace climbs to its fold and returns along
      x → 0⁻, ending at p = −1. Special point (exact): the fold x = −√ε, p = −2√ε
      (∂F/∂x = p − 2x = 0); the other arm's fold, (√ε, 2√ε), is 2√(5ε) = 0.1 away.
    - ε < 0: neither arm turns (dp/dx = 1 − ε/x² > 0). Start on the arm x > 0 at
      x = (p + √(p² − 4ε))/2; the trace follows it from x ≈ |ε|/0.9 to x ≈ 1 at p = 1,
      passing the other arm at the distance 2√(|ε|/λ), λ = (1 + √2)/2 the positive eigenvalue
      of the quadratic form x² − p x (ε = −3·10⁻³: 0.0997). No special point; x > 0 all along.
    """
    p0 = -0.9
    sign = -1.0 if eps > 0 else 1.0
    x0 = (p0 + sign * (p0**2 - 4 * eps) ** 0.5) / 2

    def references():
        if eps <= 0:
            return ()
        import mpmath as mp

        with mp.workdps(DPS):
            r = mp.sqrt(mp.mpf(eps))
            return (Reference("fold", {"x": float(-r), "p": float(-2 * r), "eps": eps}, ("p",)),)

    return one_unknown(
        "imperfect transcritical" + (" (arms passing)" if eps < 0 else ""),
        lambda x, p: x * (p["p"] - x) - p["eps"],
        lambda x, p: p["p"] - 2 * x,
        lambda x, p, name: x if name == "p" else -1.0,
        {"p": p0, "eps": eps},
        derivatives=derivatives,
        x0=x0,
        free="p",
        bounds={"p": (-1.0, 1.0), "x": (-1.0, 1.0)},
        refs=references,
    )


def imperfect_pitchfork(eps: float = 2e-3, *, derivatives: str = "analytic") -> Example:
    """The imperfect subcritical pitchfork ``x (p + x²) + ε = 0`` (ε > 0): the branch
    p = −x² − ε/x, x > 0, with a limit point, and the arm x < 0 beside it.

    Unknown ``x``, parameters ``p`` (free) and ``eps``. Start: x = 0.9 at
    p = −0.81 − ε/0.9; bounds p ∈ [−1, 1], x ∈ [−1, 1]. The trace runs up to the limit
    point and down along x → 0⁺, ending at p = −1.

    Special point (exact): dp/dx = −2x + ε/x² = 0 at x = (ε/2)^{1/3}, p = −3 (ε/2)^{2/3}
    (ε = 2·10⁻³: x = 0.1, p = −0.03); the arm x < 0 passes 0.3 away at the same p
    (x = −0.2).
    """

    def references():
        import mpmath as mp

        with mp.workdps(DPS):
            x = mp.cbrt(mp.mpf(eps) / 2)
            return (Reference("fold", {"x": float(x), "p": float(-3 * x**2), "eps": eps}, ("p",)),)

    return one_unknown(
        "imperfect subcritical pitchfork",
        lambda x, p: x * (p["p"] + x**2) + p["eps"],
        lambda x, p: p["p"] + 3 * x**2,
        lambda x, p, name: x if name == "p" else 1.0,
        {"p": -0.81 - eps / 0.9, "eps": eps},
        derivatives=derivatives,
        x0=0.9,
        free="p",
        bounds={"p": (-1.0, 1.0), "x": (-1.0, 1.0)},
        refs=references,
    )


def narrow_transcritical(kappa: float = 0.05, *, derivatives: str = "analytic") -> Example:
    """A transcritical bifurcation whose branches cross at a narrow angle:
    ``x (κ p − x) = 0``, branches x = 0 and x = κ p (κ = 0.05: 2.9° apart).

    Unknown ``x``, parameters ``p`` (free) and ``kappa``. Start x = 0 at p = −1; bounds
    p ∈ [−1, 1]. Special point (exact): the branch point x = p = 0. Switching there must
    leave along the other branch, whose tangent differs from the trivial branch's by only
    atan κ.
    """
    return one_unknown(
        "transcritical, narrow crossing",
        lambda x, p: x * (p["kappa"] * p["p"] - x),
        lambda x, p: p["kappa"] * p["p"] - 2 * x,
        lambda x, p, name: p["kappa"] * x if name == "p" else p["p"] * x,
        {"p": -1.0, "kappa": kappa},
        derivatives=derivatives,
        x0=0.0,
        free="p",
        bounds={"p": (-1.0, 1.0)},
        refs=lambda: (Reference("branch_point", {"x": 0.0, "p": 0.0, "kappa": kappa}, ("p",)),),
    )
