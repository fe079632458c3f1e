"""The one list of bodies: scene model names, their parameters, their factories.

Every body a scene can name is an entry here. The scene schema (:mod:`cusp.app.scene`: the
model names, each body's parameters with unit and allowed range, which are required and
which form an all-or-none group, the refusal of bodies without a contact-loss path) and the
runner (:func:`cusp.app.run.build_body`) are read from it; nothing else lists bodies.

An entry names its factory lazily, as ``"module:attribute"`` (a class or a function taking
the body's parameters as keywords and returning a :class:`~cusp.models.protocol.PathBody`):
the module is imported only when a body is built, so parsing a scene imports no body and an
exponential scene never imports the Gaussian or quadrature code.

Adding a body is one module (see :mod:`cusp.models.protocol`) plus one registry line::

    from cusp.models.registry import MU, Parameter, register_body

    register_body(
        "toy-brush",
        "mypackage.brush:BrushBody",
        required=(MU, Parameter("stiffness", "N/µm²"), Parameter("compliance")),
        description="a brush of elastic bristles",
    )

after which a scene may say ``model = "toy-brush"``. :func:`unregister_body` removes it
again, :func:`registered_body` registers for the duration of a ``with`` block.

Units: lengths µm, forces N, moduli N/µm².
"""

from __future__ import annotations

import importlib
import math
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

from .errors import ModelParameterError

__all__ = [
    "Parameter",
    "BodyEntry",
    "register_body",
    "unregister_body",
    "registered_body",
    "body_entry",
    "body_names",
    "surface_keys",
    "build_body",
    "SIGMA",
    "NU",
    "MU",
    "E",
    "RADIUS",
    "DENSITY",
    "NOMINAL_AREA",
    "SHAPE",
    "LOAD_SCALE",
]


@dataclass(frozen=True)
class Parameter:
    """A numeric parameter: its name, unit and allowed range.

    The value must also be finite. The default range is ``> 0``.

    Parameters
    ----------
    name : str
        The keyword (a Python identifier), as in a scene's ``[surface]``.
    unit : str, optional
        Its unit (``"µm"``, ``"N"``, ``"N/µm²"``, ``"1/µm²"``, ``"µm²"``; "" if none).
    lower, upper : float, optional
        The bounds (±inf for none; default 0 and inf).
    lower_inclusive, upper_inclusive : bool, optional
        Whether each bound itself is allowed.
    description : str, optional
        What it is, in words.

    Raises
    ------
    ModelParameterError
        A name that is no identifier, or ``lower >= upper``.
    """

    name: str
    unit: str = ""
    lower: float = 0.0
    upper: float = math.inf
    lower_inclusive: bool = False
    upper_inclusive: bool = False
    description: str = ""

    def __post_init__(self) -> None:
        if not (isinstance(self.name, str) and self.name.isidentifier()):
            raise ModelParameterError(
                f"Parameter name must be a Python identifier, got {self.name!r}"
            )
        if math.isnan(self.lower) or math.isnan(self.upper) or not self.lower < self.upper:
            raise ModelParameterError(
                f"Parameter {self.name}: lower must be < upper, got lower={self.lower!r}, "
                f"upper={self.upper!r}"
            )

    def range_text(self) -> str:
        """Return the allowed range as written in messages.

        Returns
        -------
        str
            ``(-1, 0.5]``, ``> 0``, ``<= 1``, or "" for any finite number.
        """
        lo, hi = self.lower, self.upper
        if math.isfinite(lo) and math.isfinite(hi):
            left = "[" if self.lower_inclusive else "("
            right = "]" if self.upper_inclusive else ")"
            return f"{left}{lo:g}, {hi:g}{right}"
        if math.isfinite(lo):
            return f"{'>=' if self.lower_inclusive else '>'} {lo:g}"
        if math.isfinite(hi):
            return f"{'<=' if self.upper_inclusive else '<'} {hi:g}"
        return ""

    def allowed(self) -> str:
        """Return the allowed values as written in messages.

        Returns
        -------
        str
            ``a finite number <range> [<unit>]``.
        """
        rng = self.range_text()
        unit = f" [{self.unit}]" if self.unit else ""
        return f"a finite number{' ' + rng if rng else ''}{unit}"

    def accepts(self, value: float) -> bool:
        """Return whether ``value`` is finite and within the range.

        Parameters
        ----------
        value : float
            The value, in the parameter's unit.

        Returns
        -------
        bool
            True if allowed.
        """
        lo_ok = value >= self.lower if self.lower_inclusive else value > self.lower
        hi_ok = value <= self.upper if self.upper_inclusive else value < self.upper
        return math.isfinite(value) and lo_ok and hi_ok


#: parameters shared by the built-in bodies (reuse them for a body of your own)
SIGMA = Parameter("sigma", "µm", description="composite rms roughness σ*")
NU = Parameter("nu", "", -1.0, 0.5, upper_inclusive=True, description="Poisson ratio ν")
MU = Parameter("mu", "", description="friction coefficient μ")
E = Parameter("E", "N/µm²", description="Young's modulus of each body")
RADIUS = Parameter("radius", "µm", description="summit radius ρ* or sphere radius R")
DENSITY = Parameter("density", "1/µm²", description="summit density η")
NOMINAL_AREA = Parameter("nominal_area", "µm²", description="nominal contact area A_n")
SHAPE = Parameter("shape", "", description="Weibull shape k")
#: the load scale K = (4/3) E* √ρ* η A_n of a rough surface
LOAD_SCALE = (E, RADIUS, DENSITY, NOMINAL_AREA)


@dataclass(frozen=True)
class BodyEntry:
    """One registered body (see :func:`register_body` for the fields)."""

    name: str
    factory: str | Callable[..., Any]
    required: tuple[Parameter, ...] = ()
    optional: tuple[Parameter, ...] = ()
    optional_name: str = "the optional parameters"
    refusal: str | None = None
    description: str = ""
    _by_name: dict[str, Parameter] = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        by_name = {p.name: p for p in (*self.required, *self.optional)}
        object.__setattr__(self, "_by_name", by_name)

    @property
    def parameters(self) -> dict[str, Parameter]:
        """Every parameter by name, required first, in the order given."""
        return dict(self._by_name)

    @property
    def has_path(self) -> bool:
        """Can this body follow the contact-loss path (no refusal)?"""
        return self.refusal is None

    def load_factory(self) -> Callable[..., Any]:
        """The factory, importing its module now if it was named as ``"module:attribute"``."""
        if callable(self.factory):
            return self.factory
        module_name, _, attribute = self.factory.partition(":")
        try:
            obj: Any = importlib.import_module(module_name)
            for part in attribute.split("."):
                obj = getattr(obj, part)
        except (ImportError, AttributeError) as exc:
            raise ModelParameterError(
                f"body {self.name!r}: cannot load its factory {self.factory!r} ({exc})"
            ) from exc
        if not callable(obj):
            raise ModelParameterError(
                f"body {self.name!r}: factory {self.factory!r} is not callable, got {obj!r}"
            )
        return obj

    def build(self, **params: float) -> Any:
        """The body with these parameters (keywords as in the scene's ``[surface]``)."""
        return self.load_factory()(**params)


_REGISTRY: dict[str, BodyEntry] = {}


def register_body(
    name: str,
    factory: str | Callable[..., Any],
    *,
    required: Sequence[Parameter] = (),
    optional: Sequence[Parameter] = (),
    optional_name: str = "the optional parameters",
    refusal: str | None = None,
    description: str = "",
    replace: bool = False,
) -> BodyEntry:
    """Register a body under the scene model name ``name``.

    Parameters
    ----------
    name : str
        The scene's ``[surface] model`` name.
    factory : str or callable
        ``"module:attribute"`` (imported only when a body is built; dotted attributes such
        as ``"module:Class.method"`` work) or a callable, taking the parameters as keywords
        and returning a :class:`~cusp.models.PathBody`.
    required : sequence of Parameter, optional
        The parameters a scene must give.
    optional : sequence of Parameter, optional
        An all-or-none group: a scene gives every one of them or none.
    optional_name : str, optional
        The group's name in messages, e.g. "the load scale".
    refusal : str or None, optional
        For a body without a contact-loss path, why (a scene naming it is refused with
        this text).
    description : str, optional
        What the body is, in words.
    replace : bool, optional
        Allow replacing an entry of the same name.

    Returns
    -------
    BodyEntry
        The new entry.

    Raises
    ------
    ModelParameterError
        A name already taken (without ``replace``), an empty name, a malformed factory, or
        a parameter given twice or named ``model``.
    """
    if not isinstance(name, str) or not name.strip() or name != name.strip():
        raise ModelParameterError(f"body name must be a non-empty string, got {name!r}")
    if name in _REGISTRY and not replace:
        raise ModelParameterError(
            f"body {name!r} is already registered (pass replace=True to replace it, or "
            f"unregister_body({name!r}) first)"
        )
    if isinstance(factory, str):
        module_name, colon, attribute = factory.partition(":")
        if not (colon and module_name and attribute):
            raise ModelParameterError(
                f"body {name!r}: factory must be 'module:attribute' or a callable, got {factory!r}"
            )
    elif not callable(factory):
        raise ModelParameterError(
            f"body {name!r}: factory must be 'module:attribute' or a callable, got {factory!r}"
        )
    params = (*required, *optional)
    names = [p.name for p in params if isinstance(p, Parameter)]
    if len(names) != len(params):
        bad = next(p for p in params if not isinstance(p, Parameter))
        raise ModelParameterError(f"body {name!r}: parameters must be Parameter, got {bad!r}")
    if len(set(names)) != len(names) or "model" in names:
        raise ModelParameterError(
            f"body {name!r}: parameter names must be distinct and not 'model', got {names}"
        )
    if refusal is not None and not (isinstance(refusal, str) and refusal):
        raise ModelParameterError(f"body {name!r}: refusal must be a non-empty string or None")
    entry = BodyEntry(
        name,
        factory,
        tuple(required),
        tuple(optional),
        optional_name,
        refusal,
        description,
    )
    _REGISTRY[name] = entry
    return entry


def unregister_body(name: str) -> BodyEntry:
    """Remove a body from the registry.

    Parameters
    ----------
    name : str
        The registered name.

    Returns
    -------
    BodyEntry
        The entry removed.

    Raises
    ------
    ModelParameterError
        No body of that name is registered.
    """
    entry = body_entry(name)
    del _REGISTRY[name]
    return entry


@contextmanager
def registered_body(
    name: str, factory: str | Callable[..., Any], **kwargs: Any
) -> Iterator[BodyEntry]:
    """Register a body for the duration of a ``with`` block.

    Afterwards the registry is as before (an entry it replaced is put back).

    Parameters
    ----------
    name : str
        The scene's ``[surface] model`` name.
    factory : str or callable
        As for :func:`register_body`.
    **kwargs
        The other arguments of :func:`register_body`.

    Yields
    ------
    BodyEntry
        The entry, registered inside the block.
    """
    previous = _REGISTRY.get(name)
    entry = register_body(name, factory, **kwargs)
    try:
        yield entry
    finally:
        if _REGISTRY.get(name) is entry:
            del _REGISTRY[name]
        if previous is not None:
            _REGISTRY[name] = previous


def body_entry(name: str) -> BodyEntry:
    """The entry of a registered body (ModelParameterError naming the known ones if none)."""
    try:
        return _REGISTRY[name]
    except (KeyError, TypeError):
        raise ModelParameterError(
            f"no body {name!r} is registered; registered: {', '.join(body_names())}"
        ) from None


def body_names(*, with_path: bool | None = None) -> tuple[str, ...]:
    """Registered model names, sorted; ``with_path=True`` only those that can follow the
    contact-loss path, ``False`` only the refused ones."""
    return tuple(
        sorted(n for n, e in _REGISTRY.items() if with_path is None or e.has_path == with_path)
    )


def surface_keys() -> frozenset[str]:
    """Every key a scene's ``[surface]`` may hold: ``model`` and the parameters of every
    registered body."""
    return frozenset({"model"}.union(*(e.parameters for e in _REGISTRY.values())))


def build_body(name: str, **params: float) -> Any:
    """The body registered as ``name``, built with ``params`` (imports its module now)."""
    return body_entry(name).build(**params)


# ------------------------------------------------------------------------------------------
# The built-in bodies: one line each.
_ROUGH = (SIGMA, NU, MU)

register_body(
    "rough-exponential",
    "cusp.models.exponential:ExponentialRoughSurface",
    required=_ROUGH,
    optional=LOAD_SCALE,
    optional_name="the load scale",
    description="exponential summit heights (Eqs 1, 9, 12, 15), closed form",
)
#: the Gaussian surface's σ*: its load integral J = σ*^{3/2} F_{3/2} needs σ*^{3/2} within the
#: float range (3.18e205^{3/2} overflows); far below that bound every scene's reduction range
#: is empty anyway (refused by the path, naming max_slip)
GAUSSIAN_SIGMA = Parameter(
    "sigma", "µm", upper=3e205, description="composite rms roughness σ* (σ*^{3/2} a float)"
)

register_body(
    "rough-gaussian",
    "cusp.models.gaussian:GaussianRoughSurface",
    required=(GAUSSIAN_SIGMA, NU, MU, *LOAD_SCALE),
    description="Gaussian summit heights (Greenwood-Williamson)",
)
register_body(
    "rough-weibull",
    "cusp.models.density:weibull_surface",
    required=(*_ROUGH, SHAPE, *LOAD_SCALE),
    description="Weibull summit heights of standard deviation sigma (quadrature)",
)
register_body(
    "sphere",
    "cusp.models.sphere:Sphere",
    required=(RADIUS, E, NU, MU),
    description="two identical elastic spheres (Hertz-Mindlin, Eqs 16-22)",
)
register_body(
    "cylinder",
    "cusp.models.cylinder:Cylinder",
    refusal="a cylinder has no compliance law in the paper (its 2-D elastic displacement is "
    "defined only up to a datum), so it has no contact-loss path",
    description="two parallel cylinders (Eqs 23-29), no compliance law",
)
register_body(
    "flat",
    "cusp.models.flat:FlatPlane",
    refusal="flat planes have no compliance law (they slide as a whole at F_T = mu F_N), so "
    "they have no contact-loss path",
    description="two ideally flat planes (Eqs 30-31), no compliance law",
)
