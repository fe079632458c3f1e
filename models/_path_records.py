"""The records of a contact-loss path (:mod:`cusp.models.contact_loss`): its nondimensional
leg columns and points as physical ones (µm, N), where the named points are rows of the legs,
each leg's work, and why C or D does not exist."""

from __future__ import annotations

from typing import Any

import numpy as np

from .protocol import level_lengths

__all__ = [
    "VARIABLES",
    "gross_sliding_messages",
    "leg_stats",
    "physical_point",
    "point_rows",
    "to_physical",
]

#: nondimensional variables of every leg problem (one of them is the leg's control)
VARIABLES = ("g", "t", "m", "A_SL", "p", "q")


def to_physical(columns, scales, level_names, levels=None) -> dict[str, np.ndarray]:
    """Nondimensional leg columns (g, t, m, A_SL, p, q) to physical ones (µm, N); the levels
    by the body's own :func:`~cusp.models.protocol.level_lengths` (without ``levels``:
    p·scale, q·scale)."""
    p_name, q_name = level_names
    if levels is not None:
        lp, lq = level_lengths(levels, columns["p"], columns["q"])
    else:
        lp = np.asarray(columns["p"]) * scales["level"]
        lq = np.asarray(columns["q"]) * scales["level"]
    return {
        "g_T": np.asarray(columns["g"]) * scales["g"],
        "F_T": np.asarray(columns["t"]) * scales["t"],
        "F_N": (1.0 - np.asarray(columns["m"])) * scales["F_N"],
        "A_SL": np.array(columns["A_SL"], dtype=float),
        p_name: lp,
        q_name: lq,
    }


def physical_point(values: dict[str, float], scales, level_names, levels=None) -> dict[str, float]:
    """One nondimensional point to a physical record."""
    cols = to_physical({c: [values[c]] for c in VARIABLES}, scales, level_names, levels)
    return {k: float(v[0]) for k, v in cols.items()}


def gross_sliding_messages(model, t_A: float, c_exists: bool, d_exists: bool) -> list[str]:
    """Why C or D of ``model``'s path does not exist (t_A = F_A/(μ0 F_N0))."""
    messages: list[str] = []
    if not c_exists:
        messages.append(
            f"F_A = {t_A * model.scales['t']:.6g} N >= mu F'_N = "
            f"{model.mu0 * model.F_Np:.6g} N: under force control the block slides (gross "
            f"sliding); there is no point C and no snap-through energy"
        )
    if not d_exists:
        messages.append(
            f"g_A = {model.g_A:.6g} µm exceeds the slip at which the body slides under F'_N:"
            f" under displacement control the block slides (gross sliding); there is no "
            f"point D and no snap-back energy"
        )
    return messages


def point_rows(legs, c_exists: bool, d_exists: bool) -> dict[str, tuple[str, int]]:
    """Where the named points are rows of the legs."""
    rows = {"O": ("OA", 0), "A": ("OA", len(legs["OA"]) - 1), "B": ("AB", len(legs["AB"]) - 1)}
    last = len(legs["BC"]) - 1
    if c_exists:
        rows["C"] = ("BC", last)
        hits = [sp.index for sp in legs["BC"].special("target") if sp.with_respect_to == "g"]
        if hits:
            rows["D"] = ("BC", hits[0])
    elif d_exists:
        rows["D"] = ("BC", last)
    return rows


def leg_stats(br: Any) -> dict[str, Any]:
    """The work of a traced leg: points, status, Newton iterations, rejections, residual."""
    it = br.stats["newton_iterations"]
    return {
        "points": len(br),
        "status": br.status,
        "newton_iterations_per_point": float(np.mean(it[1:])) if len(it) > 1 else 0.0,
        "rejected_steps": int(np.sum(br.stats["rejected_steps"])),
        "max_residual_norm": float(np.max(br.stats["residual_norm"])),
    }
