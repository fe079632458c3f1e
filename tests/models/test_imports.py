"""Only what is asked is imported: models is lazy, the exponential surface needs no quadrature."""

from __future__ import annotations

import json
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]

CODE = """
import json, sys
import cusp.models as models
before = sorted(sys.modules)
s = models.ExponentialRoughSurface(sigma=2.0, nu=0.3, mu=0.1, E=0.2, radius=100.0,
                                   density=1e-4, nominal_area=1e6)
s.stick_force_ratio([1e-9, 0.5]); s.stick_area_ratio(0.5)
s.tangential_force(0.3, 1000.0); s.tangential_slip(50.0, 1000.0)
s.separation(1000.0); s.real_contact_area(1.0)
models.Sphere().stick_force_ratio(0.5); models.Cylinder().stick_area_ratio(0.5)
models.FlatPlane().stick_force_ratio(0.5)
print(json.dumps(sorted(sys.modules)))
"""


def test_exponential_work_imports_no_quadrature():
    out = subprocess.run(
        [sys.executable, "-c", CODE], capture_output=True, text=True, check=True, cwd=ROOT
    ).stdout
    mods = set(json.loads(out))
    heavy = ("scipy.integrate", "scipy.optimize", "cusp.models.gaussian", "cusp.models.gw")
    heavy += ("cusp.models._quadrature", "cusp.models.density", "matplotlib", "sympy", "mpmath")
    for name in heavy:
        assert name not in mods, name


def test_import_models_is_light():
    code = (
        "import sys, cusp.models; "
        "print(sorted(m for m in sys.modules if m.startswith(('cusp', 'scipy.'))))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=ROOT
    )
    assert out.stdout.strip() == "['cusp', 'cusp.models']"


def test_lazy_names():
    import cusp.models as models

    assert "GaussianRoughSurface" in dir(models)
    assert models.Sphere.__module__ == "cusp.models.sphere"
    try:
        models.NoSuchThing  # noqa: B018
    except AttributeError as exc:
        assert "NoSuchThing" in str(exc)
    else:  # pragma: no cover
        raise AssertionError("expected AttributeError")
