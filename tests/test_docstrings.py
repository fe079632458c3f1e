"""The public API's docstrings pass numpydoc's validation (issue 32, point 2).

The public API: every class and function named in ``cusp.continuation.__all__``,
``cusp.models.__all__`` and ``cusp.app.scene.__all__`` (the scene schema's entry points),
and the public methods and properties those classes define or inherit from a class of
:mod:`cusp`. Each is run through :func:`numpydoc.validate.validate`; the test fails listing
every violation of the checks in :data:`CHECKS`, one line each.
"""

from __future__ import annotations

import importlib
import inspect
import warnings

from numpydoc import validate  # the test extra installs it

#: the modules whose ``__all__`` is the public API checked here
PUBLIC_MODULES = ("cusp.continuation", "cusp.models", "cusp.app.scene")

#: the numpydoc checks enforced (numpydoc.validate.ERROR_MSGS has their messages)
CHECKS = frozenset(
    {
        "GL02",  # closing quotes on their own line
        "GL03",  # no double blank lines
        "GL05",  # no tabs
        "GL06",  # only known section names
        "GL07",  # sections in numpydoc's order
        "GL08",  # a docstring exists
        "GL09",  # deprecation note first
        "GL10",  # a valid reST directive
        "SS01",  # a summary exists
        "SS02",  # the summary starts with a capital letter
        "SS03",  # the summary ends with a period
        "SS04",  # the summary has no leading whitespace
        "SS05",  # a summary in the infinitive ("Return", not "Returns")
        "SS06",  # the summary fits on one line
        "PR01",  # every parameter is documented
        "PR02",  # no parameter documented that does not exist
        "PR03",  # parameters in the signature's order
        "PR04",  # every parameter has a type
        "PR05",  # the type does not end with a period
        "PR06",  # "int", "bool", "str" (not "integer", "boolean", "string")
        "PR07",  # every parameter has a description
        "PR09",  # parameter descriptions end with a period
        "PR10",  # "name : type" with a space before the colon
        "RT01",  # what a function returns is documented
        "RT02",  # return entries name a type, not only a name
        "RT03",  # each return entry has a description
        "RT05",  # return descriptions end with a period
        "YD01",  # what a generator yields is documented
    }
)
# Not enforced, and why:
#   GL01  the house style opens the summary on the line of the opening quotes (PEP 257)
#   ES01  a property or a small helper says all in its summary; no extended text is forced
#   PR08  descriptions often open with a symbol or a code name (``g_T``, σ*), not a capital
#   RT04  the same, for return descriptions
#   SA01  "See Also" is written where it helps, not everywhere
#   EX01  Examples are given where they are cheap; those given run in tests/test_doctests.py


def _members(cls: type):
    """The public methods and properties of ``cls`` and its :mod:`cusp` bases.

    An override without a docstring of its own is left out when a base documents the name:
    it inherits that docstring (as :func:`inspect.getdoc` and Sphinx's autodoc read it),
    which is checked on the base.
    """
    documented: set[str] = set()
    for base in reversed(cls.__mro__):
        if not base.__module__.startswith("cusp"):
            continue
        for name, value in vars(base).items():
            if name.startswith("_"):
                continue
            if isinstance(value, (staticmethod, classmethod)):
                value = value.__func__
            if not (inspect.isfunction(value) or isinstance(value, property)):
                continue
            if value.__doc__:
                documented.add(name)
            elif name in documented:
                continue
            yield name, value


def public_api() -> dict[str, object]:
    """Qualified name -> object, each object once (under the first name that reaches it)."""
    out: dict[str, object] = {}
    seen: set[int] = set()

    def add(name: str, obj: object) -> None:
        if id(obj) not in seen:
            seen.add(id(obj))
            out[name] = obj

    for modname in PUBLIC_MODULES:
        module = importlib.import_module(modname)
        for name in module.__all__:
            obj = getattr(module, name)
            if not (inspect.isclass(obj) or inspect.isfunction(obj)):
                continue  # constants (RTOL_DEFAULT, FIGURES) carry no docstring of their own
            add(f"{modname}.{name}", obj)
            if inspect.isclass(obj):
                members = {}
                for member, value in _members(obj):
                    members[member] = value  # a subclass's override replaces the base's
                for member, value in members.items():
                    add(f"{modname}.{name}.{member}", value)
    return out


def violations(name: str, obj: object) -> list[str]:
    """The violations of :data:`CHECKS` in ``obj``'s docstring, as ``name: CODE message``."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = validate.validate(validate.get_doc_object(obj))
    checks = CHECKS
    if getattr(obj, "_is_protocol", False):
        checks = CHECKS - {"PR01"}  # a Protocol has no constructor of its own to document
    found = [f"{name}: {code} {msg}" for code, msg in result["errors"] if code in checks]
    found += [f"{name}: numpydoc could not parse it: {w.message}" for w in caught]
    return found


def test_the_public_api_is_found():
    """The enumeration reaches the entry points, methods and properties (it cannot pass by
    finding nothing)."""
    api = public_api()
    for name in (
        "cusp.continuation.trace",
        "cusp.continuation.Problem",
        "cusp.continuation.Branch.special",
        "cusp.continuation.ContinuationOptions",
        "cusp.models.ContactLoss.run",
        "cusp.models.Sphere.stick_force_ratio",
        "cusp.app.scene.load_scene",
    ):
        assert name in api
    assert any(name.endswith("RoughSurface.load_integral") for name in api)  # inherited
    assert len(api) > 200


def test_public_docstrings_pass_numpydoc_validation():
    """Every public class, function, method and property passes the chosen checks."""
    found = [v for name, obj in public_api().items() for v in violations(name, obj)]
    assert not found, f"{len(found)} numpydoc violations:\n" + "\n".join(found)


def test_the_validation_can_fail():
    """A docstring without parameter and return sections is caught."""

    def bad(x, y):
        """sum of x and y"""
        return x + y

    codes = {v.split()[1] for v in violations("bad", bad)}
    assert {"SS02", "SS03", "PR01", "RT01"} <= codes
