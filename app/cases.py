"""The computations a scene describes: its bodies, its contact-loss models, the solver
options of its paths, and the cases (one per listed μ or F'_N)."""

from __future__ import annotations

import math
from typing import Any, NamedTuple

from .scene import Scene, SceneError

__all__ = ["Case", "build_body", "make_model", "solver_options", "loci_options", "length_notes"]


class Case(NamedTuple):
    """One case of a scene: its μ, its F'_N [N] and the traced path."""

    mu: float
    load: float
    result: Any


def build_body(scene: Scene, mu: float | None = None) -> Any:
    """The body a scene describes, built by its entry in :mod:`cusp.models.registry` (which
    imports only that body's module), with friction coefficient ``mu`` (default: the
    scene's, the first listed one for a list)."""
    from cusp.models import registry
    from cusp.models.protocol import require_path_body

    params = dict(scene.surface)
    model = params.pop("model")
    if mu is not None:
        params["mu"] = mu
    elif isinstance(params.get("mu"), list):
        params["mu"] = params["mu"][0]
    try:
        return require_path_body(registry.build_body(model, **params))
    except ValueError as exc:
        text = " ".join(str(exc).split())
        if not any(text.startswith(key) for key in params):  # name the body's parameters
            given = ", ".join(f"{k} = {v!r}" for k, v in params.items())
            text = f"{text} (model {model!r} with {given})"
        raise SceneError(f"{scene.source}: [surface] {text}") from None


def make_model(scene: Scene, body: Any, load: float) -> Any:
    """The contact-loss path of ``body`` under the scene's loading, reduced to ``load``."""
    from cusp.models.contact_loss import ContactLoss
    from cusp.models.errors import ModelParameterError, NoComplianceLawError

    try:
        return ContactLoss(
            body,
            scene.loading["normal_load"],
            scene.loading["max_slip"],
            load,
            area_reading=scene.options["area_reading"],
        )
    except ModelParameterError as exc:
        at = f" at [surface] mu = {body.mu!r}" if len(scene.mus) > 1 else ""
        raise SceneError(f"{scene.source}: [loading]{at} {exc}") from None
    except NoComplianceLawError as exc:  # a registered body without a path or a refusal
        raise SceneError(f"{scene.source}: [surface] {exc}") from None


def solver_options(scene: Scene) -> Any:
    """The continuation options of the paths: the defaults
    (:data:`cusp.models.contact_loss.DEFAULT_OPTIONS`) with the scene's [solver] (``rtol``,
    and ``ds_max`` and ``tol`` when given)."""
    from cusp.models.contact_loss import DEFAULT_OPTIONS

    if not scene.solver:
        return DEFAULT_OPTIONS
    try:
        return DEFAULT_OPTIONS.replace(**scene.solver)
    except ValueError as exc:
        raise SceneError(f"{scene.source}: [solver] {exc}") from None


def loci_options(scene: Scene) -> Any:
    """The continuation options of the loci of a [manifold] scene (and of its regime map):
    their own defaults (:data:`cusp.models.manifold.DEFAULT_OPTIONS`) at the scene's
    ``[solver] rtol``; ``ds_max`` and ``tol`` of [solver] are the paths' only."""
    from cusp.models.manifold import DEFAULT_OPTIONS

    rtol = scene.solver.get("rtol")
    return DEFAULT_OPTIONS if rtol is None else DEFAULT_OPTIONS.replace(rtol=rtol)


#: lengths this far apart (a factor) look like one of them in another unit
UNIT_GAP = 1e4
#: the units a length in µm may have been given in by mistake: name -> µm per unit
_UNITS = {"metres": 1e6, "millimetres": 1e3, "nanometres": 1e-3}


def length_notes(scene: Scene) -> list[str]:
    """Notes on lengths that look like the wrong unit: σ* ([surface] sigma) or max_slip more
    than :data:`UNIT_GAP` times below or above every other length of the scene (σ*,
    max_slip, radius; all in µm). Each note names the field, how far it is from the others
    and the unit that would bring it among them (2e-06 "µm" is 2 µm given in metres)."""
    lengths = {
        ("surface", "sigma"): scene.surface.get("sigma"),
        ("loading", "max_slip"): scene.loading.get("max_slip"),
        ("surface", "radius"): scene.surface.get("radius"),
    }
    given = {k: float(v) for k, v in lengths.items() if isinstance(v, float) and v > 0.0}
    notes: list[str] = []
    for key in (("loading", "max_slip"), ("surface", "sigma")):
        if key not in given or len(given) < 2 or (notes and len(given) == 2):
            continue  # (of two lengths far apart, the note names max_slip)
        value = given[key]
        others = {k: v for k, v in given.items() if k != key}
        below = all(value * UNIT_GAP < v for v in others.values())
        above = all(value > UNIT_GAP * v for v in others.values())
        if not (below or above):
            continue
        centre = math.exp(sum(math.log(v) for v in others.values()) / len(others))
        unit, per = min(_UNITS.items(), key=lambda u: abs(math.log10(value * u[1] / centre)))
        listed = ", ".join(f"{k[1]} = {v!r} µm" for k, v in others.items())
        hint = ""
        if abs(math.log10(value * per / centre)) < abs(math.log10(value / centre)) - 2.0:
            hint = f"; if it was given in {unit}, {value!r} {unit} is {value * per:.6g} µm"
        notes.append(
            f"[{key[0]}] {key[1]} = {value!r} µm is more than {UNIT_GAP:g} times "
            f"{'below' if below else 'above'} the scene's other lengths ({listed}): lengths "
            f"are in µm{hint}"
        )
    return notes
