"""The published-problem suite from perturbed starts, and under a watchdog (issue 26, parts 3
and 2).

Every problem of :data:`~cusp.examples.suite.SUITE` is traced from its start with seeded
relative noise (:func:`~cusp.examples.suite.perturbed`: component i gets
``rel·max(|u0_i|, size_i)·N(0, 1)``, the size 1 where it is 0) at the issue's three levels
``rel`` ∈ {1e-14, 1e-10, 1e-6} and for each seed of :data:`SEEDS`. The branch must pass
:func:`~cusp.examples.suite.check` exactly as the unperturbed one does (the same special
points to PARAM_RTOL / STATE_RTOL, a normal end, on its branch for the jump risks) and end as
the unperturbed one (:func:`~cusp.examples.suite.compare_ends`: the same status, the last
point to STATE_RTOL). For the problems with a reference branch point, hypothesis draws the
level (10^U(−16, −5)) and the noise vector itself (each draw a normal's, within ±4σ and
not below 1e-3 in magnitude).

Every trace here runs under :func:`~cusp.examples.suite.watchdog`, and
:func:`test_returns_in_time` traces every suite problem with the default options under it: a
hang fails its test instead of hanging the run.

Cases the current engine fails are strict ``xfail``s naming the failure (the engine is not
changed here): a fixed case turns into an error, and its mark must go.

Run: ``python -m pytest tests/suite/test_perturbed.py``.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import signal
import time
from typing import Any

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from cusp.continuation import (
    Branch,
    Problem,
    trace,
)
from cusp.examples import Example
from cusp.examples.suite import (
    SUITE,
    Hang,
    branch_point_problems,
    check,
    compare_ends,
    perturbed,
    problem,
    watchdog,
    watchdog_available,
)

#: The issue's three noise levels (issue 26, item 3).
RELS = (1e-14, 1e-10, 1e-6)
#: Seeds of the noise, the same for every problem and level. Five: each seed costs a few
#: seconds for the suite's problems × 3 levels on a 2-core machine (the issue asks for well
#: under a minute added to the whole run; ``pytest --durations=0 tests/suite`` shows this
#: file's share); scripts/bench_branch_points.py runs 30.
SEEDS = (0, 1, 2, 3, 4)
#: The watchdog's limit: the issue's floor of 10 s. 20× a problem's normal time is less (the
#: slowest suite trace takes about 0.1 s: ``pytest -s tests/suite -k timing``).
WATCHDOG_SECONDS = 10.0
#: Hypothesis examples per branch-point problem (a few seconds for all of them).
EXAMPLES = 8
#: A draw of the noise model's N(0, 1): magnitude 1e-3..4, either sign. Beyond ±4σ lies 6e-5
#: of the normal, below 1e-3 in magnitude 8e-4 (2·φ(0)·1e-3); smaller draws would take the
#: noise below the drawn level (hypothesis draws 1e-300 happily; such starts are
#: test_a_start_component_far_below_its_scale's business).
NORMAL_DRAW = st.floats(1e-3, 4.0).flatmap(lambda m: st.sampled_from((m, -m)))

#: Starts the engine once failed from (Newton's correction of the start cycled between two
#: points 1e-16 from u = v = 0, the rounding of the strains, because u's typical size was
#: taken from its guess of 1e-15…1e-10): tested besides those of SEEDS. Found with seeds
#: 0–99, ``python scripts/bench_branch_points.py --suite-seeds 100``.
REGRESSIONS: list[tuple[str, float, int]] = [
    ("truss_2dof_h1.8", 1e-14, 16),
    ("truss_2dof_h1.8", 1e-10, 6),
    ("truss_2dof_h1.8", 1e-10, 39),
]

#: Problems whose hypothesis test the current engine fails, and how.
HYPOTHESIS_XFAIL: dict[str, str] = {}


@functools.cache
def _unperturbed(name: str) -> tuple[Example, Branch]:
    """The suite problem ``name`` (its references computed once) and its branch from the
    unperturbed start."""
    example = problem(name)
    refs = example.references()
    example = dataclasses.replace(example, reference_points=lambda: refs)
    return example, _traced(example, name)


def _traced(example: Example, name: str) -> Branch:
    """``example.trace()`` under the watchdog (where it can run)."""
    if not watchdog_available():
        return example.trace()
    with watchdog(WATCHDOG_SECONDS, f"the trace of {name} from {example.u0.tolist()}"):
        return example.trace()


def _judged(example: Example, name: str) -> list[str]:
    """What :func:`check` and :func:`compare_ends` find wrong with the perturbed example's
    branch."""
    _, reference = _unperturbed(name)
    br = _traced(example, name)
    return check(example, br, name) + compare_ends(example, reference, br)


def _cases() -> list[Any]:
    keys = [(name, rel, seed) for name, _, _ in SUITE for rel in RELS for seed in SEEDS]
    keys += [key for key in REGRESSIONS if key not in keys]
    return [pytest.param(name, rel, seed, id=f"{name}-{rel:g}-{seed}") for name, rel, seed in keys]


@pytest.mark.parametrize(("name", "rel", "seed"), _cases())
def test_perturbed_start(name, rel, seed):
    example, _ = _unperturbed(name)
    start = perturbed(example, rel, seed)
    # noise on every zero of the start; elsewhere rel·m·n can round away (1e-14·2.3·n is
    # below half an ulp of 2.3 for |n| < 0.0097: brusselator_n4, seed 4)
    assert np.all(start.u0[example.u0 == 0.0] != 0.0) and np.any(start.u0 != example.u0)
    wrong = _judged(start, name)
    assert not wrong, f"from {start.u0.tolist()!r}:\n" + "\n".join(wrong)


def _branch_point_cases() -> list[Any]:
    return [
        pytest.param(
            name,
            id=name,
            marks=[pytest.mark.xfail(strict=True, reason=HYPOTHESIS_XFAIL[name])]
            if name in HYPOTHESIS_XFAIL
            else [],
        )
        for name in branch_point_problems()
    ]


@pytest.mark.parametrize("name", _branch_point_cases())
@settings(deadline=None, max_examples=EXAMPLES, derandomize=True, database=None)
@given(data=st.data())
def test_branch_point_problem_from_any_start(name, data):
    example, _ = _unperturbed(name)
    # the level log-uniform in 1e-16 … 1e-5 (issue 26, item 3)
    exponent = data.draw(st.floats(-16.0, -5.0), label="log10(rel)")
    n = example.u0.size
    noise = data.draw(st.lists(NORMAL_DRAW, min_size=n, max_size=n), label="noise")
    start = perturbed(example, 10.0**exponent, noise=noise)
    wrong = _judged(start, name)
    assert not wrong, f"from {start.u0.tolist()!r}:\n" + "\n".join(wrong)


def test_a_start_component_far_below_its_scale():
    # lrz from [0, 0, 7.124562786900177e-151]: the start hypothesis drew (level 1e-13, noise
    # [0, 0, 7.124562786900177e-138]) before its draws were held to the normal's; it was
    # refused (its typical size outside [1e-150, 1e150]) where 0 or 1.1e-150 traced
    example, _ = _unperturbed("lrz")
    start = dataclasses.replace(example, u0=np.array([0.0, 0.0, 7.124562786900177e-151]))
    assert check(start, _traced(start, "lrz"), "lrz") == []


def test_the_branch_point_problems_are_those_of_the_issue():
    # issue 26, item 3: "pp2, lrz, log, dd2, gray_scott, brusselator_n4, elastica_n10,
    # rigid_bar, truss_2dof_*, arch_*, transcritical, pitchfork, subcritical_pitchfork,
    # narrow_transcritical, enz"; arch_e3 has its branch points beyond its window (§9 of
    # docs/test-problems.md), arch_p_x1e8 is arch_e6 rescaled (§11)
    named = {"pp2", "lrz", "log", "dd2", "gray_scott", "brusselator_n4", "elastica_n10"}
    named |= {"rigid_bar", "truss_2dof_h2", "truss_2dof_h1.8", "arch_e6", "arch_e4.8"}
    named |= {"transcritical", "pitchfork", "subcritical_pitchfork", "narrow_transcritical"}
    named |= {"enz", "arch_p_x1e8"}
    # and the symmetric branch points of applications (docs/test-problems.md §13)
    named |= {"lorenz_stenflo", "chen", "hopfield", "chafee_infante_n10"}
    named |= {"chafee_infante_n11_sparse", "brusselator_cells", "cstr_pair"}
    assert set(branch_point_problems()) == named


# ---------------------------------------------------------------------------------------------
# Watchdog
# ---------------------------------------------------------------------------------------------

needs_watchdog = pytest.mark.skipif(
    not watchdog_available(), reason="the watchdog needs SIGALRM and the main thread"
)


@needs_watchdog
@pytest.mark.parametrize("name", [name for name, _, _ in SUITE])
def test_returns_in_time(name):
    example = problem(name)
    with watchdog(WATCHDOG_SECONDS, f"the trace of {name}"):
        example.trace()


def _hanging_problem(after: float) -> Problem:
    """x − p = 0 whose residual spins forever from its ``after``-th call (a pure-Python hang
    inside the engine)."""
    calls = [0]

    def residual(u, p):
        calls[0] += 1
        while calls[0] > after:
            pass
        return [u[0] - p["p"]]

    return Problem(residual, ["x"], {"p": 0.0})


@needs_watchdog
@pytest.mark.parametrize("throw", [True, False])
def test_the_watchdog_ends_a_hang_inside_the_engine(throw):
    before = signal.getsignal(signal.SIGALRM)
    begin = time.perf_counter()
    # (5 calls: past the start, inside the steps; the window and the limit are arbitrary)
    with pytest.raises(Hang, match="did not return within 0.2 s"):
        with watchdog(0.2, "the hanging trace"):
            trace(_hanging_problem(after=5), [0.0], free="p", bounds={"p": (-1, 1)}, throw=throw)
    # fired at 0.2 s (the margin: a loaded CI machine), cancelled, the handler restored
    assert 0.2 <= time.perf_counter() - begin < 5.0
    assert signal.getitimer(signal.ITIMER_REAL) == (0.0, 0.0)
    assert signal.getsignal(signal.SIGALRM) is before


@needs_watchdog
def test_the_watchdog_leaves_a_quick_computation_alone():
    with watchdog(WATCHDOG_SECONDS):
        br = trace(_hanging_problem(after=math.inf), [0.0], free="p", bounds={"p": (-1, 1)})
    assert br.success and signal.getitimer(signal.ITIMER_REAL) == (0.0, 0.0)


def test_perturbed_starts_follow_the_rule():
    # (levels, seeds and draws arbitrary) lrz's start is the origin, every component of size
    # 0 at the start and the reference (the origin, ρ = 1): noise rel·1·N(0, 1), the draws of
    # default_rng(seed)
    example = problem("lrz")
    start = perturbed(example, 1e-10, seed=7)
    assert np.array_equal(start.u0, 1e-10 * np.random.default_rng(7).standard_normal(3))
    assert np.array_equal(start.nominal_u0, example.u0) and start.params == example.params
    # a perturbed example is perturbed from its nominal start again
    assert np.array_equal(perturbed(start, 1e-10, seed=7).u0, start.u0)
    # subcritical_pitchfork starts at x = −0.6 (§10), its reference x = 0: m = 0.6
    sub = problem("subcritical_pitchfork")
    assert np.array_equal(perturbed(sub, 1e-6, noise=[2.0]).u0, [-0.6 + 1e-6 * 0.6 * 2.0])
    with pytest.raises(ValueError, match="one per unknown"):
        perturbed(sub, 1e-6, noise=[1.0, 2.0])
