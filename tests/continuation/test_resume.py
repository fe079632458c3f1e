"""Restart and resume: ``trace(problem, branch.point(i), ...)`` starts from any row;
``trace(problem, branch, ...)`` continues a partial branch (stopped at ``max_steps``, loaded
from a file, a checkpoint of an interrupted trace) and gives the points of the
uninterrupted trace bit for bit; ``checkpoint=`` saves the branch as it goes; ``progress=``
shows a bar on a terminal only.

Oracles: the uninterrupted trace itself (bit for bit); closed forms for the restarts: the
cusp normal form x³ − a x − b = 0 has its folds where 3x² = a, at b = ±2 (a/3)^{3/2}
(a = 1: ±0.3849001794597505; a = 2: ±2 (2/3)^{3/2} = ±1.0886621079036347).
"""

from __future__ import annotations

import io
import math
import sys
import warnings

import numpy as np
import pytest

from cusp.continuation import (
    Branch,
    MaxStepsWarning,
    Problem,
    ProblemDefinitionError,
    fold_curve,
    load,
    trace,
)
from cusp.continuation.stepping import _trace
from cusp.examples import bratu, cusp_normal_form, lorenz, pp2, truss_green
from cusp.examples.symmetric import chafee_infante


def _fold_b(a: float) -> float:
    return 2.0 * (a / 3.0) ** 1.5  # closed form (module docstring)


#: examples whose branch is interrupted and continued: a scalar branch with folds, branch
#: points (2 components), a truss, dense branch points with spectra (Chafée–Infante, n = 8:
#: 9 components), sparse Bratu (61 components: partial spectra), Lorenz (a pitchfork)
CASES = {
    "cusp": cusp_normal_form,
    "pp2": pp2,
    "truss": truss_green,
    "chafee_infante": lambda: chafee_infante(8, lam_max=10.0),
    "bratu_sparse": lambda: bratu(60, sparse=True),
    "lorenz": lorenz,
}


def _partial(ex, k: int) -> Branch:
    with pytest.warns(MaxStepsWarning):
        return ex.trace(max_steps=k)


def _continue(ex, branch: Branch, **kw) -> Branch:
    return trace(ex.problem, branch, free=ex.free, bounds=ex.bounds, monitor=ex.monitor, **kw)


@pytest.mark.parametrize("name", sorted(CASES))
def test_a_continued_branch_is_the_uninterrupted_one(name, tmp_path, same_bits):
    """Stopped after k steps (k = 1, a third, all but one), saved, loaded and continued:
    the same branch, every bit of every array, special point, statistic and info."""
    ex = CASES[name]()
    full = ex.trace()
    steps = full.info["steps"]
    assert full.success and steps >= 3
    later = [sp for sp in full.special_points if sp.kind != "endpoint"]
    assert later, "the case must have special points to locate after the restart"
    for k in sorted({1, steps // 3, steps - 1}):
        part = _partial(ex, k)
        assert part.status == "max_steps" and len(part) < len(full)
        loaded = load(part.save(tmp_path / f"{name}-{k}.npz"))
        rest = _continue(ex, loaded, max_steps=5000)
        same_bits(full, rest)
    # the restart after the first step has special points still ahead of it (but on
    # Lorenz, whose only branch point is located inside the first step)
    row = len(_partial(ex, 1)) - 1
    assert any(sp.index > row for sp in later) or name == "lorenz"


def test_continued_in_memory_and_in_several_pieces(same_bits):
    """Without a file, and interrupted twice: the same bits."""
    ex = pp2()
    full = ex.trace()
    a = _partial(ex, 3)
    with pytest.warns(MaxStepsWarning):
        b = _continue(ex, a, max_steps=9)
    assert b.status == "max_steps" and b.info["steps"] == 9
    same_bits(full, _continue(ex, b, max_steps=5000))


def test_the_options_of_the_branch_are_kept(same_bits):
    """A branch traced with its own options continues with them (not the defaults)."""
    ex = cusp_normal_form()
    full = ex.trace(rtol=1e-6, ds_max=0.1)
    with pytest.warns(MaxStepsWarning):
        part = ex.trace(rtol=1e-6, ds_max=0.1, max_steps=10)
    same_bits(full, _continue(ex, part, max_steps=5000))
    assert full.info["options"]["rtol"] == 1e-6


# --- what cannot be continued ---------------------------------------------------------------


def test_refusals(tmp_path):
    ex = cusp_normal_form()
    full = ex.trace()
    part = _partial(ex, 5)
    with pytest.raises(ProblemDefinitionError, match="ended for good .*'bound'"):
        _continue(ex, full)
    with pytest.raises(ProblemDefinitionError, match="5 steps and max_steps=5: raise max_steps"):
        _continue(ex, part, max_steps=5)
    with pytest.raises(ProblemDefinitionError, match="other test functions"):
        trace(ex.problem, part, free="b", bounds={"b": (-1.0, 2.0)}, max_steps=100)
    with pytest.raises(ProblemDefinitionError, match="components are"):
        trace(ex.problem, part, free="a", bounds={"a": (-1.0, 2.0)}, max_steps=100)
    with pytest.raises(
        ProblemDefinitionError, match=r"params contradict the branch .*'a': \(2.0, 1.0\)"
    ):
        _continue(ex, part, params={"a": 2.0, "b": -1.0}, max_steps=100)
    with pytest.raises(ProblemDefinitionError, match="direction=-1, but .* direction=1"):
        _continue(ex, part, direction=-1, max_steps=100)
    fc = fold_curve(ex.problem, full.special("fold")[0], free=("b", "a"), bounds={"a": (0.0, 2.0)})
    with pytest.raises(ProblemDefinitionError, match="no resume data"):
        trace(ex.problem, fc, free="b", max_steps=100)


def test_a_branch_with_stability_is_not_continued():
    lz = lorenz()
    prob = Problem(lz.residual, list(lz.unknowns), {**lz.params, "rho": 2.0}, mass=True)
    x0 = math.sqrt(8.0 / 3.0)  # C+ at rho = 2: x = y = sqrt(beta (rho - 1)), z = rho - 1
    with pytest.warns(MaxStepsWarning):
        part = trace(
            prob, [x0, x0, 1.0], free="rho", bounds={"rho": (2.0, 30.0)}, stability=True,
            max_steps=3,
        )  # fmt: skip
    with pytest.raises(ProblemDefinitionError, match="analysed for stability"):
        trace(prob, part, free="rho", bounds={"rho": (2.0, 30.0)}, max_steps=100)


# --- restart from a row ----------------------------------------------------------------------


def test_restart_from_a_row_of_a_branch():
    """``br.point(i)`` holds the unknowns and every parameter: a trace from it (here in the
    other parameter, at the row's b rather than the problem's) finds the closed-form folds."""
    ex = cusp_normal_form()  # x^3 - a x - b, a = 1, b = -1
    br = ex.trace()
    row = br.point(1)  # b = -0.95..., before both folds (the trace goes on in +b)
    again = trace(ex.problem, row, free="b", bounds=ex.bounds)
    b_folds = [sp.values["b"] for sp in again.special("fold")]
    assert b_folds == pytest.approx([_fold_b(1.0), -_fold_b(1.0)], abs=1e-12)
    # free a at a row's b: x^3 - a x - b = 0 gives a = x^2 - b/x; for b > 0 and x < 0 it
    # folds where da/dx = 2x + b/x^2 = 0, i.e. x = -(b/2)^(1/3), a = 3 (b/2)^(2/3), its
    # minimum: a row of the middle sheet (between the folds, b > 0, x < 0), a decreasing
    i = next(i for i in range(len(br)) if br["b"][i] > 0.1 and br["x"][i] < 0)
    row = br.point(i)
    b = row["b"]
    other = trace(ex.problem, row, free="a", bounds={"a": (-3.0, 3.0)}, direction=-1)
    assert np.all(other["b"] == b)  # the row's b, not the problem's -1
    (fold,) = other.special("fold")
    assert fold.values["a"] == pytest.approx(3.0 * (b / 2.0) ** (2.0 / 3.0), rel=1e-12)
    assert fold.values["x"] == pytest.approx(-((b / 2.0) ** (1.0 / 3.0)), rel=1e-9)


def test_direction_is_still_checked():
    """direction=None is the default (+1); 0 is refused as before."""
    with pytest.raises(ProblemDefinitionError, match="direction must be"):
        cusp_normal_form().trace(direction=0)


def test_restart_from_a_point_refusals():
    ex = cusp_normal_form()
    row = ex.trace().point(3)
    with pytest.raises(ProblemDefinitionError, match=r"lacks \['x'\]"):
        trace(ex.problem, {"b": 0.1}, free="b")
    with pytest.raises(ProblemDefinitionError, match=r"u0 names \['c'\]"):
        trace(ex.problem, {**row, "c": 1.0}, free="b")
    with pytest.raises(ProblemDefinitionError, match="params contradict the point"):
        trace(ex.problem, row, free="b", params={"a": 2.0, "b": row["b"]})


# --- checkpoints ------------------------------------------------------------------------------


def test_checkpoint_every_n_steps_and_at_the_end(tmp_path, monkeypatch, same_bits):
    ex = pp2()
    path = tmp_path / "ck.npz"
    saved = []
    save = _trace.Watch.save

    def counting(self, tracer, state):
        saved.append(state.steps)
        save(self, tracer, state)

    monkeypatch.setattr(_trace.Watch, "save", counting)
    br = ex.trace(checkpoint=path, checkpoint_every=4)
    steps = br.info["steps"]
    assert saved == [*range(4, steps + 1, 4), steps]
    same_bits(br, load(path))


class _Killed(Exception):
    pass


def test_an_interrupted_trace_resumes_from_its_checkpoint(tmp_path, same_bits):
    """A trace killed mid-way (an exception out of the residual, as Ctrl-C would be) leaves
    its checkpoint, status "running", which a new trace continues to the same bits."""
    ex = cusp_normal_form()
    full = ex.trace()
    calls = {"n": 0}

    def dying(u, p):
        calls["n"] += 1
        if calls["n"] > 60:
            raise _Killed
        return ex.residual(u, p)

    fragile = Problem(dying, list(ex.unknowns), ex.params, jacobian=ex.jacobian,
                      param_jacobian=ex.param_jacobian)  # fmt: skip
    path = tmp_path / "ck.npz"
    with pytest.raises(_Killed):
        trace(fragile, ex.u0, free="b", bounds=ex.bounds, checkpoint=path, checkpoint_every=1000)
    partial = load(path)
    assert partial.status == "running" and 1 < len(partial) < len(full)
    same_bits(full, _continue(ex, partial))


def test_checkpoint_arguments_are_checked(tmp_path):
    ex = cusp_normal_form()
    with pytest.raises(ProblemDefinitionError, match="checkpoint_every must be an integer >= 1"):
        ex.trace(checkpoint=tmp_path / "c.npz", checkpoint_every=0)
    with pytest.raises(ProblemDefinitionError, match="does not exist"):
        ex.trace(checkpoint=tmp_path / "absent" / "c.npz")
    with pytest.raises(ProblemDefinitionError, match="progress must be True or False"):
        ex.trace(progress="yes")


# --- progress -----------------------------------------------------------------------------


def test_no_watch_and_no_cost_when_nothing_is_asked(monkeypatch):
    """No checkpoint and no terminal: no watch at all (the plain loop runs)."""
    monkeypatch.setattr(sys, "stderr", io.StringIO())
    assert _trace.Watch.of(None, 100, False) is None
    assert _trace.Watch.of(None, 100, True) is None  # progress asked, but not a terminal


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def _slow_cusp(delay: float) -> Problem:
    import time

    ex = cusp_normal_form()

    def residual(u, p):
        time.sleep(delay)
        return ex.residual(u, p)

    return Problem(residual, list(ex.unknowns), ex.params, jacobian=ex.jacobian,
                   param_jacobian=ex.param_jacobian)  # fmt: skip


def test_progress_is_shown_on_a_terminal_after_a_second(monkeypatch):
    pytest.importorskip("tqdm")
    ex = cusp_normal_form()
    screen = _Terminal()
    monkeypatch.setattr(sys, "stderr", screen)
    ex.trace(progress=True)  # ~10 ms: under the second, nothing shown
    assert screen.getvalue() == ""
    trace(_slow_cusp(0.01), ex.u0, free="b", bounds=ex.bounds, progress=True)  # ~1.5 s
    assert "trace b" in screen.getvalue() and "steps" in screen.getvalue()


def test_progress_when_piped_shows_nothing(capsys):
    ex = cusp_normal_form()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        trace(_slow_cusp(0.005), ex.u0, free="b", bounds=ex.bounds, progress=True)
    assert capsys.readouterr().err == ""


def test_progress_without_tqdm_names_the_extra(monkeypatch):
    monkeypatch.setattr(sys, "stderr", _Terminal())
    monkeypatch.setitem(sys.modules, "tqdm", None)
    with pytest.raises(ImportError, match=r"cusp\[progress\]"):
        cusp_normal_form().trace(progress=True)
