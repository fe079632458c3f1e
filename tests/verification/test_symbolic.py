"""The sympy derivations (cusp.verification.symbolic) and the verifier's verdicts."""

from __future__ import annotations

import dataclasses
import math
import types

import mpmath
import pytest

sp = pytest.importorskip("sympy")
symbolic = pytest.importorskip("cusp.verification.symbolic")

F = symbolic.F_hat
X = sp.sqrt(-sp.log(1 - F))


@pytest.fixture(scope="module")
def derivations():
    return {rec.equation: rec for rec in symbolic.derive_all()}


def test_import_models_does_not_import_sympy():
    import subprocess
    import sys

    code = "import sys, cusp.models; print('sympy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_every_paper_equation_is_derived(derivations):
    wanted = {"9", "10", "12", "15", "18", "19", "20", "21", "22"}
    wanted |= {"25", "26", "27", "28", "29", "30", "31", "MD", "AB", "32"}
    assert wanted <= set(derivations)


@pytest.mark.parametrize(
    "eq",
    [
        "9",
        "10",
        "12 (x)",
        "12 (slip)",
        "12",
        "15",
        "18",
        "19",
        "20",
        "21",
        "22",
        "25",
        "26",
        "27",
        "28",
        "29",
        "30",
        "31",
        "MD",
        "AB",
        "32",
    ],
)
def test_printed_form_agrees_with_derivation(derivations, eq):
    verdict = symbolic.check_printed(derivations[eq])
    assert verdict.agrees, verdict.detail


@pytest.mark.parametrize("eq", ["12 (reading b)", "12 (reading c)"])
def test_garbled_readings_of_eq12_disagree(derivations, eq):
    verdict = symbolic.check_printed(derivations[eq])
    assert not verdict.agrees
    assert verdict.method.startswith("numeric")


def test_symbolic_verdict_where_sympy_can_simplify(derivations):
    for eq in ("9", "12", "15", "19", "21", "22", "26", "29", "AB"):
        assert symbolic.check_printed(derivations[eq]).method == "symbolic", eq


def test_derived_eq12_is_Fhat_minus_regularized_lower_gamma(derivations):
    # independent reference: mpmath's regularized incomplete gamma, P(5/2, x)
    f = sp.lambdify(F, derivations["12"].derived, "mpmath")
    with mpmath.workdps(40):
        for v in ("0.1", "0.5", "0.9"):
            fh = mpmath.mpf(v)
            x = -mpmath.log(1 - fh)
            ref = fh - mpmath.gammainc(2.5, 0, x, regularized=True)
            assert abs(f(fh) - ref) < mpmath.mpf(10) ** -35


def test_wrong_erf_sign_in_eq12_is_reported(derivations):
    wrong = F - (1 - F) / (3 * sp.sqrt(sp.pi)) * (-4 * X**3 - 6 * X) + sp.erf(X)
    verdict = symbolic.check_printed(dataclasses.replace(derivations["12"], printed=wrong))
    assert not verdict.agrees
    assert "max relative difference" in verdict.detail


def test_wrong_exponent_in_eq21_is_reported(derivations):
    wrong = F - (1 - (1 - F) ** sp.Rational(2, 3)) ** sp.Rational(1, 2)
    verdict = symbolic.check_printed(dataclasses.replace(derivations["21"], printed=wrong))
    assert not verdict.agrees


def test_wrong_cube_root_in_eq19_is_reported(derivations):
    wrong = sp.sqrt(1 - F)
    assert not symbolic.check_printed(dataclasses.replace(derivations["19"], printed=wrong)).agrees


def test_ab_relation_keeps_stick_threshold_invariant(derivations):
    # g'_T - g_A = mu lambda ln(F'_N/F_N0): d0 = d + sigma g_T/(mu lambda) is invariant along AB
    ab = derivations["AB"].derived
    mu, lam = symbolic.mu, symbolic.lam
    sigma = symbolic.sigma
    d_of = lambda load: -sigma * sp.log(load)  # noqa: E731  (d up to a constant, from Eq 11)
    d0_B = d_of(symbolic.F_Np) + sigma * ab / (mu * lam)
    d0_A = d_of(symbolic.F_N0) + sigma * symbolic.g_A / (mu * lam)
    assert sp.simplify(sp.expand_log(d0_B - d0_A, force=True)) == 0


def test_exact_value_survives_cancellation():
    # the erf form of P(5/2, x) at x ~ 1e-300 cancels ~450 digits; exact_value adapts
    x = symbolic.x
    P = sp.erf(sp.sqrt(x)) - sp.exp(-x) * (4 * x ** sp.Rational(3, 2) + 6 * sp.sqrt(x)) / (
        3 * sp.sqrt(sp.pi)
    )
    val = symbolic.exact_value(P, (x,), (1e-300,))
    with mpmath.workdps(60):
        ref = mpmath.gammainc(2.5, 0, mpmath.mpf(1e-300), regularized=True)
        assert abs(val - ref) <= abs(ref) * mpmath.mpf(10) ** -28


# ---- the implementation comparison, driven with stand-in models ---------------------------


def _mp(fn):
    def wrapped(self, *args):
        with mpmath.workdps(1200):
            return float(fn(self, *[mpmath.mpf(a) for a in args]))

    return wrapped


class _GoodRough:
    def __init__(self, sigma, nu, mu):
        self.mu = mpmath.mpf(mu)
        self.sigma = mpmath.mpf(sigma)
        self.lam = mpmath.mpf(sigma) * (2 - mpmath.mpf(nu)) / (2 * (1 - mpmath.mpf(nu)))

    @_mp
    def stick_force_ratio(self, f):
        return f - mpmath.gammainc(2.5, 0, -mpmath.log1p(-f), regularized=True)

    @_mp
    def stick_area_ratio(self, f):
        return (1 - f) * (1 - mpmath.log1p(-f))

    @_mp
    def load_integral(self, h):
        return mpmath.gamma(2.5) * self.sigma**1.5 * mpmath.exp(-h / self.sigma)

    @_mp
    def slip_load_integral(self, h, g):
        j = mpmath.gamma(2.5) * self.sigma**1.5 * mpmath.exp(-h / self.sigma)
        return j * mpmath.gammainc(2.5, 0, g / self.sigma, regularized=True)

    @_mp
    def tangential_force(self, g, fn):
        return self.mu * fn * -mpmath.expm1(-g / (self.mu * self.lam))

    @_mp
    def tangential_slip(self, ft, fn):
        return -self.mu * self.lam * mpmath.log1p(-ft / (self.mu * fn))


class _GoodSphere:
    @_mp
    def stick_force_ratio(self, f):
        return f - (1 - (1 - f) ** (mpmath.mpf(2) / 3)) ** 1.5

    @_mp
    def stick_area_ratio(self, f):
        return (1 - f) ** (mpmath.mpf(2) / 3)


class _GoodCylinder:
    @_mp
    def stick_force_ratio(self, f):
        return 2 / mpmath.pi * (mpmath.sqrt(f * (1 - f)) + mpmath.acos(mpmath.sqrt(f))) + f - 1

    @_mp
    def stick_area_ratio(self, f):
        return mpmath.sqrt(1 - f)


class _GoodFlat:
    @staticmethod
    def stick_force_ratio(f):
        return f if f < 1.0 else 0.0

    @staticmethod
    def stick_area_ratio(f):
        return 1.0 if f < 1.0 else 0.0


class _NaiveRough(_GoodRough):
    """Eq 12 in plain floats with the erf form: cancels catastrophically as Fhat -> 1."""

    def stick_force_ratio(self, f):
        x = -math.log1p(-f)
        P = math.erf(math.sqrt(x)) - math.exp(-x) * (4 * x**1.5 + 6 * math.sqrt(x)) / (
            3 * math.sqrt(math.pi)
        )
        return f - P


def _fake(rough):
    return types.SimpleNamespace(
        ExponentialRoughSurface=rough,
        Sphere=_GoodSphere,
        Cylinder=_GoodCylinder,
        FlatPlane=_GoodFlat,
    )


@pytest.fixture(scope="module")
def good_verdicts():
    return symbolic.check_implementation(_fake(_GoodRough))


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


def test_naive_erf_implementation_is_reported():
    verdicts = symbolic.check_implementation(_fake(_NaiveRough))
    (v12,) = verdicts["12"]
    assert not v12.agrees
    # Fhat_ST -> 0 as Fhat_T -> 1 and the erf form loses the digits there
    assert any(f.startswith("at (0.9999999999999998,)") for f in v12.failures)
    assert all(v.agrees for v in verdicts["15"])


def test_missing_models_are_reported_not_crashed():
    verdicts = symbolic.check_implementation(types.SimpleNamespace())
    assert list(verdicts) == ["*"]
    assert not verdicts["*"][0].agrees
    assert "not available" in verdicts["*"][0].detail
