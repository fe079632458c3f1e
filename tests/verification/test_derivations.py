"""The sympy derivations (cusp.verification.exponential, .smooth, .catalogue)."""

from __future__ import annotations

import mpmath
import pytest

sp = pytest.importorskip("sympy")

import cusp.verification as verification  # noqa: E402
from cusp.verification.common import F_N0, F_hat, F_Np, g_A, lam, mu, sigma  # noqa: E402


def test_import_models_does_not_import_sympy():
    import subprocess
    import sys

    code = "import sys, cusp.models; print('sympy' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_package_exposes_the_public_api():
    for name in verification.__all__:
        assert hasattr(verification, name), name
    assert verification.derivation("12") in verification.derive_all()
    with pytest.raises(KeyError, match="no derivation"):
        verification.derivation("99")


def test_every_paper_equation_is_derived(derivations):
    wanted = {"9", "10", "12", "15", "18", "19", "20", "21", "22"}
    wanted |= {"25", "26", "27", "28", "29", "30", "31", "MD", "AB", "32"}
    assert wanted <= set(derivations)


def test_derived_eq12_is_Fhat_minus_regularized_lower_gamma(derivations):
    # independent reference: mpmath's regularized incomplete gamma, P(5/2, x)
    f = sp.lambdify(F_hat, derivations["12"].derived, "mpmath")
    with mpmath.workdps(40):
        for v in ("0.1", "0.5", "0.9"):
            fh = mpmath.mpf(v)
            x = -mpmath.log(1 - fh)
            ref = fh - mpmath.gammainc(2.5, 0, x, regularized=True)
            assert abs(f(fh) - ref) < mpmath.mpf(10) ** -35


def test_ab_relation_keeps_stick_threshold_invariant(derivations):
    # g'_T - g_A = mu lambda ln(F'_N/F_N0): d0 = d + sigma g_T/(mu lambda) is invariant along AB
    ab = derivations["AB"].derived
    d_of = lambda load: -sigma * sp.log(load)  # noqa: E731  (d up to a constant, from Eq 11)
    d0_B = d_of(F_Np) + sigma * ab / (mu * lam)
    d0_A = d_of(F_N0) + sigma * g_A / (mu * lam)
    assert sp.simplify(sp.expand_log(d0_B - d0_A, force=True)) == 0
