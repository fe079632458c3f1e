"""The fold curve's system: a fold (limit point) continued in two parameters on the minimally
augmented system (Govaerts 2000; as in MatCont and BifurcationKit)

    G(u, p1, p2) = [F(u, p1, p2); g(u, p1, p2)],   [[M, b], [cᵀ, 0]] [v; g] = [0; 1],

where ``M`` is ``∂F/∂(u, p1)`` without the column of the variable that turns (``p1`` for an
ordinary fold, a monitored unknown for the fold of a snap-back), so the system has ``n + 1``
equations in ``n + 2`` unknowns. The bordering vectors ``b, c`` are replaced by the current
left/right null vectors after every accepted point (a new, immutable :class:`FoldSystem` each
time, carried by the tracer's state). ``∇g = −wᵀ(∂M/∂z)v`` is a directional difference of the
Jacobian. The system also gives the two quantities whose sign changes mark the special points
of a fold curve (:mod:`~..detection._cusp`): the cusp coefficient and the sign of the
bordered matrix's determinant.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import scipy.sparse as sp

from ..numerics._differences import second_derivative_row
from ..numerics._linalg import (
    bordered,
    bordered_square,
    factor,
    inverse_magnitudes,
    scaled_max,
    unit_last,
)
from ..problem._problem import as_matrix, as_vector, has_exact_jacobian
from ._curve import CurveSystem, state_weights

_EPS = np.finfo(float).eps


class _Memo:
    """The last bordered solve of a :class:`FoldSystem` and the point it was made at: a memo
    (the corrector asks for the residual and the Jacobian at the same point), which changes
    no result. Each system has its own; copies get a fresh one."""

    __slots__ = ("key", "value")

    def __init__(self) -> None:
        self.key: bytes | None = None
        self.value: Any = None


class FoldSystem(CurveSystem):
    """``[F; g]`` over ``z = (u, p1, p2)``; ``k`` is the index (in ``(u, p1)``) of the variable
    that turns at the fold; ``b``, ``c`` the bordering vectors (unit vectors of length n).

    Immutable while traced: :meth:`refreshed` returns a new system with the borders updated
    to the null vectors at a point; :meth:`through` builds the first one at a fold."""

    def __init__(
        self,
        problem,
        p1: str,
        p2: str,
        k: int,
        params: Mapping[str, float],
        state_weight: float | None,
        b: np.ndarray,
        c: np.ndarray,
    ) -> None:
        self.problem = problem
        self.p1, self.p2 = p1, p2
        self.params = dict(params)
        self.n = len(problem.unknowns)
        self.k = k
        self.names = tuple(problem.unknowns) + (p1, p2)
        self.dim = self.n + 2
        self.scales = np.ones(self.dim)
        self.base_weights = state_weights(self.n, 2, state_weight)
        self.weights = self.base_weights.copy()
        self.unit_weights = False
        keep = np.ones(self.n + 1, dtype=bool)
        keep[k] = False
        self._keep = keep  # columns of ∂F/∂(u, p1) forming M
        self.b = b
        self.c = c
        self._memo = _Memo()  # the last bordered solve (see bordered_solve)
        # differences of the Jacobian are reliable only if the Jacobian itself is exact
        self._exact_jacobian = self.derivatives_exact = has_exact_jacobian(problem)

    # -- pieces
    def _p(self, z):
        p = dict(self.params)
        p[self.p1] = z[self.n]
        p[self.p2] = z[self.n + 1]
        return p

    def f(self, z):
        try:
            r = self.problem.residual(z[: self.n], self._p(z))
        except ArithmeticError:  # at a trial point: as non-finite, as for a branch (system.py)
            return np.full(self.n, np.nan)
        if type(r) is not np.ndarray or r.dtype != float:  # (any protocol object's)
            r = as_vector(r, "the residual", lambda: self.values(z))
        return r

    def df(self, z):
        """``∂F/∂(u, p1, p2)``: n × (n + 2), dense or CSR."""
        u, p = z[: self.n], self._p(z)
        at = lambda: self.values(z)  # noqa: E731 (the point, for messages only)
        j = as_matrix(self.problem.jacobian(u, p), "the jacobian", at)
        f1 = as_vector(self.problem.param_jacobian(u, p, self.p1), "the param_jacobian", at)
        f2 = as_vector(self.problem.param_jacobian(u, p, self.p2), "the param_jacobian", at)
        if sp.issparse(j):
            return sp.hstack([j, sp.csr_matrix(np.column_stack([f1, f2]))], format="csr")
        out = np.empty((self.n, self.n + 2))
        out[:, : self.n] = j
        out[:, self.n] = f1
        out[:, self.n + 1] = f2
        return out

    def m_matrix(self, df):
        cols = np.flatnonzero(self._keep)
        if sp.issparse(df):
            return sp.csc_matrix(df)[:, cols]
        return df[:, cols]

    def bordered_solve(self, z, df=None):
        """``g``, right and left null vectors ``v`` (in M's columns), ``w``, the LU and df.

        The last result is cached: the corrector asks for the residual and the Jacobian at
        the same point, and every test function asks again at each accepted point."""
        key = z.tobytes()
        memo = self._memo
        if df is None and memo.key == key:
            return memo.value
        out = self._bordered_solve(z, df)
        memo.key, memo.value = key, out
        return out

    def _bordered_solve(self, z, df=None):
        df = self.df(z) if df is None else df
        lu = factor(bordered_square(self.m_matrix(df), self.b, self.c))
        e = unit_last(self.n + 1)
        x = lu.solve(e)
        y = lu.solve(e, trans=True)
        return x[-1], x[:-1], y[:-1], lu, df

    def lift(self, v):
        """A vector over M's columns as a direction in z (zero at k and at p2)."""
        out = np.zeros(self.dim)
        out[: self.n + 1][self._keep] = v
        return out

    @classmethod
    def through(
        cls,
        problem: Any,
        p1: str,
        p2: str,
        k: int,
        params: Mapping[str, float],
        state_weight: float | None,
        z: np.ndarray,
        seed: int = 0,
    ) -> FoldSystem:
        """The system at a fold ``z``: random unit borders, then twice replaced by the null
        vectors they give there."""
        rng = np.random.default_rng(seed)
        b = rng.standard_normal(len(problem.unknowns))
        c = rng.standard_normal(len(problem.unknowns))
        b /= np.linalg.norm(b)
        c /= np.linalg.norm(c)
        system = cls(problem, p1, p2, k, params, state_weight, b, c)
        for _ in range(2):
            system = system.refreshed(z)
        return system

    refreshes = True

    def refreshed(self, z: np.ndarray) -> FoldSystem:
        """The system with the borders replaced by the left and right null vectors at ``z``."""
        _, v, w, _, _ = self.bordered_solve(z)
        new = object.__new__(FoldSystem)
        new.__dict__.update(self.__dict__)
        new.b, new.c = w / np.linalg.norm(w), v / np.linalg.norm(v)
        new._memo = _Memo()
        return new

    # -- CurveSystem interface
    def residual(self, z):
        g, *_ = self.bordered_solve(z)
        out = np.empty(self.n + 1)
        out[: self.n] = self.f(z)
        out[self.n] = g
        return out

    def jacobian(self, z):
        g, v, w, _, df = self.bordered_solve(z)
        vt = self.lift(v)
        grad = -second_derivative_row(self.df, z, vt, w, None, self.scales)
        if sp.issparse(df):
            return sp.vstack([df, sp.csr_matrix(grad[None, :])], format="csr")
        out = np.empty((self.n + 1, self.dim))
        out[: self.n] = df
        out[self.n] = grad
        return out

    def bordered_jacobian(self, z, row):
        return bordered(self.jacobian(z), row)

    def residual_floor(self, dg, z, magnitudes=None) -> float:
        """With a differenced Jacobian, ``g`` carries the differences' error: about
        ε^{2/3} (central) or ε^{1/2} (forward) of the Jacobian's size, times |v|·|w|."""
        floor = super().residual_floor(dg, z, magnitudes)
        if self._exact_jacobian:
            return floor
        # an entry of ∂F/∂z_j differenced with a step rel·m_j (m_j = max(s_j, |z_j|)) is off
        # by about rel·T_i/m_j, T_i = Σ_k |∂F_i/∂z_k|·m_k the size of the terms of F_i; so
        # g = w·M·v is off by rel·(Σ_i |w_i| T_i)·(Σ_j |v_j|/m_j)
        _, v, w, _, df = self.bordered_solve(z)
        mags = np.maximum(self.scales, np.abs(z))
        terms = abs(df) @ mags
        noise = float(np.abs(w) @ terms) * float(np.abs(self.lift(v)) @ (1.0 / mags))
        rel = _EPS ** (0.5 if getattr(self.problem, "derivatives", "") == "forward" else 2.0 / 3.0)
        return max(floor, 10.0 * rel * noise)

    def _scaled_problem(self) -> None:
        with_typical = getattr(self.problem, "with_scales", None)
        if with_typical is not None:
            n, s = self.n, self.scales
            typical_p = {self.p1: float(s[n]), self.p2: float(s[n + 1])}
            self.problem = with_typical(s[:n], typical_p)
        self._memo = _Memo()

    def fixed_values(self):
        return {k: v for k, v in self.params.items() if k not in (self.p1, self.p2)}

    def values(self, z):
        out = dict(zip(self.problem.unknowns, map(float, z[: self.n])))
        out.update(self.params)
        out[self.p1] = float(z[self.n])
        out[self.p2] = float(z[self.n + 1])
        return out

    # -- tests on the fold curve
    def cusp_coefficient(self, z) -> float:
        """``½⟨w, D²F[v, v]⟩`` with the null vectors normalised by the current borders.

        With an analytic (or complex-step) Jacobian: a five-point central difference of
        ``∂F/∂z·v`` along ``v``. With a finite-difference Jacobian that would difference differences
        (noise ~1e-7 relative); the five-point second difference of ``w·F`` along ``v`` with
        step ε^{1/6} is used instead (noise ~1e-10 relative, set by the null vectors).
        """
        _, v, w, _, _ = self.bordered_solve(z)
        vt = self.lift(v)
        if self._exact_jacobian:
            row = second_derivative_row(self.df, z, vt, w, None, self.scales, accurate=True)
            return 0.5 * float(row @ vt)
        # the five-point second difference (truncation O(h⁴)) with a step of ε^{1/6}
        # relative to the components' magnitudes: rounding ε/h² and truncation h⁴ balance
        # at ~ε^{2/3} ≈ 4e-11 relative, where the three-point one (step ε^{1/4}) is ~1e-8
        h = _EPS ** (1.0 / 6.0) / scaled_max(vt, inverse_magnitudes(self.scales, z))
        f = self.f
        wf = [float(w @ f(z + (j * h) * vt)) for j in (-2, -1, 0, 1, 2)]
        second = (-wf[0] + 16.0 * wf[1] - 30.0 * wf[2] + 16.0 * wf[3] - wf[4]) / (12.0 * h * h)
        return 0.5 * second

    def double_zero_test(self, z) -> tuple[float, float]:
        """Sign and log|det| of ``[[M, b], [cᵀ, 0]]``."""
        _, _, _, lu, _ = self.bordered_solve(z)
        return lu.sign_det(), lu.log_abs_det()


__all__ = ["FoldSystem"]
