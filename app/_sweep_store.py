"""The results of a sweep on disk: Parquet datasets written a chunk at a time.

``DIR/results.parquet/`` is a directory of part files, one per chunk of cases, each
written whole to a hidden temporary file (pyarrow ignores names starting with ``.``), synced
and renamed into place: a part is there complete or not at all. ``DIR/loci.parquet/``
(scenes with ``[manifold]``) holds the loci of the same chunks; a chunk's loci part is
written before its results part, so a results part means both are complete. Read either
with ``pyarrow.parquet.read_table(path)`` or ``pandas.read_parquet(path)``.

A case is done when its row (``index`` and ``case``, the key of its scene data) is in a
results part; a rerun computes the others only. A part holding a case of another sweep (an
index beyond the sweep, or another key at an index) is refused: the directory belongs to a
different scene.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path
from typing import Any

__all__ = ["RESULTS", "LOCI", "require_pyarrow", "results_schema", "done_cases", "write_part"]

RESULTS = "results.parquet"
LOCI = "loci.parquet"


class StoreError(ValueError):
    """The output directory holds results that are not this sweep's (one-line message)."""


def require_pyarrow() -> Any:
    """pyarrow, or an ImportError naming the extra that installs it."""
    try:
        import pyarrow
        import pyarrow.parquet  # noqa: F401
    except ImportError as exc:
        raise ImportError(
            "cusp sweep writes Parquet with pyarrow, which is not installed; install it with "
            "pip install 'cusp[sweep]'"
        ) from exc
    return pyarrow


def results_schema(fields: list[tuple[str, bool]]) -> Any:
    """The schema of ``results.parquet``: the varied fields (name, numeric?), then
    :func:`cusp.app._sweep_case.result_columns`."""
    pa = require_pyarrow()
    from ._sweep_case import result_columns

    types = {"float": pa.float64(), "int": pa.int64(), "str": pa.string()}
    cols = [(name, pa.float64() if numeric else pa.string()) for name, numeric in fields]
    cols += [(name, types[kind]) for name, kind in result_columns()]
    return pa.schema(cols)


def loci_schema() -> Any:
    """The schema of ``loci.parquet``: ``index``, ``case``, the columns of loci.csv."""
    pa = require_pyarrow()
    from cusp.models.manifold import CSV_COLUMNS

    cols = [("index", pa.int64()), ("case", pa.string())]
    cols += [(c, pa.string() if c == "event" else pa.float64()) for c in CSV_COLUMNS]
    return pa.schema(cols)


def done_cases(out: Path, keys: list[str]) -> set[int]:
    """The indices of the cases already in ``out/results.parquet`` (``keys``: the key of
    every case of this sweep); raises :class:`StoreError` for a row of another sweep."""
    require_pyarrow()
    import pyarrow.parquet as pq

    root = out / RESULTS
    parts = sorted(p for p in root.glob("*.parquet") if not p.name.startswith((".", "_")))
    done: set[int] = set()
    for part in parts:
        table = pq.read_table(part, columns=["index", "case"])
        for index, key in zip(table["index"].to_pylist(), table["case"].to_pylist()):
            if not 0 <= index < len(keys) or keys[index] != key:
                raise StoreError(
                    f"{root} holds case {index} of another sweep (part {part.name}: its scene "
                    "data differ from this scene's); allowed: the same scene and [sweep], or "
                    "another --out"
                )
            if index in done:
                raise StoreError(f"{root} holds case {index} twice (part {part.name})")
            done.add(index)
    return done


def prune_loci(out: Path) -> None:
    """Remove the loci parts of chunks whose results part was never written (a killed run):
    their cases are computed again, in chunks of other names."""
    have = {p.name for p in (out / RESULTS).glob("*.parquet")}
    for part in (out / LOCI).glob("*.parquet"):
        if part.name not in have:
            part.unlink()


def part_name(indices: list[int]) -> str:
    """The file name of the part of a chunk: its first case and a digest of its cases."""
    digest = hashlib.sha256(",".join(map(str, indices)).encode()).hexdigest()[:8]
    return f"part-{indices[0]:09d}-{digest}.parquet"


def _write_table(table: Any, path: Path) -> None:
    """Write ``table`` to ``path`` atomically (a hidden file, synced, then renamed)."""
    import pyarrow.parquet as pq

    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.parent / f".{path.name}.{os.getpid()}.tmp"
    try:
        with open(tmp, "wb") as fh:
            pq.write_table(table, fh)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()


def write_part(out: Path, schema: Any, rows: list[dict], loci: list[dict] | None) -> Path:
    """Write the rows of one chunk (and its loci rows, for a [manifold] scene) as parts of
    the datasets; returns the results part."""
    pa = require_pyarrow()
    name = part_name([r["index"] for r in rows])
    if loci is not None:
        _write_table(pa.Table.from_pylist(loci, schema=loci_schema()), out / LOCI / name)
    path = out / RESULTS / name
    _write_table(pa.Table.from_pylist(rows, schema=schema), path)
    return path
