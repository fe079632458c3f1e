"""``cusp demo``: trace the cusp normal form x³ − a·x − b = 0 over b ∈ [−1, 1] at fixed a and
print the folds, compared with the closed form b = ∓2(a/3)^{3/2}.

``cusp demo --hopf``: the Brusselator x' = a − (b + 1)x + x²y, y' = bx − x²y at fixed a,
traced in b with stability: its Hopf point against the closed forms b = 1 + a², ω = a and
l1 = −(a² + 2)/(2a(2a² + 1)), and the stability along the branch; ``--out FILE.png`` draws
the Hopf diagram (x against b, stable solid, unstable dashed)."""

from __future__ import annotations

import math
import os
import time
from pathlib import Path


def add_arguments(parser) -> None:
    parser.add_argument("--a", type=float, default=1.0, help="fixed parameter a > 0 (default 1)")
    parser.add_argument(
        "--hopf", action="store_true", help="the Brusselator's Hopf point and stability instead"
    )
    parser.add_argument("--out", default=None, help="with --hopf: write the diagram (PNG) here")


def main(args) -> int:
    from cusp.continuation import trace
    from cusp.examples import cusp_normal_form

    a = args.a
    if not (math.isfinite(a) and a > 0):
        print(f"cusp demo: --a must be a finite number > 0, got {a!r}")
        return 2
    if args.hopf:
        return hopf_demo(a, args.out)
    exact = 2.0 * (a / 3.0) ** 1.5
    bmax = max(1.0, 2.0 * exact)  # wide enough to hold both folds
    # analytic derivatives; u0 the leftmost real root at b = -bmax; bounds b in [-bmax, bmax]
    example = cusp_normal_form(a=a, b=-bmax)
    start = time.perf_counter()
    # the folds are printed to 15 decimals: located to that (the default is 1e-12 relative)
    br = trace(example.problem, example.u0, free="b", bounds=example.bounds, locate_tol=1e-15)
    elapsed = time.perf_counter() - start
    print(f"cusp normal form x^3 - a x - b = 0, a = {a:g}: traced b in [{-bmax:g}, {bmax:g}]")
    print(f"  {len(br)} points, status {br.status!r}: {br.message} ({elapsed * 1e3:.2f} ms)")
    print(f"  {'kind':<10}{'x':>22}{'b':>22}{'|b| - 2(a/3)^1.5':>20}  status")
    for sp in br.special_points:
        if sp.kind != "fold":
            continue
        err = abs(sp.values["b"]) - exact
        print(
            f"  {sp.kind:<10}{sp.values['x']:>22.15f}{sp.values['b']:>22.15f}{err:>20.2e}  "
            f"{sp.status}"
        )
    return 0 if br.success else 1


def hopf_demo(a: float, out: str | None) -> int:
    """The Brusselator's Hopf point at fixed ``a`` (see the module); 0 if found."""
    import numpy as np

    from cusp.continuation import Problem, trace

    def residual(u, p):
        x, y = u
        return np.array([a - (p["b"] + 1) * x + x * x * y, p["b"] * x - x * x * y])

    def jacobian(u, p):
        x, y = u
        b = p["b"]
        return np.array([[-(b + 1) + 2 * x * y, x * x], [b - 2 * x * y, -x * x]])

    prob = Problem(residual, ["x", "y"], {"b": 1.0}, jacobian=jacobian, mass=True)
    b_hi = 2.0 * (1.0 + a * a)
    br = trace(prob, [a, 1.0 / a], free="b", bounds={"b": (1.0, b_hi)}, stability=True)
    print(f"Brusselator, a = {a:g}: traced b in [1, {b_hi:g}], {len(br)} points, {br.status!r}")
    exact = {"b": 1 + a * a, "omega": a, "l1": -(a * a + 2) / (2 * a * (2 * a * a + 1))}
    print(f"  {'':<16}{'computed':>22}{'closed form':>22}")
    for hopf in br.special("hopf"):
        found = {"b": hopf.values["b"], "omega": hopf.details.get("omega")}
        found["l1"] = hopf.details.get("first_lyapunov")
        for key, value in found.items():
            shown = "-" if value is None else f"{value:.15g}"
            print(f"  {'hopf ' + key:<16}{shown:>22}{exact[key]:>22.15g}")
        print(f"  {hopf.status}, {hopf.details.get('criticality', 'no criticality')}")
    n = br["n_unstable"]
    print(f"  unstable eigenvalues: {int(n[0])} at b = 1, {int(n[-1])} at b = {b_hi:g}")
    if out is not None:
        _hopf_figure(br, out)
        print(f"  diagram written to {out}")
    return 0 if br.success and len(br.special("hopf")) == 1 else 1


def _hopf_figure(br, out: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from cusp.app.figures import figure_bytes

    fig, ax = plt.subplots(figsize=(5, 3.5))
    br.plot("b", "x", ax=ax)
    ax.set_title("Brusselator: a Hopf point at b = 1 + a²")
    ax.legend()
    data = figure_bytes(fig, "png")
    plt.close(fig)
    path = Path(out)
    tmp = path.with_name(path.name + ".tmp")
    try:  # atomically: an interrupted run leaves no half-written figure
        tmp.write_bytes(data)
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
