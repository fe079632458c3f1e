"""Figures of the loci of a ``[manifold]`` scene (the catastrophe manifold, Fig 9), rendered
to PNG and SVG bytes like :mod:`cusp.app.figures`.

* ``manifold-surface``: the response surface in 3-D, the path (g_T, F_T) at height μ (or
  F'_N) for :data:`SURFACE_PATHS` values across the traced range (single contact-loss runs,
  made only for this figure, in steps up to :data:`SURFACE_DS_MAX`) joined into a shaded
  surface coloured by the height (with its colour bar), folded along the loci of A and B
  (the edges of the pleat, drawn on it; those of C and D dashed);
* ``loci-control-planes``: the loci of A, B, C, D in the planes (g_T, μ) and (F_T, μ),
  the located events marked;
* ``loci-energies``: the snap-back and snap-through energies along the loci;
* ``regime-map``: over (μ, F'_N), the regimes as regions bounded by the traced boundary
  curves (C boundary F'_N = F_A/μ, F'_T = 0 at F'_N = F_N0 − F_A/μ, and where D disappears
  for a body that slides as a whole; :func:`cusp.models.regimes.regime_boundaries`, the
  locus of A in μ along its dense output, computed only for this figure), the scene's cases
  marked. Filled polygons between the curves, not a grid: no gaps along them.

Every label is mathtext (the events' names by :data:`EVENT_LABELS`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .figures import encode, leg_curve, new_figure

__all__ = ["EVENT_LABELS", "draw_manifold", "render_manifold", "surface_heights"]

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
#: the viewpoint of the response surface (elevation, azimuth) [°]: from the side of larger
#: F_T, where the pleat between the loci of A and B faces the viewer
SURFACE_VIEW = (25.0, 40.0)
#: the largest step of the surface's paths (nondimensional arclength, as ``ds_max`` of
#: :class:`cusp.continuation.ContinuationOptions`) where the scene's [solver] gives none: the
#: paths are drawn from their dense output, within the scene's ``rtol``, so their steps need
#: not be as short as the run's (0.05), which draws its raw points in its CSV
SURFACE_DS_MAX = 0.5
#: points of each leg (OA, AB, BC) across the response surface
SURFACE_SAMPLES = {"OA": 36, "AB": 16, "BC": 36}
#: how the events and boundaries are named in the figures
EVENT_LABELS = {
    "C boundary": r"C boundary $F'_N = F_A/\mu$",
    "F'_T = 0": r"$F'_T = 0$",
    "D disappears": "D disappears",
    "A slides": "A slides",
}
#: the regions of the regime map: name, colour (in the order drawn, bottom up)
_REGIONS = (
    (r"inadmissible ($F'_T < 0$)", "0.82"),
    ("gross sliding under both controls", "#c7e9c0"),
    ("snap-back; gross sliding under force control (no C)", "#9ecae1"),
    ("snap-back and snap-through", "#fdd0a2"),
)


def render_manifold(run, names) -> dict[str, dict[str, bytes]]:
    """``{figure name: {"png": bytes, "svg": bytes}}`` for the loci of ``run`` (a
    :class:`cusp.app.run.SceneRun` of a [manifold] scene)."""
    return {name: encode(fig) for name, fig in draw_manifold(run, names).items()}


def draw_manifold(run, names) -> dict:
    """``{figure name: matplotlib Figure}`` (Agg canvas, not yet laid out) for the loci of
    ``run``, as :func:`render_manifold` encodes them."""
    import matplotlib

    makers = {
        "manifold-surface": (_surface, (7.6, 6.2)),
        "loci-control-planes": (_control_planes, (10.0, 4.6)),
        "loci-energies": (_energies, (6.4, 4.8)),
        "regime-map": (_regime, (7.0, 5.6)),
    }
    out = {}
    with matplotlib.rc_context({"font.size": 10}):
        for name in names:
            make, size = makers[name]
            fig = new_figure(size)
            make(fig, run)
            if run.scene.title:
                fig.suptitle(run.scene.title)
            out[name] = fig
    return out


def _label(parameter: str) -> str:
    return r"friction coefficient $\mu$" if parameter == "mu" else r"reduced normal load $F'_N$ [N]"


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
    options = solver_options(scene)
    if "ds_max" not in scene.solver:
        options = options.replace(ds_max=SURFACE_DS_MAX)
    try:
        return make_model(scene, build_body(scene, mu), load).run(options)
    except (SceneError, PathError, ContinuationError):
        return None


def _clip(g: np.ndarray, limit: float) -> np.ndarray:
    """``g`` with the values beyond ``limit`` as NaN (C's slip diverges at the C boundary)."""
    g = np.array(g, dtype=float)
    g[g > limit] = math.nan
    return g


def _surface(fig, run) -> None:
    import matplotlib
    from matplotlib.colors import Normalize

    loci, scene = run.loci, run.scene
    p, cols = loci.parameter, loci.columns
    g_lim = 2.0 * scene.loading["max_slip"]
    ax = fig.add_subplot(projection="3d")
    cmap = matplotlib.colormaps["viridis"]
    rows = []
    for h in surface_heights(cols[p]):
        res = _path_at(scene, p, float(h))
        if res is not None and set(SURFACE_SAMPLES) <= set(res.legs):
            rows.append((float(h), _path_row(res, g_lim)))
    norm = Normalize(*_span([h for h, _ in rows] or [0.0, 1.0]))
    if len(rows) > 1:
        H = np.array([np.full(g.size, h) for h, (g, _) in rows])
        G = np.array([g for _, (g, _) in rows])
        F = np.array([f for _, (_, f) in rows])
        ax.plot_surface(
            G,
            F,
            H,
            facecolors=_pleat_lighter(cmap(norm(H))),
            shade=True,
            rstride=1,
            cstride=1,
            linewidth=0,
            antialiased=False,
        )
        for h, (g, f) in rows:
            ax.plot(g, f, np.full_like(g, h), color="k", lw=0.4, alpha=0.6)
    for x in "ABCD":
        g = _clip(cols[f"g_{x}"], g_lim)
        style = {"color": _POINT_COLORS[x], "label": f"locus of {x}", **_POINT_STYLES[x]}
        ax.plot(g, cols[f"F_{x}"], cols[p], zorder=10, **style)
    ax.plot([], [], color="k", lw=0.4, label="paths O→A→B→C (A→B lighter)")
    mappable = matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap)
    fig.colorbar(mappable, ax=ax, shrink=0.6, pad=0.14, label=_label(p))
    ax.set_xlabel(r"$g_T$ [µm]")
    ax.set_ylabel(r"$F_T$ [N]")
    ax.set_zlabel(_label(p))
    ax.view_init(*SURFACE_VIEW)
    ax.set_box_aspect(None, zoom=0.88)  # (room for the axis labels)
    ax.legend(frameon=False, loc="upper left", fontsize=9)


def _pleat_lighter(colors: np.ndarray) -> np.ndarray:
    """The facets of the leg AB (inside the pleat, between the loci of A and B) lightened
    halfway to white, so that the fold shows whatever the viewpoint."""
    n_oa, n_ab = SURFACE_SAMPLES["OA"], SURFACE_SAMPLES["AB"]
    out = np.array(colors, dtype=float)
    out[:, n_oa : n_oa + n_ab, :3] = 0.5 + 0.5 * out[:, n_oa : n_oa + n_ab, :3]
    return out


def _span(values) -> tuple[float, float]:
    lo, hi = float(min(values)), float(max(values))
    return (lo, hi) if hi > lo else (lo - 0.5, hi + 0.5)


def _path_row(res, g_lim: float) -> tuple[np.ndarray, np.ndarray]:
    """The path O→A→B→C as :data:`SURFACE_SAMPLES` points per leg, evenly spaced along each
    leg's drawn curve (its dense output), the reloading leg cut at ``g_lim`` (C's slip
    diverges at the C boundary): a row of the response surface."""
    gs, fs = [], []
    for leg, n in SURFACE_SAMPLES.items():
        d = leg_curve(res, leg)
        g, f = np.asarray(d["g_T"], dtype=float), np.asarray(d["F_T"], dtype=float)
        if leg == "BC" and g[-1] > g_lim:
            k = int(np.argmax(g > g_lim))
            f_cut = np.interp(g_lim, g[k - 1 : k + 1], f[k - 1 : k + 1]) if k else f[0]
            g, f = np.append(g[:k], g_lim), np.append(f[:k], f_cut)
        u = np.concatenate(
            [[0.0], np.cumsum(np.hypot(np.diff(g) / g_lim, np.diff(f) / max(f.max(), 1e-300)))]
        )
        u = u / u[-1] if u[-1] > 0 else np.linspace(0.0, 1.0, u.size)
        t = np.linspace(0.0, 1.0, n)
        gs.append(np.interp(t, u, g))
        fs.append(np.interp(t, u, f))
    return np.concatenate(gs), np.concatenate(fs)


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
            EVENT_LABELS.get(ev["event"], ev["event"]),
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
    """The snap-back and snap-through energies along the loci, at the rows where they were
    integrated (:data:`cusp.models.manifold.ENERGY_ROWS` of them at most, the others
    NaN), marked and joined."""
    loci = run.loci
    p, cols = loci.parameter, loci.columns
    ax = fig.add_subplot()
    for kind, color in (("snap_back", _POINT_COLORS["D"]), ("snap_through", _POINT_COLORS["C"])):
        label = f"{kind.replace('_', '-')} energy (area AB{'D' if kind == 'snap_back' else 'C'})"
        # (integrated at some rows only, ENERGY_ROWS: the others are NaN) those rows, marked
        x, e = np.asarray(cols[p], dtype=float), np.asarray(cols[f"{kind}_energy"], dtype=float)
        ok = np.isfinite(x) & np.isfinite(e)
        ax.plot(x[ok], e[ok], ".-", color=color, ms=4, label=label)
    for ev in loci.events:
        ax.axvline(ev[p], color="0.45", lw=0.8, ls=":")
        ax.annotate(
            EVENT_LABELS.get(ev["event"], ev["event"]),
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
    """The regime map over (μ, F'_N): the regions between the traced boundary curves filled
    as polygons (see the module), the boundaries drawn on them, the scene's cases marked."""
    from cusp.models.regimes import regime_boundaries

    from .cases import build_body, loci_options, make_model

    scene = run.scene
    mu0, load = scene.manifold["start"]
    model = make_model(scene, build_body(scene, mu0), load)
    mu_span, (lo, hi) = regime_spans(scene)
    rb = regime_boundaries(model, mu_span, (lo, hi), options=loci_options(scene))
    ax = fig.add_subplot()
    mu = rb.mu
    z = rb.boundaries["F'_T = 0"][1]
    c = rb.boundaries["C boundary"][1]
    d = np.full_like(mu, -math.inf)
    if "D disappears" in rb.boundaries:
        m_d, f_d = rb.boundaries["D disappears"]
        order = np.argsort(m_d)
        inside = (mu >= m_d.min()) & (mu <= m_d.max())
        d[inside] = np.interp(mu[inside], m_d[order], f_d[order])
    edges = [np.full_like(mu, lo), z, np.maximum(z, d), np.maximum.reduce([z, d, c])]
    edges = [np.clip(e, lo, hi) for e in edges] + [np.full_like(mu, hi)]
    for k, (name, color) in enumerate(_REGIONS):
        if np.any(edges[k + 1] > edges[k]):
            ax.fill_between(mu, edges[k], edges[k + 1], color=color, lw=0, label=name)
    styles = {"C boundary": "#2e7d32", "F'_T = 0": "#1f4e79", "D disappears": "#8e44ad"}
    for name, (m, f) in rb.boundaries.items():
        ax.plot(m, f, color=styles.get(name, "k"), lw=1.8, label=EVENT_LABELS.get(name, name))
    cases = [(case.mu, case.load) for case in run.cases]
    if cases:
        m_c, f_c = zip(*cases)
        ax.plot(m_c, f_c, "o", mfc="white", mec="k", ms=6, ls="none", label="the scene's cases")
    ax.set_xlim(*mu_span)
    ax.set_ylim(lo, hi)
    if mu_span[1] > 10.0 * mu_span[0]:
        ax.set_xscale("log")
    ax.set_xlabel(r"friction coefficient $\mu$")
    ax.set_ylabel(r"reduced normal load $F'_N$ [N]")
    fig.legend(frameon=False, loc="outside lower center", ncol=2, fontsize=9)
