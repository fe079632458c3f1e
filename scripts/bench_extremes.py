"""The contact-loss path at extreme but valid inputs against self-checked high-precision
references (issue 27): every body's full grid of :mod:`cusp.verification.extremes`.

    python scripts/bench_extremes.py [--bodies exponential,gaussian,weibull,sphere]
                                     [--out docs/benchmarks/extremes.md]

For each case (one input extreme, the others those of the base scene) the path is run by
``cusp.models.ContactLoss`` and every reported number (the points A–D: g_T, F_T, F_N, A_SL
and the levels; the two energies) is compared with the reference of
:mod:`cusp.verification.reference_paths` (mpmath, its precision raised until two evaluations
agree to 30 digits). Per body the report gives the cases, the worst relative error, the worst
ratio of error to the stated bound, the numbers that came with a message (a bound above
1e-12), the violations (a bound below its error, an error above 1e-12 without a message, a
number missing without one; there should be none), the runs that failed, and the time.
Writes the report atomically; exit status 1 if any case violates.
"""

from __future__ import annotations

import argparse
import pathlib
import platform
import sys
import time

from cusp._scripts.report import commit_and_load, write_report
from cusp.verification.extremes import BODIES, grid, run_case

ROOT = pathlib.Path(__file__).resolve().parents[1]


def _row(o) -> str:
    c = o.case
    if o.failure:
        return (
            f"| {c.label} | failed: {o.failure[:140].replace('|', '/')} | | | | {o.seconds:.1f} |"
        )
    ratio = "—" if o.worst_ratio == 0.0 else f"{o.worst_ratio:.2g}"
    bad = "; ".join(o.violations)[:160].replace("|", "/") or "0"
    flagged = f"{o.flagged}/{o.compared}"
    return (
        f"| {c.label} | {o.worst_error:.1e} | {ratio} | {flagged} | {bad} | "
        f"{o.seconds:.1f} + {o.reference_seconds:.1f} |"
    )


def _body_section(body: str, outcomes) -> list[str]:
    ran = [o for o in outcomes if not o.failure]
    failed = [o for o in outcomes if o.failure]
    worst = max((o.worst_error for o in ran), default=0.0)
    ratio = max((o.worst_ratio for o in ran), default=0.0)
    flagged = sum(o.flagged > 0 for o in ran)
    bad = sum(bool(o.violations) for o in ran)
    seconds = sum(o.seconds + o.reference_seconds for o in outcomes)
    return [
        f"## {body}",
        "",
        f"{len(outcomes)} cases: {len(ran)} traced, {len(failed)} failed; worst error "
        f"{worst:.1e}, worst error/bound {ratio:.2g}; {flagged} cases with a message on some "
        f"number; {bad} with a violation; {seconds:.0f} s (path + reference).",
        "",
        "| case | worst error | error/bound | numbers with a message | violations "
        "| s (path + ref.) |",
        "|---|---:|---:|---:|---|---:|",
        *(_row(o) for o in outcomes),
        "",
    ]


def report(results: dict[str, list], seconds: float) -> str:
    commit, load = commit_and_load()
    lines = [
        "# The contact-loss path at the extremes",
        "",
        "Written by `python scripts/bench_extremes.py` (issue 27). Each case runs "
        "`cusp.models.ContactLoss` with one input extreme and the others those of the base "
        "scene (Fig 6's loading on σ* = 2 µm, ν = 0.3, μ = 0.1, E = 0.2 N/µm², ρ* = 10 µm, "
        "η = 0.01/µm², A_n = 1e6 µm², F_N0 = 1000 N, g_A = 0.1 μλ, F'_N = F_N0 − F_A/(2μ); "
        "the sphere of `scenes/sphere.toml` with g_A = 0.1 of its gross-sliding slip), and "
        "compares every reported number with the mpmath reference of "
        "`cusp.verification.reference_paths` (self-checked to 30 digits).",
        "",
        "Errors are relative (the levels d, d0, a, c: to the larger of themselves and their "
        "unit); *error/bound* is the largest ratio of an error to the bound the run states "
        "(below 1: every bound bounds); *numbers with a message*: how many of the compared "
        "numbers came with a message giving their bound (above 1e-12, the documented "
        "accuracy); *violations*: a bound below its error, an error above 1e-12 without a "
        "message, or a number missing without one. A failed run is a typed error of the path "
        "(not an accuracy result; see the issue's points 4–5).",
        "",
        f"Commit {commit}; Python {platform.python_version()}; load {load:.1f}; "
        f"total {seconds:.0f} s.",
        "",
    ]
    for body, outcomes in results.items():
        lines += _body_section(body, outcomes)
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bodies", default=",".join(BODIES))
    ap.add_argument("--out", default=str(ROOT / "docs" / "benchmarks" / "extremes.md"))
    args = ap.parse_args(argv)
    bodies = [b for b in args.bodies.split(",") if b]
    t0 = time.perf_counter()
    results = {}
    for body in bodies:
        results[body] = []
        for case in grid(body):
            outcome = run_case(case)
            results[body].append(outcome)
            status = outcome.failure or ("VIOLATION" if outcome.violations else "ok")
            print(f"{body:12s} {case.label:36s} {status[:100]}", flush=True)
    write_report(args.out, report(results, time.perf_counter() - t0))
    return int(any(o.violations for outs in results.values() for o in outs))


if __name__ == "__main__":
    sys.exit(main())
