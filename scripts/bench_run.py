"""Wall time of ``cusp run`` on the Fig 6 scene, with import time separated from compute time.

Each repetition is a fresh Python process (imports are only paid once per process), timing:

* start-up: the interpreter alone (``python -c pass``);
* import: ``cusp.app.run`` and everything the computation imports (numpy, scipy, the solver,
  the exponential surface, the contact-loss model);
* compute: parse the scene, trace the three legs, place the points, integrate the energies;
* figures: import matplotlib and render the two figures to PNG and SVG bytes;
* write: summary.json, branch.csv and the figures, atomically;
* whole command: ``cusp run scenes/fig6.toml`` as a user runs it (a separate process).

Writes ``docs/benchmarks/run.md``. Usage: ``python scripts/bench_run.py [--repeat N]``.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from datetime import datetime, timezone
from pathlib import Path

from cusp._scripts.report import commit_and_load, write_report

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "scenes" / "fig6.toml"
DOC = ROOT / "docs" / "benchmarks" / "run.md"

_CHILD = r"""
import json, sys, time
t0 = time.perf_counter()
import cusp.app.run as run
import cusp.models.contact_loss, cusp.models.exponential  # what the computation imports
t1 = time.perf_counter()
scene = run.load_scene(sys.argv[1])
r, _ = run.run_scene(scene, plots=False)
t2 = time.perf_counter()
from cusp.app.figures import render
figs = render(r.cases, scene.figures, title=scene.title)
t3 = time.perf_counter()
files = {"summary.json": json.dumps(run.summary(r)).encode(),
         "branch.csv": run.branch_csv(r).encode()}
files.update({f"{n}.{k}": v for n, b in figs.items() for k, v in b.items()})
run.write_outputs(__import__("pathlib").Path(sys.argv[2]), files)
t4 = time.perf_counter()
print(json.dumps({"import": t1 - t0, "compute": t2 - t1, "figures": t3 - t2,
                  "write": t4 - t3}))
"""


def _python(args, **kw):
    env = {**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg"}
    return subprocess.run(
        [sys.executable, *args], capture_output=True, text=True, check=True, env=env, **kw
    )


def measure(repeat: int) -> dict[str, list[float]]:
    out: dict[str, list[float]] = {
        k: [] for k in ("startup", "import", "compute", "figures", "write", "command")
    }
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(repeat):
            t = time.perf_counter()
            _python(["-c", "pass"])
            out["startup"].append(time.perf_counter() - t)
            rec = json.loads(_python(["-c", _CHILD, str(SCENE), f"{tmp}/a{i}"]).stdout)
            for k, v in rec.items():
                out[k].append(v)
            t = time.perf_counter()
            _python(["-m", "cusp.app.cli", "run", str(SCENE), "--out", f"{tmp}/b{i}", "--quiet"])
            out["command"].append(time.perf_counter() - t)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--no-write", action="store_true", help="print only")
    args = ap.parse_args()
    data = measure(args.repeat)
    med = {k: statistics.median(v) for k, v in data.items()}
    lo = {k: min(v) for k, v in data.items()}
    rows = [
        ("interpreter start-up (`python -c pass`)", "startup"),
        ("import (`cusp.app.run`, numpy, scipy, solver, exponential model)", "import"),
        ("compute (parse scene, trace O→A→B→C, place A–D, energies)", "compute"),
        ("figures (import matplotlib, render 2 figures × PNG + SVG)", "figures"),
        ("write (summary.json, branch.csv, figures; atomic)", "write"),
        ("**whole command** `cusp run scenes/fig6.toml --quiet`", "command"),
    ]
    import matplotlib
    import numpy
    import scipy

    commit, load = commit_and_load()
    lines = [
        "# Benchmark: wall time of `cusp run` on the Fig 6 scene",
        "",
        f"Measured {datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC at commit `{commit}` on "
        f"{platform.processor() or platform.machine()}, {os.cpu_count()} logical CPUs (shared); "
        f"load average {load:.2f}; Python {platform.python_version()}, NumPy "
        f"{numpy.__version__}, SciPy {scipy.__version__}, Matplotlib {matplotlib.__version__}.",
        "",
        "Reproduce: `python scripts/bench_run.py` (fresh processes; median and best of "
        f"{args.repeat}).",
        "",
        "| phase | median (ms) | best (ms) |",
        "|---|---:|---:|",
    ]
    for label, key in rows:
        lines.append(f"| {label} | {med[key] * 1e3:.1f} | {lo[key] * 1e3:.1f} |")
    lines += [
        "",
        "The phases inside one process add up to the command's time less the interpreter "
        "start-up and the argument parsing. With `--no-plots` the figures phase (and the "
        "matplotlib import) is skipped.",
        "",
    ]
    text = "\n".join(lines)
    print(text)
    if not args.no_write:
        write_report(DOC, text)
        print(f"wrote {DOC.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
