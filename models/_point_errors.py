"""Error bounds of the points of a contact-loss path (and of a locus row), from the
linearised equations of the chain of points (:func:`~._loci_energy.path_chain`).

The points A, B, D, C are the solution of one square system G(u) = 0 (each point's five
equilibrium equations of :mod:`cusp.models.contact_loss` and the condition that places it
on its leg). Each equation is evaluated with an error: the rounding of its terms, and the
body's functions' own error (its levels' ``relative_error``, e.g. the GW integrals of a
Gaussian surface), relative to the terms it enters. To first order the solution is then off
by δu = G'(u)⁻¹ δG, so |δu| ≤ |G'(u)⁻¹| (|G(u)| + e), componentwise (e the evaluation
errors, |G(u)| what is left after Newton); twice that is taken, for the second order and
the rounding of the solve. The errors of the physical quantities (g_T, F_T, F_N, A_SL and
the levels as lengths) follow from those of the unknowns.

This is what float64 resolves of the exact path at the given inputs: where it is more than
the accuracy promised (1e-12 relative at the default ``rtol``), the path's messages name the
point, the quantities and their bounds (:func:`point_messages`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from .protocol import level_lengths, slipped_area

__all__ = [
    "chain_errors",
    "point_bounds",
    "point_messages",
    "polish",
    "relative",
    "underflow_messages",
]

_EPS = float(np.finfo(float).eps)
_LEGS = {"A": "OA", "B": "AB", "C": "BC", "D": "BC"}
_VARIABLES = ("g", "t", "m", "A_SL", "p", "q")


def _relative_error(levels) -> float:
    return float(getattr(levels, "relative_error", 16.0 * _EPS)) + 4.0 * _EPS


def equation_errors(model, x, mu: float, leg: str, const) -> np.ndarray:
    """The evaluation errors of the five residual equations of ``leg`` at x = (g, t, m,
    A_SL, p, q): the terms' rounding, the levels' relative error, and the rounding of the
    absolute level at which a two-level relation is evaluated (a rough surface's d = d_A +
    u·p: ε|d| shifts both levels, costing |∂_p + ∂_q|·ε|d|/u, which far in a Gaussian tail,
    where F_n ~ φ, is ε t² relative)."""
    g, t, red, a_sl, p, q = x
    L = model.levels
    eta = _relative_error(L)
    ell = L.log_normal_load(p)[0]
    F, dF_p, dF_q = L.tangential_ratio(p, q)
    s = L.slip(p, q)[0]
    a = slipped_area(L, p, q, model.area_reading)[0]
    k = model.mu0 / mu
    m = mu / model.g_A
    n = 1.0 - red
    shift = _position_rounding(L, p, q)
    e = np.empty(5)
    if leg == "OA":  # p − p0
        e[0] = _EPS * (abs(p) + abs(L.p0))
    else:
        e[0] = 2.0 * _EPS * abs(math.log1p(-red) if red < 1.0 else 0.0) + eta * abs(ell)
    e[1] = 2.0 * _EPS * abs(k * t) + (eta + 2.0 * _EPS) * abs(n * F)
    e[1] += abs(n * (dF_p + dF_q)) * shift
    e[2] = 2.0 * _EPS * abs(g) + (eta + 2.0 * _EPS) * abs(m * s)
    e[3] = 2.0 * _EPS * abs(a_sl) + (eta + 2.0 * _EPS) * abs(a) + _area_shift(L, p, q) * shift
    e[4] = _EPS * (abs(q) + abs(const) if leg == "AB" else abs(red) + abs(const or 0.0))
    return e


def _position_rounding(L, p: float, q: float) -> float:
    """2ε|the level as a length| in units of the levels: the rounding of the absolute level
    a relation is evaluated at (and of h/σ* inside it)."""
    lp = float(level_lengths(L, [p], [q])[0][0])
    return 2.0 * _EPS * abs(lp) / float(L.scale)


def _area_shift(L, p: float, q: float) -> float:
    """|∂_p + ∂_q| of the part of Â_SL evaluated at the absolute level, 1 − Â_ST (the lost
    area is formed from d_A and an increment)."""
    slip_area = getattr(L, "slip_area", None)
    _, d_p, d_q = slip_area(p, q) if slip_area is not None else L.stick_area(p, q)
    return abs(d_p + d_q)


def _point_values(row: Mapping[str, float], name: str) -> list[float]:
    return [row[f"{name}.{v}"] for v in _VARIABLES]


def _evaluation_errors(model, chain, row: Mapping[str, float]) -> np.ndarray:
    """The chain's equations' evaluation errors, in its row order."""
    out: list[np.ndarray] = []
    for pt in chain.points:
        x = _point_values(row, pt.name)
        leg = _LEGS[pt.name]
        const = row["A.q"] if leg == "AB" else (row["B.m"] if leg == "BC" else None)
        out.append(equation_errors(model, x, row["mu"], leg, const))
        target = x[_VARIABLES.index(pt.at[0])]
        out.append(np.array([_EPS * abs(target)]))
    return np.concatenate(out)


def chain_errors(model, chain, row: Mapping[str, float]) -> dict[str, float]:
    """Bounds on the absolute errors of the chain's unknowns at ``row`` (module docstring);
    inf where the chain's Jacobian is singular there."""
    p = {k: row[k] for k in chain.params}
    u = np.array([row[k] for k in chain.unknowns])
    residual = np.abs(chain.residual(u, p))
    e = _evaluation_errors(model, chain, row) + residual
    try:
        inv = np.linalg.inv(chain.jacobian(u, p))
    except np.linalg.LinAlgError:
        return dict.fromkeys(chain.unknowns, math.inf)
    du = 2.0 * (np.abs(inv) @ e)
    du = np.where(np.isfinite(du), du, math.inf)
    return dict(zip(chain.unknowns, map(float, du)))


def polish(chain, row: dict[str, float], iterations: int = 6) -> dict[str, float]:
    """``row`` Newton-polished on the chain to rounding: the iterate whose residual, scaled
    by the equations' sizes, is least (the row itself if no update improves it)."""
    p = {k: row[k] for k in chain.params}
    u = np.array([row[k] for k in chain.unknowns])
    best_u, best = u, _size(chain.residual(u, p))
    for _ in range(iterations):
        try:
            du = np.linalg.solve(chain.jacobian(u, p), -chain.residual(u, p))
        except np.linalg.LinAlgError:
            break
        if not np.all(np.isfinite(du)):
            break
        u = u + du
        r = chain.residual(u, p)
        size = _size(r)
        if size <= best:  # (the latest of equal ones: a tiny component's own equation
            best_u, best = u, size  # may still improve under a larger one's rounding)
        if np.all(np.abs(du) <= 2.0 * _EPS * np.abs(u)) or size == 0.0:
            break
    return {**row, **dict(zip(chain.unknowns, map(float, best_u)))}


def _size(r: np.ndarray) -> float:
    r = np.abs(np.asarray(r, dtype=float))
    return float(np.max(r)) if np.all(np.isfinite(r)) else math.inf


def point_bounds(
    model, values: Mapping[str, float], errors: Mapping[str, float]
) -> dict[str, float]:
    """Bounds on the absolute errors of a point's physical quantities (``g_T`` [µm], ``F_T``
    [N], ``F_N`` [N], ``A_SL`` and the levels as lengths [µm]) from its nondimensional
    ``values`` and their ``errors`` (``{variable: error}``)."""
    sc, L = model.scales, model.levels
    out = {
        "g_T": errors["g"] * sc["g"] + _EPS * abs(values["g"] * sc["g"]),
        "F_T": errors["t"] * sc["t"] + _EPS * abs(values["t"] * sc["t"]),
        "F_N": errors["m"] * sc["F_N"] + _EPS * abs((1.0 - values["m"]) * sc["F_N"]),
        "A_SL": errors["A_SL"] + _EPS * abs(values["A_SL"]),
    }
    p, q = values["p"], values["q"]
    lp, lq = level_lengths(L, [p], [q])
    step = max(abs(p), abs(q), 1.0) * 1e-7
    dp = abs(float(level_lengths(L, [p + step], [q])[0][0]) - float(lp[0])) / step
    dq = abs(float(level_lengths(L, [p], [q + step])[1][0]) - float(lq[0])) / step
    origin = float(getattr(L, "origin_error", 0.0))
    names = L.names
    out[names[0]] = 2.0 * dp * errors["p"] + origin + 4.0 * _EPS * abs(float(lp[0]))
    out[names[1]] = 2.0 * dq * errors["q"] + origin + 4.0 * _EPS * abs(float(lq[0]))
    return out


def relative(name: str, value: float, err: float, floors: Mapping[str, float]) -> float:
    """``err`` relative to ``value`` (to the larger of |value| and ``floors[name]`` for the
    levels: positions such as d, whose datum is arbitrary, are measured against their unit)."""
    size = max(abs(value), floors.get(name, 0.0))
    return err / size if size != 0.0 else (0.0 if err == 0.0 else math.inf)


def point_messages(
    physical: Mapping, bounds: Mapping, threshold: float, floors: Mapping[str, float]
) -> list[str]:
    """One message per point whose quantities have error bounds above ``threshold``
    (relative, :func:`relative`), naming them with their bounds."""
    units = {"g_T": "µm", "F_T": "N", "F_N": "N", "A_SL": ""}
    out = []
    for key, point in physical.items():
        if point is None or key not in bounds:
            continue
        worse = []
        for name, value in point.items():
            err = bounds[key].get(name)
            if err is None:
                continue
            rel = relative(name, value, err, floors)
            if rel > threshold:
                unit = units.get(name, "µm")
                worse.append(
                    f"{name} to {rel:.1e} relative (±{err:.2g}{' ' + unit if unit else ''})"
                )
        if worse:
            out.append(
                f"point {key} is resolved only to its error bounds: {', '.join(worse)}, above "
                f"{threshold:g}: float64 does not resolve the path better at these inputs"
            )
    return out


def underflow_messages(physical: Mapping) -> list[str]:
    """A message per point that has slipped (g_T > 0) but whose Â_SL is 0.0: the slipping
    summits' share of the area is then below the smallest float (on a Gaussian surface
    under 1e9 N, where d lies 1800 σ* below the mean plane, Â_SL at A is e^{−1.6e6}), or
    exactly 0 (a density with no summits between the two levels); 0.0 is its nearest
    float, not a missing value."""
    out = []
    for key, point in physical.items():
        if key == "O" or point is None:
            continue
        if point.get("A_SL") == 0.0 and point.get("g_T", 0.0) > 0.0:
            out.append(
                f"point {key}: A_SL is written as 0.0: the slipping summits' share of the "
                "contact area is below the smallest positive float (2.2e-308) at these "
                "inputs, or exactly 0 where the height density has no summits between the "
                "contact level and the stick level"
            )
    return out
