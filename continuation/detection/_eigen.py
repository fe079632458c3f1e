"""Stability of equilibria: the eigenvalues that decide it, for dense and sparse problems.

A problem declares that its residual is a vector field, ``M u' = R(u, p)``, by
``Problem(..., mass=M)`` (``mass=True``: ``M = I``). The eigenvalues of an equilibrium are
those of the pencil ``(A, M)``, ``A = ∂R/∂u``: ``A x = λ M x``.

- **dense** (a dense Jacobian, or ``n ≤ dense_limit``): all of them, one LAPACK call
  (``eigvals``; QZ for a mass matrix other than ``I``). A singular ``M`` gives infinite
  eigenvalues (the algebraic equations): those with ``|λ| > 10⁸‖A‖/‖M‖`` are dropped.
- **sparse**: the ``nev`` nearest the shift (0 by default) by shift-invert Arnoldi
  (ARPACK through :func:`scipy.sparse.linalg.eigs` on ``(A − σM)⁻¹M``, which needs no
  symmetric ``M`` and maps infinite eigenvalues to 0), started from the previous point's
  eigenvectors (``start``: a warm start; ARPACK then needs fewer restarts), then a
  **second shift** at ``2iΩ`` (``Ω`` the radius of those found): an eigenvalue of large
  imaginary part right of the lowest found (a wave instability the first pass cannot
  reach) is nearest there; any such eigenvalue not found by the first pass is added and
  counted in ``added``. This is a check, not a proof: an eigenvalue far from both shifts
  can still be missed (raise ``nev``). (A Cayley count, ``(A − aM)⁻¹(A − bM)``, was tried
  as the proof: on a discretised PDE the eigenvalues towards −∞ accumulate on its unit
  circle and ARPACK did not converge in 10⁴ iterations at 10³ unknowns.) The caller may
  skip the second pass (``verify=False``) where it already ran with the same result at
  the neighbouring point (see :mod:`~..results._stability`).

``n_unstable`` counts the computed eigenvalues with positive real part.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg as la
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from .._errors import AccuracyError, ProblemDefinitionError

#: eigenvalues whose imaginary part is below this (relative to max(1, |λ|)) count as real
REAL_TOL = 1e-6
#: ARPACK's relative accuracy of the Ritz values (they decide signs and seed Newton)
ARPACK_TOL = 1e-10


@dataclass(frozen=True, kw_only=True)
class Eigenvalues:
    """The eigenvalues computed at one equilibrium: ``values`` by decreasing real part (then
    decreasing imaginary part); ``method`` ``"dense"`` or ``"shift-invert"``; ``complete``
    (all of them, or the few nearest the shift); ``added``: eigenvalues the second shift
    found that the first missed; ``verified``: whether the second shift ran; ``start``: a
    start vector for the next point's Arnoldi (sparse only, else None)."""

    values: np.ndarray
    method: str
    complete: bool
    added: int = 0
    verified: bool = False
    start: np.ndarray | None = None


def vector_field_mass(problem: Any) -> Any:
    """The mass matrix of a problem declared a vector field (None for ``M = I``), or a
    :class:`~.._errors.ProblemDefinitionError`: stability has no meaning for a residual that
    is not a vector field (the contact problems of :mod:`cusp.models`, say)."""
    mass = getattr(problem, "mass", None)
    if mass is None:
        raise ProblemDefinitionError(
            "stability needs a vector field: declare the residual as M u' = R(u, p) with "
            "Problem(..., mass=True) (M = I) or mass=M; this problem has none"
        )
    if sp.issparse(mass):
        mass = sp.csc_matrix(mass, dtype=float)
        d = mass - sp.identity(mass.shape[0], format="csc")
        return None if d.count_nonzero() == 0 else mass
    mass = np.asarray(mass, dtype=float)
    return None if np.array_equal(mass, np.eye(mass.shape[0])) else mass


def spectrum(
    jac: Any,
    mass: Any = None,
    *,
    nev: int = 8,
    dense_limit: int = 400,
    shift: float = 0.0,
    start: np.ndarray | None = None,
    verify: bool = True,
) -> Eigenvalues:
    """The eigenvalues of ``(jac, mass)`` that decide stability (see the module)."""
    n = jac.shape[0]
    if not (sp.issparse(jac) and n > dense_limit):
        a = jac.toarray() if sp.issparse(jac) else np.asarray(jac, dtype=float)
        m = None if mass is None else (mass.toarray() if sp.issparse(mass) else mass)
        return Eigenvalues(values=_sorted(_dense(a, m)), method="dense", complete=True)
    m = sp.identity(n, format="csc") if mass is None else sp.csc_matrix(mass)
    k = max(2, min(int(nev), n - 2))
    lam, vecs = _shift_invert(sp.csc_matrix(jac), m, k, shift, start)
    extra = _second_shift(sp.csc_matrix(jac), m, lam, k) if verify else None
    added = 0 if extra is None else int(extra.size)
    if added:
        lam = np.concatenate([lam, extra])
    return Eigenvalues(
        values=_sorted(lam),
        method="shift-invert",
        complete=False,
        added=added,
        verified=verify,
        start=_next_start(vecs),
    )


def _sorted(lam: np.ndarray) -> np.ndarray:
    lam = np.asarray(lam, dtype=complex)
    real = np.abs(lam.imag) <= REAL_TOL * np.maximum(1.0, np.abs(lam))
    lam = np.where(real, lam.real + 0j, lam)
    return lam[np.lexsort((-lam.imag, -lam.real))]


def n_unstable(lam: np.ndarray) -> int:
    """The number of eigenvalues with positive real part.

    >>> n_unstable(np.array([1 + 2j, 1 - 2j, -3.0, 0.0]))
    2
    """
    return int(np.count_nonzero(np.real(lam) > 0.0))


def _dense(a: np.ndarray, m: Any) -> np.ndarray:
    if not np.all(np.isfinite(a)):
        raise AccuracyError("the Jacobian has NaN or inf entries: no eigenvalues")
    if m is None:
        return la.eigvals(a, check_finite=False)
    m = np.asarray(m, dtype=float)
    w = la.eigvals(a, m, homogeneous_eigvals=True, check_finite=False)
    alpha, beta = w[0], w[1]
    scale = max(np.abs(a).sum(axis=0).max(), 1e-300) / max(np.abs(m).sum(axis=0).max(), 1e-300)
    finite = np.abs(beta) * 1e8 * scale > np.abs(alpha)
    return alpha[finite] / beta[finite]


def _start_vector(n: int) -> np.ndarray:
    return np.random.default_rng(12345).standard_normal(n)  # reproducible Arnoldi


def _next_start(vecs: np.ndarray) -> np.ndarray:
    """A start vector for the next point's Arnoldi: the sum of this point's eigenvectors
    (real and imaginary parts), each of unit size, so that none of them is missing."""
    v = np.zeros(vecs.shape[0])
    for j in range(vecs.shape[1]):
        for part in (vecs[:, j].real, vecs[:, j].imag):
            size = float(np.linalg.norm(part))
            if size > 0.0:
                v += part / size
    return v if np.any(v) else _start_vector(vecs.shape[0])


def _factor(mat: Any, shift: complex, m: Any) -> tuple[complex, Any]:
    """``(σ, LU of A − σM)`` for ``σ`` at ``shift`` or nudged off an eigenvalue it hits."""
    scale = max(1.0, abs(shift))
    dtype = complex if isinstance(shift, complex) else float
    for nudge in (0.0, 1e-7, -3e-7):
        sigma = shift + nudge * scale
        try:
            return sigma, spla.splu(sp.csc_matrix(mat - sigma * m, dtype=dtype))
        except RuntimeError:  # exactly singular
            continue
    raise AccuracyError(f"A − σM is singular at σ = {shift} and beside it")


def _shift_invert(
    jac: Any, m: Any, k: int, shift: float, start: np.ndarray | None
) -> tuple[np.ndarray, np.ndarray]:
    """The ``k`` eigenvalues nearest ``shift`` and their eigenvectors."""
    n = jac.shape[0]
    sigma, lu = _factor(jac, shift, m)
    op = spla.LinearOperator((n, n), matvec=lambda x: lu.solve(m @ x), dtype=float)
    v0 = _start_vector(n) if start is None or start.shape != (n,) else start
    try:
        nu, vecs = spla.eigs(op, k=k, which="LM", v0=v0, tol=ARPACK_TOL)
    except spla.ArpackNoConvergence as exc:
        raise AccuracyError(f"shift-invert Arnoldi did not converge ({exc})") from None
    keep = np.abs(nu) > 0.0
    return sigma + 1.0 / nu[keep], vecs[:, keep]


def _second_shift(jac: Any, m: Any, lam: np.ndarray, k: int) -> np.ndarray | None:
    """The check that none was missed: shift-invert Arnoldi again at ``σ₂ = 2iΩ`` (``Ω`` the
    radius of the eigenvalues found, at least 1), where an eigenvalue of large imaginary part
    (a wave instability) that the first pass could not reach would be nearest. Returns None
    if every eigenvalue found there with a real part above the first pass's lowest is
    among the first pass's, else those eigenvalues (to be added)."""
    n = jac.shape[0]
    omega2 = 2.0 * max(1.0, float(np.max(np.abs(lam))))
    sigma, lu = _factor(jac, 1j * omega2, m)
    op = spla.LinearOperator((n, n), matvec=lambda x: lu.solve(m @ x), dtype=complex)
    try:
        nu = spla.eigs(op, k=min(k, 4), ncv=min(n - 1, 20), which="LM", tol=1e-6,
                       v0=_start_vector(n).astype(complex), return_eigenvectors=False)  # fmt: skip
    except spla.ArpackNoConvergence as exc:
        raise AccuracyError(f"the second-shift check did not converge ({exc})") from None
    found2 = sigma + 1.0 / nu[np.abs(nu) > 0.0]
    found2 = np.concatenate([found2, found2.conj()])
    low = float(np.min(lam.real))
    scale = max(1.0, float(np.max(np.abs(lam))))
    new = [
        x for x in found2
        if x.real > low and np.min(np.abs(lam - x)) > 1e-6 * max(scale, abs(x))
    ]  # fmt: skip
    return np.array(new) if new else None


def eigenvector_near(
    jac: Any, mass: Any, target: complex, start: np.ndarray | None = None
) -> tuple[complex, np.ndarray]:
    """The eigenvalue of ``(jac, mass)`` nearest ``target`` and its right eigenvector: dense,
    by LAPACK; sparse, by inverse iteration with the factors of ``A − target·M`` (from
    ``start``, or a fixed random vector; ARPACK with one vector took 0.6 s at 10⁴
    unknowns, inverse iteration a tenth), to a residual of 1e-10 or 8 steps (the Hopf
    system's Newton refines it)."""
    n = jac.shape[0]
    if not sp.issparse(jac) or n <= 400:
        a = jac.toarray() if sp.issparse(jac) else np.asarray(jac, dtype=float)
        m = None
        if mass is not None:
            m = mass.toarray() if sp.issparse(mass) else np.asarray(mass, dtype=float)
        w, v = la.eig(a, m)
        ok = np.isfinite(w)
        j = int(np.argmin(np.where(ok, np.abs(w - target), np.inf)))
        return complex(w[j]), v[:, j]
    m = sp.identity(n, format="csc") if mass is None else sp.csc_matrix(mass)
    sigma, lu = _factor(jac, complex(target), m)
    x = _start_vector(n).astype(complex) if start is None else np.asarray(start, complex)
    mu = complex(sigma)
    for _ in range(8):  # inverse iteration: each step multiplies the error by |λ−σ|/|λ'−σ|
        y = lu.solve(m @ x)
        x = y / np.linalg.norm(y)
        ax, mx = jac @ x, m @ x
        mu = complex(np.vdot(mx, ax) / np.vdot(mx, mx))
        if np.linalg.norm(ax - mu * mx) <= 1e-10 * max(1.0, abs(mu)) * np.linalg.norm(mx):
            break
    return mu, x


__all__ = [
    "ARPACK_TOL",
    "REAL_TOL",
    "Eigenvalues",
    "eigenvector_near",
    "n_unstable",
    "spectrum",
    "vector_field_mass",
]
