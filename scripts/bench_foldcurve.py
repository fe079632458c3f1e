"""Benchmark: the fold curve of the cusp normal form x³ − a x − b = 0, from the fold at a = 1
through the cusp to the other fold at a = 1, by ``fold_curve`` and by a plain loop.

Exact: the fold curve is (a, b) = (3x², −2x³), i.e. 4a³ = 27b², with the cusp at x = a = b = 0.

- ours: ``trace`` in b finds the fold at a = 1; ``fold_curve(free=("b", "a"), direction=-1,
  bounds a ∈ [−1, 1])`` follows it through the cusp (located by Newton on [F; g; a]) to the
  other fold at a = 1.
- plain loop: for a on a uniform grid 1 → 0, solve [F; F_x] = 0 for (x, b) with
  ``scipy.optimize.fsolve`` from the previous solution; the loop cannot turn at the cusp (a has
  a minimum there), so the second fold branch is a second loop 0 → 1 started from the
  mirrored point x → −x. The cusp is where F_xx = 6x changes sign between the two loops: its
  estimate interpolates linearly in F_xx between the two innermost points, and is then refined
  by bisection in a on whether fsolve still converges (the fold curve exists only for a ≥ 0).

Run: ``python scripts/bench_foldcurve.py`` (prints a Markdown table, writes the figure
``docs/figures/foldcurve_cusp.png`` and ``.svg``). One process, best of ``--repeats`` runs.
"""

from __future__ import annotations

import argparse
import functools
import platform
import time
from pathlib import Path

import numpy as np
from scipy.optimize import fsolve

import cusp.examples as ex
from cusp._scripts.report import save_figure
from cusp.continuation import Problem, fold_curve, trace

ROOT = Path(__file__).resolve().parents[1]

X0 = ex.cusp_start(1.0, -1.0)  # -1.324717957244746, root of x³ − x + 1 (a = 1, b = −1)


def cusp_problem() -> Problem:
    """x³ − a x − b = 0 at a = 1, b = −1, analytic derivatives (`cusp.examples`)."""
    return ex.cusp_normal_form(a=1.0, b=-1.0).problem


def start_fold(prob):
    """The fold at a = 1, x = −1/√3, b = 2/(3√3), located by ``trace`` in b."""
    return trace(prob, [X0], free="b", bounds={"b": (-1.0, 1.0)}).special("fold")[0]


def run_ours(prob, fold):
    fc = fold_curve(prob, fold, free=("b", "a"), direction=-1, bounds={"a": (-1.0, 1.0)})
    (c,) = fc.special("cusp")
    return dict(
        x=fc["x"],
        a=fc["a"],
        b=fc["b"],
        cusp=(c.values["x"], c.values["a"], c.values["b"]),
        status=fc.status,
    )


# The plain loop's own fold system [F; F_x] of the same cusp (x, b unknown at fixed a) and its
# Jacobian, written out as a user of fsolve would.
def _fold_system(xb, a):
    x, b = xb
    return [x**3 - a * x - b, 3 * x**2 - a]


def _fold_jac(xb, a):
    x, _ = xb
    return [[3 * x**2 - a, -1.0], [6 * x, 0.0]]


def _solve(guess, a, xtol=1e-13):
    sol, info, _, _ = fsolve(
        _fold_system, guess, args=(a,), fprime=_fold_jac, full_output=True, xtol=xtol
    )
    # judged by the residual: near the cusp fsolve often reports "not making good progress"
    # (ier = 5) with a residual of 1e-18, as its 2×2 Jacobian (det = 6x) becomes singular
    ok = bool(np.all(np.isfinite(sol))) and np.max(np.abs(info["fvec"])) < 1e-12
    return sol, ok


def run_plain_loop(n: int, refine: bool = True):
    """Grid a_k = 1 − k/n, k = 0 … n − 1, on each fold branch (2n points in all)."""
    grid = 1.0 - np.arange(n) / n
    x_fold = -1 / np.sqrt(3.0)
    guess = np.array([x_fold, x_fold**3 - 1.0 * x_fold])  # the same fold at a = 1
    first = []
    for a in grid:
        guess, ok = _solve(guess, a)
        if not ok:
            break
        first.append((guess[0], a, guess[1]))
    second = []
    guess = np.array([-first[-1][0], -first[-1][2]])  # mirror: the other fold branch
    for a in grid[: len(first)][::-1]:
        guess, ok = _solve(guess, a)
        if not ok:
            break
        second.append((guess[0], a, guess[1]))
    pts = np.array(first + second)
    # cusp: F_xx = 6x changes sign between the innermost points of the two loops
    (x1, a1, b1), (x2, a2, b2) = first[-1], second[0]
    f1, f2 = 6 * x1, 6 * x2
    assert f1 * f2 < 0
    t = f1 / (f1 - f2)
    cusp = (x1 + t * (x2 - x1), a1 + t * (a2 - a1), b1 + t * (b2 - b1))
    n_bisect = 0
    if refine:  # smallest a in [0, a1] where the fold system is still solvable from x1
        lo, hi, best = 0.0 - 1e-3, a1, np.array([x1, b1])
        while hi - lo > 1e-12 and n_bisect < 60:
            n_bisect += 1
            mid = 0.5 * (lo + hi)
            sol, ok = _solve(best, mid)
            if ok:
                hi, best = mid, sol
            else:
                lo = mid
        cusp = (best[0], hi, best[1])
    return dict(x=pts[:, 0], a=pts[:, 1], b=pts[:, 2], cusp=cusp, n_bisect=n_bisect)


def accuracy(res):
    a, b, x = res["a"], res["b"], res["x"]
    rel = np.abs(4 * a**3 - 27 * b**2) / np.maximum(1.0, 4 * np.abs(a) ** 3 + 27 * b**2)
    return dict(
        curve=float(rel.max()),
        state=float(np.max(np.abs(a - 3 * x**2))),
        cusp=float(max(abs(v) for v in res["cusp"])),
        cusp_a=float(abs(res["cusp"][1])),
        points=len(a),
    )


def best_time(fn, repeats):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t)
    return min(times), out


def figure(ours, loop, path_png: Path):
    """The fold curve in the (a, b) plane, both methods, the cusp and the plain loop's
    interpolated cusp estimate."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.0, 4.2), constrained_layout=True)
    xs = np.linspace(-1 / np.sqrt(3.0), 1 / np.sqrt(3.0), 401)
    ax.plot(*ex.cusp_fold_curve(xs), color="0.75", lw=4, label="exact: $4a^3 = 27b^2$")
    ax.plot(
        ours["a"],
        ours["b"],
        "o-",
        color="C0",
        ms=4,
        lw=1.2,
        label=f"fold_curve ({len(ours['a'])} points)",
    )
    ax.plot(
        loop["a"], loop["b"], "x", color="C1", ms=3, label=f"plain loop ({len(loop['a'])} points)"
    )
    ax.plot(
        [ours["cusp"][1]],
        [ours["cusp"][2]],
        "*",
        color="C3",
        ms=14,
        mec="k",
        label="cusp (fold_curve)",
    )
    ax.plot(
        [loop["cusp"][1]],
        [loop["cusp"][2]],
        "D",
        color="C1",
        ms=6,
        mec="k",
        label="cusp estimate (plain loop, interpolated)",
    )
    ax.annotate(
        "cusp $a=b=0$", (0, 0), xytext=(0.25, 0.12), arrowprops=dict(arrowstyle="->", lw=0.8)
    )
    ax.set_xlabel("$a$")
    ax.set_ylabel("$b$")
    ax.set_title("Fold curve of $x^3 - a x - b = 0$ from $a = 1$ through the cusp")
    ax.legend(loc="lower left", fontsize=8)
    save_figure(fig, path_png, dpi=150)
    save_figure(fig, path_png.with_suffix(".svg"))
    plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument(
        "--grid",
        type=int,
        nargs="*",
        default=[None, 200],
        help="plain-loop grid sizes per branch (default: ours' point count/2, 200)",
    )
    ap.add_argument("--figure", default=str(ROOT / "docs" / "figures" / "foldcurve_cusp.png"))
    args = ap.parse_args(argv)

    prob = cusp_problem()
    t_trace, fold = best_time(functools.partial(start_fold, prob), args.repeats)
    run_ours(prob, fold)  # warm-up (first calls)
    t_ours, ours = best_time(functools.partial(run_ours, prob, fold), args.repeats)
    rows = [
        (
            "fold_curve (Newton-located cusp)",
            t_ours,
            accuracy(ours),
            f"start: the fold from trace ({1e3 * t_trace:.1f} ms, not included)",
        )
    ]
    loop_for_fig = None
    for n in args.grid:
        n = n or (len(ours["a"]) + 1) // 2
        for refine in (False, True):
            t, loop = best_time(functools.partial(run_plain_loop, n, refine), args.repeats)
            note = f"grid {n}/branch" + (
                f", {loop['n_bisect']} bisection steps" if refine else ", interpolated"
            )
            rows.append(("plain loop + fsolve", t, accuracy(loop), note))
            if loop_for_fig is None:
                loop_for_fig = loop
    print(
        f"python {platform.python_version()}, numpy {np.__version__}, "
        f"{platform.machine()}, best of {args.repeats}\n"
    )
    print(
        "| method | wall time [ms] | points | max rel. abs(4a³ − 27b²) | max abs(a − 3x²) "
        "| cusp error max(abs(x), abs(a), abs(b)) | notes |"
    )
    print("|---|---:|---:|---:|---:|---:|---|")
    for name, t, acc, note in rows:
        print(
            f"| {name} | {1e3 * t:.2f} | {acc['points']} | {acc['curve']:.1e} | "
            f"{acc['state']:.1e} | {acc['cusp']:.1e} | {note} |"
        )
    figure(ours, loop_for_fig, Path(args.figure))
    print(f"\nfigure: {args.figure} (+ .svg)")


if __name__ == "__main__":
    main()
