"""Plotting helpers (matplotlib imported lazily). Each takes ``ax=None`` and returns the Axes.

A branch is drawn along its dense output (the cubic Hermite arcs between its rows,
:data:`SAMPLES` points each, not the chords; a segment without an arc within the branch's
rtol, or a branch without an interpolant, by its chord), its rows marked with small dots
(``points=False`` leaves them out). A branch traced with stability (a column
``"n_unstable"``) has its stable parts solid and unstable ones dashed; a segment with a fold
or Hopf row at one end takes the stability of its other end.
"""

from __future__ import annotations

import numpy as np

from .._errors import AccuracyError
from .._outcomes import Kind
from ._dense import arrays, check_segment, segment

#: dense-output points drawn per segment of a branch with stability
SAMPLES = 16
#: special points where stability changes: a segment takes its other end's
_CHANGES = (Kind.FOLD, Kind.HOPF, Kind.BRANCH_POINT)

_MARKERS = {
    "fold": ("o", "tab:red"),
    "branch_point": ("s", "tab:green"),
    "cusp": ("*", "tab:purple"),
    "event": ("^", "tab:orange"),
    "target": ("d", "tab:gray"),
    "endpoint": ("x", "k"),
}


def plot_branch(
    branch, x: str, y: str, ax=None, *, special: bool = True, points: bool = True, **kwargs
):
    """Plot ``branch[y]`` against ``branch[x]`` along its dense output, its rows (``points``)
    and special points marked (see the module)."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots()
    kwargs.setdefault("lw", 1.5)
    if x in branch.variables and y in branch.variables and len(branch) > 1:
        color = _plot_stability(branch, x, y, ax, kwargs)
    else:  # a column not traced (no interpolant): the rows joined
        (line,) = ax.plot(branch[x], branch[y], **kwargs)
        color = line.get_color()
    if points:
        ax.plot(branch[x], branch[y], ".", color=color, ms=3.5, ls="none")
    if special:
        seen = set()
        for sp in branch.special_points:
            marker, color = _MARKERS.get(sp.kind, ("o", "k"))
            label = sp.kind if sp.kind not in seen else None
            seen.add(sp.kind)
            ax.plot(sp.values[x], sp.values[y], marker, color=color, ms=6, label=label, ls="none")
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    return ax


def _segment_unstable(branch, i: int) -> bool:
    """Whether segment ``i`` is unstable (see the module; False without stability)."""
    if "n_unstable" not in branch:
        return False
    n = branch["n_unstable"]
    changes = {sp.index for sp in branch.special_points if sp.kind in _CHANGES}
    a, b = int(n[i]), int(n[i + 1])
    if i in changes and i + 1 not in changes:
        return b > 0
    if i + 1 in changes and i not in changes:
        return a > 0
    return max(a, b) > 0


def _samples(branch, i: int, cols: tuple[int, int], arcs) -> np.ndarray:
    """Points of segment ``i`` in the columns ``cols``: its arc, or the chord if it has none."""
    theta = np.linspace(0.0, 1.0, SAMPLES + 1)
    if arcs is not None and branch.s[i + 1] > branch.s[i]:
        Z, T, w, errors, rtol = arcs
        try:
            check_segment(branch, i, errors[i + 1], rtol)
            return segment(Z, T, w, i).sample(theta)[:, list(cols)]
        except AccuracyError:
            pass
    names = [branch.variables[c] for c in cols]
    z0 = np.array([branch[v][i] for v in names])
    z1 = np.array([branch[v][i + 1] for v in names])
    return z0 + theta[:, None] * (z1 - z0)


def _plot_stability(branch, x: str, y: str, ax, kwargs: dict):
    """Runs of equally stable segments, one line each: solid stable, dashed unstable (one
    run, in the given style, for a branch without stability); returns the colour used."""
    try:
        arcs = arrays(branch)
    except AccuracyError:
        arcs = None
    cols = (branch.variables.index(x), branch.variables.index(y))
    runs: list[tuple[bool, list[np.ndarray]]] = []
    for i in range(len(branch) - 1):
        unstable = _segment_unstable(branch, i)
        if not runs or runs[-1][0] != unstable:
            runs.append((unstable, []))
        runs[-1][1].append(_samples(branch, i, cols, arcs))
    stability = "n_unstable" in branch
    if stability:
        for key in ("ls", "linestyle"):  # (the style says the stability)
            kwargs.pop(key, None)
    color = kwargs.pop("color", kwargs.pop("c", None))
    label = kwargs.pop("label", None)
    seen: set[bool] = set()
    for unstable, pieces in runs:
        pts = np.vstack(pieces)
        style = {"ls": "--" if unstable else "-"} if stability else {}
        name = None if unstable in seen or not stability else ("unstable" if unstable else "stable")
        name = name if label is None else (label if not seen else None)
        seen.add(unstable)
        (line,) = ax.plot(pts[:, 0], pts[:, 1], color=color, label=name, **style, **kwargs)
        color = line.get_color()
    return color
