"""scripts/bench_sweep.py: its sweeps have the sizes asked for, and its scaling model is
the bound it states."""

from __future__ import annotations

import math

from cusp.app.scene import parse_scene


def test_the_bench_sweeps_have_about_the_cases_asked_for(load_script):
    bench = load_script("bench_sweep")
    for kind, n in (("exponential", 10_000), ("sphere", 1_000), ("exponential", 20)):
        sw = parse_scene(bench.scene_text(kind, n)).sweep
        n_mu = math.ceil(math.sqrt(n))  # ⌈√n⌉ values of μ by n // ⌈√n⌉ of F'_N
        assert len(sw) == n_mu * (n // n_mu) and 0.9 * n <= len(sw) <= n


def test_the_scaling_model_is_bounded_by_the_workers_or_the_driver(load_script):
    bench = load_script("bench_sweep")
    # a driver serving a chunk in s = 1 ms: 10^4 cases of t = 0.1 s on 100 workers take
    # the workers' 10 s plus the last chunk (automatic c = 25: 2.5 s) plus start-up (1 s)
    fast = {"dask_task": 0.5e-3, "write_part": 0.5e-3, "startup": 1.0}
    text = "\n".join(bench.scaling(0.1, fast))
    assert "c = 25, 400 chunks, about 14 s, limited by the workers" in text
    # s = 100 ms: the driver's 400 chunks take 40 s, more than the workers' 12.5 s
    slow = {"dask_task": 50e-3, "write_part": 50e-3, "startup": 1.0}
    text = "\n".join(bench.scaling(0.1, slow))
    assert "c = 25, 400 chunks, about 41 s, limited by the driver" in text
    # the 10 % rule: c >= 10 W s / t = 10 * 100 * 0.1 / 0.1 = 1000
    assert "c ≥ 10·W·s/t = **1000**" in text
