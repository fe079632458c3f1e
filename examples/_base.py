"""What every example returns: an :class:`Example` (a ready :class:`~cusp.continuation.Problem`
with its hand-written derivatives, a start point and its reference special points), and the
helper that builds the problem with analytic derivatives or a finite-difference fallback."""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from cusp.continuation import Problem

if TYPE_CHECKING:
    from cusp.continuation import Branch

#: How an example's :class:`Problem` gets its derivatives: ``"analytic"`` (the hand-written
#: Jacobian and parameter derivatives) or one of the solver's fallbacks (``"central"`` or
#: ``"forward"`` differences, ``"complex"`` step), the hand-written ones then left unused.
DERIVATIVES = ("analytic", "central", "forward", "complex")

#: Digits of the mpmath reference computations.
DPS = 40


class Reference(NamedTuple):
    """A known special point of an example, independent of the solver.

    ``kind`` is ``"fold"``, ``"branch_point"``, ``"cusp"``, ``"codim2"`` (a fold that is also
    a branch point) or ``"kink"`` (a non-smooth turning point: only the residual vanishes).
    ``values`` holds every unknown and parameter. ``free`` names the free parameter of the
    branch through the point (and, for a cusp or codim2 point, the second parameter of the
    fold curve). ``with_respect_to`` is the variable that turns at a fold: the free parameter
    (``None``) or a monitored unknown (a snap-back).
    """

    kind: str
    values: Mapping[str, float]
    free: tuple[str, ...]
    with_respect_to: str | None = None


@dataclass(frozen=True, eq=False)
class Example:
    """A ready example problem.

    ``problem`` is the :class:`~cusp.continuation.Problem`; ``u0`` a point on its branch (or a
    guess Newton corrects) at ``problem.params``; ``free`` the parameter the examples continue
    in and ``bounds`` a window holding its known special points; ``monitor`` the unknowns
    whose turning points are of interest. ``residual``, ``jacobian`` and ``param_jacobian``
    are the hand-written functions, whatever derivative strategy the problem uses (tests check
    solver output with them, independently of the solver). :meth:`references` computes the
    known special points on demand (some need mpmath and take a while).
    """

    name: str
    problem: Problem
    u0: np.ndarray
    free: str
    bounds: Mapping[str, tuple[float, float]]
    residual: Callable[[np.ndarray, Mapping[str, float]], np.ndarray]
    jacobian: Callable[[np.ndarray, Mapping[str, float]], Any]
    param_jacobian: Callable[[np.ndarray, Mapping[str, float], str], np.ndarray]
    monitor: tuple[str, ...] = ()
    reference_points: Callable[[], Sequence[Reference]] | None = field(default=None, repr=False)

    @property
    def unknowns(self) -> tuple[str, ...]:
        """The problem's unknowns, in the order of ``u``."""
        return self.problem.unknowns

    @property
    def params(self) -> dict[str, float]:
        """A copy of the problem's parameter values."""
        return dict(self.problem.params)

    def references(self) -> tuple[Reference, ...]:
        """The known special points (closed form or mpmath; see each example's docstring)."""
        return () if self.reference_points is None else tuple(self.reference_points())

    def trace(self, **options: Any) -> Branch:
        """``trace(problem, u0, free=free, bounds=bounds, monitor=monitor, **options)``; any of
        those may be overridden by keyword."""
        from cusp.continuation import trace

        kw: dict[str, Any] = {"free": self.free, "bounds": dict(self.bounds)}
        if self.monitor:
            kw["monitor"] = list(self.monitor)
        kw.update(options)
        return trace(self.problem, kw.pop("u0", self.u0), **kw)


def make_example(
    name: str,
    residual: Callable,
    unknowns: Sequence[str],
    params: Mapping[str, float],
    jacobian: Callable,
    param_jacobian: Callable,
    *,
    derivatives: str,
    u0: Sequence[float] | np.ndarray,
    free: str,
    bounds: Mapping[str, tuple[float, float]],
    monitor: Sequence[str] = (),
    references: Callable[[], Sequence[Reference]] | None = None,
    sparsity: Any = None,
) -> Example:
    """An :class:`Example` whose problem uses the hand-written derivatives
    (``derivatives="analytic"``) or the solver's fallback ``derivatives`` (then ``sparsity``,
    if given, is the Jacobian's pattern for grouped finite differences)."""
    if derivatives == "analytic":
        problem = Problem(
            residual,
            unknowns=list(unknowns),
            params=dict(params),
            jacobian=jacobian,
            param_jacobian=param_jacobian,
            name=name,
        )
    elif derivatives in DERIVATIVES:
        problem = Problem(
            residual,
            unknowns=list(unknowns),
            params=dict(params),
            derivatives=derivatives,
            sparsity=sparsity,
            name=name,
        )
    else:
        raise ValueError(f"derivatives must be one of {DERIVATIVES}, got {derivatives!r}")
    return Example(
        name=name,
        problem=problem,
        u0=np.array(u0, dtype=float),
        free=free,
        bounds=dict(bounds),
        residual=residual,
        jacobian=jacobian,
        param_jacobian=param_jacobian,
        monitor=tuple(monitor),
        reference_points=references,
    )


def one_unknown(name, residual, dfdx, dfdp, params, *, derivatives, x0, free, bounds, refs):
    """An example with the one unknown ``x``: ``residual(x, p)``, its derivatives
    ``dfdx(x, p)`` and ``dfdp(x, p, name)`` as scalars (see :func:`make_example`)."""

    def jacobian(u, p):
        return np.array([[dfdx(u[0], p)]])

    def param_jacobian(u, p, which):
        return np.array([dfdp(u[0], p, which)])

    return make_example(
        name,
        lambda u, p: np.array([residual(u[0], p)]),
        ["x"],
        params,
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[x0],
        free=free,
        bounds=bounds,
        references=refs,
    )
