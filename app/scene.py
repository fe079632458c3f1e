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
                                  #  (not several values in both mu and this)

    [options]
    area_reading = "printed"      # Eq 32 as printed, or "consistent"

    [solver]                      # optional
    rtol = 1e-3                   # relative accuracy of everything computed, in
                                  #  [1e-13, 1e-2] (default 1e-3); ``cusp run --rtol``
                                  #  overrides it
    ds_max = 0.05                 # largest continuation step of the paths (nondimensional)
    tol = 1e-10                   # Newton residual tolerance (default: from rtol)

    [manifold]                    # optional: the loci of A, B, C, D (Fig 9)
    parameter = "mu"              # "mu" or "reduced_normal_load"
    range = [0.01, 1.0]           # [low, high], 0 < low < high (F'_N: high <= normal_load),
                                  #  holding the scene's value (the first listed, for a list)

    [sweep]                       # optional: the fields ``cusp sweep`` varies, by dotted
    "surface.mu" = [0.05, 0.1]    #  names (cusp.app._sweep_spec); ``cusp run`` runs the
                                  #  scene as written

    [output]
    figures = ["force-slip", "force-slip-detail", "force-area"]
                                  # default; with [manifold]: fig9, manifold-surface,
                                  #  loci-control-planes, loci-energies, regime-map

The ``[surface]`` part is read from the body registry (:mod:`cusp.models.registry`): the
model names, each body's parameters with unit and allowed range, which are required and
which form an all-or-none group (the load scale of the exponential surface). A body
registered with :func:`cusp.models.registry.register_body` is a model here at once. The
cylinder and flat planes are registered but refused, with the registry's reason: the paper
gives them no compliance law, so they have no load–displacement path.

``[solver] rtol`` is the one accuracy knob (:class:`cusp.continuation.ContinuationOptions`):
it sets the Newton, step and location tolerances of the paths and of the loci, the polish of
their points and the quadrature of the energies. The default, 1e-3, keeps the points to
1e-12 and the energies to 1e-13 relative; 1e-2 is enough for a figure, smaller values cost
more steps. ``ds_max`` and ``tol`` apply to the paths only (the loci keep their own steps);
``tol``, when given, overrides what ``rtol`` sets.

The cases of a scene are every listed μ with every listed F'_N; as at most one of the two
is a list, that is one case per listed value. A ``[manifold]`` scene traces, besides its
cases, the loci from the case of the first listed value that lies in ``range``.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, NoReturn

from cusp.models import registry
from cusp.models.registry import Parameter

from .limits import (
    MAX_CASES,
    MAX_LIST,
    MAX_NAME_CHARS,
    MAX_TITLE_CHARS,
    check_text,
    read_scene_bytes,
    show,
)
from .scene_sections import MANIFOLD_PARAMETERS, check_loading, check_manifold

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

__all__ = [
    "Scene",
    "SceneError",
    "load_scene",
    "parse_scene",
    "check_title",
    "with_rtol",
    "scene_from_data",
    "FIGURES",
    "MANIFOLD_FIGURES",
]

#: figure names that draw the loci, for a scene with a [manifold] section only
MANIFOLD_FIGURES = ("manifold-surface", "loci-control-planes", "loci-energies", "regime-map")
#: figure names a scene may ask for
FIGURES = ("force-slip", "force-slip-detail", "force-area", "fig9", *MANIFOLD_FIGURES)
#: the figures of a scene without [output] (without, with a [manifold] section)
DEFAULT_FIGURES = ("force-slip", "force-slip-detail", "force-area")
DEFAULT_MANIFOLD_FIGURES = ("fig9", *MANIFOLD_FIGURES)

#: the allowed ``rtol``: ContinuationOptions' RTOL_MIN and RTOL_MAX (written out, not
#: imported: reading a scene loads no solver; tests/app/test_rtol.py checks they agree)
RTOL_RANGE = (1e-13, 1e-2)
#: the numbers of [loading] and [solver] (those of [surface] come from the body registry)
_NUMBERS: dict[str, Parameter] = {
    p.name: p
    for p in (
        Parameter("normal_load", "N", description="F_N0, the normal load on OA"),
        Parameter("max_slip", "µm", description="g_A, the slip at A (below gross sliding)"),
        Parameter(
            "reduced_normal_load",
            "N",
            description="F'_N at B, or a list (one case each); F_N0 - F_A/mu <= F'_N < F_N0",
        ),
        Parameter("ds_max", "", 1e-10, 1.0, True, True, description="largest step of the paths"),
        Parameter("tol", "", 0.0, 1e-4, upper_inclusive=True, description="Newton tolerance"),
        Parameter(
            "rtol", "", *RTOL_RANGE, True, True, description="relative accuracy (default 1e-3)"
        ),
    )
}

#: the readings of Eq 32 for [options] area_reading (the first is the default)
AREA_READINGS = ("printed", "consistent")

_SECTIONS = {
    "scene": {"name", "title"},
    "loading": {"normal_load", "max_slip", "reduced_normal_load"},
    "options": {"area_reading"},
    "solver": {"ds_max", "tol", "rtol"},
    "output": {"figures"},
    "manifold": {"parameter", "range"},
    "sweep": set(),  # dotted field names, checked by cusp.app._sweep_spec
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
    """A checked scene (made by :func:`load_scene` or :func:`parse_scene`).

    The sections are dicts of the values given, numbers as floats in the schema's units.

    Parameters
    ----------
    source : str
        How messages and the echo name the scene (its path, or a label).
    name, title : str
        ``[scene] name`` (the output label; default the file's stem) and ``title``.
    surface : dict of str to Any
        ``[surface]``: ``model`` and the body's numbers (``mu`` a float or a list, as given).
    loading : dict of str to Any
        ``[loading]``: ``normal_load`` [N], ``max_slip`` [µm] and ``reduced_normal_load``
        [N], the last always a list.
    options, solver : dict
        ``[options]`` (``area_reading``) and ``[solver]`` (``rtol``, ``ds_max``, ``tol``).
    figures : tuple of str
        The figures to draw.
    surface_units : dict of str to str, optional
        The unit of each ``[surface]`` number, from the body's registry entry.
    manifold : dict or None, optional
        None, or ``{"parameter", "range": (low, high), "start": (μ, F'_N [N])}`` (the case
        the loci start from).
    sweep : Sweep or None, optional
        The checked ``[sweep]`` section (the varied fields and their cases), or None.
    """

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
    manifold: dict[str, Any] | None = None
    #: the checked [sweep] section (:class:`cusp.app._sweep_spec.Sweep`), or None
    sweep: Any = None

    @property
    def reduced_normal_loads(self) -> tuple[float, ...]:
        """The listed reduced normal loads F'_N [N], as a tuple."""
        return tuple(self.loading["reduced_normal_load"])

    @property
    def mus(self) -> tuple[float | None, ...]:
        """The listed friction coefficients ((None,) for a body without ``mu``)."""
        mu = self.surface.get("mu")
        return tuple(mu) if isinstance(mu, list) else (mu,)

    @property
    def cases(self) -> tuple[tuple[float | None, float], ...]:
        """(μ, F'_N [N]) of each case: every listed μ with every listed F'_N (one listed)."""
        return tuple((mu, load) for mu in self.mus for load in self.reduced_normal_loads)

    def echo(self) -> dict[str, Any]:
        """Return the scene as given, with units (for ``summary.json``).

        Returns
        -------
        dict of str to Any
            ``{section: {key: {"value", "unit"}}}``, with ``[solver] rtol`` as
            ``cusp run --rtol`` set it (:func:`with_rtol`).
        """
        out: dict[str, Any] = {"source": self.source, "name": self.name, "title": self.title}
        for section in ("surface", "loading", "options", "solver"):
            block = getattr(self, section)
            units = self.surface_units if section == "surface" else UNITS
            out[section] = {
                k: ({"value": v, "unit": units[k]} if k in units else v) for k, v in block.items()
            }
        if self.manifold is not None:
            unit = MANIFOLD_PARAMETERS[self.manifold["parameter"]]
            out["manifold"] = {
                "parameter": self.manifold["parameter"],
                "range": {"value": list(self.manifold["range"]), "unit": unit},
            }
        out["output"] = {"figures": list(self.figures)}
        return out


def load_scene(path: str | Path, *, source: str | None = None) -> Scene:
    """Read and check a scene file.

    Parameters
    ----------
    path : str or pathlib.Path
        The TOML file (UTF-8).
    source : str, optional
        How messages and the echo name it (default: the path as given).

    Returns
    -------
    Scene
        The checked scene.

    Raises
    ------
    SceneError
        An unreadable file or one that does not follow the schema; the one-line message
        names the file, the field (``[section] key``), the value and what is allowed.
    """
    path = Path(path)
    label = str(path) if source is None else source
    try:
        raw = read_scene_bytes(path)
    except ValueError as exc:
        raise SceneError(f"{path}: {exc}") from None
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
    return parse_scene(text, source=label, default_name=path.stem, base_dir=path.parent)


def parse_scene(
    text: str, *, source: str = "<scene>", default_name: str = "scene", base_dir: Path | None = None
) -> Scene:
    """Parse and check scene text (see the module docstring for the schema).

    Parameters
    ----------
    text : str
        The TOML text.
    source : str, optional
        How messages and the echo name it.
    default_name : str, optional
        The scene's name when ``[scene] name`` is not given.
    base_dir : pathlib.Path, optional
        Where a ``[sweep] cases`` file is looked for (default: the working directory).

    Returns
    -------
    Scene
        The checked scene.

    Raises
    ------
    SceneError
        Text that does not follow the schema (the message names the field, the value and
        what is allowed).

    Examples
    --------
    >>> parse_scene("[surface]\\nmodel = 'sphere'\\n", source="s.toml")
    Traceback (most recent call last):
    ...
    cusp.app.scene.SceneError: s.toml: missing section [loading]; allowed: a scene needs ...
    """
    text = text.removeprefix("\ufeff")  # a UTF-8 byte-order mark
    if not text.strip():
        raise SceneError(f"{source}: empty scene; it needs at least [surface] and [loading]")
    problem = check_text(text)
    if problem is not None:
        raise SceneError(f"{source}: {problem}; see docs/limits.md")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError(f"{source}: malformed TOML: {exc}") from None
    except RecursionError:  # pragma: no cover - check_text bounds the nesting first
        raise SceneError(f"{source}: nested too deep; see docs/limits.md") from None
    return scene_from_data(data, source=source, default_name=default_name, base_dir=base_dir)


def scene_from_data(
    data: dict[str, Any],
    *,
    source: str = "<scene>",
    default_name: str = "scene",
    base_dir: Path | None = None,
) -> Scene:
    """Check parsed scene data (the TOML tables, as :func:`parse_scene` reads them).

    Parameters
    ----------
    data : dict of str to object
        The scene's tables.
    source : str, optional
        How messages and the echo name it.
    default_name : str, optional
        The scene's name when ``[scene] name`` is not given.
    base_dir : pathlib.Path, optional
        Where a ``[sweep] cases`` file is looked for (default: the working directory).

    Returns
    -------
    Scene
        The checked scene.

    Raises
    ------
    SceneError
        Data that does not follow the schema.
    """
    chk = _Checker(source)
    _check_sections(chk, data)

    meta = data.get("scene", {})
    name = _check_name(chk, meta.get("name", default_name))
    title = chk.string("scene", "title", meta.get("title", ""))
    if len(title) > MAX_TITLE_CHARS:
        chk.fail(f"[scene] title of {len(title)} characters", f"at most {MAX_TITLE_CHARS}")
    surface, surface_units = _check_surface(chk, data["surface"])
    loading = check_loading(chk, data["loading"])

    opts_in = data.get("options", {})
    reading = chk.string("options", "area_reading", opts_in.get("area_reading", AREA_READINGS[0]))
    if reading not in AREA_READINGS:
        chk.fail(f"[options] area_reading = {show(reading)}", "'printed' or 'consistent'")
    solver = {k: chk.number("solver", k, v) for k, v in data.get("solver", {}).items()}
    mus = surface.get("mu")
    if isinstance(mus, list) and len(mus) > 1 and len(loading["reduced_normal_load"]) > 1:
        chk.fail(
            f"[surface] mu = {show(surface['mu'])} and [loading] reduced_normal_load = "
            f"{show(loading['reduced_normal_load'])} are both lists",
            "several values in one of them only (one case per listed value)",
        )
    n_cases = len(mus if isinstance(mus, list) else [mus]) * len(loading["reduced_normal_load"])
    if n_cases > MAX_CASES:
        chk.fail(
            f"{n_cases} cases (listed mu times listed reduced_normal_load)", f"at most {MAX_CASES}"
        )
    manifold = None
    if "manifold" in data:
        manifold = check_manifold(chk, data["manifold"], surface, loading)
    figs = _check_figures(chk, data.get("output", {}), manifold is not None)
    sweep = None
    if "sweep" in data:
        from ._sweep_spec import check_sweep

        sweep = check_sweep(data, chk.fail, _SECTIONS, surface, loading, base_dir=base_dir)
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
        manifold=manifold,
        sweep=sweep,
    )


def with_rtol(scene: Scene, text: str, *, flag: str = "--rtol") -> Scene:
    """Return the scene with its ``[solver] rtol`` set from a command-line value.

    Parameters
    ----------
    scene : Scene
        The scene.
    text : str
        The value as typed, checked as the scene's own would be.
    flag : str, optional
        How messages name the value (default ``"--rtol"``).

    Returns
    -------
    Scene
        A copy with the new ``rtol``.

    Raises
    ------
    SceneError
        Not a number, or outside [1e-13, 1e-2].
    """
    spec = _NUMBERS["rtol"]
    try:
        value = float(text)
    except ValueError:
        raise SceneError(
            f"{flag} = {show(text)} is not a number; allowed: {spec.allowed()}"
        ) from None
    if not spec.accepts(value):
        raise SceneError(f"{flag} = {show(text)}; allowed: {spec.allowed()}")
    return replace(scene, solver={**scene.solver, "rtol": value})


def _check_name(chk: _Checker, value: Any) -> str:
    """[scene] name: it names the output directory, so a short file-name-safe label."""
    name = chk.string("scene", "name", value)
    allowed = (
        f"a file-name-safe label: 1 to {MAX_NAME_CHARS} characters, no '/', '\\', NUL or "
        "control characters, not '.' or '..'"
    )
    if (
        not name
        or len(name) > MAX_NAME_CHARS
        or any(ch in name for ch in "/\\")
        or not name.isprintable()
        or name in (".", "..")
    ):
        chk.fail(f"[scene] name = {show(name)} ({len(name)} characters)", allowed)
    return name


def check_title(scene: Scene) -> None:
    """Refuse a title matplotlib cannot draw, before any work.

    The title is drawn once on a small figure (so this imports matplotlib: only for a run
    that draws figures); broken mathtext (an unknown command, an unclosed brace) is refused.

    Parameters
    ----------
    scene : Scene
        The scene whose ``title`` is checked.

    Raises
    ------
    SceneError
        A title that cannot be drawn.
    """
    from .figures import title_problem

    problem = title_problem(scene.title)
    if problem is not None:
        raise SceneError(
            f"{scene.source}: [scene] title = {show(scene.title)} cannot be drawn "
            f"({problem[:120]}); allowed: text, with mathtext between pairs of $ "
            "(write \\$ for a dollar sign)"
        )


def _check_figures(chk: _Checker, output: dict[str, Any], manifold: bool) -> list[str]:
    """[output] figures: known names; those drawing the loci only with a [manifold]."""
    default = DEFAULT_MANIFOLD_FIGURES if manifold else DEFAULT_FIGURES
    figs = output.get("figures", list(default))
    if not isinstance(figs, list) or not all(isinstance(f, str) for f in figs):
        chk.fail(f"[output] figures = {show(figs)}", f"a list of names from {_list(FIGURES)}")
    for f in figs:
        if f not in FIGURES:
            chk.fail(f"[output] figures contains {show(f)}", f"names from {_list(FIGURES)}")
        if f in MANIFOLD_FIGURES and not manifold:
            chk.fail(
                f"[output] figures contains {show(f)} but the scene has no [manifold] section",
                f"{_list(MANIFOLD_FIGURES)} with a [manifold] section only",
            )
    return figs


def _check_sections(chk: _Checker, data: dict[str, Any]) -> None:
    """Known sections, each a table of known keys; [surface] and [loading] present."""
    sections = {*_SECTIONS, "surface"}
    for section, value in data.items():
        if section not in sections:
            chk.fail(
                f"unknown section [{section if len(section) <= 60 else section[:57] + '...'}]",
                f"sections are {_list(sections)}",
            )
        if not isinstance(value, dict):
            chk.fail(
                f"{section} = {show(value)} must be a [{section}] table",
                f"write it as a section [{section}]",
            )
        keys = _section_keys(section)
        unknown = set(value) - keys if section != "sweep" else set()
        if unknown:
            key = sorted(unknown)[0]
            chk.fail(
                f"[{section}] unknown key {show(key)}",
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
            f"[surface] model = {show(model)}: {registry.body_entry(model).refusal}",
            f"models with a contact-loss path are {_list(with_path)}",
        )
    if model not in with_path:
        chk.fail(
            f"[surface] model = {show(model)} is not a known model", f"one of {_list(with_path)}"
        )
    entry = registry.body_entry(model)
    params = entry.parameters
    required = tuple(p.name for p in entry.required)
    optional = tuple(p.name for p in entry.optional)
    extra = set(surf_in) - {"model", *params}
    if extra:
        key = sorted(extra)[0]
        chk.fail(
            f"[surface] key {show(key)} does not apply to model {show(model)}",
            f"{model} takes {_list(required + optional)}",
        )
    surface: dict[str, Any] = {"model": model}
    for key in required:
        if key not in surf_in:
            chk.fail(
                f"[surface] missing key {show(key)} for model {show(model)}",
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


class _Checker:
    def __init__(self, source: str) -> None:
        self.source = source

    def fail(self, what: str, allowed: str) -> NoReturn:
        raise SceneError(f"{self.source}: {what}; allowed: {allowed}")

    def string(self, section: str, key: str, value: Any) -> str:
        if not isinstance(value, str):
            self.fail(
                f"[{section}] {key} = {show(value)} has the wrong type ({type(value).__name__})",
                "a string",
            )
        return value

    def number(self, section: str, key: str, value: Any, spec: Parameter | None = None) -> float:
        """A finite number in the range of ``spec`` (default: the [loading]/[solver] key's)."""
        spec = _NUMBERS[key] if spec is None else spec
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            self.fail(
                f"[{section}] {key} = {show(value)} has the wrong type ({type(value).__name__})",
                spec.allowed(),
            )
        try:
            float(value)
        except OverflowError:
            self.fail(
                f"[{section}] {key} = {show(value)} is beyond the float range", spec.allowed()
            )
        if not spec.accepts(float(value)):
            u = f" [{spec.unit}]" if spec.unit else ""
            self.fail(f"[{section}] {key} = {show(value)}{u}", spec.allowed())
        return float(value)

    def numbers(
        self, section: str, key: str, values: list, spec: Parameter | None = None
    ) -> list[float]:
        """A non-empty list of numbers, each as :meth:`number`."""
        if not values:
            self.fail(f"[{section}] {key} = []", "a number or a non-empty list of numbers")
        if len(values) > MAX_LIST:
            self.fail(
                f"[{section}] {key} is a list of {len(values)} values",
                f"at most {MAX_LIST} values (the limit of a list)",
            )
        return [self.number(section, key, v, spec) for v in values]


def _list(items) -> str:
    return ", ".join(sorted(items) if isinstance(items, (set, dict)) else items)
