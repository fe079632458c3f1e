"""The report of the work–precision benchmark (`bench_work_precision.py`): the tables, the
fronts and who dominates them, "Choosing rtol", all computed from the measured rows."""

from __future__ import annotations

import math
import sys
from datetime import datetime, timezone
from pathlib import Path

from cusp._scripts.report import commit_and_load, machine, write_report
from cusp._scripts.wp_figures import GROUPS, MEASURES, draw_group
from cusp.continuation import ContinuationOptions

#: errors below this are rounding: they compare equal
FLOOR = 1e-15
DEFAULT_RTOL = ContinuationOptions().rtol


def finite(x) -> bool:
    return x is not None and math.isfinite(x)


def cost(row, axis: str) -> float:
    """A row's cost on ``axis``: "time" (s) or "nfev" (residual evaluations)."""
    value = row.time if axis == "time" else row.nfev
    return math.inf if value is None or not finite(value) else float(value)


def fmt_err(e) -> str:
    if e is None:
        return "—"
    if not math.isfinite(e):
        return "none"
    return "0" if e == 0 else f"{e:.1e}"


def fmt_ms(t) -> str:
    if not finite(t):
        return "—"
    ms = t * 1e3
    return f"{ms:.3g}" if ms < 1000 else f"{ms:.0f}"


def rtol_of(row) -> float:
    return float(row.label.split("=")[1])


def measures_of(rows) -> list[str]:
    seen: list[str] = []
    for r in rows:
        seen += [m for m in r.errors if m not in seen]
    return [m for m in MEASURES if m in seen]


# ----------------------------------------------------------------------------- tables


def table(task, rows) -> list[str]:
    ms = measures_of(rows)
    head = "| tool | setting | time (ms) | rounds | points | f-evals | J-evals | "
    head += " | ".join(f"error: {m}" for m in ms) + " | status |"
    lines = [head, "|---|---|---:|---:|---:|---:|---:|" + "---:|" * len(ms) + "---|"]
    for r in rows:
        errs = " | ".join(fmt_err(r.errors.get(m)) for m in ms)
        status = "ok" if r.ok and r.status in ("bound", "end", "ok") else r.status
        status = status if len(status) <= 80 else status[:79] + "…"
        lines.append(
            f"| {r.tool} | {r.label} | {fmt_ms(r.time)} | {r.rounds or '—'} | "
            f"{'—' if r.points is None else r.points} | {'—' if r.nfev is None else r.nfev} | "
            f"{'—' if r.jev is None else r.jev} | {errs} | {status} |"
        )
    return lines


# ----------------------------------------------------------------------------- fronts


def dominated(row, ours, measure: str, axis: str, mine: str | None = None) -> bool:
    """Whether one of ``ours`` costs no more than ``row`` on ``axis`` and is at least as
    accurate, ``row`` in ``measure`` and ours in ``mine`` (default the same; errors below
    :data:`FLOOR` compare equal)."""
    e = max(row.errors[measure], FLOOR)
    mine = mine or measure
    return any(cost(o, axis) <= cost(row, axis) and max(o.errors[mine], FLOOR) <= e for o in ours)


def _why_not(row, ours, measure, axis, mine) -> str:
    c = cost(row, axis)
    unit = (lambda v: f"{v * 1e3:.3g} ms") if axis == "time" else (lambda v: f"{v:.0f} f-evals")
    cheaper = [o for o in ours if cost(o, axis) <= c]
    if not cheaper:
        first = min(ours, key=lambda o: cost(o, axis))
        return (
            f"{row.label} ({unit(c)}, error {fmt_err(row.errors[measure])}) is cheaper than "
            f"our cheapest run ({unit(cost(first, axis))}, error {fmt_err(first.errors[mine])})"
        )
    best = min(cheaper, key=lambda o: o.errors[mine])
    return (
        f"{row.label} reaches {fmt_err(row.errors[measure])} at {unit(c)}; at that cost ours "
        f"reaches {fmt_err(best.errors[mine])} ({best.label})"
    )


def dominance(task, rows) -> list[str]:
    """The "Does our front dominate?" paragraph of a task, from its rows: each measure of
    each other tool against ours, and their curves against our dense output if there is
    one."""
    ours = [r for r in rows if r.tool == "ours"]
    others = [t for t in dict.fromkeys(r.tool for r in rows) if t != "ours"]
    lines = [_ours_failures(ours)] if _ours_failures(ours) else []
    if not others:
        return lines + ["No other tool computes this: the front is ours alone."] + _trend(ours)
    pairs = [(m, m) for m in measures_of(rows) if m != "dense"]
    if any(finite(o.errors.get("dense")) for o in ours):
        pairs.append(("curve", "dense"))
    for m, m_ours in pairs:
        mine = [o for o in ours if finite(o.errors.get(m_ours))]
        for tool in others:
            theirs = [r for r in rows if r.tool == tool]
            valid = [r for r in theirs if finite(r.errors.get(m))]
            if not valid:
                if any(m in r.errors for r in theirs):
                    lines.append(f"- {m}, {tool}: no estimate in any of its {len(theirs)} runs.")
                continue
            lines.append(_verdict(m, m_ours, tool, theirs, valid, mine))
    return lines + _fold_note(rows) + _curve_note(rows)


def _verdict(m, m_ours, tool, theirs, valid, mine) -> str:
    parts = []
    for axis, name in (("time", "time"), ("nfev", "f-evals")):
        beaten = [r for r in valid if mine and dominated(r, mine, m, axis, m_ours)]
        text = f"{len(beaten)} of {len(valid)} by {name}"
        rest = [r for r in valid if r not in beaten]
        if rest and mine:
            why = "; ".join(_why_not(r, mine, m, axis, m_ours) for r in rest[:3])
            more = f" (and {len(rest) - 3} more)" if len(rest) > 3 else ""
            text += f" — not dominated: {why}{more}"
        parts.append(text)
    verdict = f"**{_classify(valid, mine, m, m_ours)}**"
    failed = len(theirs) - len(valid)
    tail = f" {failed} of its runs gave no estimate (failed or not run)." if failed else ""
    what = m if m == m_ours else f"{m} (ours: {m_ours})"
    return f"- {what}, {tool}: {verdict}. Ours dominates {'; '.join(parts)}.{tail}"


def _classify(valid, mine, m, m_ours) -> str:
    """ "yes" (ours dominates every run), "no, only by runs cheaper than our cheapest" or
    "no", by time and by residual evaluations."""
    escaped = [
        (r, axis)
        for axis in ("time", "nfev")
        for r in valid
        if not (mine and dominated(r, mine, m, axis, m_ours))
    ]
    if not escaped:
        return "yes"
    if mine and all(cost(r, axis) < min(cost(o, axis) for o in mine) for r, axis in escaped):
        return "no, only by runs cheaper than our cheapest"
    return "no"


def headline(results) -> list[str]:
    """Per task and measure, the verdict against each other tool (the sections' first
    words), and the rtol at which ours did not complete."""
    tools = list(dict.fromkeys(r.tool for _, rows in results for r in rows if r.tool != "ours"))
    if not tools:
        return []
    lines = [
        "| task: measure | " + " | ".join(tools) + " | ours did not complete at |",
        "|---|" + "---|" * (len(tools) + 1),
    ]
    for task, rows in results:
        ours = [r for r in rows if r.tool == "ours"]
        if not any(r.tool != "ours" for r in rows):
            continue
        bad = ", ".join(f"{rtol_of(o):.0e}" for o in ours if o.rounds and not o.ok) or "—"
        pairs = [(m, m) for m in measures_of(rows) if m != "dense"]
        if any(finite(o.errors.get("dense")) for o in ours):
            pairs.append(("curve", "dense"))
        for m, m_ours in pairs:
            mine = [o for o in ours if finite(o.errors.get(m_ours))]
            cells = []
            for tool in tools:
                valid = [r for r in rows if r.tool == tool and finite(r.errors.get(m))]
                cells.append(_classify(valid, mine, m, m_ours) if valid else "—")
            what = m if m == m_ours else f"{m} (ours: {m_ours})"
            lines.append(f"| {task.key}: {what} | " + " | ".join(cells) + f" | {bad} |")
    return [
        'Does our front dominate? "yes": every run of the other tool is matched by one of '
        "ours at least as accurate in no more wall time, and by one in no more residual "
        "evaluations (details and the runs that escape under each problem).",
        "",
        *lines,
    ]


def _curve_note(rows) -> list[str]:
    """Why ours can lose on the curve between points: the tangent turn of its steps."""
    ours = sorted(
        (rtol_of(r), r) for r in rows
        if r.tool == "ours" and r.ok and finite(r.errors.get("curve")) and r.turn is not None
    )  # fmt: skip
    if not ours:
        return []
    turns = ", ".join(f"{r.turn:.2g}° at {x:.0e}" for x, r in ours[::-1])
    text = (
        f"- Why (curve): ours takes long steps. Its largest tangent turn in one step is {turns} "
        "(its step guard allows 30°, `max_angle`, and aims at 15°; the check of the step's "
        "cubic arc against rtol binds from about 1e-4 down); a straight segment of length h "
        "turning by θ "
        "misses the curve by about hθ/8, whereas contique's increment limit per component "
        "and pacopy's stepsize_max keep their segments short."
    )
    return [text]


def _ours_failures(ours) -> str:
    bad = [o for o in ours if not o.ok]
    if not bad:
        return ""
    what = ", ".join(f"{o.label} ({o.status.split(':')[0]})" for o in bad)
    return f"- Ours did not complete at: {what}."


def _fold_note(rows) -> list[str]:
    ours = [r for r in rows if r.tool == "ours" and finite(r.errors.get("fold"))]
    if not ours:
        return []
    worst = max(r.errors["fold"] for r in ours)
    return [
        f"- Why: ours locates each fold by Newton on the fold conditions (error ≤ "
        f"{fmt_err(worst)} at every rtol it completed); contique, pacopy and the SciPy loop "
        "only bracket folds between computed points, so their error is that of their step "
        "(or grid) and falls only as they take more steps. Our fold error does not "
        "depend on rtol, so for the fold alone the coarsest rtol is enough; rtol buys the "
        "curve between the points."
    ]


def _trend(ours) -> list[str]:
    lines = []
    for m in measures_of(ours):
        pts = sorted((rtol_of(o), o) for o in ours if finite(o.errors.get(m)))
        if not pts:
            continue
        (r1, a), (r2, b) = pts[-1], pts[0]
        lines.append(
            f"- {m}: error {fmt_err(a.errors[m])} at rtol = {r1:.0e} ({fmt_ms(a.time)} ms) and "
            f"{fmt_err(b.errors[m])} at rtol = {r2:.0e} ({fmt_ms(b.time)} ms)."
        )
    return lines


# ----------------------------------------------------------------------------- choosing rtol


def choosing_rtol(results) -> list[str]:
    """The cost and the errors of ours per rtol over every task, and what they say."""
    ours = {task.key: [r for r in rows if r.tool == "ours"] for task, rows in results}
    rtols = sorted({rtol_of(r) for rows in ours.values() for r in rows}, reverse=True)
    head = "| | " + " | ".join(f"{r:.0e}" for r in rtols) + " |"
    rule = "|---|" + "---:|" * len(rtols)
    cost_lines = ["Time per run (ms; — not run, ✗ did not complete):", "", head, rule]
    err_lines = ["Errors (largest; 'none': no estimate):", "", head, rule]
    prose = []
    for key, rows in ours.items():
        by = {rtol_of(r): r for r in rows}
        cells = [
            "—"
            if r not in by or not by[r].rounds
            else fmt_ms(by[r].time) + ("" if by[r].ok else " ✗")
            for r in rtols
        ]
        cost_lines.append(f"| {key} | " + " | ".join(cells) + " |")
        for m in measures_of(rows):
            cells = [fmt_err(by[r].errors.get(m)) if r in by else "—" for r in rtols]
            err_lines.append(f"| {key}: {m} | " + " | ".join(cells) + " |")
        prose.append(_advice(key, by))
    return cost_lines + [""] + err_lines + ["", *prose]


def trade(results) -> list[str]:
    """The trade the knob offers, in numbers: time and points at the loosest rtol against
    1e-12 on the cusp, and at 1e-3 against 1e-12 on the fig6 path; and the default's cost
    next to its neighbours on every task."""
    ours = {task.key: {rtol_of(r): r for r in rows if r.tool == "ours" and r.ok}
            for task, rows in results}  # fmt: skip
    lines = []
    for key, loose, fine in (("cusp", 1e-2, 1e-12), ("fig6", 1e-3, 1e-12)):
        by = ours.get(key, {})
        if loose in by and fine in by:
            a, b = by[loose], by[fine]
            lines.append(
                f"- {key}: rtol = {loose:.0e} takes {fmt_ms(a.time)} ms and {a.points} points, "
                f"rtol = {fine:.0e} {fmt_ms(b.time)} ms and {b.points} points: "
                f"{b.time / a.time:.1f}× fewer seconds at {loose:.0e}."
            )
    near = []
    for key, by in ours.items():
        d = by.get(DEFAULT_RTOL)
        lo, hi = by.get(10 * DEFAULT_RTOL), by.get(DEFAULT_RTOL / 10)
        if d and lo and hi:
            near.append(f"{key} {d.time / lo.time:.2f}× / {hi.time / d.time:.2f}×")
    if near:
        lines.append(
            f"- The default rtol = {DEFAULT_RTOL:.0e} against {10 * DEFAULT_RTOL:.0e} and "
            f"{DEFAULT_RTOL / 10:.0e} (time at the default over the looser one / time at the "
            f"tighter one over the default): {'; '.join(near)}."
        )
    return lines


def _advice(key, by) -> str:
    """One computed sentence per task: the errors that do not depend on rtol (within 10× of
    their best already at the coarsest rtol that completed), from which rtol on each other
    error falls below 1e-2, 1e-4, ..., and what a run costs at the default and the ends."""
    done = {r: row for r, row in by.items() if row.ok and row.errors}
    if not done:
        return f"- {key}: no run of ours completed."
    coarse = max(done)
    parts = []
    for m in measures_of(list(done.values())):
        errs = {r: row.errors.get(m, math.inf) for r, row in done.items()}
        best = min(errs.values())
        if errs[coarse] <= 10 * max(best, FLOOR):
            parts.append(f"{m} ≤ {fmt_err(max(errs.values()))} at every rtol (take the coarsest)")
            continue
        text = f"{m} {fmt_err(errs[coarse])} at rtol = {coarse:.0e}"
        for target in (1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14):
            good = [r for r, e in errs.items() if e <= target]
            if target < errs[coarse] and good:
                r = max(good)
                text += f", ≤ {target:.0e} from rtol = {r:.0e} ({fmt_ms(done[r].time)} ms)"
        if m == "dense":  # the interpolant's promise: within rtol
            text += f"; at most {max(e / r for r, e in errs.items()):.2g}× rtol"
        parts.append(text)
    times = {r: row.time for r, row in done.items()}
    fine = min(times)
    text = f"- {key}: " + "; ".join(parts) + ". A run costs "
    if DEFAULT_RTOL in times and DEFAULT_RTOL not in (coarse, fine):
        text += f"{fmt_ms(times[DEFAULT_RTOL])} ms at the default {DEFAULT_RTOL:.0e}, "
    text += f"{fmt_ms(times[coarse])} ms at {coarse:.0e} and {fmt_ms(times[fine])} ms at {fine:.0e}"
    failed = sorted((r for r, row in by.items() if row.rounds and not row.ok), reverse=True)
    if failed:
        text += f"; it did not complete at rtol = {', '.join(f'{r:.0e}' for r in failed)}"
    return text + "."


# ----------------------------------------------------------------------------- the report


TOOLS = (
    "Tools and knobs. Ours: `trace(..., rtol=r)` (the CO fold curve: `fold_curve(..., "
    "rtol=r)`; the paths and the locus: `ContinuationOptions(rtol=r)` with the scene's or "
    "`point_loci`'s other options), r = 1e-2 … 1e-13. contique 1.1.1: `solve` with "
    "`dxmax = dlpfmax` (the largest increment of every unknown and of the parameter) and "
    "`tol` (on the residual's 2-norm). pacopy 0.1.9: `euler_newton` with `stepsize_max` and "
    "`newton_tol`, the states' inner product their mean (as ours weighs them), Jacobian "
    "solves by LAPACK (dense) or SuperLU (sparse). The SciPy loop: `scipy.optimize.root` "
    "(hybr) at n equal steps of the parameter, forward and back; on the Bratu problem Newton "
    "with SuperLU (hybr is dense) and forward only (there is no solution past the fold). "
    "contique, pacopy and the SciPy loop do not locate folds: their estimate is the extreme "
    "parameter among their points, or the midpoint of the step where the SciPy loop fails. "
    "The tolerances of contique and pacopy are absolute: on the Bratu problem they start at "
    "1e-2 (N = 999) and 1e-1 (N = 99 999), since the residual's 2-norm cannot fall below its "
    "rounding, about ε(N + 1)²√N (3e-9 and 3e-4). N = 999 and 99 999 are the sizes with "
    "h = 1e-3 and 1e-5 (the references: mpmath shooting, and its stored value for 99 999)."
)


def _header(args, argv, rounds, notes, elapsed) -> list[str]:
    commit, load = commit_and_load()
    now = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    given = sys.argv[1:] if argv is None else argv
    command = "python scripts/bench_work_precision.py" + "".join(f" {a}" for a in given)
    dense = (
        "Dense output: the `dense` errors are those of our interpolant (`Branch.interpolate`); "
        "the `curve` errors, of every tool's points joined by straight lines."
    )
    return [
        "# Work–precision: speed against accuracy",
        "",
        f"Measured {now} at commit `{commit}` on {machine()}; load average {load:.2f}. "
        f"The whole run took {elapsed:.0f} s.",
        "",
        f"Reproduce from the repository root: `{command}` (contique 1.1.1 and pacopy 0.1.9 are "
        "optional, not dependencies: see `scripts/bench_trace.py` for how to install them).",
        "",
        "Each setting runs once first (its errors and counts come from that run; settings go "
        f"coarse to fine per tool, and a tool whose run takes over {args.max_run:g} s skips its "
        f"finer ones); runs shorter than {args.long:g} s are then timed timeit-style, best of "
        f"{rounds} round(s) of a loop of at least 0.05 s, rounds interleaved across all runs "
        "of the problem, so that load from other jobs hits every tool alike; longer runs keep "
        "their first time (rounds = 1). All tools get the analytic Jacobian. f-evals: "
        "residual evaluations, counted by wrapping the residual (J-evals: Jacobian "
        "evaluations or solves with it); for (c) and (d), evaluations of the body's "
        "tangential equilibrium F̂_T (one per leg residual and one per quadrature node). "
        f"Errors below {FLOOR:.0e} count as equal (rounding); the figures draw errors below "
        "1e-16 at 1e-16.",
        "",
        TOOLS,
        "",
        dense,
        "",
        *[f"Note: {n}" for n in notes],
    ]


def write_all(results, args, argv, rounds, notes, elapsed) -> Path:
    """Write the figures and the report; returns the report's path."""
    out = Path(args.out)
    figures = Path(args.figures)
    lines = _header(args, argv, rounds, notes, elapsed)
    lines += ["", "## Summary", "", *headline(results)]
    for group, (title, stem) in GROUPS.items():
        these = [(t, rows) for t, rows in results if t.group == group]
        if not these:
            continue
        paths = draw_group(these, figures / stem)
        lines += ["", f"## ({group}) {title}", ""]
        lines += [f"![{title}: {axis}]({_relative(p, out.parent)})" for axis, p in paths]
        for task, rows in these:
            lines += ["", f"### {task.name}", "", f"Reference: {task.reference}.", ""]
            lines += [f"Measures: {', '.join(f'`{m}`: {MEASURES[m]}' for m in measures_of(rows))}."]
            lines += ["", *table(task, rows), "", "**Does our front dominate?**", ""]
            lines += dominance(task, rows)
    lines += ["", "## The trade", "", *trade(results)]
    lines += ["", "## Choosing rtol", "", *choosing_rtol(results), ""]
    return write_report(out, "\n".join(lines))


def _relative(path: Path, start: Path) -> str:
    import os

    return os.path.relpath(path, start).replace(os.sep, "/")
