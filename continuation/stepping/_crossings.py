"""Phases 3 and 4 of a step: evaluate the test functions at a step's end, find the tests
whose sign changed (also twice inside the step, :func:`pairs`) and locate their zeros
inside the step (:func:`locate_crossings`)."""

from __future__ import annotations

import logging
import math
from collections.abc import Sequence

import numpy as np

from .._options import ContinuationOptions
from ..detection._bracket import Bracket, Located, tangent_at
from ..detection._spectrum import Factored
from ..detection._tests import Record, TestFunction
from ..systems._curve import CurveSystem
from ._state import Point, TracerState
from ._step import Trial, wnorm

logger = logging.getLogger(__name__)

#: a test that changed sign in a step: (test, value at the start, value at the end, and
#: None, or the part of the step that holds the zero: (z_a, t_a, z_b, t_b, its start's
#: pseudo-arclength from the step's start))
Crossing = tuple[TestFunction, float, float, "tuple | None"]


def evaluate(
    tests: Sequence[TestFunction], has_bp: bool, state: TracerState, trial: Trial
) -> tuple[CurveSystem, tuple, list[Crossing]]:
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
            # the factorization at the point itself (corrector.factor_at), kept for the
            # branch-point test's partial spectrum (module spectrum)
            sdet = Factored(sdet, res.lu)
    values = tuple([tt.value(system, z1, t1, sdet) for tt in tests])
    # no crossing unless the sign changed or an end is exactly zero
    crossings: list[Crossing] = [
        (tt, old, new, None)
        for tt, old, new in zip(tests, state.tests, values)
        if old is not None
        and ((old < 0) != (new < 0) or new == 0.0 or old == 0.0)
        and tt.crossed(old, new)
    ]
    return system, values, crossings


def splits(
    split_tests: Sequence[tuple[int, TestFunction]],
    options: ContinuationOptions,
    state: TracerState,
    system: CurveSystem,
    trial: Trial,
    values: tuple,
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
    data = None
    tests = state.tests
    for i, tt in split_tests:
        old, new = tests[i], values[i]
        if old is None or old == 0.0 or new == 0.0:
            continue
        if data is None:
            if options.predictor == "tangent" and trial.aimed is None and not trial.corner:
                # the step's h and rt are the pseudo-arclength along t_a and (W t_a)·t_b
                data = (z_a, t_a, z_b, t_b, trial.h, trial.rt)
            else:
                data = _part_data(system, (z_a, t_a, 0.0), (z_b, t_b, math.nan))
            if data[4] == 0.0:
                break
        thetas = tt.split_points(old, new, data)
        if not thetas:  # (most steps: nothing to split)
            continue
        a, b = (z_a, t_a, 0.0), (z_b, t_b, math.nan)
        found = _split(tt, options, system, a, old, b, new, SPLIT_DEPTH, data, thetas)
        if found is not None:
            replaced.add(tt)
            out += found
    return replaced, out


SPLIT_DEPTH = 3
"""How often a part of a step is split again when its test sees further zeros inside it."""


def _split(
    tt: TestFunction,
    options: ContinuationOptions,
    system: CurveSystem,
    a: tuple[np.ndarray, np.ndarray, float],
    va: float,
    b: tuple[np.ndarray, np.ndarray, float],
    vb: float,
    depth: int,
    data: tuple | None = None,
    thetas: tuple[float, ...] | None = None,
) -> list[Crossing] | None:
    """The crossings of ``tt`` between the curve points ``a`` and ``b`` ((z, unit tangent,
    pseudo-arclength from the step's start)) split where the test sees several zeros; None
    if it sees none (or a split point cannot be corrected): the part is taken whole.
    ``data``: :func:`_part_data` of the part, and ``thetas`` its split points, if known."""
    if thetas is None:
        if data is None:
            data = _part_data(system, a, b)
        if data[4] == 0.0:
            return None
        thetas = tt.split_points(va, vb, data)
    if not thetas:
        return None
    za, ta, sa = a
    zb, tb, _ = b
    W = system.weights
    br = Bracket(system, za, ta, zb, tb, W, options)
    points = [(a, va)]
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
            out.append((tt, vp, vq, (p[0], p[1], q[0], q[1], p[2])))
    return out


SEARCH_SAMPLES = 6
"""How many more points of a step a test may ask for (:meth:`~..detection._tests.TestFunction.
next_split_point`) when the split points show no zero."""


def _search(
    tt: TestFunction, system: CurveSystem, br: Bracket, points: list, thetas: list[float]
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


def _part_data(system: CurveSystem, a: tuple, b: tuple) -> tuple:
    """``(z_a, t_a, z_b, t_b, h, cos_b)`` of the part of a step between curve points ``a``
    and ``b``: its pseudo-arclength along ``t_a`` and the cosine of its turn."""
    za, ta, _ = a
    zb, tb, _ = b
    wta = system.weights * ta
    return (za, ta, zb, tb, float(wta.dot(zb - za)), float(wta.dot(tb)))


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
) -> list[tuple[TestFunction, Located, Bracket | None]]:
    """Each crossing located inside the step (or the part of it that holds it), in the
    order of travel, with the bracket it was located in (None for the step's own end).
    ``br``: the step's bracket on ``system``, if it was made already."""
    last = state.last
    z1 = trial.res.z
    W = system.weights
    found = []
    for tt, old, new, part in crossings:
        where: Bracket | None
        if tt is trial.aimed:  # the step ended on this bound: nothing to locate
            loc = Located(
                z1,
                trial.h,
                "converged",
                trial.res.iterations,
                {"method": "step aimed at the bound"},
                tangent=trial.t,
                residual_norm=trial.res.residual_norm,
            )
            where = None
        elif part is not None:  # one of two zeros inside the step
            where = Bracket(system, part[0], part[1], part[2], part[3], W, options)
            loc = tt.locate(where, old, new)
            loc = loc._replace(sigma=loc.sigma + part[4])
        else:
            if br is None:
                br = step_bracket(options, system, last, trial)
            loc, where = tt.locate(br, old, new), br
        found.append((loc.sigma, tt, loc, where))
    direction = math.copysign(1.0, trial.h if br is None else br.h)
    found.sort(key=lambda item: item[0] * direction)
    return _turning_at_branch_points(
        [(tt, loc, where) for _, tt, loc, where in found], W, trial.h, options
    )


def _turning_at_branch_points(
    found: list[tuple[TestFunction, Located, Bracket | None]],
    weights: np.ndarray,
    h: float,
    options: ContinuationOptions,
) -> list[tuple[TestFunction, Located, Bracket | None]]:
    """Drop a fold located at a branch point located in the same step.

    A parameter may turn at a branch point (the parabola p = −x² of a subcritical pitchfork
    at its vertex): the fold test changes sign there, but the point is singular, not a fold,
    and the fold's Newton iteration (on a system singular at that point) creeps towards it,
    its state off by about √tol. A fold within ``max(10⁻³·|h|, 100·√locate_tol)`` (weighted
    distance) of a converged branch point is that turn: it is dropped, and the branch point
    says which component turns there (``details["turning"]``)."""
    bps = [loc for tt, loc, _ in found if tt.kind == "branch_point" and loc.status == "converged"]
    if not bps:
        return found
    near = max(1e-3 * abs(h), 100.0 * math.sqrt(options.locate_tol))
    out = []
    turning: dict[int, list[str | None]] = {}
    for tt, loc, where in found:
        if tt.kind == "fold":
            at = next((b for b in bps if wnorm(loc.z - b.z, weights) <= near), None)
            if at is not None:
                logger.info("%r located at a branch point: the parameter turns there", tt)
                turning.setdefault(id(at), []).append(tt.wrt)
                continue
        out.append((tt, loc, where))
    return [
        (tt, loc._replace(details={**loc.details, "turning": tuple(turning[id(loc)])}), where)
        if id(loc) in turning
        else (tt, loc, where)
        for tt, loc, where in out
    ]


def corner_folds(
    crossings: list[Crossing], s: float, h: float
) -> tuple[tuple[Record, ...] | None, list[Crossing]]:
    """The tangent jumped across a corner: a fold there is non-smooth and only bracketed;
    it is recorded on the corner step's own end point (not located inside the step)."""
    records = tuple(
        (
            tt.kind,
            f"{tt.label} (non-smooth)",
            tt.wrt,
            "guess",
            (s, s + h),
            {"non_smooth": True, "method": "corner step (natural parameter)"},
        )
        for tt, _, _, _ in crossings
        if tt.kind == "fold"
    )
    return records or None, [c for c in crossings if c[0].kind != "fold"]
