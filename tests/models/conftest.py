"""Fixtures of the model tests, from :mod:`tests.models._reference` (imported only here):
the mpmath reference table and the code that computed it.

* ``reference_table``: ``tests/models/reference/reference_values.json`` (floats as
  float.hex, each with its provenance in the file);
* ``rel_err``: |value − ref|/|ref| in mpmath;
* ``integrated_rows``: :func:`tests.models._loci_rows.integrated_rows`, the rows of a
  locus table whose energies were integrated (the others left empty by the work limit);
* ``mp_reference``: ``tests/models/reference/mp_reference.py``, the mpmath code of the
  table, loaded from its file (a script's sibling, not a package's module: the import path
  is left as it is).

The toy body (``toy_body``) is a fixture of tests/conftest.py (the application tests use
it too); the closed forms and mpmath paths of the contact-loss path are
:mod:`cusp.verification.oracles`, imported by the tests themselves.
"""

from __future__ import annotations

import importlib.util
from types import ModuleType

import pytest

from tests.models import _loci_rows, _reference


@pytest.fixture(scope="session")
def reference_table() -> dict:
    """The mpmath reference table (loaded once)."""
    return _reference.table()


@pytest.fixture(scope="session")
def rel_err():
    """``rel_err(value, ref)``: |value − ref|/|ref| in mpmath (absolute when ref = 0)."""
    return _reference.rel_err


@pytest.fixture(scope="session")
def mp_reference() -> ModuleType:
    """The mpmath code of the reference table (``BODIES``, ``gaussian``, ...)."""
    path = _reference.HERE / "mp_reference.py"
    spec = importlib.util.spec_from_file_location("mp_reference", path)
    assert spec is not None and spec.loader is not None, path
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="session")
def integrated_rows():
    """``integrated_rows(loci, kept)``: the rows of a locus table whose energies were
    integrated (:func:`tests.models._loci_rows.integrated_rows`)."""
    return _loci_rows.integrated_rows
