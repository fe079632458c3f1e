"""Two-parameter continuation of folds (limit points) and the cusps on them.

The fold curve is traced by the ordinary tracer on the minimally augmented system
(Govaerts 2000; as in MatCont and BifurcationKit)

    G(u, p1, p2) = [F(u, p1, p2); g(u, p1, p2)],   [[M, b], [cᵀ, 0]] [v; g] = [0; 1],

where ``M`` is ``∂F/∂(u, p1)`` without the column of the variable that turns (``p1`` for an
ordinary fold, a monitored unknown for the fold of a snap-back), so the system has ``n + 1``
equations in ``n + 2`` unknowns. The bordering vectors ``b, c`` are replaced by the current
left/right null vectors after every accepted point (a new, immutable :class:`FoldSystem` each
time, carried by the tracer's state). ``∇g = −wᵀ(∂M/∂z)v`` is a directional difference of the
Jacobian.

On the curve:

- **cusp**: the normal-form coefficient ``a = ½⟨w, D²F[v, v]⟩`` changes sign; located by
  Newton on ``[F; g; a] = 0`` (n + 2 equations and unknowns), cross-checked by the parameter
  components of the fold curve's tangent (both vanish at a cusp);
- **second zero eigenvalue** (codimension 2, e.g. a limit point meeting a branch point): the
  determinant of the bordered matrix ``[[M, b], [cᵀ, 0]]`` changes sign (it is
  ``−cᵀ adj(M) b``, proportional to the product of the non-zero eigenvalues of ``M``);
- bounds, targets, events and monitored folds exactly as on ordinary branches.

The fold-curve system brings its own two test functions (:class:`CuspTest`,
:class:`Codim2Test`); the tracer knows nothing of them.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import scipy.sparse as sp

from .branch import Branch, SpecialPoint
from .directions import trace_directions
from .errors import ProblemDefinitionError, SingularMatrixError
from .linalg import (
    bordered,
    bordered_square,
    factor,
    inverse_magnitudes,
    scaled_max,
    unit_last,
)
from .locate import (
    Bracket,
    Located,
    newton_done,
    second_derivative_row,
    tangent_at,
)
from .options import ContinuationOptions
from .problem import as_matrix, as_problem, as_vector, has_exact_jacobian
from .regula import locate_on_arc
from .state import TracerState
from .system import CurveSystem, state_weights
from .testfunctions import TestFunction
from .tracer import Tracer

_EPS = np.finfo(float).eps


class FoldSystem(CurveSystem):
    """``[F; g]`` over ``z = (u, p1, p2)``; ``k`` is the index (in ``(u, p1)``) of the variable
    that turns at the fold; ``b``, ``c`` the bordering vectors (unit vectors of length n).

    Immutable while traced: :meth:`refreshed` returns a new system with the borders updated
    to the null vectors at a point; :meth:`through` builds the first one at a fold."""

    def __init__(
        self,
        problem,
        p1: str,
        p2: str,
        k: int,
        params: Mapping[str, float],
        state_weight: float | None,
        b: np.ndarray,
        c: np.ndarray,
    ) -> None:
        self.problem = problem
        self.p1, self.p2 = p1, p2
        self.params = dict(params)
        self.n = len(problem.unknowns)
        self.k = k
        self.names = tuple(problem.unknowns) + (p1, p2)
        self.dim = self.n + 2
        self.scales = np.ones(self.dim)
        self.base_weights = state_weights(self.n, 2, state_weight)
        self.weights = self.base_weights.copy()
        self.unit_weights = False
        keep = np.ones(self.n + 1, dtype=bool)
        keep[k] = False
        self._keep = keep  # columns of ∂F/∂(u, p1) forming M
        self.b = b
        self.c = c
        self._cache: tuple | None = None  # the last bordered solve (a memo, see below)
        # differences of the Jacobian are reliable only if the Jacobian itself is exact
        self._exact_jacobian = self.derivatives_exact = has_exact_jacobian(problem)

    # -- pieces
    def _p(self, z):
        p = dict(self.params)
        p[self.p1] = z[self.n]
        p[self.p2] = z[self.n + 1]
        return p

    def f(self, z):
        try:
            r = self.problem.residual(z[: self.n], self._p(z))
        except ArithmeticError:  # at a trial point: as non-finite, as for a branch (system.py)
            return np.full(self.n, np.nan)
        if type(r) is not np.ndarray or r.dtype != float:  # (any protocol object's)
            r = as_vector(r, "the residual", lambda: self.values(z))
        return r

    def df(self, z):
        """``∂F/∂(u, p1, p2)``: n × (n + 2), dense or CSR."""
        u, p = z[: self.n], self._p(z)
        at = lambda: self.values(z)  # noqa: E731 (the point, for messages only)
        j = as_matrix(self.problem.jacobian(u, p), "the jacobian", at)
        f1 = as_vector(self.problem.param_jacobian(u, p, self.p1), "the param_jacobian", at)
        f2 = as_vector(self.problem.param_jacobian(u, p, self.p2), "the param_jacobian", at)
        if sp.issparse(j):
            return sp.hstack([j, sp.csr_matrix(np.column_stack([f1, f2]))], format="csr")
        out = np.empty((self.n, self.n + 2))
        out[:, : self.n] = j
        out[:, self.n] = f1
        out[:, self.n + 1] = f2
        return out

    def m_matrix(self, df):
        cols = np.flatnonzero(self._keep)
        if sp.issparse(df):
            return sp.csc_matrix(df)[:, cols]
        return df[:, cols]

    def bordered_solve(self, z, df=None):
        """``g``, right and left null vectors ``v`` (in M's columns), ``w``, the LU and df.

        The last result is cached: the corrector asks for the residual and the Jacobian at
        the same point, and every test function asks again at each accepted point."""
        key = z.tobytes()
        if df is None and self._cache is not None and self._cache[0] == key:
            return self._cache[1]
        out = self._bordered_solve(z, df)
        self._cache = (key, out)
        return out

    def _bordered_solve(self, z, df=None):
        df = self.df(z) if df is None else df
        lu = factor(bordered_square(self.m_matrix(df), self.b, self.c))
        e = unit_last(self.n + 1)
        x = lu.solve(e)
        y = lu.solve(e, trans=True)
        return x[-1], x[:-1], y[:-1], lu, df

    def lift(self, v):
        """A vector over M's columns as a direction in z (zero at k and at p2)."""
        out = np.zeros(self.dim)
        out[: self.n + 1][self._keep] = v
        return out

    @classmethod
    def through(
        cls,
        problem: Any,
        p1: str,
        p2: str,
        k: int,
        params: Mapping[str, float],
        state_weight: float | None,
        z: np.ndarray,
        seed: int = 0,
    ) -> FoldSystem:
        """The system at a fold ``z``: random unit borders, then twice replaced by the null
        vectors they give there."""
        rng = np.random.default_rng(seed)
        b = rng.standard_normal(len(problem.unknowns))
        c = rng.standard_normal(len(problem.unknowns))
        b /= np.linalg.norm(b)
        c /= np.linalg.norm(c)
        system = cls(problem, p1, p2, k, params, state_weight, b, c)
        for _ in range(2):
            system = system.refreshed(z)
        return system

    refreshes = True

    def refreshed(self, z: np.ndarray) -> FoldSystem:
        """The system with the borders replaced by the left and right null vectors at ``z``."""
        _, v, w, _, _ = self.bordered_solve(z)
        new = object.__new__(FoldSystem)
        new.__dict__.update(self.__dict__)
        new.b, new.c = w / np.linalg.norm(w), v / np.linalg.norm(v)
        new._cache = None
        return new

    def own_tests(self, options: ContinuationOptions) -> tuple[TestFunction, ...]:
        return (CuspTest(), Codim2Test())

    # -- CurveSystem interface
    def residual(self, z):
        g, *_ = self.bordered_solve(z)
        out = np.empty(self.n + 1)
        out[: self.n] = self.f(z)
        out[self.n] = g
        return out

    def jacobian(self, z):
        g, v, w, _, df = self.bordered_solve(z)
        vt = self.lift(v)
        grad = -second_derivative_row(self.df, z, vt, w, None, self.scales)
        if sp.issparse(df):
            return sp.vstack([df, sp.csr_matrix(grad[None, :])], format="csr")
        out = np.empty((self.n + 1, self.dim))
        out[: self.n] = df
        out[self.n] = grad
        return out

    def bordered_jacobian(self, z, row):
        return bordered(self.jacobian(z), row)

    def residual_floor(self, dg, z, magnitudes=None) -> float:
        """With a differenced Jacobian, ``g`` carries the differences' error: about
        ε^{2/3} (central) or ε^{1/2} (forward) of the Jacobian's size, times |v|·|w|."""
        floor = super().residual_floor(dg, z, magnitudes)
        if self._exact_jacobian:
            return floor
        # an entry of ∂F/∂z_j differenced with a step rel·m_j (m_j = max(s_j, |z_j|)) is off
        # by about rel·T_i/m_j, T_i = Σ_k |∂F_i/∂z_k|·m_k the size of the terms of F_i; so
        # g = w·M·v is off by rel·(Σ_i |w_i| T_i)·(Σ_j |v_j|/m_j)
        _, v, w, _, df = self.bordered_solve(z)
        mags = np.maximum(self.scales, np.abs(z))
        terms = abs(df) @ mags
        noise = float(np.abs(w) @ terms) * float(np.abs(self.lift(v)) @ (1.0 / mags))
        rel = _EPS ** (0.5 if getattr(self.problem, "derivatives", "") == "forward" else 2.0 / 3.0)
        return max(floor, 10.0 * rel * noise)

    def _scaled_problem(self) -> None:
        with_typical = getattr(self.problem, "with_typical_sizes", None)
        if with_typical is not None:
            n, s = self.n, self.scales
            typical_p = {self.p1: float(s[n]), self.p2: float(s[n + 1])}
            self.problem = with_typical(s[:n], typical_p)
        self._cache = None

    def fixed_values(self):
        return {k: v for k, v in self.params.items() if k not in (self.p1, self.p2)}

    def values(self, z):
        out = dict(zip(self.problem.unknowns, map(float, z[: self.n])))
        out.update(self.params)
        out[self.p1] = float(z[self.n])
        out[self.p2] = float(z[self.n + 1])
        return out

    # -- tests on the fold curve
    def cusp_coefficient(self, z) -> float:
        """``½⟨w, D²F[v, v]⟩`` with the null vectors normalised by the current borders.

        With an analytic (or complex-step) Jacobian: a five-point central difference of
        ``∂F/∂z·v`` along ``v``. With a finite-difference Jacobian that would difference differences
        (noise ~1e-7 relative); the five-point second difference of ``w·F`` along ``v`` with
        step ε^{1/6} is used instead (noise ~1e-10 relative, set by the null vectors).
        """
        _, v, w, _, _ = self.bordered_solve(z)
        vt = self.lift(v)
        if self._exact_jacobian:
            row = second_derivative_row(self.df, z, vt, w, None, self.scales, accurate=True)
            return 0.5 * float(row @ vt)
        # the five-point second difference (truncation O(h⁴)) with a step of ε^{1/6}
        # relative to the components' magnitudes: rounding ε/h² and truncation h⁴ balance
        # at ~ε^{2/3} ≈ 4e-11 relative, where the three-point one (step ε^{1/4}) is ~1e-8
        h = _EPS ** (1.0 / 6.0) / scaled_max(vt, inverse_magnitudes(self.scales, z))
        f = self.f
        wf = [float(w @ f(z + (j * h) * vt)) for j in (-2, -1, 0, 1, 2)]
        second = (-wf[0] + 16.0 * wf[1] - 30.0 * wf[2] + 16.0 * wf[3] - wf[4]) / (12.0 * h * h)
        return 0.5 * second

    def double_zero_test(self, z) -> tuple[float, float]:
        """Sign and log|det| of ``[[M, b], [cᵀ, 0]]``."""
        _, _, _, lu, _ = self.bordered_solve(z)
        return lu.sign_det(), lu.log_abs_det()


class CuspTest(TestFunction):
    """The cusp coefficient ``a = ½⟨w, D²F[v, v]⟩`` of the fold: it changes sign at a cusp
    (located by Newton on ``[F; g; a] = 0``)."""

    __slots__ = ()
    kind = "cusp"

    def __init__(self) -> None:
        super().__init__("cusp")

    def value(self, system, z, t, sdet) -> float:
        return system.cusp_coefficient(z)

    def locate(self, br: Bracket, f_a: float, f_b: float) -> Located:
        return _locate_cusp(br.system, br, f_a, f_b)


class Codim2Test(TestFunction):
    """The sign of det ``[[M, b], [cᵀ, 0]]``: it changes where ``M`` has a second zero
    eigenvalue (a limit point meeting a branch point, a Bogdanov–Takens point)."""

    __slots__ = ()
    kind = "codim2"

    def __init__(self) -> None:
        super().__init__("second zero eigenvalue")

    def value(self, system, z, t, sdet) -> float:
        return system.double_zero_test(z)[0]

    def locate(self, br: Bracket, f_a: float, f_b: float) -> Located:
        return _locate_codim2(br.system, br, f_a, f_b)


def _locate_cusp(system: FoldSystem, br: Bracket, f_a: float, f_b: float) -> Located:
    """Newton on ``[F; g; a] = 0`` from the regula-falsi estimate; Illinois if it fails."""
    o = br.options
    theta = f_a / (f_a - f_b) if f_a != f_b else 0.5
    start = br.point_at(theta * br.h)
    z = start.z if start.converged else br.guess(theta)
    dim = system.dim
    converged = False
    it = 0
    previous = np.inf
    size = np.inf
    while it < o.max_locate_iterations:
        it += 1
        if dim > 200:
            break  # a dense gradient of the coefficient is too costly: Illinois below
        G = system.residual(z)
        a = system.cusp_coefficient(z)
        jac = system.jacobian(z)
        jac = jac.toarray() if sp.issparse(jac) else jac
        grad = np.empty(dim)
        for i in range(dim):
            h = _EPS ** (1.0 / 3.0) * max(system.scales[i], abs(z[i]))
            e = np.zeros(dim)
            e[i] = h
            grad[i] = (system.cusp_coefficient(z + e) - system.cusp_coefficient(z - e)) / (2 * h)
        big = np.vstack([jac, grad[None, :]])
        rhs = -np.concatenate([G, [a]])
        try:
            dz = factor(big).solve(rhs)
        except SingularMatrixError:
            break
        z = z + dz
        if not np.all(np.isfinite(z)):
            break
        size = scaled_max(dz, inverse_magnitudes(system.scales, z))
        # the gradient of the coefficient is a finite difference: Newton converges linearly
        # and, with finite-difference Jacobians, stalls at the noise floor of the coefficient
        if newton_done(it, size, previous, o.locate_tol, stall=1e-9):
            converged = True
            break
        previous = size
    if converged:
        found = Located(
            z, br.sigma(z), "converged", it, {"method": "Newton on [F; g; a]", "last_update": size}
        )
    else:
        found = locate_on_arc(br, system.cusp_coefficient, f_a, f_b)
        found = found._replace(
            details={**found.details, "method": "Illinois on the cusp coefficient"}
        )
    tan = tangent_at(system, found.z, br.row, system.weights, br)
    details = dict(found.details)
    details.update(
        coefficient_before=float(f_a),
        coefficient_after=float(f_b),
        # the unfolding parameters of the cusp: the variable that turns and p2 (both
        # components of the fold curve's tangent vanish there)
        tangent_parameters={
            system.names[system.k]: float(tan[system.k]),
            system.p2: float(tan[-1]),
        },
        fold_branches=(system.values(br.z_a), system.values(br.z_b)),
        residual=float(np.max(np.abs(system.residual(found.z)))),
    )
    return found._replace(details=details)


def _locate_codim2(system: FoldSystem, br: Bracket, f_a: float, f_b: float) -> Located:
    ref = system.double_zero_test(br.z_a)

    def f(z):
        try:
            sgn, logdet = system.double_zero_test(z)
        except SingularMatrixError:
            return 0.0
        return sgn * np.exp(min(logdet - ref[1], 700.0))

    fb = f(br.z_b)
    found = locate_on_arc(br, f, ref[0], fb if fb * ref[0] < 0 else -ref[0])
    details = {
        **found.details,
        "type": "second zero eigenvalue of the fold's matrix",
        "method": "Illinois on det[[M, b], [c^T, 0]]",
    }
    return found._replace(details=details)


def fold_curve(
    problem,
    fold_point: SpecialPoint,
    *,
    free: tuple[str, str],
    direction: str | int = "both",
    bounds: Mapping[str, tuple[float, float]] | None = None,
    targets: Mapping[str, Sequence[float]] | None = None,
    events: Sequence = (),
    monitor: Sequence[str] = (),
    scales: Mapping[str, float] | None = None,
    options: ContinuationOptions | None = None,
    throw: bool = True,
    **overrides: Any,
) -> Branch:
    """Continue a fold in two parameters.

    Parameters
    ----------
    problem:
        the problem the fold was found on.
    fold_point:
        a :class:`SpecialPoint` of kind ``"fold"`` returned by :func:`trace` (a fold in the
        free parameter, or in a monitored unknown: the fold curve of a snap-back).
    free:
        ``(p1, p2)``: the branch's free parameter and the second parameter.

    Other parameters
    ----------------
    direction:
        ``"both"`` (default: the two halves joined at the starting fold), ``+1`` or ``-1``
        (the sign of the initial change of ``p2``).
    bounds, targets, events, monitor, scales, options, throw:
        as for :func:`trace`; they apply to the fold curve (bounds may name any unknown or
        either parameter). An unknown whose value at the fold is far below its typical size
        on the branch (0, or 0 up to rounding) takes that size unless ``scales`` gives one.

    The result is a :class:`Branch` whose special points include ``"cusp"`` (details: the
    coefficient on each side, the tangent's parameter components, the fold branches that
    meet) and ``"codim2"`` (a second zero eigenvalue). ``info["direction"]`` says which way(s)
    were traced and ``info["start_index"]`` where the starting fold is.
    """
    problem = as_problem(problem)
    p1, p2, k, params = _fold_setup(problem, fold_point, free)
    options = options or ContinuationOptions(detect_branch_points=False)
    if overrides:
        options = options.replace(**overrides)
    if direction not in ("both", 1, -1):
        raise ProblemDefinitionError(f"direction must be 'both', +1 or -1, got {direction!r}")

    z0 = np.array(
        [fold_point.values[nm] for nm in problem.unknowns]
        + [fold_point.values[p1], fold_point.values[p2]],
        dtype=float,
    )
    system = FoldSystem.through(problem, p1, p2, k, params, options.state_weight, z0)

    def begin(d: int) -> tuple[Tracer, TracerState]:
        tracer = Tracer.for_system(
            system,
            options=options,
            bounds=bounds,
            targets=targets,
            events=events,
            monitor=monitor,
            scales=scales,
            direction=d,
            throw=throw,
        )
        return tracer, tracer.init_at(z0, start_label="start (fold)", sizes=fold_point.scales)

    return trace_directions(begin, direction, start_kind="fold", start_label="start (fold)")


def _fold_setup(
    problem: Any, fold_point: SpecialPoint, free: tuple[str, str]
) -> tuple[str, str, int, dict[str, float]]:
    """Check the arguments of :func:`fold_curve`: the two parameters, the index of the
    variable that turns, and the parameter values at the fold."""
    if not isinstance(fold_point, SpecialPoint) or fold_point.kind != "fold":
        raise ProblemDefinitionError(
            f"fold_point must be a SpecialPoint of kind 'fold' returned by trace, "
            f"got {fold_point!r}"
        )
    try:
        p1, p2 = free
    except (TypeError, ValueError):
        raise ProblemDefinitionError(
            f"free must be a pair (branch parameter, second parameter), got {free!r}"
        ) from None
    params = dict(problem.params)
    for name in (p1, p2):
        if name not in params:
            raise ProblemDefinitionError(
                f"{name!r} is not a parameter of the problem; parameters are {sorted(params)}"
            )
    if p1 == p2:
        raise ProblemDefinitionError(f"the two free parameters must differ, got {free!r}")
    for key in params:
        if key in fold_point.values:
            params[key] = float(fold_point.values[key])
    wrt = fold_point.with_respect_to or p1
    names_y = list(problem.unknowns) + [p1]
    if wrt not in names_y:
        raise ProblemDefinitionError(
            f"the fold is a turning point of {wrt!r}, which is neither an unknown nor {p1!r}: "
            f"was it traced with free={wrt!r}? Pass free=({wrt!r}, second parameter)"
        )
    return p1, p2, names_y.index(wrt), params


__all__ = ["Codim2Test", "CuspTest", "FoldSystem", "fold_curve"]
