"""The corrector's float path for scalar problems (`systems._newton._on_floats`, with
`numerics._linalg.PairLU`) against its path on arrays (`_on_arrays`, LAPACK):
the same decisions (converged, iterations, reason) and the same numbers to rounding, on
problems with exact and differenced derivatives, from near and far starts, with and without
the hyperplane's offset, in the chord and rounding-floor regimes; and the fall-back to the
general path wherever the float path cannot decide (non-finite values, a singular matrix,
callbacks that return lists). The oracle is the general path itself, which the rest of the
suite checks against closed forms."""

from __future__ import annotations

import copy
import dataclasses
import math

import numpy as np
import pytest

import cusp.examples as ex
from cusp.continuation import BranchSystem, Problem
from cusp.continuation.detection._folds import fold_newton
from cusp.continuation.numerics._linalg import DenseLU, PairLU
from cusp.continuation.systems._newton import NewtonSettings, _on_arrays, _on_floats, newton


def _settings(tol, step_tol, max_iter, strict=False, contract=False):
    return NewtonSettings(
        tol=tol, step_tol=step_tol, max_iterations=max_iter, strict=strict, contract=contract
    )


def _first_sq(max_first):
    return math.inf if max_first is None else max_first * max_first


def scalar_newton(system, z0, row, c, tol, step_tol, max_iter, g0, strict, contract, max_first):
    """The float path alone (None where it cannot decide)."""
    settings = _settings(tol, step_tol, max_iter, strict, contract)
    return _on_floats(system, z0, row, c, settings, g0, _first_sq(max_first))


def array_newton(system, z0, row, c, tol, step_tol, max_iter, g0, strict, contract, max_first):
    """The array path alone."""
    settings = _settings(tol, step_tol, max_iter, strict, contract)
    return _on_arrays(system, z0, row, c, settings, g0, _first_sq(max_first))


def run_newton(system, z0, row, c, *, tol, step_tol, max_iter, g0=None, strict=False,
               contract=False, max_first=None):  # fmt: skip
    """The corrector (both paths, as it chooses)."""
    settings = _settings(tol, step_tol, max_iter, strict, contract)
    return newton(system, z0, row, c, settings, g0=g0, max_first=max_first)


def _cusp(scale: float = 1.0, derivatives: str = "analytic") -> BranchSystem:
    """x³ − x − b, multiplied by ``scale`` (large terms: the rounding floor decides)."""
    kw = {}
    if derivatives == "analytic":
        kw = {
            "jacobian": lambda u, p: np.array([[scale * (3.0 * u[0] ** 2 - 1.0)]]),
            "param_jacobian": lambda u, p, name: np.array([-scale]),
        }
    else:
        kw = {"derivatives": derivatives}
    problem = Problem(
        lambda u, p: np.array([scale * (u[0] ** 3 - u[0] - p["b"])]), ["x"], {"b": 0.1}, **kw
    )
    return BranchSystem(problem, "b")


CASES = [
    # (system, start z0, row, c, keyword arguments)
    (_cusp(), [1.3, 0.5], [0.6, 0.8], None, {}),
    (_cusp(), [1.3, 0.5], [0.6, 0.8], 1.1, {}),
    (_cusp(), [-0.2, 0.9], [0.0, 1.0], 0.9, {"contract": True}),
    (_cusp(), [2.5, -1.0], [1.0, 0.0], None, {"max_first": 0.05}),  # too far
    (_cusp(), [0.57, 0.38], [1.0, 0.0], None, {"contract": True}),  # near the fold
    (_cusp(1e12), [1.3, 0.5], [0.6, 0.8], None, {}),  # residual floor
    (_cusp(1e12), [1.3, 0.5], [0.6, 0.8], None, {"strict": True}),
    (_cusp(derivatives="central"), [1.3, 0.5], [0.6, 0.8], None, {}),
    (_cusp(derivatives="forward"), [-1.1, 0.2], [0.8, 0.6], None, {"contract": True}),
]


@pytest.mark.parametrize("system, z0, row, c, kw", CASES)
# (tol, step_tol): the defaults; a residual tolerance no residual meets (the chord steps of
# the quadratic regime, then AUTO's test with the rounding floor); a tight update tolerance
@pytest.mark.parametrize("tol, step_tol", [(1e-10, 1e-12), (1e-300, 1e-12), (1e-10, 1e-20)])
def test_float_path_matches_the_array_path(system, z0, row, c, kw, tol, step_tol):
    z0, row = np.array(z0), np.array(row)
    args = dict(tol=tol, step_tol=step_tol, max_iter=10)
    options = dict(g0=None, strict=False, contract=False, max_first=None) | kw
    ours = scalar_newton(system, z0, row, c, *args.values(), *options.values())
    ref = array_newton(system, z0, row, c, *args.values(), *options.values())
    assert ours is not None
    assert (ours.converged, ours.iterations, ours.reason) == (
        ref.converged,
        ref.iterations,
        ref.reason,
    )
    if ref.reason == "too_far":
        return
    np.testing.assert_allclose(ours.z, ref.z, rtol=1e-13, atol=1e-15)
    # residuals near the rounding floor differ by rounding: compared to the size of the
    # terms (the system's Jacobian times the point's magnitude, as the floor itself)
    terms = abs(system.scalar_jacobian(ref.z)[0]) * max(1.0, abs(ref.z[0])) + 1.0
    assert ours.residual_norm == pytest.approx(ref.residual_norm, rel=1e-6, abs=1e-13 * terms)
    assert ours.contraction == pytest.approx(ref.contraction, rel=1e-6, abs=1e-12)
    assert ours.first_update == pytest.approx(ref.first_update, rel=1e-12)
    e = np.array([0.0, 1.0])
    np.testing.assert_allclose(ours.lu.solve(e), ref.lu.solve(e), rtol=1e-12)
    assert ours.lu.sign_det() == ref.lu.sign_det()
    # the dispatcher takes the float path
    assert run_newton(system, z0, row, c, **args, **options).z.tolist() == ours.z.tolist()


def _problem(residual, jacobian) -> BranchSystem:
    return BranchSystem(
        Problem(residual, ["x"], {"b": 0.0}, jacobian=jacobian,
                param_jacobian=lambda u, p, name: np.array([-1.0])),
        "b",
    )  # fmt: skip


def test_what_the_float_path_cannot_decide_goes_to_the_array_path():
    # the row (0, 1) holds b: Newton moves x alone
    row, args = np.array([0.0, 1.0]), (1e-10, 1e-12, 10, None, False, False, None)
    z0 = np.array([0.5, 0.0])
    # a residual that is not finite after the first update
    nan_after = _problem(
        lambda u, p: np.array([math.nan if u[0] < 0.4 else u[0] ** 2 - 0.1]),
        lambda u, p: np.array([[2.0 * u[0]]]),
    )
    assert scalar_newton(nan_after, z0, row, None, *args) is None
    res = run_newton(nan_after, z0, row, None, tol=1e-10, step_tol=1e-12, max_iter=10)
    assert (res.converged, res.reason) == (False, "nonfinite")
    # a singular bordered matrix: ∂G/∂x = 0 with the row holding b
    singular = _problem(lambda u, p: np.array([u[0] - 1.0]), lambda u, p: np.array([[0.0]]))
    assert scalar_newton(singular, z0, row, None, *args) is None
    assert run_newton(singular, z0, row, None, tol=1e-10, step_tol=1e-12, max_iter=10).reason == (
        "singular"
    )
    # callbacks returning lists: the general path converts them
    lists = _problem(lambda u, p: [u[0] ** 2 - 0.25], lambda u, p: [[2.0 * u[0]]])
    assert lists.scalar
    assert scalar_newton(lists, np.array([0.6, 0.0]), row, None, *args) is None
    assert lists.scalar  # (a system never changes)
    # the start of a curve looks at what the functions return: the array path from there on,
    # so that no call is made twice
    assert not lists.checked(np.array([0.6, 0.0])).scalar
    assert nan_after.checked(z0) is nan_after  # (values that are not finite say nothing)
    res = run_newton(lists, np.array([0.6, 0.0]), row, None, tol=1e-10, step_tol=1e-12, max_iter=10)
    assert res.converged and res.z[0] == pytest.approx(0.5, rel=1e-14)


def test_pair_lu_matches_lapack():
    rng = np.random.default_rng(7)
    for _ in range(500):
        a = rng.normal(size=(2, 2)) * 10.0 ** rng.integers(-6, 7, size=(2, 2))
        b = rng.normal(size=2)
        ours, ref = PairLU(*a.ravel().tolist()), DenseLU(a)
        for trans in (False, True):
            np.testing.assert_allclose(ours.solve(b, trans), ref.solve(b, trans), rtol=1e-8)
        assert ours.sign_det() == ref.sign_det() == np.sign(np.linalg.det(a))
        assert ours.log_abs_det() == pytest.approx(ref.log_abs_det(), rel=1e-12, abs=1e-12)


FOLD_CASES = [
    # the cusp x³ − x − b: the fold at x = −1/√3, b = 2/(3√3), exact and differenced
    (ex.cusp_normal_form().problem, [-1.3247], (), (-1 / np.sqrt(3), 2 / (3 * np.sqrt(3))), 1e-12),
    (
        ex.cusp_normal_form(derivatives="central").problem,
        [-1.3247],
        (),
        (-1 / np.sqrt(3), 2 / (3 * np.sqrt(3))),
        1e-10,
    ),
    # the circle x² + b² = 1 from (0.6, −0.8): x turns at (1, 0) (a fold in the unknown)
    (
        Problem(
            lambda u, p: np.array([u[0] ** 2 + p["b"] ** 2 - 1.0]), ["x"], {"b": -0.8},
            jacobian=lambda u, p: np.array([[2.0 * u[0]]]),
            param_jacobian=lambda u, p, name: np.array([2.0 * p["b"]]),
        ),
        [0.6],
        ("x",),
        (1.0, 0.0),
        1e-12,
    ),
]  # fmt: skip


@pytest.mark.parametrize("problem, u0, monitor, exact, tol", FOLD_CASES)
def test_fold_located_in_floats_as_on_arrays(problem, u0, monitor, exact, tol, first_fold_step):
    """A fold located by the float path and by the array path (the same bracket on the
    system with its scalar flag off): the same point, iterations and tangent to rounding,
    and at the exact fold."""
    *_, br, crossing = first_fold_step(problem, u0, monitor=monitor)
    k = crossing.test.k
    assert br.system.scalar
    floats = fold_newton(br, k)
    on_arrays = copy.copy(br.system)
    on_arrays.scalar = False
    arrays = fold_newton(dataclasses.replace(br, system=on_arrays), k)
    assert floats is not None and arrays is not None
    assert floats.status == arrays.status == "converged"
    assert floats.iterations == arrays.iterations
    np.testing.assert_allclose(floats.z, arrays.z, rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(floats.tangent, arrays.tangent, rtol=1e-9, atol=1e-12)
    # the exact fold (with differenced derivatives, to 1e-10)
    np.testing.assert_allclose(floats.z, exact, atol=tol)
