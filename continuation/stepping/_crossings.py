"""What a step finds: the test functions evaluated at its end (:func:`evaluate`), the tests
whose sign changed (also twice inside the step, :func:`splits`) and their zeros located
inside it (:func:`locate_crossings`)."""

from __future__ import annotations

import logging
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from .._options import ContinuationOptions
from .._outcomes import Kind, PointStatus
from ..detection._bracket import Bracket, Located, Span, tangent_at
from ..detection._spectrum import Factored
from ..detection._tests import Record, TestFunction
from ..systems._curve import CurveSystem
from ._state import Point, TracerState
from ._step import Trial, wnorm

# records are made by a static method of() and this bound object.__new__: a class method's
# binding and the lookup of __new__ on object cost a third of a record (callgrind), and the
# stepper makes several records a step
_new = object.__new__

logger = logging.getLogger(__name__)

SPLIT_DEPTH = 3
"""How often a part of a step is split again when its test sees further zeros inside it."""

SEARCH_SAMPLES = 6
"""How many more points of a step a test may ask for
(:meth:`~..detection._tests.TestFunction.next_split_point`) when the split points show no
zero."""


@dataclass(frozen=True, slots=True)
class Crossing:
    """A test whose sign changed in a step (built by keyword): the ``test``, its values at
    the start (``old``) and end (``new``) of the step, or of the ``part`` of it that holds
    the zero (one of several zeros inside the step; None: the whole step)."""

    test: TestFunction
    old: float
    new: float
    part: Span | None = None


@dataclass(slots=True)
class Evaluation:
    """A step's trial seen by the tests: the ``trial``, the curve ``system`` refreshed at its
    end, the test ``values`` there and the ``crossings`` (the tests whose change from the
    last point counts); the tracer adds the step's ``bracket`` where a test of the curve's
    geometry changed sign (else None) and whether its confirmation waits for the crossings
    to be located (``deferred``: folds only)."""

    trial: Trial
    system: CurveSystem
    values: tuple[Any, ...]
    crossings: list[Crossing]
    bracket: Bracket | None = None
    deferred: bool = False

    @staticmethod
    def of(
        *,
        trial: Trial,
        system: CurveSystem,
        values: tuple[Any, ...],
        crossings: list[Crossing],
        bracket: Bracket | None = None,
        deferred: bool = False,
    ) -> Evaluation:
        """Built by keyword, fast: a class called with keywords first gathers them in a
        dict (three times the cost of this call, on every step)."""
        self = _new(Evaluation)
        self.trial = trial
        self.system = system
        self.values = values
        self.crossings = crossings
        self.bracket = bracket
        self.deferred = deferred
        return self

    def with_bracket(self, bracket: Bracket | None, deferred: bool = False) -> Evaluation:
        """A copy with the step's ``bracket`` (and ``deferred``) set; this one unchanged."""
        return Evaluation.of(
            trial=self.trial,
            system=self.system,
            values=self.values,
            crossings=self.crossings,
            bracket=bracket,
            deferred=deferred,
        )


class Found(NamedTuple):
    """A crossing located: the ``test``, the point (``located``) and the ``bracket`` it was
    located in (None for the step's own end)."""

    test: TestFunction
    located: Located
    bracket: Bracket | None


def evaluate(
    tests: Sequence[TestFunction], has_bp: bool, state: TracerState, trial: Trial
) -> Evaluation:
    """The curve system refreshed at the trial's point, the test values there and the
    tests whose change from the last point counts."""
    res, t1 = trial.res, trial.t
    z1 = res.z
    system = state.system
    if system.refreshes:
        system = system.refreshed(z1)
    sdet = None
    if has_bp:
        # the sign of det [∂G/∂z; (W t_new)ᵀ] from the corrector's LU with border `row`
        # (Cramer: the two determinants differ by the factor row·t_new)
        sdet = res.lu.sign_det() * (1.0 if trial.rt > 0 else -1.0)
        if system.dim > 2 and system is state.system and trial.aimed is None and not trial.corner:
            # the factorization at the point itself (systems._newton.factor_at), kept for the
            # branch-point test's partial spectrum (detection._spectrum)
            sdet = Factored(sdet, res.lu)
    values = tuple([tt.value(system, z1, t1, sdet) for tt in tests])
    # no crossing unless the sign changed or an end is exactly zero
    crossings = [
        Crossing(test=tt, old=old, new=new)
        for tt, old, new in zip(tests, state.test_values, values)
        if old is not None
        and ((old < 0) != (new < 0) or new == 0.0 or old == 0.0)
        and tt.crossed(old, new)
    ]
    return Evaluation.of(trial=trial, system=system, values=values, crossings=crossings)


def splits(
    split_tests: Sequence[tuple[int, TestFunction]],
    options: ContinuationOptions,
    state: TracerState,
    system: CurveSystem,
    trial: Trial,
    values: tuple[Any, ...],
) -> tuple[set[TestFunction], list[Crossing]]:
    """Several zeros of one test inside the step (two leave no net sign change): where the
    test sees them (:meth:`~..detection._tests.TestFunction.split_points`), the curve points
    between them are corrected, and each part of the step whose ends have opposite signs
    holds one crossing (parts are split again, up to :data:`SPLIT_DEPTH` times). Returns
    the tests whose crossings these replace, and the crossings."""
    last = state.last
    z_a, t_a, z_b, t_b = last.z, last.t, trial.res.z, trial.t
    replaced: set[TestFunction] = set()
    out: list[Crossing] = []
    span = None
    for i, tt in split_tests:
        old, new = state.test_values[i], values[i]
        if old is None or old == 0.0 or new == 0.0:
            continue
        if span is None:
            if options.predictor == "tangent" and trial.aimed is None and not trial.corner:
                # the step's h and rt are the pseudo-arclength along t_a and (W t_a)·t_b
                span = Span.of(z_a=z_a, t_a=t_a, z_b=z_b, t_b=t_b, h=trial.h, cos_b=trial.rt)
            else:
                span = _span(system, (z_a, t_a, 0.0), (z_b, t_b, math.nan))
            if span.h == 0.0:
                break
        thetas = tt.split_points(old, new, span)
        if not thetas:  # (most steps: nothing to split)
            continue
        a, b = (z_a, t_a, 0.0), (z_b, t_b, math.nan)
        found = _split(tt, options, system, a, old, b, new, SPLIT_DEPTH, span, thetas)
        if found is not None:
            replaced.add(tt)
            out += found
    return replaced, out


#: a curve point inside a step: (z, unit tangent, pseudo-arclength from the step's start)
_Ends = tuple[np.ndarray, np.ndarray, float]


def _split(
    tt: TestFunction,
    options: ContinuationOptions,
    system: CurveSystem,
    a: _Ends,
    va: float,
    b: _Ends,
    vb: float,
    depth: int,
    span: Span | None = None,
    thetas: tuple[float, ...] | None = None,
) -> list[Crossing] | None:
    """The crossings of ``tt`` between the curve points ``a`` and ``b`` split where the test
    sees several zeros; None if it sees none (or a split point cannot be corrected): the
    part is taken whole. ``span``: the part's :class:`~..detection._bracket.Span`, and
    ``thetas`` its split points, if known."""
    if thetas is None:
        if span is None:
            span = _span(system, a, b)
        if span.h == 0.0:
            return None
        thetas = tt.split_points(va, vb, span)
    if not thetas:
        return None
    za, ta, sa = a
    zb, tb, _ = b
    W = system.weights
    br = Bracket(system, za, ta, zb, tb, W, options)
    points: list[tuple[_Ends, float]] = [(a, va)]
    for theta in thetas:
        res = br.point_at(theta * br.h)
        if not res.converged:
            return None
        tm = tangent_at(system, res.z, br.row, W, br)
        points.append(((res.z, tm, sa + br.sigma(res.z)), tt.value(system, res.z, tm, None)))
    points.append((b, vb))
    if depth == SPLIT_DEPTH and _search(tt, system, br, points, [0.0, *thetas, 1.0]) is None:
        return None
    logger.info("%r sees several zeros inside one step: split at theta=%s", tt, thetas)
    out: list[Crossing] = []
    for (p, vp), (q, vq) in zip(points[:-1], points[1:]):
        inner = _split(tt, options, system, p, vp, q, vq, depth - 1) if depth > 1 else None
        if inner is not None:
            out += inner
        elif vp != 0.0 and ((vp < 0) != (vq < 0) or vq == 0.0) and tt.crossed(vp, vq):
            part = _span(system, p, q, with_arclength=False)
            out.append(Crossing(test=tt, old=vp, new=vq, part=part))
    return out


def _search(
    tt: TestFunction,
    system: CurveSystem,
    br: Bracket,
    points: list[tuple[_Ends, float]],
    thetas: list[float],
) -> list | None:
    """More samples of ``tt`` inside the step ``br``, inserted in ``points`` (at the step
    fractions ``thetas``, both ascending) while the test asks for them and none has the
    other sign: a search for the zeros that the split points suggest but do not show. None
    if a point cannot be corrected."""
    sign = points[0][1] < 0
    for _ in range(SEARCH_SAMPLES):
        if any((v < 0) != sign or v == 0.0 for _, v in points):
            break
        theta = tt.next_split_point(list(zip(thetas, (v for _, v in points))))
        if theta is None:
            break
        res = br.point_at(theta * br.h)
        if not res.converged:
            return None
        tm = tangent_at(system, res.z, br.row, br.weights, br)
        i = next(i for i, th in enumerate(thetas) if th > theta)
        thetas.insert(i, theta)
        point = (res.z, tm, points[0][0][2] + br.sigma(res.z))
        points.insert(i, (point, tt.value(system, res.z, tm, None)))
    return points


def _span(system: CurveSystem, a: _Ends, b: _Ends, with_arclength: bool = True) -> Span:
    """The :class:`~..detection._bracket.Span` of the part of a step between the curve
    points ``a`` and ``b``: its pseudo-arclength along ``t_a`` and the cosine of its turn
    (``with_arclength`` False: only its ends and the arclength ``s_a`` of its start)."""
    za, ta, s_a = a
    zb, tb, _ = b
    if not with_arclength:
        return Span(z_a=za, t_a=ta, z_b=zb, t_b=tb, h=math.nan, cos_b=math.nan, s_a=s_a)
    wta = system.weights * ta
    h, cos_b = float(wta.dot(zb - za)), float(wta.dot(tb))
    return Span(z_a=za, t_a=ta, z_b=zb, t_b=tb, h=h, cos_b=cos_b, s_a=s_a)


def step_bracket(
    options: ContinuationOptions, system: CurveSystem, last: Point, trial: Trial
) -> Bracket:
    """The :class:`~..detection._bracket.Bracket` of the step from the point ``last`` to the
    trial's."""
    return Bracket(system, last.z, last.t, trial.res.z, trial.t, system.weights, options)


def locate_crossings(
    options: ContinuationOptions,
    state: TracerState,
    system: CurveSystem,
    trial: Trial,
    crossings: list[Crossing],
    br: Bracket | None = None,
) -> list[Found]:
    """Each crossing located inside the step (or the part of it that holds it), in the
    order of travel, with the bracket it was located in (None for the step's own end).
    ``br``: the step's bracket on ``system``, if it was made already."""
    found = []
    for crossing in crossings:
        tt, part = crossing.test, crossing.part
        where: Bracket | None
        if tt is trial.aimed:  # the step ended on this bound: nothing to locate
            loc = _aimed_end(trial)
            where = None
        elif part is not None:  # one of several zeros inside the step
            where = Bracket(system, part.z_a, part.t_a, part.z_b, part.t_b, system.weights, options)
            loc = tt.locate(where, crossing.old, crossing.new)
            loc = loc._replace(sigma=loc.sigma + part.s_a)
        else:
            if br is None:
                br = step_bracket(options, system, state.last, trial)
            loc, where = tt.locate(br, crossing.old, crossing.new), br
        found.append((loc.sigma, Found(test=tt, located=loc, bracket=where)))
    direction = math.copysign(1.0, trial.h if br is None else br.h)
    found.sort(key=lambda item: item[0] * direction)
    return _turning_at_branch_points([f for _, f in found], system.weights, trial.h, options)


def _aimed_end(trial: Trial) -> Located:
    """The end of a step aimed at a bound, as the bound's located point."""
    return Located(
        z=trial.res.z,
        sigma=trial.h,
        status=PointStatus.CONVERGED,
        iterations=trial.res.iterations,
        details={"method": "step aimed at the bound"},
        tangent=trial.t,
        residual_norm=trial.res.residual_norm,
    )


def _turning_at_branch_points(
    found: list[Found], weights: np.ndarray, h: float, options: ContinuationOptions
) -> list[Found]:
    """Drop a fold located at a branch point located in the same step.

    A parameter may turn at a branch point (the parabola p = −x² of a subcritical pitchfork
    at its vertex): the fold test changes sign there, but the point is singular, not a fold,
    and the fold's Newton iteration (on a system singular at that point) creeps towards it,
    its state off by about √tol. A fold within ``max(10⁻³·|h|, 100·√locate_tol)`` (weighted
    distance) of a converged branch point is that turn: it is dropped, and the branch point
    says which component turns there (``details["turning"]``)."""
    bps = [
        f.located
        for f in found
        if f.test.kind == Kind.BRANCH_POINT and f.located.status is PointStatus.CONVERGED
    ]
    if not bps:
        return found
    near = max(1e-3 * abs(h), 100.0 * math.sqrt(options.locate_tol))
    out = []
    turning: dict[int, list[str | None]] = {}
    for f in found:
        if f.test.kind == Kind.FOLD:
            at = next((b for b in bps if wnorm(f.located.z - b.z, weights) <= near), None)
            if at is not None:
                logger.info("%r located at a branch point: the parameter turns there", f.test)
                turning.setdefault(id(at), []).append(f.test.with_respect_to)
                continue
        out.append(f)
    return [
        _with_turning(f, turning[id(f.located)]) if id(f.located) in turning else f for f in out
    ]


def _with_turning(f: Found, turning: list[str | None]) -> Found:
    details = {**f.located.details, "turning": tuple(turning)}
    return Found(test=f.test, located=f.located._replace(details=details), bracket=f.bracket)


def corner_folds(
    crossings: list[Crossing], s: float, h: float
) -> tuple[tuple[Record, ...] | None, list[Crossing]]:
    """The tangent jumped across a corner: a fold there is non-smooth and only bracketed;
    it is recorded on the corner step's own end point (not located inside the step).
    Returns those records (None if none) and the other crossings."""
    records = tuple(
        Record(
            kind=c.test.kind,
            label=f"{c.test.label} (non-smooth)",
            with_respect_to=c.test.with_respect_to,
            status=PointStatus.GUESS,
            interval=(s, s + h),
            details={"non_smooth": True, "method": "corner step (natural parameter)"},
        )
        for c in crossings
        if c.test.kind == Kind.FOLD
    )
    return records or None, [c for c in crossings if c.test.kind != Kind.FOLD]


__all__ = [
    "Crossing",
    "Evaluation",
    "Found",
    "corner_folds",
    "evaluate",
    "locate_crossings",
    "splits",
    "step_bracket",
]
