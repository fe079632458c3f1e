"""Drawing a :class:`~._records.Diagram` (matplotlib imported lazily)."""

from __future__ import annotations

from typing import Any

import numpy as np


def plot_diagram(diagram: Any, x: str, y: str, ax: Any = None, *, points: bool = True) -> Any:
    """Every branch of ``diagram`` (one colour each; solid where a column ``n_unstable`` is
    0, dashed where it is positive, solid throughout without it) and its branch points."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots()
    colors = plt.rcParams["axes.prop_cycle"].by_key().get("color", ["k"])
    for i, item in enumerate(diagram.branches):
        br = item.branch
        color = colors[i % len(colors)]
        label = f"branch {i}" + (" (closed)" if item.closed else "")
        if "n_unstable" in br:
            unstable = np.asarray(br["n_unstable"]) > 0
            stable_x = np.where(unstable, np.nan, br[x])
            unstable_x = np.where(unstable, br[x], np.nan)
            ax.plot(stable_x, br[y], "-", color=color, lw=1.5, label=label)
            ax.plot(unstable_x, br[y], "--", color=color, lw=1.2)
        else:
            ax.plot(br[x], br[y], "-", color=color, lw=1.5, label=label)
    if points and diagram.points:
        px = [p.point.values[x] for p in diagram.points]
        py = [p.point.values[y] for p in diagram.points]
        ax.plot(px, py, "s", color="k", ms=5, ls="none", label="branch points")
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    return ax


__all__ = ["plot_diagram"]
