"""Whole bifurcation diagrams (:func:`cusp.continuation.diagram`): recursive branch switching,
each branch once, closed branches, deflation for disconnected branches.

Oracles: closed forms (derived in each test's docstring; the FD Laplacian's eigenvalues in
mpmath at 40 digits through :func:`cusp.examples.symmetric.chafee_infante_eigenvalue`).
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest

from cusp.continuation import DeflationStarts, Problem, deflate, diagram, trace
from cusp.continuation.diagram import _diagram as diag
from cusp.examples.diagrams import isola, painleve, two_modes
from cusp.examples.symmetric import chafee_infante, chafee_infante_eigenvalue
from cusp.examples.symmetric_cells import cstr_pair, cstr_pair_references


def _sign_changes(u: np.ndarray) -> int:
    s = np.sign(u[np.abs(u) > 1e-8 * np.max(np.abs(u))])
    return int(np.count_nonzero(s[1:] != s[:-1]))


# --- a cascade of pitchforks: Chafee–Infante by finite differences --------------------------


def test_chafee_infante_every_mode_once():
    """u'' + λ(u − u³) = 0 on (0, π), u(0) = u(π) = 0, n = 20 interior nodes, h = π/21
    (:func:`cusp.examples.symmetric.chafee_infante`): on u = 0 the Jacobian Δ_h + λI is
    singular at λ_k = (4/h²) sin²(kh/2) (the FD Laplacian's eigenvalues, exact; mpmath):
    λ_1 = 0.99814, λ_2 = 3.97025, λ_3 = 8.84995 below 10, λ_4 = 15.56 above. Each is a
    pitchfork whose branch leaves along sin(k x_i) and, by Chafee & Infante (1974), carries
    no further branch point (its Morse index k − 1 is constant along it). So: 4 branches, 3
    points, each mode's branch once (both signs ±u on one branch), k − 1 sign changes."""
    n = 20
    ex = chafee_infante(n, lam_max=10.0)
    d = diagram(ex.problem, ex.u0, free="lam", bounds={"lam": (0.0, 10.0)}, max_depth=3)
    expected = [chafee_infante_eigenvalue(n, k) for k in (1, 2, 3)]
    assert chafee_infante_eigenvalue(n, 4) > 10.0
    assert len(d.branches) == 4 and len(d.points) == 3, d
    assert d.recognised == ()
    found = sorted(p.point.values["lam"] for p in d.points)
    for lam, want in zip(found, expected):
        assert abs(lam / want - 1.0) <= 1e-10, (lam, want)
    h = math.pi / (n + 1)
    x = h * np.arange(1, n + 1)
    names = [f"u{i + 1}" for i in range(n)]
    for k, point in enumerate(sorted(d.points, key=lambda p: p.point.values["lam"]), start=1):
        assert point.on[0] == 0 and len(point.leaving) == 1
        item = d.branches[point.leaving[0]]
        assert item.depth == 1 and item.source == d.points.index(point)
        assert item.ends == ("bound", "bound") and not item.closed
        U = np.column_stack([item.branch[v] for v in names])
        far = np.argmax(np.abs(U).max(axis=1))
        u = U[far]
        assert _sign_changes(u) == k - 1
        modes = np.array([np.sin(j * x) for j in range(1, n + 1)])
        proj = np.abs(modes @ u)
        assert int(np.argmax(proj)) == k - 1  # the sine projection peaks at mode k
        # both halves: +u and −u (the pitchfork's symmetry u → −u)
        amp = U @ np.sin(k * x)
        assert amp.max() > 0.1 and amp.min() < -0.1


def test_depth_limit_and_max_branches():
    """max_depth = 0 keeps the start's branch only; max_branches caps the count; the points
    say why they were not switched."""
    ex = chafee_infante(10, lam_max=10.0)
    d0 = diagram(ex.problem, ex.u0, free="lam", bounds={"lam": (0.0, 10.0)}, max_depth=0)
    assert len(d0.branches) == 1 and len(d0.points) == 3
    assert all("max_depth" in p.notes[0] for p in d0.points)
    d2 = diagram(ex.problem, ex.u0, free="lam", bounds={"lam": (0.0, 10.0)}, max_branches=2)
    assert len(d2.branches) == 2
    assert sum("max_branches" in p.notes[0] for p in d2.points) == 2


# --- secondary bifurcations: two interacting modes ------------------------------------------


def test_secondary_bifurcations():
    """Five branches (trivial, x, y, mixed x > 0, mixed x < 0) and four branch points
    (λ = 1, 2 and λ = 3 at x = ±√2), the mixed branches at depth 2; every row on its closed
    form to Newton's tolerance."""
    d = diagram(two_modes(), [0.0, 0.0], free="lam",
                bounds={"lam": (0.0, 6.0)})  # fmt: skip
    assert len(d.branches) == 5 and len(d.points) == 4, d
    pts = sorted((round(p.point.values["lam"], 9), round(p.point.values["x"], 9)) for p in d.points)
    r2 = round(math.sqrt(2.0), 9)
    assert pts == [(1.0, 0.0), (2.0, 0.0), (3.0, -r2), (3.0, r2)]
    kinds = []
    for item in d.branches:
        x, y, lam = item.branch["x"], item.branch["y"], item.branch["lam"]
        if np.all(x == 0) and np.all(y == 0):
            kinds.append(("trivial", item.depth))
        elif np.all(np.abs(y) <= 1e-12):
            assert np.max(np.abs(x * x - (lam - 1))) <= 1e-9
            kinds.append(("x", item.depth))
        elif np.all(np.abs(x) <= 1e-12):
            assert np.max(np.abs(y * y - (lam - 2))) <= 1e-9
            kinds.append(("y", item.depth))
        else:
            assert np.max(np.abs(x * x - 2 * lam / 3)) <= 1e-9
            assert np.max(np.abs(y * y - (2 * lam - 6) / 3)) <= 1e-9
            assert np.all(x > 0) or np.all(x < 0)
            assert y.max() > 0.5 and y.min() < -0.5  # both halves of the pitchfork
            kinds.append(("mixed", item.depth))
    assert sorted(kinds) == [("mixed", 2), ("mixed", 2), ("trivial", 0), ("x", 1), ("y", 1)]
    shallow = diagram(two_modes(), [0.0, 0.0], free="lam", bounds={"lam": (0.0, 6.0)},
                      max_depth=1)  # fmt: skip
    assert len(shallow.branches) == 3


# --- each branch once: found again from its other end ---------------------------------------


def test_loop_between_two_pitchforks_is_traced_once():
    """Two stirred tanks (:func:`cusp.examples.symmetric_cells.cstr_pair`): the symmetric
    S-curve has two symmetry-breaking pitchforks (closed form, mpmath,
    :func:`cstr_pair_references`); the asymmetric branch from the first runs through the
    second and, past it, through the mirror image θ1 ↔ θ2 back to the first: a loop. It is
    traced once (closed), the second pitchfork's other branch is recognised as it, and the
    pitchforks it locates lead back to the symmetric branch (recognised too)."""
    ex = cstr_pair()
    d = diagram(ex.problem, ex.u0, free="Da", bounds=ex.bounds)
    assert len(d.branches) == 2 and len(d.points) == 2, d
    loop = d.branches[1]
    assert loop.closed and loop.ends == ("closed",) and loop.branch.success
    t1, t2 = loop.branch["theta1"], loop.branch["theta2"]
    assert (t1 - t2).max() > 0.1 and (t1 - t2).min() < -0.1  # both mirror halves
    _, forks = cstr_pair_references()
    found = sorted(p.point.values["Da"] for p in d.points)
    for got, want in zip(found, sorted(f.values["Da"] for f in forks)):
        assert abs(got / want - 1.0) <= 1e-10, (got, want)
    assert all(p.on == (0, 1) and p.leaving == (1,) for p in d.points)
    assert len(d.recognised) == 3
    assert d.traces == 2  # nothing traced twice


def test_crossing_branches_with_nearly_equal_slopes_are_both_kept():
    """(x − p)(x − 1.3 p) = 0 with unit typical sizes: the branches x = p and x = 1.3 p cross
    at the origin atan(1.3) − 45° = 7.43° apart, closer than MAX_ANGLE (computed below). The branch
    point's other branch is traced, not taken for the branch it was located on: a known
    branch's tangent must lie within a quarter of the two tangents' angle of the other one's
    too."""
    from cusp.continuation.diagram._geometry import cosine, pair_weights

    prob = Problem(lambda u, p: [(u[0] - p["p"]) * (u[0] - 1.3 * p["p"])], ["x"], {"p": -1.0})
    d = diagram(prob, [-1.0], free="p", bounds={"p": (-1.0, 1.0)}, scales={"x": 1.0, "p": 1.0})
    sp = d.points[0].point
    w = pair_weights(d.branches[0].branch, d.branches[0].branch)
    angle = math.degrees(math.acos(cosine(sp.tangent, sp.details["other_tangent"], w)))
    assert angle < diag.MAX_ANGLE  # the MAX_ANGLE rule alone would merge them
    assert len(d.branches) == 2, d
    other = d.branches[1].branch
    assert abs(angle - (math.degrees(math.atan(1.3)) - 45.0)) < 1e-6
    assert np.max(np.abs(other["x"] - 1.3 * other["p"])) <= 1e-9
    assert d.recognised == ()


def test_a_failed_switch_is_reported_not_taken_for_a_duplicate():
    """(x − p)(x − 1.1 p) = 0: the trace from the branch point fails next to it (the
    tracer's own limit, 2.7° apart); what it traced lies on the start's branch, but that
    branch does not leave along the other direction: the point's note says the switch
    failed, nothing is counted as recognised."""
    prob = Problem(lambda u, p: [(u[0] - p["p"]) * (u[0] - 1.1 * p["p"])], ["x"], {"p": -1.0})
    d = diagram(prob, [-1.0], free="p", bounds={"p": (-1.0, 1.0)})
    assert len(d.branches) == 1 and d.recognised == ()
    assert "switching failed" in d.points[0].notes[0]


def test_a_half_that_jumps_back_is_dropped():
    """(x − p)(x − 1.2 p) = 0 with the default typical sizes: one half of the switch jumps
    back onto x = p next to the branch point (the tracer's limit at 4° apart); that half lies
    on the start's branch, which does not leave along the other direction, so it is dropped
    and the other half, on x = 1.2 p, is kept alone: no branch mixes the two lines."""
    prob = Problem(lambda u, p: [(u[0] - p["p"]) * (u[0] - 1.2 * p["p"])], ["x"], {"p": -1.0})
    d = diagram(prob, [-1.0], free="p", bounds={"p": (-1.0, 1.0)})
    assert len(d.branches) == 2, d
    other = d.branches[1]
    assert other.ends[0] == "jumped onto branch 0" and other.ends[1] == "bound"
    assert np.max(np.abs(other.branch["x"] - 1.2 * other.branch["p"])) <= 1e-12
    assert "jumped onto branch 0" in d.points[0].notes[0]


def test_nearby_parallel_branches_are_not_merged():
    """x = p and x = p + c: a branch lies on another only if all its checked points are
    within tol = 4·rtol (weighted, relative to the typical sizes); at c = 10·tol they are
    kept apart, at c = tol/10 (the same curve at this accuracy) merged."""
    rtol = 1e-3
    tol = diag.DUPLICATE_FACTOR * rtol

    def line(c):
        prob = Problem(lambda u, p: [u[0] - p["p"] - c], ["x"], {"p": -1.0})
        return trace(prob, [-1.0 + c], free="p", bounds={"p": (-1.0, 1.0)}, rtol=rtol)

    base = line(0.0)
    for c, same in ((10 * tol, False), (tol / 10, True)):
        book = diag._Book(None, "p", tol, 1, 10)
        book.branches.append(diag.DiagramBranch(branch=base, depth=0, origin="start",
                                                source=None, closed=False, ends=()))  # fmt: skip
        assert (diag._duplicate_of(book, line(c)) == 0) is same, c


# --- closed branches and deflation ----------------------------------------------------------


def test_isola_only_by_deflation():
    """Without deflation one branch (x = 0); with deflation at λ = 2 from x = 1 the isola:
    deflation finds x = 2 and 4 (0 is on the known branch and deflated first), the branch
    from x = 2 closes on itself (the whole circle), and x = 4 is recognised on it."""
    bounds = {"lam": (0.0, 5.0), "x": (-1.0, 6.0)}
    alone = diagram(isola(), [0.0], free="lam", bounds=bounds)
    assert len(alone.branches) == 1 and alone.points == ()
    d = diagram(isola(), [0.0], free="lam", bounds=bounds,
                deflation={"at": [2.0], "guesses": [[1.0]]})  # fmt: skip
    assert len(d.branches) == 2, d
    assert sorted(float(u[0]) for u in d.deflation[0].solutions) == [2.0, 4.0]
    ring = d.branches[1]
    assert ring.origin == "deflation" and ring.closed and ring.depth == 0
    x, lam = ring.branch["x"], ring.branch["lam"]
    assert np.max(np.abs((x - 3) ** 2 + (lam - 2) ** 2 - 1)) <= 1e-10
    angles = np.sort(np.mod(np.arctan2(lam - 2, x - 3), 2 * np.pi))
    gaps = np.diff(np.concatenate([angles, [angles[0] + 2 * np.pi]]))
    assert gaps.max() < 0.5  # the whole circle, no arc missing
    assert len(ring.branch) < 60  # and once round: stopped on its return
    assert any("on branch 1" in r for r in d.recognised)
    same = diagram(isola(), [0.0], free="lam", bounds=bounds,
                   deflation=DeflationStarts(at=(2.0,), guesses=((1.0,),)))  # fmt: skip
    assert len(same.branches) == 2


def test_deflation_arguments_are_checked():
    prob = isola()
    with pytest.raises(Exception, match="shift must be > 0"):
        deflate(prob, [[1.0]], params={"lam": 2.0}, shift=0.0)
    with pytest.raises(Exception, match="not a parameter"):
        deflate(prob, [[1.0]], params={"mu": 2.0})
    with pytest.raises(Exception, match="must map 'at' and 'guesses'"):
        diagram(prob, [0.0], free="lam", bounds={"lam": (0, 5)}, deflation={"at": [2.0]})
    with pytest.raises(Exception, match="bounds must bound the free parameter"):
        diagram(prob, [0.0], free="lam", bounds={"x": (0, 5)})


def test_deflation_roots_of_a_polynomial():
    """(x − 1)(x − 2)(x − 3)(x² + 1): three real roots, all found from x = 0 and no more
    (x² + 1 has none); each verified by the residual."""
    prob = Problem(lambda u, p: [(u[0] - 1) * (u[0] - 2) * (u[0] - 3) * (u[0] ** 2 + 1)],
                   ["x"], {})  # fmt: skip
    found = deflate(prob, [[0.0]], max_solutions=10)
    assert sorted(float(u[0]) for u in found.solutions) == pytest.approx([1, 2, 3], abs=1e-14)
    assert all(r <= 1e-10 for r in found.residual_norms)
    assert found.runs == 4  # three found, the fourth run fails: no root left


def test_deflation_beside_a_singular_jacobian_finds_the_roots_quietly():
    """two_modes at λ = 2: the trivial root (0, 0) is a branch point (J = diag(1, 0)); Newton
    steps beside it meet an ill-conditioned J (scipy's solve warned, a LinAlgWarning that the
    suite's filterwarnings turns into an error). The roots from the closed forms: x² = λ − 1
    = 1 with y = 0, and the trivial one (reached linearly: the root is singular)."""
    out = deflate(two_modes(), [[1.0, 0.0], [0.0, 1.0]], params={"lam": 2.0})
    sols = sorted(out.solutions, key=lambda u: -u[0])
    assert len(sols) == 2
    assert np.allclose(sols[0], [1.0, 0.0], atol=1e-12)
    assert np.allclose(sols[1], [0.0, 0.0], atol=1e-10)


def test_deflation_jacobian_is_sherman_morrison():
    """The deflated update δ/(1 − g·δ) equals the Newton update of M·R with the Jacobian
    M J + R ∇Mᵀ formed explicitly (mpmath at 40 digits, M differentiated symbolically by
    hand: ∇m = −p‖d‖^{−p−2} W d)."""
    from cusp.continuation.diagram import _deflation as dfl

    mpmath.mp.dps = 40
    roots = [np.array([0.3, -0.2]), np.array([1.0, 1.5])]
    u = np.array([0.7, 0.4])
    w = np.array([0.5, 0.5])
    s = dfl._Settings(2.0, 1.0, w, 1e-10, 1e-12, 10, 1e-6)
    J = np.array([[2.0, 0.3], [-0.4, 1.5]])
    R = np.array([0.2, -0.1])
    delta = -np.linalg.solve(J, R)
    ours = delta / (1.0 - dfl._log_gradient(u, roots, s).dot(delta))
    U, Jm, Rm = mpmath.matrix(u.tolist()), mpmath.matrix(J.tolist()), mpmath.matrix(R.tolist())
    M, grad = mpmath.mpf(1), mpmath.matrix([0, 0])
    ms, gs = [], []
    for r in roots:
        dv = U - mpmath.matrix(r.tolist())
        n2 = sum(w[i] * dv[i] ** 2 for i in range(2))
        m = n2**-1 + 1
        ms.append(m)
        gs.append(mpmath.matrix([-2 * n2**-2 * w[i] * dv[i] for i in range(2)]))
    M = ms[0] * ms[1]
    grad = gs[0] * ms[1] + gs[1] * ms[0]
    Jd = M * Jm + Rm * grad.T
    want = -mpmath.lu_solve(Jd, M * Rm)
    assert np.allclose(ours, [float(v) for v in want], rtol=1e-13, atol=0)


# --- a published deflation example: the first Painlevé transcendent --------------------------


def test_painleve_two_solutions_from_one_guess():
    """Farrell, Birkisson & Funke (2015), the first Painlevé transcendent example: the
    problem has two solutions, and deflation finds both from one initial guess. Here from
    y = √x: exactly two (a third deflated run finds none), each with residual ≤ 1e-10. The
    oracle is an independent solver: scipy's collocation ``solve_bvp`` (tol 1e-10) started
    from each, which gives y'(0) = 0.92438 and −3.79199; the finite-difference solutions
    converge to them at second order (the error's ratio from n = 99 to 199, h halved, is
    4 to 1 %)."""
    from scipy.integrate import solve_bvp

    errors: list[list[float]] = [[], []]
    slopes = []
    for n in (99, 199):
        prob, x = painleve(n)
        found = deflate(prob, [np.sqrt(x)], max_solutions=10)
        assert len(found) == 2 and found.runs == 3
        assert all(r <= 1e-10 for r in found.residual_norms)
        for j, u in enumerate(sorted(found.solutions, key=lambda v: -v[0])):
            xs = np.concatenate([[0.0], x, [10.0]])
            ys = np.concatenate([[0.0], u, [math.sqrt(10.0)]])
            ref = solve_bvp(
                lambda t, Y: np.vstack([Y[1], Y[0] ** 2 - t]),
                lambda a, b: np.array([a[0], b[0] - math.sqrt(10.0)]),
                xs, np.vstack([ys, np.gradient(ys, xs)]), tol=1e-10, max_nodes=200000,
            )  # fmt: skip
            assert ref.status == 0
            errors[j].append(float(np.max(np.abs(ref.sol(x)[0] - u))))
            slopes.append(float(ref.sol(0.0)[1]))
    for e in errors:
        assert abs(e[0] / e[1] - 4.0) <= 0.04, errors
    assert slopes[0] == pytest.approx(slopes[2], abs=1e-8)  # the same solution at both n
    assert slopes[0] > 0.9 and slopes[1] < -3.7  # one rising, one dipping below zero
    # as docs/continuation.md quotes them (solve_bvp at tol 1e-10, to 5 decimals)
    assert [f"{s:.5f}" for s in slopes[:2]] == ["0.92438", "-3.79199"], slopes


def test_plot_draws_every_branch_and_the_points():
    """One line per branch (no stability column here) and one marker line for the points."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    d = diagram(two_modes(), [0.0, 0.0], free="lam", bounds={"lam": (0.0, 6.0)})
    ax = d.plot("lam", "x")
    assert len(ax.lines) == len(d.branches) + 1
    plt.close(ax.figure)
