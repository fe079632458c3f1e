"""Two-parameter continuation of Hopf points, and the codimension-2 points on the curve.

:func:`hopf_curve` traces the regular Hopf system of :mod:`~..detection._hopf` as an ordinary
:class:`~..problem._problem.Problem` with the public tracer: unknowns ``(u, qr, qi, ω, p2)``, free
parameter ``p1`` (``3n + 2`` equations). Its test functions are :class:`~..problem._events.Event`
objects, located on the curve by the tracer's own event location (regula falsi on the
arc, to ``locate_tol``):

- ``"bautin"`` (generalised Hopf): the first Lyapunov coefficient ``l1``
  (:mod:`~..detection._lyapunov`) changes sign (a sign change through a pole of ``l1``, as
  ``ω → 0``, is not reported);
- ``"bogdanov_takens"``: ``ω`` changes sign. The extended system is smooth through
  ``ω = 0`` (``ω ↦ −ω``, ``q ↦ q̄`` maps it to itself), so past the point the curve retraces
  the same Hopf points: the event is terminal;
- ``"zero_hopf"`` (fold–Hopf): a real eigenvalue crosses 0 beside the pair:
  ``det A / ω²`` (the product of the other eigenvalues, up to ``det M``) changes sign,
  normalised by its size at the start (the sign and log-magnitude of an LU).

The located points are reported with their own kinds (``details``: ``omega``,
``first_lyapunov`` where defined).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import replace
from typing import Any

import numpy as np
import scipy.sparse as sp

from .._errors import ContinuationError, ProblemDefinitionError, SingularMatrixError
from .._options import KEEP, ContinuationOptions, Keep, with_overrides
from .._outcomes import Kind, PointStatus
from ..detection._eigen import eigenvector_near, vector_field_mass
from ..detection._hopf import HopfSystem
from ..detection._lyapunov import first_lyapunov
from ..numerics._linalg import factor
from ..problem._events import Event
from ..problem._problem import ContinuationProblem, Problem, as_matrix, as_problem
from ..results._branch import Branch, SpecialPoint, join_halves
from ..stepping._trace import trace

CODIM2 = (Kind.BAUTIN, Kind.BOGDANOV_TAKENS, Kind.ZERO_HOPF)
#: the value of l1 where it is undefined (ω = 0, A singular): its poles, never a zero
_POLE = 1e300


class _Curve:
    """The Hopf system as a problem in ``z = (u, qr, qi, ω, p2)`` with ``p1`` free."""

    def __init__(self, problem: Any, mass: Any, q0: np.ndarray, p1: str, p2: str) -> None:
        self.base = problem
        self.mass = mass
        self.n = len(problem.unknowns)
        self.system = HopfSystem(problem, mass, q0)
        self.p1, self.p2 = p1, p2
        self.scale0 = 0.0

    def split(self, z: np.ndarray, pars: Mapping[str, float]) -> tuple:
        n = self.n
        p = {k: float(pars[k]) for k in self.base.params if k != self.p2}
        p[self.p2] = float(z[3 * n + 1])
        return z[:n], z[n : 2 * n] + 1j * z[2 * n : 3 * n], float(z[3 * n]), p

    def residual(self, z: np.ndarray, pars: Mapping[str, float]) -> np.ndarray:
        u, q, omega, p = self.split(z, pars)
        jac, _ = self.system.derivatives(u, p, self.p1)
        return self.system.residual(u, p, q, omega, jac)

    def jacobian(self, z: np.ndarray, pars: Mapping[str, float]) -> Any:
        u, q, omega, p = self.split(z, pars)
        jac, dp2 = self.system.derivatives(u, p, self.p2)
        state = self.system.state_jacobian(u, p, q, omega, jac)
        col = self.system.param_column(u, p, q, self.p2, dp2)
        if sp.issparse(state):
            return sp.hstack([state, sp.csc_matrix(col.reshape(-1, 1))], format="csc")
        return np.column_stack([state, col])

    def param_jacobian(self, z: np.ndarray, pars: Mapping[str, float], name: str) -> np.ndarray:
        u, q, omega, p = self.split(z, pars)
        _, dp = self.system.derivatives(u, p, name)
        return self.system.param_column(u, p, q, name, dp)

    # -- test functions (events)
    def l1(self, z: np.ndarray, pars: Mapping[str, float]) -> float:
        u, q, omega, p = self.split(z, pars)
        if omega < 0.0:  # the same Hopf point as (−ω, q̄)
            omega, q = -omega, q.conj()
        jac = as_matrix(self.base.jacobian(u, p))
        try:
            return first_lyapunov(self.base, u, p, omega, q, jac, self.mass).l1
        except ContinuationError:  # ω = 0 or A singular: a pole of l1 (not a zero)
            return _POLE

    def omega(self, z: np.ndarray, pars: Mapping[str, float]) -> float:
        return float(z[3 * self.n])

    def others(self, z: np.ndarray, pars: Mapping[str, float]) -> float:
        """``det A / ω²`` over its size at the start (see the module)."""
        u, _, omega, p = self.split(z, pars)
        sign, logdet = _slogdet(as_matrix(self.base.jacobian(u, p)))
        if sign == 0.0 or omega == 0.0:
            return 0.0
        return float(sign * np.exp(logdet - 2.0 * np.log(abs(omega)) - self.scale0))


def _slogdet(jac: Any) -> tuple[float, float]:
    """Sign and log-magnitude of ``det jac`` by its LU (``(0, −inf)`` if singular)."""
    try:
        lu = factor(jac)
    except SingularMatrixError:
        return 0.0, -np.inf
    return lu.sign_det(), lu.log_abs_det()


def hopf_curve(
    problem: ContinuationProblem,
    hopf_point: SpecialPoint,
    *,
    free: tuple[str, str],
    direction: str | int = "both",
    bounds: Mapping[str, Sequence[float]] | None = None,
    targets: Mapping[str, Sequence[float]] | None = None,
    events: Sequence[Event] = (),
    scales: Mapping[str, float] | None = None,
    codim2: bool = True,
    options: ContinuationOptions | None = None,
    throw: bool = True,
    rtol: float | Keep = KEEP,
    ds: float | Keep = KEEP,
    ds_min: float | Keep = KEEP,
    ds_max: float | Keep = KEEP,
    max_steps: int | Keep = KEEP,
    tol: float | Keep = KEEP,
    step_tol: float | Keep = KEEP,
    max_step_solves: int | Keep = KEEP,
    max_newton_iterations: int | Keep = KEEP,
    target_newton_iterations: int | Keep = KEEP,
    max_angle: float | Keep = KEEP,
    target_angle: float | Keep = KEEP,
    target_contraction: float | Keep = KEEP,
    target_distance: float | Keep = KEEP,
    curve_tol: float | Keep = KEEP,
    growth: float | Keep = KEEP,
    predictor: str | Keep = KEEP,
    state_weight: float | None | Keep = KEEP,
    detect_folds: bool | Keep = KEEP,
    detect_branch_points: bool | Keep = KEEP,
    locate_tol: float | Keep = KEEP,
    max_locate_iterations: int | Keep = KEEP,
) -> Branch:
    """Continue a Hopf point in two parameters.

    Parameters
    ----------
    problem : Problem or ContinuationProblem
        The problem the Hopf point was found on (declared a vector field: ``mass=``).
    hopf_point : SpecialPoint
        A converged ``"hopf"`` special point of ``trace(..., stability=True)``.
    free : (str, str)
        ``(p1, p2)``: the branch's free parameter and the second parameter.
    direction : {"both", 1, -1}, optional
        ``"both"`` (default: the two halves joined at the starting point), ``+1`` or ``-1``
        (the sign of the initial change of ``p1``).
    bounds, targets, events, scales : optional
        As for :func:`~cusp.continuation.trace`, on the Hopf curve: bounds may name any
        unknown, ``p1``, ``p2`` or ``"omega"``.
    codim2 : bool, optional
        Detect and locate ``"bautin"``, ``"bogdanov_takens"`` and ``"zero_hopf"`` (see the
        module; default True).
    options : ContinuationOptions, optional
        Default: ``ContinuationOptions(detect_branch_points=False)``.
    throw : bool, optional
        If False, a failure returns the partial curve with its status instead of raising.

    Returns
    -------
    Branch
        The Hopf curve: columns the unknowns, the eigenvector's parts ``"qr:<name>"`` and
        ``"qi:<name>"``, ``"omega"`` and the parameters; its codimension-2 points as
        special points of their kinds (``details``: ``omega``, and ``first_lyapunov`` at a
        Bautin point).

    Other Parameters
    ----------------
    rtol, ds, ds_min, ds_max, max_steps, tol, step_tol, max_step_solves, \
max_newton_iterations, target_newton_iterations, max_angle, target_angle, \
target_contraction, target_distance, curve_tol, growth, predictor, state_weight, \
detect_folds, detect_branch_points, locate_tol, max_locate_iterations : optional
        The field of the same name of ``options``, overridden.

    Raises
    ------
    ProblemDefinitionError
        ``hopf_point`` not a converged Hopf point, ``free`` not a pair of the problem's
        parameters, a bad ``direction``, or a problem that is no vector field.
    ContinuationError
        A failure of the continuation (with ``throw=True``).
    """
    problem = as_problem(problem)
    mass = vector_field_mass(problem)
    p1, p2, z0, q0 = _setup(problem, hopf_point, free, mass)
    if direction not in ("both", 1, -1):
        raise ProblemDefinitionError(f"direction must be 'both', +1 or -1, got {direction!r}")
    options = with_overrides(options, HOPF_OPTIONS, locals())
    curve, pars, aug = _augmented(problem, hopf_point, mass, q0, p1, p2, z0)
    tests = list(events) + (_codim2_events(curve) if codim2 else [])
    sizes = {**_scales(problem, hopf_point, aug.unknowns), **dict(scales or {})}
    halves = [
        _traced(curve, aug, z0, free=p1, direction=d, bounds=bounds, targets=targets,
                events=tests, scales=sizes, options=options, throw=throw)
        for d in ((1, -1) if direction == "both" else (int(direction),))
    ]  # fmt: skip
    if len(halves) == 1:
        out = halves[0]
        out.info.update(direction=direction, start_index=0)
    else:
        out = join_halves(halves[1], halves[0], start_kind=Kind.HOPF, start_label="start (hopf)")
    return _relabel(out, curve, pars)


_DIFFERENCED = (
    " (The Hopf system holds the problem's Jacobian, here by finite differences: Newton "
    "cannot bring the system's residual below their rounding noise, which grows with the "
    "residual's size; where it nears tol it stalls the corrector or trips a step guard. "
    "Give the problem its jacobian=, or derivatives='complex' for a residual that takes "
    "complex numbers.)"
)


def _traced(curve: _Curve, aug: ContinuationProblem, z0: np.ndarray, **kw: Any) -> Branch:
    """One half of the curve (:func:`trace`); the failure of a curve whose Jacobian is
    differenced says what that costs."""
    try:
        return trace(aug, z0, **kw)
    except ContinuationError as exc:
        if not curve.system.exact:
            exc.args = (f"{exc.args[0]}{_DIFFERENCED}", *exc.args[1:])
        raise


HOPF_OPTIONS = ContinuationOptions(detect_branch_points=False)
"""The default options of a Hopf curve (as a fold curve's: no branch points of the extended
system)."""


def _augmented(
    problem: Any,
    hopf_point: SpecialPoint,
    mass: Any,
    q0: np.ndarray,
    p1: str,
    p2: str,
    z0: np.ndarray,
) -> tuple[_Curve, dict[str, float], Problem]:
    """The Hopf system as a curve, the parameters at the start and the problem traced."""
    curve = _Curve(problem, mass, q0, p1, p2)
    pars = {k: float(hopf_point.values[k]) for k in problem.params}
    curve.scale0 = _log_scale(curve, z0, pars)
    aug = Problem(
        curve.residual,
        _names(problem, p2),
        {k: v for k, v in pars.items() if k != p2},
        jacobian=curve.jacobian,
        param_jacobian=curve.param_jacobian,
    )
    return curve, pars, aug


def _codim2_events(curve: _Curve) -> list[Event]:
    return [
        Event(curve.l1, label=Kind.BAUTIN),
        Event(curve.omega, label=Kind.BOGDANOV_TAKENS, terminal=True),
        Event(curve.others, label=Kind.ZERO_HOPF),
    ]


def _setup(problem: Any, hp: SpecialPoint, free: tuple[str, str], mass: Any) -> tuple:
    if not (
        isinstance(hp, SpecialPoint) and hp.kind == Kind.HOPF and hp.status == PointStatus.CONVERGED
    ):
        raise ProblemDefinitionError(
            f"hopf_point must be a converged 'hopf' SpecialPoint from trace(..., "
            f"stability=True), got {hp!r}"
        )
    try:
        p1, p2 = free
    except (TypeError, ValueError):
        raise ProblemDefinitionError(f"free must be a pair (p1, p2), got {free!r}") from None
    for name in (p1, p2):
        if name not in problem.params:
            raise ProblemDefinitionError(
                f"{name!r} is not a parameter of the problem; parameters are "
                f"{sorted(problem.params)}"
            )
    if p1 == p2:
        raise ProblemDefinitionError(f"the two free parameters must differ, got {free!r}")
    u = np.array([hp.values[k] for k in problem.unknowns], dtype=float)
    p = {k: float(hp.values[k]) for k in problem.params}
    omega = float(hp.details["omega"])
    q = hp.details.get("eigenvector")
    if q is None:
        _, q = eigenvector_near(as_matrix(problem.jacobian(u, p)), mass, 1j * omega)
    q = np.asarray(q, dtype=complex) / np.linalg.norm(q)
    z0 = np.concatenate([u, q.real, q.imag, [omega, p[p2]]])
    return p1, p2, z0, q


def _names(problem: Any, p2: str) -> list[str]:
    names = list(problem.unknowns)
    names += [f"qr:{k}" for k in problem.unknowns] + [f"qi:{k}" for k in problem.unknowns]
    names += ["omega", p2]
    clash = set(names[len(problem.unknowns) :]) & (set(problem.params) - {p2})
    if clash or "omega" in problem.unknowns:
        raise ProblemDefinitionError(
            f"the Hopf curve's columns {sorted(clash or {'omega'})} clash with the problem's names"
        )
    return names


def _scales(problem: Any, hp: SpecialPoint, names: Sequence[str]) -> dict[str, float]:
    """Typical sizes: the branch's for the unknowns and parameters (a component 0 at the
    Hopf point has no size of its own), ``|ω|``, ``1/√n`` for the eigenvector's parts."""
    given = hp.scales or {}
    n = len(problem.unknowns)
    out = {k: float(given.get(k, max(1.0, abs(hp.values[k])))) for k in problem.unknowns}
    for k in names[n : 3 * n]:
        out[k] = 1.0 / np.sqrt(n)
    out["omega"] = abs(float(hp.details["omega"]))
    for k in problem.params:
        out[k] = float(given.get(k, max(1.0, abs(hp.values[k]))))
    return out


def _log_scale(curve: _Curve, z0: np.ndarray, pars: Mapping[str, float]) -> float:
    """``log|det A / ω²|`` at the start (the zero-Hopf test's unit)."""
    u, _, omega, p = curve.split(z0, pars)
    _, logdet = _slogdet(as_matrix(curve.base.jacobian(u, p)))
    return float(logdet - 2.0 * np.log(abs(omega))) if np.isfinite(logdet) else 0.0


def _relabel(branch: Branch, curve: _Curve, pars: Mapping[str, float]) -> Branch:
    """Events of the codimension-2 tests reported under their own kinds."""
    out = []
    for sp_ in branch.special_points:
        if sp_.kind == Kind.EVENT and sp_.label in CODIM2:
            z = np.array([sp_.values[k] for k in branch.variables[:-1]])
            details = dict(sp_.details, omega=float(sp_.values["omega"]))
            if sp_.label == "bautin":
                details["first_lyapunov"] = curve.l1(z, {**pars, **sp_.values})
            sp_ = replace(sp_, kind=Kind(sp_.label), details=details)
        out.append(sp_)
    # the augmented curve turns back at a Bogdanov–Takens point (ω ↦ −ω): the fold of p1
    # located there with it is that point, not a fold of the Hopf curve
    bts = [q.index for q in out if q.kind == Kind.BOGDANOV_TAKENS]
    out = [q for q in out if not (q.kind == Kind.FOLD and any(abs(q.index - i) <= 1 for i in bts))]
    branch.special_points = out
    branch.kinds = branch.kinds | set(CODIM2)
    return branch


__all__ = ["hopf_curve"]
