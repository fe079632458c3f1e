"""Figures of a contact-loss scene (the paper's Figs 6–8), rendered to PNG and SVG bytes.

* ``force-slip``: F_T against g_T along O→A→B→C (Fig 6a; with several reductions of the
  normal load, Fig 8, the post-peak paths AB dashed);
* ``force-slip-detail``: the region around AB magnified, with the snap-back A→D, the
  snap-through A→C and the released areas ABD and ABC shaded (Fig 6b);
* ``force-area``: F_T against the total slipped area Â_SL (Fig 7), on which the path is
  single-valued;
* ``fig9``: one panel per case, F_T against g_T (Fig 9 (a) and (b): a low and a high μ),
  each with the snap-back and snap-through.

The figures of the loci of a ``[manifold]`` scene are drawn by :mod:`cusp.app.manifold_figures`.

Matplotlib is imported here only (never by the solver or the models), with the Agg canvas
and no pyplot state; SVG output carries no date and a fixed hash salt, so a scene renders to
the same bytes every time.
"""

from __future__ import annotations

import io

import numpy as np

__all__ = ["figure_bytes", "render", "title_problem"]

_COLORS = ("#1f4e79", "#c0392b", "#2e7d32", "#8e44ad", "#d35400", "#546e7a")


def render(cases, names, *, title: str = "") -> dict[str, dict[str, bytes]]:
    """``{figure name: {"png": bytes, "svg": bytes}}`` for ``cases`` (a list of
    :class:`cusp.app.run.Case`: μ, F'_N [N], ContactLossResult)."""
    import matplotlib

    mus = {mu for mu, _, _ in cases}
    dense = [
        (_case_label(mu, load, len(mus) > 1), res, {leg: res.dense(leg) for leg in res.legs})
        for mu, load, res in cases
    ]
    makers = {"force-slip": _force_slip, "force-slip-detail": _detail, "force-area": _force_area}
    out: dict[str, dict[str, bytes]] = {}
    with matplotlib.rc_context({"font.size": 10}):
        for name in names:
            if name == "fig9":
                fig = new_figure((4.6 * len(dense), 4.4))
                _panels(fig, dense, title)
            else:
                fig = new_figure((6.4, 4.8))
                ax = fig.add_subplot()
                makers[name](ax, dense)
                if title:
                    ax.set_title(title)
            out[name] = {fmt: figure_bytes(fig, fmt, dpi=150) for fmt in ("png", "svg")}
    return out


def title_problem(title: str) -> str | None:
    """Why ``title`` cannot be drawn (broken mathtext), or None: it is drawn once."""
    fig = new_figure((2.0, 1.0))
    fig.suptitle(title)
    try:
        fig.canvas.draw()
    except ValueError as exc:
        return " ".join(str(exc).split())
    return None


def new_figure(size: tuple[float, float]):
    """A matplotlib Figure on the Agg canvas (no pyplot state)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=size, layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def _case_label(mu: float, load: float, by_mu: bool) -> str:
    """How a case is named in legends and panel titles: by what varies among the cases."""
    return f"$\\mu$ = {mu:g}" if by_mu else f"$F'_N$ = {load:g} N"


def figure_bytes(fig, fmt: str, **savefig_kw) -> bytes:
    """``fig`` saved as ``fmt`` ("png", "svg", ...) without what changes from run to run: no
    PNG software tag, no SVG date, and SVG ids from a fixed hash salt, so the same figure
    gives the same bytes."""
    import matplotlib

    meta = {"svg": {"Date": None}, "png": {"Software": None}}.get(fmt, {})
    buf = io.BytesIO()
    with matplotlib.rc_context({"svg.hashsalt": "cusp"}):
        fig.savefig(buf, format=fmt, metadata=meta, **savefig_kw)
    return buf.getvalue()


def _label_points(ax, res, x: str, which=("O", "A", "B", "C", "D"), color="k") -> None:
    offsets = {"O": (6, -12), "A": (4, 6), "B": (-12, -12), "C": (4, 6), "D": (6, -10)}
    for key in which:
        pt = res.points.get(key)
        if pt is None:
            continue
        ax.plot(pt[x], pt["F_T"], "o", color=color, ms=4, zorder=5)
        ax.annotate(
            key,
            (pt[x], pt["F_T"]),
            textcoords="offset points",
            xytext=offsets[key],
            fontsize=10,
            fontweight="bold",
        )


def _plot_path(ax, dense_legs, x: str, color, label, dashed_ab: bool) -> None:
    for leg, cols in dense_legs.items():
        style = "--" if (leg == "AB" and dashed_ab) else "-"
        ax.plot(
            cols[x], cols["F_T"], style, color=color, lw=1.6, label=label if leg == "OA" else None
        )


def _paths(ax, dense, x: str, xlabel: str) -> None:
    """F_T against ``x`` for every case (Figs 6a, 7, 8): AB dashed when there are several
    reductions, the points labelled for the first case (B only for the others)."""
    several = len(dense) > 1
    for i, (label, res, legs) in enumerate(dense):
        color = _COLORS[i % len(_COLORS)]
        _plot_path(ax, legs, x, color, label, dashed_ab=several)
        if not several or i == 0:
            _label_points(ax, res, x)
        elif res.points["B"] is not None:
            _label_points(ax, res, x, which=("B",), color=color)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(r"tangential force $F_T$ [N]")
    ax.set_xlim(left=0.0)
    ax.set_ylim(bottom=0.0)
    if several:
        ax.legend(frameon=False, loc="lower right")
    ax.grid(alpha=0.3)


def _force_slip(ax, dense) -> None:
    _paths(ax, dense, "g_T", r"relative tangential displacement $g_T$ [µm]")


def _force_area(ax, dense) -> None:
    _paths(ax, dense, "A_SL", r"total slipped contact area $\hat A_{SL} = A_{SL}/A_r$")


def _panels(fig, dense, title: str) -> None:
    """Fig 9 (a), (b), ...: one panel per case, the whole path with the snap-back A→D and
    the snap-through A→C drawn as arrows."""
    axes = fig.subplots(1, len(dense), squeeze=False)[0]
    for i, (ax, case) in enumerate(zip(axes, dense)):
        label, res, legs = case
        _paths(ax, [case], "g_T", r"$g_T$ [µm]")
        for key, color in (("D", _COLORS[1]), ("C", _COLORS[2])):
            end, A = res.points[key], res.points["A"]
            if end is not None:
                ax.annotate(
                    "",
                    xy=(end["g_T"], end["F_T"]),
                    xytext=(A["g_T"], A["F_T"]),
                    arrowprops={"arrowstyle": "->", "color": color, "lw": 1.2},
                )
        ax.set_title(f"({chr(ord('a') + i)}) {label}")
        if i:
            ax.set_ylabel("")
    if title:
        fig.suptitle(title)


def _detail(ax, dense) -> None:
    _, res, legs = dense[0]
    A, B, C, D = (res.points[k] for k in "ABCD")
    ab, bc = legs["AB"], legs["BC"]
    ax.plot(ab["g_T"], ab["F_T"], "-", color=_COLORS[0], lw=1.8)
    ax.plot(bc["g_T"], bc["F_T"], "-", color=_COLORS[0], lw=1.8)
    oa = legs["OA"]
    ax.plot(oa["g_T"], oa["F_T"], "-", color=_COLORS[0], lw=1.8)
    g_hi = C["g_T"] if C is not None else bc["g_T"][-1]
    if D is not None:
        # area ABD: between AB (above) and the reloading curve (below), g_B <= g <= g_A
        g = np.linspace(B["g_T"], A["g_T"], 200)
        upper = np.interp(g, ab["g_T"][::-1], ab["F_T"][::-1])
        lower = np.interp(g, bc["g_T"], bc["F_T"])
        ax.fill_between(
            g,
            lower,
            upper,
            color=_COLORS[1],
            alpha=0.35,
            label=f"area ABD = snap-back energy, {res.energy['snap_back']:.6g} N·µm",
        )
        ax.annotate(
            "",
            xy=(D["g_T"], D["F_T"]),
            xytext=(A["g_T"], A["F_T"]),
            arrowprops={"arrowstyle": "->", "color": _COLORS[1], "lw": 1.4},
        )
    if C is not None:
        g = np.linspace(A["g_T"], C["g_T"], 200)
        lower = np.interp(g, bc["g_T"], bc["F_T"])
        ax.fill_between(
            g,
            lower,
            np.full_like(g, A["F_T"]),
            color=_COLORS[2],
            alpha=0.3,
            label="area ABC = ABD + ADC = snap-through energy, "
            f"{res.energy['snap_through']:.6g} N·µm",
        )
        ax.annotate(
            "",
            xy=(C["g_T"], C["F_T"]),
            xytext=(A["g_T"], A["F_T"]),
            arrowprops={"arrowstyle": "->", "color": _COLORS[2], "lw": 1.4},
        )
    _label_points(ax, res, "g_T", which=("A", "B", "C", "D"))
    g_lo = B["g_T"]
    span = g_hi - g_lo
    f_lo = min(B["F_T"], D["F_T"] if D is not None else B["F_T"])
    f_hi = A["F_T"]
    fspan = f_hi - f_lo
    ax.set_xlim(g_lo - 0.15 * span, g_hi + 0.15 * span)
    ax.set_ylim(f_lo - 0.25 * fspan, f_hi + 0.25 * fspan)
    ax.set_xlabel(r"relative tangential displacement $g_T$ [µm]")
    ax.set_ylabel(r"tangential force $F_T$ [N]")
    ax.legend(frameon=False, loc="lower right", fontsize=9)
    ax.grid(alpha=0.3)
