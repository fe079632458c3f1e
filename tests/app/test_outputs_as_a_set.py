"""``cusp run`` writes its outputs as one set (cusp.app.output): injected failures at every
step and kills at every step leave DIR as it was (after the next run's recovery), concurrent
runs into one DIR both succeed, and owned files a run does not write are removed."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from cusp.app import cli, output
from cusp.app.output import recover, write_outputs

ROOT = Path(__file__).resolve().parents[2]
NEW = {"summary.json": b"new", "branch.csv": b"new", "force-slip.png": b"new"}


def _old_dir(tmp_path: Path) -> Path:
    out = tmp_path / "o"
    out.mkdir()
    for name in ("summary.json", "branch.csv", "force-area.svg"):
        (out / name).write_bytes(b"old")
    (out / "notes.txt").write_text("mine")
    (out / "sub").mkdir()
    (out / "sub" / "x").write_text("mine too")
    return out


def _state(parent: Path) -> dict[str, dict[str, bytes] | None]:
    return {
        p.name: {str(f.relative_to(p)): f.read_bytes() for f in sorted(p.rglob("*")) if f.is_file()}
        if p.is_dir()
        else None
        for p in sorted(parent.iterdir())
    }


def test_a_run_replaces_the_whole_set_and_keeps_foreign_files(tmp_path):
    out = _old_dir(tmp_path)
    write_outputs(out, NEW)
    assert _state(tmp_path) == {
        "o": {
            "branch.csv": b"new",
            "force-slip.png": b"new",
            "notes.txt": b"mine",
            "sub/x": b"mine too",
            "summary.json": b"new",
        }
    }  # force-area.svg of the old set is gone


@pytest.mark.parametrize("step", range(8))
def test_a_failure_at_any_step_leaves_dir_as_it_was(tmp_path, monkeypatch, step):
    out = _old_dir(tmp_path)
    before = _state(tmp_path)
    calls = []
    real_rename = os.rename

    def rename(src, dst):
        calls.append(src)
        if len(calls) == step + 1:
            raise OSError(28, "No space left on device (injected)")
        real_rename(src, dst)

    monkeypatch.setattr(output.os, "rename", rename)
    try:
        write_outputs(out, NEW)
    except OSError:
        assert _state(tmp_path) == before
    else:  # fewer renames than ``step``: the run went through
        assert (out / "summary.json").read_bytes() == b"new"
        assert sorted(p.name for p in tmp_path.iterdir()) == ["o"]


_KILLER = """
import os, signal, sys
from cusp.app import output
n, real = int(sys.argv[2]), os.rename
calls = []
def rename(src, dst):
    calls.append(src)
    if len(calls) == n:
        os.kill(os.getpid(), signal.SIGKILL)
    real(src, dst)
output.os.rename = rename
output.write_outputs(sys.argv[1], {"summary.json": b"new", "branch.csv": b"new"})
"""


@pytest.mark.parametrize("step", range(1, 8))
def test_a_run_killed_at_any_step_is_undone_by_the_next_run(tmp_path, step):
    out = _old_dir(tmp_path)
    before = _state(tmp_path)
    proc = subprocess.run([sys.executable, "-c", _KILLER, str(out), str(step)], cwd=ROOT)
    if proc.returncode == 0:  # fewer renames than ``step``: it went through
        assert (out / "summary.json").read_bytes() == b"new"
        return
    assert proc.returncode == -9
    recover(out)  # what the next run into DIR does first, under the lock
    assert _state(tmp_path) == before


def test_stale_staging_directories_are_removed_by_the_next_run(tmp_path):
    out = _old_dir(tmp_path)
    for kind in ("partial", "ready", "old"):
        (tmp_path / f".o.{kind}-abc").mkdir()
        (tmp_path / f".o.{kind}-abc" / "summary.json").write_bytes(b"stale")
    write_outputs(out, NEW)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["o"]


_CONCURRENT = """
import sys
from cusp.app.output import write_outputs
for i in range(20):
    write_outputs(sys.argv[1], {"summary.json": sys.argv[2].encode() * 1000})
"""


def test_concurrent_runs_into_one_new_dir_both_succeed(tmp_path):
    out = tmp_path / "new"
    procs = [
        subprocess.Popen([sys.executable, "-c", _CONCURRENT, str(out), tag], cwd=ROOT)
        for tag in ("a", "b")
    ]
    assert [p.wait(timeout=120) for p in procs] == [0, 0]
    assert (out / "summary.json").read_bytes() in (b"a" * 1000, b"b" * 1000)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["new"]


def test_no_plots_into_a_dir_with_figures_removes_the_old_figures(tmp_path, capsys):
    out = tmp_path / "o"
    argv = ["run", str(ROOT / "scenes" / "fig6.toml"), "--out", str(out), "--quiet"]
    assert cli.main(argv) == 0
    assert (out / "force-slip.png").exists()
    (out / "notes.txt").write_text("mine")
    assert cli.main([*argv, "--no-plots"]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["branch.csv", "notes.txt", "summary.json"]
    assert json.loads((out / "summary.json").read_text())["warnings"] == []
    assert capsys.readouterr().err == ""


def test_the_new_dir_gets_the_usual_permissions(tmp_path):
    write_outputs(tmp_path / "o", NEW)
    mask = os.umask(0)
    os.umask(mask)
    assert (tmp_path / "o").stat().st_mode & 0o777 == 0o777 & ~mask
