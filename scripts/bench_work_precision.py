"""Work–precision: what each accuracy setting costs and gives, ours against contique, pacopy
and a SciPy natural-parameter loop, in one process.

Usage (from the repository root):

    python scripts/bench_work_precision.py [--rounds 3] [--quick] [--only cusp,co,...]
        [--out docs/benchmarks/work-precision.md] [--figures docs/figures]

Ours runs at rtol = 1e-2, 1e-3, ..., 1e-13 (`ContinuationOptions(rtol=...)`); contique
1.1.1 over its step limits (dxmax = dlpfmax) and residual tolerance; pacopy 0.1.9 over
stepsize_max and newton_tol; the SciPy loop over its number of parameter steps (the runners
are those of `bench_trace.py`, in `cusp._scripts.tools`). The tasks (`cusp._scripts.wp_problems`,
`cusp._scripts.wp_contact`; all in scripts/_shared/):

(a) fold location on the cusp normal form, the Green truss and the FD Bratu problem with
    N = 999 and N = 99 999 (h = 1e-3 and 1e-5), and the curve itself on the first two;
(b) the fold curve of the CO model and its cusp point (ours only);
(c) the points A–D and the energies of the bundled scenes fig6 and gaussian (ours only);
(d) the μ-locus of the manifold of the fig6 scene (ours only).

Every run is timed on its own first (the errors come from that run), coarse to fine per
tool: a tool whose run takes longer than ``--max-run`` seconds skips its finer settings.
Runs shorter than ``--long`` seconds are then timed timeit-style, best of ``--rounds``
rounds interleaved across all of the task's runs (a loop of at least 0.05 s per round);
longer runs keep the time of their first run. Residual evaluations are counted by
wrapping the residual callables. Writes the report and two figures per group (error
against wall time and against residual evaluations). ``--quick``: fewer settings, no
N = 99 999, one round (about a minute; a smoke test).
"""

from __future__ import annotations

import argparse
import contextlib
import logging
import math
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path

from cusp._scripts.tools import best_times, import_contique, import_pacopy
from cusp._scripts.wp_contact import locus_task, path_tasks
from cusp._scripts.wp_problems import (
    BRATU_BIG_PLAN,
    BRATU_PLANS,
    QUICK_RTOLS,
    RTOLS,
    SMALL_PLANS,
    Setting,
    Task,
    bratu_problem,
    co_measure,
    co_run,
    fold_measure,
    fold_settings,
    small_problems,
)
from cusp._scripts.wp_report import write_all

ROOT = Path(__file__).resolve().parents[1]
TASK_KEYS = ("cusp", "truss", "bratu999", "bratu99999", "co", "fig6", "gaussian", "manifold")


@dataclass
class Row:
    """The outcome of one setting: best time per run [s] (NaN if it did not run), rounds,
    the run's counts and errors ({measure: error}, inf where it gives no estimate)."""

    tool: str
    label: str
    family: str
    time: float = math.nan
    rounds: int = 0
    points: int | None = None
    nfev: int | None = None
    jev: int | None = None
    errors: dict[str, float] = field(default_factory=dict)
    ok: bool = False
    status: str = ""
    turn: float | None = None  # ours: the largest tangent turn of a step (degrees)


@contextlib.contextmanager
def quiet():
    """No warnings and no log records of the solver while the tools run (failures are
    recorded in the rows: a tool stopping early is data here)."""
    log = logging.getLogger("cusp")
    level = log.level
    log.setLevel(logging.CRITICAL)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            yield
    finally:
        log.setLevel(level)


def build_tasks(quick: bool, only, contique, pacopy) -> list[Task]:
    """The tasks selected by ``only`` (all by default), with their settings."""
    mode = "quick" if quick else "full"
    rtols = QUICK_RTOLS if quick else RTOLS
    keys = [k for k in TASK_KEYS if (only is None or k in only)]
    if quick and only is None:
        keys.remove("bratu99999")
    out: list[Task] = []
    for pb in small_problems():
        if pb["key"] in keys:
            settings = fold_settings(pb, rtols, SMALL_PLANS[mode], contique, pacopy)
            out.append(
                Task(pb["key"], "a", pb["name"], settings, fold_measure(pb), pb["reference"])
            )
    for n, key, plan, these in (
        (999, "bratu999", BRATU_PLANS[mode], (1e-2, 1e-4) if quick else RTOLS),
        (99_999, "bratu99999", BRATU_BIG_PLAN, (1e-2, 1e-3, 1e-4, 1e-5, 1e-6)),
    ):
        if key in keys:
            pb = bratu_problem(n)
            settings = fold_settings(pb, these, plan, contique, pacopy)
            out.append(Task(key, "a", pb["name"], settings, fold_measure(pb), pb["reference"]))
    if "co" in keys:
        settings = [
            Setting("ours", f"rtol = {r:.0e}", "ours", lambda r=r: co_run(r)) for r in rtols
        ]
        reference = (
            "the cusp CO_CUSP (mpmath, 40 digits); the fold curve: double roots of the quartic"
        )
        out.append(
            Task(
                "co",
                "b",
                "CO oxidation: fold curve in (q2, k) through the cusp",
                settings,
                co_measure,
                reference,
            )
        )
    out += [t for t in path_tasks(rtols) if t.key in keys]
    if "manifold" in keys:
        out.append(locus_task(rtols))
    return out


def first_runs(task: Task, max_run: float) -> list[Row]:
    """Each setting once, coarse to fine per tool (its errors and a first time); a tool
    whose run exceeds ``max_run`` seconds skips the rest."""
    rows, capped = [], set()
    for s in task.settings:
        row = Row(s.tool, s.label, s.family)
        rows.append(row)
        if s.tool in capped:
            row.status = f"not run: a coarser run took over {max_run:g} s"
            continue
        t0 = time.perf_counter()
        try:
            with quiet():
                summary_fn = s.run()
                row.time, row.rounds = time.perf_counter() - t0, 1
                summary = summary_fn()
                row.errors = task.measure(summary)
        except Exception as exc:  # a tool that raises: data too
            row.time, row.rounds = time.perf_counter() - t0, 1
            row.status = f"raised {type(exc).__name__}: {str(exc).splitlines()[0][:120]}"
            row.errors = {}
        else:
            row.points, row.nfev, row.jev = summary["points"], summary["nfev"], summary["jev"]
            row.ok, row.status = bool(summary["ok"]), str(summary["status"])
            row.turn = summary.get("max_turn_deg")
        if row.time > max_run:
            capped.add(s.tool)
    return rows


def retime(task: Task, rows: list[Row], rounds: int, long_run: float) -> None:
    """Best of ``rounds`` interleaved rounds for every run shorter than ``long_run``."""
    short = [i for i, r in enumerate(rows) if r.rounds and r.time < long_run]
    if not short or rounds < 1:
        return
    numbers = [max(1, min(1000, math.ceil(0.05 / max(rows[i].time, 1e-6)))) for i in short]
    with quiet():
        best = best_times([task.settings[i].run for i in short], rounds, numbers)
    for i, t in zip(short, best, strict=True):
        rows[i].time, rows[i].rounds = t, rounds


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--rounds", type=int, default=3, help="timing rounds (best of)")
    ap.add_argument("--quick", action="store_true", help="fewer settings, one round")
    ap.add_argument("--only", default=None, help=f"comma-separated tasks of {TASK_KEYS}")
    ap.add_argument("--max-run", type=float, default=30.0, help="s: finer settings skipped")
    ap.add_argument("--long", type=float, default=2.0, help="s: runs timed once")
    ap.add_argument("--out", default=str(ROOT / "docs" / "benchmarks" / "work-precision.md"))
    ap.add_argument("--figures", default=str(ROOT / "docs" / "figures"))
    args = ap.parse_args(argv)
    only = None if args.only is None else set(args.only.split(","))
    if only is not None and not only <= set(TASK_KEYS):
        ap.error(f"--only: unknown task(s) {sorted(only - set(TASK_KEYS))}")
    rounds = 1 if args.quick else args.rounds
    contique = import_contique()
    pacopy, pacopy_note = import_pacopy()
    t_start = time.perf_counter()
    results = []
    for task in build_tasks(args.quick, only, contique, pacopy):
        t0 = time.perf_counter()
        rows = first_runs(task, args.max_run)
        retime(task, rows, rounds, args.long)
        results.append((task, rows))
        print(f"{task.key}: {len(rows)} runs, {time.perf_counter() - t0:.1f} s", flush=True)
    notes = []
    if contique is None:
        notes.append("contique is not installed: no contique rows.")
    if pacopy_note:
        notes.append(pacopy_note.replace("no rows", "no pacopy rows"))
    write_all(results, args, argv, rounds, notes, time.perf_counter() - t_start)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
