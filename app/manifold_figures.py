"""Figures of the loci of a ``[manifold]`` scene (the catastrophe manifold, Fig 9), rendered
to PNG and SVG bytes like :mod:`cusp.app.figures`.

* ``manifold-surface``: the response surface in 3-D, the path (g_T, F_T) drawn at height
  μ (or F'_N) for a dozen values across the traced range (single contact-loss runs, made
  only for this figure), with the loci of A and B, the edges of the pleat, drawn on it
  (those of C and D dashed);
* ``loci-control-planes``: the loci of A, B, C, D in the planes (g_T, μ) and (F_T, μ),
  the located events marked;
* ``loci-energies``: the snap-back and snap-through energies along the loci;
* ``regime-map``: over (μ, F'_N), the boundaries of the regimes (C boundary, F'_T = 0, ...)
  as curves on the energies drawn as filled contours
  (:func:`cusp.models.manifold.regime_map`, computed only for this figure).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .figures import figure_bytes, new_figure

__all__ = ["render_manifold", "surface_heights"]

#: the colour of each point's locus
_POINT_COLORS = {"A": "#c0392b", "B": "#1f4e79", "C": "#2e7d32", "D": "#8e44ad"}
#: the line of each point's locus: A and B (the edges of the pleat) solid, C and D dashed
_POINT_STYLES: dict[str, dict[str, Any]] = {
    "A": {"lw": 2.4},
    "B": {"lw": 2.4},
    "C": {"lw": 1.3, "ls": "--"},
    "D": {"lw": 1.3, "ls": "--"},
}
#: how many paths the response surface shows
SURFACE_PATHS = 12
#: the regime map's grid: F'_N values × μ values (μ spaced logarithmically)
REGIME_GRID = (40, 32)


def render_manifold(run, names) -> dict[str, dict[str, bytes]]:
    """``{figure name: {"png": bytes, "svg": bytes}}`` for the loci of ``run`` (a
    :class:`cusp.app.run.SceneRun` of a [manifold] scene)."""
    import matplotlib

    makers = {
        "manifold-surface": (_surface, (7.2, 6.0)),
        "loci-control-planes": (_control_planes, (10.0, 4.6)),
        "loci-energies": (_energies, (6.4, 4.8)),
        "regime-map": (_regime, (11.0, 5.0)),
    }
    out: dict[str, dict[str, bytes]] = {}
    with matplotlib.rc_context({"font.size": 10}):
        for name in names:
            make, size = makers[name]
            fig = new_figure(size)
            make(fig, run)
            if run.scene.title:
                fig.suptitle(run.scene.title)
            out[name] = {fmt: figure_bytes(fig, fmt, dpi=150) for fmt in ("png", "svg")}
    return out


def _label(parameter: str) -> str:
    return r"friction coefficient $\mu$" if parameter == "mu" else r"$F'_N$ [N]"


def surface_heights(values: np.ndarray, n: int = SURFACE_PATHS) -> np.ndarray:
    """``n`` values spread evenly inside the traced range of the parameter (the ends, where
    the locus meets an event, excluded)."""
    finite = values[np.isfinite(values)]
    lo, hi = float(np.min(finite)), float(np.max(finite))
    return lo + (hi - lo) * (np.arange(n) + 0.5) / n


def _path_at(scene, parameter: str, height: float) -> Any:
    """The contact-loss path at μ = ``height`` (or F'_N), or None where there is none."""
    from cusp.continuation import ContinuationError
    from cusp.models.contact_loss import PathError

    from .cases import build_body, make_model, solver_options
    from .scene import SceneError

    mu, load = scene.manifold["start"]
    if parameter == "mu":
        mu = height
    else:
        load = height
    try:
        return make_model(scene, build_body(scene, mu), load).run(solver_options(scene))
    except (SceneError, PathError, ContinuationError):
        return None


def _clip(g: np.ndarray, limit: float) -> np.ndarray:
    """``g`` with the values beyond ``limit`` as NaN (C's slip diverges at the C boundary)."""
    g = np.array(g, dtype=float)
    g[g > limit] = math.nan
    return g


def _surface(fig, run) -> None:
    import matplotlib

    loci, scene = run.loci, run.scene
    p, cols = loci.parameter, loci.columns
    g_lim = 2.0 * scene.loading["max_slip"]
    ax = fig.add_subplot(projection="3d")
    cmap = matplotlib.colormaps["viridis"]
    heights = surface_heights(cols[p])
    for k, h in enumerate(heights):
        res = _path_at(scene, p, float(h))
        if res is None:
            continue
        for leg in res.legs:
            d = res.dense(leg, 60)
            g = _clip(d["g_T"], g_lim)
            ax.plot(g, d["F_T"], np.full_like(g, h), color=cmap(k / len(heights)), lw=0.9)
    for x in "ABCD":
        g = _clip(cols[f"g_{x}"], g_lim)
        style = {"color": _POINT_COLORS[x], "label": f"locus of {x}", **_POINT_STYLES[x]}
        ax.plot(g, cols[f"F_{x}"], cols[p], **style)
    ax.set_xlabel(r"$g_T$ [µm]")
    ax.set_ylabel(r"$F_T$ [N]")
    ax.set_zlabel(_label(p))
    ax.view_init(elev=24, azim=-62)
    ax.legend(frameon=False, loc="upper left", fontsize=9)


def _mark_events(axes, loci, x_of) -> None:
    """Each event as a dotted line at its parameter value, named once, on every axes;
    ``x_of(ax)`` gives the columns whose points are marked on ``ax``."""
    p = loci.parameter
    for ev in loci.events:
        for j, ax in enumerate(axes):
            ax.axhline(ev[p], color="0.45", lw=0.8, ls=":")
            for col in x_of(j):
                if math.isfinite(ev.get(col, math.nan)):
                    ax.plot(ev[col], ev[p], "o", color=_POINT_COLORS[col[-1]], ms=4)
        axes[-1].annotate(
            ev["event"],
            (1.0, ev[p]),
            xycoords=("axes fraction", "data"),
            xytext=(4, 0),
            textcoords="offset points",
            va="center",
            fontsize=8,
        )


def _control_planes(fig, run) -> None:
    """The loci of A, B, C, D in the planes (g_T, μ) and (F_T, μ)."""
    loci = run.loci
    p, cols = loci.parameter, loci.columns
    g_lim = 2.0 * run.scene.loading["max_slip"]
    ax_g, ax_f = fig.subplots(1, 2, sharey=True)
    for x in "ABCD":
        style = {"color": _POINT_COLORS[x], "label": x, **_POINT_STYLES[x]}
        ax_g.plot(_clip(cols[f"g_{x}"], g_lim), cols[p], **style)
        ax_f.plot(cols[f"F_{x}"], cols[p], **style)
    _mark_events((ax_g, ax_f), loci, lambda j: [f"{'gF'[j]}_{x}" for x in "ABCD"])
    ax_g.set_xlim(0.0, g_lim)
    ax_g.set_xlabel(r"$g_T$ [µm]")
    ax_f.set_xlabel(r"$F_T$ [N]")
    ax_g.set_ylabel(_label(p))
    ax_g.legend(frameon=False, loc="best", title="locus of")
    for ax in (ax_g, ax_f):
        ax.grid(alpha=0.3)


def _energies(fig, run) -> None:
    """The snap-back and snap-through energies along the loci."""
    loci = run.loci
    p, cols = loci.parameter, loci.columns
    ax = fig.add_subplot()
    for kind, color in (("snap_back", _POINT_COLORS["D"]), ("snap_through", _POINT_COLORS["C"])):
        label = f"{kind.replace('_', '-')} energy (area AB{'D' if kind == 'snap_back' else 'C'})"
        ax.plot(cols[p], cols[f"{kind}_energy"], color=color, label=label)
    for ev in loci.events:
        ax.axvline(ev[p], color="0.45", lw=0.8, ls=":")
        ax.annotate(
            ev["event"],
            (ev[p], 1.0),
            xycoords=("data", "axes fraction"),
            xytext=(-3, -4),
            textcoords="offset points",
            rotation=90,
            ha="right",
            va="top",
            fontsize=8,
        )
    ax.set_yscale("log")
    ax.set_xlabel(_label(p))
    ax.set_ylabel("released energy [N·µm]")
    ax.legend(frameon=False, loc="lower right")
    ax.grid(alpha=0.3, which="both")


def regime_spans(scene) -> tuple[tuple[float, float], tuple[float, float]]:
    """The (μ, F'_N) window of the regime map: the [manifold] range in its parameter; μ
    over a decade each side of the scene's, F'_N from a tenth of F_N0 up to F_N0."""
    man = scene.manifold
    mu, load = man["start"]
    F_N0 = scene.loading["normal_load"]
    mu_span = man["range"] if man["parameter"] == "mu" else (mu / 10.0, 10.0 * mu)
    load_span = (
        man["range"] if man["parameter"] == "reduced_normal_load" else (min(0.1 * F_N0, load), F_N0)
    )
    return mu_span, load_span


def _regime(fig, run) -> None:
    """The regime map over (μ, F'_N): energies as filled contours (blank where the landing
    point does not exist), boundaries as curves, the inadmissible region grey."""
    from cusp.models.regimes import regime_map

    from .cases import build_body, loci_options, make_model

    scene = run.scene
    mu, load = scene.manifold["start"]
    model = make_model(scene, build_body(scene, mu), load)
    mu_span, load_span = regime_spans(scene)
    n_loads, n_mus = REGIME_GRID
    rm = regime_map(
        model,
        mu_span=mu_span,
        load_span=load_span,
        loads=n_loads,
        mus=n_mus,
        options=loci_options(scene),
    )
    axes = fig.subplots(1, 2, sharey=True)
    for ax, kind in zip(axes, ("snap_back", "snap_through")):
        values = np.ma.masked_invalid(np.asarray(getattr(rm, kind), dtype=float))
        if values.count():
            filled = ax.contourf(rm.mu, rm.loads, values, levels=12, cmap="magma_r")
            fig.colorbar(filled, ax=ax, label=f"{kind.replace('_', '-')} energy [N·µm]")
        for k, (name, (m, f)) in enumerate(rm.boundaries.items()):
            ax.plot(m, f, color=("#00bcd4", "#1f4e79", "#2e7d32")[k % 3], lw=1.8, label=name)
            if name == "F'_T = 0":  # below it the reduction is too deep
                ax.fill_between(
                    m, load_span[0], f, color="0.88", zorder=0.5, label="inadmissible (F'_T < 0)"
                )
        for case in run.cases:
            ax.plot(case.mu, case.load, "k+", ms=8)
        ax.set_xlim(*mu_span)
        ax.set_ylim(*load_span)
        if mu_span[1] > 10.0 * mu_span[0]:
            ax.set_xscale("log")
        ax.set_xlabel(r"friction coefficient $\mu$")
        ax.set_title(kind.replace("_", "-"))
    axes[0].set_ylabel(r"reduced normal load $F'_N$ [N]")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, frameon=False, loc="outside lower center", ncol=len(labels))
