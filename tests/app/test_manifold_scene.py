"""``cusp run`` on scenes with a list of μ and a ``[manifold]`` section: the bundled Fig 9
scene by name, ``loci.csv`` and the ``manifold`` entry of ``summary.json``, the loci figures,
and the refusals of bad [manifold] fields."""

from __future__ import annotations

import csv
import json
import math
from pathlib import Path

import pytest

from cusp.app import cli
from cusp.app.scene import parse_scene

ROOT = Path(__file__).resolve().parents[2]
FIG6_TEXT = (ROOT / "scenes" / "fig6.toml").read_text(encoding="utf-8")
COLUMNS = [
    "mu",
    "reduced_normal_load",
    "g_A",
    "F_A",
    "g_B",
    "F_B",
    "g_C",
    "F_C",
    "g_D",
    "F_D",
    "A_SL_A",
    "A_SL_B",
    "snap_back_energy",
    "snap_through_energy",
    "event",
]
# the events of the Fig 9 scene (exponential heights, F'_N = 850 N): F_A = μF'_N at μ_C and
# F'_T = 0 at μ_0, with F_A = μF_N0(1 − exp(−g_A/(λμ))) (the closed forms that sympy solves
# in cusp.verification.manifold_events, checked against the loci in tests/models; typed here
# to keep this test free of sympy's ~10 s)
LAM = 2.0 * (2.0 - 0.3) / (2.0 * (1.0 - 0.3))
MU_C = 0.34 / (LAM * math.log(1000.0 / 150.0))
MU_0 = 0.34 / (LAM * math.log(1000.0 / 850.0))


def _run(capsys, *argv) -> tuple[int, str, str]:
    status = cli.main([str(a) for a in argv])
    out = capsys.readouterr()
    return status, out.out, out.err


def _read_loci(path: Path) -> tuple[str, list[str], list[dict[str, str]]]:
    lines = path.read_text(encoding="utf-8").splitlines()
    rows = list(csv.reader(lines[1:]))
    return lines[0], rows[0], [dict(zip(rows[0], r)) for r in rows[1:]]


def _manifold_scene(extra: str = "", manifold: str | None = None, **lines: str) -> str:
    """The Fig 6 scene with lines replaced (key -> line) and a [manifold] section."""
    text = "\n".join(lines.get(line.split("=")[0].strip(), line) for line in FIG6_TEXT.splitlines())
    text = text.replace('figures = ["force-slip", "force-slip-detail"]', "figures = []")
    section = 'parameter = "mu"\nrange = [0.05, 0.3]' if manifold is None else manifold
    return f"{text}\n[manifold]\n{section}\n{extra}"


# ------------------------------------------------------------------ the bundled Fig 9 scene
def test_fig9_by_name_writes_loci_csv_and_the_manifold_summary(tmp_path, capsys):
    out = tmp_path / "f9"
    status, stdout, err = _run(capsys, "run", "fig9", "--out", out, "--no-plots")
    assert status == 0, err
    assert "scene fig9 (scenes/fig9.toml (bundled))" in stdout
    assert sorted(p.name for p in out.iterdir()) == ["branch.csv", "loci.csv", "summary.json"]
    units, header, rows = _read_loci(out / "loci.csv")
    assert header == COLUMNS
    assert units.startswith("# units: ")
    for col, unit in (("mu", "[1]"), ("F_A", "[N]"), ("g_C", "[µm]"), ("snap_back_energy", "[N·")):
        assert f"{col} {unit}" in units
    traced = [r for r in rows if not r["event"]]
    events = {r["event"]: r for r in rows if r["event"]}
    assert len(traced) > 20 and set(events) == {"C boundary", "F'_T = 0"}
    assert float(events["C boundary"]["mu"]) == pytest.approx(MU_C, rel=1e-10)
    assert float(events["F'_T = 0"]["mu"]) == pytest.approx(MU_0, rel=1e-10)
    assert MU_C == pytest.approx(0.0738, abs=1e-4) and MU_0 == pytest.approx(0.8614, abs=1e-4)
    mus = [float(r["mu"]) for r in rows]
    assert mus == sorted(mus) and mus[0] == 0.01
    for r in traced:
        assert r["reduced_normal_load"] == "850.0"
        assert r["g_A"] == "0.34"  # A is where the slip reaches g_A: exact
        # no C below the C boundary: the cells are empty, not NaN (nor within 1e-6 above
        # it, where rounding decides whether C exists: cusp.models.manifold.C_MARGIN; nor at
        # the end, where the locus without C may end a rounding beyond the one with C)
        mu = float(r["mu"])
        if mu < MU_C or MU_C * (1.0 + 1e-5) < mu < MU_0 * (1.0 - 1e-12):
            assert (r["g_C"] == "" and r["F_C"] == "") == (mu < MU_C), r
        for cell in r.values():
            assert cell.lower() not in ("nan", "inf")
            if cell and cell[0] not in "CF":
                assert repr(float(cell)) == cell  # written with repr: round-trip
    s = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    man = s["manifold"]
    assert man["parameter"] == "mu"
    assert man["range"] == {"value": [0.01, 1.0], "unit": ""}
    assert man["start"]["mu"]["value"] == 0.1
    assert man["points"] == len(traced)
    by_name = {e["event"]: e["values"] for e in man["events"]}
    assert by_name["C boundary"]["mu"] == float(events["C boundary"]["mu"])
    assert by_name["C boundary"]["g_C"] is None  # C's slip diverges there
    assert by_name["F'_T = 0"]["F_B"] == pytest.approx(0.0, abs=1e-9)
    assert man["units"]["F_A"] == "N" and man["units"]["snap_back_energy"].startswith("N·")
    assert man["messages"] and all(isinstance(m, str) for m in man["messages"])
    # the two panels: one case per listed μ; the higher μ has the larger snap-back
    assert [c["mu"]["value"] for c in s["cases"]] == [0.1, 0.5]
    low, high = (c["energy"]["snap_back"] for c in s["cases"])
    assert high > low > 0
    assert s["scene"]["manifold"]["parameter"] == "mu"
    with (out / "branch.csv").open(encoding="utf-8") as fh:
        assert {r["mu"] for r in csv.DictReader(fh)} == {"0.1", "0.5"}


def test_a_manifold_scene_renders_its_figures(tmp_path, capsys, monkeypatch):
    from cusp.app import manifold_figures

    monkeypatch.setattr(manifold_figures, "SURFACE_PATHS", 3)
    scene = tmp_path / "m.toml"
    scene.write_text(
        _manifold_scene(mu="mu = [0.1, 0.2]").replace("figures = []\n", ""), encoding="utf-8"
    )
    out = tmp_path / "o"
    status, _, err = _run(capsys, "run", scene, "--out", out, "--quiet")
    assert status == 0, err
    names = {p.name for p in out.iterdir()}
    for fig in ("fig9", "manifold-surface", "loci-control-planes", "loci-energies", "regime-map"):
        assert {f"{fig}.png", f"{fig}.svg"} <= names, fig
        assert (out / f"{fig}.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert {"loci.csv", "summary.json", "branch.csv"} <= names


def test_a_load_locus_starts_from_the_first_listed_load_in_its_range(tmp_path, capsys):
    scene = tmp_path / "m.toml"
    scene.write_text(
        _manifold_scene(
            manifold='parameter = "reduced_normal_load"\nrange = [700.0, 1000.0]',
            reduced_normal_load="reduced_normal_load = [600.0, 900.0, 800.0]",
        ),
        encoding="utf-8",
    )
    out = tmp_path / "o"
    status, _, err = _run(capsys, "run", scene, "--out", out, "--quiet")
    assert status == 0, err
    man = json.loads((out / "summary.json").read_text())["manifold"]
    assert man["start"]["reduced_normal_load"]["value"] == 900.0
    assert man["range"]["unit"] == "N"
    _, header, rows = _read_loci(out / "loci.csv")
    assert header == COLUMNS
    loads = [float(r["reduced_normal_load"]) for r in rows]
    assert loads == sorted(loads) and 700.0 <= loads[0] and loads[-1] <= 1000.0
    assert {r["mu"] for r in rows} == {"0.1"}
    # F_A/μ = 753.4 N: below it no C (its cells empty), above it C exists
    assert any(r["event"] == "C boundary" for r in rows)
    for r in rows:
        load = float(r["reduced_normal_load"])
        if abs(load - 753.403) > 0.01:
            assert (r["g_C"] == "") == (load < 753.403), r


# ------------------------------------------------------------------ refusals
BAD = {
    "unknown parameter": (
        _manifold_scene(manifold='parameter = "sigma"\nrange = [0.05, 0.3]'),
        "[manifold] parameter = 'sigma'; allowed: 'mu' or 'reduced_normal_load'",
    ),
    "parameter not a string": (
        _manifold_scene(manifold="parameter = 1\nrange = [0.05, 0.3]"),
        "[manifold] parameter = 1 has the wrong type",
    ),
    "range of three": (
        _manifold_scene(manifold='parameter = "mu"\nrange = [0.05, 0.2, 0.3]'),
        "[manifold] range = [0.05, 0.2, 0.3]; allowed: two finite numbers",
    ),
    "range decreasing": (
        _manifold_scene(manifold='parameter = "mu"\nrange = [0.3, 0.05]'),
        "[manifold] range = [0.3, 0.05]; allowed: two finite numbers [low, high], 0 < low",
    ),
    "range not positive": (
        _manifold_scene(manifold='parameter = "mu"\nrange = [0.0, 0.3]'),
        "[manifold] range = [0.0, 0.3]",
    ),
    "range not numbers": (
        _manifold_scene(manifold='parameter = "mu"\nrange = ["a", 0.3]'),
        "[manifold] range = ['a', 0.3]",
    ),
    "range a number": (
        _manifold_scene(manifold='parameter = "mu"\nrange = 0.3'),
        "[manifold] range = 0.3",
    ),
    "range infinite": (
        _manifold_scene(manifold='parameter = "mu"\nrange = [0.05, inf]'),
        "[manifold] range = [0.05, inf]",
    ),
    "range above normal_load": (
        _manifold_scene(manifold='parameter = "reduced_normal_load"\nrange = [500.0, 1200.0]'),
        "[manifold] range = [500.0, 1200.0] [N]; allowed: two finite numbers [low, high], "
        "0 < low < high <= normal_load = 1000.0 N",
    ),
    "range misses mu": (
        _manifold_scene(manifold='parameter = "mu"\nrange = [0.2, 0.3]'),
        "[manifold] range = [0.2, 0.3] does not hold [surface] mu = 0.1",
    ),
    "range misses every listed mu": (
        _manifold_scene(manifold='parameter = "mu"\nrange = [0.2, 0.3]', mu="mu = [0.1, 0.5]"),
        "does not hold [surface] mu = [0.1, 0.5]; allowed: a range holding a listed value",
    ),
    "range misses the load": (
        _manifold_scene(manifold='parameter = "reduced_normal_load"\nrange = [100.0, 500.0]'),
        "does not hold [loading] reduced_normal_load = 850.0",
    ),
    "extra key": (
        _manifold_scene(manifold='parameter = "mu"\nrange = [0.05, 0.3]\nsteps = 10'),
        "[manifold] unknown key 'steps'; allowed: keys of [manifold] are parameter, range",
    ),
    "missing range": (
        _manifold_scene(manifold='parameter = "mu"'),
        "[manifold] missing key 'range'",
    ),
    "loci figure without [manifold]": (
        FIG6_TEXT.replace('"force-slip-detail"', '"regime-map"'),
        "[output] figures contains 'regime-map' but the scene has no [manifold] section",
    ),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_manifold_scene_exits_2_naming_the_field(tmp_path, capsys, case):
    text, expect = BAD[case]
    scene = tmp_path / "bad.toml"
    scene.write_text(text, encoding="utf-8")
    status, stdout, err = _run(capsys, "run", scene, "--out", tmp_path / "out")
    assert status == 2 and stdout == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err, err
    assert expect in lines[0], lines[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.toml"]


def test_manifold_scene_defaults_to_the_loci_figures():
    text = _manifold_scene().replace("[output]\nfigures = []\n", "")
    scene = parse_scene(text)
    assert scene.figures == (
        "fig9",
        "manifold-surface",
        "loci-control-planes",
        "loci-energies",
        "regime-map",
    )
    assert scene.manifold == {"parameter": "mu", "range": (0.05, 0.3), "start": (0.1, 850.0)}


def test_a_manifold_scene_without_plots_loads_neither_matplotlib_nor_sympy(tmp_path):
    import subprocess
    import sys

    code = (
        "import sys; from cusp.app import cli; "
        f"rc = cli.main(['run', 'fig9', '--out', {str(tmp_path / 'o')!r}, '--no-plots', "
        "'--quiet']); "
        "print(rc, [m for m in ('matplotlib', 'sympy', 'cusp.app.manifold_figures', "
        "'cusp.models.regimes') if m in sys.modules])"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True
    ).stdout.strip()
    assert out == "0 []"
    assert (tmp_path / "o" / "loci.csv").exists()
