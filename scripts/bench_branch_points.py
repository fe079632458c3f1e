"""Branch points from inexact starts: the Lorenz reproduction of issue 26 from seeded random
starts, and the published-problem suite from perturbed starts.

    python scripts/bench_branch_points.py [--starts 1000] [--seed 0] [--suite-seeds 30]
        [--watchdog 10] [--out docs/benchmarks/branch-points.md]

**Lorenz.** The equilibria of the Lorenz equations, σ = 10, β = 8/3, in r from r = 0.5 to the
bound r = 3 (``trace(problem, u0, free="r", bounds={"r": (0, 3)})``), from ``--starts`` guesses
u0 uniform in [−0.5, 0.5]³ (``numpy.random.default_rng(seed)``, one (N, 3) draw, the same
starts for both Jacobians) which Newton corrects to the origin; with central differences
(the engine's default) and with the analytic Jacobian. The origin's branch has a pitchfork at
r = 1 (det ∂G/∂u = σβ(r − 1)), where the branches x = y = ±√(β(r − 1)), z = r − 1 cross it.
Per start:

- *switch*: a traced point off the origin's branch, a component of (x, y, z) above
  :data:`OFF_ORIGIN` (the trace visits or ends on the crossing branch);
- *creep*: more steps than from the exact start (0, 0, 0) plus :data:`CREEP_STEPS`;
- *hang*: the trace does not return within ``--watchdog`` seconds
  (:func:`cusp.examples.suite.watchdog`);
- *error*: it raises anything else;
- the branch point: reported exactly once, status "converged", at |r − 1| ≤ 1e-10.

**Suite.** Every problem of ``cusp.examples.suite.SUITE`` from its start with relative noise
1e-14, 1e-10 and 1e-6 (``suite.perturbed``, seeds 0 … ``--suite-seeds`` − 1), judged by
``suite.check`` (the same special points to PARAM_RTOL / STATE_RTOL, a normal end, on its
branch) and ``suite.compare_ends`` (the same status and last point as from the unperturbed
start), each trace under the watchdog. The report also lists the problems on which a
passing perturbed start takes more than :data:`CREEP_STEPS` steps beyond the unperturbed one
(not part of the mode's criteria: a measurement).

Writes the Markdown report ``--out`` atomically (default docs/benchmarks/branch-points.md).
"""

from __future__ import annotations

import argparse
import dataclasses
import datetime
import platform
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import scipy

from cusp._scripts.report import commit_and_load, write_report
from cusp.continuation import Problem, trace
from cusp.examples.suite import (
    SUITE,
    Hang,
    check,
    compare_ends,
    perturbed,
    problem,
    watchdog,
)

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "benchmarks" / "branch-points.md"

SIGMA, BETA = 10.0, 8.0 / 3.0  # the Lorenz constants of the reproduction
BOUNDS = {"r": (0.0, 3.0)}
OFF_ORIGIN = 1e-8
"""A traced point is off the origin's branch when a component of (x, y, z) exceeds this: the
suite's STATE_RTOL on the unit size it gives a state that is 0 at its start and references.
The crossing branch has |x| = √(β(r − 1)) ≥ 1e-8 from r = 1 + 4e-17 on."""
CREEP_STEPS = 3
"""The issue's 'a few steps': steps beyond those from the exact start that count as a creep."""
BP_RTOL = 1e-10
"""The issue's tolerance on the branch point's r (relative to r = 1)."""
RELS = (1e-14, 1e-10, 1e-6)
"""The issue's noise levels for the suite."""


def lorenz_problem(jacobian: str) -> Problem:
    """The issue's Lorenz problem (r = 0.5 at the start) with ``jacobian`` ``"fd"`` (the
    engine's default central differences) or ``"analytic"``."""

    def residual(u, p):
        return [
            SIGMA * (u[1] - u[0]),
            p["r"] * u[0] - u[1] - u[0] * u[2],
            u[0] * u[1] - BETA * u[2],
        ]

    if jacobian == "fd":
        return Problem(residual, ["x", "y", "z"], {"r": 0.5})
    if jacobian != "analytic":
        raise ValueError(f"jacobian must be 'fd' or 'analytic', got {jacobian!r}")

    def jac(u, p):
        x, y, z = u
        return np.array([[-SIGMA, SIGMA, 0.0], [p["r"] - z, -1.0, -x], [y, x, -BETA]])

    def param_jac(u, p, name):
        return np.array([0.0, u[0], 0.0])

    return Problem(residual, ["x", "y", "z"], {"r": 0.5}, jacobian=jac, param_jacobian=param_jac)


def lorenz_starts(n: int, seed: int) -> np.ndarray:
    """``n`` guesses uniform in [−0.5, 0.5]³: rows of one draw of ``default_rng(seed)``."""
    return np.random.default_rng(seed).uniform(-0.5, 0.5, (n, 3))


def classify(prob: Problem, u0: Sequence[float], exact_steps: int, seconds: float) -> dict:
    """What the trace of ``prob`` from ``u0`` did (keys: ``hang``, ``error``, ``status``,
    ``steps``, ``switch``, ``creep``, ``bp``: the number of branch points reported, ``bp_ok``,
    ``bp_r``, ``off``: the largest |x|, |y|, |z| on the branch, ``seconds``)."""
    out: dict[str, Any] = {"hang": False, "error": None, "switch": False, "creep": False}
    out.update(status=None, steps=None, bp=0, bp_ok=False, bp_r=None, off=None)
    begin = time.perf_counter()
    try:
        with watchdog(seconds, f"the Lorenz trace from {list(u0)}"):
            br = trace(prob, np.array(u0, dtype=float), free="r", bounds=BOUNDS, throw=False)
    except Hang:
        out["hang"] = True
        return {**out, "seconds": time.perf_counter() - begin}
    except Exception as exc:  # counted and listed
        out["error"] = f"{type(exc).__name__}: {exc}"
        return {**out, "seconds": time.perf_counter() - begin}
    out["seconds"] = time.perf_counter() - begin
    off = max(float(np.max(np.abs(br[k]))) for k in ("x", "y", "z"))
    bps = br.special("branch_point")
    out.update(status=br.status, steps=int(br.info["steps"]), off=off, bp=len(bps))
    out["switch"] = off > OFF_ORIGIN
    out["creep"] = out["steps"] > exact_steps + CREEP_STEPS
    if bps:
        out["bp_r"] = float(bps[0].values["r"])
        located = abs(out["bp_r"] - 1.0) <= BP_RTOL
        out["bp_ok"] = len(bps) == 1 and bps[0].status == "converged" and located
    return out


def run_lorenz(jacobian: str, starts: np.ndarray, seconds: float) -> dict:
    """:func:`classify` of every start: the counts, the exact start's steps, the worst
    |r − 1|, the time, and the starts with anything wrong (``bad``: (index, u0, outcome))."""
    prob = lorenz_problem(jacobian)
    exact = trace(prob, [0.0, 0.0, 0.0], free="r", bounds=BOUNDS)
    exact_steps = int(exact.info["steps"])
    rows = [classify(prob, u0, exact_steps, seconds) for u0 in starts.tolist()]
    bad = [
        (i, starts[i].tolist(), r)
        for i, r in enumerate(rows)
        if r["hang"] or r["error"] or r["switch"] or r["creep"] or not r["bp_ok"]
        or r["status"] != "bound"
    ]  # fmt: skip
    located = [abs(r["bp_r"] - 1.0) for r in rows if r["bp_r"] is not None]
    return {
        "jacobian": jacobian,
        "starts": len(rows),
        "exact_steps": exact_steps,
        "switches": sum(r["switch"] for r in rows),
        "creeps": sum(r["creep"] for r in rows),
        "hangs": sum(r["hang"] for r in rows),
        "errors": sum(r["error"] is not None for r in rows),
        "bound": sum(r["status"] == "bound" for r in rows),
        "bp_ok": sum(r["bp_ok"] for r in rows),
        "bp_once": sum(r["bp"] == 1 for r in rows),
        "max_steps": max((r["steps"] for r in rows if r["steps"] is not None), default=0),
        "worst_r": max(located, default=float("nan")),
        "seconds": sum(r["seconds"] for r in rows),
        "bad": bad,
    }


def run_suite(seeds: Sequence[int], seconds: float, names: Sequence[str] | None = None) -> dict:
    """Every suite problem (or those of ``names``) × :data:`RELS` × ``seeds`` from perturbed
    starts: ``cases`` (name → [(rel, seed, what is wrong, steps or None)]), ``exact_steps``
    (name → the steps from the unperturbed start) and the time."""
    begin = time.perf_counter()
    cases: dict[str, list[tuple[float, int, list[str], int | None]]] = {}
    exact_steps: dict[str, int] = {}
    for name, _, _ in SUITE:
        if names is not None and name not in names:
            continue
        example = problem(name)
        refs = example.references()  # (computed once: the same for every start)
        example = dataclasses.replace(example, reference_points=lambda refs=refs: refs)
        reference = example.trace()
        exact_steps[name] = int(reference.info["steps"])
        cases[name] = [_suite_case(example, reference, name, rel, seed, seconds) for rel in RELS
                       for seed in seeds]  # fmt: skip
    return {"cases": cases, "exact_steps": exact_steps, "seconds": time.perf_counter() - begin}


def _suite_case(example, reference, name, rel, seed, seconds):
    """(rel, seed, what is wrong, steps) of the suite problem from one perturbed start."""
    start = perturbed(example, rel, seed)
    try:
        with watchdog(seconds, f"the trace of {name} from {start.u0.tolist()}"):
            br = start.trace()
        wrong = check(start, br, name) + compare_ends(start, reference, br)
        return rel, seed, wrong, int(br.info["steps"])
    except Hang as exc:
        return rel, seed, [f"hang: {exc}"], None
    except Exception as exc:  # listed
        return rel, seed, [f"{type(exc).__name__}: {exc}"], None


def _lorenz_lines(results: list[dict], starts: int, seed: int, seconds: float) -> list[str]:
    lines = [
        "## Lorenz from random starts",
        "",
        f"{starts} guesses u0 uniform in [−0.5, 0.5]³ (`default_rng({seed})`), each corrected "
        "by Newton to the origin at r = 0.5 and traced to the bound r = 3; the pitchfork is at "
        f"r = 1. A *switch* is a traced point with |x|, |y| or |z| > {OFF_ORIGIN:g}; a *creep* "
        f"more than {CREEP_STEPS} steps beyond the exact start's; a *hang* no return within "
        f"{seconds:g} s. The branch point is right when it is reported exactly once, "
        f'"converged", at |r − 1| ≤ {BP_RTOL:g}.',
        "",
        "| Jacobian | starts | switches | creeps | hangs | errors | ended at r = 3 | "
        "branch point once | … right | steps (exact start) | steps (most) | worst abs(r − 1) | "
        "time (s) |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in results:
        lines.append(
            f"| {r['jacobian']} | {r['starts']} | {r['switches']} | {r['creeps']} | "
            f"{r['hangs']} | {r['errors']} | {r['bound']} | {r['bp_once']} | {r['bp_ok']} | "
            f"{r['exact_steps']} | {r['max_steps']} | {r['worst_r']:.1e} | {r['seconds']:.1f} |"
        )
    lines.append("")
    for r in results:
        for i, u0, out in r["bad"][:20]:
            what = {k: v for k, v in out.items() if k != "seconds"}
            lines.append(f"- {r['jacobian']}, start {i} `{u0}`: {what}")
        if len(r["bad"]) > 20:
            lines.append(f"- {r['jacobian']}: {len(r['bad']) - 20} more starts with a failure")
    if not any(r["bad"] for r in results):
        lines.append("Every start: no switch, creep, hang or error, the branch point right.")
    return [*lines, ""]


def _suite_lines(suite: dict, seeds: Sequence[int]) -> list[str]:
    cases, exact = suite["cases"], suite["exact_steps"]
    lines = [
        "## The suite from perturbed starts",
        "",
        f"{len(cases)} problems × noise levels {', '.join(f'{r:g}' for r in RELS)} × seeds "
        f"0–{max(seeds)} (`suite.perturbed`: component i of the start plus "
        "rel·max(|u0_i|, size_i)·N(0, 1), the size 1 where it is 0), each judged by "
        "`suite.check` and `suite.compare_ends` (the same special points, a normal end, on "
        "its branch; the same status and end point as from the unperturbed start); "
        f"{suite['seconds']:.1f} s in all. *More steps*: the cases that pass but take more than "
        f"{CREEP_STEPS} steps beyond the unperturbed start's (not a failure of the mode; "
        "listed below).",
        "",
        "| rel | cases | pass | fail | more steps |",
        "|---:|---:|---:|---:|---:|",
    ]
    failures = []
    for rel in RELS:
        results = [(n, c) for n, rows in cases.items() for c in rows if c[0] == rel]
        failed = [(n, c) for n, c in results if c[2]]
        slow = [(n, c) for n, c in results if not c[2] and c[3] > exact[n] + CREEP_STEPS]
        failures += failed
        lines.append(
            f"| {rel:g} | {len(results)} | {len(results) - len(failed)} | {len(failed)} | "
            f"{len(slow)} |"
        )
    lines += ["", "Failures:" if failures else "No failure.", ""]
    for name, (rel, seed, wrong, _) in failures:
        lines.append(f"- {name}, rel {rel:g}, seed {seed}: " + "; ".join(wrong))
    lines += [""] if failures else []
    lines += _steps_lines(cases, exact)
    return [*lines, ""]


def _steps_lines(cases: dict, exact: dict[str, int]) -> list[str]:
    """The problems some passing perturbed start takes more steps on: the range of steps per
    level (of every start whose trace returned)."""
    lines = []
    for name, rows in cases.items():
        if not any(not c[2] and c[3] > exact[name] + CREEP_STEPS for c in rows):
            continue
        ranges = []
        for rel in RELS:
            steps = [c[3] for c in rows if c[0] == rel and c[3] is not None]
            ranges.append(f"{min(steps)}–{max(steps)} at {rel:g}" if steps else f"none at {rel:g}")
        lines.append(f"- {name}: {exact[name]} steps unperturbed; " + ", ".join(ranges))
    if not lines:
        return [
            f"No passing case takes more than {CREEP_STEPS} steps beyond its unperturbed start."
        ]
    return ["More steps than from the unperturbed start:", "", *lines]


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--starts", type=int, default=1000, help="Lorenz starts per Jacobian")
    ap.add_argument("--seed", type=int, default=0, help="seed of the Lorenz starts")
    ap.add_argument("--suite-seeds", type=int, default=30, help="seeds per problem and level")
    ap.add_argument("--problems", nargs="+", help="suite problems (default: all)")
    ap.add_argument("--watchdog", type=float, default=10.0, help="seconds before a hang")
    ap.add_argument("--out", default=str(DOC))
    args = ap.parse_args(argv)
    starts = lorenz_starts(args.starts, args.seed)
    results = []
    for jacobian in ("fd", "analytic"):
        r = run_lorenz(jacobian, starts, args.watchdog)
        print(
            f"Lorenz {jacobian}: {r['switches']} switches, {r['creeps']} creeps, {r['hangs']} "
            f"hangs, {r['errors']} errors, branch point right {r['bp_ok']}/{r['starts']}",
            flush=True,
        )
        results.append(r)
    seeds = range(args.suite_seeds)
    suite = run_suite(seeds, args.watchdog, args.problems)
    commit, load = commit_and_load()
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    command = "python scripts/bench_branch_points.py"
    given = " ".join(sys.argv[1:] if argv is None else argv)
    lines = [
        "# Benchmark: branch points from inexact starts",
        "",
        f"Measured {now} at commit `{commit}` on {platform.machine()}, Python "
        f"{platform.python_version()}, NumPy {np.__version__}, SciPy {scipy.__version__}; "
        f"load average {load:.2f}.",
        "",
        f"Reproduce from the repository root: `{command}{' ' + given if given else ''}` "
        "(issue 26: the Lorenz reproduction, and the suite's perturbed-start mode of "
        "[test-problems.md §12](../test-problems.md#12-the-published-problem-suite)).",
        "",
        *_lorenz_lines(results, args.starts, args.seed, args.watchdog),
        *_suite_lines(suite, seeds),
    ]
    text = "\n".join(lines)
    print(text)
    path = write_report(args.out, text)
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
