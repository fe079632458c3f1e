"""Distinct solutions at fixed parameters by deflated Newton (P. E. Farrell, Á. Birkisson and
S. W. Funke, "Deflation techniques for finding distinct solutions of nonlinear partial
differential equations", SIAM J. Sci. Comput. 37(4), A2026–A2045, 2015).

Once solutions ``u_1 … u_k`` are known, Newton is run on the deflated residual

    F(u) = M(u) R(u),   M(u) = Π_i (‖u − u_i‖^{−p} + σ)

(``p`` the power, ``σ`` the shift; with σ > 0, M ≥ σ^k, so F vanishes exactly where R does,
away from the known solutions, where M is infinite). Its Jacobian ``M J + R ∇Mᵀ`` is a rank-one
update of ``M J``, and by the Sherman–Morrison formula (the paper's §3) the deflated Newton
update is the undeflated one scaled: with ``δ = −J⁻¹R`` and ``g = ∇M/M = Σ_i ∇m_i/m_i``,

    δ_deflated = δ / (1 − g·δ),

one solve with ``J`` per iteration, no differencing of M. Each solution found is verified by
the undeflated residual and polished by plain Newton on R, and kept only if it is farther
than ``distinct`` (weighted) from every solution known.

The norm is ``‖d‖² = Σ d_i²/(n s_i²)`` (``s`` the unknowns' typical sizes, default 1): a root
mean square, so a discretisation's deflation does not depend on its number of nodes.
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sps
import scipy.sparse.linalg as spla
from numpy.typing import ArrayLike

from .._errors import ProblemDefinitionError
from ..problem._problem import ContinuationProblem, as_problem


@dataclass(frozen=True)
class Deflation:
    """The solutions :func:`deflate` found, in the order found.

    ``len(deflation)`` is the number of solutions.

    Parameters
    ----------
    unknowns : tuple of str
        The problem's unknowns, the order of each solution's entries.
    params : dict of str to float
        The parameter values.
    solutions : tuple of numpy.ndarray, each shape (n,)
        The unknowns of each solution (polished by Newton on R).
    residual_norms : tuple of float
        The max-norm of R at each.
    iterations : tuple of int
        The deflated Newton iterations that reached each.
    runs : int
        Deflated Newton runs (one per solution found and one per run that found none).
    solves : int
        Linear solves in all (deflated and polishing Newton).
    """

    unknowns: tuple[str, ...]
    params: dict[str, float]
    solutions: tuple[np.ndarray, ...]
    residual_norms: tuple[float, ...]
    iterations: tuple[int, ...]
    runs: int
    solves: int

    def __len__(self) -> int:
        return len(self.solutions)


@dataclass(frozen=True)
class _Settings:
    power: float
    shift: float
    weights: np.ndarray
    tol: float
    step_tol: float
    max_iterations: int
    distinct: float


def deflate(
    problem: ContinuationProblem,
    guesses: Sequence[ArrayLike],
    *,
    params: Mapping[str, float] | None = None,
    max_solutions: int = 10,
    known: Sequence[ArrayLike] = (),
    power: float = 2.0,
    shift: float = 1.0,
    scales: Mapping[str, float] | None = None,
    tol: float = 1e-10,
    step_tol: float = 1e-12,
    max_iterations: int = 100,
    distinct: float = 1e-6,
) -> Deflation:
    """Distinct solutions of ``R(u, p) = 0`` at fixed parameters by deflated Newton.

    Each guess in turn starts deflated Newton, deflating every solution found so far (and
    ``known``); a run that converges adds a solution and the same guess is tried again; a run
    that fails moves to the next guess. Stops at ``max_solutions``.

    Parameters
    ----------
    problem : Problem or ContinuationProblem
        The equations.
    guesses : sequence of array_like, each shape (n,)
        Starting points of deflated Newton.
    params : mapping of str to float, optional
        Parameter values overriding ``problem.params``.
    max_solutions : int, optional
        At most this many solutions (not counting ``known``).
    known : sequence of array_like, optional
        Solutions already known: deflated from the start, not returned.
    power, shift : float, optional
        The deflation operator's ``p`` (> 0) and ``σ`` (> 0; the paper's defaults 2 and 1).
    scales : mapping of str to float, optional
        Typical sizes of unknowns for the norm (default 1).
    tol : float, optional
        A solution's residual (max-norm) must be at most this, after polishing.
    step_tol : float, optional
        Newton stops when its undeflated update is this small (the norm above).
    max_iterations : int, optional
        Deflated Newton iterations per run.
    distinct : float, optional
        Solutions closer than this (the norm above) are the same.

    Returns
    -------
    Deflation
        The solutions found, with their residuals and the work done.

    Raises
    ------
    ProblemDefinitionError
        A setting out of its range, or a guess or known solution of the wrong shape.

    Examples
    --------
    >>> from cusp.continuation import Problem, deflate
    >>> prob = Problem(lambda u, p: [(u[0] - 1) * (u[0] - 2) * (u[0] - 3)], ["x"], {})
    >>> found = deflate(prob, [[0.0]], max_solutions=5)
    >>> sorted(round(float(u[0]), 12) for u in found.solutions)
    [1.0, 2.0, 3.0]
    """
    prob = as_problem(problem)
    p = _params(prob, params)
    n = len(prob.unknowns)
    sizes = np.array([float((scales or {}).get(name, 1.0)) for name in prob.unknowns])
    _validate(max_solutions, power, shift, tol, step_tol, max_iterations, distinct, sizes)
    settings = _Settings(power, shift, 1.0 / (n * sizes * sizes), tol, step_tol,
                         max_iterations, distinct)  # fmt: skip
    starts = [_vector(g, n, "guesses") for g in guesses]
    roots = [_vector(k, n, "known") for k in known]
    found: list[tuple[np.ndarray, float, int]] = []
    runs = solves = 0
    for g in starts:
        while len(found) < max_solutions:
            runs += 1
            u, iters, used = _deflated_newton(prob, p, g, roots, settings)
            solves += used
            if u is None:
                break
            u, norm, used = _polish(prob, p, u, settings)
            solves += used
            if u is None or not _is_new(u, roots, settings):
                break
            roots.append(u)
            found.append((u, norm, iters))
    return Deflation(
        unknowns=tuple(prob.unknowns), params=dict(p),
        solutions=tuple(f[0] for f in found), residual_norms=tuple(f[1] for f in found),
        iterations=tuple(f[2] for f in found), runs=runs, solves=solves,
    )  # fmt: skip


def _deflated_newton(
    prob: ContinuationProblem, p: dict, u0: np.ndarray, roots: list, s: _Settings
) -> tuple[np.ndarray | None, int, int]:
    """(solution or None, iterations, solves) of Newton on the deflated residual from u0."""
    u = u0.copy()
    for it in range(1, s.max_iterations + 1):
        delta = _newton_step(prob, p, u)
        if delta is None:
            return None, it, it
        g = _log_gradient(u, roots, s)
        denom = 1.0 - float(g.dot(delta))
        if not np.isfinite(denom) or denom == 0.0:
            return None, it, it
        u = u + delta / denom
        if not np.all(np.isfinite(u)):
            return None, it, it
        if _norm(delta, s.weights) <= s.step_tol:
            return u, it, it
    return None, s.max_iterations, s.max_iterations


def _polish(
    prob: ContinuationProblem, p: dict, u: np.ndarray, s: _Settings
) -> tuple[np.ndarray | None, float, int]:
    """Plain Newton on R from a deflated solution (at most 5 iterations), then the residual
    check: (u or None, max-norm of R, solves)."""
    solves = 0
    for _ in range(5):
        delta = _newton_step(prob, p, u)
        solves += 1
        if delta is None:
            return None, float("inf"), solves
        u = u + delta
        if _norm(delta, s.weights) <= s.step_tol:
            break
    r = np.asarray(prob.residual(u, p), dtype=float)
    norm = float(np.max(np.abs(r))) if r.size else 0.0
    if not (np.isfinite(norm) and norm <= s.tol):
        return None, norm, solves
    return u, norm, solves


def polished(problem: ContinuationProblem, params: Mapping[str, float], u: ArrayLike) -> np.ndarray:
    """``u`` after plain Newton on R at ``params`` (at most 5 iterations, stopping at an
    update of 1e-12 relative), or ``u`` itself if Newton fails there: a known solution read
    off a branch's dense output (within its ``rtol``), made exact before it is deflated."""
    prob = as_problem(problem)
    p = _params(prob, params)
    v = np.array(u, dtype=float)
    n = v.size
    s = _Settings(2.0, 1.0, np.full(n, 1.0 / max(n, 1)), 1e-10, 1e-12, 5, 1e-6)
    out, _, _ = _polish(prob, p, v, s)
    return v if out is None else out


def _newton_step(prob: ContinuationProblem, p: dict, u: np.ndarray) -> np.ndarray | None:
    """``−J⁻¹R`` at u, or None where R is not finite or J is singular."""
    r = np.asarray(prob.residual(u, p), dtype=float)
    if not np.all(np.isfinite(r)):
        return None
    jac = prob.jacobian(u, p)
    try:
        if sps.issparse(jac):
            step = spla.splu(sps.csc_matrix(jac)).solve(-r)
        else:
            step = _dense_solve(np.asarray(jac, dtype=float), -r)
    except (np.linalg.LinAlgError, RuntimeError, ValueError):
        return None
    return step if np.all(np.isfinite(step)) else None


def _dense_solve(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a⁻¹b`` by scipy's ``solve``, without its warning for an ill-conditioned ``a``
    (``LinAlgWarning``: Newton beside a singular root meets such a J on every step, and
    crosses it; an exactly singular one still raises)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", sla.LinAlgWarning)
        return sla.solve(a, b)


def _log_gradient(u: np.ndarray, roots: list, s: _Settings) -> np.ndarray:
    """``∇M/M = Σ_i ∇m_i/m_i``, ``m_i = ‖u − u_i‖^{−p} + σ``, ``∇‖d‖ = W d/‖d‖``."""
    g = np.zeros_like(u)
    for root in roots:
        d = u - root
        r2 = float(d.dot(s.weights * d))
        if r2 == 0.0:
            continue
        inv = r2 ** (-0.5 * s.power)  # ‖d‖^{-p}
        g += (-s.power * inv / r2) * (s.weights * d) / (inv + s.shift)
    return g


def _is_new(u: np.ndarray, roots: list, s: _Settings) -> bool:
    return all(_norm(u - r, s.weights) > s.distinct for r in roots)


def _norm(d: np.ndarray, w: np.ndarray) -> float:
    return float(np.sqrt(d.dot(w * d)))


def _params(prob: ContinuationProblem, params: Mapping[str, float] | None) -> dict:
    p = dict(prob.params)
    for name, value in (params or {}).items():
        if name not in p:
            raise ProblemDefinitionError(
                f"params names {name!r}, which is not a parameter of the problem {sorted(p)}"
            )
        p[name] = float(value)
    return p


def _vector(x: ArrayLike, n: int, what: str) -> np.ndarray:
    v = np.array(x, dtype=float, ndmin=1)
    if v.shape != (n,) or not np.all(np.isfinite(v)):
        raise ProblemDefinitionError(
            f"each of {what} must hold {n} finite values (one per unknown), got {v!r}"
        )
    return v


def _validate(max_solutions, power, shift, tol, step_tol, max_iterations, distinct, sizes):
    checks = (
        ("max_solutions", max_solutions, isinstance(max_solutions, int) and max_solutions >= 1,
         "an int >= 1"),
        ("power", power, power > 0, "> 0"),
        ("shift", shift, shift > 0, "> 0 (a shift of 0 lets M·R vanish away from solutions)"),
        ("tol", tol, tol > 0, "> 0"),
        ("step_tol", step_tol, step_tol > 0, "> 0"),
        ("max_iterations", max_iterations,
         isinstance(max_iterations, int) and max_iterations >= 1, "an int >= 1"),
        ("distinct", distinct, distinct > 0, "> 0"),
        ("scales", sizes.tolist(), bool(np.all(np.isfinite(sizes)) and np.all(sizes > 0)),
         "finite and > 0"),
    )  # fmt: skip
    for name, value, ok, allowed in checks:
        if not ok:
            raise ProblemDefinitionError(f"{name} must be {allowed}, got {value!r}")


__all__ = ["Deflation", "deflate", "polished"]
