"""Stress variants: badly scaled versions of published examples, and branches that lie close to
each other.

- :func:`rescaled`: any example with its unknowns and parameters multiplied by constants
  (the residual evaluated at the unscaled values, the derivatives by the chain rule, the
  references, start and bounds multiplied by the same constants);
- :func:`scaled_cusp`, :func:`scaled_truss`, :func:`scaled_ab`, :func:`scaled_arch`: a fold at
  a parameter of size 10⁷–10⁸, a fold whose unknown is of size 10⁵ or 10⁻⁷, unknowns of
  sizes 10⁶ and 10⁻⁶ in one problem, branch points at a parameter of size 10⁹;
- :func:`parallel_s_curves`: two S-shaped branches 0.02 apart in the parameter, the trace
  must stay on its own.

Tight fold pairs are the cusp normal form at a = 10⁻⁴
(:func:`~cusp.examples.normal_forms.cusp_normal_form`) and the A → B reactor near its cusp
(:func:`~cusp.examples.chemistry.ab_reactor` with p3 = 2.45).
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import scipy.sparse as sps

from ._base import DPS, Example, Reference, make_example
from .chemistry import ab_reactor
from .normal_forms import cusp_normal_form
from .structures import shallow_arch
from .trusses import truss_green


def rescaled(
    example: Example,
    unknowns: Mapping[str, float] | None = None,
    params: Mapping[str, float] | None = None,
    *,
    name: str | None = None,
    derivatives: str = "analytic",
) -> Example:
    """``example`` in scaled variables: unknown ``U_i = s_i u_i`` and parameter
    ``P_j = c_j p_j`` for the factors given (1 for the others).

    The residual is the original one at the unscaled values, ``R(U/s, P/c)``; its Jacobian
    ``J(u, p) diag(1/s)`` and parameter derivatives ``∂R/∂p_j / c_j`` (the chain rule);
    the start, the bounds and every reference value are multiplied by their factors (a
    reference that is exact stays exact to one rounding). ``derivatives`` as for every
    example.
    """
    su = np.array([float((unknowns or {}).get(k, 1.0)) for k in example.unknowns])
    cp = {k: float((params or {}).get(k, 1.0)) for k in example.params}
    factor = {**dict(zip(example.unknowns, su)), **cp}
    base_residual, base_jacobian = example.residual, example.jacobian
    base_param_jacobian = example.param_jacobian

    def unscale(u, p):
        return u / su, {k: v / cp[k] for k, v in p.items()}

    def residual(u, p):
        return base_residual(*unscale(u, p))

    def jacobian(u, p):
        jac = base_jacobian(*unscale(u, p))
        if sps.issparse(jac):
            return sps.csc_matrix(jac @ sps.diags(1.0 / su))
        return np.asarray(jac) / su

    def param_jacobian(u, p, which):
        uu, pp = unscale(u, p)
        return np.asarray(base_param_jacobian(uu, pp, which)) / cp[which]

    def references():
        return tuple(
            ref._replace(values={k: v * factor[k] for k, v in ref.values.items()})
            for ref in example.references()
        )

    return make_example(
        name or f"{example.name}, rescaled",
        residual,
        example.unknowns,
        {k: v * cp[k] for k, v in example.params.items()},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=example.u0 * su,
        free=example.free,
        bounds={k: (lo * factor[k], hi * factor[k]) for k, (lo, hi) in example.bounds.items()},
        monitor=example.monitor,
        references=references,
    )


def scaled_cusp(scale: float = 1e8, *, derivatives: str = "analytic") -> Example:
    """The cusp normal form x³ − a x − b (a = 1, from b = −1) with b scaled by ``scale``:
    B = 10⁸ b, window B ∈ [−10⁸, 10⁸], folds at B = ±2·10⁸/(3√3) = ±3.849·10⁷
    (:func:`~cusp.examples.normal_forms.cusp_folds` times 10⁸)."""
    return rescaled(
        cusp_normal_form(),
        params={"b": scale},
        name=f"cusp normal form, b x {scale:g}",
        derivatives=derivatives,
    )


def scaled_truss(scale: float = 1e6, *, derivatives: str = "analytic") -> Example:
    """The Green-strain von Mises truss (H = 0.5) with its deflection scaled: V = scale·v;
    the limit points at V = scale·H(1 ∓ 1/√3) (:func:`~cusp.examples.trusses.truss_green_limits`
    times ``scale``; 10⁶: V = 2.11·10⁵ and 7.89·10⁵, 10⁻⁶: 2.11·10⁻⁷ and 7.89·10⁻⁷)."""
    return rescaled(
        truss_green(),
        unknowns={"v": scale},
        name=f"von Mises truss, v x {scale:g}",
        derivatives=derivatives,
    )


def scaled_ab(*, derivatives: str = "analytic") -> Example:
    """The A → B reactor (AUTO-07p ``ab``, p3 = 2) with its unknowns six orders of magnitude
    apart: U1 = 10⁶ u1, U2 = 10⁻⁶ u2; its two folds in p1 (:func:`~cusp.examples.chemistry.
    ab_folds`) with the unknowns scaled alike."""
    return rescaled(
        ab_reactor(),
        unknowns={"u1": 1e6, "u2": 1e-6},
        name="A → B reactor, u1 x 1e6, u2 x 1e-6",
        derivatives=derivatives,
    )


def scaled_arch(scale: float = 1e8, *, derivatives: str = "analytic") -> Example:
    """The shallow arch with e = 6 (two branch points and two limit points,
    :func:`~cusp.examples.structures.arch_references`) with its load scaled: P = 10⁸ p (the
    branch points at P = 3.88·10⁹ and −1.48·10⁹)."""
    return rescaled(
        shallow_arch(6.0),
        params={"p": scale},
        name=f"shallow arch, p x {scale:g}",
        derivatives=derivatives,
    )


def parallel_s_curves(delta: float = 0.02, *, derivatives: str = "analytic") -> Example:
    """Two parallel S-shaped branches: ``(x³ − x − b)(x³ − x − b + δ) = 0``, the cusp
    normal form's S-curve b = x³ − x and its copy shifted by δ in b (δ = 0.02, 1 % of the
    window; on the steep outer parts they are only δ/(3x² − 1) ≈ 0.005 apart in x). They
    never meet, so there is no branch point; on the first curve ∂F/∂x = δ (3x² − 1),
    ∂F/∂b = −δ.

    Unknown ``x``, parameters ``b`` (free) and ``delta``. Start on the first curve at b = −1
    (x = −1.324717957244746); bounds b ∈ [−1, 1]. Special points: the first curve's folds,
    x = ∓1/√3, b = ±2/(3√3) (:func:`~cusp.examples.normal_forms.cusp_folds`); the second
    curve's lie δ higher in b. Every traced point must satisfy x³ − x − b = 0.
    """

    def residual(u, p):
        g = u[0] ** 3 - u[0] - p["b"]
        return np.array([g * (g + p["delta"])])

    def jacobian(u, p):
        g = u[0] ** 3 - u[0] - p["b"]
        return np.array([[(3 * u[0] ** 2 - 1) * (2 * g + p["delta"])]])

    def param_jacobian(u, p, which):
        g = u[0] ** 3 - u[0] - p["b"]
        if which == "b":
            return np.array([-(2 * g + p["delta"])])
        if which == "delta":
            return np.array([g])
        raise KeyError(which)

    def references():
        import mpmath as mp

        with mp.workdps(DPS):
            x = 1 / mp.sqrt(3)
            return tuple(
                Reference(
                    "fold",
                    {"x": float(s * x), "b": float(-2 * (s * x) ** 3), "delta": delta},
                    ("b",),
                )
                for s in (-1, 1)
            )

    return make_example(
        "parallel S-curves",
        residual,
        ["x"],
        {"b": -1.0, "delta": delta},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[-1.324717957244746],
        free="b",
        bounds={"b": (-1.0, 1.0)},
        references=references,
    )
