"""A body from outside the package: registered with one line, run from a scene by ``cusp run``.

The toy body (tests/models/_toy_body.py) has its own levels in closed form; every number
checked here comes from its closed forms (``path_closed_forms``, mpmath at 30 digits), not
from the traced path.
"""

from __future__ import annotations

import csv
import json
import types

import numpy as np
import pytest

from cusp.app import cli
from cusp.app.scene import SceneError, parse_scene
from cusp.models import registry

NAME = "toy-brush"
FACTORY = "tests.models._toy_body:BrushBody"
BODY = dict(mu=0.1, stiffness=0.1, compliance=0.05)
LOADING = dict(F_N0=1000.0, g_A=0.2)
# a0 = √(1000/0.1) = 100 µm, G = μβa0 = 0.5 µm, x_A = 0.4, q_A = 0.6, F_A = 100(1 − 0.36) = 64 N;
# 850 N: F_A < μF'_N = 85 N, C exists; 600 N: F_A ≥ μF'_N = 60 N, no C (force control slides);
# both above the floor F_N0 − F_A/μ = 360 N, and D exists (μβa0 p_B > g_A for p_B > 0.4)
REDUCTIONS = (850.0, 600.0)

SCENE = f"""
[scene]
name = "toy"

[surface]
model = "{NAME}"
mu = 0.1
stiffness = 0.1       # k [N/µm²]
compliance = 0.05     # β

[loading]
normal_load = 1000.0
max_slip = 0.2
reduced_normal_load = [850.0, 600.0]
"""


@pytest.fixture
def toy_registered(toy_body):
    with registry.registered_body(NAME, FACTORY, required=toy_body.REQUIRED) as entry:
        yield entry
    assert NAME not in registry.body_names()


def _close(got: float, want, rtol: float) -> bool:
    return abs(got - float(want)) <= rtol * abs(float(want))


def test_registered_toy_body_runs_from_a_scene_and_matches_its_closed_forms(
    toy_registered, tmp_path, capsys, toy_body
):
    scene = tmp_path / "toy.toml"
    scene.write_text(SCENE, encoding="utf-8")
    out = tmp_path / "out"
    status = cli.main(["run", str(scene), "--out", str(out), "--no-plots", "--quiet"])
    assert status == 0, capsys.readouterr().err
    s = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert [c["reduced_normal_load"]["value"] for c in s["cases"]] == list(REDUCTIONS)
    for case, F_Np in zip(s["cases"], REDUCTIONS):
        pts, energy = toy_body.path_closed_forms(**BODY, **LOADING, F_Np=F_Np)
        for key in "ABCD":
            if pts[key] is None:
                assert case["points"][key] is None, (F_Np, key)
                continue
            for q in ("g_T", "F_T", "F_N", "A_SL"):
                got, want = case["points"][key][q], pts[key][q]
                assert _close(got, want, 1e-10), (F_Np, key, q, got, float(want))
        for kind in ("snap_back", "snap_through"):
            if energy[kind] is None:
                assert case["energy"][kind] is None
            else:
                assert _close(case["energy"][kind], energy[kind], 1e-8), (F_Np, kind)
        assert case["gross_sliding"]["force_control"] == (pts["C"] is None)
    # F_A = μF_N0(1 − q_A²) = 0.1·1000·(1 − 0.6²) = 64 N, also from the toy's loading curve
    assert s["points"]["A"]["F_T"] == pytest.approx(64.0, rel=1e-12)
    assert float(toy_body.BrushBody(**BODY).tangential_force(0.2, 1000.0)) == pytest.approx(64.0)
    # the levels are the toy's own: a = a0 p, c = a0 q with a0 = 100 µm; at A p = 1, q = 0.6
    assert s["points"]["A"]["a"] == pytest.approx(100.0, rel=1e-12)
    assert s["points"]["A"]["c"] == pytest.approx(60.0, rel=1e-10)
    assert s["units"]["a"] == s["units"]["c"] == "µm"
    surface = s["scene"]["surface"]
    assert surface["model"] == NAME
    assert surface["stiffness"] == {"value": 0.1, "unit": "N/µm²"}
    assert surface["compliance"] == {"value": 0.05, "unit": ""}


def test_toy_branch_follows_the_mindlin_deresiewicz_rule_on_every_row(toy_registered, tmp_path):
    # along AB: F_T = F_A − μ(F_N0 − F_N) (toy module docstring), F_A = 64 N; and
    # g_T = G(p − q_A) with p = √(F_N/F_N0), G = 0.5 µm, q_A = 0.6
    scene = tmp_path / "toy.toml"
    scene.write_text(SCENE, encoding="utf-8")
    out = tmp_path / "out"
    assert cli.main(["run", str(scene), "--out", str(out), "--no-plots", "--quiet"]) == 0
    with (out / "branch.csv").open(encoding="utf-8") as fh:
        rows = [r for r in csv.DictReader(fh) if r["leg"] == "AB" and r["case"] == "0"]
    assert len(rows) >= 3
    F_N = np.array([float(r["F_N"]) for r in rows])
    np.testing.assert_allclose([float(r["F_T"]) for r in rows], 64.0 - 0.1 * (1000.0 - F_N), 1e-10)
    g_T = 0.5 * (np.sqrt(F_N / 1000.0) - 0.6)
    np.testing.assert_allclose([float(r["g_T"]) for r in rows], g_T, rtol=1e-10)


def _toy_scene(**lines: str | None) -> str:
    """SCENE with [surface] lines replaced: key -> new line (None drops it)."""
    out = []
    for line in SCENE.splitlines():
        key = line.split("=")[0].strip()
        if key in lines:
            if lines[key] is not None:
                out.append(lines[key])
        else:
            out.append(line)
    return "\n".join(out)


@pytest.mark.parametrize(
    "changes,expect",
    [
        (
            {"stiffness": None},
            "[surface] missing key 'stiffness' for model 'toy-brush'; allowed: toy-brush needs "
            "mu, stiffness, compliance",
        ),
        (
            {"stiffness": "stiffness = -0.1"},
            "[surface] stiffness = -0.1 [N/µm²]; allowed: a finite number > 0 [N/µm²]",
        ),
        (
            {"compliance": "compliance = 1.5"},
            "[surface] compliance = 1.5; allowed: a finite number (0, 1]",
        ),
        (
            {"compliance": "compliance = 0.05\nsigma = 2.0"},
            "[surface] key 'sigma' does not apply to model 'toy-brush'",
        ),
    ],
)
def test_scene_schema_checks_the_toy_parameters(toy_registered, changes, expect):
    with pytest.raises(SceneError) as err:
        parse_scene(_toy_scene(**changes), source="toy.toml")
    assert str(err.value).startswith("toy.toml: ")
    assert expect in str(err.value), str(err.value)


def test_unregistering_removes_the_body_from_scenes(toy_body):
    entry = registry.register_body(NAME, FACTORY, required=toy_body.REQUIRED)
    try:
        assert NAME in registry.body_names(with_path=True)
        assert "stiffness" in registry.surface_keys()
        assert parse_scene(SCENE).surface["stiffness"] == 0.1
    finally:
        assert registry.unregister_body(NAME) is entry
    assert NAME not in registry.body_names()
    assert "stiffness" not in registry.surface_keys()
    with pytest.raises(SceneError, match="unknown key 'compliance'"):
        parse_scene(SCENE)
    with pytest.raises(SceneError, match="model = 'toy-brush' is not a known model"):
        parse_scene(_toy_scene(stiffness=None, compliance=None))


def test_a_factory_that_builds_no_body_is_a_scene_error(tmp_path, capsys, toy_body):
    # the factory returns an object with mu only: exit 2, one line naming the protocol
    with registry.registered_body(
        "not-a-body",
        lambda mu, stiffness, compliance: types.SimpleNamespace(mu=mu),
        required=toy_body.REQUIRED,
    ):
        scene = tmp_path / "bad.toml"
        scene.write_text(SCENE.replace(NAME, "not-a-body"), encoding="utf-8")
        status = cli.main(["run", str(scene), "--out", str(tmp_path / "o"), "--quiet"])
    err = capsys.readouterr().err
    assert status == 2
    assert len(err.strip().splitlines()) == 1
    assert "[surface] body must follow the contact-loss protocol" in err
    assert "got SimpleNamespace, which lacks tangential_force, contact_levels" in err
    assert not (tmp_path / "o").exists()
