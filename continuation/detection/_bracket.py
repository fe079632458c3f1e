"""A step as the place where special points are located: its :class:`Bracket` (the step's
ends, its arc and the corrector at a pseudo-arclength inside it), what a locator returns
(:class:`Located`), and what every locator shares: the stopping test of a locating Newton
(:func:`newton_done`), the acceptance of its point (:func:`accept_located`), the tangent at
a point (:func:`tangent_at`, :func:`oriented_tangent`) and the exact location of a component's
value (:func:`locate_component`).

The locators: folds (:mod:`._folds`), branch points (:mod:`._branchpoints`), cusps and
codimension-2 points of fold curves (:mod:`._cusp`), anything else by regula falsi on the
arc (:mod:`._regula`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from .._errors import SingularMatrixError
from .._outcomes import PointStatus
from ..numerics._arc import HermiteArc
from ..numerics._linalg import bordered, factor, max_abs, unit_last
from ..systems._curve import CurveSystem
from ..systems._newton import NewtonResult, correct

if TYPE_CHECKING:
    from .._options import ContinuationOptions

# records are made by a static method of() and this bound object.__new__: a class method's
# binding and the lookup of __new__ on object cost a third of a record (callgrind), and the
# stepper makes several records a step
_new = object.__new__

_EPS = float(np.finfo(float).eps)


@dataclass
class Bracket:
    """An accepted step (or part of one) where a special point is located: its ends ``z_a``,
    ``z_b`` with unit tangents ``t_a``, ``t_b``; ``row = W t_a`` and the pseudo-arclength
    ``h = row·(z_b − z_a)`` of ``z_b`` along it; the step's :class:`~..numerics._arc.HermiteArc`
    (``arc``), parametrised by that pseudo-arclength (its end derivatives ``dz/dσ =
    t/(row·t)``, ``t_b`` tilted by the step's turn, up to ``max_angle``)."""

    system: CurveSystem
    z_a: np.ndarray
    t_a: np.ndarray
    z_b: np.ndarray
    t_b: np.ndarray
    weights: np.ndarray
    options: ContinuationOptions
    row: np.ndarray = field(init=False)
    h: float = field(init=False)
    arc: HermiteArc = field(init=False)

    def __post_init__(self) -> None:
        self.row = self.weights * self.t_a
        self.h = float(self.row.dot(self.z_b - self.z_a))
        d_a = self.t_a / float(self.row.dot(self.t_a))
        cos_b = float(self.row.dot(self.t_b))
        d_b = self.t_b / cos_b if cos_b > 0.1 else self.t_b
        self.arc = HermiteArc(self.z_a, d_a, self.z_b, d_b, self.h)

    def sigma(self, z: np.ndarray) -> float:
        return float(self.row.dot(z - self.z_a))

    def point_at(
        self, sigma: float, strict: bool = False, start: np.ndarray | None = None
    ) -> NewtonResult:
        """The curve point whose pseudo-arclength from ``z_a`` (along ``t_a``) is ``sigma``:
        the corrector from the arc's point there (or from ``start``), ``strict`` as for
        :class:`~..systems._newton.NewtonSettings`."""
        o = self.options
        theta = sigma / self.h if self.h != 0 else 0.0
        z0 = self.arc.at(theta) if start is None else start
        c = self.row.dot(self.z_a) + sigma
        return correct(self.system, z0, self.row, c, o, budget=2, strict=strict)

    def polish(self, z: np.ndarray, sigma: float) -> np.ndarray:
        """Newton to the update tolerance (not just the residual tolerance) at ``sigma``."""
        res = self.point_at(sigma, strict=True, start=z)
        return res.z if res.converged else z


@dataclass(slots=True)
class Span:
    """A step, or a part of one, between two points of the curve (built by keyword; never
    changed after it is made): their
    components ``z_a``, ``z_b`` and unit tangents ``t_a``, ``t_b``, the pseudo-arclength
    ``h = W t_a·(z_b − z_a)`` and the cosine of the turn ``cos_b = W t_a·t_b``; ``s_a``, the
    pseudo-arclength of ``z_a`` from the step's start (a part of a step)."""

    z_a: np.ndarray
    t_a: np.ndarray
    z_b: np.ndarray
    t_b: np.ndarray
    h: float
    cos_b: float
    s_a: float = 0.0

    @staticmethod
    def of(
        *,
        z_a: np.ndarray,
        t_a: np.ndarray,
        z_b: np.ndarray,
        t_b: np.ndarray,
        h: float,
        cos_b: float,
        s_a: float = 0.0,
    ) -> Span:
        """Built by keyword, fast: a class called with keywords first gathers them in a
        dict (three times the cost of this call, on every step)."""
        self = _new(Span)
        self.z_a = z_a
        self.t_a = t_a
        self.z_b = z_b
        self.t_b = t_b
        self.h = h
        self.cos_b = cos_b
        self.s_a = s_a
        return self


class Located(NamedTuple):
    """A special point located inside a step (immutable; built by keyword).

    ``sigma``: its pseudo-arclength from the step's start; ``status``: converged, guess
    (only bracketed) or pole (no zero: no special point); ``details``: what the locating
    method reports."""

    z: np.ndarray
    sigma: float
    status: PointStatus
    iterations: int
    details: Mapping[str, Any] = MappingProxyType({})
    tangent: np.ndarray | None = None
    """Unit tangent at ``z`` oriented like the step, when the locating iteration gave it."""
    residual_norm: float | None = None
    """Max-norm of the residual at ``z``, when the locating iteration computed it."""


def oriented_tangent(t: np.ndarray, row: np.ndarray, weights: np.ndarray) -> np.ndarray | None:
    """``t`` scaled to unit weighted norm with ``row·t > 0``; None if ``t`` is not finite or
    too close to orthogonal to ``row`` for the orientation to be trusted."""
    nt = math.sqrt(t.dot(weights * t))
    if not (math.isfinite(nt) and nt > 0.0):
        return None
    rt = row.dot(t) / nt
    if abs(rt) < 1e-3 * math.sqrt(row.dot(row / weights)):
        return None
    return t / (nt if rt > 0 else -nt)


def tangent_at(
    system: CurveSystem,
    z: np.ndarray,
    row: np.ndarray,
    weights: np.ndarray,
    br: Bracket | None = None,
) -> np.ndarray:
    """Unit tangent at ``z`` oriented so that ``row·t > 0``.

    Exactly at a branch point ``[∂G/∂z; row]`` is singular whatever the border: the tangent of
    the branch is then the limit of its tangents, taken from the step's Hermite interpolant."""
    dg = system.jacobian(z)
    try:
        t = factor(bordered(dg, row)).solve(unit_last(z.size))
    except SingularMatrixError:
        if br is None:
            raise
        t = br.arc.derivative(min(1.0, max(0.0, br.sigma(z) / br.h)))
    return t / math.sqrt(t.dot(weights * t))


def newton_done(
    it: int,
    size: float,
    previous: float,
    tol: float,
    stall: float,
    perturbation: float | None = None,
    k_ratio: float | None = None,
) -> bool:
    """Stopping test of the locating Newton iterations, with update ``size`` (max-norm of the
    update relative to the components' magnitudes ``max(scale_i, |z_i|)``).

    Once quadratic convergence is under way (the update shrank by 100 or more), the next
    update is estimated and the iteration stops if it would be below the tolerance. With
    ``perturbation`` None the estimate is the linear one, ``size²/previous`` (safe whatever
    the Newton matrix's error). Given the relative error δ of the Newton matrix, it is
    ``C·size² + δ·size`` with ``C = size/previous²`` from the last contraction: Newton's
    quadratic term plus the linear one that the matrix error adds. Given ``k_ratio`` =
    ``|z_k|/max(scale_k, |z_k|)`` for the component the point is located in (such as a
    fold's parameter), an early stop also needs the estimate below ``tol·k_ratio``: that
    component is then exact to ``tol`` relative to itself even when it is much smaller than
    its typical size."""
    if size <= tol:
        return True
    if math.isfinite(previous) and size <= 1e-2 * previous:
        if perturbation is None:
            estimate = size * size / previous
        else:
            estimate = size * (size * size / (previous * previous) + perturbation)
        if estimate <= tol and (k_ratio is None or estimate <= tol * k_ratio):
            return True
    # stagnation: the updates stopped shrinking, at a level below ``stall``
    return it >= 4 and size > 0.5 * previous and size <= stall


def accept_located(
    br: Bracket,
    z: np.ndarray,
    dg: Any,
    iterations: int,
    last_update: float,
    details: dict,
    tangent: np.ndarray | None = None,
    slack: float = 0.05,
    magnitudes: np.ndarray | None = None,
) -> Located | None:
    """A point a locating Newton converged to, as :class:`Located` — if it solves ``G = 0``
    to tolerance (or to its rounding floor, reckoned with the components' ``magnitudes`` if
    given, else their typical sizes) and lies in the step (within ``slack`` of it, 5% by
    default); else None (it converged to a point of another step, or off the curve)."""
    system = br.system
    rn = max_abs(system.residual(z))
    if not (rn <= br.options.tol or rn <= system.residual_floor(dg, z, magnitudes)):  # NaN too
        return None
    sigma = br.sigma(z)
    if not (-slack * abs(br.h) <= (sigma if br.h >= 0 else -sigma) <= (1 + slack) * abs(br.h)):
        return None
    details = {**details, "last_update": float(last_update)}
    return Located(
        z=z,
        sigma=sigma,
        status=PointStatus.CONVERGED,
        iterations=iterations,
        details=details,
        tangent=tangent,
        residual_norm=rn,
    )


def locate_component(br: Bracket, k: int, value: float) -> Located | None:
    """The curve point with ``z_k = value`` exactly (corrector with constraint row ``e_k``)."""
    o = br.options
    za, zb = br.z_a[k], br.z_b[k]
    theta = min(1.0, max(0.0, float((value - za) / (zb - za)))) if zb != za else 0.5
    row = np.zeros(br.z_a.size)
    row[k] = 1.0
    res = correct(br.system, br.arc.at(theta), row, value, o, budget=2)
    if not res.converged:
        return None
    z = res.z.copy()
    z[k] = value  # the constraint is linear: snap away the last rounding
    # the corrector's last factorization is [∂G/∂z; e_k] (at z up to its last update or
    # two): its solution t of [∂G/∂z; e_k] t = e_last has ∂G/∂z t = 0, a tangent
    return Located(
        z=z,
        sigma=br.sigma(z),
        status=PointStatus.CONVERGED,
        iterations=res.iterations,
        details={"method": "Newton with the component fixed"},
        tangent=oriented_tangent(res.lu.solve(unit_last(z.size)), br.row, br.weights),
    )
