"""Results that last: a :class:`~._branch.Branch` (a branch, a fold curve, a locus) saved to
one ``.npz`` file and loaded back bit for bit.

The file is a zip archive that numpy reads alone (``np.load(path, allow_pickle=False)``):
one ``.npy`` member per array (``columns/x``, ``s``, ``tangents``, ``stats/ds``, ...) and a
member ``metadata.json`` (bytes, UTF-8 JSON) holding the format (``"cusp-results"``), its
version (:data:`FORMAT_VERSION`), what the file holds (``"type"``), the cusp and numpy
versions and the object itself as a JSON tree whose arrays name their members
(``{"$array": "columns/x"}``). Floats in the tree are written by ``repr``, which reads back
to the same double (a NaN or an infinity as its 8 bytes in hex, ``{"$float": "7ff8..."}``:
the JSON is strict); tuples, enumerations, complex numbers, numpy scalars and dataclasses
are tagged (``{"$tuple": [...]}``, ...) so that they come back as they were.

Saving is atomic: the archive is written to a temporary file in the target's directory
and moved over the target (:func:`os.replace`), so a reader sees the old file or the new
one, never half of one. Loading refuses, with :class:`~.._errors.ResultsFileError` naming
the path and what is wrong, a file that is no zip archive, a zip archive that is not a cusp
results file, a truncated or damaged one, and one written in a newer format.
"""

from __future__ import annotations

import dataclasses
import errno
import json
import math
import os
import struct
import tempfile
import zipfile
from collections.abc import Callable, Mapping
from importlib.metadata import PackageNotFoundError, version
from pathlib import Path
from typing import Any

import numpy as np

from .._errors import ResultsFileError
from .._outcomes import Convergence, Guard, Kind, PointStatus, Status

FORMAT = "cusp-results"
"""The ``format`` field of every results file's metadata."""
FORMAT_VERSION = 1
"""The version of the file layout this cusp writes (and the newest it reads)."""
META = "metadata.json"
"""The name of the metadata member."""

_ENUMS = {cls.__name__: cls for cls in (Status, Kind, PointStatus, Convergence, Guard)}
_ZIP_MAGIC = b"PK\x03\x04"


def cusp_version() -> str:
    """The installed cusp's version (``"unknown"`` in a tree never installed)."""
    try:
        return version("cusp")
    except PackageNotFoundError:  # pragma: no cover - a source tree never installed
        return "unknown"


class Writer:
    """The arrays of a file being written, by member name, and the encoder of its tree;
    ``branch_type``: the class of the branches it may hold (:class:`~._branch.Branch`,
    given by the caller: this module imports no result class, which import it)."""

    def __init__(self, branch_type: type) -> None:
        self.arrays: dict[str, np.ndarray] = {}
        self.branch_type = branch_type

    def add(self, name: str, array: Any) -> dict[str, str]:
        """Store ``array`` as member ``name`` (made unique); the tree's reference to it."""
        a = np.asarray(array)
        if a.dtype.hasobject:
            raise TypeError(f"{name}: an array of Python objects cannot be saved (numpy only)")
        unique, n = name, 1
        while unique in self.arrays:
            unique, n = f"{name}~{n}", n + 1
        self.arrays[unique] = a
        return {"$array": unique}

    def encode(self, obj: Any, where: str) -> Any:
        """``obj`` as a JSON tree (arrays stored as members named after ``where``)."""
        if type(obj) is float and not math.isfinite(obj):  # strict JSON, every bit kept
            return {"$float": struct.pack(">d", obj).hex()}
        if obj is None or type(obj) in (bool, int, float, str):
            return obj
        if isinstance(obj, (Status, Kind, PointStatus, Convergence, Guard)):
            return {"$enum": type(obj).__name__, "value": obj.value}
        if isinstance(obj, np.ndarray):
            return self.add(where, obj)
        if isinstance(obj, np.generic):
            return {"$scalar": self.add(where, np.asarray(obj))["$array"]}
        if isinstance(obj, complex):
            return {"$complex": [self.encode(obj.real, where), self.encode(obj.imag, where)]}
        if isinstance(obj, self.branch_type):
            return {"$branch": encode_branch(self, obj, where + "/")}
        if isinstance(obj, (list, tuple, frozenset)):
            return self._sequence(obj, where)
        if isinstance(obj, Mapping):
            return self._mapping(obj, where)
        if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
            fields = {
                f.name: self.encode(getattr(obj, f.name), f"{where}/{f.name}")
                for f in dataclasses.fields(obj)
                if f.init
            }
            return {"$dataclass": type(obj).__name__, "fields": fields}
        raise TypeError(
            f"{where}: a {type(obj).__name__} cannot be saved (numbers, strings, arrays, "
            f"lists, tuples, dicts, enumerations and the engine's records can)"
        )

    def _sequence(self, obj: Any, where: str) -> Any:
        items = sorted(obj) if isinstance(obj, frozenset) else obj
        out = [self.encode(v, f"{where}/{i}") for i, v in enumerate(items)]
        if isinstance(obj, frozenset):
            return {"$frozenset": out}
        return out if type(obj) is list else {"$tuple": out}

    def _mapping(self, obj: Mapping[Any, Any], where: str) -> Any:
        if all(type(k) is str and not k.startswith("$") for k in obj):
            return {k: self.encode(v, f"{where}/{k}") for k, v in obj.items()}
        items = [
            [self.encode(k, where), self.encode(v, f"{where}/{i}")]
            for i, (k, v) in enumerate(obj.items())
        ]
        return {"$items": items}


class Reader:
    """The decoder of a file's tree, with its arrays and the classes it may hold by name
    (``"Branch"``, ``"SpecialPoint"`` and the dataclasses of a diagram)."""

    def __init__(self, arrays: Mapping[str, np.ndarray], classes: Mapping[str, type]) -> None:
        self.arrays = arrays
        self.classes = dict(classes)

    def array(self, ref: Any) -> np.ndarray:
        name = ref["$array"]
        if name not in self.arrays:
            raise KeyError(f"member {name!r} is missing")
        return self.arrays[name]

    def decode(self, tree: Any) -> Any:
        if tree is None or type(tree) in (bool, int, float, str):
            return tree
        if type(tree) is list:
            return [self.decode(v) for v in tree]
        tag = next(iter(tree), None) if len(tree) <= 2 else None
        decoder = _TAGS.get(tag) if isinstance(tag, str) else None
        if decoder is None:
            return {k: self.decode(v) for k, v in tree.items()}
        return decoder(self, tree)

    def dataclass(self, tree: Mapping[str, Any]) -> Any:
        cls = self.classes.get(tree["$dataclass"])
        if cls is None:
            raise ValueError(f"it holds a record of unknown type {tree['$dataclass']!r}")
        return cls(**{k: self.decode(v) for k, v in tree["fields"].items()})


_TAGS: dict[str, Callable[[Reader, Any], Any]] = {
    "$enum": lambda r, t: _ENUMS[t["$enum"]](t["value"]),
    "$array": lambda r, t: r.array(t),
    "$scalar": lambda r, t: r.array({"$array": t["$scalar"]})[()],
    "$float": lambda r, t: struct.unpack(">d", bytes.fromhex(t["$float"]))[0],
    "$complex": lambda r, t: complex(*(r.decode(v) for v in t["$complex"])),
    "$tuple": lambda r, t: tuple(r.decode(v) for v in t["$tuple"]),
    "$frozenset": lambda r, t: frozenset(r.decode(v) for v in t["$frozenset"]),
    "$items": lambda r, t: {r.decode(k): r.decode(v) for k, v in t["$items"]},
    "$branch": lambda r, t: decode_branch(r, t["$branch"]),
    "$dataclass": lambda r, t: r.dataclass(t),
}


def encode_branch(w: Writer, br: Any, prefix: str = "") -> dict[str, Any]:
    """The tree of a branch, its arrays stored under ``prefix``."""
    eig: Any = None
    if br.eigenvalues is not None:  # ragged rows: one array and the row lengths
        rows = [np.asarray(e) for e in br.eigenvalues]
        data = np.concatenate(rows) if rows else np.zeros(0, dtype=complex)
        eig = {
            "data": w.add(f"{prefix}eigenvalues", data),
            "lengths": w.add(f"{prefix}eigenvalue_counts", np.array([r.size for r in rows])),
        }
    return {
        "columns": {k: w.add(f"{prefix}columns/{k}", br[k]) for k in br.keys()},
        "variables": list(br.variables),
        "s": w.add(f"{prefix}s", br.s),
        "tangents": w.add(f"{prefix}tangents", br.tangents),
        "special_points": w.encode(br.special_points, f"{prefix}special_points"),
        "status": w.encode(br.status, ""),
        "message": br.message,
        "stats": {k: w.add(f"{prefix}stats/{k}", v) for k, v in br.stats.items()},
        "info": w.encode(br.info, f"{prefix}info"),
        "kinds": sorted(str(k) for k in br.kinds),
        "eigenvalues": eig,
    }


def decode_branch(r: Reader, t: Mapping[str, Any]) -> Any:
    """The branch of a tree written by :func:`encode_branch`."""
    eigenvalues = None
    if t["eigenvalues"] is not None:
        data, lengths = r.array(t["eigenvalues"]["data"]), r.array(t["eigenvalues"]["lengths"])
        eigenvalues = np.split(data, np.cumsum(lengths)[:-1]) if lengths.size else []
    kinds = frozenset(Kind.parse(k, frozenset({k})) for k in t["kinds"])
    return r.classes["Branch"](
        {k: r.array(v) for k, v in t["columns"].items()},
        variables=tuple(t["variables"]),
        s=r.array(t["s"]),
        tangents=r.array(t["tangents"]),
        special_points=r.decode(t["special_points"]),
        status=r.decode(t["status"]),
        message=t["message"],
        stats={k: r.array(v) for k, v in t["stats"].items()},
        info=r.decode(t["info"]),
        kinds=kinds,
        eigenvalues=eigenvalues,
    )


def _target(path: str | os.PathLike[str]) -> Path:
    """``path`` as the file to write, or the error that names it (not the temporary file)."""
    if not os.fspath(path):
        raise ValueError("path must name a results file (.npz), got ''")
    out = Path(path)
    if out.is_dir():
        raise IsADirectoryError(errno.EISDIR, "cannot write results: a directory", str(out))
    if not out.parent.is_dir():
        why = "cannot write results: no such directory"
        raise FileNotFoundError(errno.ENOENT, why, str(out.parent))
    return out


def write_results(path: str | os.PathLike[str], kind: str, tree: Any, w: Writer) -> Path:
    """Write a results file atomically: the archive goes to a temporary file beside
    ``path``, which then replaces it. Returns the path."""
    path = _target(path)
    meta = {
        "format": FORMAT,
        "format_version": FORMAT_VERSION,
        "type": kind,
        "cusp_version": cusp_version(),
        "numpy_version": np.__version__,
        "data": tree,
    }
    text = json.dumps(meta, indent=1, allow_nan=False)  # (non-finite floats are tagged)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent or ".")
    try:
        with os.fdopen(fd, "wb") as f:
            with zipfile.ZipFile(f, "w", zipfile.ZIP_STORED, allowZip64=True) as z:
                z.writestr(META, text.encode("utf-8"))
                for name, array in w.arrays.items():
                    with z.open(name + ".npy", "w", force_zip64=True) as member:
                        np.lib.format.write_array(member, array, allow_pickle=False)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


def read_results(path: str | os.PathLike[str]) -> tuple[dict[str, Any], dict[str, np.ndarray]]:
    """The metadata and the arrays of a results file, or :class:`ResultsFileError`."""
    path = Path(path)
    with open(path, "rb") as f:  # (FileNotFoundError names the path)
        head = f.read(4)
    try:
        with zipfile.ZipFile(path) as z:
            names = z.namelist()
            if META not in names:
                raise ResultsFileError(
                    path, f"it is a zip archive without {META}: not a cusp results file"
                )
            meta = _metadata(path, z.read(META))
            arrays = {}
            for name in names:
                if name.endswith(".npy"):
                    with z.open(name) as member:
                        arrays[name[:-4]] = np.lib.format.read_array(member, allow_pickle=False)
    except (zipfile.BadZipFile, EOFError, OSError, ValueError) as exc:
        if isinstance(exc, ResultsFileError):
            raise
        if head != _ZIP_MAGIC:
            raise ResultsFileError(path, "it is not a zip archive (.npz)") from None
        raise ResultsFileError(path, f"it is truncated or damaged ({exc})") from None
    return meta, arrays


def _metadata(path: Path, raw: bytes) -> dict[str, Any]:
    """The checked metadata of a results file."""
    try:
        meta = json.loads(raw.decode("utf-8"))
    except ValueError as exc:
        raise ResultsFileError(path, f"its {META} is not JSON ({exc})") from None
    if not isinstance(meta, dict) or meta.get("format") != FORMAT:
        raise ResultsFileError(path, f"its {META} does not say format {FORMAT!r}")
    got = meta.get("format_version")
    if not isinstance(got, int) or got < 1:
        raise ResultsFileError(path, f"its format version {got!r} is not a positive integer")
    if got > FORMAT_VERSION:
        raise ResultsFileError(
            path,
            f"it was written in format version {got} (by cusp {meta.get('cusp_version')}), "
            f"newer than this cusp ({cusp_version()}) reads (up to {FORMAT_VERSION}): "
            f"upgrade cusp to load it",
        )
    return meta


def decode_results(
    path: str | os.PathLike[str],
    meta: Mapping[str, Any],
    arrays: Mapping[str, np.ndarray],
    classes: Mapping[str, type],
) -> Any:
    """The object of a read results file (:class:`ResultsFileError` if its tree does not
    match its arrays)."""
    try:
        return Reader(arrays, classes).decode(meta["data"])
    except (KeyError, TypeError, ValueError, AttributeError, IndexError) as exc:
        raise ResultsFileError(Path(path), f"its contents are inconsistent ({exc})") from None


def save_branch(branch: Any, path: str | os.PathLike[str]) -> Path:
    """:meth:`Branch.save <._branch.Branch.save>`."""
    w = Writer(type(branch))
    return write_results(path, "Branch", {"$branch": encode_branch(w, branch)}, w)


def to_pandas(branch: Any) -> Any:
    """:meth:`Branch.to_pandas <._branch.Branch.to_pandas>`."""
    try:
        import pandas as pd
    except ImportError:
        raise ImportError(
            "Branch.to_pandas needs pandas: pip install 'cusp[pandas]' (or pip install pandas)"
        ) from None
    data: dict[str, Any] = {k: branch[k] for k in branch.keys()}
    data["s"] = branch.s
    for k, v in branch.stats.items():
        data[f"stats.{k}"] = v
    special = [""] * len(branch)
    for sp in branch.special_points:
        special[sp.index] = f"{special[sp.index]},{sp.kind}".lstrip(",")
    data["special"] = special
    return pd.DataFrame(data)


__all__ = [
    "FORMAT",
    "FORMAT_VERSION",
    "Reader",
    "Writer",
    "decode_results",
    "encode_branch",
    "read_results",
    "save_branch",
    "to_pandas",
    "write_results",
]
