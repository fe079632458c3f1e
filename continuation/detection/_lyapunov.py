"""The first Lyapunov coefficient of a Hopf point, in Kuznetsov's normalisation.

For ``M u' = R(u, p)`` with ``A = ∂R/∂u`` having the simple pair ``±iω`` of the pencil
``(A, M)``, right eigenvector ``q`` (``A q = iω M q``, ``qᴴq = 1``) and adjoint ``p``
(``Aᵀ p = −iω Mᵀ p``, ``pᴴ M q = 1``),

    l1 = 1/(2ω) · Re[ pᴴC(q, q, q̄) − 2 pᴴB(q, A⁻¹B(q, q̄)) + pᴴB(q̄, (2iωM − A)⁻¹B(q, q)) ],

``B`` and ``C`` the second and third derivatives of ``R`` in ``u`` (Kuznetsov, *Elements of
Applied Bifurcation Theory*, 3rd ed., §3.5 and (10.56) in §10.2, as MatCont reports it). With
``M = I`` it is the book's formula; with a mass matrix it is the book's formula for
``u' = M⁻¹R`` written without the inverse: ``M⁻¹A`` has the eigenvector ``q`` and the adjoint
``Mᵀp``, so ``⟨Mᵀp, M⁻¹x⟩ = pᴴx``, ``(M⁻¹A)⁻¹M⁻¹ = A⁻¹`` and
``(2iω − M⁻¹A)⁻¹M⁻¹ = (2iωM − A)⁻¹``. A singular ``M`` (algebraic equations) is allowed: the
pencil is inverted, never ``M``.

The forms are the problem's own ``second_derivative(u, p, x, y)`` and
``third_derivative(u, p, x, y, z)`` (real directions, returning ``D²R[x, y]`` and
``D³R[x, y, z]``) when it has them, else differences of the residual along real directions,
combined by polarization and Richardson-extrapolated (error ``O(h⁴)`` plus rounding ``ε/h²``,
``ε/h³``: about 1e-8 relative for a smooth residual of unit scale). Complex arguments are
expanded by multilinearity into real ones.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.linalg import lapack

from .._errors import SingularMatrixError

_EPS = float(np.finfo(float).eps)
#: relative steps of the second and third differences (optimal for O(h⁴) after Richardson)
H2, H3 = 2e-3, 1e-2


class Forms:
    """``B(x, y)`` and ``C(q, q, q̄)`` of a residual at ``(u, p)`` (complex arguments)."""

    def __init__(self, problem: Any, u: np.ndarray, p: Mapping[str, float]) -> None:
        self.u = np.asarray(u, dtype=float)
        self.p = dict(p)
        self._f: Callable[[np.ndarray], np.ndarray] = lambda v: np.asarray(
            problem.residual(self.u + v, self.p), dtype=float
        )
        self._second = getattr(problem, "second_derivative", None)
        self._third = getattr(problem, "third_derivative", None)
        self._size = max(1.0, float(np.max(np.abs(self.u)))) if self.u.size else 1.0
        self.exact = self._second is not None and self._third is not None

    # -- real forms
    def quad(self, v: np.ndarray) -> np.ndarray:
        """``D²R[v, v]`` for a real ``v``."""
        if self._second is not None:
            return np.asarray(self._second(self.u, self.p, v, v), dtype=float)
        nv = float(np.max(np.abs(v)))
        if nv == 0.0:
            return np.zeros_like(self.u)
        f0 = self._f(np.zeros_like(self.u))

        def d(h: float) -> np.ndarray:
            return (self._f(h * v) - 2.0 * f0 + self._f(-h * v)) / (h * h)

        h = H2 * self._size / nv
        return (4.0 * d(0.5 * h) - d(h)) / 3.0

    def real_b(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """``D²R[x, y]`` for real ``x, y`` (polarization of :meth:`quad`)."""
        if self._second is not None:
            return np.asarray(self._second(self.u, self.p, x, y), dtype=float)
        return 0.25 * (self.quad(x + y) - self.quad(x - y))

    def cube(self, v: np.ndarray) -> np.ndarray:
        """``D³R[v, v, v]`` for a real ``v``."""
        if self._third is not None:
            return np.asarray(self._third(self.u, self.p, v, v, v), dtype=float)
        nv = float(np.max(np.abs(v)))
        if nv == 0.0:
            return np.zeros_like(self.u)
        f = self._f

        def d(h: float) -> np.ndarray:
            return (f(2 * h * v) - 2.0 * f(h * v) + 2.0 * f(-h * v) - f(-2 * h * v)) / (2.0 * h**3)

        h = H3 * self._size / nv
        return (4.0 * d(0.5 * h) - d(h)) / 3.0

    # -- complex forms
    def b(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        """``B(x, y)`` for complex ``x, y`` (bilinear, not sesquilinear)."""
        xr, xi, yr, yi = x.real, np.imag(x), y.real, np.imag(y)
        out = self.real_b(xr, yr).astype(complex)
        if np.any(xi) and np.any(yi):
            out -= self.real_b(xi, yi)
        if np.any(yi):
            out += 1j * self.real_b(xr, yi)
        if np.any(xi):
            out += 1j * self.real_b(xi, yr)
        return out

    def c_qqqbar(self, q: np.ndarray) -> np.ndarray:
        """``C(q, q, q̄)``: with ``q = a + ib``, ``C(a,a,a) + C(a,b,b) + i(C(a,a,b) + C(b,b,b))``."""
        a, b = q.real.copy(), q.imag.copy()
        if self._third is not None:
            t = self._third
            u, p = self.u, self.p
            aaa, bbb = t(u, p, a, a, a), t(u, p, b, b, b)
            aab, abb = t(u, p, a, a, b), t(u, p, a, b, b)
            return (
                np.asarray(aaa, float)
                + np.asarray(abb, float)
                + 1j * (np.asarray(aab, float) + np.asarray(bbb, float))
            )
        ca, cb = self.cube(a), self.cube(b)
        cp, cm = self.cube(a + b), self.cube(a - b)
        aab = (cp - cm - 2.0 * cb) / 6.0
        abb = (cp + cm - 2.0 * ca) / 6.0
        return ca + abb + 1j * (aab + cb)


class Factored:
    """A square matrix (dense or sparse, real or complex) factored once for repeated solves
    (SuperLU; LAPACK getrf, with the condition number estimated by gecon). Building it or
    :meth:`solve` raises :class:`~.._errors.SingularMatrixError` for a matrix singular to
    working precision (a dense one's reciprocal condition number below ε, where
    :func:`scipy.linalg.solve` warns)."""

    def __init__(self, matrix: Any) -> None:
        self.matrix = matrix
        self.complex = np.iscomplexobj(matrix.data if sp.issparse(matrix) else matrix)
        if sp.issparse(matrix):
            try:
                self.lu: Any = spla.splu(sp.csc_matrix(matrix))
            except RuntimeError as exc:  # "Factor is exactly singular"
                raise SingularMatrixError(f"singular matrix in a Lyapunov solve: {exc}") from None
            return
        a = np.asarray(matrix, dtype=complex if self.complex else float)
        if not np.all(np.isfinite(a)):
            raise SingularMatrixError("a Lyapunov solve met a matrix with NaN or inf")
        getrf, gecon = lapack.get_lapack_funcs(("getrf", "gecon"), (a,))
        lu, piv, info = getrf(a)
        anorm = float(np.max(np.sum(np.abs(a), axis=0)))
        rcond = float(gecon(lu, anorm, norm="1")[0]) if info == 0 else 0.0
        if not rcond >= _EPS:
            raise SingularMatrixError(
                f"singular matrix in a Lyapunov solve (reciprocal condition {rcond:.3g})"
            )
        self.lu = (lu, piv)

    def solve(self, rhs: np.ndarray, trans: str = "N") -> np.ndarray:
        """``matrix⁻¹ rhs`` (``trans``: ``"T"`` the transpose's, ``"H"`` the adjoint's)."""
        if np.iscomplexobj(rhs) and not self.complex:
            t = trans.replace("H", "T")
            re = self._solve(np.ascontiguousarray(rhs.real), t)
            return re + 1j * self._solve(np.ascontiguousarray(rhs.imag), t)
        out = self._solve(rhs.astype(complex) if self.complex else rhs, trans)
        if not np.all(np.isfinite(out)):
            raise SingularMatrixError("singular matrix in a Lyapunov solve (non-finite solution)")
        return out

    def _solve(self, rhs: np.ndarray, trans: str) -> np.ndarray:
        if not isinstance(self.lu, tuple):
            return self.lu.solve(rhs, trans=trans)
        lu, piv = self.lu
        (getrs,) = lapack.get_lapack_funcs(("getrs",), (lu,))
        return getrs(lu, piv, rhs, trans={"N": 0, "T": 1, "H": 2}[trans])[0]


def solve(matrix: Any, rhs: np.ndarray) -> np.ndarray:
    """``matrix⁻¹ rhs`` (dense or sparse, real or complex); a singular matrix raises
    :class:`~.._errors.SingularMatrixError`."""
    return Factored(matrix).solve(rhs)


def null_vector(lu: Factored, start: np.ndarray, trans: str = "N", steps: int = 3) -> np.ndarray:
    """Inverse iteration with the factors of a matrix singular to rounding (``A − iωM`` at a
    Hopf point): its null vector (of the adjoint, ``trans="H"``), each step multiplying the
    error by the ratio of the smallest to the next singular value (~1e-10 at a located
    point): ``steps`` are more than enough."""
    x = np.asarray(start, dtype=complex)
    for _ in range(steps):
        try:
            y = lu.solve(x, trans=trans)
        except SingularMatrixError:  # an exact zero pivot: its column is the null vector
            break
        x = y / np.linalg.norm(y)
    return x


def mass_times(mass: Any, x: np.ndarray) -> np.ndarray:
    """``M x`` (``mass`` None is the identity)."""
    return x if mass is None else mass @ x


def adjoint_vector(jac: Any, mass: Any, omega: float, q: np.ndarray) -> np.ndarray:
    """``p`` with ``Aᵀp = −iω Mᵀp`` and ``pᴴMq = 1``. Dense: the bordered system
    ``[[Aᵀ + iωMᵀ, q], [(Mq)ᴴ, 0]] [p; s] = [0; 1]`` (regular at a simple eigenvalue: ``q``
    spans the orthogonal complement of the range, and ``(Mq)ᴴp = conj(pᴴMq) ≠ 0``). Sparse:
    inverse iteration on ``(A − iωM)ᴴ`` from ``Mq`` (its dense border would fill SuperLU's
    factors: 1.8 s against 0.1 s at 10⁴ unknowns)."""
    n = q.size
    mq = mass_times(mass, q)
    if sp.issparse(jac) or sp.issparse(mass):
        m = sp.identity(n, format="csc") if mass is None else sp.csc_matrix(mass)
        lu = Factored(sp.csc_matrix(jac, dtype=complex) - 1j * omega * m)
        p = null_vector(lu, mq, trans="H")
    else:
        m_t = np.eye(n) if mass is None else np.asarray(mass).T
        big = np.zeros((n + 1, n + 1), dtype=complex)
        big[:n, :n] = np.asarray(jac).T + 1j * omega * m_t
        big[:n, n] = q
        big[n, :n] = mq.conj()
        rhs = np.zeros(n + 1, dtype=complex)
        rhs[n] = 1.0
        p = solve(big, rhs)[:n]
    return p / np.conj(np.vdot(p, mq))  # pᴴMq = 1 exactly (it is 1 up to rounding)


@dataclass(frozen=True, kw_only=True)
class Lyapunov:
    """The first Lyapunov coefficient ``l1`` at a Hopf point, with the eigenvector ``q``
    (``qᴴq = 1``) and the adjoint ``adjoint`` (``pᴴMq = 1``) it was computed with."""

    l1: float
    q: np.ndarray
    adjoint: np.ndarray


def first_lyapunov(
    problem: Any,
    u: np.ndarray,
    p: Mapping[str, float],
    omega: float,
    q: np.ndarray,
    jac: Any,
    mass: Any = None,
    jac_lu: Factored | None = None,
) -> Lyapunov:
    """The first Lyapunov coefficient at a Hopf point with ``q`` normalised to ``qᴴq = 1``
    and the adjoint ``pᴴMq = 1`` (see the module). ``jac``: ``∂R/∂u`` at the point,
    ``jac_lu`` its factors if the caller has them."""
    if not omega > 0.0:
        raise SingularMatrixError(f"the first Lyapunov coefficient needs omega > 0, got {omega}")
    q = np.asarray(q, dtype=complex)
    q = q / np.linalg.norm(q)
    padj = adjoint_vector(jac, mass, omega, q)
    forms = Forms(problem, u, p)
    qb = q.conj()
    lu = Factored(jac) if jac_lu is None else jac_lu
    r1 = lu.solve(forms.b(q, qb).real)  # B(q, q̄) is real
    if sp.issparse(jac) or sp.issparse(mass):
        m = sp.identity(q.size) if mass is None else sp.csc_matrix(mass)
        shifted = 2j * omega * m - sp.csc_matrix(jac)
    else:
        m = np.eye(q.size) if mass is None else np.asarray(mass)
        shifted = 2j * omega * m - np.asarray(jac)
    r2 = solve(shifted, forms.b(q, q))
    total = forms.c_qqqbar(q) - 2.0 * forms.b(q, r1.astype(complex)) + forms.b(qb, r2)
    l1 = float(np.real(np.vdot(padj, total))) / (2.0 * omega)
    return Lyapunov(l1=l1, q=q, adjoint=padj)


__all__ = [
    "Factored",
    "Forms",
    "Lyapunov",
    "adjoint_vector",
    "first_lyapunov",
    "null_vector",
    "solve",
]
