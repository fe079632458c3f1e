"""Benchmark how `trace` scales with the number of unknowns on a banded (sparse) problem.

    python scripts/bench_sparse.py [--sizes 999 3999 ...] [--out docs/benchmarks/sparse.md]

The problem is docs/test-problems.md §2, the finite-difference Bratu problem
u'' + λ e^u = 0 on (0, 1), u(0) = u(1) = 0, with N interior nodes. Its Jacobian is
tridiagonal and is given as scipy.sparse (CSC), with ∂R/∂λ = e^u. The branch is traced
from u = 0, λ = 0 to u at the midpoint = 2, past the fold, with the default options
(max_steps = 400). The problem and its references come from `cusp.examples` (`bratu`).

For each N the script reports:
- wall time of the whole trace (best of the repeats), steps, and Newton iterations;
- time per step divided by N;
- the same time in units of one sparse LU (SuperLU) of the bordered matrix at the start
  point, timed in the same process just before. That LU is what a step costs at least, so
  the ratio shows the solver's overhead independent of the machine's speed.
- the fold λ against the mpmath shooting reference (N ≤ 9999) or the stored 40-digit value
  (N = 99999).

For N ≤ 999 the dense Jacobian is timed too, for contrast. The fitted exponent p of
time/step ∝ N^p says how the cost grows: p ≈ 1 is linear.
"""

from __future__ import annotations

import argparse
import datetime
import pathlib
import platform
import time

import numpy as np
import scipy
import scipy.sparse.linalg as spla

import cusp.examples as ex
from cusp._scripts.report import commit, write_report
from cusp.continuation import BranchSystem, trace

ROOT = pathlib.Path(__file__).resolve().parents[1]


def run(n: int, sparse: bool):
    # u = 0 at λ = 0, bounds u at the midpoint in [-1, 2] (past the fold)
    case = ex.bratu(n, sparse=sparse)
    t0 = time.perf_counter()
    br = trace(case.problem, u0=case.u0, free="lam", bounds=case.bounds, max_steps=400)
    elapsed = time.perf_counter() - t0
    folds = [sp for sp in br.special_points if sp.kind == "fold"]
    return elapsed, br, folds


def lu_time(n: int, repeat: int) -> float:
    """Best time of one SuperLU factorization of the bordered start matrix [J, e^u; e_λ]."""
    case = ex.bratu(n, sparse=True)
    system = BranchSystem(case.problem, "lam")
    z = np.zeros(n + 1)
    row = np.zeros(n + 1)
    row[-1] = 1.0
    a = system.bordered_jacobian(z, row).tocsc()
    best = float("inf")
    for _ in range(max(repeat, 3)):
        t0 = time.perf_counter()
        spla.splu(a)
        best = min(best, time.perf_counter() - t0)
    return best


def reference_fold(n: int):
    if n == 99_999:
        return ex.BRATU_FOLD_N99999, "stored 40-digit shooting value"
    if n <= 9_999:
        return float(ex.bratu_fd_fold(n)[0]), "mpmath shooting"
    return None, "none"


def measure(n: int, sparse: bool, reps: int, ref) -> dict:
    """The best of ``reps`` traces at size ``n``, as a table row (``lu_units`` NaN)."""
    elapsed, br, folds = min((run(n, sparse) for _ in range(reps)), key=lambda r: r[0])
    steps = br.info["steps"]
    lam = folds[0].values["lam"] if folds else float("nan")
    value, kind = ref
    return {
        "n": n,
        "kind": "sparse" if sparse else "dense",
        "time": elapsed,
        "steps": steps,
        "newton": int(np.sum(br.stats["newton_iterations"])),
        "us_per_step_per_n": elapsed / steps / n * 1e6,
        "lu_units": float("nan"),
        "lam": lam,
        "err": abs(lam - value) / value if value is not None else float("nan"),
        "ref": kind,
        "ok": br.success and len(folds) == 1,
    }


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[999, 3999, 9999, 39999, 99999])
    ap.add_argument(
        "--repeat",
        type=int,
        default=3,
        help="repeats per size (sizes above 20 000 unknowns run once)",
    )
    ap.add_argument("--out", default=str(ROOT / "docs" / "benchmarks" / "sparse.md"))
    args = ap.parse_args(argv)
    for n in args.sizes:
        if n < 3:
            ap.error(f"--sizes: each size must be >= 3, got {n}")

    rows = []
    for n in args.sizes:
        reps = args.repeat if n <= 20_000 else 1
        t_lu = lu_time(n, reps)
        ref = reference_fold(n)
        row = measure(n, True, reps, ref)
        row["lu_units"] = row["time"] / t_lu
        rows.append(row)
        print(
            f"N={n}: {row['time']:.3f} s, {row['steps']} steps, {row['newton']} Newton, "
            f"fold λ={row['lam']:.15g} (rel. err {row['err']:.1e}), "
            f"{row['lu_units']:.0f} LU",
            flush=True,
        )
        if n <= 999:
            rows.append(measure(n, False, reps, ref))

    sparse_rows = [r for r in rows if r["kind"] == "sparse"]
    ns = np.array([r["n"] for r in sparse_rows], dtype=float)
    ts = np.array([r["time"] / r["steps"] for r in sparse_rows])
    slope = float(np.polyfit(np.log(ns), np.log(ts), 1)[0]) if len(ns) >= 2 else float("nan")

    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    lines = [
        "# Benchmark: cost per step on a banded problem (sparse Bratu)",
        "",
        f"Measured {now} at commit `{commit()}` on {platform.machine()}, "
        f"{platform.python_implementation()} {platform.python_version()}, NumPy "
        f"{np.__version__}, SciPy {scipy.__version__} (2 logical CPUs shared with other jobs).",
        "",
        "Reproduce from the repository root: `python scripts/bench_sparse.py` (needs the test "
        "extra for the mpmath references).",
        "",
        "FD Bratu with N interior nodes ([test problem §2](../test-problems.md#2-bratu-problem)): "
        "tridiagonal scipy.sparse "
        "Jacobian, traced from u = 0, λ = 0 to u(½) = 2 through the fold with default "
        'options. Wall time is the best of 3 runs (1 run above 20 000 unknowns). "LU units" '
        "is the trace's time divided by one SuperLU factorization of the bordered start "
        "matrix, timed in the same process: the per-step floor, and independent of the "
        "machine's speed.",
        "",
        "| N | Jacobian | trace (s) | steps | Newton iterations | µs per step per unknown | "
        "trace / one LU | fold λ | rel. error | reference |",
        "|---:|---|---:|---:|---:|---:|---:|---:|---:|---|",
    ]
    for r in rows:
        lu = f"{r['lu_units']:.0f}" if np.isfinite(r["lu_units"]) else "—"
        err = "—" if not np.isfinite(r["err"]) else f"{r['err']:.1e}"
        lines.append(
            f"| {r['n']} | {r['kind']} | {r['time']:.3f} | {r['steps']} | {r['newton']} | "
            f"{r['us_per_step_per_n']:.3f} | {lu} | {r['lam']:.13g} | {err} | {r['ref']} |"
        )
    lines += [
        "",
        f"Fitted growth of the sparse time per step: ∝ N^{slope:.2f} over N = "
        f"{int(ns.min())}…{int(ns.max())} (1 is linear).",
        "",
    ]
    dense_rows = {r["n"]: r for r in rows if r["kind"] == "dense"}
    if len(sparse_rows) >= 2:
        lo, hi = sparse_rows[0], sparse_rows[-1]
        cost = [r["us_per_step_per_n"] for r in sparse_rows]
        lines += [
            "Reading:",
            "",
            f"- The cost per step per unknown stays between {min(cost):.2f} and "
            f"{max(cost):.2f} µs over a {hi['n'] / lo['n']:.0f}-fold range of N: the work per "
            "step is linear in N. At small N the fixed Python cost per step still shows "
            "(it pulls the fitted exponent below 1), and timings on this shared machine vary "
            "by tens of per cent from run to run.",
            f"- Steps ({lo['steps']}–{hi['steps']}) and Newton iterations "
            f"({lo['newton']}–{hi['newton']}) barely change with N, because the state enters "
            "the arclength as a root-mean-square (`state_weight = 1/n`).",
        ]
        for n, d in dense_rows.items():
            sp_ = next(r for r in sparse_rows if r["n"] == n)
            lines.append(
                f"- At N = {n} the dense Jacobian (LAPACK on the full bordered "
                f"matrix) takes {d['time'] / sp_['time']:.0f}× as long as the "
                "sparse one."
            )
        lines.append("")
    out = write_report(args.out, "\n".join(lines))
    print(f"wrote {out}; time per step ∝ N^{slope:.2f}")
    return 0 if all(r["ok"] for r in rows) else 1


if __name__ == "__main__":
    raise SystemExit(main())
