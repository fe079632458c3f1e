"""Scene files: one TOML file describes one contact-loss computation.

A scene is parsed with :mod:`tomllib` (data only: a scene never executes code) and checked
against the schema below before anything is modelled. Every error is a :class:`SceneError`
whose one-line message names the file, the field (``[section] key``), the value found and
what is allowed.

Schema (units in brackets)::

    [scene]                       # optional
    name = "fig6"                 # output label
    title = "..."                 # figure title

    [surface]
    model = "rough-exponential"   # rough-exponential | rough-gaussian | rough-weibull | sphere
    sigma = 2.0                   # composite rms roughness σ* [µm]        (rough-*)
    nu = 0.3                      # Poisson ratio, in (-1, 0.5]
    mu = 0.1                      # friction coefficient, > 0
    E = 0.2                       # Young's modulus [N/µm²]   (rough-gaussian, rough-weibull,
    radius = 10.0                 # ρ* or R [µm]               sphere; optional all-or-none
    density = 0.01                # summits η [1/µm²]          for rough-exponential)
    nominal_area = 1.0e6          # A_n [µm²]
    shape = 2.0                   # Weibull shape k            (rough-weibull; its scale is
                                  #  set by sigma, the standard deviation of the heights)

    [loading]
    normal_load = 1000.0          # F_N0 [N]
    max_slip = 0.34               # g_A [µm]
    reduced_normal_load = 850.0   # F'_N [N], or a list for several reductions (Fig 8)

    [options]
    area_reading = "printed"      # Eq 32 as printed, or "consistent"

    [solver]
    ds_max = 0.05                 # largest continuation step (nondimensional)
    tol = 1e-10                   # Newton residual tolerance

    [output]
    figures = ["force-slip", "force-slip-detail", "force-area"]

The cylinder and flat planes are recognised but rejected: the paper gives them no compliance
law, so they have no load–displacement path.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

__all__ = ["Scene", "SceneError", "load_scene", "parse_scene", "MODELS", "FIGURES"]

#: figure names a scene may ask for
FIGURES = ("force-slip", "force-slip-detail", "force-area")

_LOAD_SCALE = ("E", "radius", "density", "nominal_area")

#: surface model -> (required keys, optional keys)
MODELS: dict[str, tuple[tuple[str, ...], tuple[str, ...]]] = {
    "rough-exponential": (("sigma", "nu", "mu"), _LOAD_SCALE),
    "rough-gaussian": (("sigma", "nu", "mu") + _LOAD_SCALE, ()),
    "rough-weibull": (("sigma", "nu", "mu", "shape") + _LOAD_SCALE, ()),
    "sphere": (("radius", "E", "nu", "mu"), ()),
}
_NO_COMPLIANCE = {
    "cylinder": "a cylinder has no compliance law in the paper (its 2-D elastic displacement is "
    "defined only up to a datum), so it has no contact-loss path",
    "flat": "flat planes have no compliance law (they slide as a whole at F_T = mu F_N), so "
    "they have no contact-loss path",
}

# key -> (unit, lower bound, lower inclusive, upper bound, upper inclusive)
_NUMBERS: dict[str, tuple[str, float, bool, float, bool]] = {
    "sigma": ("µm", 0.0, False, math.inf, False),
    "nu": ("", -1.0, False, 0.5, True),
    "mu": ("", 0.0, False, math.inf, False),
    "E": ("N/µm²", 0.0, False, math.inf, False),
    "radius": ("µm", 0.0, False, math.inf, False),
    "density": ("1/µm²", 0.0, False, math.inf, False),
    "nominal_area": ("µm²", 0.0, False, math.inf, False),
    "shape": ("", 0.0, False, math.inf, False),
    "normal_load": ("N", 0.0, False, math.inf, False),
    "max_slip": ("µm", 0.0, False, math.inf, False),
    "reduced_normal_load": ("N", 0.0, False, math.inf, False),
    "ds_max": ("", 0.0, False, 1.0, True),
    "tol": ("", 0.0, False, 1e-4, True),
}

_SECTIONS = {
    "scene": {"name", "title"},
    "surface": {"model", "sigma", "nu", "mu", "shape", *_LOAD_SCALE},
    "loading": {"normal_load", "max_slip", "reduced_normal_load"},
    "options": {"area_reading"},
    "solver": {"ds_max", "tol"},
    "output": {"figures"},
}
_REQUIRED_SECTIONS = ("surface", "loading")

#: units of every numeric field, for the echo in summary.json
UNITS = {key: spec[0] for key, spec in _NUMBERS.items()}


class SceneError(ValueError):
    """A scene file is unreadable or does not follow the schema (one-line message)."""


@dataclass(frozen=True)
class Scene:
    """A checked scene. ``surface``, ``loading``, ``options``, ``solver``, ``output`` are
    plain dicts of the values given (numbers as floats); ``reduced_normal_loads`` is always
    a tuple."""

    source: str
    name: str
    title: str
    surface: dict[str, Any]
    loading: dict[str, Any]
    options: dict[str, Any]
    solver: dict[str, Any]
    figures: tuple[str, ...]

    @property
    def reduced_normal_loads(self) -> tuple[float, ...]:
        return tuple(self.loading["reduced_normal_load"])

    def echo(self) -> dict[str, Any]:
        """The scene as given, with units: ``{section: {key: {"value", "unit"}}}``."""
        out: dict[str, Any] = {"source": self.source, "name": self.name, "title": self.title}
        for section in ("surface", "loading", "options", "solver"):
            block = getattr(self, section)
            out[section] = {
                k: ({"value": v, "unit": UNITS[k]} if k in UNITS else v) for k, v in block.items()
            }
        out["output"] = {"figures": list(self.figures)}
        return out


def load_scene(path: str | Path, *, source: str | None = None) -> Scene:
    """Read and check a scene file (``source``: how messages and the echo name it; default
    the path as given)."""
    path = Path(path)
    label = str(path) if source is None else source
    try:
        raw = path.read_bytes()
    except FileNotFoundError:
        raise SceneError(f"{path}: no such scene file") from None
    except IsADirectoryError:
        raise SceneError(f"{path}: is a directory, not a scene file") from None
    except OSError as exc:
        raise SceneError(f"{path}: cannot read the scene file ({exc.strerror})") from None
    if b"\x00" in raw:
        raise SceneError(f"{path}: binary file (NUL bytes); a scene is a UTF-8 TOML text file")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise SceneError(
            f"{path}: not UTF-8 text (byte {exc.start}); a scene is a UTF-8 TOML text file"
        ) from None
    return parse_scene(text, source=label, default_name=path.stem)


def parse_scene(text: str, *, source: str = "<scene>", default_name: str = "scene") -> Scene:
    """Parse and check scene text (see the module docstring for the schema)."""
    if not text.strip():
        raise SceneError(f"{source}: empty scene; it needs at least [surface] and [loading]")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"{source}: malformed TOML: {exc}") from None
    chk = _Checker(source)
    for section, value in data.items():
        if section not in _SECTIONS:
            chk.fail(f"unknown section [{section}]", f"sections are {_list(_SECTIONS)}")
        if not isinstance(value, dict):
            chk.fail(
                f"{section} = {value!r} must be a [{section}] table",
                f"write it as a section [{section}]",
            )
        unknown = set(value) - _SECTIONS[section]
        if unknown:
            key = sorted(unknown)[0]
            chk.fail(
                f"[{section}] unknown key {key!r}",
                f"keys of [{section}] are {_list(_SECTIONS[section])}",
            )
    for section in _REQUIRED_SECTIONS:
        if section not in data:
            chk.fail(f"missing section [{section}]", "a scene needs [surface] and [loading]")

    meta = data.get("scene", {})
    name = chk.string("scene", "name", meta.get("name", default_name))
    if not name or any(ch in name for ch in "/\\\0") or name in (".", ".."):
        chk.fail(f"[scene] name = {name!r}", "a non-empty file-name-safe label")
    title = chk.string("scene", "title", meta.get("title", ""))

    surf_in = data["surface"]
    if "model" not in surf_in:
        chk.fail("[surface] missing key 'model'", f"one of {_list(MODELS)}")
    model = chk.string("surface", "model", surf_in["model"])
    if model in _NO_COMPLIANCE:
        chk.fail(
            f"[surface] model = {model!r}: {_NO_COMPLIANCE[model]}",
            f"models with a contact-loss path are {_list(MODELS)}",
        )
    if model not in MODELS:
        chk.fail(f"[surface] model = {model!r} is not a known model", f"one of {_list(MODELS)}")
    required, optional = MODELS[model]
    extra = set(surf_in) - {"model", *required, *optional}
    if extra:
        key = sorted(extra)[0]
        chk.fail(
            f"[surface] key {key!r} does not apply to model {model!r}",
            f"{model} takes {_list(required + optional)}",
        )
    surface: dict[str, Any] = {"model": model}
    for key in required:
        if key not in surf_in:
            chk.fail(
                f"[surface] missing key {key!r} for model {model!r}",
                f"{model} needs {_list(required)}",
            )
        surface[key] = chk.number("surface", key, surf_in[key])
    given = [k for k in optional if k in surf_in]
    if given and len(given) != len(optional):
        missing = [k for k in optional if k not in surf_in]
        chk.fail(
            f"[surface] {', '.join(given)} given without {', '.join(missing)}",
            f"the load scale needs all of {_list(optional)} or none",
        )
    for key in given:
        surface[key] = chk.number("surface", key, surf_in[key])

    load_in = data["loading"]
    loading: dict[str, Any] = {}
    for key in ("normal_load", "max_slip", "reduced_normal_load"):
        if key not in load_in:
            chk.fail(
                f"[loading] missing key {key!r}",
                "[loading] needs normal_load, max_slip and reduced_normal_load",
            )
    loading["normal_load"] = chk.number("loading", "normal_load", load_in["normal_load"])
    loading["max_slip"] = chk.number("loading", "max_slip", load_in["max_slip"])
    red = load_in["reduced_normal_load"]
    reds = red if isinstance(red, list) else [red]
    if not reds:
        chk.fail("[loading] reduced_normal_load = []", "a number or a non-empty list of numbers")
    loading["reduced_normal_load"] = [chk.number("loading", "reduced_normal_load", v) for v in reds]
    for v in loading["reduced_normal_load"]:
        if v >= loading["normal_load"]:
            chk.fail(
                f"[loading] reduced_normal_load = {v!r} N",
                f"less than normal_load = {loading['normal_load']!r} N (a reduction)",
            )

    opts_in = data.get("options", {})
    reading = chk.string("options", "area_reading", opts_in.get("area_reading", "printed"))
    if reading not in ("printed", "consistent"):
        chk.fail(f"[options] area_reading = {reading!r}", "'printed' or 'consistent'")
    solver = {k: chk.number("solver", k, v) for k, v in data.get("solver", {}).items()}

    figs = data.get("output", {}).get("figures", list(FIGURES))
    if not isinstance(figs, list) or not all(isinstance(f, str) for f in figs):
        chk.fail(f"[output] figures = {figs!r}", f"a list of names from {_list(FIGURES)}")
    for f in figs:
        if f not in FIGURES:
            chk.fail(f"[output] figures contains {f!r}", f"names from {_list(FIGURES)}")
    return Scene(
        source=source,
        name=name,
        title=title,
        surface=surface,
        loading=loading,
        options={"area_reading": reading},
        solver=solver,
        figures=tuple(dict.fromkeys(figs)),
    )


class _Checker:
    def __init__(self, source: str) -> None:
        self.source = source

    def fail(self, what: str, allowed: str):
        raise SceneError(f"{self.source}: {what}; allowed: {allowed}")

    def string(self, section: str, key: str, value) -> str:
        if not isinstance(value, str):
            self.fail(
                f"[{section}] {key} = {value!r} has the wrong type ({type(value).__name__})",
                "a string",
            )
        return value

    def number(self, section: str, key: str, value) -> float:
        unit, lo, lo_in, hi, hi_in = _NUMBERS[key]
        u = f" [{unit}]" if unit else ""
        rng = (
            f"{'[' if lo_in else '('}{lo:g}, {hi:g}{']' if hi_in else ')'}"
            if math.isfinite(hi)
            else f"{'>=' if lo_in else '>'} {lo:g}"
        )
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            self.fail(
                f"[{section}] {key} = {value!r} has the wrong type ({type(value).__name__})",
                f"a finite number {rng}{u}",
            )
        v = float(value)
        ok = math.isfinite(v) and (v >= lo if lo_in else v > lo) and (v <= hi if hi_in else v < hi)
        if not ok:
            self.fail(f"[{section}] {key} = {value!r}{u}", f"a finite number {rng}{u}")
        return v


def _list(items) -> str:
    return ", ".join(sorted(items) if isinstance(items, (set, dict)) else items)
