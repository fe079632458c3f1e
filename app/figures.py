"""Figures of a contact-loss scene (the paper's Figs 6–8), rendered to PNG and SVG bytes.

* ``force-slip``: F_T against g_T along O→A→B→C (Fig 6a; with several reductions of the
  normal load, Fig 8: the shared loading curve O→A in black, each reduction's A→B dashed and
  B→C solid in its own colour, B, C and D marked for every case);
* ``force-slip-detail``: the region around AB magnified, with the snap-back A→D, the
  snap-through A→C and the released areas ABD and ABC shaded (Fig 6b);
* ``force-area``: F_T against the total slipped area Â_SL (Fig 7), on which the path is
  single-valued;
* ``fig9``: one panel per case, F_T against g_T (Fig 9 (a) and (b): a low and a high μ),
  each with the snap-back and snap-through.

The curves are the legs' dense output (the tracer's cubic Hermite arcs, within the
branch's ``rtol`` of the path, no Newton; :meth:`cusp.continuation.Branch.interpolate`),
:data:`ARC_SAMPLES` points per step. Every label is mathtext; the point labels sit inside
the axes, clear of the tick labels (``tests/app/test_figures_text.py`` checks every
bundled scene's figures for overlapping text).

The figures of the loci of a ``[manifold]`` scene are drawn by :mod:`cusp.app.manifold_figures`.

Matplotlib is imported here only (never by the solver or the models), with the Agg canvas
and no pyplot state; SVG output carries no date and a fixed hash salt, so a scene renders to
the same bytes every time.
"""

from __future__ import annotations

import contextlib
import functools
import io
import threading
from typing import Any

import numpy as np

__all__ = ["draw", "encode", "figure_bytes", "leg_curve", "render", "title_problem"]

_COLORS = ("#1f4e79", "#c0392b", "#2e7d32", "#8e44ad", "#d35400", "#546e7a")
#: the colour of a curve shared by every case (the loading O→A at a common μ)
SHARED_COLOR = "0.15"
#: dense-output points per traced step of a leg
ARC_SAMPLES = 6
#: where each point's label goes, in points from the point, and its alignment: O right of
#: the origin, below the path and above the axis (clear of the 0 tick labels), the others
#: away from the path
_OFFSETS = {
    "O": ((12, 1.5), "left", "bottom"),
    "A": ((-4, 5), "right", "bottom"),
    "B": ((-5, -4), "right", "top"),
    "C": ((0, 6), "center", "bottom"),
    "D": ((5, -4), "left", "top"),
}


def render(cases, names, *, title: str = "") -> dict[str, dict[str, bytes]]:
    """``{figure name: {"png": bytes, "svg": bytes}}`` for ``cases`` (a list of
    :class:`cusp.app.run.Case`: μ, F'_N [N], ContactLossResult)."""
    return {name: encode(fig) for name, fig in draw(cases, names, title=title).items()}


def draw(cases, names, *, title: str = "") -> dict:
    """``{figure name: matplotlib Figure}`` (Agg canvas, not yet laid out) for ``cases``, as
    :func:`render` encodes them."""
    import matplotlib

    mus = {mu for mu, _, _ in cases}
    dense = [
        (_case_label(mu, load, len(mus) > 1), res, {leg: leg_curve(res, leg) for leg in res.legs})
        for mu, load, res in cases
    ]
    makers = {"force-slip": _force_slip, "force-slip-detail": _detail, "force-area": _force_area}
    out = {}
    with matplotlib.rc_context({"font.size": 10}):
        for name in names:
            if name == "fig9":
                fig = new_figure((4.6 * len(dense), 4.4))
                _panels(fig, dense, title)
            else:
                fig = new_figure((6.4, 4.8))
                ax = fig.add_subplot()
                makers[name](ax, dense, shared_oa=len(mus) == 1)
                if title:
                    ax.set_title(title)
            out[name] = fig
    return out


def leg_curve(res, leg: str, per_step: int = ARC_SAMPLES) -> dict[str, np.ndarray]:
    """Physical columns of ``res``'s leg along its dense output (``per_step`` points per
    traced step, the Hermite arcs within the branch's rtol of the path); where a step has no
    arc within rtol, the Newton-corrected points of :meth:`ContactLossResult.dense`."""
    from cusp.continuation import AccuracyError

    br = res.legs[leg]
    S = np.asarray(br.s, dtype=float)
    theta = np.arange(per_step) / per_step
    s = np.append((S[:-1, None] + np.diff(S)[:, None] * theta).ravel(), S[-1])
    try:
        return res._physical(br.interpolate(s))
    except AccuracyError:
        return res.dense(leg)


def encode(fig, dpi: int = 150) -> dict[str, bytes]:
    """``fig`` as PNG and SVG bytes (:func:`figure_bytes`), laid out once: the constrained
    layout is computed, then frozen for both formats."""
    with shared_mathtext():
        engine = fig.get_layout_engine()
        if engine is not None:
            engine.execute(fig)
            fig.set_layout_engine("none")
        return {fmt: figure_bytes(fig, fmt, dpi=dpi) for fmt in ("png", "svg")}


#: parsed mathtext strings kept across renderers by :func:`shared_mathtext`
MATHTEXT_KEPT = 512
_mathtext_lock = threading.Lock()
_mathtext_open: dict[str, Any] = {"contexts": 0, "original": None}  # (matplotlib's method
# while contexts are open)


@functools.lru_cache(maxsize=MATHTEXT_KEPT)
def _parsed(parse, parser, s, dpi, prop, antialiased, load_glyph_flags, rc):
    # (rc: the mathtext.* settings the parse reads, part of the key only)
    return parse(parser.parser, s, dpi, prop, antialiased, load_glyph_flags)


def _mathtext_settings() -> tuple:
    """The ``mathtext.*`` rcParams (fonts of the fontsets, default style, fallback): a parse
    kept under other settings is not reused."""
    import matplotlib

    rc: Any = matplotlib.rcParams
    return tuple(repr(rc[k]) for k in _mathtext_keys())


@functools.cache
def _mathtext_keys() -> tuple[str, ...]:
    """(matplotlib's rcParams accept no new keys: their names are fixed at import)"""
    import matplotlib

    return tuple(k for k in sorted(matplotlib.rcParams) if k.startswith("mathtext."))


class _ByOutput:
    """A mathtext parser as a cache key: parsers of one output type give the same parse (the
    grammar is shared by their class)."""

    __slots__ = ("parser",)

    def __init__(self, parser):
        self.parser = parser

    def __hash__(self) -> int:
        return hash(self.parser._output_type)

    def __eq__(self, other) -> bool:
        return (
            isinstance(other, _ByOutput) and self.parser._output_type == other.parser._output_type
        )


@contextlib.contextmanager
def shared_mathtext():
    """Parse each mathtext string once for all renderers while inside.

    Matplotlib keeps the parses of a renderer's own parser only, and every figure's Agg
    canvas and every SVG file makes a new one: a scene's figures parsed their title, axis
    labels and log-scale tick labels again for each figure and format (3–15 ms each, a fifth
    of the drawing). Inside, the parses are kept by what determines them (output type,
    string, dpi, font, antialiasing, hinting, the ``mathtext.*`` settings),
    :data:`MATHTEXT_KEPT` of them, across
    renderers and calls; the bytes drawn are the same. Without the private method this
    relies on (another matplotlib), nothing changes. Thread-safe; nests.
    """
    from matplotlib.mathtext import MathTextParser

    with _mathtext_lock:
        original = MathTextParser.__dict__.get("_parse_cached")
        inner = getattr(original, "__wrapped__", None)
        if _mathtext_open["contexts"] == 0 and inner is not None:

            def cached(self, s, dpi, prop, antialiased, load_glyph_flags):
                args = (s, dpi, prop, antialiased, load_glyph_flags, _mathtext_settings())
                return _parsed(inner, _ByOutput(self), *args)

            _mathtext_open["original"] = original
            setattr(MathTextParser, "_parse_cached", cached)  # noqa: B010 (private to mpl)
        _mathtext_open["contexts"] += 1
    try:
        yield
    finally:
        with _mathtext_lock:
            _mathtext_open["contexts"] -= 1
            if _mathtext_open["contexts"] == 0 and _mathtext_open["original"] is not None:
                setattr(MathTextParser, "_parse_cached", _mathtext_open["original"])  # noqa: B010
                _mathtext_open["original"] = None


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
    """A matplotlib Figure on the Agg canvas (no pyplot state), at the dpi it is saved at."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=size, dpi=150, layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def _case_label(mu: float, load: float, by_mu: bool) -> str:
    """How a case is named in legends and panel titles: by what varies among the cases."""
    return f"$\\mu = {mu:g}$" if by_mu else f"$F'_N = {load:g}$ N"


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
    for key in which:
        pt = res.points.get(key)
        if pt is None:
            continue
        offset, ha, va = _OFFSETS[key]
        ax.plot(pt[x], pt["F_T"], "o", color=color, ms=4, zorder=5)
        ax.annotate(
            key,
            (pt[x], pt["F_T"]),
            textcoords="offset points",
            xytext=offset,
            ha=ha,
            va=va,
            color=color,
            fontsize=10,
        )


def _paths(ax, dense, x: str, xlabel: str, shared_oa: bool) -> None:
    """F_T against ``x`` for every case (Figs 6a, 7, 8). With several cases: the loading
    curve O→A drawn once in a neutral colour when it is shared (one μ), each case's AB
    dashed; O and A labelled once, B, C and D for every case in its colour."""
    several = len(dense) > 1
    shared = several and shared_oa
    if shared:
        oa = dense[0][2]["OA"]
        ax.plot(oa[x], oa["F_T"], "-", color=SHARED_COLOR, lw=1.6, label="O–A (every case)")
    for i, (label, res, legs) in enumerate(dense):
        color = _COLORS[i % len(_COLORS)]
        for leg, cols in legs.items():
            if leg == "OA" and shared:
                continue
            style = "--" if (leg == "AB" and several) else "-"
            first = leg == ("BC" if shared else "OA")
            ax.plot(
                cols[x], cols["F_T"], style, color=color, lw=1.6, label=label if first else None
            )
        if shared:
            _label_points(ax, res, x, which=("B", "C", "D"), color=color)
        else:
            _label_points(
                ax,
                res,
                x,
                which="OABCD" if i == 0 else "ABCD",
                color="k" if not several else color,
            )
    if shared:
        _label_points(ax, dense[0][1], x, which=("O", "A"), color=SHARED_COLOR)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(r"tangential force $F_T$ [N]")
    ax.margins(x=0.07, y=0.09)
    ax.set_xlim(left=0.0)
    ax.set_ylim(bottom=0.0)
    if several:
        ax.legend(frameon=False, loc="lower right")
    ax.grid(alpha=0.3)


def _force_slip(ax, dense, shared_oa: bool = True) -> None:
    _paths(ax, dense, "g_T", r"relative tangential displacement $g_T$ [µm]", shared_oa)


def _force_area(ax, dense, shared_oa: bool = True) -> None:
    xlabel = r"total slipped contact area $\hat A_{SL} = A_{SL}/A_r$"
    _paths(ax, dense, "A_SL", xlabel, shared_oa)


def _panels(fig, dense, title: str) -> None:
    """Fig 9 (a), (b), ...: one panel per case, the whole path with the snap-back A→D and
    the snap-through A→C drawn as arrows."""
    axes = fig.subplots(1, len(dense), squeeze=False)[0]
    for i, (ax, case) in enumerate(zip(axes, dense)):
        label, res, legs = case
        _paths(ax, [case], "g_T", r"$g_T$ [µm]", True)
        for key, color in (("D", _COLORS[1]), ("C", _COLORS[2])):
            _arrow(ax, res.points["A"], res.points[key], color, 1.2)
        ax.set_title(f"({chr(ord('a') + i)}) {label}")
        if i:
            ax.set_ylabel("")
    if title:
        fig.suptitle(title)


def _arrow(ax, start, end, color, lw: float) -> None:
    """An arrow from point ``start`` to point ``end`` (nothing if ``end`` does not exist)."""
    if end is not None:
        ax.annotate(
            "",
            xy=(end["g_T"], end["F_T"]),
            xytext=(start["g_T"], start["F_T"]),
            arrowprops={"arrowstyle": "->", "color": color, "lw": lw},
        )


def _detail(ax, dense, shared_oa: bool = True) -> None:
    _, res, legs = dense[0]
    A, B, C, D = (res.points[k] for k in "ABCD")
    ab, bc = legs["AB"], legs["BC"]
    for leg in ("OA", "AB", "BC"):
        ax.plot(legs[leg]["g_T"], legs[leg]["F_T"], "-", color=_COLORS[0], lw=1.8)
    g_hi = C["g_T"] if C is not None else bc["g_T"][-1]
    if D is not None:
        # area ABD: between AB (above) and the reloading curve (below), g_B <= g <= g_A
        g = np.linspace(B["g_T"], A["g_T"], 200)
        upper = np.interp(g, ab["g_T"][::-1], ab["F_T"][::-1])
        lower = np.interp(g, bc["g_T"], bc["F_T"])
        energy = f"{res.energy['snap_back']:.6g}"
        ax.fill_between(
            g,
            lower,
            upper,
            color=_COLORS[1],
            alpha=0.35,
            label=f"area ABD = snap-back energy, ${energy}$ N·µm",
        )
        _arrow(ax, A, D, _COLORS[1], 1.4)
    if C is not None:
        g = np.linspace(A["g_T"], C["g_T"], 200)
        lower = np.interp(g, bc["g_T"], bc["F_T"])
        energy = f"{res.energy['snap_through']:.6g}"
        ax.fill_between(
            g,
            lower,
            np.full_like(g, A["F_T"]),
            color=_COLORS[2],
            alpha=0.3,
            label=f"area ABC = ABD + ADC = snap-through energy, ${energy}$ N·µm",
        )
        _arrow(ax, A, C, _COLORS[2], 1.4)
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
