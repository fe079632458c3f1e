"""Interleaved A/B timing of `trace` at two git revisions, in one process.

Usage (from the repository root):

    python scripts/bench_ab.py BASE [NEW] [--rounds 11]

BASE and NEW are git revisions (NEW defaults to the working tree, i.e. the installed
`cusp.continuation`). The engine folder `continuation/` of a revision is loaded under a name
of its own (the engine imports only relatively, so this works for revisions before and after
the `cusp` namespace), and both trace
the benchmark problems of `scripts/bench_trace.py` (cusp and truss, analytic derivatives)
in alternating rounds of 100 branches, so load from other jobs on this shared machine hits
both alike. Prints, per problem, each side's points, Newton iterations and folds, and the
ratio of the best round times (NEW/BASE; < 1 means NEW is faster). Changes of a few per
cent are only visible this way: separate runs drift by more than that.

    python scripts/bench_ab.py BASE [NEW] --sparse N [--rounds 3]

traces the sparse FD Bratu problem with N unknowns (as `scripts/bench_sparse.py`) by both
sides instead, one trace a round, and reports steps, sparse LU factorizations, and the cost
per step and per LU (a side that takes longer steps costs more per step, not per LU).
"""

from __future__ import annotations

import argparse
import importlib
import importlib.util
import tempfile
import time
from pathlib import Path

from cusp._scripts.revisions import load_folder
from cusp._scripts.tools import run_ours, trace_problems


def load_revision(rev: str | None, into: Path, name: str):
    """The engine at git revision ``rev`` (None: the working tree, as installed), imported as
    module ``name`` from its ``continuation/`` folder extracted under ``into``
    (:func:`cusp._scripts.revisions.load_folder`)."""
    if rev is None:
        return importlib.import_module("cusp.continuation")
    return load_folder(rev, "continuation", into, name)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("base")
    ap.add_argument("new", nargs="?", default=None)
    ap.add_argument("--rounds", type=int, default=11)
    ap.add_argument(
        "--sparse",
        type=int,
        metavar="N",
        help="instead: the sparse FD Bratu problem with N unknowns (as scripts/bench_sparse.py), "
        "one trace a round, with its steps, sparse LUs and the cost per step and per LU",
    )
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        sides = {
            "base": load_revision(args.base, Path(tmp), "continuation_ab_base"),
            "new": load_revision(args.new, Path(tmp), "continuation_ab_new"),
        }
        if args.sparse:
            return sparse_ab(sides, args.sparse, args.rounds)
        for pb in trace_problems():
            runs = {
                side: (lambda m=m, pb=pb: run_ours(pb, True, api=m)) for side, m in sides.items()
            }
            for side, run in runs.items():
                out = run()()
                folds = [f"{lam:.17g}" for lam in out["folds"]]
                print(
                    f"{pb['name']} [{side}]: {out['points']} points, "
                    f"{out['newton']} Newton iterations, folds {folds}"
                )
            times = {side: [] for side in runs}
            for r in range(args.rounds):
                for side in ("base", "new") if r % 2 == 0 else ("new", "base"):
                    t0 = time.perf_counter()
                    for _ in range(100):
                        runs[side]()
                    times[side].append((time.perf_counter() - t0) / 100 * 1e3)
            b, n = min(times["base"]), min(times["new"])
            print(
                f"  best of {args.rounds}: base {b:.3f} ms, new {n:.3f} ms, "
                f"ratio new/base {n / b:.3f}"
            )
    return 0


def sparse_ab(sides: dict, n: int, rounds: int) -> int:
    """The sparse Bratu trace of ``scripts/bench_sparse.py`` by both sides, interleaved: the
    best time of each, its steps, its sparse LU factorizations (counted by wrapping SuperLU)
    and the cost per step and per LU."""
    import scipy.sparse.linalg as spla

    import cusp.examples as ex

    case = ex.bratu(n, sparse=True)
    splu = spla.splu
    count = [0]

    def counted(*a, **k):
        count[0] += 1
        return splu(*a, **k)

    best: dict[str, tuple] = {}
    spla.splu = counted
    try:
        for r in range(rounds):
            for side in ("base", "new") if r % 2 == 0 else ("new", "base"):
                count[0] = 0
                t0 = time.perf_counter()
                br = sides[side].trace(
                    case.problem, case.u0, free="lam", bounds=case.bounds, max_steps=400
                )
                dt = time.perf_counter() - t0
                if side not in best or dt < best[side][0]:
                    folds = [sp.values["lam"] for sp in br.special_points if sp.kind == "fold"]
                    best[side] = (dt, br.info["steps"], count[0], folds, br.status)
    finally:
        spla.splu = splu
    for side, (dt, steps, lus, folds, status) in best.items():
        print(
            f"sparse Bratu N = {n} [{side}]: best {dt:.3f} s, {steps} steps, {lus} sparse LUs, "
            f"{dt / steps * 1e3:.1f} ms per step, {dt / lus * 1e3:.1f} ms per LU, "
            f"folds {[f'{f:.16g}' for f in folds]}, {status}"
        )
    b, nw = best["base"], best["new"]
    print(
        f"  ratio new/base: trace {nw[0] / b[0]:.3f}, per step "
        f"{(nw[0] / nw[1]) / (b[0] / b[1]):.3f}, per LU {(nw[0] / nw[2]) / (b[0] / b[2]):.3f}"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
