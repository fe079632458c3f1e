"""Located Hopf points as rows of a branch: the row's record (:class:`HopfRow`), the point
by Newton on the Hopf system with its details and tangent (:func:`hopf_row`), and a branch
with such rows inserted and the stability columns added (:func:`inserted`)."""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from .._errors import ContinuationError
from .._outcomes import Kind, PointStatus
from ..detection._eigen import eigenvector_near, n_unstable
from ..detection._hopf import HopfPoint, locate_hopf
from ..detection._lyapunov import Factored, first_lyapunov
from ..problem._problem import as_matrix
from ._branch import Branch, SpecialPoint


@dataclass(frozen=True, kw_only=True)
class HopfRow:
    """A row to insert after row ``after`` at fraction ``theta`` of the segment: the curve
    vector ``z``, its tangent, its eigenvalues, its special point, the locating Newton's
    iterations and ``max|R|``."""

    after: int
    theta: float
    z: np.ndarray
    tangent: np.ndarray
    eigenvalues: np.ndarray | None
    special: SpecialPoint
    iterations: int
    residual_norm: float


def hopf_row(
    problem: Any,
    branch: Branch,
    *,
    i: int,
    z_guess: np.ndarray,
    p_guess: dict[str, float],
    omega: float,
    mass: Any,
) -> HopfRow | None:
    """The Hopf point located by Newton from a guess on segment ``i`` (its eigenvalues left
    to the caller); None if the point found lies off the segment. A failure of Newton
    raises its :class:`~.._errors.ContinuationError`."""
    n = len(problem.unknowns)
    free = branch.variables[-1]
    jac = as_matrix(problem.jacobian(z_guess[:n], p_guess))
    _, q0 = eigenvector_near(jac, mass, 1j * omega)
    h = locate_hopf(
        problem, mass=mass, u0=z_guess[:n], params=p_guess, free=free, omega0=omega, q0=q0
    )
    z = np.concatenate([h.u, [h.params[free]]])
    if not _on_segment(branch, i, z):
        return None
    theta = _project(branch, i, z)
    lu = Factored(h.jacobian)  # (for the tangent and the Lyapunov coefficient)
    tangent = _tangent(problem, branch, i, theta, h, lu)
    special = SpecialPoint(
        kind=Kind.HOPF,
        index=-1,
        values={**dict(zip(problem.unknowns, h.u.tolist())), **h.params},
        tangent=tangent,
        status=PointStatus.CONVERGED,
        s=float(branch.s[i] + theta * (branch.s[i + 1] - branch.s[i])),
        interval=(float(branch.s[i]), float(branch.s[i + 1])),
        details=hopf_details(problem, h, mass, lu),
        scales=branch.info.get("scales"),
    )
    return HopfRow(
        after=i,
        theta=theta,
        z=z,
        tangent=tangent,
        eigenvalues=None,
        special=special,
        iterations=h.iterations,
        residual_norm=h.residual_norm,
    )


def hopf_details(
    problem: Any, h: HopfPoint, mass: Any, lu: Factored | None = None
) -> dict[str, Any]:
    """A Hopf point's ``details``: ``omega``, Newton's ``iterations``, ``first_lyapunov``,
    ``criticality``, the ``eigenvector`` and ``adjoint`` (or a ``message`` saying why there
    is no first Lyapunov coefficient)."""
    details: dict[str, Any] = {"omega": h.omega, "iterations": h.iterations}
    try:
        lya = first_lyapunov(problem, h.u, h.params, h.omega, h.q, h.jacobian, mass, lu)
    except ContinuationError as exc:
        details.update(first_lyapunov=None, message=f"no first Lyapunov coefficient: {exc}")
        return details
    l1 = lya.l1
    crit = "supercritical" if l1 < 0 else "subcritical" if l1 > 0 else "degenerate"
    details.update(first_lyapunov=l1, criticality=crit, eigenvector=lya.q, adjoint=lya.adjoint)
    return details


def _on_segment(branch: Branch, i: int, z: np.ndarray) -> bool:
    z0 = np.array([branch[v][i] for v in branch.variables])
    z1 = np.array([branch[v][i + 1] for v in branch.variables])
    lo, hi = np.minimum(z0, z1), np.maximum(z0, z1)
    pad = 0.25 * (hi - lo) + 1e-9 * np.maximum(1.0, np.abs(z0))
    return bool(np.all((z >= lo - pad) & (z <= hi + pad)))


def _project(branch: Branch, i: int, z: np.ndarray) -> float:
    """The fraction of segment ``i`` nearest ``z`` (on the chord, scaled by the branch's
    typical sizes)."""
    scales = branch.info.get("scales") or {}
    sc = np.array([scales.get(v, 1.0) for v in branch.variables], dtype=float)
    z0 = np.array([branch[v][i] for v in branch.variables]) / sc
    z1 = np.array([branch[v][i + 1] for v in branch.variables]) / sc
    d = z1 - z0
    dd = float(d @ d)
    theta = float((z / sc - z0) @ d / dd) if dd > 0 else 0.5
    return min(1.0, max(0.0, theta))


def _tangent(
    problem: Any, branch: Branch, i: int, theta: float, h: HopfPoint, lu: Factored
) -> np.ndarray:
    """The branch's tangent at the Hopf point, ``(−A⁻¹ ∂R/∂p, 1)`` (``A`` is regular
    there), oriented and sized as the interpolated tangent ``t``."""
    t0, t1 = branch.tangents[i], branch.tangents[i + 1]
    t = t0 + theta * (t1 - t0)
    free = branch.variables[-1]
    dp = np.asarray(problem.param_jacobian(h.u, h.params, free), dtype=float)
    x = np.concatenate([-lu.solve(dp), [1.0]])
    if float(x @ t) < 0.0:
        x = -x
    return x * (np.linalg.norm(t) / np.linalg.norm(x))


def inserted(branch: Branch, rows: list[HopfRow], eigs: list[np.ndarray]) -> Branch:
    """A new branch with ``rows`` inserted, the special points re-indexed, the column
    ``n_unstable`` and ``eigenvalues`` (``eigs``: the old rows')."""
    rows = sorted(rows, key=lambda r: (r.after, r.theta))
    order: list[int | HopfRow] = []
    k = 0
    for i in range(len(branch)):
        order.append(i)
        while k < len(rows) and rows[k].after == i:
            order.append(rows[k])
            k += 1
    new_index = {item: j for j, item in enumerate(order) if isinstance(item, int)}
    columns: dict[str, list] = {key: [] for key in branch.keys()}
    stats: dict[str, list] = {key: [] for key in branch.stats}
    s, tangents, lam_rows, specials = [], [], [], []
    for j, item in enumerate(order):
        if isinstance(item, int):
            for key in columns:
                columns[key].append(branch[key][item])
            for key in stats:
                stats[key].append(branch.stats[key][item])
            s.append(branch.s[item])
            tangents.append(branch.tangents[item])
            lam_rows.append(eigs[item])
            continue
        named = dict(zip(branch.variables, item.z.tolist()))
        for key in columns:
            columns[key].append(named.get(key, branch[key][item.after]))
        _row_stats(stats, branch, item)
        s.append(item.special.s)
        tangents.append(item.tangent)
        lam_rows.append(np.zeros(0, complex) if item.eigenvalues is None else item.eigenvalues)
        specials.append(replace(item.special, index=j))
    specials += [replace(q, index=new_index[q.index]) for q in branch.special_points]
    specials.sort(key=lambda q: (q.index, q.kind != Kind.HOPF))
    return _assembled(branch, columns, s, tangents, specials, stats, lam_rows, new_index)


def _row_stats(stats: dict[str, list], branch: Branch, r: HopfRow) -> None:
    seg_error = branch.stats.get("interpolation_error")
    for key in stats:
        if key == "newton_iterations":
            stats[key].append(r.iterations)
        elif key == "residual_norm":
            stats[key].append(r.residual_norm)
        elif key == "interpolation_error" and seg_error is not None:
            stats[key].append(seg_error[r.after + 1])
        else:
            stats[key].append(0 if key == "rejected_steps" else 0.0)


def _assembled(
    branch: Branch,
    columns: dict[str, list],
    s: list,
    tangents: list,
    specials: list[SpecialPoint],
    stats: dict[str, list],
    lam_rows: list[np.ndarray],
    new_index: dict[int, int],
) -> Branch:
    cols = {key: np.asarray(v, dtype=float) for key, v in columns.items()}
    cols["n_unstable"] = np.array([n_unstable(lam) for lam in lam_rows], dtype=int)
    info = dict(branch.info)
    if "start_index" in info:
        info["start_index"] = new_index[int(info["start_index"])]
    return Branch(
        cols,
        variables=branch.variables,
        s=np.asarray(s, dtype=float),
        tangents=np.asarray(tangents, dtype=float),
        special_points=specials,
        status=branch.status,
        message=branch.message,
        stats={key: np.asarray(v) for key, v in stats.items()},
        info=info,
        kinds=branch.kinds | {Kind.HOPF},
        eigenvalues=lam_rows,
    )


__all__ = ["HopfRow", "hopf_details", "hopf_row", "inserted"]
