"""A folder of the repository at another git revision, imported as a package of its own:
what `bench_ab.py` (the engine, ``continuation/``) and `bench_figures.py` (the figures,
``app/``) compare this tree against, in one process."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parents[2]


def load_folder(rev: str, folder: str, into: Path, name: str) -> ModuleType:
    """The package ``folder`` (``"continuation"``, ``"app"``) of git revision ``rev``,
    extracted under ``into`` and imported as module ``name`` from its ``__init__.py`` (its
    relative imports resolve through that name; its absolute ones, ``cusp.*``, to this
    tree; the import path is left as it is)."""
    target = into / name
    target.mkdir()
    archive = subprocess.run(
        ["git", "archive", rev, folder], cwd=ROOT, check=True, capture_output=True
    ).stdout
    subprocess.run(
        ["tar", "-x", "--strip-components=1", "-C", str(target)], input=archive, check=True
    )
    spec = importlib.util.spec_from_file_location(
        name, target / "__init__.py", submodule_search_locations=[str(target)]
    )
    if spec is None or spec.loader is None:
        raise RuntimeError(f"cannot load {folder}/ of revision {rev!r} from {target}")
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    except BaseException:
        del sys.modules[name]
        raise
    return module
