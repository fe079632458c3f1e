"""The package layout: one import name, layers that import only downwards, no import cycle,
small modules and functions, light imports.

The layers (repository folder → import name): ``continuation/`` → ``cusp.continuation``
(the engine: numpy and scipy only), ``examples/`` → ``cusp.examples`` and ``models/`` →
``cusp.models`` (each on the engine only), ``verification/`` → ``cusp.verification`` (may
use the physics), ``app/`` → ``cusp.app`` (may use everything), ``scenes/`` →
``cusp.scenes`` (data), and above them all ``scripts/_shared/`` → ``cusp._scripts`` (what
the scripts share; may use everything, nothing in the package imports it).

The modules of the package come from the ``package_modules`` fixture (tests/conftest.py).
"""

from __future__ import annotations

import ast
import json
import subprocess
import sys
from collections import defaultdict
from pathlib import Path

import pytest

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))

#: package -> the cusp packages it may import (besides itself)
ALLOWED = {
    "cusp": set(),
    "cusp.__main__": {"cusp.app"},  # ``python -m cusp``: the command
    "cusp.continuation": set(),
    "cusp.examples": {"cusp.continuation"},
    "cusp.models": {"cusp.continuation"},
    "cusp.verification": {"cusp.continuation", "cusp.models"},
    "cusp.app": {
        "cusp.continuation",
        "cusp.examples",
        "cusp.models",
        "cusp.verification",
        "cusp.scenes",
    },
    "cusp.scenes": set(),
    # the scripts' shared helpers: the top layer
    "cusp._scripts": {
        "cusp.continuation",
        "cusp.examples",
        "cusp.models",
        "cusp.verification",
        "cusp.app",
        "cusp.scenes",
    },
}
MAX_FUNCTION_LINES = 80
MAX_MODULE_LINES = 600
#: the engine's functions are shorter still (issue 28): one function, one decision
MAX_ENGINE_FUNCTION_LINES = 60

#: the engine's concept packages, lowest first: each imports only from lower ones (and from
#: the package's root modules, the vocabulary every concept shares: errors, outcomes, options)
ENGINE = "cusp.continuation"
ENGINE_ORDER = (
    "problem",  # a problem R(u, p) = 0: derivatives, real values, events, sympy
    "numerics",  # linear algebra, the Hermite arc, typical sizes, second differences
    "systems",  # the curve system contract G(z) = 0, branch and fold systems, Newton
    "detection",  # test functions and locating their zeros inside a step
    "results",  # Branch, SpecialPoint, dense output
    "stepping",  # the tracer: start, step, confirmation, work budget, state
    "loci",  # fold curves, loci of located points, chains of points
    "diagram",  # whole diagrams: recursive branch switching, each branch once, deflation
)


def _package_dirs() -> dict[str, Path]:
    mapping = PYPROJECT["tool"]["setuptools"]["package-dir"]
    return {name: ROOT / folder for name, folder in mapping.items()}


def _imports(name: str, path: Path) -> set[str]:
    """The modules ``name`` imports (at import time or inside functions), absolute."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    package = name if path.stem == "__init__" else name.rpartition(".")[0]
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[: len(base) - node.level + 1]
                module = ".".join(base + ([node.module] if node.module else []))
            else:
                module = node.module or ""
            found.add(module)
            found.update(f"{module}.{alias.name}" for alias in node.names)
    return found


def _layer(module: str) -> str | None:
    for package in sorted(ALLOWED, key=len, reverse=True):
        if module == package or module.startswith(package + "."):
            return package
    return None


def test_one_import_name():
    """The distribution installs exactly one top-level package, ``cusp``, and the command."""
    setuptools_cfg = PYPROJECT["tool"]["setuptools"]
    assert all(p == "cusp" or p.startswith("cusp.") for p in setuptools_cfg["packages"])
    assert set(setuptools_cfg["packages"]) == set(setuptools_cfg["package-dir"])
    assert PYPROJECT["project"]["scripts"] == {"cusp": "cusp.app.cli:main"}
    # every package folder is listed (a forgotten folder would not be installed)
    for folder in _package_dirs().values():
        assert (folder / "__init__.py").is_file(), folder


def test_build_holds_only_cusp(tmp_path, package_modules):
    """What setuptools builds from the project's own files: only ``cusp/`` (the wheel adds its
    dist-info; ``pip install --target`` adds the ``bin/cusp`` command)."""
    pytest.importorskip("setuptools")
    code = (
        "import sys, setuptools; "
        f"sys.argv = ['setup.py', '-q', 'build_py', '--build-lib', {str(tmp_path)!r}]; "
        "setuptools.setup()"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120
    )
    assert done.returncode == 0, done.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cusp"]
    built = {p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*.py")}
    expected = {
        (f"{name.replace('.', '/')}/__init__.py" if path.stem == "__init__" else None)
        or f"{name.rpartition('.')[0].replace('.', '/')}/{path.name}"
        for name, path in package_modules.items()
    }
    assert built == expected
    assert (tmp_path / "cusp" / "scenes" / "fig6.toml").is_file()


def test_layers_import_only_downwards(package_modules):
    bad = []
    for name, path in package_modules.items():
        own = _layer(name)
        for target in _imports(name, path):
            if not (target == "cusp" or target.startswith("cusp.")):
                continue
            layer = _layer(target)
            if layer not in (own, None) and layer not in ALLOWED[own]:
                bad.append(f"{name} imports {target}")
    assert not bad, bad


def test_no_import_cycle(package_modules):
    modules = package_modules
    graph = defaultdict(set)
    for name, path in modules.items():
        for target in _imports(name, path):
            while target and target not in modules:  # `from pkg import module` or a name
                target = target.rpartition(".")[0]
            if target and target != name:
                graph[name].add(target)
    # a package importing its own modules is not a cycle (Python resolves it); a module
    # importing its package's ``__init__`` for a name defined in a sibling would be, so edges
    # into a package ``__init__`` count too
    cycles = []
    state: dict[str, int] = {}

    def visit(node, stack):
        state[node] = 1
        stack.append(node)
        for nxt in sorted(graph[node]):
            if nxt.startswith(node + "."):  # a package's own submodules
                continue
            if state.get(nxt) == 1 and not node.startswith(nxt + "."):
                cycles.append(stack[stack.index(nxt) :] + [nxt])
            elif nxt not in state:
                visit(nxt, stack)
        stack.pop()
        state[node] = 2

    for node in sorted(modules):
        if node not in state:
            visit(node, [])
    assert not cycles, cycles


def _engine_rank(module: str) -> int | None:
    """The rank of an engine module in :data:`ENGINE_ORDER` (0: a root module of the engine;
    ``len(ENGINE_ORDER) + 1``: the package itself, which re-exports everything); None
    outside the engine."""
    if module == ENGINE:
        return len(ENGINE_ORDER) + 1
    if not module.startswith(ENGINE + "."):
        return None
    part = module[len(ENGINE) + 1 :].split(".")[0]
    return ENGINE_ORDER.index(part) + 1 if part in ENGINE_ORDER else 0


def test_engine_packages_import_only_lower_ones(package_modules):
    """Each concept package of the engine imports only from packages below it in
    :data:`ENGINE_ORDER` (and from the engine's root modules), at import time, inside
    functions or for type checking alike; every engine module lies in one of them."""
    modules = package_modules
    bad = []
    for name, path in modules.items():
        own = _engine_rank(name)
        if own is None or name == ENGINE:
            continue
        part = name[len(ENGINE) + 1 :].split(".")[0]
        assert part in ENGINE_ORDER or part.startswith("_"), f"{name} is in no concept package"
        for target in _imports(name, path):
            while target and target not in modules:
                target = target.rpartition(".")[0]
            rank = _engine_rank(target) if target else None
            if rank is None or target == name:
                continue
            same = target.split(".")[:3] == name.split(".")[:3]
            if not same and rank >= own and not (own == 0 and rank == 0):
                bad.append(f"{name} imports {target}")
    assert not bad, bad


def test_engine_packages_are_small_and_their_modules_private():
    """No engine folder holds more than 12 modules; implementation modules are private
    (``_name.py``): the public API is what ``cusp.continuation`` re-exports."""
    folders = [p for p in (ROOT / "continuation").iterdir() if (p / "__init__.py").is_file()]
    for folder in [ROOT / "continuation", *folders]:
        modules = [p for p in folder.glob("*.py") if p.name != "__init__.py"]
        assert len(modules) <= 12, (folder.name, len(modules))
        public = [p.name for p in modules if not p.name.startswith("_")]
        assert not public, (folder.name, public)


def test_first_party_imports_go_through_cusp(package_modules):
    """Tests, scripts and the package never import the repository folders by their bare
    names (they would shadow or duplicate the installed package); scripts never import
    tests."""
    bare = {"continuation", "models", "verification", "app", "scenes", "examples"}
    bad = []
    files = [*ROOT.joinpath("tests").rglob("*.py"), *ROOT.joinpath("scripts").glob("*.py")]
    files += list(package_modules.values())
    for path in files:
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            names = []
            if isinstance(node, ast.Import):
                names = [alias.name for alias in node.names]
            elif isinstance(node, ast.ImportFrom) and not node.level:
                names = [node.module or ""]
            for module in names:
                top = module.split(".")[0]
                if top in bare or (top == "tests" and path.parent.name == "scripts"):
                    bad.append(f"{path.relative_to(ROOT)}: import {module}")
    assert not bad, bad


def _import_names(tree: ast.AST) -> list[tuple[str, int]]:
    """(module, relative level) of every import statement in ``tree``."""
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out += [(alias.name, 0) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            out.append((node.module or "", node.level))
    return out


def _edits_the_import_path(tree: ast.AST) -> bool:
    """Whether ``tree`` touches ``sys.path`` or calls ``syspath_prepend``."""
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute):
            if node.attr == "syspath_prepend":
                return True
            if node.attr == "path" and isinstance(node.value, ast.Name) and node.value.id == "sys":
                return True
    return False


def test_scripts_and_tests_get_their_helpers_by_name_or_fixture():
    """What the scripts share is imported from ``cusp._scripts`` (scripts/_shared/), never a
    sibling by its bare name (which needs scripts/ on the import path); tests get their
    helpers from fixtures: only conftest.py files import ``tests.*`` or relatively; no
    script or test edits ``sys.path``."""
    scripts = ROOT / "scripts"
    siblings = {p.stem for p in scripts.glob("*.py")}
    bad = []
    for path in [*scripts.glob("*.py"), *scripts.joinpath("_shared").glob("*.py")]:
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for module, level in _import_names(tree):
            top = module.split(".")[0]
            if level or top in siblings or (top.startswith("_") and top != "__future__"):
                bad.append(f"{path.relative_to(ROOT)}: imports {'.' * level}{module}")
        if _edits_the_import_path(tree):
            bad.append(f"{path.relative_to(ROOT)}: edits the import path")
    for path in ROOT.joinpath("tests").rglob("*.py"):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        if path.name != "conftest.py":
            for module, level in _import_names(tree):
                if level or module.split(".")[0] == "tests":
                    bad.append(f"{path.relative_to(ROOT)}: imports {'.' * level}{module}")
        if _edits_the_import_path(tree):
            bad.append(f"{path.relative_to(ROOT)}: edits the import path")
    assert not bad, bad


def test_script_helpers_import_no_optional_dependency(package_modules):
    """Every module of ``cusp._scripts`` imports without contique, pacopy, mpmath or
    matplotlib: each is imported where it is used."""
    names = sorted(n for n in package_modules if n.split(".")[:2] == ["cusp", "_scripts"])
    assert len(names) >= 8, names  # the package and its seven modules
    code = (
        "import importlib, json, sys\n"
        f"for name in {names!r}:\n"
        "    importlib.import_module(name)\n"
        "print(json.dumps(sorted(sys.modules)))"
    )
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=ROOT
    )
    loaded = {m.split(".")[0] for m in json.loads(done.stdout)}
    assert not loaded & {"contique", "pacopy", "mpmath", "matplotlib"}


def _docstring(node):
    body = getattr(node, "body", None)
    if (
        body
        and isinstance(body[0], ast.Expr)
        and isinstance(body[0].value, ast.Constant)
        and isinstance(body[0].value.value, str)
    ):
        return body[0]
    return None


def _code_lines(text: str) -> int:
    """A module's lines less those of its docstrings (module, classes, functions): the
    numpydoc sections the public API carries (issue 32) document a module, they do not make
    it harder to follow, and the function limit has excluded them from the start."""
    tree = ast.parse(text)
    doc_lines = sum(
        d.end_lineno - d.lineno + 1
        for node in ast.walk(tree)
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef))
        and (d := _docstring(node)) is not None
    )
    return text.count("\n") - doc_lines


def _body_lines(node) -> int:
    n = node.end_lineno - node.lineno + 1
    body = node.body
    if (
        body
        and isinstance(body[0], ast.Expr)
        and isinstance(body[0].value, ast.Constant)
        and isinstance(body[0].value.value, str)
    ):
        n -= body[0].end_lineno - body[0].lineno + 1
    return n


def test_small_modules_and_functions(package_modules):
    """Modules of at most 600 lines, functions of at most 80 (60 in the engine), the
    docstring excluded, the signature included."""
    long_modules, long_functions = [], []
    for name, path in package_modules.items():
        text = path.read_text(encoding="utf-8")
        code = _code_lines(text)
        if code > MAX_MODULE_LINES:
            long_modules.append(f"{name}: {code} lines besides docstrings")
        limit = MAX_ENGINE_FUNCTION_LINES if _engine_rank(name) is not None else MAX_FUNCTION_LINES
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                n = _body_lines(node)
                if n > limit:
                    long_functions.append(f"{name}.{node.name}: {n} lines")
    assert not long_modules, long_modules
    assert not long_functions, long_functions


@pytest.mark.parametrize(
    ("package", "forbidden"),
    [
        ("cusp", ("cusp.continuation", "cusp.models", "numpy", "sympy", "matplotlib")),
        ("cusp.continuation", ("cusp.models", "cusp.app", "cusp.examples", "sympy", "matplotlib")),
        (
            "cusp.models",
            ("cusp.app", "cusp.verification", "sympy", "matplotlib", "scipy.integrate"),
        ),
    ],
)
def test_imports_are_light(package, forbidden):
    code = f"import sys, json, {package}; print(json.dumps(sorted(sys.modules)))"
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=ROOT
    )
    loaded = set(json.loads(done.stdout))
    assert not [m for m in forbidden if m in loaded]


def test_nothing_refers_to_files_a_user_does_not_have():
    """The physics and the test problems are the project's own pages (docs/physics.md,
    docs/test-problems.md); no file names a page outside the repository or a machine path."""
    forbidden = ("PHYSICS.md", "TEST-PROBLEMS.md", "../shared", "/work/", "/root/", "/home/")
    tracked = subprocess.run(
        ["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=False
    ).stdout.split()
    if not tracked:  # not a git checkout: every text file under the root
        tracked = [str(p.relative_to(ROOT)) for p in ROOT.rglob("*") if p.is_file()]
    suffixes = {".py", ".md", ".toml", ".txt", ".cfg", ".json", ".csv", ""}
    bad = []
    for name in tracked:
        path = ROOT / name
        if path.suffix not in suffixes or not path.is_file() or ".git" in path.parts:
            continue
        if path == Path(__file__).resolve():  # the list above
            continue
        text = path.read_text(encoding="utf-8", errors="replace")
        bad += [f"{name}: {word}" for word in forbidden if word in text]
    assert not bad, bad
