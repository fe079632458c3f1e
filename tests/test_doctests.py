"""The examples in the package's docstrings run and print what they say."""

from __future__ import annotations

import doctest
import importlib


def test_docstring_examples(package_module):
    """``package_module``: each module of the package (tests/conftest.py)."""
    module = importlib.import_module(package_module)
    flags = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE
    result = doctest.testmod(module, optionflags=flags, report=True, verbose=False)
    assert result.failed == 0, f"{result.failed} of {result.attempted} examples failed"


def test_the_examples_are_counted():
    """The package does have examples (a collection error would otherwise pass silently)."""
    finder = doctest.DocTestFinder()
    total = 0
    for name in ("cusp.continuation", "cusp.continuation.stepping._tracer"):
        total += sum(len(t.examples) for t in finder.find(importlib.import_module(name)))
    assert total >= 8
