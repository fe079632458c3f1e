"""``cusp run``: scenes end to end through the command line, bad scenes included."""

from __future__ import annotations

import csv
import json
import subprocess
import sys
from pathlib import Path

import pytest

from cusp.app import cli
from cusp.app.run import bundled_scene, write_outputs

ROOT = Path(__file__).resolve().parents[2]
SCENES = ROOT / "scenes"

FIG6_TEXT = (SCENES / "fig6.toml").read_text(encoding="utf-8")


def _run(capsys, *argv) -> tuple[int, str, str]:
    status = cli.main(list(argv))
    out = capsys.readouterr()
    return status, out.out, out.err


def _leftovers(parent: Path) -> list[str]:
    return sorted(p.name for p in parent.iterdir())


# ------------------------------------------------------------------ the Fig 6 scene
def test_fig6_scene_writes_summary_csv_and_figures(tmp_path, capsys):
    out = tmp_path / "fig6"
    status, stdout, err = _run(capsys, "run", str(SCENES / "fig6.toml"), "--out", str(out))
    assert status == 0, err
    assert err == ""
    names = sorted(p.name for p in out.iterdir())
    assert names == [
        "branch.csv",
        "force-slip-detail.png",
        "force-slip-detail.svg",
        "force-slip.png",
        "force-slip.svg",
        "summary.json",
    ]
    assert (out / "force-slip.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert b"<svg" in (out / "force-slip.svg").read_bytes()[:2000]
    s = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    for key in "OABCD":
        assert set(s["points"][key]) >= {"g_T", "F_T", "F_N", "A_SL"}
    # the closed forms (tests/models/test_contact_loss.py checks them to 1e-10 at 50 digits;
    # these literals are the sympy values printed by cusp.verification.contact_loss_path())
    assert s["points"]["C"]["g_T"] == pytest.approx(0.52813876635581604949, rel=1e-10)
    assert s["points"]["D"]["F_T"] == pytest.approx(64.039258064963450428, rel=1e-10)
    assert s["energy"]["snap_back"] == pytest.approx(0.21302894093713884714, rel=1e-8)
    assert s["energy"]["snap_through"] == pytest.approx(1.1402052093236064225, rel=1e-8)
    assert s["energy"]["unit"].startswith("N·µm")
    assert {(f["point"], f["kind"]) for f in s["folds"]} >= {
        ("A", "snap-back"),
        ("A", "snap-through"),
    }
    assert set(s["solver"]) == {"OA", "AB", "BC"}
    assert s["scene"]["surface"]["sigma"] == {"value": 2.0, "unit": "µm"}
    assert s["scene"]["loading"]["reduced_normal_load"]["unit"] == "N"
    assert s["units"]["g_T"] == "µm" and s["units"]["F_T"] == "N"
    with (out / "branch.csv").open(encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    labels = [r["point"] for r in rows if r["point"]]
    assert labels == ["O", "A", "B", "D", "C"]
    assert {r["leg"] for r in rows} == {"OA", "AB", "BC"}
    a_row = next(r for r in rows if r["point"] == "A")
    assert float(a_row["g_T"]) == 0.34
    assert "snap_back" in stdout and "wrote" in stdout
    assert _leftovers(tmp_path) == ["fig6"]  # no staging directory left behind


def test_outputs_are_reproducible(tmp_path, capsys):
    for name in ("a", "b"):
        assert _run(capsys, "run", str(SCENES / "fig6.toml"), "--out", str(tmp_path / name))[0] == 0
    for f in ("summary.json", "branch.csv", "force-slip.svg", "force-slip-detail.svg"):
        assert (tmp_path / "a" / f).read_bytes() == (tmp_path / "b" / f).read_bytes(), f


def test_rerun_into_an_existing_directory_replaces_the_files(tmp_path, capsys):
    out = tmp_path / "o"
    out.mkdir()
    (out / "summary.json").write_text("old")
    (out / "notes.txt").write_text("mine")
    assert _run(capsys, "run", str(SCENES / "fig7.toml"), "--out", str(out), "--quiet")[0] == 0
    assert json.loads((out / "summary.json").read_text())["points"]["A"]["g_T"] == 0.34
    assert (out / "notes.txt").read_text() == "mine"  # files we do not write are kept
    assert _leftovers(tmp_path) == ["o"]


def test_fig8_scene_has_all_reductions_and_gross_sliding(tmp_path, capsys):
    out = tmp_path / "fig8"
    assert (
        _run(capsys, "run", str(SCENES / "fig8.toml"), "--out", str(out), "--no-plots", "--quiet")[
            0
        ]
        == 0
    )
    s = json.loads((out / "summary.json").read_text())
    loads = [c["reduced_normal_load"]["value"] for c in s["cases"]]
    assert loads == [900.0, 800.0, 600.0, 400.0]
    for case in s["cases"]:
        # no C below F_A/mu = 753.40 N (F_A = 75.3403036 N, the sympy value of the Fig 6 test)
        deep = case["reduced_normal_load"]["value"] < 753.4
        assert (case["points"]["C"] is None) == deep
        assert (case["energy"]["snap_through"] is None) == deep
        assert case["gross_sliding"]["force_control"] == deep
        assert case["energy"]["snap_back"] > 0
    # snap-back energy grows with the depth of the reduction
    e = [c["energy"]["snap_back"] for c in s["cases"]]
    assert e == sorted(e)
    text = (out / "summary.json").read_text()
    assert "NaN" not in text and "Infinity" not in text
    assert not list(out.glob("*.png"))


def test_no_plots_loads_neither_matplotlib_nor_gaussian_code(tmp_path):
    code = (
        "import sys; from cusp.app import cli; "
        f"rc = cli.main(['run', {str(SCENES / 'fig6.toml')!r}, '--out', "
        f"{str(tmp_path / 'o')!r}, '--no-plots', '--quiet']); "
        "heavy = [m for m in ('matplotlib', 'sympy', 'cusp.models.gaussian', 'cusp.models.gw', "
        "'cusp.models._quadrature', 'cusp.models.density', 'cusp.app.figures') "
        "if m in sys.modules]; "
        "print(rc, heavy)"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True
    ).stdout.strip()
    assert out == "0 []"


def test_cusp_run_without_arguments_runs_the_bundled_fig6_scene(tmp_path):
    assert bundled_scene().read_text(encoding="utf-8") == FIG6_TEXT
    proc = subprocess.run(
        [
            sys.executable,
            "-c",
            "import sys; from cusp.app import cli; sys.exit(cli.main(['run', '--no-plots']))",
        ],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"},
    )
    assert proc.returncode == 0, proc.stderr
    s = json.loads((tmp_path / "cusp-out" / "fig6" / "summary.json").read_text())
    assert s["scene"]["name"] == "fig6"


def test_cusp_without_a_subcommand_is_cusp_run(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    status, stdout, _ = _run(capsys)
    assert status == 0
    assert "scene fig6 (scenes/fig6.toml (bundled))" in stdout
    out = tmp_path / "cusp-out" / "fig6"
    assert sorted(p.suffix for p in out.iterdir()) == [
        ".csv",
        ".json",
        ".png",
        ".png",
        ".svg",
        ".svg",
    ]


# ------------------------------------------------------------------ other bodies
@pytest.mark.parametrize("name", ["gaussian", "sphere"])
def test_gaussian_and_sphere_scenes_match_mpmath(tmp_path, capsys, name):
    from cusp.verification import oracles

    out = tmp_path / name
    status, _, err = _run(
        capsys, "run", str(SCENES / f"{name}.toml"), "--out", str(out), "--no-plots", "--quiet"
    )
    assert status == 0, err
    s = json.loads((out / "summary.json").read_text())
    sc = {k: v["value"] for k, v in s["scene"]["surface"].items() if k != "model"}
    ld = {k: v["value"] for k, v in s["scene"]["loading"].items()}
    args = dict(F_N0=ld["normal_load"], g_A=ld["max_slip"], F_Np=ld["reduced_normal_load"][0])
    ref_fn = oracles.gaussian_path if name == "gaussian" else oracles.sphere_path
    pts, energy = ref_fn(**sc, **args)
    for key in "ABCD":
        for q in ("g_T", "F_T", "F_N", "A_SL"):
            assert s["points"][key][q] == pytest.approx(float(pts[key][q]), rel=1e-10)
    for kind in ("snap_back", "snap_through"):
        assert s["energy"][kind] == pytest.approx(float(energy[kind]), rel=1e-8)


# ------------------------------------------------------------------ bad scenes
def _scene(**changes) -> str:
    """The Fig 6 scene with lines replaced: key -> new line (None drops the line)."""
    lines = []
    for line in FIG6_TEXT.splitlines():
        key = line.split("=")[0].strip()
        if key in changes:
            if changes[key] is not None:
                lines.append(changes[key])
        else:
            lines.append(line)
    return "\n".join(lines) + "\n"


BAD = {
    "malformed": ("[surface\nmodel = 'x'", "malformed TOML"),
    "empty": ("", "empty scene"),
    "blank": ("  \n\n", "empty scene"),
    "unknown model": (_scene(model='model = "rough-fractal"'), "model = 'rough-fractal'"),
    "cylinder": (_scene(model='model = "cylinder"'), "no compliance law"),
    "flat": (_scene(model='model = "flat"'), "no compliance law"),
    "unknown key": (_scene(nu="nu = 0.3\nnu_typo = 1.0"), "unknown key 'nu_typo'"),
    "unknown section": (FIG6_TEXT + "\n[extra]\na = 1\n", "unknown section [extra]"),
    "missing field": (_scene(max_slip=None), "missing key 'max_slip'"),
    "missing section": (
        "[surface]\nmodel = 'rough-exponential'\nsigma = 2.0\nnu = 0.3\nmu = 0.1\n",
        "missing section [loading]",
    ),
    "wrong type": (_scene(sigma='sigma = "two"'), "sigma = 'two' has the wrong type"),
    "boolean": (_scene(mu="mu = true"), "mu = True has the wrong type"),
    "nan": (_scene(sigma="sigma = nan"), "sigma = nan"),
    "inf": (_scene(normal_load="normal_load = inf"), "normal_load = inf"),
    "sigma <= 0": (_scene(sigma="sigma = 0.0"), "[surface] sigma = 0.0"),
    "nu > 0.5": (_scene(nu="nu = 0.6"), "[surface] nu = 0.6"),
    "reduced above": (
        _scene(reduced_normal_load="reduced_normal_load = 1200.0"),
        "reduced_normal_load = 1200.0 N",
    ),
    "too deep": (
        _scene(reduced_normal_load="reduced_normal_load = 100.0"),
        "[loading] reduced_normal_load = 100.0 N is too deep",
    ),
    "load scale half given": (_scene(nu="nu = 0.3\nE = 0.2"), "the load scale needs all"),
    "key of another model": (_scene(nu="nu = 0.3\nshape = 2.0"), "does not apply"),
    "bad figure": (FIG6_TEXT.replace('"force-slip-detail"', '"fig99"'), "figures contains 'fig99'"),
    "bad reading": (FIG6_TEXT + '\n[options]\narea_reading = "other"\n', "area_reading"),
    "bad solver": (FIG6_TEXT + "\n[solver]\nds_max = -1.0\n", "[solver] ds_max = -1.0"),
    "section as value": (
        "surface = 1\n" + FIG6_TEXT.replace("[surface]", "[surfacex]"),
        "surface = 1 must be a [surface] table",
    ),
    "code": ("import os\nos.system('touch hacked')\n", "malformed TOML"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_scene_exits_2_with_one_line_and_no_output(tmp_path, capsys, case):
    text, expect = BAD[case]
    scene = tmp_path / "bad.toml"
    scene.write_text(text, encoding="utf-8")
    out = tmp_path / "out"
    status, stdout, err = _run(capsys, "run", str(scene), "--out", str(out))
    assert status == 2
    assert stdout == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert "Traceback" not in err
    assert lines[0].startswith("cusp run: error: ")
    assert expect in lines[0], lines[0]
    assert _leftovers(tmp_path) == ["bad.toml"]  # nothing written, not even a staging dir


def test_binary_and_missing_scene_files(tmp_path, capsys):
    binary = tmp_path / "b.toml"
    binary.write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00")
    status, _, err = _run(capsys, "run", str(binary), "--out", str(tmp_path / "o"))
    assert status == 2 and "binary file" in err and len(err.strip().splitlines()) == 1
    latin = tmp_path / "l.toml"
    latin.write_bytes("[surface]\nmodel = 'caf\xe9'\n".encode("latin-1"))
    status, _, err = _run(capsys, "run", str(latin), "--out", str(tmp_path / "o"))
    assert status == 2 and "not UTF-8" in err
    status, _, err = _run(capsys, "run", str(tmp_path / "nope.toml"))
    assert status == 2 and "no such scene file" in err
    assert not (tmp_path / "o").exists()


def test_bad_scene_through_the_console_script_has_no_traceback(tmp_path):
    scene = tmp_path / "bad.toml"
    scene.write_text(_scene(nu="nu = 0.7"), encoding="utf-8")
    proc = subprocess.run(
        [sys.executable, "-m", "cusp.app.cli", "run", str(scene)],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert proc.returncode == 2
    assert proc.stderr.count("\n") == 1 and "Traceback" not in proc.stderr
    assert "[surface] nu = 0.7" in proc.stderr and "(-1, 0.5]" in proc.stderr


def test_failed_write_leaves_nothing(tmp_path):
    files = {"summary.json": b"1", "branch.csv": object()}  # the second write fails
    with pytest.raises(TypeError):
        write_outputs(tmp_path / "out", files)  # type: ignore[arg-type]
    assert _leftovers(tmp_path) == []


def test_numerical_failure_exits_1_with_one_line(tmp_path, capsys, monkeypatch):
    from cusp.models import contact_loss

    def fail(self, options=None):
        raise contact_loss.PathError("the contact-loss leg AB ended with status 'max_steps'")

    monkeypatch.setattr(contact_loss.ContactLoss, "run", fail)
    status, stdout, err = _run(
        capsys, "run", str(SCENES / "fig6.toml"), "--out", str(tmp_path / "o")
    )
    assert status == 1 and stdout == ""
    assert err.strip().splitlines() == [
        "cusp run: numerical failure: the contact-loss leg AB ended with status 'max_steps'"
    ]
    assert not (tmp_path / "o").exists()
