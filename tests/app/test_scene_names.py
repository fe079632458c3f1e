"""``cusp run NAME``: the bundled scenes by name, and an unknown name refused with the list."""

from __future__ import annotations

from pathlib import Path

from cusp.app import cli
from cusp.app.run import bundled_names, bundled_scene, resolve_scene

ROOT = Path(__file__).resolve().parents[2]


def test_bundled_scenes_by_name(tmp_path, monkeypatch):
    assert {"fig6", "fig7", "fig8", "gaussian", "sphere"} <= set(bundled_names())
    path, source = resolve_scene("fig8")
    assert path == bundled_scene("fig8.toml") and source == "scenes/fig8.toml (bundled)"
    assert resolve_scene("fig8.toml")[0] == path
    assert resolve_scene(None) == (bundled_scene(), "scenes/fig6.toml (bundled)")
    monkeypatch.chdir(tmp_path)
    (tmp_path / "fig8").mkdir()  # e.g. an earlier --out fig8: the bundled scene still runs
    assert resolve_scene("fig8")[0] == path
    (tmp_path / "fig8.toml").write_text("")  # a file of that name comes first
    assert resolve_scene("fig8.toml") == (Path("fig8.toml"), None)


def test_cusp_run_by_name(tmp_path, capsys):
    out = tmp_path / "o"
    status = cli.main(["run", "fig7", "--out", str(out), "--no-plots"])
    stdout, err = capsys.readouterr()
    assert status == 0, err
    assert "scene fig7 (scenes/fig7.toml (bundled))" in stdout
    assert (out / "summary.json").exists()


def test_unknown_scene_name_lists_the_bundled_scenes(tmp_path, capsys):
    status = cli.main(["run", "fig99", "--out", str(tmp_path / "o")])
    stdout, err = capsys.readouterr()
    assert status == 2 and stdout == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in err
    assert lines[0].startswith("cusp run: error: fig99: no such scene file")
    assert lines[0].endswith(f"a bundled scene: {', '.join(bundled_names())}")
    assert not (tmp_path / "o").exists()
