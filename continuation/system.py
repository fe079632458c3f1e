"""Curve systems: an underdetermined system ``G(z) = 0``, ``G: R^{m+1} -> R^m``, whose
solution set is the curve the tracer follows.

For an ordinary branch ``z = (u, p_free)`` and ``G = R``. Fold curves and other augmented
systems supply their own ``G`` with the same interface, so every special-point test, event,
target and bound works on them unchanged.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import scipy.sparse as sp

from .errors import ProblemDefinitionError
from .linalg import bordered


class CurveSystem:
    """Interface of what the tracer follows.

    Attributes: ``names`` (one per component of z), ``dim`` (= m + 1), ``weights`` (of the
    arclength inner product), ``problem``, ``fixed`` (values of parameters not in z).
    """

    names: tuple[str, ...]
    dim: int
    weights: np.ndarray

    def residual(self, z: np.ndarray) -> np.ndarray:  # pragma: no cover - interface
        raise NotImplementedError

    def jacobian(self, z: np.ndarray):  # pragma: no cover - interface
        raise NotImplementedError

    def values(self, z: np.ndarray) -> dict[str, float]:  # pragma: no cover - interface
        raise NotImplementedError

    def index(self, name: str) -> int | None:
        try:
            return self.names.index(name)
        except ValueError:
            return None

    def bordered_jacobian(self, z: np.ndarray, row: np.ndarray):
        """The square matrix ``[∂G/∂z; row]``."""
        return bordered(self.jacobian(z), row)

    def refresh(self, z: np.ndarray) -> None:
        """Called after each accepted point (augmented systems update their borders here)."""

    def fixed_values(self) -> dict[str, float]:
        """Parameters held fixed on this curve (reported as constant columns)."""
        return {}


def state_weights(n: int, n_params: int, state_weight: float | None) -> np.ndarray:
    w = np.ones(n + n_params)
    w[:n] = (1.0 / n) if state_weight is None else state_weight
    return w


class BranchSystem(CurveSystem):
    """``G(u, p_free) = R(u, p)``: one free parameter, the others held at their values."""

    def __init__(self, problem, free: str, params: Mapping[str, float] | None = None,
                 state_weight: float | None = None) -> None:
        self.problem = problem
        params = dict(problem.params if params is None else params)
        if free not in params:
            raise ProblemDefinitionError(
                f"free parameter {free!r} is not a parameter of the problem; "
                f"parameters are {sorted(params)}")
        self.free = free
        self.params = params
        self.n = len(problem.unknowns)
        self.names = tuple(problem.unknowns) + (free,)
        self.dim = self.n + 1
        self.weights = state_weights(self.n, 1, state_weight)

    def _p(self, z) -> dict[str, float]:
        p = dict(self.params)
        p[self.free] = z[-1]
        return p

    # residual and bordered_jacobian are the corrector's inner loop: the parameter dict is
    # built inline and the dense case checked first (for the tiny systems of most problems
    # the wrappers cost more than the user's functions)

    def residual(self, z):
        p = dict(self.params)
        p[self.free] = z[-1]
        r = self.problem.residual(z[:-1], p)
        if r.shape != (self.n,):
            raise ProblemDefinitionError(
                f"residual must return {self.n} values (one per unknown), got shape {r.shape}")
        return r

    def _parts(self, z):
        u = z[:-1]
        p = dict(self.params)
        p[self.free] = z[-1]
        problem = self.problem
        j = problem.jacobian(u, p)
        fp = problem.param_jacobian(u, p, self.free)
        if type(j) is not np.ndarray and sp.issparse(j):
            return j, fp, True
        n = self.n
        if j.shape != (n, n) or fp.shape != (n,):
            raise ProblemDefinitionError(
                f"jacobian must be {n}×{n} and param_jacobian of length {n}, "
                f"got shapes {j.shape} and {fp.shape}")
        return j, fp, False

    def jacobian(self, z):
        j, fp, sparse = self._parts(z)
        if sparse:
            return _sparse_border(j, fp, None)
        n = self.n
        dg = np.empty((n, n + 1))
        dg[:, :n] = j
        dg[:, n] = fp
        return dg

    def bordered_jacobian(self, z, row):
        j, fp, sparse = self._parts(z)
        if sparse:
            return _sparse_border(j, fp, row)
        n = self.n
        a = np.empty((n + 1, n + 1))
        a[:n, :n] = j
        a[:n, n] = fp
        a[n] = row
        return a

    def fixed_values(self) -> dict[str, float]:
        return {k: v for k, v in self.params.items() if k != self.free}

    def values(self, z) -> dict[str, float]:
        out = dict(zip(self.problem.unknowns, map(float, z[:-1])))
        out.update(self.params)
        out[self.free] = float(z[-1])
        return out


def _sparse_border(j, col: np.ndarray, row: np.ndarray | None):
    """``[j, col]`` (``row`` None) or ``[[j, col], [row]]`` as CSC, assembled in one pass."""
    jc = j.tocoo()
    n = jc.shape[0]
    k = jc.shape[1]
    parts_r = [jc.row, np.arange(n)]
    parts_c = [jc.col, np.full(n, k)]
    parts_d = [jc.data, col]
    shape = (n, k + 1)
    if row is not None:
        parts_r.append(np.full(k + 1, n))
        parts_c.append(np.arange(k + 1))
        parts_d.append(row)
        shape = (n + 1, k + 1)
    return sp.csc_matrix((np.concatenate(parts_d),
                          (np.concatenate(parts_r), np.concatenate(parts_c))), shape=shape)
