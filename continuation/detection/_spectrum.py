"""Partial spectra of the branch-point test's matrix: several branch points inside one step
on curves of any size or storage.

The branch-point test is the sign of det M, ``M = [∂G/∂z; (W t)ᵀ]``; two branch points inside
one step leave it unchanged. Dense curves of up to :data:`~._tests.SPECTRUM_MAX_DIM`
components carry M's whole spectrum (:class:`~._tests.SignWithSpectrum`); for all
other curves (larger, or with a sparse Jacobian) the test's value is a :class:`PartialSign`,
whose few eigenvalues nearest zero are computed when a step asks for them, from the
factorization the step already has.

**The eigenproblem** is the pencil

    ∂G/∂z x = μ E x,   (W t)·x = 0        (E x: the first m of the m + 1 components of x),

i.e. ``det(M − μE) = 0`` with ``E = diag(1, …, 1, 0)``. At μ = 0 that is det M, so a real
eigenvalue passes through zero exactly where the test does (a simple branch point), and
nowhere else: unlike M's own eigenvalues, the pencil's do not depend on the scale of the
border row (scaling M's last row scales ``det(M − μE)``), the border contributes no
eigenvalue near zero of its own, and on a branch whose tangent is the free parameter (a
trivial branch) they are the eigenvalues of ``∂G/∂u``. Where the tangent's last component
vanishes (a fold in the free parameter) one eigenvalue passes through infinity instead:
det M keeps its sign there, and it is no crossing.

**Shift-invert Arnoldi** at σ = 0: the operator ``x ↦ M⁻¹E x`` is applied with the step's
factorization ``F`` of ``[∂G/∂z; r]`` at the point (any border ``r`` with ``r·t ≠ 0``: the
tangent's, or the previous point's of the corrector, :func:`~..systems._newton.factor_at`): solve
``F y = E x``, then ``y − (W t·y) t`` solves ``M y' = E x`` (``∂G/∂z t = 0``). One solve an
Arnoldi vector, no factorization. The Ritz pairs of largest |1/μ| whose residual is below
:data:`RITZ_TOL` form the spectrum, nearest zero first, with its *radius*: every eigenvalue
inside it is among them (the usual convergence order of Krylov methods from a start with
components along every eigenvector: the start mixes a seeded random vector with the last
point's eigenvectors).

**A step is accounted for** (:func:`follow`) when the partial spectra at its ends explain
it: eigenvalues are matched by their eigenvectors (most parallel first, |cos| ≥
:data:`MATCH_COS`), matched eigenvalues and complex pairs form groups, and a group whose
product of eigenvalues changes sign holds a crossing (at the zero of its linear
interpolant). With ``D`` the largest displacement of a matched eigenvalue over the step and
``R = 2D`` the reach of any eigenvalue in it,

- an eigenvalue outside both spectra would have to move by more than the two radii to cross
  zero: the radii must add up to more than ``R``;
- an eigenvalue seen at one end only (unmatched, or a group whose count differs between the
  ends) must be too far from zero to cross within ``R``, and not so deep inside the other
  end's spectrum that a partner within ``R`` should have been matched (in a whole spectrum
  a missing partner went through infinity, and every pair is matched);
- the number of crossings must have the parity of the determinant's sign change.

A step that is not accounted for first gets larger spectra (twice the Krylov space), then is
split at its corrected midpoint, and each half is accounted for in turn (up to
:data:`~..stepping._crossings.SPLIT_DEPTH` levels, after which its determinant's sign decides). What
this cannot see: one eigenvalue crossing zero and back inside a step (two branch points of
one mode: no end-point spectrum shows them), and eigenvalues moving more than twice as fast
as every matched one (``R`` is an estimate from the matched eigenvalues, not a bound).
"""

from __future__ import annotations

import logging
import math
from typing import Any, NamedTuple

import numpy as np
from scipy.linalg import lapack

from .._errors import SingularMatrixError
from .._outcomes import Outcome
from ..numerics._linalg import bordered, factor
from ..systems._curve import CurveSystem

logger = logging.getLogger(__name__)

KRYLOV = 8
"""Arnoldi vectors (solves with the step's factorization) of a first partial spectrum."""

MAX_KRYLOV = 32
"""The largest Krylov space a step's spectra grow to before the step is split instead."""

RITZ_TOL = 1e-6
"""A Ritz pair is an eigenpair when its residual is below this, relative to its value."""

MATCH_COS = 0.5
"""Eigenvectors at a step's two ends are the same mode when |cos| is at least this."""

REACH = 2.0
"""How much farther than the farthest-moving matched eigenvalue any eigenvalue may move."""


class Spectrum(NamedTuple):
    """A partial spectrum of the pencil: eigenvalues ``wr + i·wi`` nearest zero first (a
    complex pair j, j + 1, positive imaginary part first), unit real ``vectors`` (columns;
    a pair has Re v, Im v), the ``radius`` inside which all eigenvalues are known (inf: the
    whole spectrum) and the Krylov ``size`` it was computed with."""

    wr: np.ndarray
    wi: np.ndarray
    vectors: np.ndarray
    radius: float
    size: int


class Factored(float):
    """The sign of det M at a step's end with the factorization ``lu`` of ``[∂G/∂z; r]`` at
    the point itself (:func:`~..stepping._crossings.evaluate` passes it to the branch-point
    test, whose :class:`PartialSign` keeps it for the partial spectrum)."""

    lu: Any

    def __new__(cls, sign: float, lu: Any) -> Factored:
        self = super().__new__(cls, sign)
        self.lu = lu
        return self


class PartialSign(float):
    """The branch-point test's value (the sign of det M) on curves without a full spectrum:
    the point ``z``, its unit tangent ``t`` and the factorization ``lu`` of ``[∂G/∂z; r]``
    there (or None: made when needed), from which :meth:`spectrum` computes the pencil's
    partial spectrum when a step asks for it (once per Krylov size; a point is the end of one step
    and the start of the next)."""

    system: CurveSystem
    z: np.ndarray
    t: np.ndarray
    lu: Any
    cached: Spectrum | None

    def __new__(
        cls, sign: float, system: CurveSystem, z: np.ndarray, t: np.ndarray, lu: Any = None
    ) -> PartialSign:
        self = super().__new__(cls, sign)
        self.system, self.z, self.t, self.lu, self.cached = system, z, t, lu, None
        return self

    def spectrum(self, size: int = KRYLOV, warm: Spectrum | None = None) -> Spectrum | None:
        """The eigenvalues nearest zero from a Krylov space of ``size`` (at most the
        curve's ``m``), started from ``warm``'s eigenvectors and a seeded random vector;
        None where M is singular or not finite."""
        cached = self.cached
        if cached is not None and (cached.size >= size or math.isinf(cached.radius)):
            return cached
        op = self._operator()
        if op is None:
            return None
        n = self.z.size
        rng = np.random.default_rng(n)
        v0 = rng.random(n) - 0.5
        v0 /= _norm(v0)
        start = warm if warm is not None and warm.vectors.shape[0] == n else cached
        if start is not None and start.vectors.shape[1]:
            w = start.vectors.sum(axis=1)
            v0 += w / _norm(w)
        with np.errstate(all="ignore"):
            found = arnoldi_spectrum(op, v0, min(size, n - 1))
        if found is not None:
            self.cached = found
        return found

    def _operator(self) -> Any:
        """``x ↦ M⁻¹E x`` on the hyperplane ``(W t)·x = 0`` (see the module docstring)."""
        system, t = self.system, self.t
        w = system.weights * t
        lu = self.lu
        if lu is None:
            try:
                lu = factor(bordered(system.jacobian(self.z), w))
            except SingularMatrixError:
                return None
            self.lu = lu

        def op(x: np.ndarray) -> np.ndarray:
            b = x.copy()
            b[-1] = 0.0
            y = lu.solve(b)
            return y - _dot(w, y) * t

        return op


def arnoldi_spectrum(op: Any, v0: np.ndarray, p: int) -> Spectrum | None:
    """The eigenvalues μ = 1/ν of the operator ``op`` (ν its Ritz values of largest
    modulus) and their vectors, from ``p`` steps of Arnoldi from ``v0`` (classical
    Gram–Schmidt, repeated where it cancels: the criterion of Daniel, Gragg, Kaufman and
    Stewart); None if ``op`` gives anything but finite numbers."""
    n = v0.size
    basis = np.empty((p + 1, n))
    h = np.zeros((p + 1, p))
    v = op(v0)  # (the start in the operator's range: on its hyperplane)
    norm = _norm(v)
    if not math.isfinite(norm) or norm == 0.0:
        return None
    basis[0] = v / norm
    k = p
    for j in range(p):
        w = op(basis[j])
        size = _norm(w)
        for _ in range(2):  # (a second pass only when the first cancelled much: DGKS)
            c = np.einsum("ij,j->i", basis[: j + 1], w)
            w -= np.einsum("i,ij->j", c, basis[: j + 1])
            h[: j + 1, j] += c
            beta = _norm(w)
            if beta > 0.7 * size:
                break
            size = beta
        if not math.isfinite(beta):
            return None
        h[j + 1, j] = beta
        if beta <= 1e-12 * _norm(h[: j + 2, j]):
            k = j + 1  # an invariant subspace: its Ritz pairs are exact
            break
        basis[j + 1] = w / beta
    # (a space of n - 1 vectors is the whole hyperplane: every eigenvalue, exactly)
    return _ritz_pairs(basis[:k], h, k, p, k < p or k >= n - 1, k >= n - 1)


def _ritz_pairs(
    basis: np.ndarray, h: np.ndarray, k: int, p: int, exact: bool, whole: bool
) -> Spectrum:
    """The converged Ritz pairs of the Arnoldi relation of size ``k`` (of ``p`` asked for;
    ``exact``: an invariant subspace, ``whole``: the operator's whole space), largest |ν|
    first, up to the first one that has not converged (a complex pair only with its
    partner)."""
    nu, s = np.linalg.eig(h[:k, :k])
    beta = 0.0 if exact else abs(h[k, k - 1])
    residual = beta * np.abs(s[k - 1])
    order = np.argsort(-np.abs(nu), kind="stable").tolist()
    keep: list[int] = []
    for i in order:
        if nu[i] == 0.0 or residual[i] > RITZ_TOL * abs(nu[i]):
            break
        keep.append(i)
    keep = _whole_pairs(nu, keep)
    wr: list[float] = []
    wi: list[float] = []
    cols: list[np.ndarray] = []
    for i in keep:
        if nu[i].imag < 0.0:
            continue  # (its partner, first, brings both)
        mu = 1.0 / nu[i]
        x = np.einsum("ij,i->j", basis, s[:, i].real)  # (no complex copy of the basis)
        if nu[i].imag == 0.0:
            wr.append(mu.real)
            wi.append(0.0)
            cols.append(_unit(x))
        else:  # μ = 1/ν: ν's positive imaginary part is μ's negative one
            wr += [mu.real, mu.real]
            wi += [abs(mu.imag), -abs(mu.imag)]
            cols += [_unit(x), _unit(np.einsum("ij,i->j", basis, s[:, i].imag))]
    n = basis.shape[1]
    vectors = np.array(cols).T if cols else np.zeros((n, 0))
    if whole:  # (every ν ≠ 0 kept: every finite eigenvalue)
        radius = math.inf
    else:
        radius = float(np.hypot(wr[-1], wi[-1])) if wr else 0.0
    return Spectrum(wr=np.array(wr), wi=np.array(wi), vectors=vectors, radius=radius, size=p)


def _whole_pairs(nu: np.ndarray, keep: list[int]) -> list[int]:
    """``keep`` up to the first complex Ritz value whose conjugate is not in it."""
    kept = set(keep)
    for pos, i in enumerate(keep):
        if nu[i].imag != 0.0:
            partner = next(
                (j for j in kept if j != i and abs(nu[j] - np.conj(nu[i])) <= 1e-8 * abs(nu[i])),
                None,
            )
            if partner is None:
                return keep[:pos]
    return keep


def _dot(x: np.ndarray, y: np.ndarray) -> float:
    """``x·y`` without BLAS, as the other products with the long vectors here: a threaded
    BLAS spends milliseconds waking its threads for each (a spectrum of the sparse Bratu
    problem with 1e5 unknowns took 190 ms besides its solves on a loaded machine, 30 ms
    with numpy's own loops; single-threaded BLAS 15 ms)."""
    return float(np.einsum("i,i->", x, y))


def _norm(x: np.ndarray) -> float:
    return math.sqrt(_dot(x, x))


def _unit(x: np.ndarray) -> np.ndarray:
    norm = _norm(x)
    return x / norm if norm > 0.0 else x


class Unaccounted(Outcome):
    """Why the spectra at a step's ends do not account for it (:func:`follow`)."""

    NOTHING = "", "the step is accounted for"
    EMPTY = "empty", "a spectrum is empty"
    UNMATCHED = "unmatched", "an eigenvalue seen at one end only may have crossed zero"
    WINDOW = "window", "the radii add up to less than an eigenvalue's reach over the step"
    PARITY = "parity", "the crossings' count has not the parity of the determinant's change"


class Verdict(NamedTuple):
    """What the spectra at a step's ends say: the crossings' estimated places θ ∈ (0, 1),
    ascending, and why the step is not accounted for (NOTHING when it is)."""

    thetas: list[float]
    problem: Unaccounted


def follow(sa: Spectrum, sb: Spectrum, changed: bool) -> Verdict:
    """Follow the eigenvalues of the spectra ``sa`` and ``sb`` at a step's ends through it
    (``changed``: whether det M changed sign): see the module docstring."""
    ka, kb = sa.wr.size, sb.wr.size
    if ka == 0 or kb == 0:
        return Verdict(thetas=[], problem=Unaccounted.EMPTY)
    mu_a, mu_b = sa.wr + 1j * sa.wi, sb.wr + 1j * sb.wi
    parent = list(range(ka + kb))  # union-find: eigenvalue i of a is i, j of b is ka + j

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    cos = np.abs(np.einsum("ij,ik->jk", sa.vectors, sb.vectors))
    free_a, free_b = [True] * ka, [True] * kb
    moved = 0.0
    # (whole spectra match every pair, as eigenvalue_crossings: a count that differs is an
    # eigenvalue through infinity, at a fold of the free parameter)
    least = 0.0 if math.isinf(sa.radius) and math.isinf(sb.radius) else MATCH_COS
    for f in np.argsort(-cos, axis=None).tolist():
        i, j = divmod(f, kb)
        if cos[i, j] < least:
            break
        if free_a[i] and free_b[j]:
            free_a[i] = free_b[j] = False
            parent[root(i)] = root(ka + j)
            # (a complex pair's vectors carry no order: either member is the partner)
            moved = max(moved, min(abs(mu_b[j] - mu_a[i]), abs(mu_b[j] - mu_a[i].conjugate())))
    if free_a == [True] * ka:
        return Verdict(thetas=[], problem=Unaccounted.UNMATCHED)
    for offset, wi in ((0, sa.wi), (ka, sb.wi)):
        for i in np.flatnonzero(wi > 0.0).tolist():
            parent[root(offset + i + 1)] = root(offset + i)
    reach = REACH * moved
    groups: dict[int, list[int]] = {}
    for i in range(ka + kb):
        groups.setdefault(root(i), []).append(i)
    thetas: list[float] = []
    problem = Unaccounted.NOTHING
    for members in groups.values():
        at_a = [i for i in members if i < ka]
        at_b = [i - ka for i in members if i >= ka]
        if len(at_a) != len(at_b):  # some partners missing from the other end's spectrum
            if any(_suspect(mu_a[i], reach, sb.radius) for i in at_a) or any(
                _suspect(mu_b[j], reach, sa.radius) for j in at_b
            ):
                problem = problem or Unaccounted.UNMATCHED
            continue
        pa, pb = _product(sa, at_a), _product(sb, at_b)
        if pa != 0.0 and pb != 0.0 and (pa < 0) != (pb < 0):
            thetas.append(pa / (pa - pb))
    if sa.radius + sb.radius <= reach:
        problem = problem or Unaccounted.WINDOW
    if (len(thetas) % 2 == 1) != changed:
        problem = problem or Unaccounted.PARITY
    return Verdict(thetas=sorted(thetas), problem=problem)


def _suspect(mu: complex, reach: float, radius: float) -> bool:
    """Whether an eigenvalue ``mu`` without a partner in the other end's spectrum (of
    ``radius``) may hide a crossing: it could have crossed zero within the ``reach`` from
    outside that spectrum, or it lies so deep inside it that a partner within the reach
    should have been matched (the matching or the reach is wrong; an eigenvalue without
    partner in a whole spectrum went through infinity)."""
    return abs(mu) + radius <= reach or abs(mu) + reach < radius < math.inf


def _product(s: Spectrum, members: list[int]) -> float:
    """The product of a group's eigenvalues (a complex pair contributes |λ|² once)."""
    out = 1.0
    for i in members:
        if s.wi[i] == 0.0:
            out *= float(s.wr[i])
        elif s.wi[i] > 0.0:
            out *= float(s.wr[i] ** 2 + s.wi[i] ** 2)
    return out


def split_points(old: PartialSign, new: PartialSign) -> tuple[float, ...]:
    """Where to split a step between the points whose test values are ``old`` and ``new``:
    midway between the crossings its spectra account for (none for fewer than two), or its
    middle when they do not account for it (see the module docstring)."""
    changed = (old < 0) != (new < 0)
    size = KRYLOV
    while True:
        sa = old.spectrum(size)
        sb = new.spectrum(size, warm=sa)
        if sa is None or sb is None:
            return ()
        verdict = follow(sa, sb, changed)
        problem = verdict.problem
        if problem is Unaccounted.NOTHING:
            thetas = verdict.thetas
            return tuple(0.5 * (a + b) for a, b in zip(thetas[:-1], thetas[1:]))
        grow = problem is not Unaccounted.PARITY and size < MAX_KRYLOV
        if not grow or (math.isinf(sa.radius) and math.isinf(sb.radius)):
            break
        size = min(2 * size, MAX_KRYLOV)
    logger.info(
        "the spectra at a step's ends do not account for it (%s; radii %.3g, %.3g): split",
        problem, sa.radius, sb.radius,
    )  # fmt: skip
    return (0.5,)


_geev = lapack.dgeev

SPECTRUM_MAX_DIM = 50
"""Dense curve systems of 3 to this many components carry the whole spectrum of the
branch-point test's matrix at every point (one LAPACK eigendecomposition a step), which shows
two or more branch points of different modes inside one step. Larger or sparse ones carry a
partial spectrum, its few eigenvalues nearest zero computed only when a step asks for them
(:mod:`.spectrum`). Curves with one unknown (2 components) carry none: their matrix holds one
row of the Jacobian, one mode, and two branch points in one step are one eigenvalue crossing
zero and back, which the spectra at the step's ends cannot show either."""


class SignWithSpectrum(float):
    """The branch-point test's value (the sign of det M, M = [∂G/∂z; (W t)ᵀ]) that also
    carries M's spectrum from LAPACK's dgeev: ``spectrum`` = (real parts, imaginary parts,
    unit real eigenvectors; a complex pair j, j + 1 has the vectors Re v, Im v), or None."""

    spectrum: tuple[list[float], list[float], np.ndarray] | None

    def __new__(cls, sign: float, m: np.ndarray) -> SignWithSpectrum:
        self = super().__new__(cls, sign)
        if not np.all(np.isfinite(m)):  # LAPACK's xerbla would print to stdout
            self.spectrum = None
            return self
        wr, wi, _, vr, info = _geev(m, compute_vl=0, compute_vr=1)
        if info != 0 or not np.all(np.isfinite(vr)):
            self.spectrum = None
        else:
            norms = np.sqrt(np.einsum("ij,ij->j", vr, vr))
            self.spectrum = (wr.tolist(), wi.tolist(), vr / np.where(norms > 0, norms, 1.0))
        return self


def eigenvalue_crossings(old: Any, new: Any) -> list[float]:
    """Where eigenvalues of the branch-point matrix change sign between two points (values
    :class:`SignWithSpectrum`), as estimates θ ∈ (0, 1), ascending; empty when either point
    carries no spectrum.

    Each eigenvector at the first point is matched to the one at the second most parallel
    to it (greedily, best match first); matched eigenvalues and complex-conjugate pairs form
    groups (a complex pair may turn into two real eigenvalues inside the step and one of
    them cross zero). A group whose product of eigenvalues changes sign holds a crossing,
    estimated where the linear interpolant of that product vanishes, θ = P_a/(P_a − P_b).

    Two modes crossing zero in opposite directions within one step leave the determinant's
    sign (and the count of negative eigenvalues) unchanged: only following each eigenvalue
    shows them (a Turing window of the Brusselator, where one mode destabilises as another
    restabilises)."""
    sa, sb = getattr(old, "spectrum", None), getattr(new, "spectrum", None)
    if sa is None or sb is None or len(sa[0]) != len(sb[0]):
        return []
    n = len(sa[0])
    parent = list(range(2 * n))  # union-find: eigenvalue i of a is i, j of b is n + j

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    flat = np.argsort(-np.abs(sa[2].T @ sb[2]), axis=None).tolist()
    free_a, free_b = [True] * n, [True] * n
    for f in flat:
        i, j = divmod(f, n)
        if free_a[i] and free_b[j]:
            free_a[i] = free_b[j] = False
            parent[root(i)] = root(n + j)
    # products of each group at each end: a complex pair contributes |λ|² (> 0) once
    factors = []
    for offset, (wr, wi, _) in ((0, sa), (n, sb)):
        for i in range(n):
            if wi[i] > 0.0:  # the first of a pair (LAPACK: positive imaginary part first)
                parent[root(offset + i + 1)] = root(offset + i)
                factors.append((offset + i, wr[i] * wr[i] + wi[i] * wi[i]))
            elif wi[i] == 0.0:
                factors.append((offset + i, wr[i]))
    products: dict[int, list[float]] = {}
    for k, value in factors:
        pair = products.setdefault(root(k), [1.0, 1.0])
        pair[k >= n] *= value
    out = []
    for a, b in products.values():
        if a != 0.0 and b != 0.0 and (a < 0) != (b < 0):
            out.append(a / (a - b))
    return sorted(out)


__all__ = [
    "SPECTRUM_MAX_DIM",
    "Unaccounted",
    "Factored",
    "PartialSign",
    "SignWithSpectrum",
    "Spectrum",
    "arnoldi_spectrum",
    "eigenvalue_crossings",
    "follow",
    "split_points",
]
