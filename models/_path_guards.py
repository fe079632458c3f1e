"""What keeps the contact-loss path (:mod:`cusp.models.contact_loss`) to valid scenes and
ends it in the scene's terms: the legs traced with their failures told in words, the point A
of a loading leg that reached the gross-sliding fold, the refusal of an empty range of
reductions, and the notes on what rounding leaves of a point.

A leg that cannot be traced ends with :class:`PathError`, one line naming the leg, where it
stopped (g_T, F_T, F_N) and why, in the terms of a scene: never the solver's internal
variables or its advice (``max_steps``, ``ds_min``, ``throw=False``), which no scene can act on.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import numpy as np

from cusp.continuation import (
    Branch,
    ContinuationError,
    ConvergenceError,
    NonFiniteResidualError,
    SingularMatrixError,
    StalledError,
    StepGuardError,
    trace,
)

from ._loci_energy import _invert
from ._loci_energy import polish_point as _polish
from .protocol import sliding_level, slipped_area

#: the physics' logger (``cusp -v`` shows it): each leg of a path as it is traced
logger = logging.getLogger("cusp.models")

__all__ = [
    "PathError",
    "SIZES",
    "STATUSES",
    "trace_leg",
    "polish",
    "loading_end",
    "leg_end",
    "explicit_point",
    "stopped",
    "quiet_stops",
    "empty_range",
    "flat",
]

_EPS = float(np.finfo(float).eps)

#: the typical sizes of the legs' unknowns that their start does not give: m (F_N/F_N0's
#: reduction, 0 on OA) and A_SL, a share of the contact area (0 at O). Sized by itself, a
#: share that stays at rounding level (a Gaussian surface with σ* ≪ |d|, where no summit lies
#: between d and d0: σ* = 1e-4 µm, g_A = 5e-6 µm) weighed its noise as motion, and the legs
#: stalled on sign changes of that noise
SIZES = {"m": 1.0, "A_SL": 1.0}

#: the legs in words
LEGS = {
    "OA": "the loading leg O-A (the slip raised under normal_load)",
    "AB": "the unloading leg A-B (normal_load reduced to reduced_normal_load)",
    "BC": "the reloading leg B-C (the tangential force raised again under reduced_normal_load)",
}

#: statuses of a branch that ended before its bound, in words (also of the loci)
STATUSES = {
    "max_steps": "it needed more steps than the solver allows a leg",
    "ds_min": "the step size fell to the solver's smallest step",
    "stalled": "the steps made no progress at the smallest step size",
    "guard_failure": "the path turned too sharply to be followed",
    "nonfinite_residual": "the body's equations gave a value beyond the float range",
    "nonconvergence": "Newton's method did not converge",
}


class PathError(RuntimeError):
    """A leg of the path ended before its end point (one line, in the scene's terms)."""


def _cause(exc: ContinuationError) -> str:
    """A solver failure in words."""
    if isinstance(exc, StepGuardError):
        return "the path turned too sharply to be followed"
    if isinstance(exc, StalledError):
        return "the steps made no progress at the smallest step size"
    if isinstance(exc, NonFiniteResidualError):
        return "the body's equations gave a value beyond the float range"
    if isinstance(exc, SingularMatrixError):
        return "the equations became singular"
    if isinstance(exc, ConvergenceError):
        return "Newton's method did not converge"
    return "the solver failed"


def _where(model: Any, values: Any) -> str:
    """The physical point of nondimensional leg values (what of it is known)."""
    v = dict(values or {})
    parts = []
    if "g" in v:
        parts.append(f"g_T = {v['g'] * model.g_A:.6g} µm")
    if "t" in v:
        parts.append(f"F_T = {v['t'] * model.mu0 * model.F_N0:.6g} N")
    if "m" in v:
        parts.append(f"F_N = {(1.0 - v['m']) * model.F_N0:.6g} N")
    return f" at {', '.join(parts)}" if parts else ""


def trace_leg(
    model: Any, leg: str, prob: Any, u0, what: str, partial: bool = False, **kwargs: Any
) -> Branch:
    """The branch of one leg, traced to its bound (``what``: the end point in words; the
    typical sizes :data:`SIZES` and any ``scales`` given); a failure of the solver, or a
    branch that ended otherwise, raises :class:`PathError` (with ``partial``, a branch that
    ended otherwise is returned as far as it went: :func:`leg_end`)."""
    scales = SIZES | kwargs.pop("scales", {})
    try:
        with quiet_stops():
            br = trace(prob, u0, scales=scales, throw=not partial, **kwargs)
    except ContinuationError as exc:
        raise PathError(
            f"{LEGS[leg]} stopped{_where(model, exc.values)} before reaching {what}: {_cause(exc)}"
        ) from exc
    logger.info(
        "leg %s: %d points, %s, %d special points", leg, len(br), br.status, len(br.special_points)
    )
    if br.status != "bound" and not partial:
        raise stopped(model, leg, br, what)
    return br


@contextmanager
def quiet_stops() -> Iterator[None]:
    """While a leg or a locus is traced: one that stops early (``throw=False``) is reported
    in the result's messages or its failure, so the tracer's log line saying so is not also
    printed."""
    log = logging.getLogger("cusp.continuation.stepping._tracer")

    def drop(record: logging.LogRecord) -> bool:
        return not str(record.msg).startswith("continuation stopped")

    log.addFilter(drop)
    try:
        yield
    finally:
        log.removeFilter(drop)


def stopped(model: Any, leg: str, br: Branch, what: str) -> PathError:
    """The failure of a leg that ended before its bound, in the scene's terms."""
    cause = STATUSES.get(br.status, f"it ended ({br.status})")
    return PathError(
        f"{LEGS[leg]} stopped{_where(model, br.point(len(br) - 1))} before reaching {what}: {cause}"
    )


def polish(model: Any, name: str, prob: Any, br: Branch, var: str, value: float, o) -> dict:
    """The point ``name`` of a traced leg, polished (:func:`polish_point`); a failure raises
    :class:`PathError`."""
    try:
        return _polish(prob, br, var, value, o)
    except ContinuationError as exc:
        raise PathError(
            f"the point {name} could not be placed on its leg{_where(model, exc.values)}: "
            f"{_cause(exc)}"
        ) from exc


def ended_at(br: Branch) -> str | None:
    """The component whose bound ended the branch (None: not a bound)."""
    ends = [sp for sp in br.special("endpoint") if sp.index == len(br) - 1]
    return ends[-1].with_respect_to if ends and br.status == "bound" else None


def flat(br: Branch, name: str) -> bool:
    """Does component ``name`` stay within rounding of one value along the whole leg (its
    typical size :data:`SIZES` or its largest value)? Its tangent component is then rounding
    noise, and the turning points located on its sign changes are not the body's (a Gaussian
    surface with σ* ≪ |d|: A_SL at rounding level on OA and constant on BC gave 21)."""
    col = np.asarray(br[name], dtype=float)
    size = max(SIZES.get(name, 0.0), float(np.max(np.abs(col))))
    return float(np.ptp(col)) <= 1e3 * _EPS * size


def loading_end(model: Any, br: Branch, p: float | None = None, m: float = 0.0) -> dict:
    """A on a loading leg that ended at the gross-sliding fold (the stick bound): the
    stick level q with g(q) = 1 between the last row below g_A and the fold (g rises
    monotonically there), by safeguarded Newton to rounding (Newton on the leg with g
    fixed does not converge within a few ulps of the fold, and from a guess past it
    lands on the other side, c < 0); the other unknowns are explicit at p = p0, m = 0.
    Likewise D on a reloading leg that ended there (``p``, ``m``: B's; a sphere at g_A =
    (1 − 1e-12)·g_lim with F'_N 1e-12 of F_A/μ below F_N0: D was 'not placed')."""
    p = float(model.levels.p0) if p is None else float(p)
    leg = "OA" if m == 0.0 else "BC"
    g = np.asarray(br["g"])
    above = np.flatnonzero(g >= 1.0)
    if not above.size or above[0] == 0:
        raise PathError(
            f"{LEGS[leg]} reached gross sliding (the stick zone vanished) at g_T = "
            f"{g[-1] * model.g_A:.6g} µm, before max_slip = {model.g_A!r} µm"
        )
    i = int(above[0])
    return explicit_point(model, br, p, m, "g", 1.0, (float(br["q"][i - 1]), float(br["q"][i])))


def leg_end(model: Any, br: Branch, p: float, m: float, var: str, value: float) -> dict:
    """The point of a reloading leg at ``var`` (``"g"`` or ``"t"``) = ``value`` where the
    trace stopped short of it (``partial``): on B→C the contact level p is B's and g, F_T
    and Â_SL are explicit in the stick level q, monotone, so the point is the root in q
    beyond the last row (bracketed by doubling the distance from B, up to gross sliding).
    A sphere at F'_N = F_N0 − 1 ulp: C lies a few ulps of q beyond D, and the leg's steps
    between them failed ('Newton's method did not converge'). Raises ArithmeticError where
    no bracket is found."""
    q = np.asarray(br["q"], dtype=float)
    lo, start = float(q[-1]), float(q[0])
    edge = sliding_level(model.levels)
    fun = _explicit(model, br, p, m, var)
    span = max(abs(lo - start), 4.0 * _EPS * max(1.0, abs(lo)))  # (the leg may be B alone)
    for _ in range(200):
        hi = lo + span
        if math.isfinite(edge):
            hi = min(hi, edge) if lo < edge else max(hi, edge)
        if fun(hi)[0] >= value:
            return explicit_point(model, br, p, m, var, value, (lo, hi))
        if hi == edge:
            break
        span *= 2.0
    raise ArithmeticError(f"no stick level beyond the last row reaches {var} = {value!r}")


def _explicit(model: Any, br: Branch, p: float, m: float, var: str):
    """``var`` (g or t) of a leg at contact level p and reduction m as a function of q."""
    L = model.levels
    mu = float(br["mu"][0])
    k = mu / model.g_A

    def fun(q: float) -> tuple[float, float]:
        if var == "g":
            s, _, ds_q = L.slip(p, q)
            return k * s, k * ds_q
        f, _, df_q = L.tangential_ratio(p, q)
        c = (1.0 - m) * mu / model.mu0
        return c * f, c * df_q

    return fun


def explicit_point(model: Any, br: Branch, p: float, m: float, var: str, value: float, bracket):
    """The point of a leg of contact level p and reduction m where ``var`` = ``value``, its
    stick level q inside ``bracket`` (clamped at gross sliding) by safeguarded Newton, the
    other unknowns explicit (module docstring of :mod:`cusp.models.contact_loss`)."""
    L = model.levels
    lo, hi = bracket
    edge = sliding_level(L)
    if math.isfinite(edge):
        hi = min(hi, edge) if lo < edge else max(hi, edge)
    q = _invert(_explicit(model, br, p, m, var), value, lo, hi)
    mu = float(br["mu"][0])
    g = float(L.slip(p, q)[0]) * mu / model.g_A
    t = (1.0 - m) * float(L.tangential_ratio(p, q)[0]) * mu / model.mu0
    a_sl = float(slipped_area(L, p, q, model.area_reading)[0])
    row = {key: float(v) for key, v in br.point(len(br) - 1).items()}
    values = {"g": g, "t": t, var: value}
    return {**row, **values, "m": m, "A_SL": a_sl, "p": p, "q": float(q)}


def refused_reduction(model: Any, F_A: float, F_Np: float) -> bool:
    """Is F'_N too deep, F'_T = F_A − μΔF_N < 0? (A reduction a rounding below the floor,
    F'_T = 0 located on a locus and evaluated again here, is the floor: F'_T is 0 to
    rounding there, which the path takes.)"""
    rounding = 8.0 * _EPS * (F_A + model.mu0 * (model.F_N0 - F_Np))
    return F_A - model.mu0 * (model.F_N0 - F_Np) < -rounding


def empty_range(model: Any, F_A: float, g_lim: float) -> str | None:
    """The refusal of a max_slip whose F_A is so small against F_N0 that even the shallowest
    reduction, the float just below F_N0, is too deep: the allowed range of
    reduced_normal_load, [F_N0 − F_A/μ, F_N0), is empty in floating point (None: it is not).
    Names the smallest max_slip that makes it non-empty (found on the body's loading curve by
    bisection in log g_T), and the roughness it is small against."""
    prev = float(np.nextafter(model.F_N0, 0.0))
    if not refused_reduction(model, F_A, prev):
        return None
    top = math.log(g_lim) if math.isfinite(g_lim) else 700.0
    lo, hi = math.log(model.g_A), top
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        try:
            ok = not refused_reduction(
                model, float(model.body.tangential_force(math.exp(mid), model.F_N0)), prev
            )
        except (ArithmeticError, ValueError):
            ok = False  # beyond what the body computes: count it as too small
        lo, hi = (lo, mid) if ok else (mid, hi)
        if hi - lo < 1e-6:
            break
    sigma = getattr(model.body, "sigma", None)
    against = ""
    if isinstance(sigma, float) and sigma > 0.0:
        against = f" (max_slip/sigma = {model.g_A / sigma:.3g} with sigma = {sigma!r} µm)"
    allowed = (
        f"max_slip >= {math.exp(hi):.3g} µm for this body and normal_load"
        if hi < top
        else "a max_slip at which F_A/mu exceeds the rounding of normal_load"
    )
    return (
        f"max_slip = {model.g_A!r} µm is too small for this body{against}: F_A = {F_A:.3g} N, "
        f"so small against normal_load = {model.F_N0!r} N that F_N0 - F_A/mu rounds to F_N0 "
        f"and no reduced_normal_load is shallow enough (the allowed range F_N0 - F_A/mu <= "
        f"reduced_normal_load < F_N0 is empty); allowed: {allowed}"
    )


def near_sliding_messages(model: Any) -> list[str]:
    """A note where g_A is so close to the gross-sliding slip g_lim under F_N0 that the
    stick zone at A is resolved only roughly: near g_lim the slip is quadratic in the stick
    level's distance from gross sliding, so rounding ε of the slip leaves that distance (the
    stick radius c of a sphere) known to about ε·g_lim/(2(g_lim − g_A))."""
    L = model.levels
    g_lim = model.mu0 * L.slip_limit(L.p0)
    if not math.isfinite(g_lim):
        return []
    share = (g_lim - model.g_A) / g_lim
    rel = _EPS / (2.0 * share)
    if rel <= 1e-8:
        return []
    return [
        f"max_slip = {model.g_A!r} µm is within {share:.2g} (relative) of the slip {g_lim!r} "
        f"µm at which the body slides under normal_load: the stick zone at A is so small that "
        f"its level {L.names[1]} is known only to about {rel:.1g} relative (rounding amplified "
        f"by 1/(2(1 - g_A/g_lim))), and so are the points and energies that depend on it"
    ]
