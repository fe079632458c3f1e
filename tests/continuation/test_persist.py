"""Saving and loading results (:meth:`Branch.save`, :meth:`Diagram.save`,
:func:`cusp.continuation.load`): one ``.npz`` that numpy reads alone, read back bit for bit,
written atomically; the refusals of a file that is not one, a newer format, a truncated or
damaged file.

Oracles: the objects themselves (a round trip must give back the same bits); the cusp
normal form's folds at b = ±2/(3√3) (closed form: x³ − x − b = 0 and 3x² − 1 = 0 give
x = ∓1/√3, b = ±2/(3√3) = ±0.3849001794597505).
"""

from __future__ import annotations

import json
import math
import sys
import zipfile

import numpy as np
import pytest

from cusp.continuation import (
    Branch,
    Diagram,
    Problem,
    ResultsFileError,
    diagram,
    fold_curve,
    load,
    point_locus,
    trace,
)
from cusp.continuation.results import _persist
from cusp.examples import cusp_normal_form, lorenz, pp2
from cusp.examples.symmetric import chafee_infante

B_FOLD = 2.0 / (3.0 * math.sqrt(3.0))  # closed form (module docstring)


@pytest.fixture(scope="module")
def cusp_branch() -> Branch:
    return cusp_normal_form().trace()


def _round_trip(obj, path):
    saved = obj.save(path)
    assert saved == path and path.is_file()
    return load(path)


def test_branch_round_trip_bit_for_bit(cusp_branch, tmp_path, same_bits):
    """Columns, tangents, arclength, statistics, special points (with their enums and
    details), status, message, info (options, resume data) and kinds come back the same."""
    back = _round_trip(cusp_branch, tmp_path / "cusp.npz")
    same_bits(cusp_branch, back)
    folds = back.special("fold")
    assert [type(sp.kind).__name__ for sp in folds] == ["Kind", "Kind"]
    assert type(back.status).__name__ == "Status" and back.status == "bound"
    # the folds are the closed form's (to the solver's 1e-12), read from the file
    assert [sp.values["b"] for sp in folds] == pytest.approx([B_FOLD, -B_FOLD], abs=1e-12)


@pytest.mark.parametrize("name", ["branch_points", "fold_curve", "stability", "locus"])
def test_other_results_round_trip(name, tmp_path, same_bits):
    """A branch with branch points (switching data: arrays and tuples in details), a fold
    curve (traced both ways, with a cusp), a branch with eigenvalues (complex, per row) and
    Hopf points, and a locus of fold points all come back bit for bit."""
    ex = cusp_normal_form()
    if name == "branch_points":
        obj = pp2().trace()
        assert obj.special("branch_point")
    elif name == "fold_curve":
        br = ex.trace()
        obj = fold_curve(
            ex.problem, br.special("fold")[0], free=("b", "a"), bounds={"a": (0.0, 2.0)}
        )
        assert obj.special("cusp")
    elif name == "stability":
        lz = lorenz()  # declared a vector field (M = I), on C+ from rho = 2
        prob = Problem(
            lz.residual,
            list(lz.unknowns),
            {**lz.params, "rho": 2.0},
            jacobian=lz.jacobian,
            mass=True,
        )
        x0 = math.sqrt(8.0 / 3.0)  # C+ at rho = 2: x = y = sqrt(beta (rho - 1)), z = rho - 1
        obj = trace(prob, [x0, x0, 1.0], free="rho", bounds={"rho": (2.0, 30.0)}, stability=True)
        assert obj.special("hopf") and np.iscomplexobj(obj.eigenvalues[0])
    else:
        br = ex.trace()
        obj = point_locus(
            ex.problem, br.special("fold")[0], free=("b", "a"), bounds={"a": (0.5, 2.0)}
        )
    same_bits(obj, _round_trip(obj, tmp_path / f"{name}.npz"))


def test_diagram_round_trip(tmp_path, same_bits):
    """A whole diagram (branches, branch points, deflation records) comes back bit for bit."""
    ex = chafee_infante(6, lam_max=10.0)
    dg = diagram(ex.problem, ex.u0, free=ex.free, bounds=ex.bounds)
    assert len(dg.branches) > 1 and dg.points
    back = _round_trip(dg, tmp_path / "diagram.npz")
    assert isinstance(back, Diagram)
    same_bits(dg, back)


def test_non_finite_floats_keep_their_bits_in_strict_json(cusp_branch, tmp_path, same_bits):
    """NaN (both signs), infinities and complex numbers holding them, in a branch's info,
    come back with the same bits; metadata.json stays strict JSON (no NaN literal)."""
    import struct

    negative_nan = struct.unpack("<d", struct.pack("<Q", 0xFFF8000000000000))[0]
    odd = Branch(
        {k: cusp_branch[k] for k in cusp_branch.keys()},
        variables=cusp_branch.variables,
        s=cusp_branch.s,
        tangents=cusp_branch.tangents,
        special_points=list(cusp_branch.special_points),
        status=cusp_branch.status,
        message=cusp_branch.message,
        stats=cusp_branch.stats,
        info={"values": [math.nan, negative_nan, math.inf, -math.inf, complex(math.nan, 1.0)]},
    )
    path = odd.save(tmp_path / "odd.npz")
    same_bits(odd, load(path))
    with np.load(path, allow_pickle=False) as f:
        json.loads(f["metadata.json"], parse_constant=lambda c: pytest.fail(f"JSON has {c}"))


def test_numpy_alone_reads_the_file(cusp_branch, tmp_path):
    """``np.load(path, allow_pickle=False)`` reads every array and the JSON metadata: the
    format, its version, the type, the versions and the options."""
    path = cusp_branch.save(tmp_path / "b.npz")
    with np.load(path, allow_pickle=False) as f:
        assert "metadata.json" in f.files
        assert np.array_equal(f["columns/b"], cusp_branch["b"])
        assert np.array_equal(f["tangents"], cusp_branch.tangents)
        assert np.array_equal(f["stats/ds"], cusp_branch.stats["ds"])
        meta = json.loads(f["metadata.json"])
        arrays = [name for name in f.files if name != "metadata.json"]
        assert all(isinstance(f[name], np.ndarray) for name in arrays)
    assert meta["format"] == "cusp-results" and meta["format_version"] == 1
    assert meta["type"] == "Branch" and meta["cusp_version"] == _persist.cusp_version()
    options = meta["data"]["$branch"]["info"]["options"]
    assert options["max_steps"] == 5000 and options["rtol"] == 1e-3


# --- refusals ---------------------------------------------------------------------------------


def _refused(path, fragment: str) -> None:
    with pytest.raises(ResultsFileError, match=fragment) as err:
        load(path)
    assert str(path) in str(err.value) and err.value.path == path


def test_refuses_a_file_that_is_not_a_zip(tmp_path):
    path = tmp_path / "notes.npz"
    path.write_text("x, b\n1, 2\n")
    _refused(path, "not a zip archive")


def test_refuses_a_plain_numpy_archive(tmp_path):
    path = tmp_path / "plain.npz"
    np.savez(path, x=np.arange(3.0))
    _refused(path, "without metadata.json: not a cusp results file")


def test_refuses_a_foreign_metadata_member(tmp_path):
    path = tmp_path / "foreign.npz"
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("metadata.json", json.dumps({"format": "something-else"}))
    _refused(path, "does not say format 'cusp-results'")


@pytest.mark.parametrize("keep", [0.5, 0.95])
def test_refuses_a_truncated_file(cusp_branch, tmp_path, keep):
    path = cusp_branch.save(tmp_path / "b.npz")
    data = path.read_bytes()
    path.write_bytes(data[: int(keep * len(data))])
    _refused(path, "truncated or damaged")


def test_refuses_a_damaged_member(cusp_branch, tmp_path):
    """A flipped byte inside an array fails the zip's CRC check."""
    path = cusp_branch.save(tmp_path / "b.npz")
    data = bytearray(path.read_bytes())
    k = data.index(b"columns/x.npy") + 200  # inside that member's data
    data[k] ^= 0xFF
    path.write_bytes(bytes(data))
    _refused(path, "truncated or damaged")


def test_refuses_a_newer_format(cusp_branch, tmp_path):
    path = cusp_branch.save(tmp_path / "b.npz")
    newer = tmp_path / "newer.npz"
    with zipfile.ZipFile(path) as src, zipfile.ZipFile(newer, "w") as dst:
        for item in src.infolist():
            data = src.read(item.filename)
            if item.filename == "metadata.json":
                meta = json.loads(data)
                meta["format_version"] = 2
                data = json.dumps(meta).encode()
            dst.writestr(item, data)
    _refused(newer, "format version 2 .* newer than this cusp .* upgrade cusp")


def test_a_missing_file_is_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError):
        load(tmp_path / "absent.npz")


# --- atomic writes ------------------------------------------------------------------------------


def test_a_path_that_cannot_be_written_names_itself(cusp_branch, tmp_path):
    """The error names the path the user gave (or its missing directory), not the temporary
    file beside it, and nothing is left behind."""
    with pytest.raises(ValueError, match="path must name a results file .*got ''"):
        cusp_branch.save("")
    with pytest.raises(IsADirectoryError, match="a directory.*" + tmp_path.name):
        cusp_branch.save(tmp_path)
    missing = tmp_path / "absent" / "b.npz"
    with pytest.raises(FileNotFoundError, match="no such directory.*absent'") as info:
        cusp_branch.save(missing)
    assert info.value.filename == str(missing.parent)
    assert list(tmp_path.iterdir()) == []


def test_a_failed_save_leaves_the_old_file(cusp_branch, tmp_path, monkeypatch):
    """A save that fails half-way leaves the file that was there whole, and no temporary
    file behind."""
    path = cusp_branch.save(tmp_path / "b.npz")
    before = path.read_bytes()
    calls = []

    def failing(member, array, allow_pickle):
        calls.append(1)
        if len(calls) == 3:
            raise OSError("disk full")
        return np.lib.format.write_array.__wrapped__(member, array, allow_pickle=allow_pickle)

    failing.__wrapped__ = np.lib.format.write_array  # type: ignore[attr-defined]
    monkeypatch.setattr(np.lib.format, "write_array", failing)
    with pytest.raises(OSError, match="disk full"):
        cusp_branch.save(path)
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["b.npz"]


def test_an_unsavable_detail_is_refused_by_name(cusp_branch, tmp_path):
    """A value the format cannot hold (here an arbitrary object in a special point's
    details) is a TypeError naming where it is; no file is written."""
    sp = cusp_branch.special("fold")[0]
    odd = Branch(
        {k: cusp_branch[k] for k in cusp_branch.keys()},
        variables=cusp_branch.variables,
        s=cusp_branch.s,
        tangents=cusp_branch.tangents,
        special_points=[type(sp)(**{**sp.__dict__, "details": {"thing": object()}})],
        status=cusp_branch.status,
        message="",
        stats=cusp_branch.stats,
    )
    with pytest.raises(TypeError, match="special_points/0/details/thing: a object cannot"):
        odd.save(tmp_path / "odd.npz")
    assert list(tmp_path.iterdir()) == []


# --- pandas ---------------------------------------------------------------------------------------


def test_to_pandas(cusp_branch):
    pd = pytest.importorskip("pandas")
    df = cusp_branch.to_pandas()
    assert isinstance(df, pd.DataFrame) and len(df) == len(cusp_branch)
    assert list(df.columns[:4]) == ["x", "b", "a", "s"]
    assert np.array_equal(df["b"].to_numpy(), cusp_branch["b"])
    assert np.array_equal(
        df["stats.newton_iterations"].to_numpy(), cusp_branch.stats["newton_iterations"]
    )
    rows = [i for i, kinds in enumerate(df["special"]) if "fold" in kinds]
    assert rows == [sp.index for sp in cusp_branch.special("fold")]


def test_to_pandas_without_pandas_names_the_extra(cusp_branch, monkeypatch):
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas raises ImportError
    with pytest.raises(ImportError, match=r"cusp\[pandas\]"):
        cusp_branch.to_pandas()


def test_trace_records_the_options(tmp_path):
    """A saved branch says how it was computed: every option (a tolerance that follows
    rtol as None)."""
    ex = cusp_normal_form()
    br = trace(ex.problem, ex.u0, free="b", bounds=ex.bounds, rtol=1e-6, ds_max=0.2)
    options = load(br.save(tmp_path / "b.npz")).info["options"]
    assert options["rtol"] == 1e-6 and options["ds_max"] == 0.2 and options["tol"] is None
