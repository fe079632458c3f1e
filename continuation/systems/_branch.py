"""The ordinary branch of a problem: ``G(u, p_free) = R(u, p)``, one free parameter, the others
held at their values (:class:`BranchSystem`), with the user's functions called directly in
the corrector's inner loop."""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
import scipy.sparse as sp

from .._errors import ProblemDefinitionError
from ..problem._problem import (
    Problem,
    as_matrix,
    as_vector,
    extrapolated_derivatives,
    has_exact_jacobian,
)
from ._curve import CurveSystem, state_weights

_NDARRAY = np.ndarray
_FLOAT = np.dtype(float)  # (the one float64 dtype numpy's arrays carry: tested by identity)


class BranchSystem(CurveSystem):
    """``G(u, p_free) = R(u, p)``: one free parameter, the others held at their values.

    Parameters
    ----------
    problem : Problem or ContinuationProblem
        The equations.
    free : str
        The free parameter.
    params : mapping of str to float, optional
        Every parameter's value (default: ``problem.params``).
    state_weight : float or None, optional
        Each unknown's weight in the arclength norm (None: ``1/n``).

    Raises
    ------
    ProblemDefinitionError
        ``free`` is not a parameter of the problem.
    """

    def __init__(
        self,
        problem,
        free: str,
        params: Mapping[str, float] | None = None,
        state_weight: float | None = None,
    ) -> None:
        self.problem = problem
        params = dict(problem.params if params is None else params)
        if free not in params:
            raise ProblemDefinitionError(
                f"free parameter {free!r} is not a parameter of the problem; "
                f"parameters are {sorted(params)}"
            )
        self.free = free
        self.params = params
        self.n = len(problem.unknowns)
        self.names = tuple(problem.unknowns) + (free,)
        self.dim = self.n + 1
        self.scales = np.ones(self.dim)
        self.base_weights = state_weights(self.n, 1, state_weight)
        self.weights = self.base_weights.copy()
        self.unit_weights = all(w == 1.0 for w in self.weights.tolist())
        self.exact_jacobian = self.derivatives_exact = has_exact_jacobian(problem)
        self.supplied_derivatives = _supplies_derivatives(problem)
        self._bind_callbacks()
        self._shapes = ((self.n, self.n), (self.n,))
        self.fold_components = (free,)
        self.scalar = self.n == 1

    def _bind_callbacks(self) -> None:
        # bound once: the corrector's inner loop calls these for every iteration (a
        # Problem's own callbacks, skipping its normalising wrappers: see below)
        problem = self.problem
        callbacks = getattr(problem, "callbacks", None)
        self._residual, self._jacobian, self._param_jacobian = (
            callbacks()
            if callbacks is not None
            else (problem.residual, problem.jacobian, problem.param_jacobian)
        )

    def _scaled_problem(self) -> None:
        with_typical = getattr(self.problem, "with_scales", None)
        if with_typical is not None:
            n = self.n
            self.problem = with_typical(self.scales[:n], {self.free: float(self.scales[n])})
            self._bind_callbacks()

    def with_values(self, values: Mapping[str, float]) -> BranchSystem:
        fixed = {k: float(values[k]) for k in self.params if k in values and k not in self.names}
        if all(self.params[k] == v for k, v in fixed.items()):
            return self
        new = object.__new__(BranchSystem)
        new.__dict__.update(self.__dict__)
        new.params = {**self.params, **fixed}
        return new

    def start_vector(self, u: np.ndarray) -> np.ndarray:
        return np.concatenate([u, [self.params[self.free]]])

    # residual and bordered_jacobian (and their scalar_ forms) are the corrector's inner
    # loop: the user's functions are called by _residual_at and _derivatives_at, and the
    # dense case is checked first (for the tiny systems of most problems the wrappers cost
    # more than the user's functions). An ArithmeticError raised by the user's functions
    # (ZeroDivisionError, OverflowError) or the "math domain error" of math.sqrt or math.log
    # at a trial point outside where they are defined reads as a non-finite value, which the
    # corrector rejects like any other (_reraise_unless_domain). The parameters are copied
    # by dict.copy and the free one set: half the cost of the display {**params, free: v},
    # which builds a second dict for the one item and merges both (measured by callgrind)

    def _residual_at(self, z):
        """The user's residual at ``z`` (its parameters with the free one at ``z[-1]``)."""
        p = self.params.copy()
        p[self.free] = z[-1]
        try:
            return self._residual(z[:-1], p)
        except KeyError as exc:
            raise _undeclared(exc, p, "residual") from None

    def _derivatives_at(self, z):
        """The user's ``(jacobian, param_jacobian)`` at ``z``, as they return them."""
        u = z[:-1]
        p = self.params.copy()
        p[self.free] = z[-1]
        try:
            return self._jacobian(u, p), self._param_jacobian(u, p, self.free)
        except KeyError as exc:
            raise _undeclared(exc, p, "jacobian or param_jacobian") from None

    def residual(self, z):
        try:
            r = self._residual_at(z)
        except _OUT_OF_DOMAIN as exc:  # division by zero, overflow, math domain: as NaN
            _reraise_unless_domain(exc)
            return np.full(self.n, np.nan)
        if type(r) is _NDARRAY and r.dtype is _FLOAT and r.shape == self._shapes[1]:
            return r  # (the common case, one test)
        if type(r) is not np.ndarray or r.dtype != float:
            r = as_vector(r, "the residual", lambda: self.values(z))
        if r.shape != self._shapes[1]:
            raise ProblemDefinitionError(
                f"residual must return {self.n} values (one per unknown), got shape {r.shape}"
            )
        return r

    def bordered_jacobian(self, z, row):
        """Return ``[∂R/∂u, ∂R/∂p_free]``, with ``row`` appended as a last row.

        Parameters
        ----------
        z : numpy.ndarray, shape (n + 1,)
            The unknowns and the free parameter.
        row : numpy.ndarray, shape (n + 1,), or None
            The bordering row (None: none).

        Returns
        -------
        numpy.ndarray or scipy.sparse matrix, shape (n + 1, n + 1) or (n, n + 1)
            The (bordered) Jacobian.
        """
        try:
            j, fp = self._derivatives_at(z)
        except _OUT_OF_DOMAIN as exc:  # as for the residual: a matrix the corrector finds NaN
            _reraise_unless_domain(exc)
            j, fp = np.full(self._shapes[0], np.nan), np.full(self.n, np.nan)
        return self._assembled(z, j, fp, row)

    def accurate_jacobian(self, z):
        """Return ``∂G/∂z`` at ``z`` with the differenced parts extrapolated.

        The differences are extrapolated to a higher order
        (:func:`~..problem._problem.extrapolated_derivatives`); the Jacobian itself is
        returned where the derivatives are exact or cannot be differenced there (a
        non-finite value).

        Parameters
        ----------
        z : numpy.ndarray, shape (n + 1,)
            The unknowns and the free parameter.

        Returns
        -------
        numpy.ndarray or scipy.sparse matrix, shape (n, n + 1)
            The Jacobian.
        """
        if self.derivatives_exact and not isinstance(self.problem, Problem):
            return self.jacobian(z)
        u = z[:-1]
        p = dict(self.params)
        p[self.free] = z[-1]
        try:
            j, fp = extrapolated_derivatives(self.problem, u, p, self.free)
        except _OUT_OF_DOMAIN as exc:
            _reraise_unless_domain(exc)
            return self.jacobian(z)
        a = self._assembled(z, j, fp, None)
        data = a.data if hasattr(a, "tocsr") else a
        return a if np.all(np.isfinite(data)) else self.jacobian(z)

    def _assembled(self, z, j, fp, row):
        """The user's ``(jacobian, param_jacobian)`` at ``z`` checked and bordered."""
        if type(fp) is not _NDARRAY or fp.dtype is not _FLOAT:
            fp = as_vector(fp, f"the param_jacobian (for {self.free!r})", lambda: self.values(z))
        if type(j) is not _NDARRAY or j.dtype is not _FLOAT:
            j = as_matrix(j, "the jacobian", lambda: self.values(z))
            if type(j) is not np.ndarray:
                return _sparse_border(j, fp, row)
        if j.shape != self._shapes[0] or fp.shape != self._shapes[1]:
            n = self.n
            raise ProblemDefinitionError(
                f"jacobian must be {n}×{n} and param_jacobian of length {n}, "
                f"got shapes {j.shape} and {fp.shape}"
            )
        n = self.n
        if row is None:
            a = np.empty((n, n + 1))
        else:
            a = np.empty((n + 1, n + 1))
            a[n] = row
        a[:n, :n] = j
        a[:n, n] = fp
        return a

    def scalar_residual(self, z) -> float | None:
        """Evaluate the residual of a problem of one unknown at ``z`` as a float.

        Parameters
        ----------
        z : numpy.ndarray, shape (n + 1,)
            The unknowns and the free parameter.

        Returns
        -------
        float or None
            The residual; None where it is not a finite float array of one value (or
            raises an ArithmeticError): the general path (:meth:`residual`) then says what
            is wrong.
        """
        try:
            r = self._residual_at(z)
        except _OUT_OF_DOMAIN as exc:
            _reraise_unless_domain(exc)
            return None
        if type(r) is _NDARRAY and r.dtype is _FLOAT and r.shape == (1,):
            v = r.item()
            return v if abs(v) < math.inf else None  # (NaN too)
        return None

    def scalar_jacobian(self, z) -> tuple[float, float] | None:
        """Evaluate ``(∂R/∂u, ∂R/∂p_free)`` of a problem of one unknown at ``z`` as floats.

        Parameters
        ----------
        z : numpy.ndarray, shape (n + 1,)
            The unknowns and the free parameter.

        Returns
        -------
        tuple of (float, float) or None
            The two derivatives; None as for :meth:`scalar_residual`.
        """
        try:
            j, fp = self._derivatives_at(z)
        except _OUT_OF_DOMAIN as exc:
            _reraise_unless_domain(exc)
            return None
        if (
            type(j) is _NDARRAY and j.dtype is _FLOAT and j.shape == (1, 1)
            and type(fp) is _NDARRAY and fp.dtype is _FLOAT and fp.shape == (1,)
        ):  # fmt: skip
            a, b = j.item(), fp.item()
            return (a, b) if abs(a) < math.inf and abs(b) < math.inf else None
        return None

    def checked(self, z) -> BranchSystem:
        """Return this system, or a copy with :attr:`scalar` off.

        The float path is turned off when the user's functions return anything but float
        arrays of one value at ``z`` (lists, other dtypes): it would give way to the array
        path at every call, each time after a call made for nothing. (Values that are not
        finite, or an ArithmeticError, say nothing of the types: the system is kept.)

        Parameters
        ----------
        z : numpy.ndarray, shape (n + 1,)
            The unknowns and the free parameter.

        Returns
        -------
        BranchSystem
            This system, or the copy.
        """
        if not self.scalar:
            return self
        try:
            r = self._residual_at(z)
            j, fp = self._derivatives_at(z)
        except _OUT_OF_DOMAIN as exc:
            _reraise_unless_domain(exc)
            return self
        if _floats(r, (1,)) and _floats(j, (1, 1)) and _floats(fp, (1,)):
            return self
        new = object.__new__(BranchSystem)
        new.__dict__.update(self.__dict__)
        new.scalar = False
        return new

    def jacobian(self, z):
        return self.bordered_jacobian(z, None)

    def fixed_values(self) -> dict[str, float]:
        return {k: v for k, v in self.params.items() if k != self.free}

    def values(self, z) -> dict[str, float]:
        out = dict(zip(self.problem.unknowns, map(float, z[:-1])))
        out.update(self.params)
        out[self.free] = float(z[-1])
        return out


_OUT_OF_DOMAIN = (ArithmeticError, ValueError)


def _floats(x: Any, shape: tuple[int, ...]) -> bool:
    """Whether ``x`` is a float64 array of ``shape`` (what the float path takes)."""
    return type(x) is _NDARRAY and x.dtype is _FLOAT and x.shape == shape


def _reraise_unless_domain(exc: Exception) -> None:
    """Re-raise ``exc`` unless it says the user's function was called outside its domain: an
    ArithmeticError (division by zero, overflow) or the ValueError of Python's ``math``
    functions (``math.sqrt`` or ``math.log`` of a negative number). Those read as a
    non-finite value, which the corrector rejects like NaN (the step is shortened; at the
    edge of the domain the branch stops and says why); any other error is the user's."""
    if isinstance(exc, ValueError) and (
        isinstance(exc, ProblemDefinitionError) or str(exc) != "math domain error"
    ):
        raise exc


def _supplies_derivatives(problem: Any) -> bool:
    """Whether the problem's Jacobian or parameter derivatives are the user's own functions
    (a :class:`Problem` given ``jacobian`` or ``param_jacobian``, or any other object
    following the protocol), not differences or the complex step."""
    if isinstance(problem, Problem):
        return problem.has_jacobian or problem.has_param_jacobian
    return True


def _undeclared(exc: KeyError, p: Mapping[str, float], what: str) -> Exception:
    """A KeyError raised by the user's ``what`` for a parameter name the problem does not
    declare, as a :class:`~.._errors.ProblemDefinitionError` naming it (any other KeyError
    unchanged)."""
    key = exc.args[0] if exc.args else None
    if isinstance(key, str) and key not in p:
        return ProblemDefinitionError(
            f"the {what} reads the parameter {key!r}, which the problem does not declare; "
            f"its parameters are {sorted(p)}: give {key!r} a value in params"
        )
    return exc


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
    return sp.csc_matrix(
        (np.concatenate(parts_d), (np.concatenate(parts_r), np.concatenate(parts_c))), shape=shape
    )
