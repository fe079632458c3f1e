"""Locating special points inside an accepted step ``z_a -> z_b``.

- folds (turning points of any component ``z_k``): Newton on the minimally augmented system
  ``[G(z); g_k(z)] = 0``, with ``g_k`` from the bordered system of ``∂G/∂z`` without column
  ``k`` (Govaerts, *Numerical methods for bifurcations of dynamical equilibria*, 2000) —
  quadratic convergence, bordering vectors updated every iteration;
- component targets and bounds: the corrector with the constraint ``z_k = value`` (exact);
- events and branch points: the Illinois variant of regula falsi on the pseudo-arclength,
  each evaluation a corrected point on the curve.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from .corrector import correct
from .errors import SingularMatrixError
from .linalg import (
    PairLU,
    bordered,
    bordered_square,
    delete_column,
    dense_solve,
    factor,
    getrs,
    inverse_magnitudes,
    max_abs,
    scaled_max,
    unit_last,
)

if TYPE_CHECKING:
    from .options import ContinuationOptions

_EPS = float(np.finfo(float).eps)
_SQRT_EPS = _EPS**0.5
_CBRT_EPS = _EPS ** (1.0 / 3.0)
# relative error of the fold Newton's matrix when the Jacobian is exact: its last row is a
# forward difference of the Jacobian (√ε ≈ 1.5e-8, with a margin for its truncation error)
_FORWARD_D2_ERROR = 1e-7


@dataclass
class Bracket:
    """An accepted step: end points, unit tangents and the pseudo-arclength ``h`` of ``z_b``."""

    system: Any
    """The curve system (a :class:`~.system.CurveSystem`)."""
    z_a: np.ndarray
    t_a: np.ndarray
    z_b: np.ndarray
    t_b: np.ndarray
    weights: np.ndarray
    options: ContinuationOptions
    row: np.ndarray = field(init=False)
    h: float = field(init=False)
    d_a: np.ndarray = field(init=False)
    d_b: np.ndarray = field(init=False)
    _basis: np.ndarray | None = field(init=False, default=None, repr=False)

    def __post_init__(self) -> None:
        self.row = self.weights * self.t_a
        self.h = float(self.row.dot(self.z_b - self.z_a))
        # the interpolant is parametrised by σ, not by arclength: its end derivatives are
        # dz/dσ = t/(row·t) (t_b is tilted by the step's turn, up to max_angle)
        self.d_a = self.t_a / float(self.row.dot(self.t_a))
        cos_b = float(self.row.dot(self.t_b))
        self.d_b = self.t_b / cos_b if cos_b > 0.1 else self.t_b

    def sigma(self, z: np.ndarray) -> float:
        return float(self.row.dot(z - self.z_a))

    def _hermite(self, coefficients) -> np.ndarray:
        """``c0·z_a + c1·h·d_a + c2·z_b + c3·h·d_b`` (one product with the stacked data; a
        row of coefficients per result)."""
        basis = self._basis
        if basis is None:
            basis = self._basis = np.array(
                (self.z_a, self.h * self.d_a, self.z_b, self.h * self.d_b)
            )
        return np.array(coefficients).dot(basis)

    def guess(self, theta: float) -> np.ndarray:
        """Cubic Hermite interpolation between the end points (θ ∈ [0, 1])."""
        return self._hermite(self._weights(theta))

    def guess_derivative(self, theta: float) -> np.ndarray:
        """``dz/dσ`` of the interpolant at θ."""
        return self._hermite(self._derivative_weights(theta))

    def guess_and_derivative(self, theta: float) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`guess` and :meth:`guess_derivative` at θ, in one product."""
        both = self._hermite((self._weights(theta), self._derivative_weights(theta)))
        return both[0], both[1]

    @staticmethod
    def _weights(s: float) -> tuple[float, float, float, float]:
        s2 = s * s
        s3 = s2 * s
        return (2 * s3 - 3 * s2 + 1, s3 - 2 * s2 + s, -2 * s3 + 3 * s2, s3 - s2)

    def _derivative_weights(self, s: float) -> tuple[float, float, float, float]:
        s2 = s * s
        h = self.h
        return (
            (6 * s2 - 6 * s) / h,
            (3 * s2 - 4 * s + 1) / h,
            (-6 * s2 + 6 * s) / h,
            (3 * s2 - 2 * s) / h,
        )

    def turning_theta(self, k: int) -> float:
        """θ ∈ [0, 1] where component ``k`` of the Hermite interpolant is stationary: the
        root of its derivative, a quadratic in θ that changes sign on [0, 1] when
        ``t_a[k]`` and ``t_b[k]`` do. On the benchmark folds (cusp, truss) the interpolant
        there is 1e-5 to 3e-3 off the fold, against 1e-3 to 1e-1 at the zero of the linearly
        interpolated tangent component: the fold Newton needs 2–3 iterations, not 3–5."""
        ta, tb = float(self.d_a[k]), float(self.d_b[k])
        if ta == tb:
            return 0.5
        linear = min(1.0, max(0.0, ta / (ta - tb)))
        delta = float(self.z_b[k] - self.z_a[k]) / self.h
        a = 3.0 * (ta + tb) - 6.0 * delta
        b = 6.0 * delta - 4.0 * ta - 2.0 * tb
        disc = b * b - 4.0 * a * ta
        if ta * tb > 0 or disc < 0 or not math.isfinite(disc):
            return linear
        q = -0.5 * (b + math.copysign(math.sqrt(disc), b))
        roots = [
            r
            for r in ((q / a) if a != 0 else math.nan, (ta / q) if q != 0 else math.nan)
            if 0.0 <= r <= 1.0
        ]
        return min(roots, key=lambda r: abs(r - linear)) if roots else linear

    def pair_theta(self, k: int) -> float | None:
        """θ ∈ (0, 1) between two turning points of component ``k`` of the interpolant that
        leave no net sign change of its derivative (see :func:`hermite_turning_pair`)."""
        delta = float(self.z_b[k] - self.z_a[k]) / self.h
        return hermite_turning_pair(float(self.d_a[k]), float(self.d_b[k]), delta)

    def point_at(self, sigma: float, strict: bool = False, start=None):
        """The curve point whose pseudo-arclength from ``z_a`` (along ``t_a``) is ``sigma``."""
        o = self.options
        theta = sigma / self.h if self.h != 0 else 0.0
        z0 = self.guess(theta) if start is None else start
        c = self.row.dot(self.z_a) + sigma
        return correct(self.system, z0, self.row, c, o, budget=2, strict=strict)

    def polish(self, z: np.ndarray, sigma: float) -> np.ndarray:
        """Newton to the update tolerance (not just the residual tolerance) at ``sigma``."""
        res = self.point_at(sigma, strict=True, start=z)
        return res.z if res.converged else z


class Located(NamedTuple):
    """A special point located inside a step (immutable).

    ``sigma``: its pseudo-arclength from the step's start; ``status``: ``"converged"`` or
    ``"guess"`` (only bracketed); ``details``: what the locating method reports."""

    z: np.ndarray
    sigma: float
    status: str
    iterations: int
    details: Mapping = MappingProxyType({})
    tangent: np.ndarray | None = None
    """Unit tangent at ``z`` oriented like the step, when the locating iteration gave it."""
    residual_norm: float | None = None
    """Max-norm of the residual at ``z``, when the locating iteration computed it."""


def hermite_turning_pair(ta: float, tb: float, delta: float) -> float | None:
    """Two turning points of one component inside a step, seen by its cubic Hermite
    interpolant: ``ta``, ``tb`` the component's derivatives with respect to θ ∈ [0, 1]
    (divided by the step's length ``h``) at the ends, ``delta`` its change over the step
    divided by ``h``. The interpolant's derivative ``ta + bθ + aθ²`` (a = 3(ta + tb) − 6δ,
    b = 6δ − 4ta − 2tb) has the same sign at both ends but two roots inside when its vertex
    lies in (0, 1) with the other sign; the vertex θ is returned (else None): a tight S-curve
    whose two folds one step spans, which the end values alone cannot show.

    >>> # x³ − a x at a = 0.03 over x ∈ [−0.4, 0.4]: folds at x = ±0.1
    >>> round(hermite_turning_pair(3 * 0.16 - 0.03, 3 * 0.16 - 0.03, 0.16 - 0.03), 12)
    0.5
    """
    if not ta * tb > 0.0:
        return None
    a = 3.0 * (ta + tb) - 6.0 * delta
    if a == 0.0:
        return None
    b = 6.0 * delta - 4.0 * ta - 2.0 * tb
    theta = -b / (2.0 * a)
    if not 0.0 < theta < 1.0:
        return None
    vertex = ta - b * b / (4.0 * a)
    return theta if vertex * ta < 0.0 else None


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
    system, z: np.ndarray, row: np.ndarray, weights: np.ndarray, br: Bracket | None = None
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
        t = br.guess_derivative(min(1.0, max(0.0, br.sigma(z) / br.h)))
    return t / math.sqrt(t.dot(weights * t))


def second_derivative_row(
    jacobian,
    z: np.ndarray,
    v: np.ndarray,
    w: np.ndarray,
    j0=None,
    scales=None,
    accurate: bool = False,
) -> np.ndarray:
    """``∇_z (w·J(z) v) = w·D²G(z)[v, ·]`` by central differences of ``jacobian(z)`` along
    ``v`` (exact in exact arithmetic for quadratic G; error O(h²) otherwise), or, given
    ``j0 = jacobian(z)``, by a forward difference (one evaluation fewer; relative error
    ~1e-8, enough for a Newton matrix, not for a differenced Jacobian), or, if
    ``accurate``, by the five-point central difference (two evaluations more; error O(h⁴):
    ~ε^{4/5} ≈ 3e-13 relative instead of ~ε^{2/3} ≈ 4e-11, for a test function whose zero
    is located). The step moves each component by at most ε^{1/3} (ε^{1/2}, ε^{1/5}) of
    its magnitude ``max(scales_i, |z_i|)``."""
    vmax = max_abs(v)
    if vmax == 0.0:
        return np.zeros(z.size)
    if scales is None:
        scales = np.ones(z.size)
    scale = 1.0 / scaled_max(v, inverse_magnitudes(scales, z))
    if j0 is not None:
        z1 = z + (_SQRT_EPS * scale) * v
        h = max_abs(z1 - z) / vmax  # the step actually taken
        return (jacobian(z1) - j0).T.dot(w) / h
    if accurate:
        h = _EPS**0.2 * scale
        near = jacobian(z + h * v).T.dot(w) - jacobian(z - h * v).T.dot(w)
        far = jacobian(z + 2.0 * h * v).T.dot(w) - jacobian(z - 2.0 * h * v).T.dot(w)
        return (8.0 * near - far) / (12.0 * h)
    h = _CBRT_EPS * scale
    return (jacobian(z + h * v).T.dot(w) - jacobian(z - h * v).T.dot(w)) / (2.0 * h)


def minimally_augmented(
    system, z: np.ndarray, k: int, b: np.ndarray, c: np.ndarray, e: np.ndarray | None = None
):
    """Test function ``g`` of the fold in component ``k``, its right/left null vectors and the
    Jacobian ``dg`` of G at ``z``: ``[[M, b], [c^T, 0]] [v; g] = [0; 1]`` with ``M = ∂G/∂z``
    without column ``k`` (``e``: that right-hand side, if the caller holds one)."""
    dg = system.jacobian(z)
    a = bordered_square(delete_column(dg, k), b, c)
    if e is None:
        e = unit_last(b.size + 1)
    if type(a) is np.ndarray:
        lu, piv, x = dense_solve(a, e)
        y = getrs(lu, piv, e, trans=True)
    else:
        lu = factor(a)
        x = lu.solve(e)
        y = lu.solve(e, trans=True)
    return x[-1], x[:-1], y[:-1], dg


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


def locate_fold(
    br: Bracket, k: int, start: np.ndarray | None = None, tangent: np.ndarray | None = None
) -> Located | None:
    """Newton on ``[G(z); g_k(z)] = 0`` started from the Hermite interpolant of the bracket
    (or from ``start`` with its ``tangent``); None if it fails or leaves the bracket."""
    o = br.options
    system = br.system
    if start is None or tangent is None:
        z, tangent = br.guess_and_derivative(br.turning_theta(k))
    if start is not None:
        z = start.copy()
    if getattr(system, "scalar", False):  # a curve of two components: in plain floats
        found = _locate_fold_pair(br, k, z, tangent)
        if found is not _UNDECIDED:
            return found
    # the components other than k (a slice for the usual fold in the last one)
    keep = slice(None, -1) if k == z.size - 1 else np.arange(z.size) != k
    v0 = tangent[keep].copy()
    v0 /= math.sqrt(v0.dot(v0))
    b = c = v0
    rhs = np.empty(z.size)
    vt = np.zeros(z.size)
    e = unit_last(z.size)
    exact = getattr(system, "exact_jacobian", False)
    jacobian, residual = system.jacobian, system.residual
    converged, it, previous = False, 0, math.inf
    for it in range(1, o.max_locate_iterations + 1):
        try:
            g, v, w, dg = minimally_augmented(system, z, k, b, c, e)
        except SingularMatrixError:
            return None
        vt[keep] = v
        # the Newton system [∂G/∂z; ∇g] dz = −[G; g] with ∇g = −w·D²G[v, ·], solved for
        # d = −dz with that row negated (sign flips are exact: bitwise the same update)
        rhs[:-1] = residual(z)
        rhs[-1] = -g
        scales = system.scales
        a = bordered(dg, second_derivative_row(jacobian, z, vt, w, dg if exact else None, scales))
        try:
            d = dense_solve(a, rhs)[2] if type(a) is np.ndarray else factor(a).solve(rhs)
        except SingularMatrixError:
            return None
        inv = inverse_magnitudes(scales, z)
        size = scaled_max(d, inv)
        if not math.isfinite(size):
            return None
        z = z - d
        nb, nc = math.sqrt(w.dot(w)), math.sqrt(v.dot(v))
        if nb > 0 and nc > 0:
            b, c = w / nb, v / nc
        # stagnation accepted up to 1e-6: ill-conditioned systems (cond ~ N² for discretised
        # operators) and forward differences stall there; the fold's parameter is still
        # exact to second order, its state to the accuracy of the derivatives
        zk = abs(float(z[k]))
        k_ratio = zk / max(float(scales[k]), zk)
        if newton_done(
            it,
            size,
            previous,
            o.locate_tol,
            stall=1e-6,
            perturbation=_FORWARD_D2_ERROR if exact else None,
            k_ratio=k_ratio,
        ):
            converged = True
            break
        previous = size
    if not converged:
        return None
    # the tangent at a fold in z_k spans the kernel of ∂G/∂z, which has no k component: v
    # (from the last iterate, one update of ≤ locate_tol away)
    details = {"method": "minimally augmented Newton", "test_function": float(g)}
    return accept_located(br, z, dg, it, size, details, oriented_tangent(vt, br.row, br.weights))


_UNDECIDED = object()


def _locate_fold_pair(br: Bracket, k: int, z: np.ndarray, tangent: np.ndarray) -> Any:
    """:func:`locate_fold` on a curve of two components in plain floats (``system.scalar``):
    with one unknown the minimally augmented system has a closed form — ``M = ∂G/∂z_j``
    (j ≠ k) is a number, ``v = 1/c``, ``w = 1/b``, ``g = −M/(bc)`` — and the Newton matrix
    ``[∂G/∂z; w·D²G[v, ·]]`` is 2×2 (:class:`~.linalg.PairLU`); the second derivatives are
    differenced as :func:`second_derivative_row` does, and the stopping test is the same.
    The located point, or None if Newton fails; ``_UNDECIDED`` where a value is not finite,
    a callback returns another type or a matrix is singular (the array path then runs)."""
    o, system = br.options, br.system
    j = 1 - k
    if not abs(tangent[j]) > 0.0:
        return _UNDECIDED
    x = z.tolist()
    s = system.scales.tolist()
    b = c = 1.0 if tangent[j] > 0 else -1.0
    exact = system.exact_jacobian
    jac_row, res = system.scalar_jacobian, system.scalar_residual
    converged, it, previous, size = False, 0, math.inf, math.inf
    for it in range(1, o.max_locate_iterations + 1):
        zz = np.array(x)
        row0 = jac_row(zz)
        G = res(zz)
        if row0 is None or G is None:
            return _UNDECIDED
        v, w = 1.0 / c, 1.0 / b
        g = -row0[j] * v / b
        # w·D²G[v·e_j, ·] by differences of the Jacobian row along e_j (the step of
        # second_derivative_row: forward for exact derivatives, central otherwise)
        scale = 1.0 / (abs(v) * (1.0 / max(s[j], abs(x[j]))))
        if exact:
            z1 = list(x)
            z1[j] = x[j] + (_SQRT_EPS * scale) * v
            h = abs(z1[j] - x[j]) / abs(v)
            up, down = jac_row(np.array(z1)), row0
        else:
            h = _CBRT_EPS * scale
            zp, zm = list(x), list(x)
            zp[j], zm[j] = x[j] + h * v, x[j] - h * v
            up, down, h = jac_row(np.array(zp)), jac_row(np.array(zm)), 2.0 * h
        if up is None or down is None:
            return _UNDECIDED
        try:
            lu = PairLU(row0[0], row0[1], (up[0] - down[0]) * w / h, (up[1] - down[1]) * w / h)
        except SingularMatrixError:
            return None
        d0, d1 = lu.solve_pair(G, -g)
        i0, i1 = inverse_magnitudes(system.scales, zz)
        size = max(abs(d0) * i0, abs(d1) * i1)
        if not size < math.inf:
            return None
        x = [x[0] - d0, x[1] - d1]
        b, c = (1.0 if w > 0 else -1.0), (1.0 if v > 0 else -1.0)
        zk = abs(x[k])
        if newton_done(
            it, size, previous, o.locate_tol, stall=1e-6,
            perturbation=_FORWARD_D2_ERROR if exact else None, k_ratio=zk / max(s[k], zk),
        ):  # fmt: skip
            converged = True
            break
        previous = size
    if not converged:
        return None
    vt = np.zeros(2)
    vt[j] = v
    details = {"method": "minimally augmented Newton", "test_function": float(g)}
    dg = np.array([row0])
    return accept_located(
        br, np.array(x), dg, it, size, details, oriented_tangent(vt, br.row, br.weights)
    )


def accept_located(
    br: Bracket,
    z: np.ndarray,
    dg: Any,
    iterations: int,
    last_update: float,
    details: dict,
    tangent: np.ndarray | None = None,
) -> Located | None:
    """A point a locating Newton converged to, as :class:`Located` — if it solves ``G = 0``
    to tolerance (or to its rounding floor) and lies in the step (within 5% of it); else
    None (it converged to a point of another step, or off the curve)."""
    system = br.system
    rn = max_abs(system.residual(z))
    if not (rn <= br.options.tol or rn <= system.residual_floor(dg, z)):  # NaN fails too
        return None
    sigma = br.sigma(z)
    if not (-0.05 * abs(br.h) <= (sigma if br.h >= 0 else -sigma) <= 1.05 * abs(br.h)):
        return None
    details = {**details, "last_update": float(last_update)}
    return Located(z, sigma, "converged", iterations, details, tangent, rn)


def locate_component(br: Bracket, k: int, value: float) -> Located | None:
    """The curve point with ``z_k = value`` exactly (corrector with constraint row ``e_k``)."""
    o = br.options
    za, zb = br.z_a[k], br.z_b[k]
    theta = min(1.0, max(0.0, float((value - za) / (zb - za)))) if zb != za else 0.5
    row = np.zeros(br.z_a.size)
    row[k] = 1.0
    res = correct(br.system, br.guess(theta), row, value, o, budget=2)
    if not res.converged:
        return None
    z = res.z.copy()
    z[k] = value  # the constraint is linear: snap away the last rounding
    # the corrector's last factorization is [∂G/∂z; e_k] (at z up to its last update or
    # two): its solution t of [∂G/∂z; e_k] t = e_last has ∂G/∂z t = 0, a tangent
    return Located(
        z,
        br.sigma(z),
        "converged",
        res.iterations,
        {"method": "Newton with the component fixed"},
        tangent=oriented_tangent(res.lu.solve(unit_last(z.size)), br.row, br.weights),
    )
