"""Which rows of a locus table carry their released energies (cusp.models.manifold)."""

from __future__ import annotations

import numpy as np

from cusp.models import manifold


def integrated_rows(loci, kept) -> np.ndarray:
    """The rows of a locus table whose released energies are integrated: one in k beyond
    manifold.ENERGY_ROWS rows (the work limit, which a message states), and the rows at
    requested values (``kept``)."""
    n = loci.columns["mu"].size
    stride = -(-n // manifold.ENERGY_ROWS)
    if stride > 1:
        assert any("the work limit being" in m for m in loci.messages)
    return (np.arange(n) % stride == 0) | kept
