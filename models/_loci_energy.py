"""Released energies at a point of a locus, from the levels of its points A, B, C, D.

On the legs AB and BC one level is constant: the stick level q = q_A on AB (the frozen stick
zone) and the contact level p = p_B on BC (F_N = F'_N), so each leg is an explicit curve in
its other level (module docstring of :mod:`cusp.models.contact_loss`, nondimensional):

* AB: 1 − m = exp ℓ(p), t = (μ/μ0) (1 − m) F̂_T(p, q_A),   g = (μ/g_A) s(p, q_A);
* BC: m = m_B,         t = (μ/μ0) (1 − m_B) F̂_T(p_B, q), g = (μ/g_A) s(p_B, q).

The areas are integrals in g of the gap between two such curves, ABD = ∫_{g_B}^{g_A}
(F_AB − F_BC) dg and ABC − ABD = ∫_{g_A}^{g_C} (F_A − F_BC) dg, by Gauss–Legendre with the
nodes doubled until two rules agree; at each node the level is found from g by safeguarded
Newton inside the bracket the leg's end points give (g is monotone along each leg). No
continuation problem is solved here: the locus supplies the end points, exact, and the legs
between them are explicit. The gap is evaluated as a difference, so its rounding error
(≈ ε·F·Δg, which dominates for very small reductions where the area shrinks like ΔF_N², and
at small slips where the legs' slopes agree to ~g_A over the gross-sliding slip) is added to
the reported error estimate.

Levels that give the areas in closed form (the optional ``leg_areas`` of
:mod:`cusp.models.protocol`: the sphere's, written in the differences between the levels of
A, B, C, D so that nothing cancels) are used instead of the quadrature (:func:`energies`).
"""

from __future__ import annotations

import inspect
import math
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from cusp.continuation import (
    RTOL_DEFAULT,
    ChainPoint,
    ConvergenceError,
    PointChain,
    points_at,
    quadrature_tol,
)

from ._point_errors import chain_errors, polish

#: two Gauss-Legendre rules agreeing to this (relative) end the doubling, unless told
#: otherwise: the quadrature tolerance of the default ``rtol`` (1e-13); a path or a locus
#: passes its options' :attr:`~cusp.continuation.ContinuationOptions.quad_tol`
QUAD_RTOL = quadrature_tol(RTOL_DEFAULT)
#: an energy whose error estimate exceeds this (relative) comes with a message (see
#: :func:`flag_rtol`)
ENERGY_RTOL = 1e-8
_MAX_NODES = 512
_EPS = np.finfo(float).eps
_RULES: dict[int, tuple[np.ndarray, np.ndarray]] = {}


def _rule(n: int) -> tuple[np.ndarray, np.ndarray]:
    if n not in _RULES:
        _RULES[n] = np.polynomial.legendre.leggauss(n)
    return _RULES[n]


def _invert(fun: Callable[[float], tuple[float, float]], target: float, lo: float, hi: float):
    """The level x in [lo, hi] (either order) with fun(x)[0] = target, fun monotone there and
    the target inside; safeguarded Newton (bisection when a step leaves the bracket)."""
    f_lo, f_hi = fun(lo)[0] - target, fun(hi)[0] - target
    if f_lo == 0.0:
        return lo
    if f_hi == 0.0:
        return hi
    if f_lo * f_hi > 0.0:
        # the target at an end of the bracket but off it by rounding, or g not monotone
        near = min((abs(f_lo), lo), (abs(f_hi), hi))
        if near[0] <= 64.0 * _EPS * max(abs(target), 1.0):
            return near[1]
        raise ArithmeticError("the slip is not monotone along the leg")
    x = lo + (hi - lo) * f_lo / (f_lo - f_hi)
    for _ in range(100):
        f, df = fun(x)
        f -= target
        if f == 0.0:
            return x
        if (f < 0.0) == (f_lo < 0.0):
            lo, f_lo = x, f
        else:
            hi = x
        step = f / df if df != 0.0 else math.inf
        new = x - step
        if not (min(lo, hi) < new < max(lo, hi)):
            new = 0.5 * (lo + hi)
        if abs(new - x) <= 4.0 * _EPS * max(abs(x), abs(new)) or new in (lo, hi):
            return new
        x = new
    return x


def flag_rtol(quad_tol: float = QUAD_RTOL) -> float:
    """The relative error estimate above which an energy is flagged (a message on a path,
    an empty cell in a locus): :data:`ENERGY_RTOL`, or a hundred times the quadrature
    tolerance asked for when that is looser, so that an energy integrated to the accuracy
    asked for is not flagged for it (only for a ``quad_tol`` above 1e-10: not reached within
    ``rtol``'s range, whose loosest quadrature is 1e-11)."""
    return max(ENERGY_RTOL, 100.0 * quad_tol)


def note_rtol(quad_tol: float = QUAD_RTOL) -> float:
    """The relative error bound above which an energy that is given comes with a message
    naming its bound: the documented accuracy, 1e-12 (as the points'), or ten times the
    quadrature tolerance asked for when that is looser (1e-10 at ``rtol`` = 1e-2). Above
    :func:`flag_rtol` a locus leaves the energy empty instead."""
    return max(1e-12, 10.0 * quad_tol)


def gauss_legendre(
    f: Callable[[np.ndarray], np.ndarray],
    a: float,
    b: float,
    floor: float = 0.0,
    rtol: float = QUAD_RTOL,
) -> tuple[float, float]:
    """∫_a^b f by Gauss–Legendre, nodes doubled from 8 until two rules agree to
    ``rtol``·|value| or to ``floor`` (the rounding level of the integrand); returns the value
    and an error estimate (the last difference, the error of the coarser rule, plus the
    floor)."""
    if a == b:
        return 0.0, 0.0
    prev = None
    n = 8
    while True:
        x, w = _rule(n)
        val = 0.5 * (b - a) * float(w @ f(0.5 * (b - a) * x + 0.5 * (a + b)))
        if prev is not None:
            diff = abs(val - prev)
            if diff <= max(rtol * abs(val), floor) or n >= _MAX_NODES:
                return val, diff + floor
        prev = val
        n *= 2


class LegCurves:
    """The legs AB and BC of one point of a locus (``row``: the chain's values, nondimensional
    ``{"A.q", "B.p", ...}``; ``mu``; ``mu0``, ``g_A``: the model's)."""

    def __init__(self, levels, row: Mapping[str, float], mu: float, mu0: float, g_A: float):
        self.L = levels
        self.m = mu / g_A
        self.k = mu / mu0
        self.qA, self.pA, self.pB = row["A.q"], row["A.p"], row["B.p"]
        self.nB = 1.0 - row["B.m"]  # F'_N/F_N0
        self.row = row

    def g_ab(self, p: float) -> tuple[float, float]:
        s, ds, _ = self.L.slip(p, self.qA)
        return self.m * s, self.m * ds

    def g_bc(self, q: float) -> tuple[float, float]:
        s, _, ds = self.L.slip(self.pB, q)
        return self.m * s, self.m * ds

    def t_ab(self, g: float) -> float:
        p = _invert(self.g_ab, g, self.pA, self.pB)
        return (
            self.k * math.exp(self.L.log_normal_load(p)[0]) * self.L.tangential_ratio(p, self.qA)[0]
        )

    def t_bc(self, g: float, q_end: float) -> float:
        q = _invert(self.g_bc, g, self.row["B.q"], q_end)
        return self.k * self.nB * self.L.tangential_ratio(self.pB, q)[0]


def _no_energies() -> dict[str, float]:
    """The energies and their errors, all NaN (not computed)."""
    return dict.fromkeys(
        ("snap_back", "snap_through", "snap_back_error", "snap_through_error"), math.nan
    )


def _has_d(row: Mapping[str, float]) -> bool:
    """True if the row carries the point D (without it, no area ABD, hence none at all)."""
    return "D.q" in row and math.isfinite(row["D.q"])


class EnergyError(ArithmeticError):
    """The released energies could not be integrated on the legs (the message says why)."""


def _accepts(func, name: str) -> bool:
    try:
        return name in inspect.signature(func).parameters
    except (TypeError, ValueError):
        return False


def energies(
    levels,
    row: Mapping[str, float],
    mu: float,
    mu0: float,
    g_A: float,
    state_tol: float,
    quad_tol: float = QUAD_RTOL,
    errors: Mapping[str, float] | None = None,
) -> dict[str, float]:
    """Snap-back (area ABD) and snap-through (area ABC) energies, nondimensional (times
    μ0 F_N0 g_A for N·µm), with error bounds (``*_error``); NaN where D or C is missing
    from ``row``. ``state_tol``: the points' own error (relative: the tolerance they were
    converged to); ``errors``: the absolute errors of the row's unknowns
    (:func:`~._point_errors.chain_errors`), used instead where the levels take them.
    ``quad_tol``: the relative tolerance of the quadratures. Raises :class:`EnergyError`
    where the levels do not resolve the legs.

    Levels with ``leg_areas`` (the sphere's, the rough surfaces', :mod:`cusp.models.protocol`)
    give the areas with their own error bounds; the others are integrated along the legs
    (:func:`quadrature_energies`)."""
    out = _no_energies()
    if not _has_d(row):
        return out
    closed = getattr(levels, "leg_areas", None)
    if closed is None:
        return quadrature_energies(levels, row, mu, mu0, g_A, state_tol, quad_tol)
    q_C = row.get("C.q", math.nan)  # NaN: no C (then no ABC)
    kw: dict[str, Any] = {}
    if _accepts(closed, "quad_tol"):
        kw["quad_tol"] = quad_tol
    if errors is not None and _accepts(closed, "errors"):
        kw["errors"] = tuple(errors.get(k, 0.0) for k in ("A.p", "A.q", "B.p", "D.q", "C.q"))
    abd, dc = closed(row["A.p"], row["A.q"], row["B.p"], row["D.q"], q_C, state_tol, **kw)
    unit = (mu / mu0) * (mu / g_A)  # ∫ T ds [µm] -> ∫ t dg (LegCurves)
    if math.isfinite(abd[0]):
        out["snap_back"] = unit * abd[0]
        out["snap_back_error"] = unit * abd[1] + 4.0 * _EPS * abs(out["snap_back"])
    if math.isfinite(abd[0]) and math.isfinite(dc[0]):
        out["snap_through"] = unit * (abd[0] + dc[0])
        err = unit * (abd[1] + dc[1]) + 4.0 * _EPS * abs(out["snap_through"])
        out["snap_through_error"] = err
    return out


def quadrature_energies(
    levels,
    row: Mapping[str, float],
    mu: float,
    mu0: float,
    g_A: float,
    state_tol: float,
    quad_tol: float = QUAD_RTOL,
    errors: Mapping[str, float] | None = None,
) -> dict[str, float]:
    """:func:`energies` by quadrature on the legs (module docstring), for any levels
    (``errors`` is not used: the points' error is taken as ``state_tol``).

    The estimate adds to the quadrature's the rounding of the gap and the effect of the
    points' own error (``state_tol``, relative to max(1, |level|)), both of order F·Δg: an
    area much smaller than F·Δg (a tiny reduction) is resolved only to their ratio."""
    out = _no_energies()
    if not _has_d(row):
        return out
    legs = LegCurves(levels, row, mu, mu0, g_A)
    g_B, t_A, t_B = row["B.g"], row["A.t"], row["B.t"]
    q_D = row["D.q"]
    try:
        floor = 64.0 * _EPS * (abs(t_A) + abs(t_B)) * abs(1.0 - g_B)
        # the levels carry their rounding, relative to their own size (large far in a tail)
        size = max(1.0, abs(row["A.q"]), abs(row["B.p"]))
        state = state_tol * size * (abs(t_A) + abs(t_B)) * abs(1.0 - g_B)

        def gap(gs):
            return np.array([legs.t_ab(g) - legs.t_bc(g, q_D) for g in gs])

        abd, abd_err = gauss_legendre(gap, g_B, 1.0, floor, quad_tol)
        abd_err += state
        out["snap_back"], out["snap_back_error"] = abd, abd_err
        if math.isfinite(row.get("C.q", math.nan)):  # C in the row: ABC too
            g_C, q_C = row["C.g"], row["C.q"]
            floor_c = 64.0 * _EPS * abs(t_A) * abs(g_C - 1.0)

            def rest(gs):
                return np.array([t_A - legs.t_bc(g, q_C) for g in gs])

            extra, extra_err = gauss_legendre(rest, 1.0, g_C, floor_c, quad_tol)
            out["snap_through"] = abd + extra
            out["snap_through_error"] = (
                abd_err + extra_err + state_tol * size * abs(t_A) * (g_C - 1.0)
            )
    except (ArithmeticError, ValueError) as exc:
        raise EnergyError(f"the legs are not resolved between the points: {exc}") from exc
    return out


def path_points(model, A, B, C, D):
    """The points ``A``...``D`` of a path (:class:`~cusp.models.ContactLoss`, nondimensional,
    C and D None where missing) as one chain polished to rounding, with bounds on the
    absolute errors of its unknowns (:mod:`cusp.models._point_errors`). Returns (chain,
    row, errors), ``row`` the polished unknowns (``"B.t"``, ...) and parameters."""
    pts = {"A": A, "B": B} | ({"D": D} if D is not None else {}) | ({"C": C} if C else {})
    params = {"mu": model.mu0, "m_B": model.m_B}
    chain = path_chain(model, params, A["q"], "".join(pts))
    row = {f"{x}.{k}": v for x, pt in pts.items() for k, v in pt.items()} | params
    row = polish(chain, row)
    return chain, row, chain_errors(model, chain, row)


def path_energies(model, row, errors, quad_tol: float = QUAD_RTOL):
    """Areas ABD and ABC [N·µm] of a path (:class:`~cusp.models.ContactLoss`) from its
    polished points (``row``, ``errors``: :func:`path_points`) and their error bounds
    (:func:`energies`, to ``quad_tol``); with a message where a bound exceeds
    :func:`note_rtol` of its energy, or where an energy whose point exists could not be
    integrated. Returns (energies, errors, messages)."""
    energy: dict[str, float | None] = {"snap_back": None, "snap_through": None}
    error: dict[str, float | None] = {"snap_back": None, "snap_through": None}
    notes: list[str] = []
    if "D.q" not in row:  # no D, hence no C either
        return energy, error, notes
    unit = model.scales["t"] * model.scales["g"]
    try:
        e = energies(
            model.levels, row, model.mu0, model.mu0, model.g_A, 64.0 * _EPS, quad_tol, errors
        )
        failed = False
    except EnergyError as exc:
        e, failed = _no_energies(), True
        notes.append(f"the released energies are not given: {exc}")
    flag = note_rtol(quad_tol)
    exists = {"snap_back": True, "snap_through": "C.q" in row}
    for kind in energy:
        if not math.isfinite(e[kind]):
            if exists[kind] and not failed:
                notes.append(
                    f"the {kind.replace('_', '-')} energy is not given: its integral is not "
                    f"finite ({e[kind]!r}) although its landing point exists"
                )
            continue
        value, err = float(e[kind] * unit), float(e[f"{kind}_error"] * unit)
        energy[kind], error[kind] = value, err
        if err > flag * abs(value):
            notes.append(
                f"the {kind.replace('_', '-')} energy's error bound is {err / abs(value):.1e}"
                f" relative ({err:.3g} N·µm), above {flag:g}: the points it is integrated "
                f"between are resolved only so far at these inputs (a bound: the actual "
                f"error is often smaller)"
            )
    return energy, error, notes


# ------------------------------------------------------------------------------------------
# the points of a path as one system, polished to rounding


def path_chain(model, params: dict[str, float], q_A: float, names: str) -> PointChain:
    """The chain of the points ``names`` (A, B, then D and/or C) of the path."""
    oa = model.problem("OA", start=1.0)
    ab = model.problem("AB", start=params["m_B"], constant=q_A)
    bc = model.problem("BC", start=1.0, constant=params["m_B"])
    points = {
        "A": ChainPoint("A", oa, "g", ("g", 1.0)),
        "B": ChainPoint("B", ab, "m", ("m", "m_B"), links={"q_A": ("A", "q")}),
        "D": ChainPoint("D", bc, "g", ("g", 1.0), links={"m_B": ("B", "m")}),
        "C": ChainPoint("C", bc, "g", ("t", ("A", "t")), links={"m_B": ("B", "m")}),
    }
    return PointChain([points[x] for x in names], params)


def polish_point(problem, br, name: str, value: float, o) -> dict[str, float]:
    """The point of a traced leg at ``name = value``, Newton-polished to the update tolerance;
    where Newton does not converge there (C within ~1e-6 of the C boundary, where its slip
    diverges), the leg's own row located at it (a bound or target of the trace)."""
    try:
        cols = points_at(problem, br, name, value, options=o)
    except ConvergenceError:
        hits = np.flatnonzero(np.asarray(br[name]) == value)
        if not hits.size:
            raise
        return {k: float(v) for k, v in br.point(int(hits[0])).items()}
    return {k: float(v[0]) for k, v in cols.items()}


def polish_row(chain: PointChain, row: dict[str, Any]) -> dict[str, Any]:
    """A row of a locus Newton-polished to rounding at its parameters: the tracer accepts
    points to its update tolerance, and the released energies (areas between legs that meet
    at B) are sensitive to the frozen stick level to ~1e3 times that.

    To rounding whatever the ``rtol`` of the trace: from a row within the update tolerance
    (:func:`~cusp.continuation.point_tol`, 1e-10 at the loosest rtol) Newton reaches
    rounding in one or two updates (on Fig 9's locus in μ most rows need one at the default
    rtol), so a looser stop would save at most one iteration per row, while the energies'
    error bounds (``state_tol`` of :func:`energies`) would grow by the sensitivity above."""
    p = {k: row[k] for k in chain.params}
    u = np.array([row[k] for k in chain.unknowns])
    for _ in range(4):
        r = chain.residual(u, p)
        try:
            du = np.linalg.solve(chain.jacobian(u, p), -r)
        except np.linalg.LinAlgError:
            break
        if not np.all(np.isfinite(du)):
            break
        u = u + du
        if np.all(np.abs(du) <= 4.0 * np.finfo(float).eps * np.maximum(np.abs(u), 1.0)):
            break
    return {**row, **dict(zip(chain.unknowns, map(float, u)))}
