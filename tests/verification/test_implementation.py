"""Derived against the float code (cusp.verification.implementation), with stand-in models."""

from __future__ import annotations

import types

import mpmath
import pytest

sp = pytest.importorskip("sympy")

from cusp.verification import check_implementation, exact_value  # noqa: E402
from cusp.verification.common import x  # noqa: E402


def test_exact_value_survives_cancellation():
    # the erf form of P(5/2, x) at x ~ 1e-300 cancels ~450 digits; exact_value adapts
    P = sp.erf(sp.sqrt(x)) - sp.exp(-x) * (4 * x ** sp.Rational(3, 2) + 6 * sp.sqrt(x)) / (
        3 * sp.sqrt(sp.pi)
    )
    val = exact_value(P, (x,), (1e-300,))
    with mpmath.workdps(60):
        ref = mpmath.gammainc(2.5, 0, mpmath.mpf(1e-300), regularized=True)
        assert abs(val - ref) <= abs(ref) * mpmath.mpf(10) ** -28


@pytest.fixture(scope="module")
def good_verdicts(stand_ins):
    return check_implementation(stand_ins.fake_models(stand_ins.GoodRough))


def test_correct_stand_in_implementation_agrees(good_verdicts):
    assert set(good_verdicts) == {
        "9",
        "12 (slip)",
        "12",
        "15",
        "21",
        "22",
        "28",
        "29",
        "30",
        "31",
        "MD",
        "AB",
        "32",
    }
    for eq, verdicts in good_verdicts.items():
        for v in verdicts:
            assert v.agrees, (eq, v.detail)
            assert v.points >= 8


def test_naive_erf_implementation_is_reported(stand_ins):
    verdicts = check_implementation(stand_ins.fake_models(stand_ins.NaiveRough))
    (v12,) = verdicts["12"]
    assert not v12.agrees
    # Fhat_ST -> 0 as Fhat_T -> 1 and the erf form loses the digits there
    assert any(f.startswith("at (0.9999999999999998,)") for f in v12.failures)
    assert all(v.agrees for v in verdicts["15"])


def test_missing_models_are_reported_not_crashed():
    verdicts = check_implementation(types.SimpleNamespace())
    assert list(verdicts) == ["*"]
    assert not verdicts["*"][0].agrees
    assert "not available" in verdicts["*"][0].detail
