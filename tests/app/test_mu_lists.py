"""Scenes with a list of μ: one case per value (the panels of Fig 9), the ``fig9`` figure,
``mu`` in ``branch.csv`` and ``summary.json``, and the refusals (μ and F'_N both lists)."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import pytest

from cusp.app import cli
from cusp.app.scene import SceneError, parse_scene

ROOT = Path(__file__).resolve().parents[2]
FIG6_TEXT = (ROOT / "scenes" / "fig6.toml").read_text(encoding="utf-8")


def _scene(mu: str, loads: str = "850.0", figures: str = "[]") -> str:
    return (
        FIG6_TEXT.replace("mu = 0.1", f"mu = {mu}")
        .replace("reduced_normal_load = 850.0", f"reduced_normal_load = {loads}")
        .replace('figures = ["force-slip", "force-slip-detail"]', f"figures = {figures}")
    )


def test_a_mu_list_gives_one_case_per_value(tmp_path, capsys):
    scene = tmp_path / "m.toml"
    scene.write_text(_scene("[0.1, 0.5]", figures='["fig9", "force-slip"]'), encoding="utf-8")
    out = tmp_path / "o"
    status = cli.main(["run", str(scene), "--out", str(out)])
    stdout, err = capsys.readouterr()
    assert status == 0, err
    assert "mu = 0.1, F'_N = 850 N" in stdout and "mu = 0.5, F'_N = 850 N" in stdout
    s = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert [c["mu"] for c in s["cases"]] == [{"value": 0.1, "unit": ""}, {"value": 0.5, "unit": ""}]
    assert [c["reduced_normal_load"]["value"] for c in s["cases"]] == [850.0, 850.0]
    assert s["scene"]["surface"]["mu"] == {"value": [0.1, 0.5], "unit": ""}
    # the top level is the first case: the Fig 6 path
    assert s["points"]["C"]["g_T"] == pytest.approx(0.52813876635581604949, rel=1e-10)
    # "the snap-back instability is even more severe when higher and higher friction
    # coefficients are considered"
    low, high = (c["energy"]["snap_back"] for c in s["cases"])
    assert high > 5 * low > 0
    with (out / "branch.csv").open(encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert {(r["case"], r["mu"]) for r in rows} == {("0", "0.1"), ("1", "0.5")}
    for name in ("fig9", "force-slip"):
        assert (out / f"{name}.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert b"<svg" in (out / f"{name}.svg").read_bytes()[:2000]


def test_scene_cases_and_echo():
    scene = parse_scene(_scene("[0.1, 0.3, 0.2]"))
    assert scene.mus == (0.1, 0.3, 0.2)
    assert scene.cases == ((0.1, 850.0), (0.3, 850.0), (0.2, 850.0))
    assert scene.echo()["surface"]["mu"] == {"value": [0.1, 0.3, 0.2], "unit": ""}
    single = parse_scene(_scene("0.1", loads="[900.0, 800.0]"))
    assert single.mus == (0.1,) and single.cases == ((0.1, 900.0), (0.1, 800.0))
    assert single.surface["mu"] == 0.1
    one = parse_scene(_scene("[0.1]", loads="[900.0, 800.0]"))  # a list of one value is fine
    assert one.cases == ((0.1, 900.0), (0.1, 800.0))


BAD = {
    "both lists": (
        _scene("[0.1, 0.2]", loads="[850.0, 900.0]"),
        "[surface] mu = [0.1, 0.2] and [loading] reduced_normal_load = [850.0, 900.0] are "
        "both lists; allowed: several values in one of them only (one case per listed value)",
    ),
    "empty list": (_scene("[]"), "[surface] mu = []; allowed: a number or a non-empty list"),
    "bad value": (_scene("[0.1, -0.2]"), "[surface] mu = -0.2; allowed: a finite number > 0"),
    "boolean": (_scene("[0.1, true]"), "[surface] mu = True has the wrong type"),
    "nested": (_scene("[[0.1]]"), "[surface] mu = [0.1] has the wrong type"),
    "too deep for one": (
        _scene("[0.1, 0.9]"),
        "[loading] at [surface] mu = 0.9 reduced_normal_load = 850.0 N is too deep",
    ),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_mu_list_exits_2_naming_the_field(tmp_path, capsys, case):
    text, expect = BAD[case]
    scene = tmp_path / "bad.toml"
    scene.write_text(text, encoding="utf-8")
    status = cli.main(["run", str(scene), "--out", str(tmp_path / "out")])
    stdout, err = capsys.readouterr()
    assert status == 2 and stdout == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    assert expect in lines[0], lines[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]
    if case != "too deep for one":
        with pytest.raises(SceneError):
            parse_scene(text)
