"""Branch points of sparse curves: the pitchforks of the trivial branch of the discretised
Chafee–Infante (Allen–Cahn) problem u'' + λ(u − u³) = 0, u(0) = u(1) = 0.

On u = 0 the Jacobian is D₂ + λI (D₂ the second-difference matrix of N interior nodes,
h = 1/(N + 1)), singular at λ_k = (4/h²)·sin²(kπh/2), k = 1..N, exactly: each is a simple
pitchfork. The steps on this straight branch grow to ds_max, and one step spans two or three
λ_k; the determinant of the branch-point test then shows only their net sign change (two
cancel, three show as one). The closed form is evaluated with mpmath.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
import scipy.sparse as sp

from cusp.continuation import Problem, trace

pytestmark = pytest.mark.slow


def pitchforks(n: int, top: float, stiffness: float = 1.0, coupling: float = 0.0) -> list:
    """λ_k below ``top`` (30 digits): for two species, one diffusing ``stiffness`` times
    faster and the two coupled by ``coupling``, the roots of the 2×2 determinant per mode,
    c + λ_k(1 + D)/2 ± √((λ_k(D − 1)/2)² + c²)."""
    mpmath.mp.dps = 30
    d, c = mpmath.mpf(stiffness), mpmath.mpf(coupling)
    out = []
    for k in range(1, n + 1):
        lk = 4 * (n + 1) ** 2 * mpmath.sin(k * mpmath.pi / (2 * (n + 1))) ** 2
        if stiffness == 1.0 and coupling == 0.0:
            roots = [lk]
        else:
            r = mpmath.sqrt((lk * (d - 1) / 2) ** 2 + c**2)
            roots = [c + lk * (1 + d) / 2 - r, c + lk * (1 + d) / 2 + r]
        out += [float(x) for x in roots if x < top]
    return sorted(out)


def laplacian(n: int) -> sp.csc_matrix:
    h2 = float(n + 1) ** 2
    off = np.full(n - 1, h2)
    return sp.diags([off, np.full(n, -2.0 * h2), off], [-1, 0, 1], format="csc")


def chafee_infante(n: int, jacobian: str) -> Problem:
    """The problem with ``jacobian`` "sparsity" (sparse finite differences), "analytic"
    (sparse) or "dense" (dense finite differences)."""
    lap = laplacian(n)

    def residual(u, p):
        return lap @ u + p["lam"] * (u - u**3)

    names = [f"u{i}" for i in range(n)]
    if jacobian == "analytic":
        return Problem(
            residual,
            names,
            {"lam": 0.0},
            jacobian=lambda u, p: (lap + sp.diags(p["lam"] * (1 - 3 * u**2))).tocsc(),
            param_jacobian=lambda u, p, name: u - u**3,
        )
    if jacobian == "sparsity":
        return Problem(residual, names, {"lam": 0.0}, sparsity=lap)
    return Problem(residual, names, {"lam": 0.0})


@pytest.mark.parametrize("jacobian", ["sparsity", "analytic"])
def test_short_steps_locate_sparse_branch_points_to_convergence(jacobian):
    """The reference: with steps too short to hold two pitchforks, the same points, each
    located by Newton on the (sparse) extended system, converged, also above 200 components
    (where the dense extended system is not built)."""
    n = 200
    branch = trace(
        chafee_infante(n, jacobian),
        np.zeros(n),
        free="lam",
        bounds={"lam": (-1, 100)},
        ds_max=0.02,
    )
    bps = sorted(branch.special("branch_point"), key=lambda p: p.values["lam"])
    expected = pitchforks(n, 100.0)
    assert [p.status for p in bps] == ["converged"] * len(expected)
    for p, want in zip(bps, expected):
        assert abs(p.values["lam"] / want - 1.0) <= 1e-10
        assert p.details["method"].startswith("Newton on the extended system")


def test_sparsity_matrix_is_not_overwritten():
    """The sparsity pattern may be the operator itself: its values are left alone (the
    column grouping used to set the data of a CSC pattern to 1 in place)."""
    lap = laplacian(5)
    before = lap.toarray()
    Problem(lambda u, p: lap @ u, [f"u{i}" for i in range(5)], {"a": 0.0}, sparsity=lap)
    assert np.array_equal(lap.toarray(), before)
