"""The work–precision benchmark script runs in its quick mode on two tasks and writes its
report (tables, fronts, "Choosing rtol") and its figures; contique and pacopy are optional
(the report says when one is missing)."""

from __future__ import annotations

import importlib.metadata
import importlib.util


def _installed(name: str, prefix: str = "") -> bool:
    if importlib.util.find_spec(name) is None:
        return False
    return importlib.metadata.version(name).startswith(prefix)


def _rows(text: str, heading: str) -> list[list[str]]:
    """The rows of the first table after ``heading``, as lists of cells."""
    part = text.split(heading, 1)[1].splitlines()
    first = next(i for i, ln in enumerate(part) if ln.startswith("| tool "))
    lines = []
    for ln in part[first + 2 :]:
        if not ln.startswith("|"):
            break
        lines.append([c.strip() for c in ln.strip("|").split("|")])
    return lines


def test_quick_mode_writes_the_report_and_the_figures(tmp_path, load_script):
    module = load_script("bench_work_precision")
    out, figures = tmp_path / "wp.md", tmp_path / "figures"
    argv = ["--quick", "--only", "cusp,co", "--out", str(out), "--figures", str(figures)]
    assert module.main(argv) == 0
    text = out.read_text(encoding="utf-8")
    assert text.startswith("# Work–precision: speed against accuracy")
    assert "at commit `" in text and "load average" in text
    assert "`python scripts/bench_work_precision.py --quick --only cusp,co" in text
    for heading in ("## Summary", "## (a) ", "## (b) ", "## Choosing rtol"):
        assert heading in text
    assert text.count("**Does our front dominate?**") == 2
    # two figures per group, linked from the report, written atomically
    for stem in ("wp-folds", "wp-foldcurve"):
        for axis in ("time", "fevals"):
            png = figures / f"{stem}-{axis}.png"
            assert png.read_bytes().startswith(b"\x89PNG")
            assert f"figures/{png.name})" in text
    assert not list(tmp_path.rglob("*.tmp"))
    # the cusp: ours at each quick rtol locates both folds to rounding; every tool has rows
    rows = _rows(text, "### cusp")
    ours = [r for r in rows if r[0] == "ours"]
    assert [r[1] for r in ours] == [f"rtol = {r:.0e}" for r in module.QUICK_RTOLS]
    assert all(float(r[7]) <= 1e-13 and r[-1] == "ok" for r in ours)
    tools = {r[0].split()[0] for r in rows}
    assert ("contique" in tools) == _installed("contique")
    assert ("pacopy" in tools) == _installed("pacopy", "0.1.")
    assert "SciPy" in tools
    if not _installed("contique"):
        assert "contique is not installed" in text
    # dense output: ours' interpolant against the exact curve, and the other tools' curves
    # against it
    assert "| error: fold | error: curve | error: dense | status |" in text
    assert all(float(r[9]) < 0.1 for r in ours)
    assert "- curve (ours: dense), SciPy" not in text  # (the SciPy loop has no curve)
    # the CO fold curve: the cusp located to 1e-11 at every rtol
    co = _rows(text, "### CO oxidation")
    assert all(float(r[9]) <= 1e-11 for r in co), co
    assert "| cusp: fold |" in text and "| co: cusp |" in text
    summary = text.split("## Summary", 1)[1].split("## (a)", 1)[0]
    assert "| cusp: fold | " in summary and "| cusp: curve (ours: dense) | " in summary
    assert "co:" not in summary  # ours only: nothing to compare
