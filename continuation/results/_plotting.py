"""Plotting helpers (matplotlib imported lazily). Each takes ``ax=None`` and returns the Axes.

A branch traced with stability (a column ``"n_unstable"``) is drawn along its dense output
(the cubic Hermite arcs between its rows, :data:`SAMPLES` points each, not the chords),
stable parts solid and unstable ones dashed; a segment with a fold or Hopf row at one end
takes the stability of its other end.
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


def plot_branch(branch, x: str, y: str, ax=None, *, special: bool = True, **kwargs):
    """Plot ``branch[y]`` against ``branch[x]`` with its special points marked."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots()
    kwargs.setdefault("lw", 1.5)
    if "n_unstable" in branch and x in branch.variables and y in branch.variables:
        _plot_stability(branch, x, y, ax, kwargs)
    else:
        ax.plot(branch[x], branch[y], **kwargs)
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
    """Whether segment ``i`` is unstable (see the module)."""
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


def _plot_stability(branch, x: str, y: str, ax, kwargs: dict) -> None:
    """Runs of equally stable segments, one line each: solid stable, dashed unstable."""
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
    for key in ("ls", "linestyle"):  # (the style says the stability)
        kwargs.pop(key, None)
    color = kwargs.pop("color", kwargs.pop("c", None))
    label = kwargs.pop("label", None)
    seen: set[bool] = set()
    for unstable, pieces in runs:
        pts = np.vstack(pieces)
        style = "--" if unstable else "-"
        name = None if unstable in seen else ("unstable" if unstable else "stable")
        name = name if label is None else (label if not seen else None)
        seen.add(unstable)
        (line,) = ax.plot(pts[:, 0], pts[:, 1], ls=style, color=color, label=name, **kwargs)
        color = line.get_color()
