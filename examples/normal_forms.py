"""Normal forms: the cusp x³ − a x − b = 0, and the transcritical and pitchfork bifurcations.

The cusp normal form is the smallest problem with both folds of an S-shaped branch and, in two
parameters, a fold curve 4a³ = 27b² closing in a cusp at a = b = 0. The transcritical and
pitchfork forms each have one branch point at x = p = 0.
"""

from __future__ import annotations

import functools

import numpy as np
from numpy.typing import ArrayLike

from ._base import DPS, Example, Reference, make_example, one_unknown

# ---------------------------------------------------------------------------------------------
# Cusp normal form x^3 - a x - b = 0
# ---------------------------------------------------------------------------------------------


def _cusp_residual(u, p):
    x = u[0]
    return np.array([x**3 - p["a"] * x - p["b"]])


def _cusp_jacobian(u, p):
    return np.array([[3.0 * u[0] ** 2 - p["a"]]])


def _cusp_param_jacobian(u, p, name):
    if name == "b":
        return np.array([-1.0])
    if name == "a":
        return np.array([-u[0]])
    raise KeyError(name)


def cusp_normal_form(a: float = 1.0, b: float = -1.0, *, derivatives: str = "analytic") -> Example:
    """The cusp normal form ``x³ − a x − b = 0``: unknown ``x``, parameters ``a`` and ``b``.

    Start: the lowest real root at ``b`` (numpy's ``roots``; for a = 1, b = −1 it is minus the
    plastic number, −1.324717957244746: :func:`cusp_start` to 40 digits); free parameter
    ``b``, bounds ``b ∈ [−|b|, |b|]``.

    Special points (:func:`cusp_folds`): for a > 0 two folds in b at ``x = ∓√(a/3)``,
    ``b = ±2 (a/3)^{3/2}`` (for a = 1: b = ±2/(3√3) = ±0.3849001794597505); the fold curve
    in (b, a) is ``(a, b) = (3x², −2x³)``, i.e. ``4a³ = 27b²`` (:func:`cusp_fold_curve`),
    with the cusp at ``x = a = b = 0``.
    """
    roots = np.roots([1.0, 0.0, -a, -b])
    x0 = float(roots[np.abs(roots.imag) < 1e-9].real.min())
    B = abs(b)

    def references():
        folds = [Reference("fold", {"x": x, "a": a, "b": bf}, ("b",)) for x, bf in cusp_folds(a)]
        cusp = Reference("cusp", {"x": 0.0, "a": 0.0, "b": 0.0}, ("b", "a"))
        return (*folds, cusp) if a > 0 else (cusp,)

    return make_example(
        "cusp normal form",
        _cusp_residual,
        ["x"],
        {"a": a, "b": b},
        _cusp_jacobian,
        _cusp_param_jacobian,
        derivatives=derivatives,
        u0=[x0],
        free="b",
        bounds={"b": (-B, B)},
        references=references,
    )


@functools.lru_cache
def cusp_start(a: float = 1.0, b: float = -1.0) -> float:
    """The real root of x³ − a x − b nearest −1.3, by mpmath ``findroot`` at 40 digits
    (b = −1: x = −1.324717957244746, minus the plastic number)."""
    import mpmath as mp

    with mp.workdps(DPS):
        return float(mp.findroot(lambda x: x**3 - a * x - b, -1.3))


def cusp_real_roots(a: float, b: float, dps: int = 30) -> list[float]:
    """The real roots of x³ − a x − b, ascending (mpmath ``polyroots`` at ``dps`` digits)."""
    import mpmath as mp

    with mp.workdps(dps):
        roots = [r.real for r in mp.polyroots([1, 0, -a, -b]) if abs(r.imag) < 1e-20]
    return sorted(float(r) for r in roots)


@functools.lru_cache
def cusp_folds(a: float = 1.0) -> tuple[tuple[float, float], ...]:
    """Folds of the cusp at fixed a > 0: 3x² = a, b = x³ − a x = −2x³ (exact), evaluated in
    mpmath at 40 digits. Returns the (x, b) pairs in path order of increasing x:
    x = −√(a/3) with b = +2 (a/3)^{3/2}, then its mirror image."""
    import mpmath as mp

    with mp.workdps(DPS):
        x = mp.sqrt(mp.mpf(a) / 3)
        # (x, b) pairs: x = -sqrt(a/3) gives b = +2/(3 sqrt 3) for a = 1, and vice versa.
        return tuple((float(s * x), float(-2 * (s * x) ** 3)) for s in (-1, 1))


def cusp_fold_curve(x: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """The fold curve of the cusp parametrised by the fold state: ``(a, b) = (3x², −2x³)``
    (from x³ − a x − b = 0 and 3x² − a = 0); it satisfies 4a³ = 27b²."""
    x = np.asarray(x, dtype=float)
    return 3 * x**2, -2 * x**3


# ---------------------------------------------------------------------------------------------
# Transcritical and pitchfork
# ---------------------------------------------------------------------------------------------


def transcritical(p: float = -1.0, *, derivatives: str = "analytic") -> Example:
    """Transcritical normal form ``x (p − x) = 0``: unknown ``x``, parameter ``p``.

    Start x = 0 at ``p``, free ``p``, bounds p ∈ [−1, 1]. The branches x = 0 and x = p cross
    (not orthogonally) at the branch point x = p = 0 (exact).
    """

    return one_unknown(
        "transcritical normal form",
        lambda x, q: x * (q["p"] - x),
        lambda x, q: q["p"] - 2.0 * x,
        lambda x, q, name: x,
        {"p": p},
        derivatives=derivatives,
        x0=0.0,
        free="p",
        bounds={"p": (-1.0, 1.0)},
        refs=lambda: (Reference("branch_point", {"x": 0.0, "p": 0.0}, ("p",)),),
    )


def pitchfork(p: float = -1.0, *, derivatives: str = "analytic") -> Example:
    """Pitchfork normal form ``x (p − x²) = 0``: unknown ``x``, parameter ``p``.

    Start x = 0 at ``p``, free ``p``, bounds p ∈ [−1, 1]. The branch x = 0 and the parabola
    p = x² meet at the branch point x = p = 0 (exact).
    """

    return one_unknown(
        "pitchfork normal form",
        lambda x, q: x * (q["p"] - x**2),
        lambda x, q: q["p"] - 3.0 * x**2,
        lambda x, q, name: x,
        {"p": p},
        derivatives=derivatives,
        x0=0.0,
        free="p",
        bounds={"p": (-1.0, 1.0)},
        refs=lambda: (Reference("branch_point", {"x": 0.0, "p": 0.0}, ("p",)),),
    )
