"""Fixtures of the continuation tests, from :mod:`tests.continuation.helpers` (imported only
here): the derivative strategies and their fold-state tolerances, and checks of a branch.

* ``strategy``: each derivative strategy (``helpers.STRATEGIES``) in turn; a test that
  wants only some, or combinations, parametrizes ``strategy`` itself;
* ``state_rtol``: the tolerance on a refined fold's state for that strategy;
* ``special``, ``first_fold_step``, ``branch_residual_norms``,
  ``assert_special_points_consistent``: the functions of the same names;
* ``hopf_l1``: the independent 50-digit Hopf oracle (:mod:`tests.continuation.hopf_oracle`:
  sympy derivatives, mpmath linear algebra, Kuznetsov's formula).
"""

from __future__ import annotations

import pytest

from tests.continuation import helpers, hopf_oracle


@pytest.fixture(params=helpers.STRATEGIES)
def strategy(request) -> str:
    """A derivative strategy: the hand-written Jacobian or a finite-difference fallback."""
    return request.param


@pytest.fixture
def state_rtol(strategy) -> float:
    """The tolerance on a refined fold's state under ``strategy`` (``helpers.STATE_RTOL``)."""
    return helpers.STATE_RTOL[strategy]


@pytest.fixture(scope="session")
def special():
    """``special(br, kind, with_respect_to=None)``: a branch's special points of one kind."""
    return helpers.special


@pytest.fixture(scope="session")
def first_fold_step():
    """``first_fold_step(problem, u0, ...)``: step until a step crosses a fold."""
    return helpers.first_fold_step


@pytest.fixture(scope="session")
def branch_residual_norms():
    """``branch_residual_norms(case, br)``: the example's own residual at every point."""
    return helpers.branch_residual_norms


@pytest.fixture(scope="session")
def assert_special_points_consistent():
    """``assert_special_points_consistent(case, br)``: special points match the columns."""
    return helpers.assert_special_points_consistent


@pytest.fixture(scope="session")
def hopf_l1():
    """``hopf_l1(f, variables, point, ...)``: ω and the first Lyapunov coefficient at a Hopf
    point, by Kuznetsov's formula at 50 digits (:func:`tests.continuation.hopf_oracle.hopf_l1`)."""
    return hopf_oracle.hopf_l1


@pytest.fixture(scope="session")
def same_bits():
    """``same_bits(a, b)``: two results equal bit for bit (arrays, floats, records,
    branches; :func:`tests.continuation.helpers.same_bits`)."""
    return helpers.same_bits
