"""``fold_curve(..., stability=True)`` (issue 29 point 3): Bogdanov–Takens and zero-Hopf
points on fold curves of normal forms whose points are known in closed form; a neutral
saddle on a fold curve is not reported."""

from __future__ import annotations

import numpy as np
import pytest

from cusp.continuation import Problem, ProblemDefinitionError, fold_curve, trace

#: codimension-2 points located to (issue 29)
TOL = 1e-8


def bt_family() -> Problem:
    # x' = y, y' = β1 + β2/2 + β2 x + x² − xy. Equilibria y = 0, β1 + β2/2 + β2 x + x² = 0;
    # folds where β2 + 2x = 0: the fold curve β1 = β2²/4 − β2/2, x = −β2/2. There the
    # Jacobian is [[0, 1], [0, −x]] (eigenvalues 0 and −x = β2/2): a Jordan block at x = 0,
    # the Bogdanov–Takens point β1 = β2 = 0
    return Problem(
        lambda u, p: np.array(
            [u[1], p["b1"] + 0.5 * p["b2"] + p["b2"] * u[0] + u[0] ** 2 - u[0] * u[1]]
        ),
        ["x", "y"],
        {"b1": 0.0, "b2": -1.0},
        mass=True,
    )


def test_bogdanov_takens_on_a_fold_curve():
    prob = bt_family()
    br = trace(prob, [1.3, 0.0], free="b1", bounds={"b1": (-2.0, 2.0)})
    (fold,) = br.special("fold")
    assert fold.values["x"] == pytest.approx(0.5, abs=1e-12)  # x = −β2/2 at β2 = −1
    curve = fold_curve(prob, fold, free=("b1", "b2"), bounds={"b2": (-2.0, 2.0)}, stability=True)
    (bt,) = curve.special("bogdanov_takens")
    assert bt.status == "converged"
    assert abs(bt.values["b1"]) < TOL and abs(bt.values["b2"]) < TOL and abs(bt.values["x"]) < TOL
    assert curve.special("zero_hopf") == []
    # the curve is the closed form β1 = β2²/4 − β2/2
    assert np.max(np.abs(curve["b1"] - (curve["b2"] ** 2 / 4 - curve["b2"] / 2))) < 1e-9
    # without stability, no such point (and the default tests are unchanged)
    plain = fold_curve(prob, fold, free=("b1", "b2"), bounds={"b2": (-2.0, 2.0)})
    assert "bogdanov_takens" not in {sp.kind for sp in plain.special_points}


def pair_family(kind: str) -> Problem:
    # x' = β1 + x² (a fold at β1 = 0, x = 0, for every β2) beside a linear pair (y, z):
    # "hopf": [[β2, −2], [2, β2]], eigenvalues β2 ± 2i: zero-Hopf at β2 = 0, ω = 2;
    # "saddle": [[β2 − 1, 2], [1, −1]], trace β2 − 2, determinant −β2 − 1 (< 0 for
    # β2 > −1): at β2 = 2 the eigenvalues are ±sqrt(3) (a neutral saddle: λ1 + λ2 = 0, real)
    def residual(u, p):
        x, y, z = u
        b2 = p["b2"]
        if kind == "hopf":
            pair = [b2 * y - 2 * z, 2 * y + b2 * z]
        else:
            pair = [(b2 - 1) * y + 2 * z, y - z]
        return np.array([p["b1"] + x * x + 0.1 * (y * y + z * z), *pair])

    return Problem(residual, ["x", "y", "z"], {"b1": -1.0, "b2": -0.5}, mass=True)


def _fold(prob: Problem):
    br = trace(prob, [-1.0, 0.0, 0.0], free="b1", bounds={"b1": (-1.0, 1.0)})
    (fold,) = br.special("fold")
    assert abs(fold.values["b1"]) < 1e-12 and abs(fold.values["x"]) < 1e-6
    return fold


def test_zero_hopf_on_a_fold_curve():
    prob = pair_family("hopf")
    curve = fold_curve(
        prob, _fold(prob), free=("b1", "b2"), bounds={"b2": (-0.5, 0.5)}, stability=True
    )
    (zh,) = curve.special("zero_hopf")
    assert zh.status == "converged"
    assert abs(zh.values["b2"]) < TOL and abs(zh.values["b1"]) < TOL
    assert zh.details["omega"] == pytest.approx(2.0, abs=TOL)
    assert curve.special("bogdanov_takens") == []


def test_neutral_saddle_on_a_fold_curve_is_not_zero_hopf():
    prob = pair_family("saddle")
    # the pair's trace β2 − 2 passes 0 at β2 = 2 with determinant −3 < 0: real ±sqrt(3)
    curve = fold_curve(
        prob, _fold(prob), free=("b1", "b2"), bounds={"b2": (-0.5, 3.0)}, stability=True
    )
    assert curve["b2"].min() < 2.0 < curve["b2"].max()
    assert curve.special("zero_hopf") == [] and curve.special("bogdanov_takens") == []


def test_fold_curve_stability_refuses_a_residual_that_is_no_vector_field():
    prob = Problem(lambda u, p: [p["a"] + u[0] ** 2 + p["b"]], ["x"], {"a": -1.0, "b": 0.0})
    br = trace(prob, [-1.0], free="a", bounds={"a": (-1.0, 1.0)})
    with pytest.raises(ProblemDefinitionError, match="mass=True"):
        fold_curve(prob, br.special("fold")[0], free=("a", "b"), stability=True)
