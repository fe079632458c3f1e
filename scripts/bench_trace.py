"""Benchmark `continuation.trace` against contique, pacopy and a plain SciPy natural-parameter loop.

Usage (from the repository root):

    python scripts/bench_trace.py [--repeat 7] [--out docs/benchmarks/trace.md]

All of them run in ONE process on the same problems, each timed timeit-style (autorange a loop
count, then the best of `--repeat` rounds, per full branch; rounds interleaved across tools):

* cusp normal form x^3 - x - b = 0, b from -1 to 1 (folds at b = -+2/(3 sqrt 3));
* Green-strain von Mises truss (EA = L = 1, H = 0.5), P from P(v=-0.5) to P(v=1.5) (limit
  points at v = H(1 -+ 1/sqrt 3)).

Both come from `cusp.examples` (`cusp_normal_form`, `truss_green`), with their references.

Tools:

* ours: `trace` with the analytic Jacobian, and with the "central" finite-difference fallback;
* contique (optional, `pip install contique`): `contique.solve`, a generator, stopped when the
  parameter leaves the range; analytic Jacobian and its default central differences. It prints
  a table per step, which we send to a StringIO (the printing is part of its cost: it cannot be
  switched off). Folds are not located by contique: we take the point with the extreme
  parameter where the parameter increment changes sign (a bracket), and report its error;
* pacopy 0.1.9 (optional, GPL, not on PyPI at that version: `pip install
  "git+https://github.com/sigma-py/pacopy@354702b056094e707c2447f98d2f90718cc5ef69"`, the
  commit that sets version 0.1.9; the repository moved from nschloe/pacopy): `pacopy.euler_newton`
  (pseudo-arclength, tangent predictor, Newton corrector by two solves with the Jacobian), with
  a `jacobian_solver` on the example's analytic Jacobian (LAPACK gesv, as the floor below);
  pacopy has no finite-difference mode, so analytic only. Settings: its defaults
  (stepsize0 = 0.5, max_newton_steps = 5, stepsize_aggressiveness = 2, cos_alpha_min = 0.9,
  theta0 = 1, i.e. the same Euclidean arclength in (x, lam) as ours) except newton_tol = 1e-10
  (ours: tol) and stepsize_max = 0.5 (ours: ds_max), verbose off. A callback records the points
  and stops it (a private exception) once the parameter passes the end. It builds a rich
  `Console` in every corrector call (and its start-up Newton prints, sent to a StringIO):
  part of its cost, it cannot be switched off. Folds: bracketed as for contique. Newton
  iterations: the corrector iterations of the accepted steps (read by wrapping its
  `_newton_corrector` during the run);
* floor: a bare pseudo-arclength loop (about 40 lines) with the same step rules as ours
  (tangent predictor, bordered Newton by LAPACK gesv, the same convergence test, step control
  and angle guard) but no special points, no bookkeeping and no result: what the step
  sequence itself costs in Python on this machine. It stops at the first point past the end;
* SciPy natural-parameter loop: `scipy.optimize.root` (hybr) at parameter steps of 0.01 of the
  range, forward and then backward (hysteresis sweep); a fold is "detected" by the jump of the
  solution to the other sheet, and estimated by the last parameter before the jump.

contique and pacopy are optional: if one is missing the report says so.
"""

from __future__ import annotations

import argparse
import datetime
import importlib.metadata
import math
import time
from pathlib import Path

import numpy as np
from scipy.linalg import lapack

from cusp._scripts.report import commit, machine, write_report
from cusp._scripts.tools import (
    TOL,
    best_times,
    fold_errors,
    functions,
    import_contique,
    import_pacopy,
    run_contique,
    run_ours,
    run_pacopy,
    run_scipy,
    trace_problems,
)

ROOT = Path(__file__).resolve().parents[1]

# The problems (cusp and truss) are `trace_problems()` of cusp._scripts.tools, shared with
# bench_ab.py and bench_work_precision.py.
PROBLEMS = trace_problems()


# ----------------------------------------------------------------------------- runners
# The tools' runners are in cusp._scripts.tools (shared with bench_work_precision.py); here only the
# floor, which no other script uses.


def run_floor(pb):
    """The bare loop (see the module docstring): defaults of `ContinuationOptions`."""
    gesv, getrs = lapack.dgesv, lapack.dgetrs
    cnt = {"f": 0}
    res, jac, pjac, free, params = functions(pb)

    def residual(z):
        cnt["f"] += 1
        p = dict(params)
        p[free] = z[-1]
        return res(z[:-1], p)

    def bordered(z, row):
        p = dict(params)
        p[free] = z[-1]
        a = np.empty((2, 2))
        a[:1, :1] = jac(z[:-1], p)
        a[:1, 1] = pjac(z[:-1], p, free)
        a[1] = row
        return a

    def norm(x):
        v = x.tolist()
        return max(abs(max(v)), abs(min(v)))

    e = np.array([0.0, 1.0])
    z = np.array([pb["x0"], pb["lam0"]])
    up = pb["lam1"] > pb["lam0"]
    t = gesv(bordered(z, e), e)[2]
    t /= math.copysign(math.sqrt(t.dot(t)), t[-1] if up else -t[-1])
    ds, points, newton = 0.05, 1, 0
    while ((z[-1] < pb["lam1"]) if up else (z[-1] > pb["lam1"])) and points < 1000:
        while True:
            zp = z + ds * t
            c = t.dot(zp)
            zz, g, ok, sn_prev, k = zp, residual(zp), False, math.inf, 0
            sq = 1e-5 * (1.0 + norm(zp))  # √step_tol·(1 + |z|), as ours
            while k < 10:
                k += 1
                rhs = np.empty(2)
                rhs[:1] = g
                rhs[1] = t.dot(zz) - c
                lu, piv, dz, _ = gesv(bordered(zz, t), rhs)
                zz = zz - dz
                g = residual(zz)
                sn = norm(dz)
                if norm(g) <= TOL and sn <= sq:
                    ok = True
                    break
                if sn > sn_prev:
                    break
                sn_prev = sn
            newton += k
            if ok:
                tn = getrs(lu, piv, e)[0]
                tn /= math.sqrt(tn.dot(tn))
                angle = math.degrees(math.acos(max(-1.0, min(1.0, t.dot(tn)))))
                if angle <= 30.0:
                    break
            ds *= 0.5
        ds = min(0.5, ds * min(2.0, max(0.5, min(5.0 / k, 15.0 / max(angle, 1e-12)))))
        z, t = zz, tn
        points += 1
    return lambda: {
        "points": points,
        "newton": newton,
        "nfev": cnt["f"],
        "folds": [],
        "located": "none (no special points)",
        "ok": True,
    }


# ----------------------------------------------------------------------------- timing


def phases(pb, rounds=100, repeat=7):
    """Where `trace` spends its time (analytic derivatives): wall time inside the corrector of
    the steps (and the start), inside special-point location (fold Newton, bound, and the
    tangent there), setup and result, and the rest; of `repeat` batches of `rounds` branches,
    the batch with the least total time (as for the wall times: load from other jobs only
    adds). The wrappers add ~0.3 µs a call, so the shares are approximate."""
    best = None
    for _ in range(repeat):
        total, parts = _phases_once(pb, rounds)
        if best is None or total < best[0]:
            best = (total, parts)
    return best


def _phases_once(pb, rounds):
    import cusp.continuation.stepping._advance as ad
    import cusp.continuation.stepping._crossings as cr
    import cusp.continuation.stepping._insert as ins
    import cusp.continuation.stepping._start as sr
    import cusp.continuation.stepping._step as st
    import cusp.continuation.stepping._tracer as tr

    acc = {}
    active = set()  # a phase is timed once even if its functions nest
    saved = []

    def wrap(owner, name, key):
        fn = getattr(owner, name)
        saved.append((owner, name, fn))

        def timed(*a, **k):
            if key in active:
                return fn(*a, **k)
            active.add(key)
            t0 = time.perf_counter()
            try:
                return fn(*a, **k)
            finally:
                acc[key] = acc.get(key, 0.0) + time.perf_counter() - t0
                active.discard(key)

        setattr(owner, name, timed)

    wrap(st, "newton", "corrector (steps and start)")
    wrap(st, "damped_newton", "corrector (steps and start)")
    wrap(ad, "correct", "corrector (steps and start)")  # steps aimed at a bound or target
    wrap(sr, "correct", "corrector (steps and start)")  # the start's corrector
    wrap(tr, "locate_crossings", "special-point location")
    wrap(tr, "corner_folds", "special-point location")
    wrap(ins, "located_point", "special-point location")  # (called by _insert.link_located)
    wrap(cr, "tangent_at", "special-point location")
    wrap(ins, "tangent_at", "special-point location")
    wrap(tr.Tracer, "__init__", "setup and result")
    wrap(tr.Tracer, "result", "setup and result")
    try:
        t0 = time.perf_counter()
        for _ in range(rounds):
            run_ours(pb, True)
        total = time.perf_counter() - t0
    finally:
        for owner, name, fn in saved:
            setattr(owner, name, fn)
    out = {k: v / rounds for k, v in acc.items()}
    out["the rest: start tangent, step control, test functions"] = (
        total - sum(acc.values())
    ) / rounds
    return total / rounds, out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeat", type=int, default=15)
    ap.add_argument("--out", default=str(ROOT / "docs" / "benchmarks" / "trace.md"))
    args = ap.parse_args(argv)

    contique = import_contique()
    pacopy, pacopy_note = import_pacopy()

    variants = [
        ("ours", "analytic", lambda pb: run_ours(pb, True)),
        ("ours", "central FD", lambda pb: run_ours(pb, False)),
    ]
    if contique is not None:
        variants += [
            (
                "contique " + contique.__version__,
                "analytic",
                lambda pb: run_contique(pb, True, contique),
            ),
            (
                "contique " + contique.__version__,
                "central FD",
                lambda pb: run_contique(pb, False, contique),
            ),
        ]
    if pacopy is not None:
        variants.append(
            (
                "pacopy " + importlib.metadata.version("pacopy"),
                "analytic",
                lambda pb: run_pacopy(pb, pacopy),
            )
        )
    variants += [
        ("floor: bare loop", "analytic", run_floor),
        ("SciPy root loop", "analytic", lambda pb: run_scipy(pb, True)),
        ("SciPy root loop", "FD (hybr)", lambda pb: run_scipy(pb, False)),
    ]

    rows, ratios = [], []
    for pb in PROBLEMS:
        times = {}
        bests = best_times([lambda fn=fn, pb=pb: fn(pb) for _, _, fn in variants], args.repeat)
        for (tool, deriv, fn), t in zip(variants, bests, strict=True):
            out = fn(pb)()
            times[(tool.split()[0], deriv)] = t
            errs = fold_errors(out["folds"], pb["folds"])
            located = sum(
                e is not None and e <= 1e-12 * max(1.0, abs(lam))
                for e, (_, lam) in zip(errs, pb["folds"], strict=True)
            )
            err_txt = ", ".join("—" if e is None else f"{e:.1e}" for e in errs)
            newton = out["newton"]
            rows.append(
                (
                    pb["name"],
                    tool,
                    deriv,
                    t * 1e3,
                    out["points"],
                    "—" if newton is None else f"{newton / out['points']:.2f}",
                    f"{out['nfev'] / out['points']:.1f}",
                    f"{located}/{len(pb['folds'])} to 1e-12 ({out['located']})",
                    err_txt,
                    "yes" if out["ok"] else "NO",
                )
            )
        if contique is not None:
            for deriv in ("analytic", "central FD"):
                ratios.append(
                    (
                        "contique",
                        pb["name"],
                        deriv,
                        times[("ours", deriv)] / times[("contique", deriv)],
                    )
                )
        if pacopy is not None:
            ratios.append(
                (
                    "pacopy",
                    pb["name"],
                    "analytic",
                    times[("ours", "analytic")] / times[("pacopy", "analytic")],
                )
            )

    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    lines = [
        "# Benchmark: `trace` vs contique vs pacopy vs a SciPy natural-parameter loop",
        "",
        f"Measured {now} at commit `{commit()}` on: {machine()}.",
        "",
        "Reproduce from the repository root: `python scripts/bench_trace.py` "
        "(contique is optional: `pip install contique==1.1.1`; so is pacopy 0.1.9, GPL, "
        "not on PyPI at that version and not a dependency of this project: `pip install "
        '"git+https://github.com/sigma-py/pacopy@354702b056094e707c2447f98d2f90718cc5ef69"`, '
        "the commit that sets version 0.1.9, in the repository formerly nschloe/pacopy).",
        "",
        "pacopy runs `euler_newton` with its defaults (stepsize0 = 0.5, max_newton_steps = 5, "
        "stepsize_aggressiveness = 2, cos_alpha_min = 0.9, theta0 = 1: the same Euclidean "
        "arclength in (x, λ) as ours) except newton_tol = 1e-10 (ours: `tol`) and "
        "stepsize_max = 0.5 (ours: `ds_max`), and a `jacobian_solver` on the analytic "
        "Jacobian (LAPACK gesv); it has no finite-difference mode. It builds a rich `Console` "
        "in every corrector call, part of its cost (it cannot be switched off), as contique's "
        "printing is part of contique's. Both stop (by a callback) at the first point past the "
        "end of the range.",
        "",
        "Wall time per full branch (the solve only, not this script's summary of it): "
        "timeit-style, best of "
        f"{args.repeat} rounds of an autoranged loop, all tools in one process, rounds "
        "interleaved across tools so that load from other jobs hits all of them alike. "
        "Newton iterations per point are each tool's own count (ours: `stats`; contique: "
        "`NewtonResult.niterations` of accepted steps only; pacopy: the corrector iterations "
        "of accepted steps); residual evaluations per point "
        "include finite-difference evaluations. A fold counts as located when its parameter is "
        "within 1e-12 (relative, or absolute below 1) of the exact value; the error column "
        "gives, for each exact fold in path order, the distance to the nearest estimate.",
        "",
        "| problem | tool | derivatives | time (ms) | points | Newton it/pt | f evals/pt "
        "| folds located | fold parameter error | reached end |",
        "|---|---|---|---:|---:|---:|---:|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r[0]} | {r[1]} | {r[2]} | {r[3]:.3f} | {r[4]} | {r[5]} | {r[6]} "
            f"| {r[7]} | {r[8]} | {r[9]} |"
        )
    for other, missing in (
        ("contique", None if contique is not None else "contique is not installed: no ratio."),
        ("pacopy", None if pacopy is not None else pacopy_note.replace("rows", "ratio")),
    ):
        lines += [
            "",
            f"Ratio of wall times, ours / {other} (same run; < 1 means ours is faster):",
            "",
        ]
        if missing:
            lines.append(f"- {missing}")
        for tool, name, deriv, ratio in ratios:
            if tool == other:
                lines.append(
                    f"- {name}, {deriv}: {ratio:.3f} (ours {1 / ratio:.1f}× faster)"
                    if ratio < 1
                    else f"- {name}, {deriv}: {ratio:.3f} ({other} {ratio:.1f}× faster)"
                )
    total, parts = phases(PROBLEMS[0])
    lines += [
        "",
        f"Where our time goes ({PROBLEMS[0]['name']}, analytic; per branch, "
        f"{total * 1e3:.3f} ms with the timing wrappers):",
        "",
        "| phase | time (µs) | share |",
        "|---|---:|---:|",
    ]
    for key, value in parts.items():
        lines.append(f"| {key} | {value * 1e6:.0f} | {value / total:.0%} |")
    lines += [
        "",
        "Target for the solver: the cusp branch with both folds located in about "
        "1 ms, at least 10× faster than contique.",
        "",
    ]
    text = "\n".join(lines)
    write_report(args.out, text)
    print(text)


if __name__ == "__main__":
    main()
