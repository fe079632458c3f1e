"""Derivative strategies: finite differences (forward, central), complex step, and a check
of user-supplied Jacobians against finite differences."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.sparse as sp

from ._realvalues import Where, real_array, real_matrix

STRATEGIES = ("forward", "central", "complex")

_EPS = np.finfo(float).eps
_H_FORWARD = np.sqrt(_EPS)
_H_CENTRAL = _EPS ** (1.0 / 3.0)
_H_COMPLEX = 1e-30
_FD_WHAT = "the residual (evaluated for finite differences near the point)"


def _steps(x: np.ndarray, rel: float, scales: Any = 1.0) -> np.ndarray:
    """Steps ``rel·max(scales, |x|)``: relative to the component's scale (its typical size, 1
    unless the caller knows better), so that a variable of size 1e-8 or 1e8 is differenced
    as accurately as one of size 1."""
    h = rel * np.maximum(scales, np.abs(x))
    # make x + h exactly representable so the divided difference uses the true step
    return (x + h) - x


def column_groups(pattern) -> list[np.ndarray]:
    """Greedy grouping of structurally orthogonal columns of a sparse pattern (CPR / Curtis–
    Powell–Reid), so one residual evaluation per group gives all columns of the group."""
    pat = sp.csc_matrix(pattern, copy=True)  # (a CSC pattern would be shared: not the caller's)
    pat.data[:] = 1
    n = pat.shape[1]
    rows_of = [pat.indices[pat.indptr[j] : pat.indptr[j + 1]] for j in range(n)]
    groups: list[list[int]] = []
    used: list[np.ndarray] = []
    for j in range(n):
        for g, mask in enumerate(used):
            if not mask[rows_of[j]].any():
                groups[g].append(j)
                mask[rows_of[j]] = True
                break
        else:
            mask = np.zeros(pat.shape[0], dtype=bool)
            mask[rows_of[j]] = True
            groups.append([j])
            used.append(mask)
    return [np.asarray(g) for g in groups]


def fd_jacobian(
    f: Callable[[np.ndarray], np.ndarray],
    x: np.ndarray,
    *,
    method: str = "central",
    f0: np.ndarray | None = None,
    sparsity: Any = None,
    groups: list[np.ndarray] | None = None,
    scales: Any = 1.0,
    where: Where = None,
    step_factor: float = 1.0,
) -> Any:
    """Jacobian of ``f`` at ``x`` by finite differences or complex step.

    Parameters
    ----------
    f : callable, ``f(x) -> array of m``
        The function, of the float array ``x`` (complex under ``method="complex"``).
    x : ndarray, shape (n,)
        Where to differentiate.
    method : {"central", "forward", "complex"}
        The difference (steps ε^{1/3}, ε^{1/2} of the magnitudes) or the complex step.
    f0 : ndarray, shape (m,), optional
        ``f(x)``, if known (forward differences use it).
    sparsity : sparse or dense matrix, shape (m, n), optional
        Marks the possible nonzeros: columns are then grouped (:func:`column_groups`, or
        ``groups`` if given) so that one (forward, complex) or two (central) evaluations
        serve a group, and a CSR matrix is returned.
    scales : float or ndarray, shape (n,)
        The components' scales (typical sizes): the steps are
        ``h_j = step_factor·rel·max(scales_j, |x_j|)``.
    where : mapping, callable or str, optional
        The point, for the message refusing complex values of ``f`` under the real methods
        (:func:`~._realvalues.real_array`).
    step_factor : float
        Multiplies the steps (the extrapolation of :func:`extrapolated` takes 1 and 1/2).

    Returns
    -------
    ndarray, shape (m, n), or CSR matrix
    """
    x = np.asarray(x, dtype=float)
    n = x.size

    def real(y):
        return y if type(y) is np.ndarray and y.dtype == float else real_array(y, _FD_WHAT, where)

    if method == "forward":
        if f0 is None:
            f0 = real(f(x))
        h = _steps(x, step_factor * _H_FORWARD, scales)
    elif method == "central":
        h = _steps(x, step_factor * _H_CENTRAL, scales)
    elif method == "complex":
        h = np.full(n, _H_COMPLEX)
    else:
        raise ValueError(f"derivative method must be one of {STRATEGIES}, got {method!r}")

    def directional(d: np.ndarray) -> np.ndarray:
        if method == "forward":
            return real(f(x + d)) - f0
        if method == "central":
            return (real(f(x + d)) - real(f(x - d))) * 0.5
        return np.imag(np.asarray(f(x + 1j * d), dtype=complex))

    if sparsity is None:
        cols = []
        for j in range(n):
            d = np.zeros(n)
            d[j] = h[j]
            cols.append(directional(d) / h[j])
        return np.column_stack(cols) if cols else np.zeros((0, 0))
    return _grouped_jacobian(directional, h, sp.csc_matrix(sparsity), groups)


def _grouped_jacobian(
    directional: Callable[[np.ndarray], np.ndarray],
    h: np.ndarray,
    pat: Any,
    groups: list[np.ndarray] | None,
) -> Any:
    """The sparse Jacobian of pattern ``pat`` (CSC) from one directional difference a group
    of structurally orthogonal columns (steps ``h``), as CSR."""
    n = h.size
    if groups is None:
        groups = column_groups(pat)
    rows_list, cols_list, vals_list = [], [], []
    for g in groups:
        d = np.zeros(n)
        d[g] = h[g]
        df = directional(d)
        for j in g:
            rows = pat.indices[pat.indptr[j] : pat.indptr[j + 1]]
            rows_list.append(rows)
            cols_list.append(np.full(rows.size, j))
            vals_list.append(df[rows] / h[j])
    m = pat.shape[0]
    if not rows_list:
        return sp.csr_matrix((m, n))
    return sp.csr_matrix(
        (np.concatenate(vals_list), (np.concatenate(rows_list), np.concatenate(cols_list))),
        shape=(m, n),
    )


def fd_derivative(
    f: Callable[[Any], Any],
    x: float,
    *,
    method: str = "central",
    scale: float = 1.0,
    where: Where = None,
    step_factor: float = 1.0,
) -> np.ndarray:
    """Derivative of a vector function of one real variable (steps relative to
    ``max(scale, |x|)``, times ``step_factor``; complex values refused as in
    :func:`fd_jacobian`)."""
    if method == "complex":
        value = np.asarray(f(x + 1j * _H_COMPLEX), dtype=complex)
        return np.imag(value) / _H_COMPLEX
    if method == "forward":
        h = (x + step_factor * _H_FORWARD * max(scale, abs(x))) - x
        return (real_array(f(x + h), _FD_WHAT, where) - real_array(f(x), _FD_WHAT, where)) / h
    h = (x + step_factor * _H_CENTRAL * max(scale, abs(x))) - x
    up, down = real_array(f(x + h), _FD_WHAT, where), real_array(f(x - h), _FD_WHAT, where)
    return (up - down) / (2 * h)


def extrapolated(differenced: Callable[[float], Any]) -> Any:
    """Richardson's extrapolation of central difference quotients: ``differenced(factor)``
    is the quotient with the plain central step times ``factor``; the steps 1 and 1/2 are
    combined as (4 D(h/2) − D(h))/3, which cancels the h² term of their truncation error
    and leaves h⁴ (and about twice the rounding of one quotient). Where the third derivative
    is large next to the step (a variable far from where it varies, x ≈ 1000 in
    (x − 1000)(p − (x − 1000)²), whose plain central difference is off by h² = 3.7e-5),
    this is the difference between a branch point's parameter off by 1e-5 and by 1e-15.
    (The plain step, not a larger one: the step is relative to |x|, and larger steps would
    reach far from where such a variable varies.)"""
    coarse, fine = differenced(1.0), differenced(0.5)
    return (4.0 * fine - coarse) / 3.0


@dataclass(frozen=True)
class JacobianCheck:
    """Result of :func:`check_jacobian`; true when the derivatives agree.

    Parameters
    ----------
    ok : bool
        True when every entry agrees with central differences within the tolerance.
    max_error : float
        The largest scaled error (an entry fails above 1).
    worst : list of tuple of (int, str, float, float), optional
        ``(row, column name, supplied, finite-difference)`` for the worst failing entries.
    message : str, optional
        The same in words (``str(check)``).
    """

    ok: bool
    max_error: float
    worst: list[tuple[int, str, float, float]] = field(default_factory=list)
    message: str = ""

    def __bool__(self) -> bool:
        return self.ok

    def __str__(self) -> str:
        return self.message


def check_jacobian(
    problem, u, p=None, *, rtol: float = 1e-6, atol: float = 1e-8, show: int = 5
) -> JacobianCheck:
    """Compare a problem's Jacobian and parameter derivatives with central differences.

    The error of an entry is ``|supplied − fd| / (atol + rtol·max(|fd|, scale))`` with
    ``scale`` the largest magnitude in the column; an entry fails when that exceeds 1.

    Parameters
    ----------
    problem : Problem or ContinuationProblem
        The problem whose ``jacobian`` and ``param_jacobian`` are checked.
    u : array_like, shape (n,)
        The unknowns at which to compare.
    p : mapping of str to float, optional
        The parameter values (default: ``problem.params``).
    rtol, atol : float, optional
        The relative and absolute tolerances of the comparison.
    show : int, optional
        At most this many failing entries are listed in ``worst``.

    Returns
    -------
    JacobianCheck
        Whether they agree, the largest error and the worst entries.

    Examples
    --------
    >>> from cusp.continuation import Problem, check_jacobian
    >>> prob = Problem(lambda u, p: [u[0] ** 2 - p["a"]], ["x"], {"a": 2.0},
    ...                jacobian=lambda u, p: [[3.0 * u[0]]])  # wrong: 2x
    >>> bool(check_jacobian(prob, [1.0]))
    False
    """
    u = np.asarray(u, dtype=float)
    p = dict(problem.params if p is None else p)
    names = list(problem.unknowns) + list(p)
    supplied = problem.jacobian(u, p)
    at = {**dict(zip(problem.unknowns, u.tolist())), **p}
    supplied = real_matrix(supplied, "the jacobian", at)
    supplied = supplied.toarray() if sp.issparse(supplied) else supplied
    cols = [supplied]
    fd_cols = [fd_jacobian(lambda v: problem.residual(v, p), u, method="central", where=at)]
    for name in p:
        dp = real_array(problem.param_jacobian(u, p, name), f"the param_jacobian ({name!r})", at)
        cols.append(dp[:, None])

        def fp(val, name=name):
            q = dict(p)
            q[name] = val
            return problem.residual(u, q)

        fd_cols.append(fd_derivative(fp, float(p[name]), where=at)[:, None])
    a = np.hstack(cols)
    b = np.hstack(fd_cols)
    scale = np.maximum(np.abs(b), np.abs(b).max(axis=0, keepdims=True))
    err = np.abs(a - b) / (atol + rtol * scale)
    max_error = float(err.max()) if err.size else 0.0
    order = np.argsort(err, axis=None)[::-1][:show]
    worst = []
    for flat in order:
        i, j = np.unravel_index(flat, err.shape)
        if err[i, j] > 1.0:
            worst.append((int(i), names[j], float(a[i, j]), float(b[i, j])))
    ok = max_error <= 1.0
    if ok:
        message = f"Jacobian agrees with central differences (max scaled error {max_error:.3g})"
    else:
        lines = [
            f"row {i}, d/d{n}: supplied {x:.10g}, finite differences {y:.10g}"
            for i, n, x, y in worst
        ]
        message = (
            f"Jacobian disagrees with central differences (max scaled error "
            f"{max_error:.3g} with rtol={rtol}, atol={atol}):\n  " + "\n  ".join(lines)
        )
    return JacobianCheck(ok=ok, max_error=max_error, worst=worst, message=message)
