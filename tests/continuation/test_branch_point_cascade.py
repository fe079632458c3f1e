"""Several branch points inside one step on curves of more than 50 components, dense or
sparse: the pitchforks of the trivial branch of the discretised Chafee–Infante (Allen–Cahn)
problem u'' + λ(u − u³) = 0, u(0) = u(1) = 0, traced with the default options.

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
from cusp.continuation.detection import _spectrum as spectrum

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


def two_species(n: int, stiffness: float, coupling: float) -> Problem:
    """u'' + λ(u − u³) + c(v − u) = 0 and D v'' + λ(v − v³) + c(u − v) = 0: near-double
    pitchforks (analytic sparse Jacobian)."""
    lap = laplacian(n)
    lap2 = sp.block_diag([lap, stiffness * lap], format="csc")
    swap = sp.bmat([[None, sp.identity(n)], [sp.identity(n), None]], format="csc")
    mix = coupling * (swap - sp.identity(2 * n))

    def residual(w, p):
        return lap2 @ w + p["lam"] * (w - w**3) + mix @ w

    def jacobian(w, p):
        return (lap2 + mix + sp.diags(p["lam"] * (1 - 3 * w**2))).tocsc()

    names = [f"u{i}" for i in range(n)] + [f"v{i}" for i in range(n)]
    return Problem(
        residual, names, {"lam": 0.0}, jacobian=jacobian, param_jacobian=lambda w, p, k: w - w**3
    )


def check_pitchforks(branch, expected: list[float]) -> None:
    """Each expected λ found once, converged, to 1e-10 relative; and at least one step of the
    trace spanned two or more of them (so that the test exercises what it is about)."""
    bps = sorted(branch.special("branch_point"), key=lambda p: p.values["lam"])
    found = [p.values["lam"] for p in bps]
    assert len(found) == len(expected), (found, expected)
    assert all(p.status == "converged" for p in bps), [p.status for p in bps]
    for lam, want in zip(found, expected):
        assert abs(lam / want - 1.0) <= 1e-10, (lam, want)
    inserted = {p.index for p in branch.special_points}
    ends = [lam for i, lam in enumerate(branch["lam"]) if i not in inserted]
    spanned = [sum(a < x < b for x in expected) for a, b in zip(ends[:-1], ends[1:])]
    assert max(spanned) >= 2, spanned


@pytest.mark.parametrize("n", [60, 100, 200])
@pytest.mark.parametrize("jacobian", ["sparsity", "analytic"])
def test_every_pitchfork_of_a_long_straight_branch(n, jacobian):
    """Six pitchforks below λ = 400, two or three of them inside one step."""
    branch = trace(chafee_infante(n, jacobian), np.zeros(n), free="lam", bounds={"lam": (-1, 400)})
    assert branch.status == "bound"
    check_pitchforks(branch, pitchforks(n, 400.0))


def test_every_pitchfork_dense_above_the_full_spectrum():
    """A dense Jacobian of 60 unknowns (more than SPECTRUM_MAX_DIM = 50 components)."""
    n = 60
    branch = trace(chafee_infante(n, "dense"), np.zeros(n), free="lam", bounds={"lam": (-1, 400)})
    check_pitchforks(branch, pitchforks(n, 400.0))


def test_near_double_pitchforks_of_two_species():
    """Two species diffusing 2e-4 apart, coupled by 1e-3: each mode's pitchforks lie
    3e-4 apart (relative) and always inside one step, with mixed eigenvectors."""
    n, stiffness, coupling = 60, 1.0 + 2e-4, 1e-3
    expected = pitchforks(n, 100.0, stiffness, coupling)
    assert len(expected) == 6
    assert min(b / a - 1.0 for a, b in zip(expected[::2], expected[1::2])) < 1e-3
    branch = trace(
        two_species(n, stiffness, coupling),
        np.zeros(2 * n),
        free="lam",
        bounds={"lam": (-1, 100)},
    )
    check_pitchforks(branch, expected)


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


# --- the partial spectrum and the rule that accounts for a step (detection/_spectrum.py)


def test_arnoldi_finds_the_eigenvalues_nearest_zero():
    """Shift-invert Arnoldi on a non-normal matrix with a complex pair near zero: the
    eigenvalues nearest zero, in order, with eigenvectors, inside the radius."""
    rng = np.random.default_rng(3)
    n = 200
    reals = np.arange(3.0, n + 1.0) * (-1.0) ** np.arange(n - 2)  # 3, -4, 5, ...
    d = np.diag(np.concatenate([[0.0, 0.0], reals]))
    d[0, 0], d[0, 1], d[1, 0], d[1, 1] = 0.5, 1.0, -1.0, 0.5  # 0.5 ± i
    s = np.eye(n) + np.triu(rng.standard_normal((n, n)), 1) / n
    a = s @ d @ np.linalg.inv(s)
    lu = np.linalg.inv(a)
    found = spectrum.arnoldi_spectrum(lambda x: lu @ x, rng.random(n), 24)
    mu = found.wr + 1j * found.wi
    assert np.allclose(mu[:2], [0.5 + 1j, 0.5 - 1j], rtol=1e-8)
    assert np.allclose(found.wr[2:5], [3.0, -4.0, 5.0], rtol=1e-8)
    assert abs(mu[-1]) == pytest.approx(found.radius)
    for j in range(2, found.wr.size):  # real eigenvectors
        x = found.vectors[:, j]
        assert np.linalg.norm(a @ x - found.wr[j] * x) <= 1e-6 * abs(found.wr[j])


def _spectrum(values, vectors, radius):
    values = np.asarray(values, dtype=complex)
    return spectrum.Spectrum(values.real, values.imag, np.asarray(vectors, float), radius, 8)


def test_follow_accounts_for_two_opposite_crossings():
    """Two modes crossing zero in opposite directions inside one step: the determinant
    keeps its sign, the followed eigenvalues show both crossings where their linear
    interpolants vanish."""
    e = np.eye(4)
    sa = _spectrum([-1.0, 3.0, 10.0], e[:, :3], 10.0)
    sb = _spectrum([1.0, -1.0, 11.0], e[:, [0, 1, 2]], 11.0)
    thetas, problem = spectrum.follow(sa, sb, changed=False)
    assert problem == ""
    assert thetas == pytest.approx([0.5, 0.75])
    assert spectrum.follow(sa, sb, changed=True).problem == "parity"


def test_follow_does_not_account_for_what_it_cannot_see():
    """An eigenvalue near zero at one end only, or spectra too narrow for the step's
    displacements: not accounted for (the step is then split)."""
    e = np.eye(4)
    sa = _spectrum([-1.0, 8.0], e[:, :2], 8.0)
    lone = _spectrum([1.0, 0.5, 8.0], e[:, [0, 3, 1]], 8.0)  # 0.5: a mode unseen at a
    assert spectrum.follow(sa, lone, changed=True).problem == "unmatched"
    narrow = _spectrum([-1.0, 2.0], e[:, :2], 2.0)
    moved = _spectrum([3.0, 0.5], e[:, :2], 3.0)  # displacements up to 4: reach 8 > 2 + 3
    assert spectrum.follow(narrow, moved, changed=True).problem == "window"


def test_steps_the_spectra_do_not_account_for_are_split(monkeypatch, caplog):
    """With spectra of two Arnoldi vectors (nothing converges) every step is split at its
    midpoint, three levels deep: the six pitchforks are still found."""
    monkeypatch.setattr(spectrum, "KRYLOV", 2)
    monkeypatch.setattr(spectrum, "MAX_KRYLOV", 2)
    n = 60
    with caplog.at_level("INFO", logger="cusp.continuation.detection._spectrum"):
        branch = trace(
            chafee_infante(n, "analytic"), np.zeros(n), free="lam", bounds={"lam": (-1, 400)}
        )
    assert any("do not account" in r.getMessage() for r in caplog.records)
    found = sorted(p.values["lam"] for p in branch.special("branch_point"))
    assert np.allclose(found, pitchforks(n, 400.0), rtol=1e-10, atol=0.0)
