"""``cusp sweep``: the ``[sweep]`` section, the rows against ``cusp run`` and the closed
forms, resuming after a kill, local workers and a Dask cluster."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from cusp.app import cli
from cusp.app.scene import SceneError, load_scene, parse_scene

pq = pytest.importorskip("pyarrow.parquet")

BASE = """\
[surface]
model = "rough-exponential"
sigma = 2.0
nu = 0.3
mu = 0.1

[loading]
normal_load = 1000.0
max_slip = 0.34
reduced_normal_load = 850.0
"""
# 2 x 2 cases: mu 0.1 has C (F_A = 75.34 N < mu F'_N = 85 N at 850 N) and gross sliding
# under force control at 700 N (75.34 >= 70); mu 0.2 has C at both
GRID = (
    BASE
    + """
[sweep]
"surface.mu" = [0.1, 0.2]
"loading.reduced_normal_load" = [850.0, 700.0]
"""
)


def _sweep(scene: Path, out: Path, *more: str) -> int:
    return cli.main(["sweep", str(scene), "--out", str(out), "--quiet", *more])


def _rows(out: Path) -> list[dict]:
    rows = pq.read_table(out / "results.parquet").to_pylist()
    return sorted(rows, key=lambda r: r["index"])


def _numbers(row: dict) -> dict:
    """A row without what changes from run to run (the time taken)."""
    return {k: v for k, v in row.items() if k != "seconds"}


@pytest.fixture(scope="module")
def grid(tmp_path_factory):
    """The 2 x 2 grid swept in this process: (scene file, output directory)."""
    root = tmp_path_factory.mktemp("grid")
    scene = root / "grid.toml"
    scene.write_text(GRID, encoding="utf-8")
    out = root / "out"
    assert _sweep(scene, out, "--workers", "0") == 0
    return scene, out


def _fail_text(extra: str, tmp_path: Path | None = None) -> str:
    with pytest.raises(SceneError) as info:
        if tmp_path is None:
            parse_scene(BASE + "\n[sweep]\n" + extra, source="s.toml")
        else:
            path = tmp_path / "s.toml"
            path.write_text(BASE + "\n[sweep]\n" + extra, encoding="utf-8")
            load_scene(path)
    return str(info.value)


@pytest.mark.parametrize(
    ("extra", "words"),
    [
        (
            '"surface.foo" = [1.0]',
            ["unknown field 'surface.foo'", "surface.mu", "loading.max_slip"],
        ),
        ('"surface.shape" = [2.0]', ["unknown field 'surface.shape'", "surface.sigma"]),
        ('"surface.model" = ["sphere"]', ["unknown field 'surface.model'"]),
        ('"surface.mu" = []', ["'surface.mu' = []", "a non-empty list"]),
        ('"surface.mu" = { start = 0.1, stop = 0.2, num = 0 }', ["num = 0", "from 1 to"]),
        ('"surface.mu" = { start = 0.1, stop = 0.2, num = 2.5 }', ["num = 2.5", "an integer"]),
        ('"surface.mu" = { start = 0.1, num = 3 }', ["misses stop"]),
        (
            '"surface.mu" = { start = 0.0, stop = 0.2, num = 3, spacing = "log" }',
            ["spacing = 'log' with start = 0.0", "start > 0 and stop > 0"],
        ),
        ('"surface.mu" = { start = 0.1, stop = 0.2, num = 3, spacing = "cubic" }', ["'cubic'"]),
        ('"surface.mu" = [true]', ["holds True", "numbers"]),
        ('"surface.mu" = [[0.1]]', ["holds [0.1]"]),
        ('"surface.mu" = 0.1', ["'surface.mu' = 0.1", "a list of values"]),
        ('cases = "c.csv"\n"surface.mu" = [0.1]', ["cases and 'surface.mu' together"]),
    ],
)
def test_a_bad_sweep_section_names_the_field_its_value_and_what_is_allowed(extra, words):
    text = _fail_text(extra)
    assert text.startswith("s.toml: [sweep]") and "; allowed: " in text
    for word in words:
        assert word in text, (word, text)


def test_an_empty_sweep_section_is_refused():
    with pytest.raises(SceneError, match=r"\[sweep\] is empty; allowed: fields to vary"):
        parse_scene(BASE + "\n[sweep]\n", source="s.toml")


def test_a_cases_file_missing_or_with_unknown_columns_is_refused(tmp_path):
    assert "cases = 'none.csv': no such file" in _fail_text('cases = "none.csv"', tmp_path)
    (tmp_path / "c.csv").write_text("surface.mu,loading.foo\n0.1,2\n", encoding="utf-8")
    text = _fail_text('cases = "c.csv"', tmp_path)
    assert "unknown column 'loading.foo'" in text and "loading.max_slip" in text
    (tmp_path / "c.csv").write_text("surface.mu,surface.nu\n0.1\n", encoding="utf-8")
    assert "case 0 has 1 cells" in _fail_text('cases = "c.csv"', tmp_path)
    (tmp_path / "c.csv").write_text("surface.mu\n", encoding="utf-8")
    assert "has no case" in _fail_text('cases = "c.csv"', tmp_path)


def test_a_listed_field_must_be_swept():
    text = BASE.replace("mu = 0.1", "mu = [0.1, 0.2]") + '[sweep]\n"surface.nu" = [0.3]\n'
    with pytest.raises(SceneError, match=r"\[surface\] mu lists several values but \[sweep\]"):
        parse_scene(text, source="s.toml")


def test_ranges_and_combinations():
    text = BASE + (
        '[sweep]\n"surface.mu" = { start = 0.01, stop = 1.0, num = 5, spacing = "log" }\n'
        '"loading.reduced_normal_load" = { start = 500.0, stop = 900.0, num = 3 }\n'
    )
    sw = parse_scene(text).sweep
    assert sw.fields == ("surface.mu", "loading.reduced_normal_load") and len(sw) == 15
    mus = sorted({v[0] for v in sw.values})
    loads = [v[1] for v in sw.values[:3]]
    # log spacing: 0.01 * 100**(i/4) = 10**(i/2 - 2), i = 0..4; linear: 500 + 200 i
    for i, mu in enumerate(mus):
        assert mu == pytest.approx(10.0 ** (i / 2 - 2), rel=4e-16), (i, mu)
    assert mus[0] == 0.01 and mus[-1] == 1.0  # the ends exactly as given
    assert loads == [500.0, 700.0, 900.0]
    # every combination, the first field slowest
    assert sw.values[3] == (mus[1], 500.0)
    assert sw.case_data(4)["surface"]["mu"] == mus[1]
    assert sw.case_data(4)["loading"]["reduced_normal_load"] == 700.0
    assert "sweep" not in sw.case_data(0)


def test_cases_file_rows_are_the_cases(tmp_path):
    (tmp_path / "c.csv").write_text(
        "# a comment line\nsurface.mu,options.area_reading\n0.1,printed\n0.25,consistent\n",
        encoding="utf-8",
    )
    path = tmp_path / "s.toml"
    path.write_text(BASE + '[sweep]\ncases = "c.csv"\n', encoding="utf-8")
    sw = load_scene(path).sweep
    assert sw.fields == ("surface.mu", "options.area_reading")
    assert sw.values == ((0.1, "printed"), (0.25, "consistent"))


def test_rows_equal_cusp_run_of_the_same_case(grid, tmp_path):
    scene, out = grid
    rows = _rows(out)
    assert [r["index"] for r in rows] == [0, 1, 2, 3] and {r["status"] for r in rows} == {"ok"}
    for row in rows[:3]:
        one = tmp_path / f"case{row['index']}.toml"
        one.write_text(
            BASE.replace("mu = 0.1", f"mu = {row['surface.mu']!r}").replace(
                "= 850.0", f"= {row['loading.reduced_normal_load']!r}"
            ),
            encoding="utf-8",
        )
        run_out = tmp_path / f"run{row['index']}"
        assert cli.main(["run", str(one), "--out", str(run_out), "--no-plots", "--quiet"]) == 0
        summary = json.loads((run_out / "summary.json").read_text(encoding="utf-8"))
        for point in "ABCD":
            pt = summary["points"][point]
            for q, col in (("g_T", "g"), ("F_T", "F"), ("A_SL", "A_SL")):
                want = None if pt is None else pt[q]
                assert row[f"{col}_{point}"] == want, (row["index"], point, q)
        for kind in ("snap_back", "snap_through"):
            assert row[f"{kind}_energy"] == summary["energy"][kind]
            assert row[f"{kind}_error"] == summary["energy"]["error_estimate"][kind]
        assert row["message"] == "; ".join(summary["messages"])
        assert row["rtol"] == summary["accuracy"]["rtol"] == 1e-3
        assert row["version"] == summary["software"]["cusp"]


def test_rows_against_the_exponential_closed_forms(grid):
    # cusp.verification.oracles.exponential_closed_form: the sympy closed forms of the path
    # (docs/physics.md §7), evaluated exactly at the binary inputs (σ* = 2, ν = 0.3,
    # F_N0 = 1000 N, g_A = 0.34 µm as in BASE); C and the snap-through exist where
    # F_A < μ F'_N, i.e. not at μ = 0.1, F'_N = 700 N (F_A = 75.34 N)
    from cusp.verification.oracles import exponential_closed_form as closed_form

    _, out = grid
    for row in _rows(out):
        mu, load = row["surface.mu"], row["loading.reduced_normal_load"]
        assert (row["mu"], row["reduced_normal_load"]) == (mu, load)
        has_c = not (mu == 0.1 and load == 700.0)
        cols = ["F_A", "g_B", "F_B", "F_D", "A_SL_A", "A_SL_B", "A_SL_D"]
        cols += ["g_C", "A_SL_C"] if has_c else []
        for col in cols:
            want = closed_form(col, mu, load)
            assert row[col] == pytest.approx(want, rel=1e-10), (row["index"], col)
            assert abs(row[col] - want) <= max(row[f"{col}_error"], 1e-13 * abs(want))
        assert (row["g_C"] is None) == (not has_c) and (row["F_C"] is None) == (not has_c)
        for kind in ("snap_back", "snap_through") if has_c else ("snap_back",):
            want = closed_form(kind, mu, load)
            assert abs(row[f"{kind}_energy"] - want) <= row[f"{kind}_error"], (row, kind)
        if not has_c:
            assert row["snap_through_energy"] is None and "gross sliding" in row["message"]


def test_a_refused_case_is_a_row_and_the_sweep_goes_on(tmp_path):
    scene = tmp_path / "s.toml"
    # F'_N = 1000 N is no reduction of F_N0 = 1000 N: the scene schema refuses that case
    scene.write_text(BASE + '[sweep]\n"loading.reduced_normal_load" = [1000.0, 900.0]\n')
    assert _sweep(scene, tmp_path / "out", "--workers", "0") == 0
    refused, ok = _rows(tmp_path / "out")
    assert refused["status"] == "refused" and ok["status"] == "ok"
    assert "reduced_normal_load = 1000.0 N; allowed: less than normal_load" in refused["message"]
    assert refused["F_A"] is None and refused["g_A"] is None and refused["rtol"] is None
    assert ok["F_A"] == pytest.approx(75.34030360583935, rel=1e-12)  # Fig 6's F_A


def test_a_deleted_part_is_computed_again_and_nothing_twice(grid, tmp_path):
    import shutil

    scene, first = grid
    out = tmp_path / "out"
    assert _sweep(scene, out, "--workers", "0", "--chunk-size", "1") == 0
    parts = sorted((out / "results.parquet").glob("part-*.parquet"))
    assert len(parts) == 4
    parts[2].unlink()
    before = {p.name for p in parts} - {parts[2].name}
    assert _sweep(scene, out, "--workers", "0", "--chunk-size", "3") == 0
    after = {p.name for p in (out / "results.parquet").glob("part-*.parquet")}
    assert before < after and len(after) == 4  # one new part: the missing case only
    assert [_numbers(r) for r in _rows(out)] == [_numbers(r) for r in _rows(first)]
    # a rerun with nothing missing computes nothing
    assert _sweep(scene, out, "--workers", "0") == 0
    assert {p.name for p in (out / "results.parquet").glob("part-*.parquet")} == after
    shutil.rmtree(out)


def test_a_killed_sweep_resumes_with_the_missing_cases_only(tmp_path):
    scene = tmp_path / "s.toml"
    scene.write_text(
        BASE + '[sweep]\n"surface.mu" = { start = 0.1, stop = 0.3, num = 8 }\n'
        '"loading.reduced_normal_load" = [850.0, 800.0, 750.0, 700.0, 650.0]\n',
        encoding="utf-8",
    )
    out = tmp_path / "out"
    args = [sys.executable, "-m", "cusp", "sweep", str(scene), "--out", str(out), "--quiet"]
    proc = subprocess.Popen([*args, "--workers", "0", "--chunk-size", "1"])
    parts = out / "results.parquet"
    deadline = time.monotonic() + 120
    while not (parts.is_dir() and any(parts.glob("part-*.parquet"))):
        assert proc.poll() is None and time.monotonic() < deadline
        time.sleep(0.005)
    os.kill(proc.pid, signal.SIGKILL)
    proc.wait()
    done = len(_rows(out))
    assert 1 <= done < 40  # killed midway
    resumed = subprocess.run(
        [*args[:-1], "--workers", "0"], capture_output=True, text=True, check=True
    )
    assert f"{done} cases already in {out}; computed {40 - done} in" in resumed.stdout
    rows = _rows(out)
    assert [r["index"] for r in rows] == list(range(40))  # each case once
    assert {r["status"] for r in rows} == {"ok"}


def test_another_scene_into_the_same_directory_is_refused(grid, tmp_path, capsys):
    scene, out = grid
    other = tmp_path / "other.toml"
    other.write_text(GRID.replace("nu = 0.3", "nu = 0.25"), encoding="utf-8")
    assert _sweep(other, out) == 2
    err = capsys.readouterr().err
    assert "holds case 0 of another sweep" in err and "allowed: the same scene" in err


def test_local_workers_give_the_rows_of_a_sweep_in_this_process(grid, tmp_path):
    scene, first = grid
    out = tmp_path / "out"
    assert _sweep(scene, out, "--workers", "2", "--chunk-size", "1") == 0
    assert [_numbers(r) for r in _rows(out)] == [_numbers(r) for r in _rows(first)]


def test_a_dask_local_cluster_gives_the_same_rows(grid, tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    scene, first = grid
    out = tmp_path / "out"
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None
    ) as cluster:
        assert _sweep(scene, out, "--scheduler", cluster.scheduler_address) == 0
    assert [_numbers(r) for r in _rows(out)] == [_numbers(r) for r in _rows(first)]


def test_manifold_cases_write_their_loci_as_cusp_run_does(tmp_path):
    import csv

    scene = tmp_path / "m.toml"
    man = '[manifold]\nparameter = "mu"\nrange = [0.05, 0.5]\n'
    scene.write_text(BASE + man + '[sweep]\n"surface.mu" = [0.1, 0.6]\n', encoding="utf-8")
    out = tmp_path / "out"
    assert _sweep(scene, out, "--workers", "0") == 0
    ok, refused = _rows(out)
    assert (
        refused["status"] == "refused"
        and "does not hold [surface] mu = 0.6" in (refused["message"])
    )
    loci = pq.read_table(out / "loci.parquet").to_pylist()
    assert {r["index"] for r in loci} == {0} and ok["loci_points"] == sum(
        1 for r in loci if not r["event"]
    )
    plain = tmp_path / "plain.toml"
    plain.write_text(BASE + man, encoding="utf-8")
    assert cli.main(["run", str(plain), "--out", str(tmp_path / "r"), "--no-plots", "--quiet"]) == 0
    with open(tmp_path / "r" / "loci.csv", encoding="utf-8") as fh:
        table = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    assert len(table) == len(loci)
    for want, got in zip(table, loci):
        for col, text in want.items():
            value = got[col]
            if col == "event":
                assert value == text
            else:
                assert (value is None and text == "") or value == float(text), (col, text, value)


@pytest.mark.parametrize(
    ("more", "words"),
    [
        (["--workers", "-1"], "--workers = '-1'; allowed: an integer >= 0"),
        (["--chunk-size", "0"], "--chunk-size = '0'; allowed: an integer >= 1"),
    ],
)
def test_bad_options_exit_2(grid, tmp_path, capsys, more, words):
    scene, _ = grid
    assert _sweep(scene, tmp_path / "o", *more) == 2
    assert words in capsys.readouterr().err
    assert not (tmp_path / "o").exists()


def test_a_scene_without_sweep_is_refused(tmp_path, capsys):
    scene = tmp_path / "s.toml"
    scene.write_text(BASE, encoding="utf-8")
    assert _sweep(scene, tmp_path / "o") == 2
    assert "no [sweep] section" in capsys.readouterr().err


def test_cusp_run_runs_a_sweep_scene_as_written(grid, tmp_path):
    scene, out = grid
    assert cli.main(["run", str(scene), "--out", str(tmp_path / "r"), "--no-plots", "--quiet"]) == 0
    summary = json.loads((tmp_path / "r" / "summary.json").read_text(encoding="utf-8"))
    assert summary["points"]["C"]["g_T"] == _rows(out)[0]["g_C"]  # mu 0.1, F'_N 850 N


def test_a_second_sweep_into_a_directory_in_use_is_refused(grid, tmp_path, capsys):
    import fcntl

    scene, _ = grid
    out = tmp_path / "out"
    out.mkdir()
    fd = os.open(out / ".lock", os.O_RDWR | os.O_CREAT)
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)  # as a running sweep holds it
        assert _sweep(scene, out, "--workers", "0") == 2
    finally:
        os.close(fd)
    assert "another cusp sweep is writing into it" in capsys.readouterr().err
    assert not (out / "results.parquet").exists()


def test_cases_run_by_threads_of_one_worker_run_one_at_a_time(monkeypatch):
    """A Dask worker of several threads runs chunks side by side in one process; a case's
    warnings are recorded process-wide (warnings.catch_warnings) into its row's message, so
    two cases at once would take each other's warnings: they run one at a time."""
    import threading

    from cusp.app import _sweep_case, run

    active, most = [0], [0]
    guard = threading.Lock()
    barrier = threading.Barrier(4, timeout=5)

    def fake_run_scene(scene, plots):  # a slow case
        with guard:
            active[0] += 1
            most[0] = max(most[0], active[0])
        time.sleep(0.05)  # (the other threads would come in here if they could)
        with guard:
            active[0] -= 1
        raise run.NumericalFailure(f"case {scene.loading['normal_load']:g} stops here")

    monkeypatch.setattr(run, "run_scene", fake_run_scene)
    rows: dict[int, dict] = {}

    def one(i: int) -> None:
        data = {
            "surface": {"model": "rough-exponential", "sigma": 2.0, "nu": 0.3, "mu": 0.1},
            "loading": {"normal_load": 1000.0 + i, "max_slip": 0.34, "reduced_normal_load": 850.0},
        }
        barrier.wait()
        rows[i] = _sweep_case.run_case(i, f"k{i}", data, "t.toml")[0]

    threads = [threading.Thread(target=one, args=(i,)) for i in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert most[0] == 1
    assert {i: r["message"] for i, r in rows.items()} == {
        i: f"case {1000 + i} stops here" for i in range(4)
    }
