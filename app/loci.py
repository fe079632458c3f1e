"""The loci of a ``[manifold]`` scene: traced (:func:`cusp.models.manifold.point_loci`),
written as ``loci.csv`` and summarised in ``summary.json``.

``loci.csv``: a comment line (``#``) with the unit of every column, then the header
:data:`cusp.models.manifold.CSV_COLUMNS`, then one row per traced point of the loci and one
per located event (named in ``event``, empty on traced rows), in the order of the
parameter. A point that does not exist at a row (C below the C boundary, ...) leaves its
cells empty; numbers are written with ``repr(float)``, so they read back exactly.
"""

from __future__ import annotations

import csv
import io
import math
from typing import Any

from .scene import MANIFOLD_PARAMETERS, Scene, SceneError

__all__ = ["trace_loci", "loci_csv", "manifold_summary", "report"]


def trace_loci(scene: Scene) -> Any:
    """The loci of the scene's [manifold] section, from the case it starts from, at the
    scene's ``[solver] rtol`` (:func:`cusp.app.cases.loci_options`)."""
    from cusp.models.errors import ModelParameterError
    from cusp.models.manifold import point_loci

    from .cases import build_body, loci_options, make_model

    man = scene.manifold
    assert man is not None
    mu, load = man["start"]
    model = make_model(scene, build_body(scene, mu), load)
    try:
        return point_loci(model, man["parameter"], span=man["range"], options=loci_options(scene))
    except ModelParameterError as exc:
        raise SceneError(f"{scene.source}: [manifold] {exc}") from None


def _units() -> dict[str, str]:
    """The unit of every column but ``event`` ("1": a pure number)."""
    from cusp.models.manifold import CSV_COLUMNS, LOCI_UNITS

    return {c: LOCI_UNITS.get(c) or "1" for c in CSV_COLUMNS if c != "event"}


def _cell(value: Any) -> str:
    x = float(value)
    return "" if math.isnan(x) else repr(x)


def loci_rows(loci: Any) -> list[tuple[list[float], str]]:
    """The rows of ``loci.csv`` (values of every column but ``event``, and the event name
    or ""), traced rows and event rows together in the order of the parameter."""
    cols = list(_units())
    n = len(loci.columns[cols[0]])
    rows = [([float(loci.columns[c][i]) for c in cols], "") for i in range(n)]
    rows += [([float(ev.get(c, math.nan)) for c in cols], ev["event"]) for ev in loci.events]
    at = cols.index(loci.parameter)
    rows.sort(key=lambda row: (row[0][at], row[1] != ""))  # an event after a row at its value
    return rows


def loci_csv(loci: Any) -> str:
    """The text of ``loci.csv`` (see the module docstring)."""
    units = _units()
    buf = io.StringIO()
    buf.write(
        "# units: "
        + ", ".join(f"{c} [{u}]" for c, u in units.items())
        + "; event: the located event of the row (empty: a traced row); an empty cell: the "
        "point does not exist there\n"
    )
    w = csv.writer(buf, lineterminator="\n")
    w.writerow([*units, "event"])
    for values, event in loci_rows(loci):
        w.writerow([*(_cell(v) for v in values), event])
    return buf.getvalue()


def _number(value: Any) -> float | None:
    x = float(value)
    return None if math.isnan(x) else x


def manifold_summary(scene: Scene, loci: Any) -> dict[str, Any]:
    """The ``manifold`` entry of ``summary.json``: the parameter, its range, the case the
    loci start from, the number of traced points, the events (values, None where a point
    does not exist), the units and how each locus ended."""
    man = scene.manifold
    assert man is not None
    units = _units()
    mu, load = man["start"]
    return {
        "parameter": loci.parameter,
        "range": {"value": list(man["range"]), "unit": MANIFOLD_PARAMETERS[loci.parameter]},
        "start": {
            "mu": {"value": mu, "unit": ""},
            "reduced_normal_load": {"value": load, "unit": "N"},
        },
        "points": len(loci.columns[loci.parameter]),
        "events": [
            {"event": ev["event"], "values": {c: _number(ev.get(c, math.nan)) for c in units}}
            for ev in loci.events
        ],
        "units": {c: ("" if u == "1" else u) for c, u in units.items()},
        "messages": list(loci.messages),
    }


def report(scene: Scene, loci: Any) -> None:
    """The loci in a few lines of ``cusp run``'s report."""
    param = loci.parameter
    unit = MANIFOLD_PARAMETERS[param]
    u = f" {unit}" if unit else ""
    lo, hi = scene.manifold["range"] if scene.manifold else (math.nan, math.nan)
    print(f"  loci in {param} over [{lo:g}, {hi:g}]{u}: {len(loci.columns[param])} points")
    for ev in loci.events:
        print(f"    event {ev['event']}: {param} = {ev[param]:.10g}{u}")
    for msg in loci.messages:
        print(f"    note: {msg}")
