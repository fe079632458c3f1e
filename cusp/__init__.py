"""cusp: numerical continuation and bifurcation analysis, with the contact mechanics of the
stick-slip cusp catastrophe (Carpinteri, Paggi & Zavarise).

One installed namespace in layers; each imports only the layers below it:

- :mod:`cusp.continuation`: the generic engine (numpy and scipy only): problems, tracing
  branches, special points, fold curves, results;
- :mod:`cusp.examples`: example problems written once (cusp normal form, trusses, Bratu, ...)
  on top of the engine;
- :mod:`cusp.models`: the physics: rough surfaces and smooth bodies, the body protocol and
  registry, the contact-loss path;
- :mod:`cusp.verification`: the paper's closed forms derived with sympy and compared with
  the physics;
- :mod:`cusp.app`: the application: scene files, the runner, figures and the ``cusp``
  command.

Importing :mod:`cusp` itself loads nothing else.
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("cusp")
except PackageNotFoundError:  # pragma: no cover - a source tree that was never installed
    __version__ = "unknown"

__all__ = ["__version__"]
