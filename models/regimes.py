"""The regime map of the contact-loss path over the friction coefficient μ and the reduced
normal load F'_N: which landings exist after the reduction, the boundaries between the
regimes traced as curves, and the released energies over the plane.

Regimes (at fixed F_N0 and g_A):

* ``"snap-back and snap-through"``: D and C exist (F_A < μF'_N);
* ``"snap-back, gross sliding under force control"``: D exists, C does not (F_A ≥ μF'_N);
* ``"gross sliding under both controls"``: neither (a body that slides as a whole, such as a
  sphere, when g_A exceeds the slip at which it slides under F'_N);
* ``"inadmissible"``: F'_N < F_N0 − F_A/μ, a reduction so deep that F'_T would be negative.

The boundaries: ``"C boundary"`` F'_N = F_A(μ)/μ and ``"F'_T = 0"`` F'_N = F_N0 − F_A(μ)/μ
follow from the locus of A in μ (A does not depend on F'_N), traced by continuation along the
shallowest reduction of the map (the "spine"); ``"D disappears"`` (a sphere) is located on
each locus in F'_N. The energies are the loci in F'_N, one per μ of the grid, started from
the spine's rows at those μ and evaluated at the loads of the grid (targets of the loci).

Units: µm, N, N·µm.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from cusp.continuation import AccuracyError, ChainPoint, ContinuationOptions, PointChain, locus

from .contact_loss import DEFAULT_OPTIONS as PATH_OPTIONS
from .contact_loss import ContactLoss
from .errors import ModelParameterError
from .manifold import DEFAULT_OPTIONS, point_loci, trace_loci
from .protocol import sliding_level, stick_bounds

__all__ = ["REGIMES", "RegimeBoundaries", "RegimeMap", "regime_boundaries", "regime_map"]

#: the regimes, in the order of their codes in :attr:`RegimeMap.regimes`
REGIMES = (
    "snap-back and snap-through",
    "snap-back, gross sliding under force control",
    "gross sliding under both controls",
    "inadmissible",
)


@dataclass(frozen=True)
class RegimeMap:
    """The regime map (:func:`regime_map`).

    Parameters
    ----------
    mu : numpy.ndarray, shape (m,)
        The friction coefficients of the grid (dimensionless).
    loads : numpy.ndarray, shape (k,)
        The reduced normal loads F'_N of the grid [N].
    snap_back, snap_through : numpy.ndarray, shape (k, m)
        The released energies [N·µm], NaN where the point does not exist, is not resolved
        (see the loci) or lies above the spine (ΔF_N < 1e-3·F_N0).
    regimes : numpy.ndarray of int, shape (k, m)
        Index into :data:`REGIMES` (−1 at a μ the spine did not reach).
    boundaries : dict of str to tuple of (numpy.ndarray, numpy.ndarray)
        Name -> (μ, F'_N [N]) arrays, each a curve between regimes.
    messages : list of str
        What the loci said about where they ended.
    """

    mu: np.ndarray
    loads: np.ndarray
    snap_back: np.ndarray
    snap_through: np.ndarray
    regimes: np.ndarray
    boundaries: dict[str, tuple[np.ndarray, np.ndarray]]
    messages: list[str]


def regime_map(
    model: ContactLoss,
    mu_span: tuple[float, float],
    load_span: tuple[float, float],
    *,
    mus: int | Sequence[float] = 24,
    loads: int | Sequence[float] = 40,
    options: ContinuationOptions | None = None,
) -> RegimeMap:
    """Compute the regime map of ``model``'s body at its F_N0 and g_A over μ × F'_N.

    Parameters
    ----------
    model : ContactLoss
        The path whose body, F_N0 [N] and g_A [µm] are used; its own μ must lie in
        ``mu_span``.
    mu_span : tuple of (float, float)
        The range of μ (dimensionless).
    load_span : tuple of (float, float)
        The range of F'_N [N], increasing, within (0, F_N0].
    mus, loads : int or sequence of float, optional
        The grid: numbers of points spaced evenly (μ logarithmically), or the values.
    options : ContinuationOptions, optional
        Of the loci (default :data:`cusp.models.manifold.DEFAULT_OPTIONS`; for another
        accuracy, ``DEFAULT_OPTIONS.replace(rtol=...)``).

    Returns
    -------
    RegimeMap
        The energies [N·µm], the regime of each grid point and the boundary curves.

    Raises
    ------
    ModelParameterError
        A span or grid out of range.
    """
    lo, hi = _load_span(model, load_span)
    mu_grid = _grid(mus, mu_span, log=True, name="mus")
    load_grid = _grid(loads, (lo, hi), log=False, name="loads")
    # the spine: the shallowest reduction of the map, admissible over the widest range of μ
    # (not shallower than 1e-3·F_N0: as ΔF_N → 0 the legs AB and BC shrink to A, and the
    # loci in F'_N started there are ill-conditioned)
    top = min(hi, model.F_N0 * (1.0 - 1e-3))
    spine_model = ContactLoss(
        model.body, model.F_N0, model.g_A, top, area_reading=model.area_reading
    )
    spine = point_loci(spine_model, "mu", mu_span, at=mu_grid, options=options)
    messages = [f"spine (F'_N = {top!r} N): {m}" for m in spine.messages]
    mu_s = spine.columns["mu"]
    F_A = spine.columns["F_A"]
    boundaries = {
        "C boundary": (mu_s, F_A / mu_s),
        "F'_T = 0": (mu_s, model.F_N0 - F_A / mu_s),
    }
    shape = (load_grid.size, mu_grid.size)
    back, through = np.full(shape, math.nan), np.full(shape, math.nan)
    d_gone: list[tuple[float, float]] = []
    for j, mu in enumerate(mu_grid):
        i = _row_at(mu_s, mu)
        if i is None:
            continue
        row = spine.rows[i]
        loci = trace_loci(
            spine_model,
            "reduced_normal_load",
            (lo, top),
            spine.start_at(i),
            {"mu": row["mu"], "m_B": row["m_B"]},
            at=load_grid,
            options=options,
        )
        cols = loci.columns
        for k, load in enumerate(load_grid):
            r = _row_at(cols["reduced_normal_load"], load)
            if r is not None:
                back[k, j] = cols["snap_back_energy"][r]
                through[k, j] = cols["snap_through_energy"][r]
        gone = [ev["reduced_normal_load"] for ev in loci.events if ev["event"] == "D disappears"]
        if gone:
            d_gone.append((float(mu), max(gone)))
    d_curve = _d_boundary(spine_model, spine, mu_span, (lo, top), options)
    if d_curve is not None:
        boundaries["D disappears"] = d_curve
    regimes = _classify(spine_model, mu_grid, load_grid, mu_s, F_A, dict(d_gone))
    return RegimeMap(mu_grid, load_grid, back, through, regimes, boundaries, messages)


def _load_span(model: ContactLoss, load_span) -> tuple[float, float]:
    lo, hi = (float(x) for x in load_span)
    if not 0.0 < lo < hi <= model.F_N0:
        raise ModelParameterError(
            f"load_span must be two increasing loads in (0, F_N0 = {model.F_N0!r}] N, got "
            f"{load_span!r}"
        )
    return lo, hi


@dataclass(frozen=True)
class RegimeBoundaries:
    """The boundaries of the regime map without its energies (:func:`regime_boundaries`).

    Parameters
    ----------
    mu : numpy.ndarray, shape (n,)
        μ (dimensionless) along the locus of A, sampled along its dense output (A does not
        depend on F'_N).
    F_A : numpy.ndarray, shape (n,)
        The tangential force at A [N] at those μ.
    F_N0 : float
        The normal load before the reduction [N].
    boundaries : dict of str to tuple of numpy.ndarray
        Name -> (μ, F'_N [N]) arrays, as in :class:`RegimeMap`: ``"C boundary"``
        F'_N = F_A/μ, ``"F'_T = 0"`` F'_N = F_N0 − F_A/μ, and ``"D disappears"`` for a body
        that slides as a whole.
    messages : list of str
        How the loci ended.
    """

    mu: np.ndarray
    F_A: np.ndarray
    F_N0: float
    boundaries: dict[str, tuple[np.ndarray, np.ndarray]]
    messages: list[str]


def regime_boundaries(
    model: ContactLoss,
    mu_span: tuple[float, float],
    load_span: tuple[float, float],
    *,
    options: ContinuationOptions | None = None,
    per_step: int = 4,
) -> RegimeBoundaries:
    """Trace the boundaries between the regimes of :func:`regime_map` as curves.

    No energies on a grid: the locus of A in μ alone (one point, no reduction), sampled
    along its dense output; for a body that slides as a whole (a sphere) also the curve
    where D disappears (as :func:`regime_map`, from the loci of A, B, D).

    Parameters
    ----------
    model : ContactLoss
        The path whose body, F_N0 [N] and g_A [µm] are used.
    mu_span : tuple of (float, float)
        The range of μ (dimensionless, increasing, positive).
    load_span : tuple of (float, float)
        The range of F'_N [N], increasing, within (0, F_N0].
    options : ContinuationOptions, optional
        Of the loci (default :data:`cusp.models.manifold.DEFAULT_OPTIONS`).
    per_step : int, optional
        Points sampled per traced step of the locus (within its rtol; default 4).

    Returns
    -------
    RegimeBoundaries
        The locus of A and the boundary curves.

    Raises
    ------
    ModelParameterError
        A span out of range.
    """
    lo, hi = _load_span(model, load_span)
    mus = (float(mu_span[0]), float(mu_span[1]))
    if not 0.0 < mus[0] < mus[1]:
        raise ModelParameterError(
            f"mu_span must be two increasing positive values, got {mu_span!r}"
        )
    o = options or DEFAULT_OPTIONS
    res = model.run(PATH_OPTIONS.replace(rtol=o.rtol))  # (as point_loci)
    leg, row = res.point_rows["A"]
    oa = model.problem("OA", start=1.0)
    chain = PointChain([ChainPoint("A", oa, "g", ("g", 1.0))], {"mu": model.mu0})
    bounds: dict[str, tuple[float, float]] = {"mu": mus}
    slides = math.isfinite(model.levels.slip_limit(model.levels.p0))
    if slides:
        bounds["A.q"] = stick_bounds(model.levels)
    scales = {"A.m": 1.0, "A.p": max(1.0, abs(model.levels.p0)), "mu": model.mu0}
    br = locus(
        chain,
        {"A": res.legs[leg].point(row)},
        free="mu",
        bounds=bounds,
        scales=scales,
        options=o,
        throw=False,
    )
    m_lo, m_hi = float(br["mu"].min()), float(br["mu"].max())
    messages = [f"locus of A in mu: {br.status}, mu in [{m_lo!r}, {m_hi!r}]"]
    S = np.asarray(br.s, dtype=float)
    theta = np.arange(per_step) / per_step
    try:
        dense = br.interpolate(
            np.append((S[:-1, None] + np.diff(S)[:, None] * theta).ravel(), S[-1])
        )
    except AccuracyError as exc:  # a step without an arc within rtol: the rows alone
        dense, messages = {k: br[k] for k in ("mu", "A.t")}, [*messages, str(exc)]
    mu, F_A = np.asarray(dense["mu"]), np.asarray(dense["A.t"]) * res.scales["t"]
    boundaries = {"C boundary": (mu, F_A / mu), "F'_T = 0": (mu, model.F_N0 - F_A / mu)}
    if slides:
        top = min(hi, model.F_N0 * (1.0 - 1e-3))
        spine_model = ContactLoss(
            model.body, model.F_N0, model.g_A, top, area_reading=model.area_reading
        )
        spine = point_loci(spine_model, "mu", mus, options=options)
        d_curve = _d_boundary(spine_model, spine, mus, (lo, top), options)
        if d_curve is not None:
            boundaries["D disappears"] = d_curve
    return RegimeBoundaries(mu, F_A, float(model.F_N0), boundaries, messages)


def _d_boundary(model: ContactLoss, spine, mu_span, load_span, options):
    """Where D disappears (a body that slides as a whole): the point of the reloading leg at
    g_T = g_A whose stick zone has just vanished (q = 0), its load F'_N free, continued in μ
    from where the spine's locus of D ended; None if it did not end there."""
    ends = [
        sp for br in spine.branches.values() for sp in br.special("endpoint", with_respect_to="D.q")
    ]
    if not ends:
        return None
    v = ends[0].values
    bc = model.problem("BC", start=1.0, constant=v["m_B"], mu=v["mu"])
    point = ChainPoint("D", bc, "m_B", ("q", sliding_level(model.levels)))
    chain = PointChain([point], {"g": 1.0, "mu": v["mu"]})
    start = {"D": {k: v[f"D.{k}"] for k in ("t", "m", "A_SL", "p", "q")} | {"m_B": v["m_B"]}}
    bounds = {
        "mu": tuple(float(x) for x in mu_span),
        "D.m_B": (0.0, (model.F_N0 - load_span[0]) / model.F_N0),
    }
    o = options or DEFAULT_OPTIONS
    scales = {"D.m": 1.0, "D.m_B": 1.0}  # the size of F_N/F_N0, not of the reduction
    br = locus(chain, start, free="mu", bounds=bounds, scales=scales, options=o, throw=False)
    return np.asarray(br["mu"]), model.F_N0 * (1.0 - np.asarray(br["D.m_B"]))


def _grid(spec, span, *, log: bool, name: str) -> np.ndarray:
    a, b = (float(x) for x in span)
    if isinstance(spec, int | np.integer):
        if spec < 2:
            raise ModelParameterError(f"{name} must be at least 2 points, got {spec!r}")
        return np.geomspace(a, b, int(spec)) if log else np.linspace(a, b, int(spec))
    values = np.asarray(spec, dtype=float)
    if values.ndim != 1 or values.size < 2 or not np.all(np.diff(values) > 0):
        raise ModelParameterError(f"{name} must be increasing values, got {spec!r}")
    if values[0] < a or values[-1] > b:
        raise ModelParameterError(f"{name} must lie in {span!r}, got {spec!r}")
    return values


def _row_at(column: np.ndarray, value: float) -> int | None:
    """The row of a locus at a target value (located to rounding), None if not reached."""
    if column.size == 0:
        return None
    i = int(np.argmin(np.abs(column - value)))
    return i if abs(column[i] - value) <= 1e-9 * abs(value) else None


def _classify(model, mu_grid, load_grid, mu_s, F_A, d_gone: dict[float, float]) -> np.ndarray:
    """The regime at each node of the grid, from F_A(μ) on the spine and the load below which
    D does not exist (``d_gone``, by μ; a sphere)."""
    out = np.full((load_grid.size, mu_grid.size), -1, dtype=int)
    for j, mu in enumerate(mu_grid):
        i = _row_at(mu_s, mu)
        if i is None:
            continue
        f_a, d_load = F_A[i], d_gone.get(float(mu), -math.inf)
        for k, load in enumerate(load_grid):
            if load < model.F_N0 - f_a / mu:
                out[k, j] = 3
            elif load < d_load:
                out[k, j] = 2  # no D, hence no C: the reloading leg slides before g_A
            elif f_a < mu * load:
                out[k, j] = 0
            else:
                out[k, j] = 1
    return out
