"""Every valid scene ends (issue 27, point 4): exit 0 with the polished points in both
outputs, exit 1 with one line in the scene's terms, or exit 2 naming the input that makes
the model meaningless and what is allowed; a length that looks like the wrong unit gets a
note."""

from __future__ import annotations

import csv
import json
import re
from pathlib import Path

import pytest

from cusp.app import cli
from cusp.app.cases import length_notes
from cusp.app.scene import load_scene

ROOT = Path(__file__).resolve().parents[2]
SCENES = ROOT / "scenes"
#: the sphere of scenes/sphere.toml slides as a whole at g_lim = 5.504687316624741 µm under
#: 1000 N (Sphere.slip_limit; 3(2 - ν)μF_N/(8Ga), Mindlin)
G_LIM = 5.504687316624741


def _scene(tmp_path: Path, base: str, **values: object) -> Path:
    """scenes/BASE.toml with ``key = value`` replaced (keys unique across its sections)."""
    text = (SCENES / f"{base}.toml").read_text(encoding="utf-8")
    for key, value in values.items():
        text, n = re.subn(rf"(?m)^{key}\s*=.*$", f"{key} = {value}", text)
        assert n == 1, key
    path = tmp_path / "scene.toml"
    path.write_text(text, encoding="utf-8")
    return path


def _run(capsys, scene: Path, out: Path, *extra: str) -> tuple[int, str]:
    status = cli.main(["run", str(scene), "--out", str(out), "--no-plots", "--quiet", *extra])
    return status, capsys.readouterr().err


def test_sphere_near_gross_sliding_rows_are_the_polished_points(tmp_path, capsys):
    # max_slip = (1 - 1e-5) g_lim at rtol 1e-8: exit 1 before (the loading leg ran past the
    # gross-sliding fold), and with the fold found, branch.csv's row A was the traced row
    # (c = 0.476092003063915) while summary.json had the polished A (0.476092003066556)
    scene = _scene(tmp_path, "sphere", max_slip=repr((1 - 1e-5) * G_LIM))
    out = tmp_path / "out"
    status, err = _run(capsys, scene, out, "--rtol", "1e-8")
    assert status == 0, err
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    with open(out / "branch.csv", encoding="utf-8") as fh:
        rows = [r for r in csv.DictReader(fh) if r["point"]]
    assert sorted(r["point"] for r in rows) == ["A", "B", "O"]  # no C, no D: gross sliding
    for row in rows:
        point = summary["points"][row["point"]]
        for key in ("g_T", "F_T", "F_N", "A_SL", "a", "c"):
            assert float(row[key]) == point[key], (row["point"], key)
    A = summary["points"]["A"]
    assert A["c"] > 0.0 and A["F_T"] <= 0.1 * A["F_N"]


@pytest.mark.parametrize("share", [1e-3, 1e-8, 1e-12])
def test_sphere_near_gross_sliding_ends(tmp_path, capsys, share):
    scene = _scene(tmp_path, "sphere", max_slip=repr((1 - share) * G_LIM))
    status, err = _run(capsys, scene, tmp_path / "out")
    assert status == 0, err


@pytest.mark.parametrize("sigma", ["1e-6", "2e-6"])
def test_gaussian_roughness_in_metres_ends_with_a_note(tmp_path, capsys, sigma):
    # 2e-6 is 2 µm given in metres: the start did not converge (σ* = 1e-6) or the leg ended
    # with the solver's "lower ds_min ... throw=False" (σ* = 2e-6); now exit 0, and a note
    scene = _scene(tmp_path, "gaussian", sigma=sigma)
    out = tmp_path / "out"
    status, err = _run(capsys, scene, out)
    assert status == 0, err
    messages = json.loads((out / "summary.json").read_text(encoding="utf-8"))["messages"]
    assert any(
        m.startswith(f"[surface] sigma = {float(sigma)!r} µm is more than 10000 times below")
        and "given in metres" in m
        for m in messages
    ), messages


def test_unit_notes_only_for_lengths_far_from_all_others():
    base = load_scene(SCENES / "gaussian.toml")
    assert length_notes(base) == []  # σ* = 2, max_slip = 0.1, radius = 10
    for name in ("fig6", "fig8", "fig9", "sphere"):
        assert length_notes(load_scene(SCENES / f"{name}.toml")) == [], name


def test_unit_note_for_max_slip_in_nanometres(tmp_path):
    scene = load_scene(_scene(tmp_path, "fig6", max_slip="3.4e-4"))
    assert length_notes(scene) == []  # 5900 times below σ* = 2: not yet
    scene = load_scene(_scene(tmp_path, "fig6", max_slip="3.4e5"))
    (note,) = length_notes(scene)
    assert note.startswith("[loading] max_slip = 340000.0 µm is more than 10000 times above")
    assert "if it was given in nanometres, 340000.0 nanometres is 340 µm" in note


@pytest.mark.parametrize("sigma", ["1e50", "1e200"])
def test_empty_reduction_range_is_refused_naming_max_slip(tmp_path, capsys, sigma):
    scene = _scene(tmp_path, "gaussian", sigma=sigma)
    out = tmp_path / "out"
    status, err = _run(capsys, scene, out)
    assert status == 2
    assert err.count("\n") == 1
    assert "[loading] max_slip = 0.1 µm is too small for this body" in err
    assert "allowed: max_slip >= " in err
    assert "1000.0 N <= reduced_normal_load < 1000.0 N" not in err
    assert not out.exists()


def test_gaussian_sigma_beyond_its_float_range_is_refused(tmp_path, capsys):
    # σ*^{3/2} overflows: "unexpected OverflowError in the models ... this is a bug"
    status, err = _run(capsys, _scene(tmp_path, "gaussian", sigma="1e300"), tmp_path / "o")
    assert status == 2
    assert err == (
        f"cusp run: error: {tmp_path / 'scene.toml'}: [surface] sigma = 1e+300 [µm]; allowed: "
        "a finite number (0, 3e+205) [µm]\n"
    )


def test_a_leg_that_cannot_be_traced_is_told_in_the_scene_terms(monkeypatch, tmp_path, capsys):
    # a leg that stops (here: a solver limited to 3 steps) names the leg, where it stopped
    # and why, without the solver's variables or advice
    from cusp.models import contact_loss

    monkeypatch.setattr(
        contact_loss, "DEFAULT_OPTIONS", contact_loss.DEFAULT_OPTIONS.replace(max_steps=3)
    )
    status, err = _run(capsys, SCENES / "fig6.toml", tmp_path / "out")
    assert status == 1
    assert err.startswith(
        "cusp run: numerical failure: the loading leg O-A (the slip raised under normal_load) "
        "stopped at g_T = "
    )
    assert "before reaching g_T = max_slip (point A): it needed more steps" in err
    for word in ("max_steps", "ds_min", "throw", "Raise", "A_SL=", " p=", " q="):
        assert word not in err
