"""Benchmark whole diagrams and deflation (issue 30).

    python scripts/bench_diagram.py [--repeat 3] [--out docs/benchmarks/diagram.md]

For each problem: the wall time of ``diagram`` against tracing the same branches one by one
the way a user would by hand (the start's branch with ``trace``, then ``trace(problem, bp,
direction=±1)`` at every branch point it and the branches after it locate, to the same
depth; no check for repeats, so a branch reached twice is traced twice), best of the
repeats, and the number of traces each made. Then deflation: solutions found, deflated
Newton runs and linear solves, and the time per solution.

Problems: Chafee–Infante by finite differences (n = 50, λ ∈ [0, 30]: five pitchforks of
u = 0), the two interacting modes of cusp.examples.diagrams (secondary
branch points), the two stirred tanks (cusp.examples.cstr_pair: a loop through two
pitchforks: by hand, with no test for a return, each half runs round it until
max_steps). Deflation: the first Painlevé transcendent
(n = 199, two solutions from y = √x), Chafee–Infante n = 50 at λ = 30 (u = 0 and ±u_k for
the five modes below 30: 11 solutions), the isola problem (x = 2 and 4 at λ = 2).
"""

from __future__ import annotations

import argparse
import datetime
import math
import pathlib
import platform
import time

import numpy as np

from cusp._scripts.report import commit_and_load, write_report
from cusp.continuation import deflate, diagram, trace
from cusp.examples.diagrams import isola, painleve, two_modes
from cusp.examples.symmetric import chafee_infante, chafee_infante_eigenvalue
from cusp.examples.symmetric_cells import cstr_pair

ROOT = pathlib.Path(__file__).resolve().parents[1]


def by_hand(problem, u0, free, bounds, depth):
    """Trace the start's branch, then both halves at every branch point, to ``depth``."""
    first = trace(problem, u0, free=free, bounds=bounds, throw=False)
    level, traces = [first], 1
    for _ in range(depth):
        nxt = []
        for br in level:
            for sp in br.special("branch_point", status="converged"):
                for d in (1, -1):
                    nxt.append(trace(problem, sp, free=free, bounds=bounds, direction=d,
                                     throw=False))  # fmt: skip
                    traces += 1
        level = nxt
    return traces


def best(fn, args, repeat):
    times, out = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn(*args)
        times.append(time.perf_counter() - t0)
    return min(times), out


def _diagram(prob, u0, free, bounds, depth):
    return diagram(prob, u0, free=free, bounds=bounds, max_depth=depth)


def _deflate(prob, guesses, params):
    return deflate(prob, guesses, params=params, max_solutions=20)


def diagrams(repeat):
    ci = chafee_infante(50, lam_max=30.0)
    cs = cstr_pair()
    cases = [
        ("Chafee–Infante n = 50, λ ≤ 30", ci.problem, ci.u0, "lam", {"lam": (0.0, 30.0)}, 1),
        ("two interacting modes", two_modes(), [0.0, 0.0], "lam", {"lam": (0.0, 6.0)}, 2),
        ("two stirred tanks (cstr_pair)", cs.problem, cs.u0, "Da", cs.bounds, 1),
    ]
    rows = []
    for name, prob, u0, free, bounds, depth in cases:
        td, d = best(_diagram, (prob, u0, free, bounds, depth), repeat)
        th, n_hand = best(by_hand, (prob, u0, free, bounds, depth), repeat)
        rows.append((name, len(d.branches), len(d.points), td, d.traces, th, n_hand))
    return rows


def deflations(repeat):
    p_prob, x = painleve(199)
    ci = chafee_infante(50, lam_max=30.0)
    h = math.pi / 51
    nodes = h * np.arange(1, 51)
    want_ci = 1 + 2 * sum(chafee_infante_eigenvalue(50, k) < 30.0 for k in range(1, 51))
    cases = [
        ("Painlevé I, n = 199, from y = √x", p_prob, [np.sqrt(x)], None, 2),
        ("Chafee–Infante n = 50 at λ = 30, from sin kx, k = 1 … 5",
         ci.problem, [np.sin(k * nodes) for k in range(1, 6)], {"lam": 30.0}, want_ci),
        ("isola at λ = 2, from x = 1", isola(), [[1.0]], {"lam": 2.0}, 3),
    ]  # fmt: skip
    rows = []
    for name, prob, guesses, params, want in cases:
        t, found = best(_deflate, (prob, guesses, params), repeat)
        rows.append((name, len(found), want, found.runs, found.solves, t))
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--out", default=str(ROOT / "docs" / "benchmarks" / "diagram.md"))
    args = ap.parse_args(argv)
    drows, frows = diagrams(args.repeat), deflations(args.repeat)
    commit, load = commit_and_load()
    lines = [
        "# Whole diagrams and deflation",
        "",
        f"`python scripts/bench_diagram.py` (commit {commit}, {datetime.date.today()}, "
        f"Python {platform.python_version()}, load {load:.2f}; best of {args.repeat}).",
        "",
        "## `diagram` against tracing the branches one by one",
        "",
        "By hand: the start's branch, then `trace(problem, bp, direction=±1)` at every "
        "branch point to the same depth, with no check for repeats.",
        "",
        "| problem | branches | points | diagram [ms] | traces | by hand [ms] | traces |",
        "|---|---|---|---|---|---|---|",
    ]
    for name, nb, npt, td, tr, th, nh in drows:
        lines.append(f"| {name} | {nb} | {npt} | {1e3 * td:.1f} | {tr} | {1e3 * th:.1f} | {nh} |")
    lines += [
        "",
        "A diagram's trace is one branch both ways (two halves), by hand one half each.",
        "",
        "## Deflation",
        "",
        "| problem | found | expected | runs | solves | time [ms] | per solution [ms] |",
        "|---|---|---|---|---|---|---|",
    ]
    for name, n, want, runs, solves, t in frows:
        per = 1e3 * t / max(n, 1)
        lines.append(f"| {name} | {n} | {want} | {runs} | {solves} | {1e3 * t:.1f} | {per:.1f} |")
    lines += [
        "",
        "Runs: one per solution found, and one per guess whose last run found none (up to "
        "`max_iterations` = 100 iterations: most of the solves).",
        "",
    ]
    out = write_report(args.out, "\n".join(lines))
    print("\n".join(lines))
    print(f"wrote {out}")
    return 0 if all(n == want for _, n, want, *_ in frows) else 1


if __name__ == "__main__":
    raise SystemExit(main())
