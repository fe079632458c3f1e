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
                                  #  (the built-in bodies) | any registered body
    sigma = 2.0                   # composite rms roughness σ* [µm]        (rough-*)
    nu = 0.3                      # Poisson ratio, in (-1, 0.5]
    mu = 0.1                      # friction coefficient, > 0; or a list: one case per
                                  #  value (Fig 9's panels)
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
                                  #  (mu and reduced_normal_load are not both lists)

    [options]
    area_reading = "printed"      # Eq 32 as printed, or "consistent"

    [solver]
    ds_max = 0.05                 # largest continuation step (nondimensional)
    tol = 1e-10                   # Newton residual tolerance

    [output]
    figures = ["force-slip", "force-slip-detail", "force-area"]
                                  # default; also "fig9" (one panel per case)

The ``[surface]`` part is read from the body registry (:mod:`cusp.models.registry`): the
model names, each body's parameters with unit and allowed range, which are required and
which form an all-or-none group (the load scale of the exponential surface). A body
registered with :func:`cusp.models.registry.register_body` is a model here at once. The
cylinder and flat planes are registered but refused, with the registry's reason: the paper
gives them no compliance law, so they have no load–displacement path.

The cases of a scene are every listed μ with every listed F'_N; as at most one of the two
is a list, that is one case per listed value.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NoReturn

from cusp.models import registry
from cusp.models.registry import Parameter

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

__all__ = ["Scene", "SceneError", "load_scene", "parse_scene", "FIGURES"]

#: figure names a scene may ask for
FIGURES = ("force-slip", "force-slip-detail", "force-area", "fig9")
#: the figures of a scene without [output]
DEFAULT_FIGURES = ("force-slip", "force-slip-detail", "force-area")

#: the numbers of [loading] and [solver] (those of [surface] come from the body registry)
_NUMBERS: dict[str, Parameter] = {
    p.name: p
    for p in (
        Parameter("normal_load", "N"),
        Parameter("max_slip", "µm"),
        Parameter("reduced_normal_load", "N"),
        Parameter("ds_max", "", 0.0, 1.0, upper_inclusive=True),
        Parameter("tol", "", 0.0, 1e-4, upper_inclusive=True),
    )
}

_SECTIONS = {
    "scene": {"name", "title"},
    "loading": {"normal_load", "max_slip", "reduced_normal_load"},
    "options": {"area_reading"},
    "solver": {"ds_max", "tol"},
    "output": {"figures"},
}
_REQUIRED_SECTIONS = ("surface", "loading")

#: units of the numeric fields of [loading] and [solver], for the echo in summary.json
UNITS = {key: spec.unit for key, spec in _NUMBERS.items()}


def _section_keys(section: str) -> set[str] | frozenset[str]:
    """The keys a section may hold ([surface]: those of every registered body)."""
    return registry.surface_keys() if section == "surface" else _SECTIONS[section]


class SceneError(ValueError):
    """A scene file is unreadable or does not follow the schema (one-line message)."""


@dataclass(frozen=True)
class Scene:
    """A checked scene. ``surface``, ``loading``, ``options``, ``solver``, ``output`` are
    plain dicts of the values given (numbers as floats; ``surface["mu"]`` a float or a
    list, as given); ``reduced_normal_loads`` and ``mus`` are always tuples."""

    source: str
    name: str
    title: str
    surface: dict[str, Any]
    loading: dict[str, Any]
    options: dict[str, Any]
    solver: dict[str, Any]
    figures: tuple[str, ...]
    #: units of the [surface] numbers, from the body's registry entry
    surface_units: dict[str, str] = field(default_factory=dict)

    @property
    def reduced_normal_loads(self) -> tuple[float, ...]:
        return tuple(self.loading["reduced_normal_load"])

    @property
    def mus(self) -> tuple[float | None, ...]:
        """The listed friction coefficients ((None,) for a body without ``mu``)."""
        mu = self.surface.get("mu")
        return tuple(mu) if isinstance(mu, list) else (mu,)

    @property
    def cases(self) -> tuple[tuple[float | None, float], ...]:
        """(μ, F'_N) of each case: every listed μ with every listed F'_N (at most one of
        them is a list)."""
        return tuple((mu, load) for mu in self.mus for load in self.reduced_normal_loads)

    def echo(self) -> dict[str, Any]:
        """The scene as given, with units: ``{section: {key: {"value", "unit"}}}``."""
        out: dict[str, Any] = {"source": self.source, "name": self.name, "title": self.title}
        for section in ("surface", "loading", "options", "solver"):
            block = getattr(self, section)
            units = self.surface_units if section == "surface" else UNITS
            out[section] = {
                k: ({"value": v, "unit": units[k]} if k in units else v) for k, v in block.items()
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
    _check_sections(chk, data)

    meta = data.get("scene", {})
    name = chk.string("scene", "name", meta.get("name", default_name))
    if not name or any(ch in name for ch in "/\\\0") or name in (".", ".."):
        chk.fail(f"[scene] name = {name!r}", "a non-empty file-name-safe label")
    title = chk.string("scene", "title", meta.get("title", ""))
    surface, surface_units = _check_surface(chk, data["surface"])
    loading = _check_loading(chk, data["loading"])

    opts_in = data.get("options", {})
    reading = chk.string("options", "area_reading", opts_in.get("area_reading", "printed"))
    if reading not in ("printed", "consistent"):
        chk.fail(f"[options] area_reading = {reading!r}", "'printed' or 'consistent'")
    solver = {k: chk.number("solver", k, v) for k, v in data.get("solver", {}).items()}
    if isinstance(surface.get("mu"), list) and len(loading["reduced_normal_load"]) > 1:
        chk.fail(
            f"[surface] mu = {surface['mu']!r} and [loading] reduced_normal_load = "
            f"{loading['reduced_normal_load']!r} are both lists",
            "a list in one of them only (one case per listed value)",
        )
    figs = _check_figures(chk, data.get("output", {}))
    return Scene(
        source=source,
        name=name,
        title=title,
        surface=surface,
        loading=loading,
        options={"area_reading": reading},
        solver=solver,
        figures=tuple(dict.fromkeys(figs)),
        surface_units=surface_units,
    )


def _check_figures(chk: _Checker, output: dict[str, Any]) -> list[str]:
    """[output] figures: known names."""
    figs = output.get("figures", list(DEFAULT_FIGURES))
    if not isinstance(figs, list) or not all(isinstance(f, str) for f in figs):
        chk.fail(f"[output] figures = {figs!r}", f"a list of names from {_list(FIGURES)}")
    for f in figs:
        if f not in FIGURES:
            chk.fail(f"[output] figures contains {f!r}", f"names from {_list(FIGURES)}")
    return figs


def _check_sections(chk: _Checker, data: dict[str, Any]) -> None:
    """Known sections, each a table of known keys; [surface] and [loading] present."""
    sections = {*_SECTIONS, "surface"}
    for section, value in data.items():
        if section not in sections:
            chk.fail(f"unknown section [{section}]", f"sections are {_list(sections)}")
        if not isinstance(value, dict):
            chk.fail(
                f"{section} = {value!r} must be a [{section}] table",
                f"write it as a section [{section}]",
            )
        keys = _section_keys(section)
        unknown = set(value) - keys
        if unknown:
            key = sorted(unknown)[0]
            chk.fail(
                f"[{section}] unknown key {key!r}",
                f"keys of [{section}] are {_list(set(keys))}",
            )
    for section in _REQUIRED_SECTIONS:
        if section not in data:
            chk.fail(f"missing section [{section}]", "a scene needs [surface] and [loading]")


def _check_surface(chk: _Checker, surf_in: dict[str, Any]) -> tuple[dict[str, Any], dict[str, str]]:
    """[surface] against the registry entry of its model: the values and their units."""
    with_path = registry.body_names(with_path=True)
    if "model" not in surf_in:
        chk.fail("[surface] missing key 'model'", f"one of {_list(with_path)}")
    model = chk.string("surface", "model", surf_in["model"])
    if model in registry.body_names(with_path=False):
        chk.fail(
            f"[surface] model = {model!r}: {registry.body_entry(model).refusal}",
            f"models with a contact-loss path are {_list(with_path)}",
        )
    if model not in with_path:
        chk.fail(f"[surface] model = {model!r} is not a known model", f"one of {_list(with_path)}")
    entry = registry.body_entry(model)
    params = entry.parameters
    required = tuple(p.name for p in entry.required)
    optional = tuple(p.name for p in entry.optional)
    extra = set(surf_in) - {"model", *params}
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
        if key == "mu" and isinstance(surf_in[key], list):
            surface[key] = chk.numbers("surface", key, surf_in[key], params[key])
            continue
        surface[key] = chk.number("surface", key, surf_in[key], params[key])
    given = [k for k in optional if k in surf_in]
    if given and len(given) != len(optional):
        missing = [k for k in optional if k not in surf_in]
        chk.fail(
            f"[surface] {', '.join(given)} given without {', '.join(missing)}",
            f"{entry.optional_name} needs all of {_list(optional)} or none",
        )
    for key in given:
        surface[key] = chk.number("surface", key, surf_in[key], params[key])
    return surface, {k: params[k].unit for k in surface if k != "model"}


def _check_loading(chk: _Checker, load_in: dict[str, Any]) -> dict[str, Any]:
    """[loading]: the three loads, the reductions as a list, each below normal_load."""
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
    loading["reduced_normal_load"] = chk.numbers("loading", "reduced_normal_load", reds)
    for v in loading["reduced_normal_load"]:
        if v >= loading["normal_load"]:
            chk.fail(
                f"[loading] reduced_normal_load = {v!r} N",
                f"less than normal_load = {loading['normal_load']!r} N (a reduction)",
            )
    return loading


class _Checker:
    def __init__(self, source: str) -> None:
        self.source = source

    def fail(self, what: str, allowed: str) -> NoReturn:
        raise SceneError(f"{self.source}: {what}; allowed: {allowed}")

    def string(self, section: str, key: str, value: Any) -> str:
        if not isinstance(value, str):
            self.fail(
                f"[{section}] {key} = {value!r} has the wrong type ({type(value).__name__})",
                "a string",
            )
        return value

    def number(self, section: str, key: str, value: Any, spec: Parameter | None = None) -> float:
        """A finite number in the range of ``spec`` (default: the [loading]/[solver] key's)."""
        spec = _NUMBERS[key] if spec is None else spec
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            self.fail(
                f"[{section}] {key} = {value!r} has the wrong type ({type(value).__name__})",
                spec.allowed(),
            )
        if not spec.accepts(float(value)):
            u = f" [{spec.unit}]" if spec.unit else ""
            self.fail(f"[{section}] {key} = {value!r}{u}", spec.allowed())
        return float(value)

    def numbers(
        self, section: str, key: str, values: list, spec: Parameter | None = None
    ) -> list[float]:
        """A non-empty list of numbers, each as :meth:`number`."""
        if not values:
            self.fail(f"[{section}] {key} = []", "a number or a non-empty list of numbers")
        return [self.number(section, key, v, spec) for v in values]


def _list(items) -> str:
    return ", ".join(sorted(items) if isinstance(items, (set, dict)) else items)
