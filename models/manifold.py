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

Units as in :mod:`cusp.models.contact_loss`: µm, N.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from cusp.continuation import Branch, ChainPoint, ContinuationOptions, Event, PointChain, locus

from .contact_loss import ContactLoss, ContactLossResult
from .errors import ModelParameterError

__all__ = ["LOCUS_PARAMETERS", "Loci", "point_loci"]

#: the parameters a locus can be traced in: name -> the chain's parameter (μ; F'_N/F_N0)
LOCUS_PARAMETERS = {"mu": "mu", "reduced_normal_load": "n_B"}
#: where the locus of C stops: g_C = C_G_MAX·g_A (C's slip diverges at the C boundary)
C_G_MAX = 100.0
#: the bounds of a locus that are events of the path
_BOUND_EVENTS = {"B.t": "F'_T = 0", "D.q": "D disappears", "A.q": "A slides"}


@dataclass(frozen=True)
class Loci:
    """The loci of the points of the path (:func:`point_loci`).

    ``parameter``: ``"mu"`` or ``"reduced_normal_load"``; ``columns``: physical columns
    along the locus, in the order of the parameter: the parameter, then ``g_X``, ``F_X``,
    ``A_SL_X`` for each traced point X (µm, N); ``events``: the located events, each
    ``{"event", parameter, and the columns there}``; ``branch``: the traced (nondimensional)
    locus of the chain; ``c_locus``: the columns and events of the locus of A, B, D and C
    (while C exists, up to g_C = :data:`C_G_MAX`·g_A), None if there is no C at the model's
    own parameters."""

    parameter: str
    columns: dict[str, np.ndarray]
    events: list[dict[str, Any]]
    branch: Branch
    points: tuple[str, ...]
    c_locus: tuple[dict[str, np.ndarray], list[dict[str, Any]]] | None = None


def _chain(
    model: ContactLoss, res: ContactLossResult, with_c: bool
) -> tuple[PointChain, dict, tuple]:
    """The chain of A, B, D (where D exists) and, ``with_c``, C, and its start."""
    raw = {name: res.legs[leg].point(row) for name, (leg, row) in res.point_rows.items()}
    n_B = model.F_Np / model.F_N0
    A, B = raw["A"], raw["B"]
    oa = model.problem("OA", start=1.0)
    ab = model.problem("AB", start=n_B, constant=A["q"])
    bc = model.problem("BC", start=1.0, constant=n_B)
    points = [
        ChainPoint("A", oa, "g", ("g", 1.0)),
        ChainPoint("B", ab, "n", ("n", "n_B"), links={"q_A": ("A", "q")}),
    ]
    start = {"A": A, "B": B}
    if "D" in raw:
        points.append(ChainPoint("D", bc, "g", ("g", 1.0), links={"n_B": ("B", "n")}))
        start["D"] = raw["D"]
    if with_c:
        points.append(ChainPoint("C", bc, "g", ("t", ("A", "t")), links={"n_B": ("B", "n")}))
        start["C"] = raw["C"]
    chain = PointChain(points, {"mu": model.mu0, "n_B": n_B})
    return chain, start, tuple(pt.name for pt in points)


def point_loci(
    model: ContactLoss,
    parameter: str = "mu",
    span: tuple[float, float] | None = None,
    *,
    options: ContinuationOptions | None = None,
) -> Loci:
    """The loci of A, B, D (and C while it exists) as ``parameter`` (``"mu"`` or
    ``"reduced_normal_load"`` [N]) runs over ``span`` (default: μ over (μ/100, 100μ), F'_N
    over (F'_N/100, F_N0)), from the model's own path; the locus ends early where B
    reaches F'_T = 0 or C ceases to exist (both located, in ``events``)."""
    if parameter not in LOCUS_PARAMETERS:
        raise ModelParameterError(
            f"parameter must be one of {sorted(LOCUS_PARAMETERS)}, got {parameter!r}"
        )
    free = LOCUS_PARAMETERS[parameter]
    scale = 1.0 if free == "mu" else model.F_N0
    here = model.mu0 if free == "mu" else model.F_Np
    lo, hi = (
        span
        if span is not None
        else ((here / 100, 100 * here) if free == "mu" else (here / 100, model.F_N0))
    )
    if not (0.0 < lo <= here <= hi) or (free == "n_B" and hi > model.F_N0):
        raise ModelParameterError(
            f"span of {parameter} must hold the model's value {here!r} and lie in (0, "
            f"{'inf' if free == 'mu' else model.F_N0!r}], got {span!r}"
        )
    res = model.run(options)
    o = options or ContinuationOptions(ds=0.02, ds_max=0.1)
    bounds = {free: (lo / scale, hi / scale), "B.t": (0.0, math.inf)}
    if math.isfinite(model.levels.slip_limit(model.levels.p0)):
        # a body that slides as a whole (a sphere): A's stick zone must not vanish, and D
        # ceases to exist where its stick zone does (the locus ends there)
        bounds.update({"A.q": (0.0, math.inf), "D.q": (0.0, math.inf)})
    chain, start, names = _chain(model, res, with_c=False)
    mu0, ia = model.mu0, chain.unknowns.index("A.t")
    # F_A = μF'_N: t_A·μ0 = μ·n_B (t = F_T/(μ0 F_N0), n = F_N/F_N0)
    boundary = Event(lambda u, p: u[ia] * mu0 - p["mu"] * p["n_B"], label="C boundary")
    br = locus(chain, start, free=free, bounds=bounds, events=[boundary], options=o)
    loci = _physical_loci(parameter, free, scale, model.scales, br, names)
    c_loci = None
    if res.points["C"] is not None:
        # C's slip grows without bound towards the C boundary: its locus stops at C_G_MAX·g_A
        chain_c, start_c, names_c = _chain(model, res, with_c=True)
        bounds_c = {**bounds, "C.g": (-math.inf, C_G_MAX)}
        # (or earlier, where the body's levels stop resolving C: kept as far as it went)
        br_c = locus(chain_c, start_c, free=free, bounds=bounds_c, options=o, throw=False)
        c_loci = _physical_loci(parameter, free, scale, model.scales, br_c, names_c)
    return Loci(parameter, loci[0], loci[1], br, names, c_loci)


def _physical_loci(parameter, free, scale, s, br: Branch, names):
    """Physical columns along a locus (sorted by the parameter) and its located events."""
    order = np.argsort(br[free], kind="stable")

    def cols(row: Any, take) -> dict[str, Any]:  # a Branch, or one point's values
        out = {parameter: take(row[free]) * scale}
        for x in names:
            out[f"g_{x}"] = take(row[f"{x}.g"]) * s["g"]
            out[f"F_{x}"] = take(row[f"{x}.t"]) * s["t"]
            out[f"A_SL_{x}"] = take(row[f"{x}.A_SL"])
        return out

    columns = cols(br, lambda c: np.asarray(c)[order])
    events = []
    for sp in br.special_points:
        if sp.kind == "event":
            events.append({"event": sp.label, **cols(sp.values, float)})
        elif sp.kind == "endpoint" and sp.with_respect_to in _BOUND_EVENTS:
            events.append({"event": _BOUND_EVENTS[sp.with_respect_to], **cols(sp.values, float)})
    return columns, events
