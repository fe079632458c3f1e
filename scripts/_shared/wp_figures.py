"""The figures of the work–precision benchmark (`bench_work_precision.py`): per group of
tasks, error against wall time and against residual evaluations, one panel per task; every
run as a faint marker, each tool's front (the runs no other run of the tool beats in both
cost and error) as a line."""

from __future__ import annotations

import math

from cusp._scripts.report import save_figure

#: group -> (title, file stem of its figures)
GROUPS = {
    "a": ("Fold location (and the curve)", "wp-folds"),
    "b": ("Fold curve and cusp point of the CO model", "wp-foldcurve"),
    "c": ("Contact-loss paths: the scenes fig6 and gaussian", "wp-contact"),
    "d": ("The μ-locus of the manifold", "wp-manifold"),
}
#: measure -> what it is (the report's words)
MEASURES = {
    "fold": "the folds' parameters, largest relative error",
    "curve": "the branch between its computed points joined by straight lines, largest "
    "distance to the exact curve relative to the typical sizes",
    "dense": "the same for our dense output (`Branch.interpolate`)",
    "cusp": "the cusp point (x, y, s, q2, k), largest relative error",
    "points": "the points A–D (g_T, F_T, Â_SL), largest relative error",
    "energies": "the snap-back and snap-through energies, largest relative error",
    "loci": "the loci of the points at 8 values of μ, largest relative error",
    "events": "the μ of the two events (C boundary, F'_T = 0), largest relative error",
}
_MARKERS = {"fold": "o", "curve": "s", "dense": "^", "cusp": "D", "points": "o",
            "energies": "s", "loci": "o", "events": "v"}  # fmt: skip
_STYLES = ("-", "--", ":", "-.")
_COLORS = {"ours": "C0", "contique": "C1", "pacopy": "C2", "SciPy": "C3"}
PLOT_FLOOR = 1e-16


def front(points):
    """The runs (cost, error) no other run beats in both, by increasing cost."""
    out, best = [], math.inf
    for c, e in sorted(points):
        if e < best:
            out.append((c, e))
            best = e
    return out


def _series(rows, measure, axis):
    pts = []
    for r in rows:
        e = r.errors.get(measure)
        c = r.time * 1e3 if axis == "time" else r.nfev
        if e is None or not math.isfinite(e) or c is None or not math.isfinite(c) or c <= 0:
            continue
        pts.append((float(c), max(float(e), PLOT_FLOOR)))
    return pts


def _panel(ax, task, rows, axis):
    tools = list(dict.fromkeys(r.tool for r in rows))
    measures = [m for m in MEASURES if any(m in r.errors for r in rows)]
    for tool in tools:
        color = _COLORS.get(tool.split()[0], "C7")
        mine = [r for r in rows if r.tool == tool]
        for k, m in enumerate(measures):
            pts = _series(mine, m, axis)
            if not pts:
                continue
            mk = _MARKERS[m]
            ax.scatter(*zip(*pts), s=12, marker=mk, color=color, alpha=0.3, linewidths=0)
            fx, fy = zip(*front(pts))
            ax.plot(fx, fy, _STYLES[k % 4], marker=mk, ms=4, color=color, label=f"{tool}: {m}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_title(task.name, fontsize=9)
    ax.set_xlabel("wall time per run (ms)" if axis == "time" else task.work)
    ax.set_ylabel("error")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=6, loc="best")


def draw_group(these, stem):
    """The two figures of a group (``stem``-time.png, ``stem``-fevals.png); returns
    [(axis, path)]."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = len(these)
    cols = 2 if n > 1 else 1
    nrows = math.ceil(n / cols)
    out = []
    for axis, suffix in (("time", "time"), ("nfev", "fevals")):
        fig, axes = plt.subplots(nrows, cols, figsize=(5.2 * cols, 3.9 * nrows), squeeze=False)
        for ax, (task, rows) in zip(axes.flat, these):
            _panel(ax, task, rows, axis)
        for ax in list(axes.flat)[n:]:
            ax.set_visible(False)
        fig.tight_layout()
        path = stem.with_name(f"{stem.name}-{suffix}.png")
        save_figure(fig, path, dpi=110)
        plt.close(fig)
        out.append(
            (
                "error against wall time"
                if axis == "time"
                else "error against residual evaluations",
                path,
            )
        )
    return out
