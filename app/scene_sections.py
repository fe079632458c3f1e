"""Checks of two sections of a scene (:mod:`cusp.app.scene`): ``[loading]`` (the three loads)
and ``[manifold]`` (the parameter the loci of A, B, C, D are traced in, its range, and the
case they start from). ``chk`` is the scene's checker: it raises the SceneError."""

from __future__ import annotations

import math
from typing import Any

from .limits import show

__all__ = ["MANIFOLD_PARAMETERS", "check_loading", "check_manifold"]

#: the parameters a [manifold] locus can be traced in, and their units
MANIFOLD_PARAMETERS = {"mu": "", "reduced_normal_load": "N"}


def check_manifold(
    chk: Any, man_in: dict[str, Any], surface: dict[str, Any], loading: dict[str, Any]
) -> dict[str, Any]:
    """[manifold]: the parameter, its range, and the case the loci start from (the first
    listed value of the parameter inside the range)."""
    allowed_params = " or ".join(repr(k) for k in MANIFOLD_PARAMETERS)
    for key in ("parameter", "range"):
        if key not in man_in:
            chk.fail(f"[manifold] missing key {show(key)}", "[manifold] needs parameter and range")
    param = chk.string("manifold", "parameter", man_in["parameter"])
    if param not in MANIFOLD_PARAMETERS:
        chk.fail(f"[manifold] parameter = {show(param)}", allowed_params)
    if param == "mu" and "mu" not in surface:
        chk.fail(
            f"[manifold] parameter = 'mu' but model {show(surface['model'])} has no mu",
            "'reduced_normal_load' for this model",
        )
    unit = MANIFOLD_PARAMETERS[param]
    u = f" [{unit}]" if unit else ""
    rng = man_in["range"]
    top = loading["normal_load"] if param == "reduced_normal_load" else math.inf
    what = "two finite numbers [low, high], 0 < low < high" + (
        f" <= normal_load = {show(top)} N" if math.isfinite(top) else ""
    )
    if (
        not isinstance(rng, list)
        or len(rng) != 2
        or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in rng)
        or not all(math.isfinite(v) for v in rng)
        or not 0.0 < rng[0] < rng[1] <= top
    ):
        chk.fail(f"[manifold] range = {show(rng)}{u}", what)
    lo, hi = float(rng[0]), float(rng[1])
    values = surface["mu"] if param == "mu" else loading["reduced_normal_load"]
    values = values if isinstance(values, list) else [values]
    inside = [v for v in values if lo <= v <= hi]
    if not inside:
        where = "[surface] mu" if param == "mu" else "[loading] reduced_normal_load"
        shown = values if len(values) > 1 else values[0]
        chk.fail(
            f"[manifold] range = {show(rng)}{u} does not hold {where} = {show(shown)}",
            f"a range holding {'a listed value of ' if len(values) > 1 else ''}{param} "
            "(the loci start from that case)",
        )
    mus = surface.get("mu")
    first_mu = mus[0] if isinstance(mus, list) else mus
    start = (
        (inside[0], loading["reduced_normal_load"][0])
        if param == "mu"
        else (
            first_mu,
            inside[0],
        )
    )
    return {"parameter": param, "range": (lo, hi), "start": start}


def check_loading(chk: Any, load_in: dict[str, Any]) -> dict[str, Any]:
    """[loading]: the three loads, the reductions as a list, each below normal_load."""
    loading: dict[str, Any] = {}
    for key in ("normal_load", "max_slip", "reduced_normal_load"):
        if key not in load_in:
            chk.fail(
                f"[loading] missing key {show(key)}",
                "[loading] needs normal_load, max_slip and reduced_normal_load",
            )
    loading["normal_load"] = chk.number("loading", "normal_load", load_in["normal_load"])
    loading["max_slip"] = chk.number("loading", "max_slip", load_in["max_slip"])
    red = load_in["reduced_normal_load"]
    reds = red if isinstance(red, list) else [red]
    loading["reduced_normal_load"] = chk.numbers("loading", "reduced_normal_load", reds)
    for v in loading["reduced_normal_load"]:
        if v >= loading["normal_load"]:
            chk.fail(
                f"[loading] reduced_normal_load = {show(v)} N",
                f"less than normal_load = {show(loading['normal_load'])} N (a reduction)",
            )
    return loading
