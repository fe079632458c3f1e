"""The contact-loss tasks of the work–precision benchmark (`bench_work_precision.py`), ours
only (no other tool computes them), over ``rtol``:

(c) the bundled scenes fig6 (exponential heights) and gaussian, built as `cusp run` builds
    them (`cusp.app.cases`) and run with the scene's solver options at each ``rtol``;
    errors: the points A–D (g_T, F_T, Â_SL) and the two released energies against the
    exact closed forms (fig6) or the independent mpmath path (gaussian), both from
    `cusp.verification.oracles`;
(d) the μ-locus of the manifold of the fig6 scene (`point_loci` over μ ∈ [0.02, 1], made
    to pass through eight values of μ); errors: the loci of the points and the energies at
    those eight values, and the two events (C boundary, F'_T = 0), against the closed forms.

The work counted is the number of evaluations of the body's tangential equilibrium
F̂_T(p, q) (`levels.tangential_ratio`): one per leg residual (with its Jacobian) and one per
quadrature node of the energies."""

from __future__ import annotations

import functools
import math

import numpy as np

from cusp._scripts.wp_problems import Setting, Task
from cusp.app.cases import build_body, make_model, solver_options
from cusp.app.run import bundled_scene
from cusp.app.scene import load_scene
from cusp.continuation import ContinuationOptions
from cusp.models import point_loci

WORK = "F̂_T evaluations (leg residuals and quadrature nodes)"
#: the values of μ the locus must pass through (rows located as targets), where its errors
#: are measured
LOCUS_MUS = tuple(float(m) for m in np.geomspace(0.03, 0.8, 8))
LOCUS_SPAN = (0.02, 1.0)
#: the closed forms compared on the loci: key -> the column of `Loci.columns`
LOCUS_KEYS = ("F_A", "g_B", "F_B", "g_C", "F_D", "A_SL_B")


def _scene_model(name):
    scene = load_scene(bundled_scene(f"{name}.toml"))
    mu, load = scene.cases[0]
    return scene, mu, load


def _counted_model(scene, mu, load):
    model = make_model(scene, build_body(scene, mu), load)
    cnt = {"f": 0}
    levels = model.levels
    inner = levels.tangential_ratio

    def tangential_ratio(*a):
        cnt["f"] += 1
        return inner(*a)

    levels.tangential_ratio = tangential_ratio  # this model's levels only
    return model, cnt


def _path_run(name, rtol):
    scene, mu, load = _scene_model(name)
    model, cnt = _counted_model(scene, mu, load)
    res = model.run(solver_options(scene).replace(rtol=rtol))
    return lambda: {
        "points": sum(len(b) for b in res.legs.values()),
        "nfev": cnt["f"],
        "jev": None,
        "ok": True,
        "status": "ok",
        "result": res,
    }


@functools.lru_cache
def fig6_reference():
    """Points A–D and energies of the fig6 scene from the exponential closed forms."""
    from cusp.verification.oracles import exponential_closed_form

    scene, mu, load = _scene_model("fig6")
    sf, ld = scene.surface, scene.loading
    kw = dict(sigma=sf["sigma"], nu=sf["nu"], F_N0=ld["normal_load"], g_A=ld["max_slip"])

    def cf(key):
        return exponential_closed_form(key, mu, load, **kw)

    g_A, F_A = ld["max_slip"], cf("F_A")
    points = {
        "A": {"g_T": g_A, "F_T": F_A, "A_SL": cf("A_SL_A")},
        "B": {"g_T": cf("g_B"), "F_T": cf("F_B"), "A_SL": cf("A_SL_B")},
        "C": {"g_T": cf("g_C"), "F_T": F_A, "A_SL": cf("A_SL_C")},
        "D": {"g_T": g_A, "F_T": cf("F_D"), "A_SL": cf("A_SL_D")},
    }
    return points, {"snap_back": cf("snap_back"), "snap_through": cf("snap_through")}


@functools.lru_cache
def gaussian_reference():
    """Points A–D and energies of the gaussian scene from the mpmath path."""
    from cusp.verification.oracles import gaussian_path

    scene, mu, load = _scene_model("gaussian")
    params = {k: v for k, v in scene.surface.items() if k != "model"}
    params["mu"] = mu
    ld = scene.loading
    pts, energy = gaussian_path(**params, F_N0=ld["normal_load"], g_A=ld["max_slip"], F_Np=load)
    points = {x: {q: float(pts[x][q]) for q in ("g_T", "F_T", "A_SL")} for x in "ABCD"}
    return points, {k: float(v) for k, v in energy.items()}


def _path_measure(reference, summary) -> dict[str, float]:
    """``points``: the largest relative error of g_T, F_T, Â_SL at A–D; ``energies``: of
    the snap-back and snap-through energies (inf where a run misses one)."""
    res = summary["result"]
    points, energy = reference()
    worst_p = worst_e = 0.0
    for x, want in points.items():
        have = res.points.get(x)
        for q, v in want.items():
            worst_p = max(worst_p, math.inf if have is None else abs(have[q] - v) / abs(v))
    for kind, v in energy.items():
        have = res.energy.get(kind)
        worst_e = max(worst_e, math.inf if have is None else abs(have - v) / abs(v))
    return {"points": worst_p, "energies": worst_e}


def path_tasks(rtols) -> list[Task]:
    """(c): the fig6 and gaussian scenes over ``rtols``."""
    out = []
    for key, name, reference, text in (
        ("fig6", "scene fig6 (exponential heights)", fig6_reference,
         "points and energies from the exact closed forms (cusp.verification)"),
        ("gaussian", "scene gaussian (Gaussian heights)", gaussian_reference,
         "points and energies from the independent mpmath path (40 digits)"),
    ):  # fmt: skip
        settings = [
            Setting("ours", f"rtol = {r:.0e}", "ours", functools.partial(_path_run, key, r))
            for r in rtols
        ]
        measure = functools.partial(_path_measure, reference)
        out.append(Task(key, "c", name, settings, measure, text, work=WORK))
    return out


# ----------------------------------------------------------------------------- (d) locus


def _locus_run(rtol):
    scene, mu, load = _scene_model("fig6")
    model, cnt = _counted_model(scene, mu, load)
    options = ContinuationOptions(ds=0.02, ds_max=0.1, rtol=rtol)  # point_loci's, at rtol
    loci = point_loci(model, "mu", LOCUS_SPAN, at=LOCUS_MUS, options=options)
    return lambda: {
        "points": len(loci.columns["mu"]),
        "nfev": cnt["f"],
        "jev": None,
        "ok": all(b.success for b in loci.branches.values()),
        "status": "ok"
        if all(b.success for b in loci.branches.values())
        else "; ".join(f"{name}: {b.status}" for name, b in loci.branches.items()),
        "result": loci,
    }


@functools.lru_cache
def locus_reference():
    """The closed forms at the eight values of μ (None where C does not exist) and the
    events' μ, at the fig6 scene's F'_N."""
    from cusp.verification.oracles import exponential_closed_form

    scene, _, load = _scene_model("fig6")
    sf, ld = scene.surface, scene.loading
    kw = dict(sigma=sf["sigma"], nu=sf["nu"], F_N0=ld["normal_load"], g_A=ld["max_slip"])
    rows = []
    for mu in LOCUS_MUS:
        c_exists = exponential_closed_form("F_A", mu, load, **kw) < mu * load
        row = {}
        for key in (*LOCUS_KEYS, "snap_back", "snap_through"):
            needs_c = key in ("g_C", "snap_through")
            row[key] = (
                exponential_closed_form(key, mu, load, **kw) if c_exists or not needs_c else None
            )
        rows.append(row)
    events = {
        "C boundary": exponential_closed_form("C boundary, mu", 0.1, load, event=True, **kw),
        "F'_T = 0": exponential_closed_form("F'_T = 0, mu", 0.1, load, event=True, **kw),
    }
    return rows, events


def _locus_measure(summary) -> dict[str, float]:
    """``loci``: the largest relative error of the points' loci at the eight μ (relative to
    max(|value|, 1e-3 of the column's largest), as F_B → 0 at F'_T = 0); ``energies``: of
    the energies there; ``events``: of the two events' μ (inf where one is missing)."""
    loci = summary["result"]
    cols = loci.columns
    rows, events = locus_reference()
    worst = {"loci": 0.0, "energies": 0.0, "events": 0.0}
    for key in (*LOCUS_KEYS, "snap_back", "snap_through"):
        col = cols[f"{key}_energy"] if key.startswith("snap") else cols[key]
        want = [r[key] for r in rows]
        size = max(abs(w) for w in want if w is not None)
        which = "energies" if key.startswith("snap") else "loci"
        for mu, w in zip(LOCUS_MUS, want, strict=True):
            if w is None:
                continue
            hit = np.flatnonzero(np.abs(cols["mu"] - mu) <= 1e-12 * mu)
            have = col[hit[0]] if hit.size else math.nan
            err = abs(have - w) / max(abs(w), 1e-3 * size) if math.isfinite(have) else math.inf
            worst[which] = max(worst[which], err)
    found = {e["event"]: e["mu"] for e in loci.events}
    for name, mu in events.items():
        err = abs(found[name] - mu) / mu if name in found else math.inf
        worst["events"] = max(worst["events"], err)
    return worst


def locus_task(rtols) -> Task:
    """(d): the μ-locus of the fig6 scene over ``rtols``."""
    settings = [
        Setting("ours", f"rtol = {r:.0e}", "ours", functools.partial(_locus_run, r)) for r in rtols
    ]
    return Task(
        "manifold",
        "d",
        f"μ-locus of the fig6 scene, μ ∈ [{LOCUS_SPAN[0]:g}, {LOCUS_SPAN[1]:g}]",
        settings,
        _locus_measure,
        "the exact closed forms of the loci and of the events (cusp.verification) at "
        f"{len(LOCUS_MUS)} values of μ",
        work=WORK,
    )
