"""Factorizations of the square (bordered) systems of continuation, dense or sparse.

Dense systems call LAPACK's getrf/getrs directly: for the tiny systems of most problems the
wrappers of numpy/scipy cost several times the factorization itself.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.linalg import lapack

from .._errors import SingularMatrixError

_getrf = lapack.dgetrf
_getrs = lapack.dgetrs
_gesv = lapack.dgesv
_EPS = float(np.finfo(float).eps)


def permutation_parity(perm: np.ndarray) -> int:
    """+1 for an even permutation, −1 for an odd one (vectorised cycle count)."""
    perm = np.asarray(perm)
    n = perm.size
    label = np.minimum(np.arange(n), perm)
    nxt = perm.copy()
    # pointer jumping: after k rounds label[i] = min over 2^k successors; log2(n) rounds
    for _ in range(max(1, int(np.ceil(np.log2(max(n, 2))))) + 1):
        label = np.minimum(label, label[nxt])
        nxt = nxt[nxt]
    cycles = int(np.count_nonzero(label == np.arange(n)))
    return 1 if (n - cycles) % 2 == 0 else -1


def dense_factors(a: np.ndarray):
    """LAPACK getrf of a square float array: ``(lu, piv)``; SingularMatrixError on a zero or
    non-finite last pivot."""
    lu, piv, info = _getrf(a)
    if info > 0 or not math.isfinite(lu[-1, -1]):
        raise SingularMatrixError(f"matrix is singular (zero pivot {info})")
    return lu, piv


def dense_solve(a: np.ndarray, b: np.ndarray) -> tuple[DenseLU, np.ndarray]:
    """LAPACK gesv (factor and solve in one call) of a square float array: the factors and
    the solution; SingularMatrixError as :func:`dense_factors`."""
    lu, piv, x, info = _gesv(a, b)
    if info > 0 or not math.isfinite(lu[-1, -1]):
        raise SingularMatrixError(f"matrix is singular (zero pivot {info})")
    return DenseLU.from_factors(lu, piv), x


class DenseLU:
    """The LU factorization (partial pivoting) of a dense square matrix, by LAPACK getrf:
    solves (also transposed), the determinant's sign and log-magnitude."""

    __slots__ = ("lu", "piv", "n")

    def __init__(self, a: np.ndarray) -> None:
        self.lu, self.piv = dense_factors(a)
        self.n = a.shape[0]

    @classmethod
    def from_factors(cls, lu: np.ndarray, piv: np.ndarray) -> DenseLU:
        """Wrap the output of :func:`dense_factors` (no copy, no check)."""
        self = object.__new__(cls)
        self.lu, self.piv, self.n = lu, piv, lu.shape[0]
        return self

    def solve(self, b: np.ndarray, trans: bool = False) -> np.ndarray:
        return _getrs(self.lu, self.piv, b, 1 if trans else 0)[0]

    def sign_det(self) -> float:
        if self.n == 2:  # (the bordered matrices of scalar problems, spelled out)
            (a, _), (_, d) = self.lu.tolist()
            p, q = self.piv.tolist()
            odd = (a < 0) + (d < 0) + (p != 0) + (q != 1)
        elif self.n <= 16:
            odd = 0
            for i, (x, q) in enumerate(zip(self.lu.diagonal().tolist(), self.piv.tolist())):
                odd += (x < 0) + (i != q)
        else:
            odd = int(np.count_nonzero(np.diagonal(self.lu) < 0))
            odd += int(np.count_nonzero(self.piv != np.arange(self.n)))
        return -1.0 if odd % 2 else 1.0

    def log_abs_det(self) -> float:
        return float(np.sum(np.log(np.abs(np.diagonal(self.lu)))))


class PairLU:
    """The LU factorization (partial pivoting) of a 2×2 matrix ``[[a11, a12], [a21, a22]]``
    held as plain floats: the bordered systems of scalar problems (one unknown and the
    parameter), where LAPACK's wrappers cost several times the arithmetic. The operations
    are getrf's and getrs's (the multiplier by the pivot's reciprocal), so the results agree
    with :class:`DenseLU` to rounding. SingularMatrixError on a zero pivot.

    >>> lu = PairLU(2.0, 1.0, 4.0, 3.0)  # det 2; rows swapped for the pivot 4
    >>> lu.solve(np.array([1.0, 1.0])).tolist(), lu.solve(np.array([1.0, 1.0]), True).tolist()
    ([1.0, -1.0], [-0.5, 0.5])
    >>> lu.sign_det()
    1.0
    """

    __slots__ = ("u11", "u12", "l21", "u22", "swapped")
    n = 2

    def __init__(self, a11: float, a12: float, a21: float, a22: float) -> None:
        self.swapped = abs(a21) > abs(a11)
        if self.swapped:
            a11, a12, a21, a22 = a21, a22, a11, a12
        if a11 == 0.0:
            raise SingularMatrixError("matrix is singular (zero pivot 1)")
        self.l21 = a21 * (1.0 / a11)
        self.u11, self.u12, self.u22 = a11, a12, a22 - self.l21 * a12
        if self.u22 == 0.0:
            raise SingularMatrixError("matrix is singular (zero pivot 2)")

    def solve_pair(self, b1: float, b2: float) -> tuple[float, float]:
        """The solution for the right-hand side ``(b1, b2)``, as floats."""
        if self.swapped:
            b1, b2 = b2, b1
        x2 = (b2 - self.l21 * b1) / self.u22
        return (b1 - self.u12 * x2) / self.u11, x2

    def solve(self, b: np.ndarray, trans: bool = False) -> np.ndarray:
        b1, b2 = b.tolist()
        if not trans:
            return np.array(self.solve_pair(b1, b2))
        # Aᵀ = Uᵀ Lᵀ P: Uᵀ y = b, Lᵀ w = y, x = P w
        y1 = b1 / self.u11
        w2 = (b2 - self.u12 * y1) / self.u22
        w1 = y1 - self.l21 * w2
        return np.array((w2, w1) if self.swapped else (w1, w2))

    def sign_det(self) -> float:
        odd = (self.u11 < 0.0) + (self.u22 < 0.0) + self.swapped
        return -1.0 if odd % 2 else 1.0

    def log_abs_det(self) -> float:
        return math.log(abs(self.u11)) + math.log(abs(self.u22))


class SparseLU:
    """The LU factorization of a sparse square matrix by SuperLU, with the interface of
    :class:`DenseLU` (the determinant's sign from U's diagonal and the permutations')."""

    __slots__ = ("lu", "n")

    def __init__(self, a) -> None:
        try:
            self.lu = spla.splu(sp.csc_matrix(a))
        except RuntimeError as exc:  # SuperLU reports exact singularity this way
            raise SingularMatrixError(f"matrix is singular ({exc})") from None
        self.n = a.shape[0]

    def solve(self, b: np.ndarray, trans: bool = False) -> np.ndarray:
        return self.lu.solve(np.asarray(b, dtype=float), trans="T" if trans else "N")

    def sign_det(self) -> float:
        d = self.lu.U.diagonal()
        s = float(np.prod(np.sign(d)))
        return s * permutation_parity(self.lu.perm_r) * permutation_parity(self.lu.perm_c)

    def log_abs_det(self) -> float:
        return float(np.sum(np.log(np.abs(self.lu.U.diagonal()))))


def factor(a):
    """LU factorization of a square dense array or sparse matrix."""
    return (
        DenseLU(a)
        if type(a) is np.ndarray
        else (SparseLU(a) if sp.issparse(a) else DenseLU(np.asarray(a, dtype=float)))
    )


def bordered(dg, row: np.ndarray):
    """The square matrix ``[dg; row]`` (``dg`` is m × (m+1), dense or sparse)."""
    if type(dg) is not np.ndarray and sp.issparse(dg):
        return sp.vstack([dg, sp.csr_matrix(row[None, :])], format="csc")
    m, k = dg.shape
    a = np.empty((m + 1, k))
    a[:m] = dg
    a[m] = row
    return a


def delete_column(dg, k: int):
    """``dg`` without column ``k`` (a view when ``k`` is the last column of a dense array)."""
    if type(dg) is not np.ndarray and sp.issparse(dg):
        keep = np.ones(dg.shape[1], dtype=bool)
        keep[k] = False
        return sp.csc_matrix(dg)[:, np.flatnonzero(keep)]
    if k == dg.shape[1] - 1 or k == -1:
        return dg[:, :-1]
    return np.delete(dg, k, axis=1)


def bordered_square(m, b: np.ndarray, c: np.ndarray):
    """``[[m, b], [c^T, 0]]`` for a square ``m``."""
    if type(m) is not np.ndarray and sp.issparse(m):
        return sp.bmat(
            [[m, sp.csc_matrix(b[:, None])], [sp.csr_matrix(c[None, :]), None]], format="csc"
        )
    n = m.shape[0]
    a = np.zeros((n + 1, n + 1))
    a[:n, :n] = m
    a[:n, n] = b
    a[n, :n] = c
    return a


def unit_last(n: int) -> np.ndarray:
    """The unit vector ``(0, …, 0, 1)`` of length ``n``: the right-hand side that picks the
    border row of a bordered system."""
    e = np.zeros(n)
    e[-1] = 1.0
    return e


def max_abs(x: np.ndarray) -> float:
    """Max-norm ``max |x_i|``; NaN if any entry is NaN or infinite. Plain Python for the tiny
    vectors of most problems (numpy's reductions cost more than the arithmetic there), with
    the one- and two-component vectors of scalar problems (state, and state with parameter)
    spelled out: a third of the general path's cost, and these are most calls."""
    n = x.size
    if n == 1:
        v = abs(x.item())
        return v if v < math.inf else math.nan
    if n == 2:
        a, b = x.tolist()
        a, b = abs(a), abs(b)
        m = a if a >= b else b
        return m if m < math.inf and a == a and b == b else math.nan
    if n <= 32:
        vals = x.tolist()
        if not vals:
            return 0.0
        total = sum(vals)  # NaN or ±inf if any entry is (or, harmlessly, on overflow)
        if total - total != 0.0 and not all(math.isfinite(v) for v in vals):
            return math.nan
        hi, lo = max(vals), min(vals)
        return abs(hi) if hi >= -lo else -lo
    m = float(np.abs(x).max())
    return m if math.isfinite(m) else math.nan


def weighted_square(x: np.ndarray, weights: np.ndarray | None) -> float:
    """``Σ_i w_i x_i²``, the square of the weighted (arclength) norm (``weights`` None: all
    1); spelled out in plain Python for the two components of scalar problems (state and
    parameter), where numpy's two calls cost three times the arithmetic."""
    if weights is None:
        return float(x.dot(x))
    if x.size == 2:
        a, b = x.tolist()
        p, q = weights.tolist()
        return p * a * a + q * b * b
    return float(x.dot(weights * x))


def inverse_magnitudes(scales: np.ndarray, z: np.ndarray) -> Any:
    """``1/max(scales_i, |z_i|)`` per component: multiplies an update into relative terms
    (a Python list for the few components of most problems, an array otherwise)."""
    if z.size == 2:  # (scalar problems, spelled out)
        (s, r), (a, b) = scales.tolist(), z.tolist()
        a, b = abs(a), abs(b)
        return [1.0 / (s if s >= a else a), 1.0 / (r if r >= b else b)]
    if z.size <= 32:
        return [1.0 / (s if s >= a else a) for s, a in zip(scales.tolist(), map(abs, z.tolist()))]
    return 1.0 / np.maximum(scales, np.abs(z))


def scaled_max(x: np.ndarray, inverse: Any) -> float:
    """``max_i |x_i|·inverse_i`` (NaN if any entry of ``x`` is NaN or infinite): the size of
    an update relative to the components' magnitudes (see :func:`inverse_magnitudes`)."""
    if type(inverse) is list:
        vals = x.tolist()
        if len(vals) == 2:  # spelled out for scalar problems (state and parameter)
            a, b = abs(vals[0]) * inverse[0], abs(vals[1]) * inverse[1]
            m = a if a >= b else b
            return m if m < math.inf and a == a and b == b else math.nan
        m = 0.0
        for v, w in zip(vals, inverse):
            a = abs(v) * w
            if not a <= m:  # larger, or NaN
                if a != a:
                    return math.nan
                m = a
        return m if m < math.inf else math.nan
    return max_abs(x * inverse)


def rounding_floor(block, z: np.ndarray, scales: np.ndarray | None = None) -> float:
    """Residual size attributable to rounding: ``100·eps·max_i Σ_j |block_ij|·m_j`` with
    ``m_j = max(scales_j, |z_j|)`` the magnitude of component j (``block``: the state part
    of the Jacobian, where the large terms of a fine discretisation live; a parameter
    derivative differenced across a jump of the residual would inflate it). Each residual
    is a sum of terms of about ``block_ij·z_j``; rounding them leaves this much."""
    k = block.shape[1]
    if scales is None:
        scales = np.ones(k)
    mags = np.maximum(scales[:k], np.abs(z[:k]))
    if sp.issparse(block):
        level = float(np.max(abs(block) @ mags)) if block.shape[0] else 0.0
    else:
        level = math.nan
        if block.size <= 64:  # plain Python for tiny blocks; NaN/inf left to numpy
            m = mags.tolist()
            sums = [sum(abs(a) * b for a, b in zip(r, m)) for r in block.tolist()]
            if math.isfinite(sum(sums)):
                level = max(sums, default=0.0)
        if level != level:
            level = float(np.max(np.abs(block) @ mags)) if block.shape[0] else 0.0
    return 100 * _EPS * level
