"""Time to draw all of the Fig 9 scene's figures, this tree against a base revision, in one
process.

The scene's paths and loci are computed once (``cusp.app.run.run_scene`` without plots);
then, in alternating rounds (so that load from other jobs on a shared machine hits both
alike), each side renders every figure the scene names (``fig9``, ``manifold-surface``,
``loci-control-planes``, ``loci-energies``, ``regime-map``) to PNG and SVG bytes, as
``cusp run`` does: whatever a figure computes for itself (the surface's paths, the regime
map's boundaries or grid) is part of its time. The base side is the ``app/`` folder of the
base revision loaded under a name of its own (its figure modules import each other
relatively, and the models and engine of this tree absolutely).

Reports wall and CPU (process) seconds, best and median of the rounds, per figure and in
all, with the machine's load average before and after. Writes ``docs/benchmarks/figures.md``.

Usage (from the repository root): ``python scripts/bench_figures.py [--base REV] [--rounds N]``
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from cusp._scripts.report import commit_and_load, write_report

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "benchmarks" / "figures.md"
#: the revision before issue 32's figure work (main at the start of it)
BASE = "462af82"
PATH_FIGURES = ("fig9", "force-slip", "force-slip-detail", "force-area")


def load_app(rev: str, into: Path, name: str):
    """The ``app/`` package of git revision ``rev``, imported as ``name``."""
    target = into / name
    target.mkdir()
    archive = subprocess.run(
        ["git", "archive", rev, "app"], cwd=ROOT, check=True, capture_output=True
    ).stdout
    subprocess.run(
        ["tar", "-x", "--strip-components=1", "-C", str(target)], input=archive, check=True
    )
    spec = importlib.util.spec_from_file_location(
        name, target / "__init__.py", submodule_search_locations=[str(target)]
    )
    if spec is None or spec.loader is None:
        raise RuntimeError(f"cannot load app/ of revision {rev!r} from {target}")
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


def render_all(figures, manifold_figures, run, scene) -> dict[str, tuple[float, float]]:
    """(wall, CPU) seconds of each figure of ``scene``, rendered by the given modules."""
    out = {}
    kept = getattr(figures, "_parsed", None)  # the mathtext parses kept across figures
    if kept is not None:
        kept.cache_clear()  # as in a fresh `cusp run`: no string parsed yet
    for name in scene.figures:
        w, c = time.perf_counter(), time.process_time()
        if name in PATH_FIGURES:
            blobs = figures.render(run.cases, [name], title=scene.title)
        else:
            blobs = manifold_figures.render_manifold(run, [name])
        assert set(blobs[name]) == {"png", "svg"}
        out[name] = (time.perf_counter() - w, time.process_time() - c)
    return out


def measure(base: str, rounds: int) -> tuple[dict, dict, str]:
    import importlib

    from cusp.app.run import bundled_scene, load_scene, run_scene

    scene = load_scene(bundled_scene("fig9.toml"))
    run, _ = run_scene(scene, plots=False)
    sides = {}
    with tempfile.TemporaryDirectory() as tmp:
        old = load_app(base, Path(tmp), "cusp_app_base")
        importlib.import_module("cusp_app_base.figures")
        importlib.import_module("cusp_app_base.manifold_figures")
        from cusp.app import figures, manifold_figures

        sides["base"] = (old.figures, old.manifold_figures)
        sides["new"] = (figures, manifold_figures)
        render_all(*sides["new"], run, scene)  # warm: matplotlib's imports and font cache
        times: dict[str, list[dict]] = {"base": [], "new": []}
        for _ in range(rounds):
            for side in ("base", "new"):
                times[side].append(render_all(*sides[side], run, scene))
    return times, {"figures": list(scene.figures)}, scene.title


def _stats(rounds: list[dict], name: str | None, k: int) -> tuple[float, float]:
    vals = [sum(r[n][k] for n in r) if name is None else r[name][k] for r in rounds]
    return min(vals), statistics.median(vals)


def report(times, info, base, rounds, load0, load1, commit) -> str:
    names = info["figures"]
    rows = []
    for name in [*names, None]:
        cells = []
        for side in ("base", "new"):
            for k in (0, 1):
                best, med = _stats(times[side], name, k)
                cells.append(f"{best:.2f} / {med:.2f}")
        b, n = _stats(times["base"], name, 0)[0], _stats(times["new"], name, 0)[0]
        label = "**all**" if name is None else f"`{name}`"
        rows.append(f"| {label} | {' | '.join(cells)} | {n / b:.2f} |")
    new_all = _stats(times["new"], None, 0)[0]
    new_cpu = _stats(times["new"], None, 1)[0]
    return "\n".join(
        [
            "# Drawing the Fig 9 scene's figures",
            "",
            "Generated by `python scripts/bench_figures.py` (do not edit by hand). Each side",
            "renders every figure of `scenes/fig9.toml` to PNG and SVG bytes from the same",
            "computed run, in alternating rounds in one process; a figure's time includes",
            "what it computes for itself (the surface's paths; the regime map's boundaries,",
            "or at the base its grid of loci). Seconds, best / median of the rounds.",
            "",
            f"- base: `{base}` (`app/` of that revision); new: this tree at `{commit}`",
            f"- rounds: {rounds}; machine: {platform.machine()}, {os.cpu_count()} cores,"
            f" Python {platform.python_version()}",
            f"- load average (1 min) before: {load0:.2f}, after: {load1:.2f}"
            " (a shared machine: wall times grow with the load, CPU times much less)",
            "",
            "| figure | base wall | base CPU | new wall | new CPU | new/base (best wall) |",
            "| --- | --- | --- | --- | --- | --- |",
            *rows,
            "",
            f"All of the scene's figures, new: {new_all:.2f} s wall, {new_cpu:.2f} s CPU (best"
            f" round); the goal of issue 32 is under 3 s.",
            "",
        ]
    )


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--base", default=BASE, help=f"base git revision (default {BASE})")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--out", type=Path, default=DOC)
    args = parser.parse_args(argv)
    if args.rounds < 1:
        parser.error(f"--rounds must be at least 1, got {args.rounds}")
    commit, load0 = commit_and_load()
    times, info, _ = measure(args.base, args.rounds)
    load1 = commit_and_load()[1]
    text = report(times, info, args.base, args.rounds, load0, load1, commit)
    write_report(args.out, text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
