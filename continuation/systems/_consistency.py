"""Is a supplied Jacobian the derivative of the residual? A directional check at one point.

A Jacobian written by hand with a wrong sign or term still lets Newton converge (linearly,
if the error is small), but its tangents, folds and branch points are those of another
problem: a trace ends as a success with false special points. The check compares the
supplied ``∂G/∂z·v`` along a fixed pseudo-random direction ``v`` (every component moved
relative to its magnitude, the free parameter included, so the parameter derivative is
checked too) with differences of the residual itself:

- one-sided differences forward and backward, each extrapolated to O(h²) (Richardson), so
  that at a kink of the residual a Jacobian of either side passes;
- relative to each equation's own terms ``Σ_j |∂G_r/∂z_j·v_j|``;
- a defect above :data:`TOLERANCE` at the step :data:`STEP` is measured again at a step
  eight times shorter: the truncation error of the differences falls like h² (64 times),
  a wrong Jacobian's defect stays. Only a defect that stays is reported.

It costs four residual evaluations and one Jacobian (eight when the first measure is in
doubt); the tracer runs it at the start of a branch, at every located fold and branch point
and before it blames the Jacobian for a Newton that contracts weakly whatever the step.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .._errors import JacobianError, SingularMatrixError, format_values
from ._curve import CurveSystem

STEP = 1e-4
"""The difference step, relative to the components' magnitudes ``max(scale_i, |z_i|)``."""

TOLERANCE = 1e-6
"""The largest relative defect of an equation taken as the differences' own error."""

FLOOR = 1e-7
"""The smallest scale an equation's defect is measured against, relative to the largest
terms of all the equations."""

_SEED = 23
_EPS = float(np.finfo(float).eps)


class Defect(NamedTuple):
    """A defect of the Jacobian along the check's direction: the equation (``row``), the
    supplied ``∂G/∂z·v`` and the residual's extrapolated difference there, and their
    relative difference (to the equation's terms)."""

    row: int
    supplied: float
    differenced: float
    relative: float


def supplied_jacobian(system: CurveSystem) -> bool:
    """Whether ``system``'s derivatives come from the user's functions (not differences or
    the complex step, which are consistent with the residual by construction)."""
    return system.supplied_derivatives


def jacobian_defect(system: CurveSystem, z: np.ndarray) -> Defect | None:
    """The defect of ``system``'s Jacobian at ``z`` (module docstring), or None where it
    agrees with the residual's differences (or they cannot be taken: a non-finite value).
    A central difference decides most points at once (two residuals); only a point in doubt
    (a kink, strong curvature, a defect) takes the one-sided extrapolated differences."""
    if system.scalar:
        agree = _scalar_agrees(system, z)
        if agree is not None and agree:
            return None
    mags = np.maximum(system.scales, np.abs(z))
    v = _direction(z.size) * mags
    try:
        dg = system.jacobian(z)
        g0 = system.residual(z)
        up, down = system.residual(z + STEP * v), system.residual(z - STEP * v)
    except (ArithmeticError, SingularMatrixError):
        return None
    central = (up - down) / (2 * STEP)
    absdg = abs(dg)
    jv = np.asarray(dg @ v).ravel()
    terms = np.asarray(absdg @ np.abs(v)).ravel()
    # the rounding of an equation is that of its terms (|∂G_r/∂z_j|·|z_j|), not of its
    # value, and that of the values it takes at the difference's points (its second-order
    # terms there, where its first-order ones vanish: at a branch point of x(p − x))
    level = np.asarray(absdg @ mags).ravel() + np.maximum(np.abs(up), np.abs(down))
    floor = FLOOR * float(terms.max(initial=0.0))
    if not (np.all(np.isfinite(jv)) and np.all(np.isfinite(g0))):
        return None
    if np.all(np.abs(jv - central) <= TOLERANCE * (terms + 16.0 * _EPS * level / STEP + floor)):
        return None
    previous = None
    found = None
    for h in (STEP, STEP / 8.0):
        sides = _one_sided(system, z, v, g0, h)
        if sides is None:
            return None
        rf, rb = sides
        err = np.minimum(np.abs(jv - rf), np.abs(jv - rb))
        # (an equation whose terms all vanish here, u2·(p2 u1 − p3) at u2 = 0, p2 u1 = p3,
        # has differences at the rounding of its factors: measured against the system's
        # largest terms times FLOOR)
        relative = err / (terms + 16.0 * _EPS * level / h + floor + 1e-300)
        worst = int(np.argmax(relative))
        if relative[worst] <= TOLERANCE:
            return None
        if previous is not None and err[worst] < 0.5 * previous:
            return None  # shrinking like h²: the differences' truncation, not a defect
        previous = float(err[worst])
        near = rf if abs(jv[worst] - rf[worst]) <= abs(jv[worst] - rb[worst]) else rb
        found = Defect(
            row=worst,
            supplied=float(jv[worst]),
            differenced=float(near[worst]),
            relative=float(relative[worst]),
        )
    return found


def _scalar_agrees(system: CurveSystem, z: np.ndarray) -> bool | None:
    """The central-difference test of :func:`jacobian_defect` for a curve of one equation in
    plain floats (``system.scalar``): True if it passes, False if the general path must
    decide, None where a value is not a finite float (the general path decides too)."""
    (s0, s1), (x, lam) = system.scales.tolist(), z.tolist()
    d0, d1 = _direction(2).tolist()
    v0, v1 = d0 * max(s0, abs(x)), d1 * max(s1, abs(lam))
    jac = system.scalar_jacobian(z)
    up = system.scalar_residual(np.array((x + STEP * v0, lam + STEP * v1)))
    down = system.scalar_residual(np.array((x - STEP * v0, lam - STEP * v1)))
    if jac is None or up is None or down is None:
        return None
    a, b = jac
    terms = abs(a * v0) + abs(b * v1)
    level = abs(a) * max(s0, abs(x)) + abs(b) * max(s1, abs(lam)) + max(abs(up), abs(down))
    err = abs(a * v0 + b * v1 - (up - down) / (2 * STEP))
    return err <= TOLERANCE * (terms + 16.0 * _EPS * level / STEP + FLOOR * terms)


_DIRECTIONS: dict[int, np.ndarray] = {}


def _direction(n: int) -> np.ndarray:
    """The check's direction for ``n`` components: fixed pseudo-random entries of magnitude
    0.5 to 1 and either sign (seeded: the check is reproducible), made once per size."""
    v = _DIRECTIONS.get(n)
    if v is None:
        rng = np.random.default_rng(_SEED)
        v = _DIRECTIONS[n] = rng.uniform(0.5, 1.0, n) * rng.choice((-1.0, 1.0), n)
    return v


def _one_sided(
    system: CurveSystem, z: np.ndarray, v: np.ndarray, g0: np.ndarray, h: float
) -> tuple[np.ndarray, np.ndarray] | None:
    """Forward and backward differences of the residual along ``v`` at step ``h``, each
    extrapolated to O(h²) from the steps ``h`` and ``h/2``; None if a value is not finite."""
    out = []
    for sign in (1.0, -1.0):
        try:
            far = system.residual(z + (sign * h) * v)
            near = system.residual(z + (sign * 0.5 * h) * v)
        except (ArithmeticError, SingularMatrixError):
            return None
        d_far = sign * (far - g0) / h
        d_near = sign * (near - g0) / (0.5 * h)
        both = 2.0 * d_near - d_far
        if not np.all(np.isfinite(both)):
            return None
        out.append(both)
    return out[0], out[1]


def check_consistent(system: CurveSystem, z: np.ndarray, where: str) -> None:
    """:class:`~.._errors.JacobianError` if ``system``'s supplied Jacobian disagrees with its
    residual at ``z`` (``where``: what the point is, for the message); nothing for
    differenced derivatives."""
    if not supplied_jacobian(system):
        return
    defect = jacobian_defect(system, z)
    if defect is None:
        return
    values = system.values(z)
    names = system.names
    entries = _entries(system, z)
    raise JacobianError(
        f"the supplied derivatives disagree with the residual at {where} "
        f"{format_values(values)}: along a test direction (every one of "
        f"{list(names)} moved) equation {defect.row} changes at {defect.differenced:.10g} per "
        f"unit, the jacobian and param_jacobian give {defect.supplied:.10g} (relative defect "
        f"{defect.relative:.2g}, "
        f"far above the differences' own error, and it does not shrink with the step). "
        "Continuation with them would report the folds and branch points of another "
        "problem. Correct them, or leave them out to use finite differences" + entries,
        values=values,
        row=defect.row,
        supplied=defect.supplied,
        differenced=defect.differenced,
    )


def _entries(system: CurveSystem, z: np.ndarray) -> str:
    """The entries of the supplied derivatives that disagree most with central differences
    (:func:`~..problem._derivatives.check_jacobian` at ``z``), as a sentence; empty for a
    curve that is not a problem's branch or too large to difference column by column."""
    problem = system.problem
    if problem is None or z.size > 201:
        return ""
    from ..problem._derivatives import check_jacobian

    u, p = system.split(z)
    try:
        found = check_jacobian(problem, u, {k: p[k] for k in problem.params})
    except Exception:  # (a diagnosis only: the defect is reported anyway)
        return ""
    if found.ok:
        return ""
    return ". check_jacobian(problem, u, p) at this point: " + found.message.split(":", 1)[1]


__all__ = ["Defect", "STEP", "TOLERANCE", "check_consistent", "jacobian_defect"]
