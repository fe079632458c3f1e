"""The sparse-scaling benchmark script runs and writes its table (small sizes only)."""

from __future__ import annotations


def test_bench_sparse_writes_its_table(tmp_path, load_script):
    module = load_script("bench_sparse")
    out = tmp_path / "sparse.md"
    assert module.main(["--sizes", "31", "63", "--repeat", "1", "--out", str(out)]) == 0
    rows = [
        [c.strip() for c in line.strip("|").split("|")]
        for line in out.read_text(encoding="utf-8").splitlines()
        if line.startswith(("| 31 ", "| 63 "))
    ]
    # sparse and dense at each size; the fold against the mpmath shooting reference
    # (cusp.examples.bratu_fd_fold) to well below the 1e-10
    assert [(r[0], r[1]) for r in rows] == [
        ("31", "sparse"),
        ("31", "dense"),
        ("63", "sparse"),
        ("63", "dense"),
    ]
    for r in rows:
        assert float(r[8]) < 1e-12, r
        assert r[9] == "mpmath shooting"
    assert not list(tmp_path.glob("*.tmp"))  # written atomically
