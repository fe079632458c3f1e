"""One case of a sweep, run as ``cusp run`` runs a scene (numbers only, no files), and the
row it gives in ``results.parquet``.

A chunk of cases (:func:`run_chunk`) is what a worker process or a Dask task runs: a
list of ``(index, key, data)``, the scene data of each case (:meth:`Sweep.case_data`).
A case never raises: a case the scene schema refuses is a row with status ``refused``, one
that fails numerically ``failed`` (the message is ``cusp run``'s), anything else
``error`` (a bug, named in the message).
"""

from __future__ import annotations

import functools
import math
import threading
import time
import warnings
from typing import Any

__all__ = ["POINT_COLUMNS", "ENERGY_COLUMNS", "run_case", "run_chunk", "result_columns"]

#: the columns of a case's points, named as in loci.csv (cusp.models.manifold.CSV_COLUMNS)
#: with the stick areas of C and D too: column -> (point, quantity)
POINT_COLUMNS = {
    **{f"{q}_{x}": (x, q) for x in "ABCD" for q in ("g", "F")},
    **{f"A_SL_{x}": (x, "A_SL") for x in "ABCD"},
}
#: the energy columns (as in loci.csv) -> the key of ContactLossResult.energy, and their
#: error bounds (named as in cusp.models.manifold.LOCI_UNITS)
ENERGY_COLUMNS = {"snap_back_energy": "snap_back", "snap_through_energy": "snap_through"}
ENERGY_ERRORS = {"snap_back_error": "snap_back", "snap_through_error": "snap_through"}
STATUSES = ("ok", "refused", "failed", "error")
_QUANTITY = {"g": "g_T", "F": "F_T", "A_SL": "A_SL"}


def result_columns() -> list[tuple[str, str]]:
    """The columns every row has after the varied fields: (name, "float" | "str" | "int")."""
    cols = [("index", "int"), ("case", "str"), ("status", "str"), ("message", "str")]
    cols += [("mu", "float"), ("reduced_normal_load", "float")]
    cols += [(c, "float") for c in POINT_COLUMNS]
    cols += [(c, "float") for c in ENERGY_COLUMNS]
    cols += [(f"{c}_error", "float") for c in POINT_COLUMNS]
    cols += [(c, "float") for c in ENERGY_ERRORS]
    cols += [("loci_points", "int"), ("rtol", "float"), ("version", "str"), ("seconds", "float")]
    return cols


def _finite(value: Any) -> float | None:
    """A number for a cell (None: no value; a NaN never reaches the results)."""
    if value is None:
        return None
    x = float(value)
    return x if math.isfinite(x) else None


def _result_cells(result: Any) -> dict[str, Any]:
    """The points, energies and their error bounds of a traced path."""
    row: dict[str, Any] = {}
    for col, (point, q) in POINT_COLUMNS.items():
        pt = result.points.get(point)
        err = result.point_errors.get(point) or {}
        row[col] = None if pt is None else _finite(pt[_QUANTITY[q]])
        row[f"{col}_error"] = None if pt is None else _finite(err.get(_QUANTITY[q]))
    for col, key in ENERGY_COLUMNS.items():
        row[col] = _finite(result.energy.get(key))
    for col, key in ENERGY_ERRORS.items():
        row[col] = _finite(result.energy_error.get(key))
    return row


@functools.cache
def _version() -> str:
    """The installed version of cusp (read once a process)."""
    from .run import _version as version

    return version()


#: one case at a time in a process: a case's warnings are recorded by
#: ``warnings.catch_warnings``, which swaps process-wide state, so two cases run by two
#: threads of one worker (a Dask worker of several threads) would take each other's
#: warnings into their rows (the GIL runs pure-Python cases one at a time anyway)
_ONE_CASE = threading.Lock()


def run_case(index: int, key: str, data: dict[str, Any], source: str) -> tuple[dict, list]:
    """Case ``index`` (scene ``data``, key ``key``) run as ``cusp run --no-plots`` runs a
    scene: its row, and the rows of its loci (``[manifold]`` scenes; else []). Cases run
    one at a time in a process (:data:`_ONE_CASE`)."""
    with _ONE_CASE:
        return _run_case(index, key, data, source)


def _run_case(index: int, key: str, data: dict[str, Any], source: str) -> tuple[dict, list]:
    import numpy as np

    from .run import NumericalFailure, run_scene
    from .scene import SceneError, scene_from_data

    t0 = time.perf_counter()
    row: dict[str, Any] = {"index": index, "case": key, "version": _version()}
    loci_rows: list[dict[str, Any]] = []
    try:
        with warnings.catch_warnings(record=True) as caught, np.errstate(all="ignore"):
            warnings.simplefilter("always")
            scene = scene_from_data(data, source=f"{source} case {index}")
            run, _ = run_scene(scene, plots=False)
        res = run.cases[0]
        row.update(mu=_finite(res.mu), reduced_normal_load=_finite(res.load))
        row.update(_result_cells(res.result))
        row["rtol"] = float(run.options.rtol)
        notes = [*run.notes, *res.result.messages]
        notes += sorted({f"{w.category.__name__}: {w.message}" for w in caught})
        if run.loci is not None:
            loci_rows = _loci_rows(index, key, run.loci)
            row["loci_points"] = len(run.loci.columns[run.loci.parameter])
            notes += [f"loci: {m}" for m in run.loci.messages]
        row.update(status="ok", message="; ".join(notes))
    except SceneError as exc:
        row.update(status="refused", message=" ".join(str(exc).split()))
    except NumericalFailure as exc:
        row.update(status="failed", message=" ".join(str(exc).split()))
    except Exception as exc:  # a bug: named, and the sweep goes on
        text = " ".join(str(exc).split())
        row.update(status="error", message=f"unexpected {type(exc).__name__}: {text}")
    row["seconds"] = time.perf_counter() - t0
    return row, loci_rows


def _loci_rows(index: int, key: str, loci: Any) -> list[dict[str, Any]]:
    """The rows of the case's loci.csv, with the case's index and key."""
    from cusp.models.manifold import CSV_COLUMNS

    from .loci import loci_rows

    cols = [c for c in CSV_COLUMNS if c != "event"]
    out = []
    for values, event in loci_rows(loci):
        cells = {c: _finite(v) for c, v in zip(cols, values)}
        out.append({"index": index, "case": key, **cells, "event": event})
    return out


def run_chunk(cases: list[tuple[int, str, dict]], source: str) -> tuple[list, list]:
    """Run a chunk of cases (see the module docstring): their rows and their loci rows."""
    rows, loci = [], []
    for index, key, data in cases:
        row, more = run_case(index, key, data, source)
        rows.append(row)
        loci += more
    return rows, loci
