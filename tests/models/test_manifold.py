"""Loci of the points of the contact-loss path in μ and in F'_N (cusp.models.manifold),
for exponential heights against the sympy closed forms of
:func:`cusp.verification.contact_loss_path` and the closed-form events:

* C boundary, F_A = μF'_N with F_A = μF_N0(1 − exp(−g_A/(λμ))):
  μ_C = g_A / (λ ln(F_N0/ΔF_N)), or at fixed μ, F'_N = F_A/μ;
* F'_T = F_A − μΔF_N = 0: μ_0 = g_A / (λ ln(F_N0/F'_N)), or F'_N = F_N0 − F_A/μ.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from cusp.models import ContactLoss, ExponentialRoughSurface
from cusp.models.manifold import C_G_MAX, point_loci

verification = pytest.importorskip("cusp.verification")

SIGMA, NU, MU, F_N0, G_A, F_NP = 2.0, 0.3, 0.1, 1000.0, 0.34, 850.0  # the Fig 6 scene
LAM = SIGMA * (2.0 - NU) / (2.0 * (1.0 - NU))  # the float λ the model uses


def _model(mu=MU, F_Np=F_NP):
    return ContactLoss(ExponentialRoughSurface(SIGMA, NU, mu), F_N0, G_A, F_Np)


def _closed(key, mu, F_Np):
    S = verification.SYMBOLS
    syms = (S["sigma"], S["mu"], S["lambda"], S["F_N0"], S["g_A"], S["Fp_N"])
    vals = (SIGMA, mu, LAM, F_N0, G_A, F_Np)
    return float(verification.exact_value(CLOSED[key], syms, vals))


CLOSED = verification.contact_loss_path()


def _check_rows(cols, mus, fnps, keys, rtol=1e-10):
    for key, col in keys.items():
        want = np.array([_closed(key, m, f) for m, f in zip(mus, fnps)])
        scale = np.maximum(np.abs(want), 1e-3 * np.max(np.abs(want)))  # F_B → 0 at F'_T = 0
        assert np.all(np.abs(cols[col] - want) <= rtol * scale), (key, cols[col], want)


def test_mu_locus_follows_the_closed_forms_and_locates_its_events():
    loci = point_loci(_model(), "mu", (0.02, 1.0))
    cols = loci.columns
    mu = cols["mu"]
    assert len(mu) > 20 and mu[0] == pytest.approx(0.02, rel=1e-14)
    keys = {"F_A": "F_A", "g_B": "g_B", "F_B": "F_B", "F_D": "F_D", "A_SL_B": "A_SL_B"}
    _check_rows(cols, mu, np.full(mu.size, F_NP), keys)
    events = {e["event"]: e for e in loci.events}
    mu_c = G_A / (LAM * math.log(F_N0 / (F_N0 - F_NP)))
    mu_0 = G_A / (LAM * math.log(F_N0 / F_NP))
    assert events["C boundary"]["mu"] == pytest.approx(mu_c, rel=1e-10)
    assert events["F'_T = 0"]["mu"] == pytest.approx(mu_0, rel=1e-10)
    assert mu[-1] == pytest.approx(mu_0, rel=1e-10)  # the locus ends there


def test_c_locus_follows_the_closed_form_until_c_runs_away():
    loci = point_loci(_model(), "mu", (0.02, 1.0))
    cols, _ = loci.c_locus
    mu = cols["mu"]
    mu_c = G_A / (LAM * math.log(F_N0 / (F_N0 - F_NP)))
    # C exists only above the C boundary; its slip diverges there (exponentially in μ − μ_C),
    # so the locus stops at g_C = C_G_MAX·g_A with μ within rounding of μ_C
    assert mu.min() >= mu_c * (1.0 - 1e-12)
    assert cols["g_C"].max() == pytest.approx(C_G_MAX * G_A, rel=1e-12)
    # rows within 1e-6 of μ_C are left out: there g_C (a log of 1 − F_A/(μF'_N)) is ill-posed
    # in the float μ itself, the closed form as much as the traced value
    away = {k: v[mu > mu_c * (1.0 + 1e-6)] for k, v in cols.items()}
    assert away["mu"].size >= 10
    _check_rows(away, away["mu"], np.full(away["mu"].size, F_NP), {"g_C": "g_C", "F_D": "F_D"})


def test_reduced_load_locus_follows_the_closed_forms():
    # at μ = 0.1, F̂_T(A) = 0.75 > 1/2: the C boundary (F'_N = F_A/μ ≈ 753 N) lies above the
    # deepest reduction (F'_N = F_N0 − F_A/μ ≈ 247 N), so the locus meets both
    loci = point_loci(_model(), "reduced_normal_load", (100.0, 990.0))
    cols = loci.columns
    fnp = cols["reduced_normal_load"]
    assert fnp[-1] == pytest.approx(990.0, rel=1e-14)
    _check_rows(cols, np.full(fnp.size, MU), fnp, {"g_B": "g_B", "F_B": "F_B", "F_D": "F_D"})
    F_A = _closed("F_A", MU, F_NP)
    events = {e["event"]: e for e in loci.events}
    assert events["F'_T = 0"]["reduced_normal_load"] == pytest.approx(F_N0 - F_A / MU, rel=1e-10)
    assert events["C boundary"]["reduced_normal_load"] == pytest.approx(F_A / MU, rel=1e-10)
