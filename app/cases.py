"""The computations a scene describes: its bodies, its contact-loss models, the solver
options of its paths, and the cases (one per listed μ or F'_N)."""

from __future__ import annotations

from typing import Any, NamedTuple

from .scene import Scene, SceneError

__all__ = ["Case", "build_body", "make_model", "solver_options", "loci_options"]


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
