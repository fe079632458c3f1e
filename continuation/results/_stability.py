"""Stability along a traced branch, and its Hopf points (``trace(..., stability=True)``).

After the branch is traced, every row gets its eigenvalues
(:func:`~..detection._eigen.spectrum`) and ``n_unstable``. On sparse problems each row's
Arnoldi starts from the previous row's eigenvectors, and the second shift (the check that no
eigenvalue far up the imaginary axis was missed) runs at the first and last rows, where the
count of unstable eigenvalues changes, at every :data:`VERIFY_EVERY`-th row, and, when a
check adds an eigenvalue, at every row since the last check.

A **Hopf point** is detected on a segment where a complex pair (``Im λ`` not 0:
:data:`~..detection._eigen.REAL_TOL`) crosses the imaginary axis: at each end the pairs of
the upper half-plane are matched to their nearest at the other end (mutually nearest), and
a matched pair whose real part changes sign is a candidate. A real pair ``λ, −λ`` (a
neutral saddle) is never one: it has no imaginary part, and its sum's zero is not a
crossing. Where the pairs found do not account for the change in the number of unstable
upper-half-plane eigenvalues, the segment is halved (spectrum at the dense output's
midpoint), up to 5 times.

Each candidate is located by Newton on the regular Hopf system
(:func:`~..detection._hopf.locate_hopf`) from the dense output at the linear root of the
pair's real part, with the eigenvector there; the located point must lie on the segment
(within its box, widened by a quarter of it), else it belongs elsewhere and is dropped
(logged). The point is inserted as a row with a ``"hopf"`` special point (``details``:
``omega``, ``first_lyapunov`` (:mod:`~..detection._lyapunov`), ``criticality``, the
eigenvector ``q`` and adjoint ``p``, Newton's ``iterations``). A candidate where Newton
fails is inserted at the dense output's guess as a ``"guess"`` with its ``interval`` and
the failure in ``details["message"]``.
"""

from __future__ import annotations

import logging
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from .._errors import AccuracyError, ContinuationError, ProblemDefinitionError
from .._options import StabilityOptions
from .._outcomes import Kind, PointStatus
from ..detection._eigen import REAL_TOL, Eigenvalues, spectrum, vector_field_mass
from ..problem._problem import as_matrix
from ._branch import Branch, SpecialPoint
from ._dense import arrays, check_segment, segment
from ._hopfrows import HopfRow, hopf_row, inserted

logger = logging.getLogger(__name__)

#: on sparse problems, the second shift runs at least at every this many rows
VERIFY_EVERY = 8


@dataclass(frozen=True, kw_only=True)
class _Setting:
    """What every row's computation shares: the problem, its mass matrix (None: ``I``),
    the options, the free parameter and the branch's states as a matrix (rows)."""

    problem: Any
    mass: Any
    options: StabilityOptions
    free: str
    states: np.ndarray
    arcs: Any


def with_stability(problem: Any, branch: Branch, options: StabilityOptions) -> Branch:
    """``branch`` with the column ``"n_unstable"``, ``eigenvalues`` per row and, if
    ``options.hopf``, its located Hopf points inserted (see the module)."""
    mass = vector_field_mass(problem)
    unknowns = tuple(problem.unknowns)
    if tuple(branch.variables[:-1]) != unknowns:
        raise ProblemDefinitionError(
            f"stability needs a branch of this problem with one free parameter; the branch "
            f"traces {list(branch.variables)}, the problem has unknowns {list(unknowns)}"
        )
    setting = _Setting(
        problem=problem,
        mass=mass,
        options=options,
        free=branch.variables[-1],
        states=np.column_stack([branch[name] for name in unknowns]),
        arcs=_arcs(branch),
    )
    eigs = _row_spectra(setting, branch)
    rows = _hopf_rows(setting, branch, eigs) if options.hopf else []
    out = inserted(branch, rows, [e.values for e in eigs])
    out.info["stability"] = {
        "method": eigs[0].method if eigs else "dense",
        "added": int(sum(e.added for e in eigs)),
        "verified_rows": int(sum(e.verified for e in eigs)),
        "nev": options.nev,
        "dense_limit": options.dense_limit,
        "shift": options.shift,
    }
    return out


def _arcs(branch: Branch) -> Any:
    """The branch's interpolant's arrays, or None if it has none."""
    try:
        return arrays(branch)
    except AccuracyError:
        return None


def _params(setting: _Setting, branch: Branch, i: int) -> dict[str, float]:
    problem = setting.problem
    return {k: float(branch[k][i]) if k in branch else float(v) for k, v in problem.params.items()}


def _at(
    setting: _Setting, u: np.ndarray, p: dict[str, float], start: Any, verify: bool
) -> Eigenvalues:
    """The eigenvalues at ``(u, p)`` (``start``: the Arnoldi's warm start)."""
    o = setting.options
    jac = as_matrix(setting.problem.jacobian(u, p))
    return spectrum(
        jac,
        setting.mass,
        nev=o.nev,
        dense_limit=o.dense_limit,
        shift=o.shift,
        start=start,
        verify=verify,
    )


def _row_spectra(setting: _Setting, branch: Branch) -> list[Eigenvalues]:
    """Every row's eigenvalues; the second shift where the module says."""
    out: list[Eigenvalues] = []
    last = len(branch) - 1
    checked = -1  # the last row the second shift ran at
    for i in range(len(branch)):
        p = _params(setting, branch, i)
        start = out[-1].start if out else None
        e = _at(setting, setting.states[i], p, start, verify=i in (0, last))
        if e.method != "dense" and not e.verified:
            changed = _unstable(e) != _unstable(out[-1])
            if changed or i - checked >= VERIFY_EVERY:
                e = _at(setting, setting.states[i], p, start, verify=True)
        if e.verified:
            if e.added:  # the first pass missed an eigenvalue: check the rows before too
                for j in range(checked + 1, i):
                    pj = _params(setting, branch, j)
                    out[j] = _at(setting, setting.states[j], pj, out[j].start, verify=True)
            checked = i
        out.append(e)
    return out


def _unstable(e: Eigenvalues) -> int:
    return int(np.count_nonzero(e.values.real > 0.0))


def crossing_pairs(ea: np.ndarray, eb: np.ndarray) -> list[tuple[float, float]]:
    """``(θ, ω)`` for each complex pair crossing the imaginary axis between two spectra:
    mutually nearest upper-half-plane eigenvalues whose real parts differ in sign, ``θ`` the
    linear root of the real part, ``ω`` the imaginary part there.

    >>> crossing_pairs(np.array([-1 + 2j, -1 - 2j, -3]), np.array([1 + 2j, 1 - 2j, -3]))
    [(0.5, 2.0)]
    >>> crossing_pairs(np.array([-1.0, 1.0]), np.array([-0.5, 0.5]))  # a neutral saddle
    []
    """
    ua = ea[ea.imag > REAL_TOL * np.maximum(1.0, np.abs(ea))]
    ub = eb[eb.imag > REAL_TOL * np.maximum(1.0, np.abs(eb))]
    out = []
    for la_ in ua.tolist():
        if ub.size == 0:
            break
        lb = complex(ub[int(np.argmin(np.abs(ub - la_)))])
        if int(np.argmin(np.abs(ua - lb))) != int(np.argmin(np.abs(ua - la_))):
            continue
        if la_.real * lb.real < 0.0:
            out.append(_root(la_, lb))
    gained = int(np.sum(ub.real > 0)) - int(np.sum(ua.real > 0))
    if not out and gained and ua.size and ub.size:
        # pairs shifted past their neighbours within the step (a ladder of modes, as in a
        # discretised PDE, all moving alike) defeat the matching: the pair nearest the axis
        # on the stable side against the one nearest it on the unstable side
        st, un = (ua, ub) if gained > 0 else (ub, ua)
        neg, pos = st[st.real < 0], un[un.real > 0]
        if neg.size and pos.size:
            a_, b_ = complex(neg[np.argmax(neg.real)]), complex(pos[np.argmin(pos.real)])
            out.append(_root(a_, b_) if gained > 0 else _root(b_, a_))
    return out


def _root(la_: complex, lb: complex) -> tuple[float, float]:
    theta = la_.real / (la_.real - lb.real)
    return float(theta), float(la_.imag + theta * (lb.imag - la_.imag))


def dense_guess(branch: Branch, i: int, theta: float, arcs: Any = None) -> np.ndarray:
    """The dense output at fraction ``theta`` of segment ``i`` (the chord if it has none).
    ``arcs``: the branch's interpolant's arrays (:func:`~._dense.arrays`), if computed."""
    try:
        Z, T, w, errors, rtol = arcs if arcs is not None else arrays(branch)
        check_segment(branch, i, errors[i + 1], rtol)
        return segment(Z, T, w, i).sample(np.array([theta]))[0]
    except AccuracyError:
        z0 = np.array([branch[v][i] for v in branch.variables])
        z1 = np.array([branch[v][i + 1] for v in branch.variables])
        return z0 + theta * (z1 - z0)


def _hopf_rows(setting: _Setting, branch: Branch, eigs: list[Eigenvalues]) -> list[HopfRow]:
    rows: list[HopfRow] = []
    for i in range(len(branch) - 1):
        a, b = (0.0, eigs[i]), (1.0, eigs[i + 1])
        for theta, omega in _candidates(setting, branch, i, a, b, 0):
            row = _locate(setting, branch, i, theta, omega, eigs[i].start)
            if row is not None and not any(_same(row, old) for old in rows):
                rows.append(row)
    return rows


def _upper_unstable(lam: np.ndarray) -> int:
    return int(np.sum((lam.imag > REAL_TOL * np.maximum(1.0, np.abs(lam))) & (lam.real > 0)))


def _candidates(
    setting: _Setting,
    branch: Branch,
    i: int,
    a: tuple[float, Eigenvalues],
    b: tuple[float, Eigenvalues],
    depth: int,
) -> list[tuple[float, float]]:
    """``(θ, ω)`` of the pairs crossing on segment ``i`` between fractions ``a[0]`` and
    ``b[0]`` (with their spectra), halving where they do not account for the change in
    the number of unstable upper-half-plane eigenvalues (see the module)."""
    (ta, ea), (tb, eb) = a, b
    pairs = crossing_pairs(ea.values, eb.values)
    change = abs(_upper_unstable(eb.values) - _upper_unstable(ea.values))
    if len(pairs) >= change or depth >= 5:
        return [(ta + th * (tb - ta), om) for th, om in pairs]
    tm = 0.5 * (ta + tb)
    n = len(setting.problem.unknowns)
    zm = dense_guess(branch, i, tm, setting.arcs)
    pm = _params(setting, branch, i)
    pm[setting.free] = float(zm[n])
    mid = (tm, _at(setting, zm[:n], pm, ea.start, verify=False))
    return _candidates(setting, branch, i, a, mid, depth + 1) + _candidates(
        setting, branch, i, mid, b, depth + 1
    )


def _same(a: HopfRow, b: HopfRow) -> bool:
    return bool(np.max(np.abs(a.z - b.z) / np.maximum(1.0, np.abs(a.z))) < 1e-8)


def _locate(
    setting: _Setting, branch: Branch, i: int, theta: float, omega: float, start: Any
) -> HopfRow | None:
    """The row of the Hopf point guessed at fraction ``theta`` of segment ``i`` (a guess's
    row if Newton fails; None if the point found lies elsewhere)."""
    zg = dense_guess(branch, i, theta, setting.arcs)
    n = len(setting.problem.unknowns)
    pg = _params(setting, branch, i)
    pg[setting.free] = float(zg[n])
    try:
        row = hopf_row(
            setting.problem, branch, i=i, z_guess=zg, p_guess=pg, omega=omega, mass=setting.mass
        )
    except ContinuationError as exc:
        logger.info("Hopf candidate on segment %d not located: %s", i, exc)
        return _guess_row(setting, branch, i, theta, zg, pg, str(exc), start)
    if row is None:
        return None
    lam = _at(setting, row.z[:n], row.special.values, start, verify=False).values
    omega_h = float(row.special.details["omega"])
    if not np.min(np.abs(lam - 1j * omega_h)) <= 1e-6 * max(1.0, omega_h):
        logger.info("Newton's point at %s has no eigenvalue i*omega: dropped", row.z[n])
        return None
    near = int(np.count_nonzero(np.abs(lam - 1j * omega_h) <= 1e-6 * max(1.0, omega_h)))
    if near > 1:  # a double pair (a symmetric problem): located, but no generic Hopf point
        details = {
            k: v for k, v in row.special.details.items() if k not in ("criticality", "adjoint")
        }
        details.update(
            first_lyapunov=None,
            multiplicity=near,
            message=f"{near} eigenvalues at i*omega: not a simple pair, so no first Lyapunov "
            "coefficient (an equivariant Hopf point, as of a symmetric problem)",
        )
        row = replace(row, special=replace(row.special, details=details))
    return replace(row, eigenvalues=lam)


def _guess_row(
    setting: _Setting,
    branch: Branch,
    i: int,
    theta: float,
    zg: np.ndarray,
    pg: dict[str, float],
    message: str,
    start: Any,
) -> HopfRow:
    problem = setting.problem
    n = len(problem.unknowns)
    t0, t1 = branch.tangents[i], branch.tangents[i + 1]
    tangent = t0 + theta * (t1 - t0)
    lam = _at(setting, zg[:n], pg, start, verify=False).values
    s = float(branch.s[i] + theta * (branch.s[i + 1] - branch.s[i]))
    special = SpecialPoint(
        kind=Kind.HOPF,
        index=-1,
        values={**dict(zip(problem.unknowns, zg[:n].tolist())), **pg},
        tangent=tangent,
        status=PointStatus.GUESS,
        s=s,
        interval=(float(branch.s[i]), float(branch.s[i + 1])),
        details={"message": message},
        scales=branch.info.get("scales"),
    )
    rn = float(np.max(np.abs(problem.residual(zg[:n], pg))))
    return HopfRow(
        after=i,
        theta=theta,
        z=zg,
        tangent=tangent,
        eigenvalues=lam,
        special=special,
        iterations=0,
        residual_norm=rn,
    )


__all__ = ["VERIFY_EVERY", "crossing_pairs", "dense_guess", "with_stability"]
