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


def test_demo_hopf_diagram(capsys, tmp_path):
    """``cusp demo --hopf``: the Brusselator's Hopf point against its closed forms
    b = 1 + a², ω = a, l1 = −(a² + 2)/(2a(2a² + 1)) (a = 2: b = 5, ω = 2, l1 = −1/6), and
    the diagram written."""
    out = tmp_path / "hopf.png"
    assert main(["demo", "--hopf", "--a", "2", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    rows = {
        ln.split()[1]: ln.split()[2:] for ln in text.splitlines() if ln.strip().startswith("hopf")
    }
    b, b_exact = map(float, rows["b"])
    omega, omega_exact = map(float, rows["omega"])
    l1, l1_exact = map(float, rows["l1"])
    assert (b_exact, omega_exact) == (5.0, 2.0) and abs(l1_exact + 1 / 6) < 1e-14
    assert abs(b - 5.0) <= 1e-10 * 5 and abs(omega - 2.0) <= 1e-10 * 2
    assert abs(l1 - l1_exact) <= 1e-6 * abs(l1_exact)
    assert "supercritical" in text and "0 at b = 1, 2 at b = 10" in text
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
