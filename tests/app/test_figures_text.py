"""Every figure fit for a paper (issue 32 point 5): each bundled scene's figures, the loci
figures of the [manifold] scene and ``Branch.plot`` are drawn, laid out as saved, and their
text checked with matplotlib's own window extents (the tight bounding boxes of the drawn
text, in pixels):

* no text label (a point's name, an event's name, a legend entry) overlaps a tick label of
  its axes or another text label;
* no text label crosses the frame of its axes (it lies wholly inside or wholly outside);
* every title and label is drawn with mathtext where it names a quantity (no literal
  ``F'_N``, ``F'_T`` or ``mu`` in plain text).

The checker is tested on figures built to fail it (a label on the 0 tick, a label across the
frame, two labels on each other), so that it cannot pass by looking at nothing.
"""

from __future__ import annotations

import re

import pytest

matplotlib = pytest.importorskip("matplotlib")

from cusp.app import figures, manifold_figures  # noqa: E402
from cusp.app.run import bundled_names, bundled_scene, load_scene, run_scene  # noqa: E402

#: plain-text spellings of quantities that must be mathtext (outside $...$)
_PLAIN_MATH = re.compile(r"F'_|F_T|F_N|g_T|\bmu\b|A_SL|sigma")
#: the figures of a scene's paths (the others are the loci figures of a [manifold] scene)
_PATH_FIGURES = ("fig9", "force-slip", "force-slip-detail", "force-area")
#: overlap below this many pixels (antialiasing, at 150 dpi) is not an overlap
_SLACK = 0.5


def _overlap(a, b) -> bool:
    return min(a.x1, b.x1) - max(a.x0, b.x0) > _SLACK and min(a.y1, b.y1) - max(a.y0, b.y0) > _SLACK


def _crosses(box, frame) -> bool:
    """Whether ``box`` is neither wholly inside nor wholly outside ``frame``."""
    inside = (
        box.x0 >= frame.x0 - _SLACK
        and box.x1 <= frame.x1 + _SLACK
        and box.y0 >= frame.y0 - _SLACK
        and box.y1 <= frame.y1 + _SLACK
    )
    return not inside and _overlap(box, frame)


def _ticks(ax, renderer):
    """The tick labels drawn on ``ax`` (visible, non-empty, within the axes' span)."""
    frame = ax.get_window_extent(renderer)
    out = []
    for axis, (lo, hi) in ((ax.xaxis, (frame.x0, frame.x1)), (ax.yaxis, (frame.y0, frame.y1))):
        for tick in axis.get_major_ticks():
            for label in (tick.label1, tick.label2):
                if not (label.get_visible() and label.get_text()):
                    continue
                box = label.get_window_extent(renderer)
                mid = (box.x0 + box.x1) / 2 if axis is ax.xaxis else (box.y0 + box.y1) / 2
                if lo - 1 <= mid <= hi + 1:
                    out.append((label.get_text(), box))
    return out


def text_problems(fig) -> list[str]:
    """What overlaps in ``fig`` (see the module), laid out and drawn as it is saved."""
    from matplotlib.text import Text

    figures.encode(fig)  # laid out once and saved, as the scenes' figures are
    fig.canvas.draw()
    r = fig.canvas.get_renderer()
    problems = []
    labels = []  # (axes, text, bbox) of every text label of the figure
    for ax in fig.axes:
        for t in ax.texts:
            if t.get_visible() and t.get_text():
                labels.append((ax, t.get_text(), Text.get_window_extent(t, r)))
        legend = ax.get_legend()
        if legend is not None:
            labels += [(None, t.get_text(), t.get_window_extent(r)) for t in legend.get_texts()]
    for legend in fig.legends:
        labels += [(None, t.get_text(), t.get_window_extent(r)) for t in legend.get_texts()]
    for k, (ax, text, box) in enumerate(labels):
        for other_ax in fig.axes:
            if other_ax.name == "3d":
                continue
            for tick, tbox in _ticks(other_ax, r):
                if _overlap(box, tbox):
                    problems.append(f"{text!r} overlaps the tick label {tick!r}")
        if ax is not None and ax.name != "3d" and _crosses(box, ax.get_window_extent(r)):
            problems.append(f"{text!r} crosses the frame of its axes")
        for _, other, obox in labels[k + 1 :]:
            if _overlap(box, obox):
                problems.append(f"{text!r} overlaps {other!r}")
    return problems


def plain_math(fig) -> list[str]:
    """The titles and labels of ``fig`` that spell a quantity in plain text."""
    texts = [t.get_text() for t in fig.findobj(matplotlib.text.Text)]
    outside = [re.sub(r"\$[^$]*\$", "", t) for t in texts]
    return [t for t, o in zip(texts, outside) if _PLAIN_MATH.search(o)]


@pytest.fixture(scope="module")
def scene_figures():
    """Every bundled scene's figures, as matplotlib Figures: ``{"scene/figure": Figure}``."""
    out = {}
    for name in bundled_names():
        scene = load_scene(bundled_scene(f"{name}.toml"))
        run, _ = run_scene(scene, plots=False)
        path_figs = [f for f in scene.figures if f in _PATH_FIGURES]
        loci_figs = [f for f in scene.figures if f not in path_figs]
        drawn = figures.draw(run.cases, path_figs, title=scene.title)
        if loci_figs:
            drawn.update(manifold_figures.draw_manifold(run, loci_figs))
        out.update({f"{name}/{fig}": f for fig, f in drawn.items()})
    return out


def test_every_bundled_figure_is_drawn(scene_figures):
    names = set(scene_figures)
    # the figures named by the scenes, among them the manifold's and the regime map
    assert {
        "fig6/force-slip",
        "fig6/force-slip-detail",
        "fig7/force-area",
        "fig8/force-slip",
    } <= names
    assert {"fig9/fig9", "fig9/manifold-surface", "fig9/regime-map"} <= names
    assert {"fig9/loci-control-planes", "fig9/loci-energies"} <= names


def test_no_text_overlaps_in_any_bundled_figure(scene_figures):
    found = {name: text_problems(fig) for name, fig in scene_figures.items()}
    assert {k: v for k, v in found.items() if v} == {}


def test_every_labelled_curve_is_drawn(scene_figures):
    # a curve whose rows are NaN between a few finite ones (the loci's energies, integrated
    # at some rows only) draws nothing: each labelled line has two consecutive finite points
    # (a marker-only line, one finite point)
    import numpy as np

    empty = []
    for name, fig in scene_figures.items():
        for ax in fig.axes:
            for line in ax.get_lines():
                if line.get_label().startswith("_") or ax.name == "3d":
                    continue
                x, y = (np.asarray(v, dtype=float) for v in line.get_data())
                ok = np.isfinite(x) & np.isfinite(y)
                drawn = ok.any() if line.get_linestyle() == "None" else (ok[:-1] & ok[1:]).any()
                if not drawn:
                    empty.append((name, line.get_label()))
    assert empty == []


def test_every_label_names_its_quantities_in_mathtext(scene_figures):
    found = {name: plain_math(fig) for name, fig in scene_figures.items()}
    assert {k: v for k, v in found.items() if v} == {}


def test_branch_plot_has_no_overlapping_text():
    import numpy as np

    from cusp.continuation import Problem, trace

    # the S-curve b = x³ − x with its two folds (x = ±1/√3) marked and labelled in a legend
    prob = Problem(lambda u, p: [p["b"] + u[0] - u[0] ** 3], ["x"], {"b": -1.0})
    br = trace(prob, [-1.3247179572447], free="b", bounds={"b": (-1.0, 1.0)})
    fig = figures.new_figure((4.0, 3.0))
    ax = fig.add_subplot()
    br.plot("b", "x", ax=ax)
    ax.legend()
    assert text_problems(fig) == []
    assert len(ax.get_lines()[0].get_xdata()) > 4 * len(br)  # the dense output
    assert np.array_equal(ax.get_lines()[1].get_xdata(), br["b"])  # the rows marked


def _figure_with(annotate):
    fig = figures.new_figure((4.0, 3.0))
    ax = fig.add_subplot()
    ax.plot([0.0, 1.0], [0.0, 1.0])
    ax.set_xlim(0.0, 1.0)
    ax.set_ylim(0.0, 1.0)
    annotate(ax)
    return fig


@pytest.mark.parametrize(
    ("annotate", "expect"),
    [
        # the old "O" label: 6 points right of and 12 below the origin, on the 0.0 tick
        (
            lambda ax: ax.annotate("O", (0, 0), textcoords="offset points", xytext=(6, -12)),
            "overlaps the tick label",
        ),
        # a label at the right edge, half outside (the old "C" of Fig 9 (b))
        (lambda ax: ax.text(1.0, 0.5, "C", ha="center"), "crosses the frame"),
        (lambda ax: (ax.text(0.5, 0.5, "A"), ax.text(0.5, 0.5, "B")), "'A' overlaps 'B'"),
    ],
)
def test_the_checker_finds_what_it_looks_for(annotate, expect):
    problems = text_problems(_figure_with(annotate))
    assert any(expect in p for p in problems), problems


def test_the_checker_passes_a_clean_figure():
    assert text_problems(_figure_with(lambda ax: ax.text(0.4, 0.5, "A"))) == []


def test_the_plain_math_check_finds_a_literal_subscript():
    fig = figures.new_figure((4.0, 3.0))
    fig.suptitle("F'_N = 850 N, $F'_T = 0$")
    assert plain_math(fig) == ["F'_N = 850 N, $F'_T = 0$"]
