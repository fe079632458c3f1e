"""The first point of a curve and its tangent, also on a fold or at a singular point.

The start is corrected by Newton with the free parameter (the last component of ``z``)
held at its value, and the tangent solves ``[∂G/∂z; e_lastᵀ] t = e_last``. Both need the
matrix ``[∂G/∂z; e_lastᵀ]`` (∂G/∂u, for a branch) to be regular, which it is not on a fold
of the free parameter: there the guess may already solve ``G = 0`` (the residual 0) and
still Newton with the parameter fixed cannot take a step. The curve itself is regular
there — ``∂G/∂z`` has full rank, a one-dimensional null space — so the start is taken from
the null space instead (:func:`kernel_tangent`: ``[∂G/∂z; cᵀ] t = e_last`` with a border
``c`` that is not orthogonal to the tangent) and corrected in the hyperplane through the
guess orthogonal to that tangent. At a singular point (a branch point: the null space of
``∂G/∂z`` two-dimensional or more) no tangent is defined and the start is refused
(:class:`~.._errors.SingularPointError`).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from .._errors import (
    ConvergenceError,
    NonFiniteResidualError,
    SingularMatrixError,
    SingularPointError,
    format_values,
)
from .._outcomes import Convergence
from ..detection._spectrum import Factored
from ..systems._curve import CurveSystem

if TYPE_CHECKING:
    from .._options import ContinuationOptions
from ..numerics._linalg import bordered, factor, max_abs
from ..systems._newton import correct, factor_at

_BORDER_SEED = 17
"""Seed of the two fixed pseudo-random borders of :func:`kernel_tangent` (the start is then
reproducible bit for bit)."""

_SAME_DIRECTION = 5e-9
"""``1 − |cos|`` of the angle between the two borders' tangents above which the null space
is taken as two-dimensional: 1e-4 rad. On a regular curve both are the null vector, to
rounding times the condition of the bordered matrix; at a branch point each border picks
its own vector of the null space."""


class Start(NamedTuple):
    """The corrected start ``z``, its tangent ``t`` (not normalised, oriented), the sign of
    ``det [∂G/∂z; (W t)ᵀ]`` (None if not known), the residual's max-norm, the Newton
    iterations and, for a start on a fold of the free parameter, the name of the component
    that orients the tangent (else None)."""

    z: np.ndarray
    t: np.ndarray
    sdet: float | None
    residual_norm: float
    iterations: int
    fold_oriented_by: str | None


def correct_start(
    system: CurveSystem,
    z0: np.ndarray,
    g0: np.ndarray,
    options: ContinuationOptions,
    e_last: np.ndarray,
    direction: int,
) -> Start:
    """The start of a curve from the guess ``z0`` (``g0`` = G(z0)): Newton with the last
    component fixed, or on a fold of that component the null-space start of the module
    docstring. ``direction`` (±1): the sign of the last component's change along the
    tangent, or, on a fold of it, of the change of the component that moves most relative
    to its typical size."""
    k = system.dim - 1
    res = correct(system, z0, e_last, z0[k], options, budget=4, g0=g0)
    if res.converged:
        z = res.z.copy()
        z[k] = z0[k]  # the constraint is linear: snap away the last rounding
        z, rn = snap_zeros(system, z, z0, res.residual_norm)
        lu = factor_at(system, z, e_last)  # (the tangent at z itself: see factor_at)
        t = _solve(lu, e_last)
        if t is not None:
            sdet = lu.sign_det()
            if t[k] * direction < 0:
                t, sdet = -t, -sdet
            if system.dim > 2:  # (kept for the branch-point test's partial spectrum)
                sdet = Factored(sdet, lu)
            return Start(
                z=z,
                t=t,
                sdet=sdet,
                residual_norm=rn,
                iterations=res.iterations,
                fold_oriented_by=None,
            )
        iters = res.iterations
    elif res.reason is Convergence.SINGULAR:
        # ∂G/∂u is singular at the guess (or an iterate): a fold of the free parameter,
        # where the curve is still regular, or a singular point
        z, rn, iters = _correct_on_fold(
            system, res.z, z0, options, res.iterations, res.residual_norm
        )
    else:
        raise ConvergenceError(
            "the starting point did not converge",
            values=system.values(z0),
            ds=0.0,
            iterations=res.iterations,
            residual_norm=res.residual_norm,
            remedy="Give a better initial guess u0 for these parameter values.",
        )
    t = kernel_tangent(system, z)
    i = int(np.argmax(np.abs(t) / np.maximum(system.scales, np.abs(z))))
    if t[i] * direction < 0:
        t = -t
    return Start(
        z=z, t=t, sdet=None, residual_norm=rn, iterations=iters, fold_oriented_by=system.names[i]
    )


def snap_zeros(
    system: CurveSystem, z: np.ndarray, guess: np.ndarray, residual: float
) -> tuple[np.ndarray, float]:
    """The corrected start ``z`` with the components that are zeros up to Newton's
    remainder set to exactly 0, and the residual's max-norm there.

    Newton corrects a guess of the trivial state of a symmetric problem (the origin of the
    Lorenz equations, the unloaded truss, u = 0 of the Bratu problem at λ = 0) to a point
    whose components are not 0 but what is left of their convergence to 0 (1e-17 from a
    guess of 0.1, 1e-28 from a guess of 1e-6): nothing in the equations tells that
    remainder from a component of that size, yet it would set the component's typical size
    and break the symmetry of the branch by that much. A component is that remainder when
    it is a millionth of the largest magnitude of the guess, of ``z`` and of the typical
    sizes known before the correction (bounds, ``scales``, 1 for a guess of 0) or less, and
    setting the candidates to 0 leaves every equation at its rounding level
    (``100·ε·Σ_j |∂G_r/∂z_j|·max(scale_j, |z_j|)``): a genuinely small component (a
    concentration of 1e-9 beside pressures of 1e6) leaves its equations off by its own
    terms, far above that, and is kept."""
    largest = max(max_abs(z), max_abs(np.asarray(guess, dtype=float)), max_abs(system.scales))
    small = np.abs(z) <= 1e-6 * largest
    small[-1] = False  # (the last component, a parameter, is held at its value)
    if not np.any(z[small] != 0.0):  # (none, or all exactly 0 already)
        return z, residual
    zs = np.where(small, 0.0, z)
    try:
        g = system.residual(zs)
        dg = system.jacobian(zs)
    except (ArithmeticError, SingularMatrixError):
        return z, residual
    terms = abs(dg) @ np.maximum(system.scales, np.abs(zs))
    terms = np.asarray(terms).ravel()
    if np.all(np.abs(g) <= 100.0 * _EPS * terms):
        return zs, float(max_abs(g))
    return z, residual


_EPS = float(np.finfo(float).eps)


def _solve(lu: Any, rhs: np.ndarray) -> np.ndarray | None:
    """``lu``'s solution for ``rhs``, None if it is not finite or ``lu`` is missing."""
    if lu is None:
        return None
    t = lu.solve(rhs)
    return t if math.isfinite(max_abs(t)) else None


def _correct_on_fold(
    system: CurveSystem,
    z: np.ndarray,
    z0: np.ndarray,
    options: ContinuationOptions,
    iterations: int,
    residual: float,
) -> tuple[np.ndarray, float, int]:
    """Newton from ``z`` in the hyperplane orthogonal to the curve's tangent there (the
    free parameter free), where ``∂G/∂u`` is singular. The free parameter may move by no
    more than Newton's update tolerance relative to its size (``√step_tol``): the start is
    at the parameter value asked for, or refused (``residual``: the max-norm of G there, for
    the message)."""
    t = kernel_tangent(system, z)
    res = correct(system, z, system.weights * t, None, options, budget=4)
    k = system.dim - 1
    moved = abs(res.z[k] - z0[k])
    allowed = math.sqrt(options.step_tol) * max(system.scales[k], abs(z0[k]))
    if not res.converged or moved > allowed:
        name = system.names[k]
        remedy = f"Give a guess u0 on the curve at this {name}, off the fold."
        if res.converged:
            remedy = (
                f"With {name} free the nearest solution has {name}={res.z[k]:.10g}, "
                f"{moved:.3g} away: start there, or give a guess u0 on the curve at this "
                f"{name}, off the fold."
            )
        raise ConvergenceError(
            f"the starting point did not converge: with {name} held fixed the Jacobian is "
            f"singular there (a fold of {name})",
            values=system.values(z0),
            ds=0.0,
            iterations=iterations + res.iterations,
            residual_norm=residual,
            remedy=remedy,
        )
    return res.z, res.residual_norm, iterations + res.iterations


def kernel_tangent(system: CurveSystem, z: np.ndarray) -> np.ndarray:
    """The null vector of ``∂G/∂z`` at ``z`` (not normalised, either sign), from the
    bordered matrices ``[∂G/∂z; cᵀ]`` with two fixed pseudo-random borders ``c`` (scaled by
    the typical sizes; one fails only if it is orthogonal to the tangent). Raises
    :class:`~.._errors.SingularPointError` where the null space is two-dimensional or more:
    then every border leaves the matrix singular, or the two borders' solutions differ."""
    dg = system.jacobian(z)
    data = dg.data if hasattr(dg, "tocsr") else np.asarray(dg)
    if not np.isfinite(data).all():
        raise NonFiniteResidualError(
            f"the Jacobian is not finite at the starting point {format_values(system.values(z))}",
            values=system.values(z),
        )
    rng = np.random.default_rng(_BORDER_SEED)
    rhs = np.zeros(system.dim)
    rhs[-1] = 1.0
    found = []
    for _ in range(2):
        row = rng.uniform(0.5, 1.5, system.dim) * rng.choice((-1.0, 1.0), system.dim)
        try:
            t = _solve(factor(bordered(dg, row / system.scales)), rhs)
        except SingularMatrixError:
            t = None
        if t is None:
            raise _singular_point(system, z)
        found.append(t / math.sqrt(t.dot(system.weights * t)))
    a, b = found
    if 1.0 - abs(a.dot(system.weights * b)) > _SAME_DIRECTION:
        raise _singular_point(system, z)
    return a


#: the step (relative to the components' magnitudes) of the directional differences of
#: :func:`singular_within_accuracy`, and the ratio below which the derivative they extract
#: counts as 0
_PROBE_STEP = 1e-3
_ZERO_RATIO = 1e-2
#: a smallest singular value above this fraction of the largest is regular without probing
_CLEARLY_REGULAR = 1e-5


def singular_within_accuracy(system: CurveSystem, z: np.ndarray) -> bool:
    """Whether ``∂G/∂z`` at the start ``z`` is rank-deficient to within its own accuracy: a
    branch point that a differenced Jacobian hides.

    At a simple branch point ``∂G/∂z`` has a two-dimensional kernel; a Jacobian by finite
    differences is off by its truncation error there (``−h²`` for ``x (p − x²)`` at the
    origin), which gives it full rank, a one-dimensional kernel and a tangent: the start
    would be taken as a regular point and its branch point located a difference step away.
    The direction ``φ`` of the smallest singular value (of the Jacobian scaled by the
    components' magnitudes) is probed with the residual itself: the derivative
    ``ψ·G'(z)φ`` (``ψ`` the left singular vector) from central differences at steps ``s``
    and ``2s``, combined by Richardson extrapolation to remove their O(s²) error. It is
    the smallest singular value at a regular point, and 0 at a branch point, where both
    differences are their O(s²) truncation alone: the start is singular when the
    extrapolated value is below 1 % of the differences. (A start within about ``1e-8``
    relative of a branch point counts as on it.)"""
    if z.size > _MAX_DENSE_CHECK:
        return False
    if system.scalar:
        found = _scalar_singular(system, z)
        if found is not None:
            return found
    dg = system.jacobian(z)
    dense = dg.toarray() if hasattr(dg, "toarray") else np.asarray(dg, dtype=float)
    m = dense.shape[0]
    if m == 0 or not np.all(np.isfinite(dense)):
        return False
    mags = np.maximum(system.scales, np.abs(z))
    u, sv, vt = np.linalg.svd(dense * mags)
    if sv[m - 1] >= _CLEARLY_REGULAR * sv[0] and m > 1:
        return False  # (no differencing error hides a branch point this far from one)
    phi, psi = vt[m - 1] * mags, u[:, m - 1]

    def derivative(s: float) -> float:
        up, down = system.residual(z + s * phi), system.residual(z - s * phi)
        return float(psi @ (up - down)) / (2.0 * s)

    return _zero_derivative(derivative, float(sv[m - 1]))


def _zero_derivative(derivative: Any, supplied: float) -> bool:
    """Whether the directional derivative ``derivative(s)`` (a central difference at step
    ``s``) extrapolates to 0 (see :func:`singular_within_accuracy`); ``supplied``: its value
    by the Jacobian. A first difference within 1 % of it decides a regular point at once."""
    try:
        first = derivative(_PROBE_STEP)
        if not math.isfinite(first):
            return False
        if abs(first - supplied) <= _ZERO_RATIO * abs(supplied):
            return False
        second = derivative(2.0 * _PROBE_STEP)
    except (ArithmeticError, SingularMatrixError):
        return False
    if not math.isfinite(second):
        return False
    extrapolated = (4.0 * first - second) / 3.0
    return abs(extrapolated) <= _ZERO_RATIO * max(abs(first), abs(second))


def _scalar_singular(system: CurveSystem, z: np.ndarray) -> bool | None:
    """:func:`singular_within_accuracy` for a curve of one equation in plain floats: its
    Jacobian is a row ``(a, b)``, whose direction (scaled by the magnitudes) is ``φ`` and
    its left singular vector 1. None where a value is not a finite float."""
    jac = system.scalar_jacobian(z)
    if jac is None:
        return None
    (s0, s1), (x, lam) = system.scales.tolist(), z.tolist()
    m0, m1 = max(s0, abs(x)), max(s1, abs(lam))
    a, b = jac[0] * m0, jac[1] * m1
    norm = math.hypot(a, b)
    if norm == 0.0:
        return True  # (exactly zero: a branch point of the one equation)
    p0, p1 = a / norm * m0, b / norm * m1

    def derivative(s: float) -> float:
        up = system.scalar_residual(np.array((x + s * p0, lam + s * p1)))
        down = system.scalar_residual(np.array((x - s * p0, lam - s * p1)))
        return math.nan if up is None or down is None else (up - down) / (2.0 * s)

    return _zero_derivative(derivative, norm)


_MAX_DENSE_CHECK = 201
"""Largest curve dimension checked by :func:`singular_within_accuracy` (a dense SVD)."""


def refuse_singular(system: CurveSystem, z: np.ndarray) -> None:
    """:class:`~.._errors.SingularPointError` if the corrected start ``z`` is a branch point
    to within the accuracy of the Jacobian (:func:`singular_within_accuracy`)."""
    if singular_within_accuracy(system, z):
        raise _singular_point(system, z)


def _singular_point(system: CurveSystem, z: np.ndarray) -> SingularPointError:
    values = system.values(z)
    return SingularPointError(
        f"the starting point {format_values(values)} is a singular point: the Jacobian of "
        f"the equations in the unknowns and {system.names[-1]} has a null space of dimension "
        f"2 or more (a branch point), so the curve has no tangent there. Start off "
        f"it, with a guess on the branch you want, or trace a branch through it and switch at "
        f"its located branch point: "
        f"trace(problem, branch.special('branch_point')[0], free=...)",
        values=values,
    )


__all__ = ["Start", "correct_start", "kernel_tangent", "refuse_singular", "snap_zeros"]
