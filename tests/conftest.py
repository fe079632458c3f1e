"""Fixtures every test folder shares; the only place (with the folders' own conftest.py)
that imports the tests' helper modules.

* ``package_modules``: every module of the installed package ``cusp`` (dotted name ->
  source file), from the package map of ``pyproject.toml``; ``package_module``, a test
  parameter, is one of them (parametrized at collection by :func:`pytest_generate_tests`);
* ``load_script``: a script of ``scripts/`` loaded from its file as a module (the script
  imports its shared helpers from the installed ``cusp._scripts``: the import path is
  left as it is);
* ``toy_body``: the toy body of ``tests/models/_toy_body.py`` (closed forms, registered by
  the tests), used by the model and the application tests;
* ``stand_ins``: the stand-in model packages of ``tests/verification/_stand_ins.py``, used
  by the verification and the application tests.
"""

from __future__ import annotations

import importlib.util
import sys
from collections.abc import Callable
from pathlib import Path
from types import ModuleType

import pytest

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]


def package_dirs() -> dict[str, Path]:
    """Each package of the distribution -> its folder in the repository."""
    pyproject = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    mapping = pyproject["tool"]["setuptools"]["package-dir"]
    return {name: ROOT / folder for name, folder in mapping.items()}


def package_modules() -> dict[str, Path]:
    """Every module of the installed package: dotted name -> source file."""
    out = {}
    for package, folder in package_dirs().items():
        for path in sorted(folder.glob("*.py")):
            name = package if path.stem == "__init__" else f"{package}.{path.stem}"
            out[name] = path
    return out


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    """``package_module``: each module of the package that can be imported on its own (not
    ``cusp.__main__``, which runs the command)."""
    if "package_module" in metafunc.fixturenames:
        names = sorted(name for name in package_modules() if not name.endswith("__main__"))
        metafunc.parametrize("package_module", names)


@pytest.fixture(scope="session", name="package_modules")
def package_modules_fixture() -> dict[str, Path]:
    """Every module of the installed package: dotted name -> source file."""
    return package_modules()


@pytest.fixture(scope="session")
def load_script() -> Callable[[str], ModuleType]:
    """``load_script(name)``: ``scripts/<name>.py`` executed as a fresh module ``name`` (its
    ``main()`` not run). The module is in ``sys.modules`` while it executes (dataclasses
    look their module up there), and is taken out again afterwards."""

    def load(name: str) -> ModuleType:
        path = ROOT / "scripts" / f"{name}.py"
        if not path.is_file():
            raise FileNotFoundError(f"no script {name!r}: {path} does not exist")
        spec = importlib.util.spec_from_file_location(name, path)
        assert spec is not None and spec.loader is not None, path
        module = importlib.util.module_from_spec(spec)
        before = sys.modules.get(name)
        sys.modules[name] = module
        try:
            spec.loader.exec_module(module)
        finally:
            if before is None:
                sys.modules.pop(name, None)
            else:
                sys.modules[name] = before
        return module

    return load


@pytest.fixture(scope="session")
def toy_body() -> ModuleType:
    """The toy body's module: ``BrushBody``, ``REQUIRED``, ``path_closed_forms``."""
    from tests.models import _toy_body

    return _toy_body


@pytest.fixture(scope="session")
def stand_ins() -> ModuleType:
    """The stand-in model packages: ``fake_models(GoodRough)``, ``fake_models(NaiveRough)``."""
    from tests.verification import _stand_ins

    return _stand_ins
