"""Reproduce Fig 5 of Carpinteri, Paggi & Zavarise: stick force (a) and stick area (b) against
the tangential force, for spheres, cylinders, rough surfaces (exponential heights) and flat
planes, all four on each plot.

    python scripts/fig5.py [--out docs/figures] [--gaussian-t 2.0]

Writes fig5a.{png,svg} and fig5b.{png,svg}. ``--gaussian-t`` adds the Gaussian rough surface
at separation d/σ* (its curves depend on the load level; not in the paper's figure).
"""

from __future__ import annotations

import argparse
import pathlib
import sys

import numpy as np

from cusp._scripts.report import save_figure
from cusp.models import Cylinder, ExponentialRoughSurface, FlatPlane, Sphere

ROOT = pathlib.Path(__file__).resolve().parents[1]


def curves(n: int = 801, gaussian_t: float | None = None):
    """{label: (F̂_T, F̂_ST, Â_ST)} for each body, F̂_T on [0, 1]."""
    F = np.linspace(0.0, 1.0, n)
    bodies = {
        "spheres": Sphere(),
        "cylinders": Cylinder(),
        "rough surfaces (exponential)": ExponentialRoughSurface(sigma=2.0, nu=0.3, mu=0.1),
        "flat planes": FlatPlane(),
    }
    out = {k: (F, b.stick_force_ratio(F), b.stick_area_ratio(F)) for k, b in bodies.items()}
    if gaussian_t is not None:
        from cusp.models import GaussianRoughSurface

        g = GaussianRoughSurface(sigma=2.0, nu=0.3, mu=0.1)
        Fg = np.linspace(0.0, 1.0, 101)
        d = 2.0 * gaussian_t
        out[f"rough surfaces (Gaussian, d/σ* = {gaussian_t:g})"] = (
            Fg,
            g.stick_force_ratio(Fg, separation=d),
            g.stick_area_ratio(Fg, separation=d),
        )
    return out


def plot(out_dir: pathlib.Path, gaussian_t: float | None = None) -> list[pathlib.Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    data = curves(gaussian_t=gaussian_t)
    styles = {"spheres": "-", "cylinders": "--", "flat planes": ":"}
    written = []
    for panel, index, ylabel, title in (
        ("a", 1, r"$\hat F_T^{ST}$", "(a) Nondimensional stick tangential force"),
        ("b", 2, r"$\hat A^{ST}$", "(b) Nondimensional stick contact area"),
    ):
        fig, ax = plt.subplots(figsize=(5.0, 4.2))
        for label, arrays in data.items():
            F, y = arrays[0], arrays[index]
            ls = styles.get(label, "-." if "Gaussian" in label else "-")
            lw = 2.2 if "exponential" in label else 1.6
            # the drop at F̂_T = 1 is vertical: draw it (the paper does)
            ax.plot(F, y, ls, lw=lw, label=label)
        ax.set_xlim(0, 1)
        ax.set_ylim(0, 1.02)
        ax.set_xlabel(r"$\hat F_T = F_T/(\mu F_N)$")
        ax.set_ylabel(ylabel)
        ax.set_title(title, fontsize=10)
        ax.legend(fontsize=8, loc="upper left" if panel == "a" else "lower left")
        ax.grid(alpha=0.3)
        fig.tight_layout()
        for ext in ("png", "svg"):
            path = out_dir / f"fig5{panel}.{ext}"
            save_figure(fig, path, dpi=150)
            written.append(path)
        plt.close(fig)
    return written


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=pathlib.Path, default=ROOT / "docs" / "figures")
    parser.add_argument("--gaussian-t", type=float, default=None)
    args = parser.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    for path in plot(args.out, args.gaussian_t):
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
