"""The problem protocol: residual R(u, p) = 0 with unknowns u and named parameters p."""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any, Protocol, runtime_checkable

import numpy as np
import scipy.sparse as sp

from .._errors import ProblemDefinitionError
from ._derivatives import STRATEGIES, column_groups, extrapolated, fd_derivative, fd_jacobian
from ._realvalues import Where, real_array, real_matrix


@runtime_checkable
class ContinuationProblem(Protocol):
    """What the solvers need from a problem.

    ``residual`` is required; :class:`Problem` supplies ``jacobian`` and ``param_jacobian`` by
    finite differences or complex step when the user does not.
    """

    @property
    def unknowns(self) -> tuple[str, ...]:
        """The names of the unknowns, in the order of ``u`` (length ``n``)."""
        ...

    @property
    def params(self) -> Mapping[str, float]:
        """Every parameter name and its value."""
        ...

    def residual(self, u: np.ndarray, p: Mapping[str, float]) -> np.ndarray:
        """Evaluate the residual ``R(u, p)``.

        Parameters
        ----------
        u : numpy.ndarray, shape (n,)
            The unknowns.
        p : mapping of str to float
            Every parameter's value.

        Returns
        -------
        numpy.ndarray, shape (n,)
            ``R(u, p)``.
        """
        ...

    def jacobian(self, u: np.ndarray, p: Mapping[str, float]) -> Any:
        """Evaluate the Jacobian ``∂R/∂u``.

        Parameters
        ----------
        u : numpy.ndarray, shape (n,)
            The unknowns.
        p : mapping of str to float
            Every parameter's value.

        Returns
        -------
        numpy.ndarray or scipy.sparse matrix, shape (n, n)
            ``∂R/∂u`` at ``(u, p)``.
        """
        ...

    def param_jacobian(self, u: np.ndarray, p: Mapping[str, float], name: str) -> np.ndarray:
        """Evaluate the derivative ``∂R/∂p[name]``.

        Parameters
        ----------
        u : numpy.ndarray, shape (n,)
            The unknowns.
        p : mapping of str to float
            Every parameter's value.
        name : str
            The parameter differentiated against.

        Returns
        -------
        numpy.ndarray, shape (n,)
            ``∂R/∂p[name]`` at ``(u, p)``.
        """
        ...


class Problem:
    """A system of ``n`` equations ``residual(u, p) = 0`` in ``n`` named unknowns.

    Parameters
    ----------
    residual : callable
        ``residual(u, p) -> array of n``; ``u`` is a float array of shape ``(n,)`` (complex
        under the ``"complex"`` strategy), ``p`` maps every parameter name to its value.
    unknowns : sequence of str, or str
        Names of the unknowns, in the order of ``u`` (one name may be given alone).
    params : mapping of str to float
        Parameter names and their (finite) values; the free parameter is chosen per
        computation.
    jacobian : callable, optional
        ``jacobian(u, p)`` returning the ``n × n`` matrix ``∂R/∂u``, dense or
        ``scipy.sparse``.
    param_jacobian : callable, optional
        ``param_jacobian(u, p, name)`` returning ``∂R/∂p[name]``, shape ``(n,)``.
    derivatives : {"central", "forward", "complex"}, optional
        Fallback for what is not supplied: central (default) or forward differences, or
        the complex step (the residual must accept complex input).
    sparsity : array_like or scipy.sparse matrix, shape (n, n), optional
        The nonzero pattern of ``∂R/∂u``: finite differences then use column grouping and
        return sparse Jacobians.
    name : str, optional
        A label shown by ``repr`` and in messages.
    mass : bool or array_like or scipy.sparse matrix, shape (n, n), optional
        Declares the residual a vector field, ``M u' = R(u, p)``: ``True`` for ``M = I``, or
        the constant ``n × n`` mass matrix (dense or sparse; singular for algebraic
        equations). Only stability and Hopf points use it (``trace(..., stability=True)``);
        None (default): ``R`` is not a vector field, and stability is refused.

    Raises
    ------
    ProblemDefinitionError
        A malformed argument: ``residual`` or a derivative not callable, empty or repeated
        unknowns, a non-finite parameter, an unknown ``derivatives`` strategy, a
        ``sparsity`` or ``mass`` of the wrong shape (the message names it).

    Examples
    --------
    >>> prob = Problem(lambda u, p: [u[0] ** 2 - p["a"]], ["x"], {"a": 4.0})
    >>> prob.residual([3.0], prob.params).tolist()
    [5.0]
    """

    def __init__(
        self,
        residual: Callable[[np.ndarray, Mapping[str, float]], Any],
        unknowns: Sequence[str],
        params: Mapping[str, float],
        *,
        jacobian: Callable | None = None,
        param_jacobian: Callable | None = None,
        derivatives: str = "central",
        sparsity=None,
        name: str | None = None,
        mass: Any = None,
    ) -> None:
        if not callable(residual):
            raise ProblemDefinitionError(f"residual must be callable, got {residual!r}")
        unknowns = _checked_unknowns(unknowns)
        clean = _checked_params(params, unknowns)
        if derivatives not in STRATEGIES:
            raise ProblemDefinitionError(
                f"derivatives must be one of {STRATEGIES}, got {derivatives!r}"
            )
        for label, fn in (("jacobian", jacobian), ("param_jacobian", param_jacobian)):
            if fn is not None and not callable(fn):
                raise ProblemDefinitionError(f"{label} must be callable or None, got {fn!r}")
        self._residual = residual
        self._jacobian = jacobian
        self._param_jacobian = param_jacobian
        self.unknowns = unknowns
        self.params = clean
        self.derivatives = derivatives
        self.name = name
        self.sparsity = None if sparsity is None else sp.csc_matrix(sparsity)
        if self.sparsity is not None and self.sparsity.shape != (len(unknowns),) * 2:
            raise ProblemDefinitionError(
                f"sparsity must be {len(unknowns)}×{len(unknowns)}, got {self.sparsity.shape}"
            )
        self._groups = None if self.sparsity is None else column_groups(self.sparsity)
        self.mass = _mass_matrix(mass, len(unknowns))
        # the scales (typical sizes) of the finite-difference steps (see with_scales)
        self._scales_u: Any = 1.0
        self._scales_p: dict[str, float] = {}

    @property
    def n(self) -> int:
        """The number of unknowns (and of equations)."""
        return len(self.unknowns)

    @property
    def has_jacobian(self) -> bool:
        """Whether ``∂R/∂u`` is the user's own function."""
        return self._jacobian is not None

    @property
    def has_param_jacobian(self) -> bool:
        """Whether the parameter derivatives are the user's own function."""
        return self._param_jacobian is not None

    def __repr__(self) -> str:
        """The name, unknowns and parameters; long lists of unknowns (discretisations) are
        shown by their first and last three names and their count.

        >>> Problem(lambda u, p: u, unknowns=[f"u{i}" for i in range(1000)], params={})
        <Problem: unknowns=['u0', 'u1', 'u2', ..., 'u997', 'u998', 'u999'] (1000), params={}>
        """
        label = f" {self.name!r}" if self.name else ""
        names = list(self.unknowns)
        if len(names) > 8:
            head = ", ".join(map(repr, names[:3]))
            tail = ", ".join(map(repr, names[-3:]))
            shown = f"[{head}, ..., {tail}] ({len(names)})"
        else:
            shown = str(names)
        return f"<Problem{label}: unknowns={shown}, params={self.params}>"

    def with_params(self, **values: float) -> Problem:
        """Return a copy with some parameter values changed.

        Parameters
        ----------
        **values : float
            New values of existing parameters, by name.

        Returns
        -------
        Problem
            The copy (this problem is left as it is).

        Raises
        ------
        ProblemDefinitionError
            A name that is not a parameter of the problem.
        """
        unknown = set(values) - set(self.params)
        if unknown:
            raise ProblemDefinitionError(
                f"unknown parameter(s) {sorted(unknown)}; the problem has {sorted(self.params)}"
            )
        new = object.__new__(Problem)
        new.__dict__.update(self.__dict__)
        new.params = {**self.params, **{k: float(v) for k, v in values.items()}}
        return new

    def with_scales(
        self, unknowns: np.ndarray | None, params: Mapping[str, float] | None = None
    ) -> Problem:
        """Return a copy whose finite differences step relative to typical sizes.

        The step is ``h = rel·max(scale, |x|)`` instead of ``rel·max(1, |x|)``, so that badly
        scaled variables are differenced accurately. The tracer sets the scales from the
        branch's own.

        Parameters
        ----------
        unknowns : numpy.ndarray, shape (n,), or None
            Typical sizes of the unknowns (None: 1).
        params : mapping of str to float, optional
            Typical sizes of parameters, by name (1 for those not given).

        Returns
        -------
        Problem
            The copy (this problem is left as it is).
        """
        new = object.__new__(Problem)
        new.__dict__.update(self.__dict__)
        new._scales_u = 1.0 if unknowns is None else np.asarray(unknowns, dtype=float)
        new._scales_p = dict(params or {})
        return new

    def callbacks(self) -> tuple[Callable, Callable, Callable]:
        """Return ``(residual, jacobian, param_jacobian)`` for inner loops.

        These are the user's own functions where given (results as returned: pass them
        through :func:`as_vector` and :func:`as_matrix`), the finite-difference methods for
        derivatives not given. Saves a call layer per evaluation (a third of the cost of a
        tiny system).

        Returns
        -------
        tuple of callable
            ``(residual, jacobian, param_jacobian)``.
        """
        return (
            self._residual,
            self.jacobian if self._jacobian is None else self._jacobian,
            self.param_jacobian if self._param_jacobian is None else self._param_jacobian,
        )

    def residual(self, u, p):
        """Evaluate the residual ``R(u, p)``, checked to be real.

        Parameters
        ----------
        u : array_like, shape (n,)
            The unknowns.
        p : mapping of str to float
            Every parameter's value.

        Returns
        -------
        numpy.ndarray, shape (n,)
            ``R(u, p)`` as floats.

        Raises
        ------
        ProblemDefinitionError
            A complex or malformed result (the message names the point).
        """
        return as_vector(self._residual(u, p), "the residual", lambda: _point(self, u, p))

    def jacobian(self, u, p):
        """Evaluate ``∂R/∂u``: the user's function, or finite differences / complex step.

        Parameters
        ----------
        u : array_like, shape (n,)
            The unknowns.
        p : mapping of str to float
            Every parameter's value.

        Returns
        -------
        numpy.ndarray or scipy.sparse matrix, shape (n, n)
            ``∂R/∂u`` at ``(u, p)`` (sparse when ``sparsity`` was given).

        Raises
        ------
        ProblemDefinitionError
            A complex or malformed result (the message names the point).
        """
        if self._jacobian is not None:
            return as_matrix(self._jacobian(u, p), "the jacobian", lambda: _point(self, u, p))
        return fd_jacobian(
            lambda v: self._residual(v, p),
            u,
            method=self.derivatives,
            sparsity=self.sparsity,
            groups=self._groups,
            scales=self._scales_u,
            where=lambda: _point(self, u, p),
        )

    def param_jacobian(self, u, p, name):
        """Evaluate ``∂R/∂p[name]``: the user's function, or a finite difference.

        Parameters
        ----------
        u : array_like, shape (n,)
            The unknowns.
        p : mapping of str to float
            Every parameter's value.
        name : str
            The parameter differentiated against.

        Returns
        -------
        numpy.ndarray, shape (n,)
            ``∂R/∂p[name]`` at ``(u, p)``.

        Raises
        ------
        ProblemDefinitionError
            A complex or malformed result (the message names the point).
        """
        if self._param_jacobian is not None:
            return as_vector(
                self._param_jacobian(u, p, name),
                f"the param_jacobian (for {name!r})",
                lambda: _point(self, u, p),
            )

        def f(value):
            q = dict(p)
            q[name] = value
            return self._residual(u, q)

        return fd_derivative(
            f,
            float(p[name]),
            method=self.derivatives,
            scale=self._scales_p.get(name, 1.0),
            where=lambda: _point(self, u, p),
        )


def _checked_unknowns(unknowns: Sequence[str] | str) -> tuple[str, ...]:
    """The names of the unknowns as a tuple (one name may be given alone), checked:
    non-empty strings, none repeated."""
    if isinstance(unknowns, str):
        unknowns = [unknowns]
    names = tuple(unknowns)
    if not names or not all(isinstance(x, str) and x for x in names):
        raise ProblemDefinitionError(
            f"unknowns must be a non-empty sequence of names, got {names!r}"
        )
    if len(set(names)) != len(names):
        raise ProblemDefinitionError(f"unknowns has repeated names: {names!r}")
    return names


def _checked_params(params: Mapping[str, float], unknowns: tuple[str, ...]) -> dict[str, float]:
    """The parameters as ``{name: float}``, checked: string names that are not unknowns,
    finite real values."""
    if not isinstance(params, Mapping):
        raise ProblemDefinitionError(
            f"params must be a mapping name -> value, got {type(params).__name__}"
        )
    clean = {}
    for key, value in params.items():
        if not isinstance(key, str) or not key:
            raise ProblemDefinitionError(f"parameter names must be strings, got {key!r}")
        if key in unknowns:
            raise ProblemDefinitionError(f"{key!r} is both an unknown and a parameter")
        try:
            value = float(value)
        except (TypeError, ValueError):
            raise ProblemDefinitionError(
                f"parameter {key!r} must be a real number, got {value!r}"
            ) from None
        if not math.isfinite(value):
            raise ProblemDefinitionError(f"parameter {key!r} must be finite, got {value!r}")
        clean[key] = value
    return clean


def extrapolated_derivatives(problem: Any, u: np.ndarray, p: Mapping[str, float], name: str):
    """``(jacobian, param_jacobian for name)`` of ``problem`` at ``(u, p)``, the parts it
    differences by central differences extrapolated to fourth order
    (:func:`~._derivatives.extrapolated`, whatever the problem's own method); the
    user's own functions and complex steps as they are. For locating points whose position
    depends on the Jacobian itself, branch points above all: their parameter is off by the
    Jacobian's error, to first order."""
    if not isinstance(problem, Problem) or problem.derivatives == "complex":
        return problem.jacobian(u, p), problem.param_jacobian(u, p, name)
    method = "central"  # (also for a forward-differenced problem: accuracy is wanted here)
    if problem.has_jacobian:
        jac = problem.jacobian(u, p)
    else:
        jac = extrapolated(
            lambda factor: fd_jacobian(
                lambda v: problem._residual(v, p),
                u,
                method=method,
                sparsity=problem.sparsity,
                groups=problem._groups,
                scales=problem._scales_u,
                where=lambda: _point(problem, u, p),
                step_factor=factor,
            ),
        )
    if problem.has_param_jacobian:
        return jac, problem.param_jacobian(u, p, name)

    def f(value):
        q = dict(p)
        q[name] = value
        return problem._residual(u, q)

    dp = extrapolated(
        lambda factor: fd_derivative(
            f,
            float(p[name]),
            method=method,
            scale=problem._scales_p.get(name, 1.0),
            where=lambda: _point(problem, u, p),
            step_factor=factor,
        ),
    )
    return jac, dp


def _mass_matrix(mass: Any, n: int) -> Any:
    """The ``mass`` argument of :class:`Problem` checked: None, or a float ``n × n`` matrix
    (sparse kept as CSC); ``True`` is the identity.

    >>> _mass_matrix(True, 2).toarray().tolist()
    [[1.0, 0.0], [0.0, 1.0]]
    """
    if mass is None or mass is False:
        return None
    if mass is True:
        return sp.identity(n, format="csc")
    try:
        m = sp.csc_matrix(mass, dtype=float) if sp.issparse(mass) else np.array(mass, float)
    except (TypeError, ValueError):
        raise ProblemDefinitionError(f"mass must be a real n×n matrix, got {mass!r}") from None
    if m.shape != (n, n):
        raise ProblemDefinitionError(f"mass must be {n}×{n} (one row per unknown), got {m.shape}")
    data = m.data if sp.issparse(m) else m
    if not np.all(np.isfinite(data)):
        raise ProblemDefinitionError("mass must be finite, got a matrix with NaN or inf")
    return m


def _point(problem: Problem, u, p) -> dict[str, Any]:
    """The values of an evaluation point by name (for messages)."""
    return {**dict(zip(problem.unknowns, np.ravel(u).tolist())), **p}


def has_exact_jacobian(problem) -> bool:
    """Whether the problem's Jacobian is analytic or by complex step (exact to rounding)."""
    return bool(
        getattr(problem, "has_jacobian", True) or getattr(problem, "derivatives", "") == "complex"
    )


def as_matrix(jac, what: str = "the jacobian", where: Where = None):
    """A Jacobian as returned by a user function, as a float array (sparse ones kept);
    complex values are refused naming ``what`` and the point ``where``
    (:func:`~._realvalues.real_array`)."""
    if type(jac) is np.ndarray and jac.dtype == float:
        return jac
    return real_matrix(jac, what, where)


def as_vector(x, what: str = "the residual", where: Where = None):
    """A residual or parameter derivative as returned by a user function, as a float array;
    complex values are refused naming ``what`` and the point ``where``."""
    if type(x) is np.ndarray and x.dtype == float:
        return x
    return real_array(x, what, where)


def as_problem(obj) -> ContinuationProblem:
    """Accept a :class:`Problem` or any object following :class:`ContinuationProblem`."""
    if isinstance(obj, Problem):
        return obj
    if all(hasattr(obj, a) for a in ("unknowns", "params", "residual")):
        if all(hasattr(obj, a) for a in ("jacobian", "param_jacobian")):
            return obj
        return Problem(obj.residual, obj.unknowns, obj.params)
    raise ProblemDefinitionError(
        f"expected a continuation.Problem (or an object with unknowns, params and residual), "
        f"got {type(obj).__name__}"
    )
