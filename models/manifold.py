"""The catastrophe manifold of the contact-loss path: the loci of the points A, B, C and D
as the friction coefficient μ or the reduced normal load F'_N varies (the end of Sec. 4 and
Fig 9 of the paper; the edges of the pleat are the loci of the turning points A and B).

Each named point of the path is a point of one leg located by the condition that ends the
leg (A: g_T = g_A on OA; B: F_N = F'_N on AB, with the stick level frozen at its value at
A; C: F_T = F_A on BC; D: g_T = g_A on BC, both at F'_N = F_N at B). Stacked and linked,
they form one :class:`cusp.continuation.PointChain`, whose branch in μ (or in F'_N) is the
locus of all of them together, traced by continuation (:func:`cusp.continuation.locus`), not
by repeating single runs. Along it two events are located exactly:

* ``"C boundary"``: F_A = μF'_N, where C appears or disappears (below it, force control
  ends in gross sliding; C's slip grows without bound as it is approached);
* ``"F'_T = 0"``: B reaches zero tangential force, the deepest admissible reduction (the
  locus ends there).

C's slip grows without bound towards the C boundary, so C is carried by a second chain
(A, B, C, D), started where C exists and stopped where F_A = (1 − :data:`C_MARGIN`)·μF'_N
(closer, rounding decides whether C exists at all); the rows of
the locus are that chain's where it runs and the first chain's beyond. At every row the
released energies are integrated on the legs between the points
(:mod:`cusp.models._loci_energy`).

Units as in :mod:`cusp.models.contact_loss`: µm, N, N·µm.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from cusp.continuation import (
    Branch,
    ContinuationOptions,
    Event,
    SingularPointError,
    locus,
    point_tol,
    points_at,
    trace,
)

from ._loci_energy import EnergyError, energies, flag_rtol, note_rtol, path_chain, polish_row
from ._path_guards import STATUSES, quiet_stops
from ._point_errors import chain_errors, point_bounds, relative
from .contact_loss import DEFAULT_OPTIONS as PATH_OPTIONS
from .contact_loss import ContactLoss
from .errors import ModelParameterError
from .protocol import stick_bounds

__all__ = ["CSV_COLUMNS", "LOCI_UNITS", "LOCUS_PARAMETERS", "Loci", "point_loci", "trace_loci"]

#: the parameters a locus can be traced in: name -> the chain's parameter (μ; the reduction
#: m_B = 1 − F'_N/F_N0, so F'_N = F_N0 (1 − m_B))
LOCUS_PARAMETERS = {"mu": "mu", "reduced_normal_load": "m_B"}
#: the locus of C stops where F_A = (1 − C_MARGIN)·μF'_N: C's slip diverges at the C boundary,
#: and its sensitivity to rounding grows like 1/margin (at 1e-6, C is resolved to ~1e-10)
C_MARGIN = 1e-6
#: the columns of a locus table (``loci.csv``), the last naming the event of an event row
CSV_COLUMNS = (
    "mu", "reduced_normal_load", "g_A", "F_A", "g_B", "F_B", "g_C", "F_C", "g_D", "F_D",
    "A_SL_A", "A_SL_B", "snap_back_energy", "snap_through_energy", "event",
)  # fmt: skip
#: the unit of every column of :attr:`Loci.columns`
LOCI_UNITS = {
    "mu": "",
    "reduced_normal_load": "N",
    **{f"g_{x}": "µm" for x in "ABCD"},
    **{f"F_{x}": "N" for x in "ABCD"},
    **{f"A_SL_{x}": "" for x in "ABCD"},
    "snap_back_energy": "N·µm",
    "snap_through_energy": "N·µm",
    "snap_back_error": "N·µm",
    "snap_through_error": "N·µm",
}
#: the bounds of a locus that are events of the path
_BOUND_EVENTS = {"B.t": "F'_T = 0", "D.q": "D disappears", "A.q": "A slides"}
#: the most rows of a locus table whose released energies are integrated: each costs up to
#: two quadratures of 512 nodes (0.5 s a row on a Gaussian surface, whose μ-locus over
#: [1e-9, 1e9] has 225 rows); a longer table has them at every k-th row, and says so
ENERGY_ROWS = 30
#: the most steps of a locus in each direction (each step at most ``max_step_solves``
#: corrector solves of the chain): a Gaussian μ-locus over [1e-9, 1e9] with σ* = 0.0117 µm
#: took over 120 s of steps; a locus that reaches it ends there, and its message says so
LOCUS_STEPS = 400
#: default solver settings of the loci (the default ``rtol``). No branch-point tests: the
#: chain stacks independent conditions on the points of one path, whose loci do not branch,
#: and the tests' sign changes at rounding level (the chain's determinant where a point's
#: equations degenerate, μ → 0) cost a fig8 locus over μ in [5e-324, 1e3] 141 s of step
#: splitting
DEFAULT_OPTIONS = ContinuationOptions(
    ds=0.02, ds_max=0.1, detect_branch_points=False, max_steps=LOCUS_STEPS
)


@dataclass(frozen=True)
class Loci:
    """The loci of the points of the path (:func:`point_loci`).

    Parameters
    ----------
    parameter : {"mu", "reduced_normal_load"}
        The parameter the loci run in (μ, or F'_N [N]).
    columns : dict of str to numpy.ndarray, each shape (k,)
        Every key of :data:`LOCI_UNITS` (in µm, N, N·µm), one entry per traced row in the
        order of the parameter, NaN where a point does not exist or is not resolved there
        (C within :data:`C_MARGIN` of the C boundary); the energies come with their error
        estimates (``*_error``, N·µm).
    events : list of dict
        The located events, each ``{"event": name, **columns}``.
    messages : list of str
        How each locus ended.
    branches : dict of str to Branch, optional
        The traced (nondimensional) loci of the chains, ``"A-B-D"`` and, where C exists,
        ``"A-B-C-D"``.
    rows : list of dict of str to float, optional
        The rows of ``columns`` as those chains' variables (``"A.q"``, ``"mu"``,
        ``"m_B"``, ...).
    """

    parameter: str
    columns: dict[str, np.ndarray]
    events: list[dict[str, Any]]
    messages: list[str]
    branches: dict[str, Branch] = field(default_factory=dict)
    rows: list[dict[str, float]] = field(default_factory=list, repr=False)

    def start_at(self, i: int) -> dict[str, dict[str, float]]:
        """Return row ``i``'s points as the ``start`` of :func:`trace_loci`.

        Parameters
        ----------
        i : int
            A row of the loci (its ``mu`` and ``m_B`` are in ``rows[i]``).

        Returns
        -------
        dict of str to dict of str to float
            ``{point: {variable: value}}`` of the nondimensional leg variables.
        """
        row = self.rows[i]
        out: dict[str, dict[str, float]] = {}
        for key, value in row.items():
            point, _, var = key.partition(".")
            if var and math.isfinite(value):
                out.setdefault(point, {})[var] = value
        return out


def _chain_value(model: ContactLoss, free: str, value):
    """A value of a locus's parameter (μ, or F'_N [N]) as the chain's (μ, or m_B)."""
    return value if free == "mu" else (model.F_N0 - value) / model.F_N0


def _user_value(model: ContactLoss, free: str, value):
    """The chain's parameter (μ, or m_B) as the locus's (μ, or F'_N [N])."""
    return value if free == "mu" else model.F_N0 - model.F_N0 * value  # ΔF_N kept exact


def _span(model: ContactLoss, parameter: str, span) -> tuple[str, float, float]:
    """The chain's parameter and the span (in the units of ``parameter``)."""
    if parameter not in LOCUS_PARAMETERS:
        raise ModelParameterError(
            f"parameter must be one of {sorted(LOCUS_PARAMETERS)}, got {parameter!r}"
        )
    free = LOCUS_PARAMETERS[parameter]
    here = model.mu0 if free == "mu" else model.F_Np
    if span is None:
        span = (here / 100, 100 * here) if free == "mu" else (here / 100, model.F_N0)
    try:
        lo, hi = (float(x) for x in span)
    except (TypeError, ValueError):
        raise ModelParameterError(
            f"span of {parameter} must be two numbers, got {span!r}"
        ) from None
    if not (0.0 < lo <= here <= hi < math.inf) or (free == "m_B" and hi > model.F_N0):
        raise ModelParameterError(
            f"span of {parameter} must hold the model's value {here!r} and lie in (0, "
            f"{'inf' if free == 'mu' else model.F_N0!r}], got {span!r}"
        )
    return free, lo, hi


def point_loci(
    model: ContactLoss,
    parameter: str = "mu",
    span: tuple[float, float] | None = None,
    *,
    at: Sequence[float] | np.ndarray = (),
    options: ContinuationOptions | None = None,
) -> Loci:
    """Trace the loci of A, B, D and C, and of the released energies, as a parameter varies.

    The loci start from the model's own path; each ends early where B reaches F'_T = 0, D
    disappears or A's stick zone vanishes (located, in ``events``, with the C boundary). A
    locus that stops for another reason (the levels of the body no longer resolve a point)
    is kept as far as it went, and ``messages`` says so.

    Parameters
    ----------
    model : ContactLoss
        The contact-loss path whose points are followed.
    parameter : {"mu", "reduced_normal_load"}, optional
        μ (default), or F'_N [N].
    span : tuple of (float, float), optional
        The parameter's range, holding the model's value (default: μ over (μ/100, 100μ),
        F'_N over (F'_N/100, F_N0) [N]).
    at : sequence of float, optional
        Values of the parameter that must be rows of the loci (located exactly).
    options : ContinuationOptions, optional
        Of the loci (default :data:`DEFAULT_OPTIONS`); the path they start from is traced
        with the path's own options at their ``rtol``.

    Returns
    -------
    Loci
        The loci: columns in µm, N and N·µm, events and messages.

    Raises
    ------
    ModelParameterError
        An unknown ``parameter``, or a ``span`` that does not hold the model's value.
    """
    _, lo, hi = _span(model, parameter, span)
    res = model.run(None if options is None else PATH_OPTIONS.replace(rtol=options.rtol))
    start = {name: res.legs[leg].point(row) for name, (leg, row) in res.point_rows.items()}
    start.pop("O", None)
    params = {"mu": model.mu0, "m_B": model.m_B}
    return trace_loci(model, parameter, (lo, hi), start, params, at, options)


def trace_loci(
    model: ContactLoss,
    parameter: str,
    span: tuple[float, float],
    start: Mapping[str, Mapping[str, float]],
    params: Mapping[str, float],
    at: Sequence[float] | np.ndarray = (),
    options: ContinuationOptions | None = None,
) -> Loci:
    """Trace the loci of :func:`point_loci` from given points.

    Parameters
    ----------
    model : ContactLoss
        The contact-loss path whose points are followed.
    parameter : {"mu", "reduced_normal_load"}
        μ, or F'_N [N].
    span : tuple of (float, float)
        The parameter's range, in its units.
    start : mapping of str to mapping of str to float
        Each of A, B, D (if it exists) and C (if it exists) as ``{point: {variable:
        value}}``: the nondimensional variables of the legs, as ``Loci.rows``.
    params : mapping of str to float
        ``mu`` and ``m_B`` = 1 − F'_N/F_N0 at ``start``.
    at : sequence of float, optional
        Values of the parameter that must be rows of the loci.
    options : ContinuationOptions, optional
        Of the loci (default :data:`DEFAULT_OPTIONS`); their ``rtol`` sets the tolerances
        of the traces and the quadrature of the energies (``quad_tol``).

    Returns
    -------
    Loci
        The loci: columns in µm, N and N·µm, events and messages.
    """
    free = LOCUS_PARAMETERS[parameter]
    lo, hi = sorted(_chain_value(model, free, float(v)) for v in span)
    o = options or DEFAULT_OPTIONS
    # (a path started at the deepest reduction may have F'_T a rounding below 0)
    t_B, t_A = start["B"]["t"], start["A"]["t"]
    bounds = {free: (lo, hi), "B.t": (min(0.0, t_B) if t_B > -1e-9 * abs(t_A) else 0.0, math.inf)}
    if math.isfinite(model.levels.slip_limit(model.levels.p0)):
        # a body that slides as a whole (a sphere): A's stick zone must not vanish, and D
        # ceases to exist where its stick zone does (the locus ends there)
        bounds.update({"A.q": stick_bounds(model.levels), "D.q": stick_bounds(model.levels)})
    kw: dict[str, Any] = {"bounds": bounds, "options": o, "throw": False}
    if len(at):
        kw["targets"] = {free: [_chain_value(model, free, float(v)) for v in at]}
    params = dict(params)
    names = "ABD" if "D" in start else "AB"
    chain = path_chain(model, params, start["A"]["q"], names)
    mu0, ia = model.mu0, chain.unknowns.index("A.t")
    # F_A = μF'_N: t_A·μ0 = μ·(1 − m_B) (t = F_T/(μ0 F_N0), m = 1 − F_N/F_N0)
    boundary = Event(lambda u, p: u[ia] * mu0 - p["mu"] * (1.0 - p["m_B"]), label="C boundary")
    with quiet_stops():
        main = locus(
            chain,
            {x: start[x] for x in names},
            free=free,
            events=[boundary],
            scales=_sizes(model, names, free),
            **kw,
        )
    branches = {"-".join(names): main}
    chains = {"-".join(names): chain}
    notes: list[str] = []
    if "D" in start:
        _locus_c(model, parameter, (start, params, main), kw, branches, chains, notes)
    keep = {_chain_value(model, free, float(v)) for v in at}
    return _assemble(model, parameter, free, branches, chains, o, keep, notes)


def _sizes(model: ContactLoss, names: str, free: str) -> dict[str, float]:
    """Typical sizes of the reductions m (and m_B): 1, that of F_N/F_N0, not their value (0
    at A, where A.m and A.p = p0 + O(A.m) carry a rounding that would set their sizes; tiny
    for a tiny reduction)."""
    out = {f"{x}.m": 1.0 for x in names} | {"A.p": max(1.0, abs(model.levels.p0))}
    # Â_SL: 1, a share of the real contact area. Taken from its value, a share that rounding
    # leaves as noise (A's -1e-24 on a Gaussian surface of σ* = 0.01 µm: error bound inf)
    # sized itself to the noise, and the locus of C crept after it (400 steps, work limit)
    out |= {f"{x}.A_SL": 1.0 for x in names}
    # μ: its value at the start, not the width of its span (a span up to 1e9 sized μ 1e9:
    # steps of 1e8 in μ from μ = 0.1, and a derivative check across them that failed the
    # locus at its start); a size only grows along the locus
    return out | ({"m_B": 1.0} if free == "m_B" else {"mu": model.mu0})


def _locus_c(model: ContactLoss, parameter, at, kw, branches, chains, notes) -> None:
    """The locus of the chain with C (``branches["A-B-C-D"]``), from the first of its seeds
    (:func:`_c_seeds`) where it can start: a seed where the chain's Jacobian is singular
    (:class:`~cusp.continuation.SingularPointError`) is passed over for the next; ``notes``
    says so when none starts."""
    free, o = LOCUS_PARAMETERS[parameter], kw["options"]
    mu0, tried = model.mu0, []
    start, params0, main = at
    for pt, params in _c_seeds(model, start, params0, main, o):
        chain_c = path_chain(model, params, pt["A"]["q"], "ABCD")
        near = Event(_c_margin(chain_c.unknowns.index("A.t"), mu0), direction=-1,
                     label="C unresolved", terminal=True)  # fmt: skip
        try:
            with quiet_stops():
                branches["A-B-C-D"] = locus(
                    chain_c, pt, free=free, events=[near], scales=_sizes(model, "ABCD", free), **kw
                )
        except SingularPointError:
            tried.append(repr(_user_value(model, free, params[free])))
            continue
        chains["A-B-C-D"] = chain_c
        return
    if tried:
        notes.append(
            f"the locus of C is not traced: where C exists, each start tried ({parameter} = "
            f"{', '.join(tried)}) is a branch point of the loci's equations"
        )


def _c_margin(ic: int, mu0: float):
    """The event function of "C unresolved": F_A/(μF'_N) = 1 − :data:`C_MARGIN`."""

    def margin(u, p) -> float:
        return 1.0 - u[ic] * mu0 / (p["mu"] * (1.0 - p["m_B"])) - C_MARGIN

    return margin


_C_SEEDS = 3
"""How many rows of the first locus are tried as the start of the locus of C."""


def _c_seeds(model, start, params, main: Branch, o):
    """Where the chain with C may start: the given C, or (if there is none) C traced on the
    reloading leg at the rows of the first locus farthest inside the region where C exists
    (at most :data:`_C_SEEDS`: the farthest, then rows a quarter and half way down the
    rows where C exists, ordered by depth); none where C exists nowhere along it.
    Yields (start values, chain parameters)."""
    if "C" in start and "D" in start:
        yield {x: start[x] for x in "ABCD"}, dict(params)
        return
    limit = main["mu"] * (1.0 - main["m_B"])  # μF'_N/(μ0 F_N0)
    depth = (limit - main["A.t"] * model.mu0) / limit  # > 0 where C exists
    rows = sorted(np.flatnonzero(depth > 0.0), key=lambda i: -depth[i])
    if not rows:
        return
    # (spread over the region: a branch point at one row is often one at its neighbours)
    picks = dict.fromkeys(rows[len(rows) * k // (2 * _C_SEEDS - 2)] for k in range(_C_SEEDS))
    for i in picks:
        seed = _c_at_row(model, main.point(int(i)), o)
        if seed is not None:
            yield seed


def _c_at_row(model: ContactLoss, row, o):
    """C traced on the reloading leg at a row of the first locus (None if that leg does not
    reach F'_T = F_A there), with the row's A, B and D."""
    params = {"mu": row["mu"], "m_B": row["m_B"]}
    pt = {x: {k[2:]: v for k, v in row.items() if k.startswith(x + ".")} for x in "ABD"}
    prob = model.problem("BC", start=pt["B"]["g"], constant=params["m_B"], mu=params["mu"])
    bounds = {"t": (-math.inf, pt["A"]["t"])}
    if math.isfinite(model.levels.slip_limit(pt["B"]["p"])):
        bounds["q"] = stick_bounds(model.levels)
    u0 = [pt["B"][v] for v in prob.unknowns]
    bc = trace(prob, u0, free="g", bounds=bounds, options=o, throw=False)
    if bc.status != "bound" or bc.special("endpoint")[-1].with_respect_to != "t":
        return None
    cols = points_at(prob, bc, "t", [pt["A"]["t"]], options=o)
    pt["C"] = {k: float(v[0]) for k, v in cols.items()}
    return pt, params


def _assemble(
    model: ContactLoss, parameter: str, free: str, branches, chains, o, keep=(), notes=()
):
    """The rows of the loci (the chain with C where it ran, the other beyond), polished to
    rounding, their physical columns, error bounds and energies (to the options'
    ``quad_tol``; at most :data:`ENERGY_ROWS` rows besides those at the values ``keep`` of
    the chain's parameter), the events and how each locus ended."""
    main = branches[next(iter(branches))]
    with_c = branches.get("A-B-C-D")
    rows: list[tuple[dict[str, float], Any]] = []  # (row, its chain)
    events: list[tuple[dict[str, Any], Any]] = []
    messages = [_ending(model, parameter, free, name, br) for name, br in branches.items()]
    messages += notes
    inside = (math.inf, -math.inf)
    if with_c is not None and len(with_c) > 1:
        # (widened by rounding: both loci end at a common bound, F'_T = 0, located twice)
        ends = float(np.min(with_c[free])), float(np.max(with_c[free]))
        inside = (ends[0] * (1.0 - 1e-9), ends[1] * (1.0 + 1e-9))
        chain_c = chains["A-B-C-D"]
        rows += [(polish_row(chain_c, with_c.point(i)), chain_c) for i in range(len(with_c))]
        events += [(polish_row(chain_c, ev), chain_c) for ev in _events(with_c)]
        for sp in with_c.special("event", label="C unresolved"):
            at = _user_value(model, free, sp.values[free])
            messages.append(
                f"C is not reported from {parameter} = {at!r} on towards "
                f"the C boundary, where F_A = (1 - {C_MARGIN:g}) mu F'_N: closer to it, "
                "rounding decides whether C exists"
            )
    first = chains[next(iter(chains))]
    rows += [
        (polish_row(first, main.point(i)), first)
        for i in range(len(main))
        if not inside[0] <= main[free][i] <= inside[1]
    ]
    located = [(ev["event"], ev[free]) for ev, _ in events]
    events += [
        (polish_row(first, ev), first)
        for ev in _events(main)
        if not inside[0] <= ev[free] <= inside[1]
        and not any(n == ev["event"] and abs(v - ev[free]) <= 1e-9 * abs(v) for n, v in located)
    ]
    kept = [r[free] in keep for r, _ in rows]  # (before the rows move to the reported F'_N)
    if free == "m_B":  # each row at the F'_N it reports (module docstring)
        rows = [(polish_row(c, _at_reported_load(model, r)), c) for r, c in rows]
        events = [(polish_row(c, _at_reported_load(model, r)), c) for r, c in events]
    order = sorted(range(len(rows)), key=lambda i: _user_value(model, free, rows[i][0][free]))
    events.sort(key=lambda r: _user_value(model, free, r[0][free]))
    stride = -(-len(rows) // ENERGY_ROWS)  # (ceiling division)
    if stride > 1:
        messages.append(
            f"the released energies are integrated at one row in {stride} of the loci "
            f"({len(range(0, len(rows), stride))} of {len(rows)} rows, the work limit being "
            f"{ENERGY_ROWS} rows); the rows between are left empty"
        )
    worst: dict[tuple[str, str], tuple[float, str]] = {}  # the points' largest error bounds
    table = [
        _physical(
            model, *rows[i], o.quad_tol, messages, worst, integrate=k % stride == 0 or kept[i]
        )
        for k, i in enumerate(order)
    ]
    rows = [rows[i] for i in order]
    columns = {key: np.array([r[key] for r in table]) for key in LOCI_UNITS}
    event_rows = [
        {"event": ev.pop("event"), **_physical(model, ev, chain, o.quad_tol, messages, worst)}
        for ev, chain in events
    ]
    messages += _bound_messages(worst, max(point_tol(o.rtol), 1e-12), note_rtol(o.quad_tol))
    return Loci(parameter, columns, event_rows, messages, dict(branches), [r for r, _ in rows])


def _at_reported_load(model: ContactLoss, row: dict[str, Any]) -> dict[str, Any]:
    """``row`` moved to m_B = (F_N0 − F'_N)/F_N0 of the F'_N it reports, the float F_N0 −
    F_N0·m_B: that F'_N rounds ΔF_N to ε F_N0, which at a reduction of 1e-9 F_N0 is 1e-7 of
    it (and 2e-7 of the released energies, ∝ ΔF_N²). As :class:`ContactLoss` forms m_B."""
    load = _user_value(model, "m_B", row["m_B"])
    return {**row, "m_B": (model.F_N0 - load) / model.F_N0}


def _bound_messages(worst, threshold: float, energy_threshold: float) -> list[str]:
    """A message per quantity of the loci whose error bound exceeds ``threshold`` somewhere
    (relative; an energy's: ``energy_threshold``), with the largest bound and where it is."""
    out = []
    for (point, name), (rel, at) in sorted(worst.items()):
        if point == "energy" and rel > energy_threshold:
            out.append(
                f"the {name.replace('_', '-')} energies along the loci are resolved only to "
                f"their error bounds, up to {rel:.1e} relative (at {at}), above "
                f"{energy_threshold:g}: the points they are integrated between are resolved "
                "only so far there"
            )
        elif point != "energy" and rel > threshold:
            out.append(
                f"{name} of {point} along the loci is resolved only to its error bound, up to "
                f"{rel:.1e} relative (at {at}), above {threshold:g}: float64 "
                "does not resolve it better there"
            )
    return out


def _ending(model: ContactLoss, parameter: str, free: str, name: str, br: Branch) -> str:
    """How a locus ended at each of its two ends, in the scene's terms (the events of the
    path, the end of the span, or why it stopped short; never the chain's variables)."""
    ends = []
    for row, status in (
        (0, br.info.get("status_minus")),
        (len(br) - 1, br.info.get("status_plus")),
    ):
        at = f"{parameter} = {_user_value(model, free, float(br[free][row])):.10g}"
        wrt = next(
            (
                sp.with_respect_to
                for sp in br.special_points
                if sp.index == row and sp.kind in ("endpoint", "event")
            ),
            None,
        )
        if status == "bound" and wrt == free:
            ends.append(f"to the end of the range, {at}")
        elif status == "bound" and wrt in _BOUND_EVENTS:
            ends.append(f"to {at}, where {_BOUND_EVENTS[wrt]}")
        elif status == "terminal_event":
            ends.append(f"to {at}, where C is no longer resolved (near the C boundary)")
        elif status == "bound":
            ends.append(f"to {at}")
        else:
            why = STATUSES.get(str(status), f"it ended ({status})")
            if status == "max_steps":
                why = f"the work limit of a locus ({LOCUS_STEPS} steps each way) was reached"
            ends.append(f"to {at}, where it stopped short: {why}")
    return f"locus of {name}: " + "; ".join(
        f"{d} {e}" for d, e in zip(("one way", "the other way"), ends)
    )


def _events(br: Branch) -> list[dict[str, Any]]:
    """The located events of a locus and its ends at bounds that are events of the path."""
    out = []
    for sp in br.special_points:
        if sp.kind == "event" and sp.label != "C unresolved":
            out.append({"event": sp.label, **sp.values})
        elif sp.kind == "endpoint" and sp.with_respect_to in _BOUND_EVENTS:
            out.append({"event": _BOUND_EVENTS[sp.with_respect_to], **sp.values})
    return out


def _physical(
    model: ContactLoss,
    row: dict[str, float],
    chain,
    quad_tol: float,
    messages: list[str],
    worst: dict[tuple[str, str], tuple[float, str]],
    integrate: bool = True,
) -> dict[str, float]:
    """One row of a locus in physical units (NaN for a point the row does not carry), with
    the released energies at it (to ``quad_tol``; NaN where not resolved to
    :func:`~._loci_energy.flag_rtol`, or not integrated, with a message saying so, or not
    ``integrate``: beyond the work limit :data:`ENERGY_ROWS`); the largest relative error
    bounds of the points' quantities are kept in ``worst``."""
    sg, st = model.scales["g"], model.scales["t"]
    out = {"mu": row["mu"], "reduced_normal_load": _user_value(model, "m_B", row["m_B"])}
    for x in "ABCD":
        out[f"g_{x}"] = row.get(f"{x}.g", math.nan) * sg
        out[f"F_{x}"] = row.get(f"{x}.t", math.nan) * st
        out[f"A_SL_{x}"] = row.get(f"{x}.A_SL", math.nan)
    errors = chain_errors(model, chain, row)
    where = f"mu = {row['mu']!r}, F'_N = {out['reduced_normal_load']!r} N"
    _track_bounds(model, row, errors, out, worst, where)
    if not integrate:
        nan = math.nan
        return out | dict.fromkeys(
            [f"{k}_{v}" for k in ("snap_back", "snap_through") for v in ("energy", "error")], nan
        )
    try:
        e = energies(model.levels, row, row["mu"], model.mu0, model.g_A, _ROW_TOL, quad_tol, errors)
    except EnergyError as exc:
        e = {k: math.nan for k in ("snap_back", "snap_through")}
        e |= {"snap_back_error": math.nan, "snap_through_error": math.nan}
        _note(messages, f"energies not given at {where} (left empty): {exc}")
    flag = flag_rtol(quad_tol)
    for kind in ("snap_back", "snap_through"):
        value, error = e[kind] * st * sg, e[f"{kind}_error"] * st * sg
        if error > flag * abs(value):
            note = (
                f"{kind} energies whose error bound exceeds {flag:g} relative are left "
                f"empty (the points they are integrated between are resolved only so far): "
                f"first at {where}"
            )
            if not any(m.startswith(note[:40]) for m in messages):
                messages.append(note)
            value = math.nan
        elif error > note_rtol(quad_tol) * abs(value):  # (given, with its bound named)
            rel = error / abs(value)
            if rel > worst.get(("energy", kind), (-1.0, ""))[0]:
                worst["energy", kind] = (rel, where)
        out[f"{kind}_energy"], out[f"{kind}_error"] = value, error
    if ("D.q" in row and math.isnan(e["snap_back"])) or (
        "C.q" in row and math.isnan(e["snap_through"])
    ):
        _note(messages, f"energies not resolved at {where} (left empty)")
    return out


#: the relative error of a row's levels once polished (where the chain's bounds are not used)
_ROW_TOL = 64.0 * float(np.finfo(float).eps)


def _note(messages: list[str], note: str) -> None:
    if note not in messages:
        messages.append(note)


def _track_bounds(model, row, errors, out, worst, where: str) -> None:
    """Keep in ``worst`` the largest relative error bound of each point's quantities."""
    names = {"g_T": "g", "F_T": "F", "A_SL": "A_SL"}
    for x in "ABCD":
        if f"{x}.t" not in row:
            continue
        values = {v: row[f"{x}.{v}"] for v in ("g", "t", "m", "A_SL", "p", "q")}
        bounds = point_bounds(model, values, {v: errors[f"{x}.{v}"] for v in values})
        for quantity, column in names.items():
            value = out[f"{column}_{x}"]
            rel = relative(quantity, value, bounds[quantity], {})
            if rel > worst.get((x, quantity), (-1.0, ""))[0]:
                worst[x, quantity] = (rel, where)
