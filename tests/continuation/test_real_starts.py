"""Branch points passed from the starts users really have, and steps whose work is bounded.

References (closed forms):

- Lorenz equilibria σ(y − x) = 0, r x − y − x z = 0, x y − β z = 0 (σ = 10, β = 8/3): the
  origin for every r, with det ∂R/∂u = σβ(r − 1): a pitchfork at r = 1, where the branches
  x = y = ±√(β(r − 1)), z = r − 1 leave it;
- x(p − x²) = 0 and x(p − x) = 0: a pitchfork and a transcritical branch point at x = p = 0;
- u − √(1 − p) = 0: the branch u = √(1 − p) ends at p = 1, the edge of the residual's
  domain (NaN beyond);
- x³ − x − b = 0: folds at b = ±2/(3√3).
"""

from __future__ import annotations

import math
import time

import numpy as np
import pytest

from cusp.continuation import (
    JacobianError,
    NonFiniteResidualError,
    Problem,
    ProblemDefinitionError,
    SingularPointError,
    StalledError,
    trace,
)

SIGMA, BETA = 10.0, 8.0 / 3.0


def _lorenz(analytic: bool) -> Problem:
    def residual(u, p):
        x, y, z = u
        return np.array([SIGMA * (y - x), p["r"] * x - y - x * z, x * y - BETA * z])

    def jacobian(u, p):
        x, y, z = u
        return np.array([[-SIGMA, SIGMA, 0.0], [p["r"] - z, -1.0, -x], [y, x, -BETA]])

    def param_jacobian(u, p, name):
        return np.array([0.0, u[0], 0.0])

    extra = {"jacobian": jacobian, "param_jacobian": param_jacobian} if analytic else {}
    return Problem(residual, ["x", "y", "z"], {"r": 0.5}, **extra)


def _exact_steps(problem: Problem) -> int:
    return trace(problem, [0.0, 0.0, 0.0], free="r", bounds={"r": (0.0, 3.0)}).info["steps"]


@pytest.mark.parametrize("analytic", [False, True], ids=["central", "analytic"])
def test_lorenz_pitchfork_from_random_corrected_starts(analytic):
    """40 guesses uniform in [−0.5, 0.5]³, each corrected by Newton to the origin (the
    remainder of its convergence): the pitchfork at r = 1 is reported once, converged, to
    1e-10; the trace stays on the origin's branch and takes the exact start's steps (+3)."""
    problem = _lorenz(analytic)
    exact = _exact_steps(problem)
    rng = np.random.default_rng(26)
    for u0 in rng.uniform(-0.5, 0.5, (40, 3)):
        br = trace(problem, u0, free="r", bounds={"r": (0.0, 3.0)})
        assert br.status == "bound"
        assert np.max(np.abs([br["x"], br["y"], br["z"]])) < 1e-12, "left the origin"
        bps = br.special("branch_point")
        assert len(bps) == 1 and bps[0].status == "converged"
        assert abs(bps[0].values["r"] - 1.0) <= 1e-10
        assert br.info["steps"] <= exact + 3, "crept towards the branch point"


def test_the_issue_start_that_hung_returns_at_once():
    # the start of the report whose step looped 26,000 times retaking its half step
    u0 = [0.4489436749377653, -0.039954860690903926, 0.25772884530829143]
    start = time.perf_counter()
    br = trace(_lorenz(False), u0, free="r", bounds={"r": (0.0, 3.0)}, max_steps=50)
    assert time.perf_counter() - start < 10.0  # (a watchdog: it takes milliseconds)
    assert br.status == "bound" and len(br.special("branch_point")) == 1


def test_newton_remainders_of_zeros_are_snapped_and_genuine_small_values_kept():
    # the guess 0.1 is corrected to ~1e-17: set to 0 exactly (the equations are then exact)
    br = trace(_lorenz(True), [0.1, 0.1, 0.1], free="r", bounds={"r": (0.0, 0.9)})
    assert br["x"][0] == br["y"][0] == br["z"][0] == 0.0
    # a concentration of 1e-9 beside 1e6: its equations are off by its own terms without it
    prob = Problem(  # c = (1 + k) P/1e15, P = 1e6 (1 + k): c = 1e-9 at k = 0
        lambda u, p: [u[0] * 1e15 - (1 + p["k"]) * u[1], u[1] - 1e6 * (1 + p["k"])],
        ["c", "P"],
        {"k": 0.0},
    )
    br = trace(prob, [1e-9, 1e6], free="k", bounds={"k": (0.0, 1.0)})
    assert br["c"][0] != 0.0 and br.info["scales"]["c"] < 1e-6  # (sized by its value)


def test_the_tangent_of_a_symmetric_branch_comes_from_its_own_point():
    # from a guess off the symmetric branch, the start and every step's tangent have no
    # component along the other branch (x = y) beyond rounding, up to the branch point
    br = trace(_lorenz(False), [0.3, -0.2, 0.1], free="r", bounds={"r": (0.0, 0.99)})
    assert np.max(np.abs(br.tangents[:, :2])) < 1e-14


@pytest.mark.parametrize("derivatives", ["central", "forward", "analytic"])
@pytest.mark.parametrize(
    ("residual", "dfdx", "dfdp"),
    [
        (lambda x, p: x * (p - x**2), lambda x, p: p - 3 * x**2, lambda x, p: x),
        (lambda x, p: x * (p - x), lambda x, p: p - 2 * x, lambda x, p: x),
    ],
    ids=["pitchfork", "transcritical"],
)
def test_a_start_exactly_on_a_branch_point_is_refused_whatever_the_derivatives(
    derivatives, residual, dfdx, dfdp
):
    kw: dict = (
        {
            "jacobian": lambda u, p: [[dfdx(u[0], p["p"])]],
            "param_jacobian": lambda u, p, n: [dfdp(u[0], p["p"])],
        }
        if derivatives == "analytic"
        else {"derivatives": derivatives}
    )
    prob = Problem(lambda u, p: [residual(u[0], p["p"])], ["x"], {"p": 0.0}, **kw)
    with pytest.raises(SingularPointError, match="branch point"):
        trace(prob, [0.0], free="p", bounds={"p": (-1.0, 1.0)})
    with pytest.raises(SingularPointError):  # (corrected onto it from a guess)
        trace(prob, [0.01], free="p", bounds={"p": (-1.0, 1.0)})


def test_a_start_exactly_on_the_lorenz_pitchfork_is_refused():
    for analytic in (False, True):
        prob = _lorenz(analytic).with_params(r=1.0)
        with pytest.raises(SingularPointError):
            trace(prob, [0.0, 0.0, 0.0], free="r", bounds={"r": (0.0, 3.0)})


def test_a_step_that_cannot_progress_ends_stalled_with_what_was_tried():
    # one corrector solve a step cannot confirm the branch point's step by its half step
    kw = {"free": "r", "bounds": {"r": (0.0, 3.0)}, "max_step_solves": 1}
    br = trace(_lorenz(False), [0.0, 0.0, 0.0], throw=False, **kw)
    assert br.status == "stalled" and not br.success
    assert "corrector solves" in br.message and "r=" in br.message
    with pytest.raises(StalledError) as info:
        trace(_lorenz(False), [0.0, 0.0, 0.0], **kw)
    assert info.value.values and info.value.ds > 0 and "tries" in info.value.tried


def test_a_residual_undefined_beyond_its_domain_is_reported_as_such():
    """u = √(1 − p) ends at p = 1; beyond it the residual is NaN (numpy's warning must not
    leak: pytest runs with warnings as errors)."""

    def jac(u, p):
        return [[1.0]]

    def pjac(u, p, name):
        return [0.5 / math.sqrt(1 - p["p"])]

    for kw in ({}, {"jacobian": jac, "param_jacobian": pjac}):
        prob = Problem(lambda u, p: [u[0] - np.sqrt(1 - p["p"])], ["u"], {"p": 0.0}, **kw)
        br = trace(prob, [1.0], free="p", bounds={"p": (-1.0, 3.0)}, throw=False)
        assert br.status == "nonfinite_residual"
        assert "not finite" in br.message and "domain" in br.message
        assert "inconsistent" not in br.message
        assert br["p"][-1] > 0.999  # (it got to the edge)
        with pytest.raises(NonFiniteResidualError):
            trace(prob, [1.0], free="p", bounds={"p": (-1.0, 3.0)})


def test_an_undeclared_parameter_is_named():
    prob = Problem(lambda u, p: [u[0] - p["q"]], ["u"], {"p": 0.0})
    with pytest.raises(ProblemDefinitionError, match="'q'.*does not declare"):
        trace(prob, [1.0], free="p", bounds={"p": (-1.0, 3.0)})
    # read only later on the branch, and by a differenced parameter derivative
    prob = Problem(lambda u, p: [u[0] - (p["q"] if p["p"] > 0.5 else 0.0)], ["u"], {"p": 0.0})
    with pytest.raises(ProblemDefinitionError, match="'q'"):
        trace(prob, [0.0], free="p", bounds={"p": (-1.0, 3.0)})


def _cusp(jacobian, param_jacobian):
    return Problem(
        lambda u, p: [u[0] ** 3 - u[0] - p["b"]],
        ["x"],
        {"b": -1.0},
        jacobian=jacobian,
        param_jacobian=param_jacobian,
    )


@pytest.mark.parametrize(
    ("jacobian", "param_jacobian"),
    [
        (lambda u, p: [[3 * u[0] ** 2 + 1]], lambda u, p, n: [-1.0]),  # −1 written +1
        (lambda u, p: [[3 * u[0] ** 2 - 1]], lambda u, p, n: [1.0]),  # ∂/∂b's sign
    ],
    ids=["jacobian", "param_jacobian"],
)
def test_a_wrong_supplied_jacobian_is_refused(jacobian, param_jacobian):
    with pytest.raises(JacobianError, match="disagree") as info:
        trace(_cusp(jacobian, param_jacobian), [-1.3247], free="b", bounds={"b": (-1, 1)})
    assert info.value.row == 0 and "x=" in str(info.value)


def test_a_wrong_term_that_vanishes_at_the_start_is_refused_where_it_matters():
    """A sign error in ∂R₂/∂z (−x written +x) is invisible on the origin (x = 0) and caught
    at the start of the branch C+ (x = y = √(β(r − 1)), z = r − 1 at r = 2)."""

    def bad(u, p):
        x, y, z = u
        return np.array([[-SIGMA, SIGMA, 0.0], [p["r"] - z, -1.0, +x], [y, x, -BETA]])

    prob = Problem(
        _lorenz(False)._residual,
        ["x", "y", "z"],
        {"r": 2.0},
        jacobian=bad,
        param_jacobian=lambda u, p, n: np.array([0.0, u[0], 0.0]),
    )
    br = trace(prob.with_params(r=0.5), [0.0, 0.0, 0.0], free="r", bounds={"r": (0.0, 3.0)})
    assert [round(sp.values["r"], 12) for sp in br.special("branch_point")] == [1.0]
    x = math.sqrt(BETA)
    with pytest.raises(JacobianError, match="equation 1"):
        trace(prob, [x, x, 1.0], free="r", bounds={"r": (1.2, 3.0)})


# Rosenzweig–MacArthur predator–prey with a Holling type II response a u/(1 + b u) and
# b = −1/2 < 0: the denominator crosses zero at u = 2 on the prey-only branch v = 0, u = K.
# The transcritical branch point there is where e a u/(1 + b u) = m: u = K = m/(e a − b m).
_HOLLING = {"r": 1.0, "a": 1.0, "e": 0.5, "m": 0.2, "b": -0.5}


def _holling(analytic: bool) -> Problem:
    r, a, e, m, b = (_HOLLING[k] for k in "raemb")

    def residual(q, p):
        u, v = q
        f = a * u / (1 + b * u)
        return np.array([r * u * (1 - u / p["K"]) - f * v, e * f * v - m * v])

    def jacobian(q, p):
        u, v = q
        f, fu = a * u / (1 + b * u), a / (1 + b * u) ** 2
        return np.array([[r * (1 - 2 * u / p["K"]) - fu * v, -f], [e * fu * v, e * f - m]])

    def param_jacobian(q, p, name):
        return np.array([r * q[0] ** 2 / p["K"] ** 2, 0.0])

    extra = {"jacobian": jacobian, "param_jacobian": param_jacobian} if analytic else {}
    return Problem(residual, ["u", "v"], {"K": 0.2}, **extra)


@pytest.mark.parametrize("analytic", [False, True], ids=["central", "analytic"])
def test_a_sign_change_through_a_pole_marks_no_special_point(analytic):
    from cusp.continuation import Event

    r, a, e, m, b = (_HOLLING[k] for k in "raemb")
    bp = m / (e * a - b * m)  # = 1/3
    pole = Event(lambda u, p: 1.0 / (u[0] - 2.5), label="pole")
    br = trace(_holling(analytic), [0.2, 0.0], free="K", bounds={"K": (0.1, 3.0)}, events=[pole])
    assert br.status == "bound"
    found = [(sp.kind, sp.status) for sp in br.special_points if sp.kind != "endpoint"]
    assert found == [("branch_point", "converged")]
    assert abs(br.special("branch_point")[0].values["K"] - bp) <= 1e-10 * bp


@pytest.mark.parametrize("analytic", [False, True], ids=["central", "analytic"])
@pytest.mark.parametrize(("slope", "shift"), [(1.0, 0.0), (0.05, 3.0), (20.0, 3.0)])
def test_a_transcritical_point_passed_along_its_oblique_branch(analytic, slope, shift):
    """(x − c)(p − (x − c)/s) = 0: the branch x = c + s p crosses x = c at p = 0 (exact).
    From guesses 30 % off the oblique branch, at random start parameters and step sizes:
    the branch point once, converged, p to 1e-10 absolute (its value is 0), and every point
    on the oblique branch."""

    def residual(u, p):
        return np.array([(u[0] - shift) * (p["p"] - (u[0] - shift) / slope)])

    kw: dict = {}
    if analytic:
        kw = {
            "jacobian": lambda u, p: np.array([[p["p"] - 2 * (u[0] - shift) / slope]]),
            "param_jacobian": lambda u, p, n: np.array([u[0] - shift]),
        }
    rng = np.random.default_rng(7)
    for _ in range(15):
        p0, ds = -rng.uniform(0.05, 1.0), 10 ** rng.uniform(-3, math.log10(0.5))
        prob = Problem(residual, ["x"], {"p": p0}, **kw)
        u0 = [shift + slope * p0 * (1 + rng.uniform(-0.3, 0.3))]
        br = trace(prob, u0, free="p", bounds={"p": (-2.0, rng.uniform(0.05, 2.0))}, ds=ds)
        assert br.status == "bound"
        assert np.max(np.abs(br["x"] - shift - slope * br["p"])) <= 1e-9 * max(1, slope)
        bps = br.special("branch_point")
        assert len(bps) == 1 and bps[0].status == "converged" and abs(bps[0].values["p"]) < 1e-10


@pytest.mark.parametrize("analytic", [False, True], ids=["central", "analytic"])
def test_switching_at_a_branch_point_from_a_real_start_reaches_both_halves(analytic):
    """From the pitchfork located on a trace started at a random guess, both directions of
    the other branch: C+ and C−, x = y = ±√(β(r − 1)), z = r − 1, each to 1e-10."""
    problem = _lorenz(analytic)
    br = trace(problem, [0.21, -0.37, 0.05], free="r", bounds={"r": (0.0, 3.0)})
    (bp,) = br.special("branch_point")
    signs = []
    for direction in (1, -1):
        other = trace(problem, bp, free="r", bounds={"r": (0.0, 3.0)}, direction=direction)
        assert other.status == "bound"
        x, y, z, r = other["x"][1:], other["y"][1:], other["z"][1:], other["r"][1:]
        assert np.max(np.abs(x - y)) < 1e-10 and np.max(np.abs(z - (r - 1))) < 1e-10
        assert np.max(np.abs(x**2 - BETA * (r - 1))) < 1e-9
        signs.append(np.sign(x[-1]))
    assert sorted(signs) == [-1.0, 1.0]


@pytest.mark.parametrize("bounds", [{"b": (0.0, 2.0)}, {"b": (0.0, 2.0), "y": (-1.0, 2.0)}])
def test_a_step_across_a_pole_is_not_taken_for_a_bound(bounds):
    """y + 1e-8/y = b from y = 1 downwards: a fold at y = 1e-4, b = 2e-4 (exact), then b
    grows without bound as y → 0⁺. A long step from y ≈ 0.33 jumped the fold and the pole at
    y = 0 onto y < 0 (b ≈ y there too), and the bound b = 0, which Newton with b fixed cannot
    reach, was 'located' between the branches by regula falsi and the branch declared ended
    on it. Such a bound has the step confirmed by its half step: the fold is found, every
    point solves the equation to the tolerance (its rounding floor is that of its terms at
    the point, |∂R/∂y·y|, not at y's typical size 1) and the branch ends at b = 2."""
    prob = Problem(
        lambda u, p: [u[0] + 1e-8 / u[0] - p["b"]],
        ["y"],
        {"b": 1.0 + 1e-8},
        jacobian=lambda u, p: [[1 - 1e-8 / u[0] ** 2]],
        param_jacobian=lambda u, p, n: [-1.0],
    )
    br = trace(prob, [1.0], free="b", bounds=bounds, direction=-1)
    assert br.status == "bound" and br["b"][-1] == 2.0 and np.all(br["y"] > 0)
    (fold,) = br.special("fold")
    assert fold.status == "converged" and abs(fold.values["b"] - 2e-4) <= 1e-10 * 2e-4
    assert np.max(np.abs(br["y"] + 1e-8 / br["y"] - br["b"])) <= 1e-10


@pytest.mark.parametrize("derivatives", ["central", "forward"])
def test_a_branch_point_located_with_differences_is_polished_to_the_tolerance(derivatives):
    """A branch point's parameter is off by the Jacobian's error to first order. x ≈ 1000 in
    (x − 1000)(p − (x − 1000)²): central steps of 6e-3 (relative to |x|) leave J off by
    h² = 3.7e-5, and the pitchfork at p = 0 (exact) was 'converged' at p = 3.7e-5. Polished
    with the Jacobian extrapolated to a higher order, within 1e-10."""
    c = 1000.0
    prob = Problem(
        lambda u, p: [(u[0] - c) * (p["p"] - (u[0] - c) ** 2)],
        ["x"],
        {"p": -0.5},
        derivatives=derivatives,
    )
    br = trace(prob, [c + 0.1], free="p", bounds={"p": (-1.0, 1.0)})
    (bp,) = br.special("branch_point")
    assert bp.status == "converged" and abs(bp.values["p"]) <= 1e-10


def test_forward_differences_locate_the_turing_point_of_two_cells():
    # brusselator_cells: B_c = (1 + 2 Dx)(1 + A²/(2 Dy)) = 1.8·1.5 = 2.7 (A = 2, Dx = 0.4,
    # Dy = 4; cusp.examples.symmetric_cells); forward differences gave 2.69999995 before
    from cusp.examples import brusselator_cells

    ex = brusselator_cells(derivatives="forward")
    (bp,) = ex.trace().special("branch_point")
    assert bp.status == "converged" and abs(bp.values["B"] - 2.7) <= 1e-10 * 2.7
