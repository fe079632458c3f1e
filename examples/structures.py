"""Structures: the shallow arch (two-mode Ritz model) and the cohesive bar.

- :func:`shallow_arch`: a pinned sinusoidal arch of rise ``e`` under a central load, reduced to
  its first symmetric and antisymmetric modes: limit points, and for e > 4 branch points onto
  an asymmetric path; the first branch point comes before the first limit point iff e > √22.
- :func:`cohesive_exponential`, :func:`cohesive_bilinear`, :func:`cohesive_bilinear_opening`:
  a bar of elastic length ℓ with a cohesive crack, nondimensional, U = ℓ s(W) + W: a smooth
  fold for exponential softening, kinked turning points for a bilinear law.
"""

from __future__ import annotations

import numpy as np

from ._base import DPS, Example, Reference, make_example

# ---------------------------------------------------------------------------------------------
# Shallow arch, two-mode Ritz: Pi = (1/8)(x1^2 - 2e x1 + 4x2^2)^2 + x1^2 + 16x2^2 - p x1
# ---------------------------------------------------------------------------------------------


def shallow_arch(e: float = 6.0, *, derivatives: str = "analytic") -> Example:
    """Shallow pinned sinusoidal arch, two-mode Ritz model: the gradient of
    ``Π = (1/8)(ξ1² − 2eξ1 + 4ξ2²)² + ξ1² + 16ξ2² − pξ1``.

    Unknowns ``xi1`` (symmetric mode), ``xi2`` (antisymmetric), parameters ``p`` (load) and
    ``e`` (rise). Start ξ = 0, p = 0; free ``p``; bounds ξ1 ∈ [−1, 2e].

    Special points (:func:`arch_references`), on the symmetric path ξ2 = 0,
    p = 2ξ1 + ξ1(ξ1 − 2e)(ξ1 − e)/2: limit points at ``ξ1 = e ∓ √((e² − 4)/3)`` (e > 2);
    branch points where Q = ξ1² − 2eξ1 = −16, ``ξ1 = e ∓ √(e² − 16)``, ``p = 8e − 6ξ1``
    (e > 4), from which the asymmetric path (ξ1 − e)² + 4ξ2² = e² − 16, p = 8e − 6ξ1 leaves.
    In (p, e) the first limit point meets the first branch point at e = √22
    (:func:`arch_codim2`).
    """

    def residual(q, p):
        x1, x2, e_ = q[0], q[1], p["e"]
        Q = x1**2 - 2 * e_ * x1 + 4 * x2**2
        return np.array([Q * (x1 - e_) / 2 + 2 * x1 - p["p"], 2 * Q * x2 + 32 * x2])

    def jacobian(q, p):
        x1, x2, e_ = q[0], q[1], p["e"]
        Q = x1**2 - 2 * e_ * x1 + 4 * x2**2
        j12 = 4 * x2 * (x1 - e_)
        return np.array([[(x1 - e_) ** 2 + Q / 2 + 2, j12], [j12, 2 * Q + 16 * x2**2 + 32]])

    def param_jacobian(q, p, name):
        if name == "p":
            return np.array([-1.0, 0.0])
        if name == "e":
            x1, x2, e_ = q[0], q[1], p["e"]
            Q = x1**2 - 2 * e_ * x1 + 4 * x2**2
            return np.array([-x1 * (x1 - e_) - Q / 2, -4 * x1 * x2])
        raise KeyError(name)

    def references():
        ref = arch_references(e)
        out = [
            Reference("fold", {"xi1": x, "xi2": 0.0, "p": pv, "e": e}, ("p",))
            for x, pv in ref["lp"]
        ]
        out += [
            Reference("branch_point", {"xi1": x, "xi2": 0.0, "p": pv, "e": e}, ("p",))
            for x, pv in ref["bp"]
        ]
        out.append(Reference("codim2", arch_codim2(), ("p", "e")))
        return out

    return make_example(
        "shallow arch (two-mode Ritz)",
        residual,
        ["xi1", "xi2"],
        {"p": 0.0, "e": e},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[0.0, 0.0],
        free="p",
        bounds={"xi1": (-1.0, 2 * e)},
        references=references,
    )


def _arch_load(x, e):
    """p on the symmetric path ξ2 = 0: p = 2x + x(x − 2e)(x − e)/2."""
    return 2 * x + x * (x - 2 * e) * (x - e) / 2


def arch_references(e: float) -> dict[str, list[tuple[float, float]]]:
    """On the symmetric path p = 2x + x(x - 2e)(x - e)/2: limit points where dp/dx = 0, i.e.
    x = e -+ sqrt((e^2 - 4)/3) (the roots of (3/2)x^2 - 3ex + e^2 + 2; sympy's roots of dp/dx
    agree, tests/continuation/test_published.py); branch points where Q + 16 = 0, i.e.
    x = e -+ sqrt(e^2 - 16), p_B = 8e - 6x = 2e +- 6 sqrt(e^2 - 16) (only if e > 4).
    Evaluated in mpmath (40 digits); ``{"lp": [(x, p), ...], "bp": [(x, p), ...]}``,
    ascending in x."""
    import mpmath as mp

    with mp.workdps(DPS):
        em = mp.mpf(e)
        out: dict[str, list[tuple[float, float]]] = {"lp": [], "bp": []}
        for key, radicand in (("lp", (em**2 - 4) / 3), ("bp", em**2 - 16)):
            if radicand < 0:
                continue
            roots = [em - mp.sqrt(radicand), em + mp.sqrt(radicand)]
            if radicand == 0:
                roots = roots[:1]
            out[key] = [(float(x), float(_arch_load(x, em))) for x in roots]
        return out


def arch_codim2() -> dict[str, float]:
    """The point of the arch where the first limit point and the first branch point coincide:
    e − √((e² − 4)/3) = e − √(e² − 16) gives e = √22 (= 4.690415759823430), ξ1 = √22 − √6,
    ξ2 = 0, p = 2ξ1 + ξ1(ξ1 − 2e)(ξ1 − e)/2; mpmath, 40 digits."""
    import mpmath as mp

    with mp.workdps(DPS):
        e = mp.sqrt(22)
        x = e - mp.sqrt(6)
        return {"xi1": float(x), "xi2": 0.0, "p": float(_arch_load(x, e)), "e": float(e)}


# ---------------------------------------------------------------------------------------------
# Cohesive bar, nondimensional: U = l s(W) + W
# ---------------------------------------------------------------------------------------------


def cohesive_exponential(ell: float = 2.0, *, derivatives: str = "analytic") -> Example:
    """Cohesive bar with exponential softening s = e^{−W}: ``U − ℓ e^{−W} − W = 0``.

    Unknown ``W`` (crack opening), parameter ``U`` (end displacement). Start W = 0 at U = ℓ
    (U decreases first); free ``U``; bounds W ∈ [−1, 3].

    Special point: for ℓ > 1 one fold where dU/dW = 1 − ℓ e^{−W} = 0, ``W = ln ℓ``,
    ``U = 1 + ln ℓ`` (ℓ = 2: U = 1.6931471805599453).
    """

    def residual(q, p):
        return np.array([p["U"] - ell * np.exp(-q[0]) - q[0]])

    def jacobian(q, p):
        return np.array([[ell * np.exp(-q[0]) - 1.0]])

    def param_jacobian(q, p, name):
        return np.array([1.0])

    def references():
        W, U = cohesive_exponential_fold(ell)
        return (Reference("fold", {"W": W, "U": U}, ("U",)),)

    return make_example(
        "cohesive bar (exponential softening)",
        residual,
        ["W"],
        {"U": ell},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[0.0],
        free="U",
        bounds={"W": (-1.0, 3.0)},
        references=references,
    )


def cohesive_exponential_fold(ell: float = 2.0) -> tuple[float, float]:
    """(W, U) = (ln ℓ, 1 + ln ℓ) at the fold of :func:`cohesive_exponential` (mpmath, 40
    digits; ℓ = 2: 1 + ln 2 = 1.6931471805599453094172321214581765680755)."""
    import mpmath as mp

    with mp.workdps(DPS):
        W = mp.log(ell)
        return float(W), float(1 + W)


def _bilinear(ell, w0):
    """s(W) and s'(W) of the bilinear law (real part decides the segment: complex-step safe)."""

    def s_and_slope(w):
        wr = np.real(w)
        if wr <= w0:
            return w / w0, 1.0 / w0
        if wr <= 1.0:
            return (1.0 - w) / (1.0 - w0), -1.0 / (1.0 - w0)
        return 0.0 * w, 0.0

    return s_and_slope


def cohesive_bilinear(
    ell: float = 2.0, w0: float = 0.01, *, derivatives: str = "analytic"
) -> Example:
    """Bilinear (intrinsic) cohesive law, a continuous piecewise-linear s(W): s = W/w0 up to
    the peak s = 1 at W = w0, then linear softening s = (1 - W)/(1 - w0) to s = 0 at W = 1,
    then s = 0. Unknown W, free U, residual U - l s(W) - W. U(W) is continuous with slope
    l/w0 + 1 > 0 before the peak and 1 - l/(1 - w0) < 0 after it (l = 2): the peak
    U = l + w0 is a turning point of U with a kink (no smooth fold), and so is the minimum
    U = 1 at W = 1 where softening ends (:func:`cohesive_bilinear_kinks`).

    Start W = 0, U = 0; free ``U``; bounds W ∈ [−0.5, 1.5].
    """
    s_and_slope = _bilinear(ell, w0)

    def residual(q, p):
        s, _ = s_and_slope(q[0])
        return np.array([p["U"] - ell * s - q[0]])

    def jacobian(q, p):
        _, ds = s_and_slope(q[0])
        return np.array([[-ell * ds - 1.0]])

    def param_jacobian(q, p, name):
        return np.array([1.0])

    def references():
        return tuple(
            Reference("kink", {"W": W, "U": U}, ("U",)) for W, U in cohesive_bilinear_kinks(ell, w0)
        )

    return make_example(
        "cohesive bar (bilinear law)",
        residual,
        ["W"],
        {"U": 0.0},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[0.0],
        free="U",
        bounds={"W": (-0.5, 1.5)},
        references=references,
    )


def cohesive_bilinear_opening(
    ell: float = 2.0, w0: float = 0.01, *, derivatives: str = "analytic"
) -> Example:
    """The bilinear cohesive bar of :func:`cohesive_bilinear` under crack-opening control: the
    same residual ``U − ℓ s(W) − W`` with the roles swapped, unknown ``U``, parameter ``W``.
    W never turns; the kinked maximum of U is a turning point with respect to the monitored U.

    Start U = 0, W = 0; free ``W``, monitor ``U``; bounds W ∈ [−0.5, 1.5]. Exact solution
    U = ℓ s(W) + W; kinks as in :func:`cohesive_bilinear_kinks`.
    """
    s_and_slope = _bilinear(ell, w0)

    def residual(q, p):
        s, _ = s_and_slope(p["W"])
        return np.array([q[0] - ell * s - p["W"]])

    def jacobian(q, p):
        return np.array([[1.0]])

    def param_jacobian(q, p, name):
        _, ds = s_and_slope(p["W"])
        return np.array([-ell * ds - 1.0])

    def references():
        return tuple(
            Reference("kink", {"U": U, "W": W}, ("W",), "U")
            for W, U in cohesive_bilinear_kinks(ell, w0)
        )

    return make_example(
        "cohesive bar (bilinear law), opening control",
        residual,
        ["U"],
        {"W": 0.0},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[0.0],
        free="W",
        bounds={"W": (-0.5, 1.5)},
        monitor=["U"],
        references=references,
    )


def cohesive_bilinear_kinks(ell: float = 2.0, w0: float = 0.01) -> tuple[tuple[float, float], ...]:
    """(W, U) of the kinked turning points of the bilinear cohesive bar (exact): the peak
    W = w0, U = ℓ + w0, and the end of softening W = 1, U = 1."""
    return ((w0, ell + w0), (1.0, 1.0))
