"""Pseudo-arclength continuation: the step-level API (:class:`Tracer`) and :func:`trace`.

A step: tangent (or secant) predictor, Newton corrector on the bordered system, acceptance
tests (Newton convergence, tangent turn ≤ ``max_angle``, correction ≤ ds), step-size update
from the Newton iteration count and the tangent turn, then the test functions of the special
points: a sign change between the two ends of the step is located and inserted.

The solver state is an immutable record replaced at every step; the branch so far is a
linked list of points, so a step costs O(1) regardless of the branch length.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Mapping, Sequence
from typing import Any, NamedTuple

import numpy as np

from .branch import Branch, SpecialPoint
from .corrector import damped_newton, newton
from .errors import (
    ConvergenceError,
    NonFiniteResidualError,
    ProblemDefinitionError,
    SingularMatrixError,
)
from .events import Event
from .linalg import bordered, factor, max_abs, unit_last
from .locate import (
    Bracket,
    Located,
    branch_point_directions,
    locate_component,
    locate_fold,
    locate_on_arc,
    oriented_tangent,
    tangent_at,
)
from .options import ContinuationOptions
from .problem import as_problem
from .system import BranchSystem, has_exact_jacobian

logger = logging.getLogger(__name__)

_STALL_STEPS = 10  # steps at ds < _STALL_FACTOR·ds_min before a corner step is tried
_STALL_FACTOR = 1e3

_DEFAULT_OPTIONS = ContinuationOptions()  # frozen: shared (validation costs 20 µs a call)

_REMEDY = (
    "Try a smaller ds_min or ds_max, a better starting point, an analytic jacobian, or "
    "check the residual for discontinuities; pass throw=False to keep the partial branch."
)


class _Point:
    """One row of the branch (linked to the previous row)."""

    __slots__ = ("z", "t", "s", "newton", "rejected", "residual", "ds", "special", "prev")

    def __init__(self, z, t, s, newton, rejected, residual, ds, special, prev):
        self.z, self.t, self.s = z, t, s
        self.newton, self.rejected, self.residual, self.ds = newton, rejected, residual, ds
        self.special = special  # tuple of (kind, label, wrt, status, interval, details)
        self.prev = prev


class TracerState(NamedTuple):
    """Immutable solver state: the last point (with the branch behind it), the next step
    size, the test-function values at the last point, the step count and, once finished,
    the status and message."""

    last: _Point
    ds: float
    tests: tuple
    steps: int
    status: str | None = None
    message: str = ""
    n_points: int = 1
    stalled: int = 0  # consecutive steps taken with ds near ds_min


# --- --- test functions


class _Test:
    """A test function of the branch: its value at each point, the sign changes that count,
    and how a zero is located."""

    __slots__ = ("kind", "label", "wrt", "k", "value_at", "direction", "terminal", "event")

    def __init__(
        self,
        kind: str,
        label: str = "",
        wrt: str | None = None,
        k: int = -1,
        value_at: float = 0.0,
        direction: int = 0,
        terminal: bool = False,
        event: Event | None = None,
    ) -> None:
        self.kind, self.label, self.wrt, self.k = kind, label, wrt, k  # k: component index
        self.value_at = value_at  # target / bound value
        self.direction, self.terminal, self.event = direction, terminal, event

    def value(self, tracer: Tracer, z, t, sdet) -> float:
        kind = self.kind
        if kind == "fold":
            return float(t[self.k])
        if kind == "bound" or kind == "target":
            return float(z[self.k]) - self.value_at
        if kind == "branch_point":
            return sdet
        if kind == "cusp":
            return tracer.system.cusp_coefficient(z)
        if kind == "codim2":
            return tracer.system.double_zero_test(z)[0]
        u, p = tracer.split(z)
        val = float(self.event.function(u, p))
        if not math.isfinite(val):
            raise NonFiniteResidualError(
                f"event {self.label!r} returned {val} at {tracer.system.values(z)}",
                values=tracer.system.values(z),
            )
        return val

    def crossed(self, old: float | None, new: float) -> bool:
        if old is None:
            return False
        if old == 0.0:
            # starting exactly on a bound: leaving through it ends the branch at once
            if self.kind == "bound":
                return new < 0 if self.direction < 0 else new > 0
            return False
        if new == 0.0:
            up = old < 0
        elif (old < 0) == (new < 0):
            return False
        else:
            up = new > 0
        if self.direction == 0:
            return True
        return (self.direction > 0) == up

    def locate(self, tracer: Tracer, br: Bracket, f_a: float, f_b: float) -> Located:
        if self.kind == "fold":
            return tracer.check_fold_resolution(self._locate_fold(tracer, br, f_a, f_b), br)
        return self._locate_other(tracer, br, f_a, f_b)

    def _locate_fold(self, tracer: Tracer, br: Bracket, f_a: float, f_b: float) -> Located:
        found = locate_fold(br, self.k)
        if found is not None:
            return found

        def tangent_k(z):
            return tracer.tangent_through(z, br)[self.k]

        # a poor start (a long step, or two folds close together): bracket the fold
        # coarsely by regula falsi and restart Newton from there
        rough = locate_on_arc(br, tangent_k, f_a, f_b, rtol=1e-3)
        found = locate_fold(br, self.k, start=rough.z, tangent=tracer.tangent_through(rough.z, br))
        if found is not None:
            found.details["method"] = "minimally augmented Newton (after regula falsi)"
            return found
        # Newton failed: regula falsi on the tangent component. The fold system has no
        # regular solution here (a kink, or derivatives too rough to locate it): the point
        # is a bracketed estimate only
        found = locate_on_arc(br, tangent_k, f_a, f_b)
        found.details["method"] = "Illinois on the tangent component (Newton failed)"
        found.status = "guess"
        ends = found.details.get("test_values", (0.0, 0.0))
        if min(abs(ends[0]), abs(ends[1])) > 1e-6:
            # the tangent component jumps instead of passing through zero
            found.details["non_smooth"] = True
        return found

    def _locate_other(self, tracer: Tracer, br: Bracket, f_a: float, f_b: float) -> Located:
        if self.kind in ("target", "bound"):
            found = locate_component(br, self.k, self.value_at)
            if found is not None:
                return found
            return locate_on_arc(br, lambda z: z[self.k] - self.value_at, f_a, f_b)
        if self.kind in ("cusp", "codim2"):
            from .foldcurve import _locate_codim2, _locate_cusp

            locate = _locate_cusp if self.kind == "cusp" else _locate_codim2
            return locate(tracer.system, br, f_a, f_b)
        if self.kind == "branch_point":
            ref = tracer.bordered_det(br.z_a, br.row)

            def f(z):
                try:
                    sgn, logdet = tracer.bordered_det(z, br.row)
                except SingularMatrixError:  # landed exactly on the branch point
                    return 0.0
                return sgn * math.exp(min(logdet - ref[1], 700.0))

            fa = ref[0]
            sb, lb = tracer.bordered_det(br.z_b, br.row)
            fb = sb * math.exp(min(lb - ref[1], 700.0))
            if fa * fb > 0:  # the sign change was seen with a different border: bisect on it
                fb = -fa
            return locate_on_arc(br, f, fa, fb)

        def fe(z):
            return self.value(tracer, z, None, None)

        return locate_on_arc(br, fe, f_a, f_b)


# --- --- the tracer


class Tracer:
    """Step-level continuation of one branch.

    >>> tracer = Tracer(problem, free="b", bounds={"b": (-1, 1)})   # doctest: +SKIP
    >>> state = tracer.init([-1.3247])
    >>> while not tracer.done(state):
    ...     state = tracer.step(state)
    >>> branch = tracer.result(state)

    The arguments are those of :func:`trace`. The tracer holds only configuration; all that
    changes lives in the :class:`TracerState` records.
    """

    def __init__(
        self,
        problem,
        *,
        free: str,
        params: Mapping[str, float] | None = None,
        bounds: Mapping[str, tuple[float, float]] | None = None,
        targets: Mapping[str, Sequence[float]] | None = None,
        events: Sequence[Event] = (),
        monitor: Sequence[str] = (),
        direction: int = 1,
        options: ContinuationOptions | None = None,
        throw: bool = True,
        **overrides: Any,
    ) -> None:
        problem = as_problem(problem)
        if not isinstance(free, str):
            raise ProblemDefinitionError(f"free must be a parameter name, got {free!r}")
        options = options or _DEFAULT_OPTIONS
        if overrides:
            options = options.replace(**overrides)
        system = BranchSystem(problem, free, params, options.state_weight)
        self._configure(
            system,
            options,
            bounds=bounds,
            targets=targets,
            events=events,
            monitor=monitor,
            direction=direction,
            throw=throw,
            fold_components=(free,),
        )
        self.problem = problem

    @classmethod
    def for_system(
        cls, system, *, options: ContinuationOptions, fold_components=(), **kwargs
    ) -> Tracer:
        """A tracer for any curve system (used by augmented systems such as fold curves)."""
        self = object.__new__(cls)
        self.problem = getattr(system, "problem", None)
        self._configure(system, options, fold_components=fold_components, **kwargs)
        return self

    def _configure(
        self,
        system,
        options,
        *,
        bounds=None,
        targets=None,
        events=(),
        monitor=(),
        direction=1,
        throw=True,
        fold_components=(),
        extra_tests=(),
    ) -> None:
        self.system = system
        self.options = options
        self.throw = bool(throw)
        if direction not in (1, -1):
            raise ProblemDefinitionError(f"direction must be +1 or -1, got {direction!r}")
        self.direction = direction
        self.weights = system.weights
        tests: list[_Test] = []
        if options.detect_folds:
            for name in fold_components:
                tests.append(
                    _Test(
                        "fold",
                        label=f"fold in {name}",
                        wrt=name,
                        k=self._component(name, "free parameter"),
                    )
                )
        for name in monitor or ():
            k = self._component(name, "monitor")
            if name not in fold_components:
                tests.append(_Test("fold", label=f"fold in {name}", wrt=name, k=k))
        if options.detect_branch_points:
            tests.append(_Test("branch_point", label="branch point"))
        for name, values in (targets or {}).items():
            k = self._component(name, "targets")
            for v in np.atleast_1d(np.asarray(values, dtype=float)):
                if not math.isfinite(v):
                    raise ProblemDefinitionError(f"targets[{name!r}] must be finite, got {v}")
                tests.append(
                    _Test("target", label=f"{name}={v:g}", wrt=name, k=k, value_at=float(v))
                )
        self.bounds = {}
        for name, pair in (bounds or {}).items():
            k = self._component(name, "bounds")
            try:
                lo, hi = (float(x) for x in pair)
            except (TypeError, ValueError):
                raise ProblemDefinitionError(
                    f"bounds[{name!r}] must be a pair (low, high), got {pair!r}"
                ) from None
            if not lo < hi or math.isnan(lo) or math.isnan(hi):
                raise ProblemDefinitionError(
                    f"bounds[{name!r}] must satisfy low < high, got ({lo}, {hi})"
                )
            self.bounds[name] = (lo, hi)
            if math.isfinite(lo):
                tests.append(
                    _Test(
                        "bound",
                        label=f"bound {name}={lo:g}",
                        wrt=name,
                        k=k,
                        value_at=lo,
                        direction=-1,
                        terminal=True,
                    )
                )
            if math.isfinite(hi):
                tests.append(
                    _Test(
                        "bound",
                        label=f"bound {name}={hi:g}",
                        wrt=name,
                        k=k,
                        value_at=hi,
                        direction=+1,
                        terminal=True,
                    )
                )
        for ev in events or ():
            if not isinstance(ev, Event):
                raise ProblemDefinitionError(f"events must be Event objects, got {ev!r}")
            tests.append(
                _Test(
                    "event", label=ev.label, direction=ev.direction, terminal=ev.terminal, event=ev
                )
            )
        tests.extend(extra_tests)
        self.tests = tuple(tests)
        self._has_bp = any(t.kind == "branch_point" for t in tests)
        self._e_last = unit_last(system.dim)
        self._unit_weights = bool((self.weights == 1.0).all())
        # (index, test, the most its component can move per unit of step: 1/√w_k, as the
        # tangent is a unit vector in the weighted norm)
        self._bound_tests = tuple(
            (i, t, 1.0 / math.sqrt(self.weights[t.k]))
            for i, t in enumerate(tests)
            if t.kind == "bound"
        )

    def _component(self, name: str, what: str) -> int:
        k = self.system.index(name)
        if k is None:
            raise ProblemDefinitionError(
                f"{what} names {name!r}, which is not traced on this curve; it must be one of "
                f"{list(self.system.names)} (fixed parameters cannot be bounded or monitored)"
            )
        return k

    # ------------------------------------------------------------------ helpers

    def split(self, z):
        vals = self.system.values(z)
        u = np.array([vals[name] for name in self.problem.unknowns]) if self.problem else z
        return u, vals

    def wnorm(self, x) -> float:
        return math.sqrt(x.dot(self.weights * x))

    def bordered_det(self, z, row):
        lu = factor(bordered(self.system.jacobian(z), row))
        return lu.sign_det(), lu.log_abs_det()

    def tangent_through(self, z, br: Bracket):
        return tangent_at(self.system, z, br.row, self.weights)

    def _fail(self, state: TracerState, status: str, message: str, exc: Exception):
        if self.throw:
            raise exc
        logger.warning("continuation stopped: %s", message)
        return state._replace(status=status, message=message)

    # ------------------------------------------------------------------ init / step / done

    def init(self, u0, *, tangent=None) -> TracerState:
        """Correct the starting point and compute the first tangent.

        ``u0``: initial guess of the unknowns (at the problem's parameter values), or a
        :class:`SpecialPoint` (a ``"branch_point"`` starts on the other branch).
        """
        system = self.system
        start_label = "start"
        skip_bp = False
        if isinstance(u0, SpecialPoint):
            z0 = np.array([u0.values[name] for name in system.names], dtype=float)
            if hasattr(system, "params"):
                for key in system.params:
                    if key in u0.values and key not in system.names:
                        system.params[key] = u0.values[key]
            if u0.kind == "branch_point" and tangent is None:
                if "other_tangent" not in u0.details:
                    raise ProblemDefinitionError("this branch point carries no switching data")
                other = np.array(u0.details["other_tangent"], dtype=float)
                names = u0.details.get("names", system.names)
                if tuple(names) != tuple(system.names):
                    raise ProblemDefinitionError(
                        f"branch switching needs the same free parameter as the branch the "
                        f"branch point came from ({names[-1]!r})"
                    )
                k = int(np.argmax(np.abs(other)))
                tangent = other * (np.sign(other[k]) * self.direction)
                start_label = "start (branch switch)"
                skip_bp = True
            elif u0.kind == "fold":
                skip_bp = True
        else:
            u = np.array(u0, dtype=float, ndmin=1)
            n = len(self.problem.unknowns) if self.problem is not None else system.dim - 1
            if u.shape != (n,):
                raise ProblemDefinitionError(
                    f"u0 must hold {n} values (one per unknown {list(system.names[:n])}), "
                    f"got shape {u.shape}"
                )
            if not math.isfinite(max_abs(u)):
                raise ProblemDefinitionError(f"u0 must be finite, got {u}")
            z0 = np.concatenate([u, [system.params[system.free]]])
        return self._start(z0, tangent, start_label, skip_bp)

    def _start(self, z0, tangent, start_label, skip_bp) -> TracerState:
        o = self.options
        system = self.system
        k_free = system.dim - 1
        row = self._e_last  # the free parameter (the last component) held at its value
        g0 = system.residual(z0)
        if not math.isfinite(max_abs(g0)):
            raise NonFiniteResidualError(
                f"the residual is not finite at the starting point {system.values(z0)}",
                values=system.values(z0),
            )
        if tangent is None:
            res = newton(
                system,
                z0,
                row,
                z0[k_free],
                tol=o.tol,
                step_tol=o.step_tol,
                max_iter=4 * o.max_newton_iterations,
                g0=g0,
            )
            if not res.converged:
                raise ConvergenceError(
                    "the starting point did not converge",
                    values=system.values(z0),
                    ds=0.0,
                    iterations=res.iterations,
                    residual_norm=res.residual_norm,
                    remedy="Give a better initial guess u0 for these parameter values.",
                )
            z0 = res.z
            t0, sdet = self._initial_tangent(z0, k_free, res.lu)
            residual = res.residual_norm
            iters = res.iterations
        else:
            t0 = np.asarray(tangent, dtype=float)
            t0 = t0 / self.wnorm(t0)
            residual = float(np.max(np.abs(g0)))
            iters = 0
            sdet = None
        self.system.refresh(z0)
        if skip_bp:
            sdet = None
        elif sdet is None:
            sdet = self._sdet(z0, t0)
        # starting on a special point, the test functions vanish there up to rounding: their
        # signs are taken after the first step instead
        tests = tuple(
            None
            if (skip_bp and t.kind in ("branch_point", "fold"))
            else t.value(self, z0, t0, sdet)
            for t in self.tests
        )
        first = _Point(
            z0,
            t0,
            0.0,
            iters,
            0,
            residual,
            o.ds,
            (("endpoint", start_label, None, "converged", None, {}),),
            None,
        )
        self._check_start_in_bounds(z0)
        return TracerState(first, o.ds, tests, 0)

    def init_at(self, z0, *, start_label: str = "start") -> TracerState:
        """Start from a full curve vector ``z0`` (corrected with its last component fixed)."""
        z0 = np.asarray(z0, dtype=float)
        if z0.shape != (self.system.dim,):
            raise ProblemDefinitionError(
                f"z0 must hold {self.system.dim} values {list(self.system.names)}, "
                f"got shape {z0.shape}"
            )
        return self._start(z0, None, start_label, False)

    def _check_start_in_bounds(self, z0) -> None:
        for name, (lo, hi) in self.bounds.items():
            v = z0[self.system.index(name)]
            if not lo <= v <= hi:
                raise ProblemDefinitionError(
                    f"the starting point has {name}={v:.10g}, outside bounds[{name!r}] = "
                    f"({lo:g}, {hi:g})"
                )

    def _initial_tangent(self, z0, k_free, lu=None):
        """Unit tangent at ``z0`` (the free parameter moving in ``direction``) and the sign of
        det [∂G/∂z; (W t)ᵀ] (None if it was not available from the factorization).

        ``lu``: a factorization of [∂G/∂z; e_kᵀ] at (or, from the corrector, one update
        from) ``z0``, if there is one."""
        system = self.system
        e = self._e_last
        sdet = None
        try:
            if lu is None:
                row = np.zeros(system.dim)
                row[k_free] = 1.0
                lu = factor(bordered(system.jacobian(z0), row))
            t = lu.solve(e)
            if not math.isfinite(max_abs(t)):
                raise SingularMatrixError("the bordered Jacobian is singular at the start")
        except Exception:  # starting at a fold in the free parameter: use the kernel
            dg = system.jacobian(z0)
            dense = dg.toarray() if hasattr(dg, "toarray") else np.asarray(dg)
            t = np.linalg.svd(dense)[2][-1]
            k_free = int(np.argmax(np.abs(t)))
        else:
            # t solves [∂G/∂z; e_kᵀ] t = e_last, so (determinant lemma) det [∂G/∂z; (W t')ᵀ]
            # = det [∂G/∂z; e_kᵀ]·(W t')·t, which for t' = ±t/|t|_W has the sign ±
            sdet = lu.sign_det()
        t = t / self.wnorm(t)
        if t[k_free] * self.direction < 0:
            t = -t
            if sdet is not None:
                sdet = -sdet
        return t, sdet

    def check_fold_resolution(self, found: Located, br: Bracket) -> Located:
        """With finite-difference derivatives, a fold whose radius of curvature is within
        100 difference steps cannot be told from a kink smoothed by the stencil: it is then
        reported as a bracketed guess."""
        problem = self.problem
        if problem is None or has_exact_jacobian(problem):
            return found
        method = getattr(problem, "derivatives", "central")
        rel = np.finfo(float).eps ** (1 / 3 if method == "central" else 1 / 2)
        h_fd = rel * (1.0 + float(np.max(np.abs(found.z))))
        cos = float(br.t_a @ (self.weights * br.t_b))
        turn = math.acos(max(-1.0, min(1.0, cos)))
        if turn > 0 and abs(br.h) / turn < 100 * h_fd:
            found.status = "guess"
            found.details["non_smooth"] = True
            found.details["reason"] = (
                f"radius of curvature {abs(br.h) / turn:.2g} is within 100 finite-difference "
                f"steps ({h_fd:.2g}): possibly a kink; supply a jacobian to decide"
            )
        return found

    def _corner_step(self, z, t, ds_hint, z_prev=None):
        """Fallback at a corner of the curve (a non-smooth turning point, where the tangent
        turns by more than 90° so no pseudo-arclength hyperplane meets the curve beyond):
        natural-parameter steps in one component at a time, largest tangent components
        first, each moving the way it was moving. Returns (result, tangent, row, angle)."""
        o = self.options
        system = self.system
        W = self.weights
        # the variable that turns at a corner is the one with the large tangent component
        # before it: the smaller components are tried first (the "control component", as in
        # contique); the approach to a corner halves ds at every step, so the trial sizes
        # start higher, and at each size every component is tried
        incoming = None
        if z_prev is not None and self.wnorm(z - z_prev) > 0:
            incoming = (z - z_prev) / self.wnorm(z - z_prev)
        mags = np.abs(t) * np.sqrt(W)
        order = [j for j in np.argsort(mags) if mags[j] > 1e-6 * mags.max()][:4]
        h0 = max(ds_hint, 1e-4 * o.ds_max)
        sizes = [h for h in (h0 * 0.25**k for k in range(12)) if h >= 10 * o.ds_min]
        for h in sizes:
            for j in order:
                sign = 1.0 if t[j] > 0 else -1.0
                row = np.zeros(system.dim)
                row[j] = 1.0
                target = z[j] + sign * h / math.sqrt(W[j])
                z0 = z.copy()
                z0[j] = target
                res = newton(
                    system,
                    z0,
                    row,
                    target,
                    tol=o.tol,
                    step_tol=o.step_tol,
                    max_iter=2 * o.max_newton_iterations,
                )
                # the other components move by (slope)·h: a looser guard than for
                # arclength steps, still against jumping to a distant branch
                if not res.converged or self.wnorm(res.z - z) > 20.0 * h:
                    continue
                if incoming is not None:  # never back along the way we came
                    chord = res.z - z
                    along = float(chord @ (W * incoming))
                    if along < 0 and self.wnorm(chord - along * incoming) < 0.1 * self.wnorm(chord):
                        continue
                # oriented by the stepped component (the chord through the corner is not
                # aligned with the tangent beyond it)
                t_new = res.lu.solve(self._e_last)
                if t_new[j] == 0.0:
                    continue
                t_new *= sign / t_new[j]
                t_new /= self.wnorm(t_new)
                cos = float(t_new @ (W * t))
                angle = math.degrees(math.acos(max(-1.0, min(1.0, cos))))
                logger.info("corner passed by a natural-parameter step in %s", system.names[j])
                return res, t_new, W * t_new, angle
        return None

    def _aim_at_bound(self, state: TracerState, z, t, ds):
        """A step that would cross a bound ends on it instead: from the tangent predictor's
        crossing of the bound, Newton with that component fixed (one solve, where a step past
        the bound and locating it would take two). Used only where the bound is transversal
        with margin — the tangent within 90° − ``max_angle`` of the bound's normal (in the
        weighted metric), so that the curve, turning by at most ``max_angle``, still crosses
        it — and accepted under the same guards as any step; otherwise None (a normal step).

        Returns ``(result, tangent, angle, h, rt, test)``: ``h`` the pseudo-arclength of the
        end point along ``t``, ``rt`` the sign of the factor by which det [∂G/∂z; (W t)ᵀ]
        differs from that of the corrector's factorization."""
        o = self.options
        W = self.weights
        for i, tt, reach in self._bound_tests:
            old = state.tests[i]
            if old is None or old == 0.0 or abs(old) > ds * reach:  # not within reach
                continue
            k = tt.k
            tk = float(t[k])
            if tk == 0.0:
                continue
            sigma = -old / tk  # where the tangent line meets the bound
            if not 0.0 < sigma <= ds or not tt.crossed(old, old + ds * tk):
                continue
            if math.sqrt(W[k]) * abs(tk) < math.sin(math.radians(o.max_angle)):
                return None  # grazing: a normal step, then locating
            z_pred = z + sigma * t
            z_pred[k] = tt.value_at
            row = np.zeros(z.size)
            row[k] = 1.0
            res = newton(
                self.system,
                z_pred,
                row,
                tt.value_at,
                tol=o.tol,
                step_tol=o.step_tol,
                max_iter=o.max_newton_iterations,
                contract=True,
            )
            if not res.converged:
                return None
            res.z[k] = tt.value_at  # the constraint is linear: snap away the last rounding
            # [∂G/∂z; e_kᵀ] tan = e_last gives a tangent (with tan_k = 1), oriented like t
            tan = res.lu.solve(self._e_last)
            wt = W * t
            t_new = oriented_tangent(tan, wt, W)
            if t_new is None:
                return None
            rt = float(t_new.dot(tan))  # the sign factor of det [∂G/∂z; (W t_new)ᵀ]
            angle = math.degrees(math.acos(max(-1.0, min(1.0, float(t_new.dot(wt))))))
            h = float(wt.dot(res.z - z))
            dc = res.z - z_pred
            if angle > o.max_angle or t_new[k] * tk <= 0.0 or h <= 0.0 or self.wnorm(dc) > ds:
                return None
            return res, t_new, angle, h, rt, tt
        return None

    def _sdet(self, z, t):
        lu = factor(bordered(self.system.jacobian(z), self.weights * t))
        return lu.sign_det()

    def done(self, state: TracerState) -> bool:
        return state.status is not None

    def step(self, state: TracerState) -> TracerState:
        """One accepted continuation step (with its special points), or the end."""
        if state.status is not None:
            return state
        o = self.options
        system = self.system
        W = self.weights
        last = state.last
        z, t = last.z, last.t
        ds = state.ds
        rejected = 0
        reason = ""
        secant = None
        if o.predictor == "secant" and last.prev is not None:
            d = z - last.prev.z
            nd = self.wnorm(d)
            if nd > 0:
                secant = d / nd
        direction = t if secant is None else secant
        # unit weights (one unknown): the weighted products are plain ones
        unit_w = self._unit_weights
        row = direction if unit_w else W * direction
        used_fallback = False
        is_corner = False
        corner = None
        aimed = None
        if state.stalled >= _STALL_STEPS:
            # creeping at ds near ds_min (say, Newton with a Jacobian differenced across a
            # kink): try to pass the corner directly
            corner = self._corner_step(z, t, ds, None if last.prev is None else last.prev.z)
        elif secant is None and self._bound_tests:
            aimed = self._aim_at_bound(state, z, t, ds)
        while corner is None and aimed is None:
            z_pred = z + ds * direction
            # above ds_min a wandering Newton gives up early (the step is halved anyway)
            res = newton(
                system,
                z_pred,
                row,
                row.dot(z_pred),
                tol=o.tol,
                step_tol=o.step_tol,
                max_iter=o.max_newton_iterations,
                contract=ds > o.ds_min,
            )
            if not res.converged and ds <= o.ds_min:
                res = damped_newton(
                    system,
                    z_pred,
                    row,
                    row.dot(z_pred),
                    tol=o.tol,
                    step_tol=o.step_tol,
                    max_iter=5 * o.max_newton_iterations,
                )
                used_fallback = True
            if res.converged:
                t_new = res.lu.solve(self._e_last)
                t_new /= math.sqrt(t_new.dot(t_new if unit_w else W * t_new))
                rt = row.dot(t_new)
                cosang = rt if secant is None else t_new.dot(W * t)
                angle = math.degrees(math.acos(max(-1.0, min(1.0, cosang))))
                dc = res.z - z_pred
                correction = math.sqrt(dc.dot(dc if unit_w else W * dc))
                if angle > o.max_angle or correction > ds:
                    reason = (
                        f"tangent turned {angle:.1f} degrees"
                        if angle > o.max_angle
                        else "correction larger than the step"
                    )
                    if ds > o.ds_min:
                        ds = max(0.5 * ds, o.ds_min)
                        rejected += 1
                        continue
                    res.converged = False
                else:
                    break
            else:
                reason = res.reason
            if ds <= o.ds_min:
                corner = self._corner_step(
                    z, t, state.ds, None if last.prev is None else last.prev.z
                )
                if corner is not None:
                    break
                values = system.values(z)
                if reason == "nonfinite":
                    msg = (
                        f"the residual is not finite within ds_min={o.ds_min:g} of "
                        f"{_fmt(values)}; the branch stops there"
                    )
                    return self._fail(
                        state, "nonfinite_residual", msg, NonFiniteResidualError(msg, values=values)
                    )
                exc = ConvergenceError(
                    f"Newton's method and the damped fallback failed ({reason})",
                    values=values,
                    ds=ds,
                    iterations=res.iterations,
                    residual_norm=res.residual_norm,
                    remedy=_REMEDY,
                )
                return self._fail(state, "convergence_failure", str(exc), exc)
            ds = max(0.5 * ds, o.ds_min)
            rejected += 1

        if corner is not None:
            res, t_new, row, angle = corner
            ds = self.wnorm(res.z - z)
            is_corner = True
            rt = row.dot(t_new)
        elif aimed is not None:
            res, t_new, angle, ds, rt, aimed = aimed
        z1 = res.z
        sdet = None
        if self._has_bp:
            # the sign of det [∂G/∂z; (W t_new)ᵀ] from the corrector's LU with border `row`
            # (Cramer: the two determinants differ by the factor row·t_new)
            sdet = res.lu.sign_det() * (1.0 if rt > 0 else -1.0)
        # step-size update
        k = max(res.iterations, 1)
        f_newton = o.target_newton_iterations / k
        f_angle = o.target_angle / max(angle, 1e-12)
        factor_ = min(o.growth, max(0.5, min(f_newton, f_angle)))
        if rejected:
            factor_ = min(factor_, 1.0)
        ds_next = min(o.ds_max, max(o.ds_min, ds * factor_))
        # the pseudo-arclength of the step: row·(z1 − z) = ds·(row·direction) = ds, as the
        # corrector satisfies the (linear) hyperplane equation to rounding (an aimed step
        # returns its own)
        h = float(row.dot(z1 - z)) if is_corner else ds
        new_point = _Point(
            z1, t_new, last.s + h, res.iterations, rejected, res.residual_norm, ds, None, last
        )
        if used_fallback:
            logger.info("step accepted by the damped fallback corrector at ds=%g", ds)
        system.refresh(z1)

        # test functions
        new_tests = []
        crossings = []
        for tt, old in zip(self.tests, state.tests):
            new = tt.value(self, z1, t_new, sdet)
            new_tests.append(new)
            # no crossing unless the sign changed or an end is exactly zero
            if (
                old is not None
                and ((old < 0) != (new < 0) or new == 0.0 or old == 0.0)
                and tt.crossed(old, new)
            ):
                crossings.append((tt, old, new))
        if is_corner:
            # the tangent jumped across a corner: a fold there is non-smooth and only
            # bracketed; it is recorded on the corner step's own end point
            records = tuple(
                (
                    tt.kind,
                    f"{tt.label} (non-smooth)",
                    tt.wrt,
                    "guess",
                    (last.s, last.s + h),
                    {"non_smooth": True, "method": "corner step (natural parameter)"},
                )
                for tt, _, _ in crossings
                if tt.kind == "fold"
            )
            new_point.special = records or None
            crossings = [c for c in crossings if c[0].kind != "fold"]
        status = None
        message = ""
        n_points = state.n_points
        if crossings:
            br = None
            found = []
            for tt, old, new in crossings:
                if tt is aimed:  # the step ended on this bound: nothing to locate
                    loc = Located(
                        z1,
                        h,
                        "converged",
                        res.iterations,
                        {"method": "step aimed at the bound"},
                        tangent=t_new,
                        residual_norm=res.residual_norm,
                    )
                else:
                    if br is None:
                        br = Bracket(system, z, t, z1, t_new, W, o)
                    loc = tt.locate(self, br, old, new)
                found.append((loc.sigma, tt, loc))
            direction = math.copysign(1.0, h if br is None else br.h)
            found.sort(key=lambda item: item[0] * direction)
            prev = last
            for _sigma, tt, loc in found:
                records = [self._record(tt, loc, br, last.s, h)]
                if tt.terminal:
                    status = "bound" if tt.kind == "bound" else "terminal_event"
                    message = (
                        f"the branch reached {tt.label}"
                        if tt.kind == "bound"
                        else f"terminal event {tt.label!r} occurred"
                    )
                    if tt.kind != "bound":
                        records.append(("endpoint", tt.label, tt.wrt, loc.status, None, {}))
                if tt is aimed:  # the step's own end point
                    new_point.special = tuple(records)
                    new_point.prev = prev
                    prev = new_point
                    n_points += 1
                    break
                tan = loc.tangent
                if tan is None:
                    tan = tangent_at(system, loc.z, br.row, W, br)
                rn = loc.residual_norm
                if rn is None:
                    rn = max_abs(system.residual(loc.z))
                prev = _Point(
                    loc.z, tan, last.s + loc.sigma, loc.iterations, 0, rn, 0.0, tuple(records), prev
                )
                n_points += 1
                if tt.terminal:
                    break
            if status is None:
                new_point.prev = prev
            else:
                new_point = prev
                new_tests = state.tests  # irrelevant once finished
        if status is None:
            n_points += 1
        steps = state.steps + 1
        if status is None and steps >= o.max_steps:
            status = "max_steps"
            message = f"the branch ended after max_steps={o.max_steps} steps"
            new_point.special = (
                *(new_point.special or ()),
                ("endpoint", "max_steps", None, "converged", None, {}),
            )
        stalled = state.stalled + 1 if ds < _STALL_FACTOR * o.ds_min else 0
        return TracerState(
            new_point, ds_next, tuple(new_tests), steps, status, message, n_points, stalled
        )

    def _record(self, tt: _Test, loc: Located, br: Bracket | None, s_a: float, h: float):
        details = dict(loc.details)
        details["iterations"] = loc.iterations
        interval = (s_a, s_a + h)
        if tt.kind == "bound":
            return ("endpoint", tt.label, tt.wrt, loc.status, interval, details)
        if tt.kind == "branch_point":
            tan = tangent_at(self.system, loc.z, br.row, self.weights, br)
            details.update(branch_point_directions(self.system, loc.z, tan, self.weights))
            details["names"] = tuple(self.system.names)
        return (tt.kind, tt.label, tt.wrt, loc.status, interval, details)

    # ------------------------------------------------------------------ result

    def result(self, state: TracerState) -> Branch:
        """Assemble the :class:`Branch` (column arrays and special points) from a state."""
        points = []
        p = state.last
        while p is not None:
            points.append(p)
            p = p.prev
        points.reverse()
        system = self.system
        n_pts = len(points)
        zs, ts, ss, newton, rejected, residual, dss = zip(
            *[(pt.z, pt.t, pt.s, pt.newton, pt.rejected, pt.residual, pt.ds) for pt in points]
        )
        Z = np.concatenate(zs).reshape(n_pts, -1)
        T = np.concatenate(ts).reshape(n_pts, -1)
        s = np.array(ss)
        names = system.names
        columns = {name: Z[:, i].copy() for i, name in enumerate(names)}
        fixed = {
            name: float(value)
            for name, value in system.fixed_values().items()
            if name not in columns
        }
        for name, value in fixed.items():
            columns[name] = np.full(n_pts, value)
        extra = system.extra_columns(Z) if hasattr(system, "extra_columns") else {}
        columns.update(extra)

        def values_at(i: int) -> dict[str, float]:  # every column at row i
            values = dict(zip(names, zs[i].tolist()))
            values.update(fixed)
            for name, col in extra.items():
                values[name] = float(col[i])
            return values

        specials = []
        for i, pt in enumerate(points):
            for kind, label, wrt, status, interval, details in pt.special or ():
                specials.append(
                    SpecialPoint(
                        kind=kind,
                        index=i,
                        values=values_at(i),
                        tangent=T[i].copy(),
                        status=status,
                        label=label,
                        with_respect_to=wrt,
                        s=float(ss[i]),
                        interval=interval,
                        details=details,
                    )
                )
        status = state.status or "running"
        if state.status is None:
            message = "the branch is still being traced (result of an unfinished state)"
        else:
            message = state.message
        if not any(sp.kind == "endpoint" for sp in specials if sp.index == n_pts - 1):
            specials.append(
                SpecialPoint(
                    kind="endpoint",
                    index=n_pts - 1,
                    values=values_at(n_pts - 1),
                    tangent=T[-1].copy(),
                    status="converged",
                    label=status,
                    s=float(ss[-1]),
                )
            )
        stats = {
            "newton_iterations": np.array(newton),
            "rejected_steps": np.array(rejected),
            "residual_norm": np.array(residual),
            "ds": np.array(dss),
        }
        return Branch(
            columns,
            variables=tuple(system.names),
            s=s,
            tangents=T,
            special_points=specials,
            status=status,
            message=message,
            stats=stats,
            info={"steps": state.steps, "direction": self.direction},
        )


def _fmt(values: Mapping[str, float], limit: int = 6) -> str:
    items = list(values.items())
    return ", ".join(f"{k}={v:.10g}" for k, v in items[:limit]) + (
        " ..." if len(items) > limit else ""
    )


def trace(problem, u0, *, free: str, **kwargs: Any) -> Branch:
    """Trace the branch of ``problem`` through ``u0`` with ``free`` as the continuation
    parameter.

    Parameters
    ----------
    problem:
        a :class:`~cusp.continuation.Problem` (or any object following its protocol).
    u0:
        guess of the unknowns at the problem's parameter values (corrected by Newton), or a
        :class:`SpecialPoint`; a ``"branch_point"`` starts on the other branch through it.
    free:
        name of the parameter that varies along the branch.

    Other parameters
    ----------------
    params:
        parameter values overriding ``problem.params`` for this computation.
    bounds:
        ``{name: (low, high)}`` for any unknown or the free parameter: the branch ends exactly
        on the bound it meets.
    targets:
        ``{name: [values]}``: points located exactly at these values and inserted.
    events:
        :class:`Event` objects, located and inserted (terminal ones end the branch).
    monitor:
        unknowns whose turning points are reported as folds too (``with_respect_to`` names
        them): a snap-back is a turning point of a controlled displacement.
    direction:
        +1 (default) or −1: the sign of the free parameter's initial change.
    options:
        a :class:`ContinuationOptions`; keyword arguments named like its fields override it.
    throw:
        if False, failures return the partial branch with a status instead of raising.
    """
    tracer = Tracer(problem, free=free, **kwargs)
    state = tracer.init(u0)
    while state.status is None:
        state = tracer.step(state)
    return tracer.result(state)
