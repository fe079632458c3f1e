"""The contact-loss protocol (cusp.models.protocol) and the body registry (cusp.models.registry)."""

from __future__ import annotations

import json
import math
import pathlib
import subprocess
import sys
import types

import pytest

from cusp.models import (
    ContactLevels,
    Cylinder,
    ExponentialRoughSurface,
    FlatPlane,
    GaussianRoughSurface,
    ModelParameterError,
    NoComplianceLawError,
    PathBody,
    Sphere,
    registry,
)
from cusp.models.contact_loss import ContactLoss
from cusp.models.protocol import sliding_level
from cusp.models.registry import Parameter

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCALE = dict(E=0.2, radius=10.0, density=0.01, nominal_area=1e6)


# ------------------------------------------------------------------ the levels of every body
def _bodies():
    """(name, make the body from the toy body's module, F_N0 [N], g_A [µm], a state (p, q) on
    the path's side of p = q)."""
    return [
        (
            "exponential",
            lambda toy: ExponentialRoughSurface(2.0, 0.3, 0.1),
            1000.0,
            0.34,
            (0.2, 1.1),
        ),
        (
            "exponential+scale",
            lambda toy: ExponentialRoughSurface(2.0, 0.3, 0.1, **SCALE),
            1000.0,
            0.34,
            None,
        ),
        ("gaussian", lambda toy: GaussianRoughSurface(2.0, 0.3, 0.1, **SCALE), 1000.0, 0.1, None),
        # (the sphere's levels are 1 − a/a0, 1 − c/a0: a = 0.95 a0, c = 0.7 a0)
        ("sphere", lambda toy: Sphere(1000.0, 0.2, 0.3, 0.1), 1000.0, 2.0, (0.05, 0.3)),
        ("toy", lambda toy: toy.BrushBody(0.1, 0.1, 0.05), 1000.0, 0.2, (0.9, 0.6)),
    ]


@pytest.mark.parametrize("name,make,F_N0,g_A,state", _bodies(), ids=[b[0] for b in _bodies()])
def test_levels_follow_the_protocol_with_exact_derivatives(name, make, F_N0, g_A, state, toy_body):
    body = make(toy_body)
    assert isinstance(body, PathBody)
    L = body.contact_levels(F_N0, g_A)
    assert isinstance(L, ContactLevels)
    assert isinstance(L.names, tuple) and len(L.names) == 2 and L.scale > 0
    p0 = L.p0
    # under F_N0 and without slip (point O): ℓ(p0) = 0, F̂_T = 0, Â_ST = 1, A_r/A_r0 = 1
    assert abs(L.log_normal_load(p0)[0]) <= 1e-12
    assert L.tangential_ratio(p0, p0)[0] == 0.0
    assert L.slip(p0, p0)[0] == 0.0
    assert L.stick_area(p0, p0)[0] == pytest.approx(1.0, rel=1e-14)
    assert L.area_ratio(p0)[0] == pytest.approx(1.0, rel=1e-12)
    # derivatives against central differences (O(h²) = 1e-10 truncation, 1e-16/h rounding)
    p, q = state if state is not None else (p0 - 0.1, p0 + 0.4)
    h = 1e-5
    for method, args in (
        ("log_normal_load", (p,)),
        ("tangential_ratio", (p, q)),
        ("slip", (p, q)),
        ("stick_area", (p, q)),
        ("area_ratio", (p,)),
        ("slip_area", (p, q)),  # optional members (protocol): the sphere's
        ("area_loss", (p,)),
    ):
        f = getattr(L, method, None)
        if f is None:
            continue
        value, *derivs = f(*args)
        for i, d in enumerate(derivs):
            up, down = list(args), list(args)
            up[i] += h
            down[i] -= h
            fd = (f(*up)[0] - f(*down)[0]) / (2 * h)
            assert d == pytest.approx(fd, rel=1e-7, abs=1e-9), (name, method, i, d, fd)


def test_slip_limit_is_the_slip_where_the_stick_zone_vanishes(toy_body):
    # sphere: κ(1 − p)² = s(p, 1) (c = 0 at q = 1); toy: βa0 p = s(p, 0); rough surfaces
    # never slide as a whole
    for body, F_N0, g_A in (
        (Sphere(1000.0, 0.2, 0.3, 0.1), 1000.0, 2.0),
        (toy_body.BrushBody(0.1, 0.1, 0.05), 1000.0, 0.2),
    ):
        L = body.contact_levels(F_N0, g_A)
        p = 0.2
        assert L.slip_limit(p) == pytest.approx(L.slip(p, sliding_level(L))[0], rel=1e-15)
    assert (
        ExponentialRoughSurface(2.0, 0.3, 0.1).contact_levels(1000.0, 0.34).slip_limit(0.0)
        == math.inf
    )


# ------------------------------------------------------------------ refusals
def test_an_object_that_is_no_body_is_refused_naming_the_protocol():
    for thing, lacks in (
        (object(), "mu, tangential_force, contact_levels"),
        (types.SimpleNamespace(mu=0.1), "tangential_force, contact_levels"),
    ):
        with pytest.raises(ModelParameterError) as err:
            ContactLoss(thing, 1000.0, 0.34, 850.0)
        msg = str(err.value)
        assert "body must follow the contact-loss protocol cusp.models.protocol.PathBody" in msg
        assert f"got {type(thing).__name__}, which lacks {lacks}" in msg


@pytest.fixture
def bad_levels_body(toy_body):
    """A toy body whose ``contact_levels`` returns the levels it is given."""

    class _BadLevelsBody(toy_body.BrushBody):
        def __init__(self, levels):
            super().__init__(0.1, 0.1, 0.05)
            self._levels = levels

        def contact_levels(self, normal_load, max_slip):
            return self._levels

    return _BadLevelsBody


def test_levels_that_do_not_follow_the_protocol_are_refused(bad_levels_body, toy_body):
    with pytest.raises(
        ModelParameterError,
        match=r"_BadLevelsBody.contact_levels\(\) returned "
        r"SimpleNamespace, which lacks .*slip_limit; it must follow",
    ):
        ContactLoss(bad_levels_body(types.SimpleNamespace(names=("a", "c"))), 1000.0, 0.2, 850.0)
    good = toy_body.BrushBody(0.1, 0.1, 0.05).contact_levels(1000.0, 0.2)
    for names in (("F_N", "c"), ("a", "a"), ("a",), ["a", "c"]):
        good.names = names
        with pytest.raises(ModelParameterError, match="names must be two distinct"):
            ContactLoss(bad_levels_body(good), 1000.0, 0.2, 850.0)


@pytest.mark.parametrize("body,name", [(Cylinder(), "Cylinder"), (FlatPlane(), "FlatPlane")])
def test_bodies_without_a_compliance_law_say_what_they_lack(body, name):
    assert isinstance(body, PathBody)  # they follow the protocol, and refuse the levels
    with pytest.raises(NoComplianceLawError) as err:
        ContactLoss(body, 1000.0, 0.34, 850.0)
    assert str(err.value) == (
        f"a {name} cannot follow the contact-loss path: the paper gives it no compliance law "
        "(no load-displacement relation g_T(F_T, F_N)), so there is no O-A-B-C path to trace; "
        "use a rough surface or a sphere"
    )


def test_sphere_without_its_parameters_is_refused_naming_them():
    with pytest.raises(ModelParameterError, match="needs Sphere.*missing: radius, E"):
        ContactLoss(Sphere(nu=0.3, mu=0.1), 1000.0, 2.0, 850.0)


# ------------------------------------------------------------------ the registry
def test_builtin_entries_are_the_scene_models_of_before():
    # the tables app/scene.py held before the registry (MODELS, _NO_COMPLIANCE)
    rough, scale = ("sigma", "nu", "mu"), ("E", "radius", "density", "nominal_area")
    want = {
        "rough-exponential": (rough, scale),
        "rough-gaussian": (rough + scale, ()),
        "rough-weibull": (rough + ("shape",) + scale, ()),
        "sphere": (("radius", "E", "nu", "mu"), ()),
    }
    for name, (required, optional) in want.items():
        entry = registry.body_entry(name)
        assert tuple(p.name for p in entry.required) == required, name
        assert tuple(p.name for p in entry.optional) == optional, name
        assert entry.has_path
    assert registry.body_names(with_path=True) == tuple(sorted(want))
    assert registry.body_names(with_path=False) == ("cylinder", "flat")
    assert "no compliance law" in registry.body_entry("cylinder").refusal
    assert registry.surface_keys() == {"model", *rough, *scale, "shape"}
    nu = registry.body_entry("sphere").parameters["nu"]
    assert (nu.unit, nu.range_text(), nu.allowed()) == (
        "",
        "(-1, 0.5]",
        "a finite number (-1, 0.5]",
    )
    assert registry.SIGMA.allowed() == "a finite number > 0 [µm]"


def test_register_twice_replace_and_context_manager_restore(toy_body):
    with registry.registered_body("toy-a", "tests.models._toy_body:BrushBody") as first:
        with pytest.raises(ModelParameterError, match="'toy-a' is already registered"):
            registry.register_body("toy-a", "tests.models._toy_body:BrushBody")
        with registry.registered_body("toy-a", toy_body.BrushBody, replace=True) as second:
            assert registry.body_entry("toy-a") is second
        assert registry.body_entry("toy-a") is first  # the replaced entry is back
    assert "toy-a" not in registry.body_names()
    with pytest.raises(
        ModelParameterError, match="no body 'toy-a' is registered; registered: cylinder"
    ):
        registry.unregister_body("toy-a")


@pytest.mark.parametrize(
    "args,kwargs,match",
    [
        (("", "m:f"), {}, "body name must be a non-empty string"),
        (("x", "no_colon"), {}, "factory must be 'module:attribute' or a callable"),
        (("x", 3), {}, "factory must be 'module:attribute' or a callable"),
        (("x", "m:f"), {"required": ("mu",)}, "parameters must be Parameter"),
        (("x", "m:f"), {"required": (Parameter("model"),)}, "not 'model'"),
        (("x", "m:f"), {"required": (registry.MU, registry.MU)}, "must be distinct"),
    ],
)
def test_register_body_checks_its_arguments(args, kwargs, match):
    with pytest.raises(ModelParameterError, match=match):
        registry.register_body(*args, **kwargs)
    assert "x" not in registry.body_names()


def test_parameter_ranges():
    with pytest.raises(ModelParameterError, match="must be a Python identifier"):
        Parameter("two words")
    with pytest.raises(ModelParameterError, match="lower must be < upper"):
        Parameter("x", lower=1.0, upper=1.0)
    p = Parameter("x", "µm", -math.inf, 2.0, upper_inclusive=True)
    assert p.allowed() == "a finite number <= 2 [µm]"
    assert p.accepts(2.0) and p.accepts(-1e300) and not p.accepts(2.5)
    assert not p.accepts(-math.inf) and not p.accepts(math.nan)
    assert Parameter("y", lower=-math.inf).allowed() == "a finite number"


def test_a_factory_that_cannot_be_loaded_says_which():
    with registry.registered_body("ghost", "tests.models.no_such_module:Body"):
        with pytest.raises(ModelParameterError, match="body 'ghost': cannot load its factory"):
            registry.build_body("ghost")
    with registry.registered_body("ghost", "tests.models._toy_body:NoSuchBody"):
        with pytest.raises(ModelParameterError, match="NoSuchBody"):
            registry.build_body("ghost")
    with registry.registered_body("ghost", "tests.models._toy_body:STIFFNESS"):
        with pytest.raises(ModelParameterError, match="is not callable"):
            registry.build_body("ghost")


def test_weibull_factory_sets_the_scale_from_sigma():
    surf = registry.build_body("rough-weibull", sigma=2.0, nu=0.3, mu=0.1, shape=2.0, **SCALE)
    assert type(surf).__name__ == "GeneralRoughSurface"
    assert surf.sigma == 2.0 and surf.has_load_scale
    # heights of standard deviation σ* = 2 µm (scale = σ*/√(Γ(2) − Γ(3/2)²) = 4.2 µm for k = 2)
    assert surf.heights.moments()[1] == pytest.approx(2.0, rel=1e-9)
    with pytest.raises(ModelParameterError, match="shape must be a finite number > 0"):
        registry.build_body("rough-weibull", sigma=2.0, nu=0.3, mu=0.1, shape=-1.0, **SCALE)


def test_parsing_scenes_imports_no_body_and_building_one_imports_only_it():
    code = (
        "import json, sys, pathlib; from cusp.app.scene import load_scene; "
        "from cusp.app.run import build_body; "
        "scenes = sorted(pathlib.Path('scenes').glob('*.toml')); "
        "parsed = [load_scene(s) for s in scenes]; "
        "bodies = ('exponential', 'gaussian', 'density', 'sphere', 'cylinder', 'flat', "
        "'_quadrature', 'gw', 'contact_loss'); "
        "loaded = lambda: [b for b in bodies if 'cusp.models.' + b in sys.modules]; "
        "before = loaded(); "
        "build_body(next(s for s in parsed if s.surface['model'] == 'sphere')); "
        "print(json.dumps([len(parsed), before, loaded()]))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=ROOT
    ).stdout
    n, before, after = json.loads(out)
    assert n == 6  # fig6, fig7, fig8, fig9, gaussian, sphere
    assert before == []
    assert after == ["sphere"]
