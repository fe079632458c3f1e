from __future__ import annotations

import pytest


@pytest.fixture(scope="session")
def derivations():
    """Every derivation record by equation id (derived once per process)."""
    from cusp.verification import derive_all

    return {rec.equation: rec for rec in derive_all()}
