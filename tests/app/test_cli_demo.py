"""The ``cusp`` command: the demo (today's main job) end to end."""

import subprocess
import sys

from cusp.app.cli import main


def test_cusp_demo_prints_both_folds(capsys):
    assert main(["demo"]) == 0
    out = capsys.readouterr().out
    assert "cusp normal form" in out
    lines = [ln for ln in out.splitlines() if ln.strip().startswith("fold")]
    assert len(lines) == 2
    # |b| at the folds = 2/(3√3) = 0.384900179459750 (to the printed 15 decimals)
    assert all("0.384900179459750" in ln or "0.384900179459751" in ln for ln in lines)


def test_demo_bad_argument_exits_2(capsys):
    assert main(["demo", "--a", "-1"]) == 2
    assert "--a must be a finite number > 0" in capsys.readouterr().out


def test_console_entry_point_runs():
    out = subprocess.run(
        [sys.executable, "-m", "cusp.app.cli", "demo", "--a", "3"],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    # at a = 3 the folds are at b = ∓2 (a/3)^{3/2} = ∓2
    assert "-2.000000000000000" in out and " 2.000000000000000" in out
