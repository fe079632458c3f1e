"""Type-check the engine, the physics and the scripts' shared helpers with mypy, as installed.

Usage (from the repository root, with the test extra installed):

    python scripts/typecheck.py [PACKAGE ...]

checks the named packages, by default ``cusp.continuation``, ``cusp.models`` and
``cusp._scripts`` (and what they import).

The repository keeps each layer in its own top-level folder, mapped into the one package
``cusp`` at install time, which mypy cannot follow from the source tree (nor through an
editable install's import hook). This script builds the package as it would be installed
(setuptools ``build_py`` into a temporary folder: the wheel's contents) and runs mypy on it
with the settings of ``[tool.mypy]`` in ``pyproject.toml``; paths in mypy's report are given
back as repository paths. Exit status: mypy's.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

try:
    import tomllib
except ModuleNotFoundError:  # Python 3.10
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]
DEFAULT = ("cusp.continuation", "cusp.models", "cusp._scripts")


def build(into: Path) -> None:
    code = (
        "import sys, setuptools; "
        f"sys.argv = ['setup.py', '-q', 'build_py', '--build-lib', {str(into)!r}]; "
        "setuptools.setup()"
    )
    done = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)
    if done.returncode:
        raise SystemExit(f"building the package failed:\n{done.stdout}{done.stderr}")


def source_paths() -> dict[str, str]:
    """Built path prefix (``cusp/continuation/``) -> repository folder (``continuation/``)."""
    config = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    mapping = config["tool"]["setuptools"]["package-dir"]
    return {name.replace(".", "/") + "/": folder + "/" for name, folder in mapping.items()}


def main(argv: list[str] | None = None) -> int:
    packages = list(argv if argv is not None else sys.argv[1:]) or list(DEFAULT)
    with tempfile.TemporaryDirectory(prefix="cusp-typecheck-") as tmp:
        build(Path(tmp))
        args = [sys.executable, "-m", "mypy", "--config-file", str(ROOT / "pyproject.toml")]
        for package in packages:
            args += ["-p", package]
        env = {**os.environ, "MYPYPATH": tmp}
        done = subprocess.run(args, cwd=tmp, env=env, capture_output=True, text=True)
    prefixes = sorted(source_paths().items(), key=lambda item: -len(item[0]))
    for line in (done.stdout + done.stderr).splitlines():
        for built, folder in prefixes:
            if line.startswith(built):
                line = folder + line[len(built) :]
                break
        print(re.sub(re.escape(tmp) + r"/?", "", line))
    return done.returncode


if __name__ == "__main__":
    raise SystemExit(main())
