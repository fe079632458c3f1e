"""docs/gallery/X holds what ``cusp run scenes/X.toml --out docs/gallery/X`` writes today
(docs/contact_loss.md says so): the numbers of every bundled scene's summary.json and CSV
files against a fresh run. fig9's loci went stale for a session once, unnoticed.

Numbers are compared to 1e-9 relative (another numpy or scipy may move last bits; a change of
the computation moves more), text with its numbers masked; the figures are not compared
(their bytes depend on matplotlib's version): regenerate them with the data."""

from __future__ import annotations

import csv
import json
import math
import re
from pathlib import Path

import pytest

from cusp.app import cli

ROOT = Path(__file__).resolve().parents[2]
GALLERY = ROOT / "docs" / "gallery"
SCENES = sorted(p.name for p in GALLERY.iterdir() if (ROOT / "scenes" / f"{p.name}.toml").exists())
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
RTOL = 1e-9

REGENERATE = "regenerate: cusp run scenes/{0}.toml --out docs/gallery/{0}"


def _same(a, b, where: str) -> None:
    if isinstance(a, dict) and isinstance(b, dict):
        assert sorted(a) == sorted(b), where
        for k in a:
            _same(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, list) and isinstance(b, list):
        assert len(a) == len(b), f"{where}: {len(a)} items, now {len(b)}"
        for i, (x, y) in enumerate(zip(a, b)):
            _same(x, y, f"{where}[{i}]")
    elif isinstance(a, str) and isinstance(b, str):
        assert NUMBER.sub("#", a) == NUMBER.sub("#", b), f"{where}: {a!r} now {b!r}"
        for x, y in zip(NUMBER.findall(a), NUMBER.findall(b)):
            _close(float(x), float(y), where)
    elif isinstance(a, (int, float)) and isinstance(b, (int, float)):
        _close(float(a), float(b), where)
    else:
        assert a == b, f"{where}: {a!r} now {b!r}"


def _close(x: float, y: float, where: str) -> None:
    if math.isnan(x) or math.isnan(y):
        assert math.isnan(x) and math.isnan(y), f"{where}: {x} now {y}"
    else:
        assert y == pytest.approx(x, rel=RTOL, abs=1e-300), f"{where}: {x!r} now {y!r}"


def _csv(path: Path) -> list[list[str]]:
    with path.open(encoding="utf-8", newline="") as f:
        return [row for row in csv.reader(f)]


@pytest.mark.parametrize("scene", SCENES)
def test_gallery_holds_what_cusp_run_writes_today(scene, tmp_path, capsys, monkeypatch):
    assert len(SCENES) >= 6  # (fig6-fig9, gaussian, sphere)
    out = tmp_path / scene
    monkeypatch.chdir(ROOT)  # (summary.json names the scene as the command was given it)
    assert cli.main(["run", f"scenes/{scene}.toml", "--out", str(out), "--no-plots"]) == 0
    capsys.readouterr()
    kept = GALLERY / scene
    fresh = sorted(p.name for p in out.iterdir())
    data = sorted(p.name for p in kept.iterdir() if p.suffix in (".csv", ".json"))
    assert fresh == data, REGENERATE.format(scene)
    for name in fresh:
        if name.endswith(".json"):
            a = json.loads((kept / name).read_text(encoding="utf-8"))
            b = json.loads((out / name).read_text(encoding="utf-8"))
        else:
            a, b = _csv(kept / name), _csv(out / name)
        _same(a, b, f"{scene}/{name} ({REGENERATE.format(scene)})")
