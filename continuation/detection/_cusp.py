"""The special points of a fold curve (:class:`~..systems._fold.FoldSystem`):

- **cusp**: the normal-form coefficient ``a = ½⟨w, D²F[v, v]⟩`` changes sign; located by
  Newton on ``[F; g; a] = 0`` (n + 2 equations and unknowns), cross-checked by the parameter
  components of the fold curve's tangent (both vanish at a cusp);
- **second zero eigenvalue** (codimension 2, e.g. a limit point meeting a branch point): the
  determinant of the bordered matrix ``[[M, b], [cᵀ, 0]]`` changes sign (it is
  ``−cᵀ adj(M) b``, proportional to the product of the non-zero eigenvalues of ``M``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp

from .._errors import SingularMatrixError
from .._outcomes import Kind, PointStatus
from ..numerics._linalg import factor, inverse_magnitudes, scaled_max
from ..systems._curve import CurveSystem
from ..systems._fold import FoldSystem
from ._bracket import Bracket, Located, newton_done, tangent_at
from ._regula import locate_on_arc
from ._tests import TestFunction

if TYPE_CHECKING:
    from .._options import ContinuationOptions

_EPS = np.finfo(float).eps


class CuspTest(TestFunction):
    """The cusp coefficient ``a = ½⟨w, D²F[v, v]⟩`` of the fold: it changes sign at a cusp
    (located by Newton on ``[F; g; a] = 0``)."""

    __slots__ = ()
    kind = Kind.CUSP

    def __init__(self) -> None:
        super().__init__("cusp")

    def value(self, system, z, t, sdet) -> float:
        return system.cusp_coefficient(z)

    def locate(self, br: Bracket, f_a: float, f_b: float) -> Located:
        return _locate_cusp(br.system, br, f_a, f_b)


class Codim2Test(TestFunction):
    """The sign of det ``[[M, b], [cᵀ, 0]]``: it changes where ``M`` has a second zero
    eigenvalue (a limit point meeting a branch point, a Bogdanov–Takens point)."""

    __slots__ = ()
    kind = Kind.CODIM2

    def __init__(self) -> None:
        super().__init__("second zero eigenvalue")

    def value(self, system, z, t, sdet) -> float:
        return system.double_zero_test(z)[0]

    def locate(self, br: Bracket, f_a: float, f_b: float) -> Located:
        return _locate_codim2(br.system, br, f_a, f_b)


def _locate_cusp(system: CurveSystem, br: Bracket, f_a: float, f_b: float) -> Located:
    """Newton on ``[F; g; a] = 0`` from the regula-falsi estimate; Illinois if it fails."""
    assert isinstance(system, FoldSystem)
    theta = f_a / (f_a - f_b) if f_a != f_b else 0.5
    start = br.point_at(theta * br.h)
    z = start.z if start.converged else br.arc.at(theta)
    newton = _cusp_newton(system, br.options, z)
    if newton is not None:
        z, it, size = newton
        found = Located(
            z=z,
            sigma=br.sigma(z),
            status=PointStatus.CONVERGED,
            iterations=it,
            details={"method": "Newton on [F; g; a]", "last_update": size},
        )
    else:
        found = locate_on_arc(br, system.cusp_coefficient, f_a, f_b)
        found = found._replace(
            details={**found.details, "method": "Illinois on the cusp coefficient"}
        )
    tan = tangent_at(system, found.z, br.row, system.weights, br)
    details = dict(found.details)
    details.update(
        coefficient_before=float(f_a),
        coefficient_after=float(f_b),
        # the unfolding parameters of the cusp: the variable that turns and p2 (both
        # components of the fold curve's tangent vanish there)
        tangent_parameters={
            system.names[system.k]: float(tan[system.k]),
            system.p2: float(tan[-1]),
        },
        fold_branches=(system.values(br.z_a), system.values(br.z_b)),
        residual=float(np.max(np.abs(system.residual(found.z)))),
    )
    return found._replace(details=details)


#: the largest fold curve whose cusp is located by Newton (its coefficient's gradient is
#: differenced densely, component by component); larger ones by Illinois
CUSP_NEWTON_MAX_DIM = 200


def _cusp_newton(
    system: FoldSystem, o: ContinuationOptions, z: np.ndarray
) -> tuple[np.ndarray, int, float] | None:
    """Newton on ``[F; g; a] = 0`` from ``z``: the point, the iterations and the last
    update, or None if it fails (or the curve is too large)."""
    dim = system.dim
    previous = size = np.inf
    for it in range(1, o.max_locate_iterations + 1):
        if dim > CUSP_NEWTON_MAX_DIM:
            return None  # a dense gradient of the coefficient is too costly
        G = system.residual(z)
        a = system.cusp_coefficient(z)
        jac = system.jacobian(z)
        jac = jac.toarray() if sp.issparse(jac) else jac
        big = np.vstack([jac, _coefficient_gradient(system, z)[None, :]])
        rhs = -np.concatenate([G, [a]])
        try:
            dz = factor(big).solve(rhs)
        except SingularMatrixError:
            return None
        z = z + dz
        if not np.all(np.isfinite(z)):
            return None
        size = scaled_max(dz, inverse_magnitudes(system.scales, z))
        # the gradient of the coefficient is a finite difference: Newton converges linearly
        # and, with finite-difference Jacobians, stalls at the noise floor of the coefficient
        if newton_done(it, size, previous, o.locate_tol, stall=1e-9):
            return z, it, size
        previous = size
    return None


def _coefficient_gradient(system: FoldSystem, z: np.ndarray) -> np.ndarray:
    """The cusp coefficient's gradient at ``z`` by central differences (steps ε^{1/3} of
    the components' magnitudes)."""
    dim = system.dim
    grad = np.empty(dim)
    for i in range(dim):
        h = _EPS ** (1.0 / 3.0) * max(system.scales[i], abs(z[i]))
        e = np.zeros(dim)
        e[i] = h
        grad[i] = (system.cusp_coefficient(z + e) - system.cusp_coefficient(z - e)) / (2 * h)
    return grad


def _locate_codim2(system: CurveSystem, br: Bracket, f_a: float, f_b: float) -> Located:
    assert isinstance(system, FoldSystem)
    ref = system.double_zero_test(br.z_a)

    def f(z):
        try:
            sgn, logdet = system.double_zero_test(z)
        except SingularMatrixError:
            return 0.0
        return sgn * np.exp(min(logdet - ref[1], 700.0))

    fb = f(br.z_b)
    found = locate_on_arc(br, f, ref[0], fb if fb * ref[0] < 0 else -ref[0])
    details = {
        **found.details,
        "type": "second zero eigenvalue of the fold's matrix",
        "method": "Illinois on det[[M, b], [c^T, 0]]",
    }
    return found._replace(details=details)


__all__ = ["Codim2Test", "CuspTest"]
