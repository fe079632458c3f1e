"""Second derivatives of a curve system by differences of its Jacobian: the rows
``w·D²G[v, ·]`` that the fold, cusp and branch-point locators and the fold curve's equations
need (exact in exact arithmetic for quadratic ``G``)."""

from __future__ import annotations

import numpy as np

from ._linalg import inverse_magnitudes, max_abs, scaled_max

_EPS = float(np.finfo(float).eps)
_SQRT_EPS = _EPS**0.5
_CBRT_EPS = _EPS ** (1.0 / 3.0)


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


__all__ = ["second_derivative_row"]
