"""The A/B timing script loads a git revision of the package beside the working tree and
times both on the benchmark problems (one round only)."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _in_git_checkout() -> bool:
    if shutil.which("git") is None:
        return False
    done = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True)
    return done.returncode == 0


def _bench_ab(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "scripts/bench_ab.py", *args],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=300,
    )


@pytest.mark.skipif(not _in_git_checkout(), reason="needs a git checkout")
def test_bench_ab_compares_head_with_the_working_tree():
    done = _bench_ab("HEAD", "--rounds", "1")
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    # both sides trace both problems and locate both folds (cusp: b = ±2/(3√3) =
    # ±0.38490017945975050..., mpmath.mpf(2)/(3*mpmath.sqrt(3)))
    assert sum("[base]" in line for line in lines) == 2
    assert sum("[new]" in line for line in lines) == 2
    assert all("0.384900179459750" in line for line in lines if line.startswith("cusp"))
    assert sum("ratio new/base" in line for line in lines) == 2


@pytest.mark.skipif(not _in_git_checkout(), reason="needs a git checkout")
def test_bench_ab_sparse_bratu_counts_steps_and_factorizations():
    done = _bench_ab("HEAD", "--sparse", "99", "--rounds", "1")
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    sides = [line for line in lines if line.startswith("sparse Bratu N = 99 [")]
    assert len(sides) == 2 and all("sparse LUs" in line and "bound" in line for line in sides)
    # one fold each, at the N = 99 fold of the FD Bratu problem: lam* = 3.513647903969307
    # (cusp.examples.bratu.bratu_fd_fold(99): mpmath shooting at 40 digits), to 1e-13
    # relative (the locator's tolerance is 1e-12; Newton's second update leaves ~3e-14)
    folds = [float(line.split("folds ['")[1].split("'")[0]) for line in sides]
    assert all(abs(lam / 3.513647903969307 - 1.0) < 1e-13 for lam in folds), folds
    assert "ratio new/base: trace" in lines[-1] and "per LU" in lines[-1]
