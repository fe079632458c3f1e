"""The accuracy knob in the application: ``[solver] rtol`` in a scene and ``cusp run --rtol``
(checked like the scene's other numbers, recorded in summary.json, followed by the paths and
the loci)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from cusp.app import cli
from cusp.app.cases import loci_options, solver_options
from cusp.app.scene import SceneError, parse_scene

ROOT = Path(__file__).resolve().parents[2]
FIG6 = (ROOT / "scenes" / "fig6.toml").read_text(encoding="utf-8")

# Fig 6's points and energies: the sympy closed forms of cusp.verification.contact_loss_path()
# at σ* = 2 µm, ν = 0.3, μ = 0.1, F_N0 = 1000 N, g_A = 0.34 µm, F'_N = 850 N, evaluated by
# verification.exact_value at 20 digits (tests/models/test_contact_loss.py compares the
# default run with them to 1e-10, the energies to 1e-8), cut to 12 digits here
CLOSED = {
    "A": {"g_T": 0.34, "F_T": 75.3403036058, "F_N": 1000.0, "A_SL": 0.408167286540},
    "B": {"g_T": 0.300531117122, "F_T": 60.3403036058, "F_N": 850.0, "A_SL": 0.500875248397},
    "C": {"g_T": 0.528138766356, "F_T": 75.3403036058, "F_N": 850.0, "A_SL": 0.789217267620},
    "D": {"g_T": 0.34, "F_T": 64.0392580650, "F_N": 850.0, "A_SL": 0.558167286540},
}
ENERGY = {"snap_back": 0.213028940937, "snap_through": 1.14020520932}


def _solver(lines: str) -> str:
    return f"{FIG6}\n[solver]\n{lines}\n"


def _run(capsys, *argv) -> tuple[int, str, str]:
    status = cli.main([str(a) for a in argv])
    out = capsys.readouterr()
    return status, out.out, out.err


# ------------------------------------------------------------------ the scene field
def test_scene_rtol_sets_the_paths_tolerances():
    scene = parse_scene(_solver("rtol = 1e-2"))
    assert scene.solver == {"rtol": 1e-2}
    assert scene.echo()["solver"] == {"rtol": {"value": 1e-2, "unit": ""}}
    o = solver_options(scene)
    # options.py: step_tol = (rtol/1000)² = 1e-10, tol = 100·step_tol (at most 1e-10),
    # quad_tol = step_tol/10
    assert (o.rtol, o.step_tol, o.tol, o.quad_tol) == (1e-2, 1e-10, 1e-10, 1e-11)
    assert (o.ds, o.ds_max) == (0.02, 0.05)  # the path's own steps are kept
    # an explicit tol overrides what rtol sets (step_tol still follows rtol)
    given = solver_options(parse_scene(_solver("rtol = 1e-2\ntol = 1e-12")))
    assert (given.tol, given.step_tol) == (1e-12, 1e-10)


def test_a_scene_without_rtol_keeps_the_defaults():
    from cusp.models.contact_loss import DEFAULT_OPTIONS
    from cusp.models.manifold import DEFAULT_OPTIONS as LOCI

    scene = parse_scene(FIG6)
    assert "rtol" not in scene.solver
    assert solver_options(scene) is DEFAULT_OPTIONS and loci_options(scene) is LOCI
    assert solver_options(scene).rtol == 1e-3  # ContinuationOptions' default
    # the loci follow the scene's rtol at their own steps (ds_max 0.1, not the paths' 0.05)
    o = loci_options(parse_scene(_solver("rtol = 1e-2\nds_max = 0.01")))
    assert (o.rtol, o.ds_max) == (1e-2, 0.1)
    assert loci_options(parse_scene(_solver("rtol = 1e-3"))) == LOCI  # the default, given


@pytest.mark.parametrize(
    "line, expect",
    [
        ('rtol = "1e-3"', "[solver] rtol = '1e-3' has the wrong type (str)"),
        ("rtol = true", "[solver] rtol = True has the wrong type (bool)"),
        ("rtol = 0.5", "[solver] rtol = 0.5; allowed: a finite number [1e-13, 0.01]"),
        ("rtol = 1e-14", "[solver] rtol = 1e-14; allowed: a finite number [1e-13, 0.01]"),
        ("rtol = 0", "[solver] rtol = 0; allowed: a finite number [1e-13, 0.01]"),
        ("rtol = -1e-3", "[solver] rtol = -0.001; allowed"),
        ("rtol = nan", "[solver] rtol = nan; allowed"),
        ("rtol = inf", "[solver] rtol = inf; allowed"),
    ],
)
def test_a_bad_scene_rtol_is_refused_naming_the_field_value_and_range(line, expect):
    with pytest.raises(SceneError) as info:
        parse_scene(_solver(line), source="s.toml")
    assert str(info.value).startswith("s.toml: ") and expect in str(info.value)


@pytest.mark.parametrize("value", [1e-13, 0.01])
def test_the_bounds_of_rtol_are_allowed(value):
    from cusp.continuation import RTOL_MIN

    assert RTOL_MIN == 1e-13  # the scene's range is the options' (not imported by scene.py)
    assert solver_options(parse_scene(_solver(f"rtol = {value!r}"))).rtol == value


# ------------------------------------------------------------------ the command line
def _summary(out: Path) -> dict:
    return json.loads((out / "summary.json").read_text(encoding="utf-8"))


def _check_fig6(s: dict, rtol: float) -> None:
    """Points A-D and the energies within 10·rtol (relative) of the closed forms."""
    for key, want in CLOSED.items():
        for q, value in want.items():
            assert s["points"][key][q] == pytest.approx(value, rel=10 * rtol), (key, q)
    for kind, value in ENERGY.items():
        assert s["energy"][kind] == pytest.approx(value, rel=10 * rtol), kind


def test_cli_rtol_is_used_and_recorded(tmp_path, capsys):
    out = tmp_path / "o"
    status, _, err = _run(capsys, "run", "fig6", "--rtol", "1e-2", "--no-plots", "--out", out)
    assert (status, err) == (0, "")
    s = _summary(out)
    # options.py at rtol = 1e-2: step_tol = locate_tol = (rtol/1000)², tol = 100·step_tol
    # within [1e-12, 1e-10], quad_tol = step_tol/10
    assert s["accuracy"] == {
        "rtol": 1e-2,
        "tol": 1e-10,
        "step_tol": 1e-10,
        "locate_tol": 1e-10,
        "quad_tol": 1e-11,
    }
    assert s["scene"]["solver"] == {"rtol": {"value": 1e-2, "unit": ""}}
    _check_fig6(s, 1e-2)


def test_cli_rtol_overrides_the_scenes(tmp_path, capsys):
    scene = tmp_path / "s.toml"
    scene.write_text(_solver("rtol = 1e-2\ntol = 1e-9"), encoding="utf-8")
    out = tmp_path / "o"
    status, _, err = _run(capsys, "run", scene, "--rtol", "1e-4", "--no-plots", "--out", out)
    assert (status, err) == (0, "")
    s = _summary(out)
    # options.py: step_tol = (1e-4/1000)² = 1e-14; the scene's tol stays (given explicitly)
    assert (s["accuracy"]["rtol"], s["accuracy"]["step_tol"], s["accuracy"]["tol"]) == (
        1e-4,
        1e-14,
        1e-9,
    )
    assert s["scene"]["solver"]["rtol"]["value"] == 1e-4
    _check_fig6(s, 1e-4)


def test_default_run_records_the_default_accuracy(tmp_path, capsys):
    out = tmp_path / "o"
    assert _run(capsys, "run", "fig6", "--no-plots", "--quiet", "--out", out)[0] == 0
    s = _summary(out)
    # the defaults of ContinuationOptions (rtol 1e-3): the tolerances the solver always used
    assert s["accuracy"] == {
        "rtol": 1e-3,
        "tol": 1e-10,
        "step_tol": 1e-12,
        "locate_tol": 1e-12,
        "quad_tol": 1e-13,
    }
    assert "solver" not in s["scene"] or "rtol" not in s["scene"]["solver"]


@pytest.mark.parametrize(
    "value, expect",
    [
        ("abc", "--rtol = 'abc' is not a number; allowed: a finite number [1e-13, 0.01]"),
        ("0.5", "--rtol = '0.5'; allowed: a finite number [1e-13, 0.01]"),
        ("1e-14", "--rtol = '1e-14'; allowed"),
        ("nan", "--rtol = 'nan'; allowed"),
        ("-inf", "--rtol = '-inf'; allowed"),
        ("", "--rtol = '' is not a number"),
    ],
)
def test_a_bad_cli_rtol_exits_2_naming_the_flag(tmp_path, capsys, value, expect):
    status, stdout, err = _run(capsys, "run", "fig6", f"--rtol={value}", "--out", tmp_path / "o")
    assert status == 2 and stdout == ""
    assert err.count("\n") == 1 and err.startswith("cusp run: error: "), err
    assert expect in err, err
    assert not (tmp_path / "o").exists()


def test_the_loci_follow_the_scenes_rtol(tmp_path, capsys, monkeypatch):
    # the Fig 9 scene's loci in μ at rtol = 1e-2: the events within 10·rtol of their closed
    # forms (μ_C: F_A = μF'_N, μ_0: F'_T = 0, with F_A = μF_N0(1 − exp(−g_A/(λμ))), λ =
    # σ*(2 − ν)/(2(1 − ν)); tests/app/test_manifold_scene.py checks the default run)
    import math

    lam = 2.0 * (2.0 - 0.3) / (2.0 * (1.0 - 0.3))
    mu_c = 0.34 / (lam * math.log(1000.0 / 150.0))
    mu_0 = 0.34 / (lam * math.log(1000.0 / 850.0))
    text = (ROOT / "scenes" / "fig9.toml").read_text(encoding="utf-8")
    scene = tmp_path / "s.toml"
    scene.write_text(text.replace("[output]", "[solver]\nrtol = 1e-2\n\n[output]"), "utf-8")
    from cusp.models import manifold

    seen = []
    point_loci = manifold.point_loci

    def spy(*args, options=None, **kw):
        seen.append(options)
        return point_loci(*args, options=options, **kw)

    monkeypatch.setattr(manifold, "point_loci", spy)
    out = tmp_path / "o"
    assert _run(capsys, "run", scene, "--no-plots", "--quiet", "--out", out)[0] == 0
    assert [(o.rtol, o.ds_max) for o in seen] == [(1e-2, 0.1)]  # the loci's own steps
    s = _summary(out)
    assert s["accuracy"]["rtol"] == 1e-2
    events = {ev["event"]: ev["values"]["mu"] for ev in s["manifold"]["events"]}
    assert events["C boundary"] == pytest.approx(mu_c, rel=0.1)
    assert events["F'_T = 0"] == pytest.approx(mu_0, rel=0.1)


def test_the_scene_range_of_rtol_is_the_solvers():
    from cusp.app.scene import RTOL_RANGE
    from cusp.continuation import RTOL_MAX, RTOL_MIN

    assert RTOL_RANGE == (RTOL_MIN, RTOL_MAX)
