"""Plotting helpers (matplotlib imported lazily). Each takes ``ax=None`` and returns the Axes."""

from __future__ import annotations

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
