"""The branch-point benchmark script (issue 26) runs on a handful of starts, tells a switch
from a clean trace, and writes its report."""

from __future__ import annotations

import math

import pytest


@pytest.fixture
def bench(load_script):
    return load_script("bench_branch_points")


@pytest.mark.parametrize("jacobian", ["fd", "analytic"])
def test_lorenz_from_a_few_random_starts(bench, jacobian):
    starts = bench.lorenz_starts(5, 0)
    assert starts.shape == (5, 3) and abs(starts).max() <= 0.5  # the issue's [−0.5, 0.5]³
    r = bench.run_lorenz(jacobian, starts, 10.0)
    assert (r["switches"], r["creeps"], r["hangs"], r["errors"]) == (0, 0, 0, 0)
    assert r["bound"] == r["bp_once"] == r["bp_ok"] == 5 and r["bad"] == []
    assert r["worst_r"] <= 1e-10  # the location of the pitchfork at r = 1


def test_a_trace_on_the_crossing_branch_is_a_switch(bench):
    # the Lorenz problem at r = 2 from the crossing branch x = y = √(β(r − 1)), z = r − 1
    # (β = 8/3): every point is off the origin, and no branch point lies on r ∈ [2, 3]
    prob = bench.lorenz_problem("analytic").with_params(r=2.0)
    x = math.sqrt(8 / 3)
    out = bench.classify(prob, [x, x, 1.0], exact_steps=4, seconds=10.0)
    assert out["switch"] and out["off"] > 1.0
    assert out["bp"] == 0 and not out["bp_ok"] and not out["hang"] and out["error"] is None


def test_the_report_is_written(bench, tmp_path):
    out = tmp_path / "branch-points.md"
    argv = ["--starts", "3", "--suite-seeds", "1", "--problems", "pitchfork", "--out", str(out)]
    assert bench.main(argv) == 0
    text = out.read_text(encoding="utf-8")
    assert "| fd | 3 | 0 | 0 | 0 | 0 | 3 | 3 | 3 |" in text
    assert "| analytic | 3 | 0 | 0 | 0 | 0 | 3 | 3 | 3 |" in text
    assert "| 1e-06 | 1 | 1 | 0 |" in text and "No failure." in text
    assert "python scripts/bench_branch_points.py --starts 3" in text
    assert not list(tmp_path.glob("*.tmp"))  # written atomically
