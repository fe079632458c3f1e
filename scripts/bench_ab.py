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
"""

from __future__ import annotations

import argparse
import importlib
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from bench_trace import PROBLEMS, run_ours

ROOT = Path(__file__).resolve().parents[1]


def load_revision(rev: str | None, into: Path, name: str):
    """The engine at git revision ``rev`` (None: the working tree, as installed), imported as
    module ``name``."""
    if rev is None:
        return importlib.import_module("cusp.continuation")
    target = into / name
    target.mkdir()
    archive = subprocess.run(
        ["git", "archive", rev, "continuation"], cwd=ROOT, check=True, capture_output=True
    ).stdout
    subprocess.run(
        ["tar", "-x", "--strip-components=1", "-C", str(target)], input=archive, check=True
    )
    if str(into) not in sys.path:
        sys.path.insert(0, str(into))
    return importlib.import_module(name)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("base")
    ap.add_argument("new", nargs="?", default=None)
    ap.add_argument("--rounds", type=int, default=11)
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        sides = {
            "base": load_revision(args.base, Path(tmp), "continuation_ab_base"),
            "new": load_revision(args.new, Path(tmp), "continuation_ab_new"),
        }
        for pb in PROBLEMS:
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


if __name__ == "__main__":
    raise SystemExit(main())
