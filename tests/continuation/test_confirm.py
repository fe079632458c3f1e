"""Confirming a step across which a test of the curve's geometry changed sign: a fold is
located first and confirmed by lying on the step's cubic Hermite arc
(`confirm.located_on_arc`); anything else, and a fold that is not on the arc, by the half
step (`confirm.confirm_step`). References: the cusp x³ − x − b = 0, folds at
b = ∓2/(3√3) (exact), and the same trace with the half step forced."""

from __future__ import annotations

import numpy as np
import pytest

import cusp.continuation.stepping._tracer as tracer_module
import cusp.examples as ex
from cusp.continuation import trace
from cusp.continuation.stepping._confirm import arc_limit, located_on_arc

FOLD_B = 2.0 / (3.0 * np.sqrt(3.0))


@pytest.fixture
def fold_step(first_fold_step):
    """A cusp tracer, the state before the first step that crosses the lower fold, that step,
    its bracket and the fold located in it."""
    tracer, state, trial, br, crossing = first_fold_step(ex.cusp_normal_form().problem, [-1.3247])
    return tracer, state, trial, br, crossing.test.locate(br, crossing.old, crossing.new)


def test_a_located_fold_confirms_its_step(fold_step):
    tracer, state, trial, br, loc = fold_step
    assert loc.status == "converged"
    assert abs(loc.z[-1] - FOLD_B) < 1e-12  # the fold at b = +2/(3√3) (x = −1/√3)
    assert located_on_arc(tracer._rules, state, trial, br, [loc])


def test_a_point_off_the_arc_or_not_located_does_not_confirm(fold_step):
    tracer, state, trial, br, loc = fold_step
    W = state.system.weights
    _, limit = arc_limit(W, state.last.z, state.last.t, trial)
    # moved across the arc (along the normal of the chord in the weighted metric) by twice
    # the limit: the step is left to the half step
    chord = trial.res.z - state.last.z
    normal = np.array([-chord[1], chord[0]]) / W
    normal /= np.sqrt(normal.dot(W * normal))
    off = loc._replace(z=loc.z + 2.0 * limit * normal)
    assert not located_on_arc(tracer._rules, state, trial, br, [off])
    assert not located_on_arc(tracer._rules, state, trial, br, [loc._replace(status="guess")])


def test_folds_are_confirmed_without_the_half_step(monkeypatch):
    def no_half_step(*args, **kwargs):
        raise AssertionError("the half step was taken for a fold on its arc")

    monkeypatch.setattr(tracer_module, "confirm_step", no_half_step)
    case = ex.cusp_normal_form()
    br = trace(case.problem, u0=[-1.3247], free="b", bounds={"b": (-1.0, 1.0)})
    folds = sorted(sp.values["b"] for sp in br.special("fold"))
    assert folds == pytest.approx([-FOLD_B, FOLD_B], abs=1e-12)


def test_a_fold_off_the_arc_falls_back_to_the_half_step(monkeypatch):
    case = ex.cusp_normal_form()
    reference = trace(case.problem, u0=[-1.3247], free="b", bounds={"b": (-1.0, 1.0)})
    calls = []
    confirm = tracer_module.confirm_step

    def counted(*args, **kwargs):
        calls.append(1)
        return confirm(*args, **kwargs)

    monkeypatch.setattr(tracer_module, "located_on_arc", lambda *args: False)
    monkeypatch.setattr(tracer_module, "confirm_step", counted)
    br = trace(case.problem, u0=[-1.3247], free="b", bounds={"b": (-1.0, 1.0)})
    assert len(calls) == 2  # one half step per fold: both steps confirmed by it
    np.testing.assert_array_equal(br["b"], reference["b"])
    np.testing.assert_array_equal(br["x"], reference["x"])


@pytest.mark.parametrize("ds", [0.1, 0.2, 0.05])
def test_a_step_landing_on_a_branch_point_is_cut_off_the_dyadic_grid(ds):
    """x(p − x) = 0 from x = 0, p = −1 (p's typical size is its bounds' width, 2: a step ds
    moves it by 2·ds): with ds = 0.1 the steps reach p = −0.8, −0.4, and the next predictor
    lands exactly on the branch point p = 0, where the bordered matrix is singular. Halving
    the step landed on it again from every dyadic point before it (−0.2, −0.1, …): 46 steps,
    30 rejections. A cut that is not a power of 2 leaves the grid: the branch point (exact:
    x = p = 0) is located and the branch ends at p = 1 in a few steps whatever ds."""
    br = ex.transcritical().trace(ds=ds)
    assert br.status == "bound"
    bps = br.special("branch_point")
    assert len(bps) == 1 and bps[0].status == "converged"
    assert abs(bps[0].values["p"]) < 1e-10 and abs(bps[0].values["x"]) < 1e-10
    assert br.info["steps"] <= 10
    assert int(np.sum(br.stats["rejected_steps"])) <= 3
