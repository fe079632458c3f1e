"""The ``[sweep]`` section of a scene: which scene fields ``cusp sweep`` varies, and the
cases it runs.

Two forms (not mixed)::

    [sweep]                                   # every combination of the listed values
    "surface.mu" = [0.05, 0.1, 0.2]           # a list of values
    "loading.reduced_normal_load" = { start = 500.0, stop = 950.0, num = 10 }
                                              # num values from start to stop (both
                                              #  included), spacing = "linear" (default)
                                              #  or "log" (start, stop > 0)

    [sweep]
    cases = "cases.csv"                       # one case a row; the header names the
                                              #  fields ("surface.mu,loading.max_slip");
                                              #  a path relative to the scene file

A field is a dotted name ``section.key`` of a number (or ``options.area_reading``) the
scene's sections hold: the ``[surface]`` parameters of the scene's model, ``[loading]``
``normal_load``, ``max_slip``, ``reduced_normal_load``, ``[options] area_reading``,
``[solver] rtol``, ``ds_max``, ``tol``. Each case is the scene with those fields replaced,
checked by the scene schema when it runs (a case the schema refuses is a row with status
``refused``; the section itself is checked here, before anything runs).
"""

from __future__ import annotations

import copy
import csv
import hashlib
import io
import itertools
import json
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, NoReturn

from .limits import show

__all__ = ["Sweep", "check_sweep", "MAX_SWEEP_CASES", "MAX_VALUES", "MAX_CASES_FILE_BYTES"]

#: the most cases of a sweep
MAX_SWEEP_CASES = 1_000_000
#: the most values a list or a range of one field may give
MAX_VALUES = 100_000
#: the largest cases file [bytes]
MAX_CASES_FILE_BYTES = 64 * 1024 * 1024
_RANGE_KEYS = ("start", "stop", "num", "spacing")

Fail = Callable[[str, str], NoReturn]


@dataclass(frozen=True)
class Sweep:
    """A checked ``[sweep]``: the varied ``fields`` (dotted names), the ``values`` of each
    case (a tuple per case, in the order of ``fields``), where they came from (``"grid"``
    or the cases file), and the scene's own data without ``[sweep]`` (``base``)."""

    fields: tuple[str, ...]
    values: tuple[tuple[Any, ...], ...]
    origin: str
    base: dict[str, Any]

    def __len__(self) -> int:
        return len(self.values)

    def case_data(self, index: int) -> dict[str, Any]:
        """The scene data of case ``index``: the base with the case's fields replaced."""
        data = copy.deepcopy(self.base)
        for name, value in zip(self.fields, self.values[index]):
            section, key = name.split(".", 1)
            data.setdefault(section, {})[key] = value
        return data

    def numeric(self, name: str) -> bool:
        """Are all values of field ``name`` numbers (else the results hold it as text)?"""
        at = self.fields.index(name)
        return all(isinstance(v[at], (int, float)) for v in self.values)


def case_key(data: Mapping[str, Any]) -> str:
    """The key of a case: 16 hex digits of the SHA-256 of its scene data (canonical JSON;
    floats by their shortest repr, so a case keeps its key across runs)."""
    text = json.dumps(data, sort_keys=True, ensure_ascii=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def check_sweep(
    data: dict[str, Any],
    fail: Fail,
    sections: Mapping[str, set[str]],
    surface: dict[str, Any],
    loading: dict[str, Any],
    *,
    base_dir: Path | None = None,
) -> Sweep:
    """Check the ``[sweep]`` table of scene ``data`` (``fail(what, allowed)`` raises the
    scene's error; ``sections``: the keys of the scene's sections; ``surface``,
    ``loading``: the checked [surface] and [loading]; ``base_dir``: where a cases file is
    looked for). A field the scene lists several values of must be varied here (a case is
    one path)."""
    from cusp.models import registry

    allowed = {s: sections[s] for s in ("loading", "options", "solver")}
    allowed["surface"] = set(registry.body_entry(surface["model"]).parameters)
    names = sorted(f"{s}.{k}" for s, keys in allowed.items() for k in keys)
    raw = data["sweep"]
    what_fields = f"dotted names of the scene's fields: {', '.join(names)}"
    if not raw:
        fail("[sweep] is empty", f"fields to vary ({what_fields}) or cases = 'FILE.csv'")
    if "cases" in raw:
        if len(raw) > 1:
            other = sorted(k for k in raw if k != "cases")[0]
            fail(
                f"[sweep] cases and {show(other)} together",
                "either cases = 'FILE.csv' or fields with values",
            )
        fields, values = _read_cases(raw["cases"], fail, names, base_dir)
        origin = str(raw["cases"])
    else:
        for name in raw:
            _check_field(name, fail, names, what_fields)
        fields = tuple(raw)
        axes = [_axis(name, raw[name], fail) for name in fields]
        n = math.prod(len(a) for a in axes)
        if n > MAX_SWEEP_CASES:
            fail(f"[sweep] gives {n} cases", f"at most {MAX_SWEEP_CASES}")
        values = tuple(itertools.product(*axes))
        origin = "grid"
    _check_listed(fields, surface, loading, fail)
    plain = {k: v for k, v in data.items() if k != "sweep"}
    return Sweep(tuple(fields), values, origin, plain)


def _check_listed(fields, surface: dict, loading: dict, fail: Fail) -> None:
    """A field the scene lists several values of is varied by the sweep."""
    for name, value in (
        ("surface.mu", surface.get("mu")),
        ("loading.reduced_normal_load", loading["reduced_normal_load"]),
    ):
        if isinstance(value, list) and len(value) > 1 and name not in fields:
            section, key = name.split(".", 1)
            fail(
                f"[{section}] {key} lists several values but [sweep] does not vary {show(name)}",
                f"one value in [{section}] {key}, or its values in [sweep] {show(name)}",
            )


def _check_field(name: str, fail: Fail, names: list[str], what: str) -> None:
    if name not in names:
        fail(f"[sweep] unknown field {show(name)}", what)


def _value(name: str, value: Any, fail: Fail) -> Any:
    """One value of a field: a finite number or a string."""
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        fail(
            f"[sweep] {show(name)} holds {show(value)} ({type(value).__name__})",
            "numbers (or strings for options.area_reading)",
        )
    if isinstance(value, float) and not math.isfinite(value):
        fail(f"[sweep] {show(name)} holds {show(value)}", "finite numbers")
    return value


def _axis(name: str, spec: Any, fail: Fail) -> list[Any]:
    """The values of one field: a list, or a range table."""
    if isinstance(spec, list):
        if not spec:
            fail(f"[sweep] {show(name)} = []", "a non-empty list of values, or a range table")
        if len(spec) > MAX_VALUES:
            fail(f"[sweep] {show(name)} lists {len(spec)} values", f"at most {MAX_VALUES}")
        return [_value(name, v, fail) for v in spec]
    if isinstance(spec, dict):
        return _range(name, spec, fail)
    fail(
        f"[sweep] {show(name)} = {show(spec)}",
        "a list of values, or { start, stop, num, spacing = 'linear' | 'log' }",
    )


def _range(name: str, spec: dict[str, Any], fail: Fail) -> list[float]:
    """``{start, stop, num, spacing}``: num values from start to stop, both included."""
    import numpy as np

    unknown = sorted(set(spec) - set(_RANGE_KEYS))
    if unknown:
        fail(f"[sweep] {show(name)} has the key {show(unknown[0])}", ", ".join(_RANGE_KEYS))
    for key in ("start", "stop", "num"):
        if key not in spec:
            fail(f"[sweep] {show(name)} misses {key}", "a range needs start, stop and num")
    start, stop, num = spec["start"], spec["stop"], spec["num"]
    for key, v in (("start", start), ("stop", stop)):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            fail(f"[sweep] {show(name)} {key} = {show(v)}", "a finite number")
    if isinstance(num, bool) or not isinstance(num, int) or not 1 <= num <= MAX_VALUES:
        fail(f"[sweep] {show(name)} num = {show(num)}", f"an integer from 1 to {MAX_VALUES}")
    spacing = spec.get("spacing", "linear")
    if spacing not in ("linear", "log"):
        fail(f"[sweep] {show(name)} spacing = {show(spacing)}", "'linear' or 'log'")
    if spacing == "log" and not (start > 0 and stop > 0):
        fail(
            f"[sweep] {show(name)} spacing = 'log' with start = {show(start)}, stop = {show(stop)}",
            "start > 0 and stop > 0 for log spacing",
        )
    if num == 1:
        return [float(start)]
    space = np.geomspace if spacing == "log" else np.linspace
    values = [float(v) for v in space(float(start), float(stop), num)]
    values[0], values[-1] = float(start), float(stop)
    return values


def _read_cases(
    file: Any, fail: Fail, names: list[str], base_dir: Path | None
) -> tuple[tuple[str, ...], tuple[tuple[Any, ...], ...]]:
    """The fields and the rows of a cases file (CSV, a header of dotted field names)."""
    if not isinstance(file, str) or not file:
        fail(f"[sweep] cases = {show(file)}", "the path of a CSV file (a string)")
    path = Path(file) if base_dir is None else base_dir / file
    try:
        with open(path, "rb") as fh:
            raw = fh.read(MAX_CASES_FILE_BYTES + 1)
    except FileNotFoundError:
        fail(f"[sweep] cases = {show(file)}: no such file ({path})", "an existing CSV file")
    except OSError as exc:
        fail(f"[sweep] cases = {show(file)}: cannot read it ({exc.strerror})", "a CSV file")
    if len(raw) > MAX_CASES_FILE_BYTES:
        fail(f"[sweep] cases = {show(file)} is too large", f"at most {MAX_CASES_FILE_BYTES} bytes")
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        fail(f"[sweep] cases = {show(file)} is not UTF-8 text", "a UTF-8 CSV file")
    rows = [r for r in csv.reader(io.StringIO(text)) if r and not r[0].startswith("#")]
    if len(rows) < 2:
        fail(f"[sweep] cases = {show(file)} has no case", "a header of fields, then a case a row")
    header = tuple(c.strip() for c in rows[0])
    for name in header:
        if name not in names:
            fail(
                f"[sweep] cases = {show(file)}: unknown column {show(name)}",
                f"columns named by the scene's fields: {', '.join(names)}",
            )
    if len(set(header)) < len(header):
        fail(f"[sweep] cases = {show(file)}: a column named twice", "each field once")
    if len(rows) - 1 > MAX_SWEEP_CASES:
        fail(
            f"[sweep] cases = {show(file)} has {len(rows) - 1} cases", f"at most {MAX_SWEEP_CASES}"
        )
    return header, tuple(_csv_row(file, i, row, header, fail) for i, row in enumerate(rows[1:]))


def _csv_row(file: str, i: int, row: list[str], header: tuple[str, ...], fail: Fail) -> tuple:
    if len(row) != len(header):
        fail(
            f"[sweep] cases = {show(file)}: case {i} has {len(row)} cells",
            f"{len(header)} cells a row, one per column",
        )
    values = []
    for name, cell in zip(header, row):
        text = cell.strip()
        if not text:
            fail(f"[sweep] cases = {show(file)}: case {i} has no {name}", "a value in every cell")
        try:
            values.append(_value(name, float(text), fail))
        except ValueError:
            values.append(text)
    return tuple(values)
