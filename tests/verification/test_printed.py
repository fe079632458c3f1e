"""Printed against derived (cusp.verification.printed): the verdicts and how they are reached."""

from __future__ import annotations

import dataclasses

import pytest

sp = pytest.importorskip("sympy")

from cusp.verification import check_printed  # noqa: E402
from cusp.verification.common import F_hat as F  # noqa: E402

X = sp.sqrt(-sp.log(1 - F))


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
    verdict = check_printed(derivations[eq])
    assert verdict.agrees, verdict.detail


@pytest.mark.parametrize("eq", ["12 (reading b)", "12 (reading c)"])
def test_garbled_readings_of_eq12_disagree(derivations, eq):
    verdict = check_printed(derivations[eq])
    assert not verdict.agrees
    assert verdict.method.startswith("numeric")


def test_symbolic_verdict_where_sympy_can_simplify(derivations):
    for eq in ("9", "12", "15", "19", "21", "22", "26", "29", "AB"):
        assert check_printed(derivations[eq]).method == "symbolic", eq


def test_wrong_erf_sign_in_eq12_is_reported(derivations):
    wrong = F - (1 - F) / (3 * sp.sqrt(sp.pi)) * (-4 * X**3 - 6 * X) + sp.erf(X)
    verdict = check_printed(dataclasses.replace(derivations["12"], printed=wrong))
    assert not verdict.agrees
    assert "max relative difference" in verdict.detail


def test_wrong_exponent_in_eq21_is_reported(derivations):
    wrong = F - (1 - (1 - F) ** sp.Rational(2, 3)) ** sp.Rational(1, 2)
    verdict = check_printed(dataclasses.replace(derivations["21"], printed=wrong))
    assert not verdict.agrees


def test_wrong_cube_root_in_eq19_is_reported(derivations):
    wrong = sp.sqrt(1 - F)
    assert not check_printed(dataclasses.replace(derivations["19"], printed=wrong)).agrees
