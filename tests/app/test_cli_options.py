"""The options every ``cusp`` command has and how it behaves around its work: ``--version``,
``-v`` logging (the ``cusp.*`` loggers), no traceback when stdout's reader goes away
(``cusp run ... | head -1``), a progress bar on a terminal only, and the printed timings
that keep imports apart from the computation."""

from __future__ import annotations

import importlib
import importlib.machinery
import io
import json
import logging
import subprocess
import sys
import time
from pathlib import Path

import pytest

import cusp
from cusp.app import cli, progress
from cusp.app import run as run_module

ROOT = Path(__file__).resolve().parents[2]
FIG6 = str(ROOT / "scenes" / "fig6.toml")


@pytest.fixture(autouse=True)
def _no_cli_logging():
    yield
    progress.configure_logging(0)  # (the handler a test's -v installed goes)


def test_version(capsys):
    assert cli.main(["--version"]) == 0
    assert capsys.readouterr().out == f"cusp {cusp.__version__}\n"


def test_version_is_listed_in_the_help(capsys):
    with pytest.raises(SystemExit):
        cli.main(["--help"])
    text = capsys.readouterr().out
    assert "--version" in text and "-v, --verbose" in text


@pytest.mark.parametrize("where", ["before", "after"])
def test_verbose_shows_the_cusp_loggers(tmp_path, capsys, where):
    args = ["run", FIG6, "--no-plots", "--out", str(tmp_path / "o")]
    argv = ["-v", *args] if where == "before" else [*args, "-v"]
    assert cli.main(argv) == 0
    err = capsys.readouterr().err
    assert "INFO cusp.app: mu = 0.1, F'_N = 850 N: " in err  # fig6.toml's case, and its time
    assert "INFO cusp.models: leg OA: " in err  # the physics' logger: each leg
    assert all(line.startswith(("INFO cusp.", "WARNING cusp.")) for line in err.splitlines())


def test_without_verbose_nothing_is_logged(tmp_path, capsys):
    assert cli.main(["run", FIG6, "--no-plots", "--out", str(tmp_path / "o")]) == 0
    assert capsys.readouterr().err == ""


def test_very_verbose_shows_debug_records(capsys):
    cli.main(["-vv", "demo"])
    assert logging.getLogger("cusp").level == logging.DEBUG
    cli.main(["demo"])
    assert logging.getLogger("cusp").level == logging.NOTSET and not [
        h for h in logging.getLogger("cusp").handlers if getattr(h, "cusp_cli", False)
    ]


def test_a_closed_pipe_ends_quietly(tmp_path):
    """``cusp run fig8 --no-plots --out o8 | head -1``: the reader goes after one line; the
    command ends with status 141 (128 + SIGPIPE) and no traceback, its outputs written."""
    code = "import sys; from cusp.app import cli; sys.exit(cli.main(sys.argv[1:]))"
    argv = [sys.executable, "-c", code, "run", "fig8", "--no-plots", "--out", str(tmp_path / "o8")]
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert proc.stdout is not None and proc.stderr is not None
    proc.stdout.close()  # (as head does once it has its line: before the report is printed)
    err = proc.stderr.read().decode()
    proc.stderr.close()
    assert proc.wait(timeout=300) == cli.BROKEN_PIPE_STATUS, err
    assert err == ""
    assert json.loads((tmp_path / "o8" / "summary.json").read_text())["scene"]["name"] == "fig8"


def test_the_printed_times_say_what_they_measure(tmp_path, capsys):
    assert cli.main(["run", FIG6, "--no-plots", "--out", str(tmp_path / "o")]) == 0
    last = capsys.readouterr().out.splitlines()[-2]
    assert last.startswith("time: compute ") and "imports on the way" in last
    assert "from the command's start" in last


class _Finder:
    """Finds the test's modules in one directory (the import path is left alone)."""

    def __init__(self, where: Path, names: set[str]) -> None:
        self.where, self.names = where, names

    def find_spec(self, name, path=None, target=None):
        if name not in self.names:
            return None
        return importlib.machinery.PathFinder.find_spec(name, [str(self.where)])


def _slow_modules(tmp_path: Path, monkeypatch) -> None:
    """Two modules that take 0.2 s each to import, the first importing the second."""
    (tmp_path / "slow_outer_i31.py").write_text("import time, slow_inner_i31\ntime.sleep(0.2)\n")
    (tmp_path / "slow_inner_i31.py").write_text("import time\ntime.sleep(0.2)\n")
    names = {"slow_outer_i31", "slow_inner_i31"}
    monkeypatch.setattr(sys, "meta_path", [*sys.meta_path, _Finder(tmp_path, names)])
    for name in names:
        monkeypatch.delitem(sys.modules, name, raising=False)


def test_the_import_clock_counts_nested_imports_once(tmp_path, monkeypatch):
    _slow_modules(tmp_path, monkeypatch)
    t0 = time.perf_counter()
    with progress.ImportClock() as clock:
        importlib.import_module("slow_outer_i31")
    wall = time.perf_counter() - t0
    assert 0.4 <= clock.seconds <= wall  # 2 × 0.2 s of sleep, the inner inside the outer
    module = sys.modules["slow_outer_i31"]
    assert type(module.__loader__).__name__ != "_TimedLoader"  # its own loader kept


def test_run_scene_reports_imports_apart_from_compute(tmp_path, monkeypatch):
    """An import made while computing (a model's module loaded on first use) is counted in
    ``imports_s``, not in ``compute_s``."""
    _slow_modules(tmp_path, monkeypatch)
    make_model = run_module.make_model

    def importing(*args, **kwargs):
        importlib.import_module("slow_outer_i31")
        return make_model(*args, **kwargs)

    monkeypatch.setattr(run_module, "make_model", importing)
    scene = run_module.load_scene(Path(FIG6))
    t0 = time.perf_counter()
    with progress.ImportClock() as clock:
        run, _ = run_module.run_scene(scene, plots=False, clock=clock)
    wall = time.perf_counter() - t0
    t = run.timing
    assert t["imports_s"] >= 0.4
    assert t["compute_s"] + t["imports_s"] <= wall and t["compute_s"] < wall - 0.4


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_tasks_bar_on_a_terminal_after_a_second(monkeypatch):
    pytest.importorskip("tqdm")
    screen = _Terminal()
    monkeypatch.setattr(sys, "stderr", screen)
    tasks = progress.Tasks(2, wanted=True)
    with tasks.task("quick"):
        pass
    assert screen.getvalue() == ""  # under a second: nothing yet
    with tasks.task("slow"):
        time.sleep(1.2)
    tasks.close()
    assert "task" in screen.getvalue()


def test_no_bar_when_piped_not_wanted_or_without_tqdm(monkeypatch):
    monkeypatch.setattr(sys, "stderr", io.StringIO())
    assert progress.Tasks(2, wanted=True).bar is None  # not a terminal
    monkeypatch.setattr(sys, "stderr", _Terminal())
    assert progress.Tasks(2, wanted=False).bar is None  # --quiet
    monkeypatch.setitem(sys.modules, "tqdm", None)
    assert progress.Tasks(2, wanted=True).bar is None  # no tqdm: no bar, no error
