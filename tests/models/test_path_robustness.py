"""Valid but extreme paths end, with right numbers or a refusal naming the input (issue 27,
point 4): a sphere loaded to within a step of its gross-sliding slip, Gaussian surfaces whose
roughness is far below or far above the other lengths, and reduction ranges that are empty
in floating point."""

from __future__ import annotations

import mpmath as mp
import numpy as np
import pytest

from cusp.models import registry
from cusp.models.contact_loss import DEFAULT_OPTIONS, ContactLoss
from cusp.models.errors import ModelParameterError

_EPS = float(np.finfo(float).eps)
_GAUSS = dict(nu=0.3, mu=0.1, E=0.2, radius=10.0, density=0.01, nominal_area=1e6)


def _sphere():
    return registry.build_body("sphere", radius=1000.0, E=0.2, nu=0.3, mu=0.1)


@pytest.mark.parametrize("rtol", [1e-3, 1e-8])
@pytest.mark.parametrize("share", [1e-3, 1e-5, 1e-8, 1e-12])
def test_sphere_loaded_to_just_below_gross_sliding(share, rtol):
    # max_slip = (1 - share)·g_lim: the loading leg stepped across the gross-sliding fold
    # (g_T is largest at c = 0) and ran on along c < 0 to t = 1e55 (exit 1), or, at rtol
    # 1e-8, wrote A with F_T = 100.0000032 N > μF_N and c < 0
    body = _sphere()
    g_A = (1.0 - share) * float(body.slip_limit(1000.0))
    model = ContactLoss(body, 1000.0, g_A, 850.0)
    res = model.run(DEFAULT_OPTIONS.replace(rtol=rtol))
    A = res.points["A"]
    L = model.levels
    # the stick radius at A in closed form (Mindlin, Eq 2 with Hertz): g_A = μκ(1 - (c/a0)²),
    # at 50 digits from the model's own κ and a0 (their rounding is the input's)
    with mp.workdps(50):
        c_exact = float(L.scale * mp.sqrt(1 - mp.mpf(g_A) / (mp.mpf(0.1) * mp.mpf(L.kappa))))
    assert res.legs["OA"].status == "bound"
    assert 0.0 < A["c"] < A["a"]
    assert A["F_T"] <= 0.1 * A["F_N"]
    # c is as sensitive to rounding as the note says (ε·g_lim/(2(g_lim - g_A))), and the
    # note is there exactly when that exceeds 1e-8
    sensitivity = _EPS / (2.0 * share)
    noted = [m for m in res.messages if "is known only to about" in m]
    assert bool(noted) == (sensitivity > 1e-8)
    assert abs(A["c"] - c_exact) <= max(4.0 * sensitivity, 1e-9) * c_exact
    assert A["g_T"] == g_A


def test_gaussian_roughness_far_below_the_slip():
    # σ* = 1e-6 µm (2 µm given in metres, say) against max_slip = 0.1 µm: every summit in
    # contact (d/σ* = -3.6e5) and A slid through (F̂_T = 1 - J(d0)/J(d) with d0 > 0 by 4.6e5
    # σ*: 1 - e^{-1e11}). The start did not converge (the GW integrals at t << 0 were noisy
    # to 1.5e-12); now the path ends with F_A = μF_N0 and no point C (gross sliding).
    body = registry.build_body("rough-gaussian", sigma=1e-6, **_GAUSS)
    res = ContactLoss(body, 1000.0, 0.1, 850.0).run()
    A, B, D = res.points["A"], res.points["B"], res.points["D"]
    assert A["F_T"] == pytest.approx(100.0, rel=4 * _EPS)
    assert A["A_SL"] == pytest.approx(1.0, rel=4 * _EPS)
    assert res.points["C"] is None and res.gross_sliding["force_control"]
    assert B["F_N"] == pytest.approx(850.0, rel=4 * _EPS)
    assert D["F_T"] == pytest.approx(85.0, rel=1e-12)  # μF'_N: slid through at D as well
    # normal equilibrium at A against mpmath: F_N0 = K σ*^{3/2} F_{3/2}(d/σ*), the GW
    # integral as the defining integral at 40 digits (split at the peak of its integrand)
    with mp.workdps(40):
        t = mp.mpf(A["d"]) / mp.mpf(1e-6)
        peak = -t

        def integrand(s):
            return (s - t) ** mp.mpf(1.5) * mp.npdf(s)

        F32 = mp.quad(integrand, [t, -40, -10, 0, 10, 40]) if t < -40 else mp.nan
        load = mp.mpf(body.load_scale) * mp.mpf(1e-6) ** mp.mpf(1.5) * F32
    assert peak > 1e5
    assert float(abs(load / 1000 - 1)) <= 1e-12


def test_gaussian_at_tiny_slip_against_tiny_roughness_ends_without_noise_folds():
    # the issue's 14-minute hang (σ* = 1e-4 µm, g_A = 5e-6 µm, F'_N = 999.9 N): no summit
    # lies between d and d0, so A_SL is 0 on OA (1 - Â_ST, Eq 32) and constant on BC; sized
    # by its rounding noise it stalled the legs, and its sign changes were reported as 21
    # turning points of A_SL. Now the path ends, with the corners A and B as its only folds.
    body = registry.build_body("rough-gaussian", sigma=1e-4, **_GAUSS)
    res = ContactLoss(body, 1000.0, 5e-6, 999.9).run()
    assert [f["point"] for f in res.folds] == ["A", "A", "B", "B"]
    assert res.points["O"]["A_SL"] == 0.0
    assert abs(res.points["A"]["A_SL"]) <= 4 * _EPS  # 0 to rounding of 1 - Â_ST
    assert res.points["C"]["F_T"] == pytest.approx(res.points["A"]["F_T"], rel=1e-12)
    assert res.points["B"]["F_N"] == pytest.approx(999.9, rel=4 * _EPS)


@pytest.mark.parametrize(
    ("model", "sigma"),
    [("rough-gaussian", 1e50), ("rough-gaussian", 1e200), ("rough-exponential", 1e50)],
)
def test_empty_reduction_range_names_max_slip(model, sigma):
    # F_A/μ below the rounding of F_N0: F_N0 - F_A/μ rounds to F_N0 and the refusal read
    # "allowed: 1000.0 N <= reduced_normal_load < 1000.0 N" (σ* = 1e50); at σ* = 1e200 the
    # Gaussian F_A underflows to 0. The refusal names max_slip and the smallest allowed one.
    extra = _GAUSS if model == "rough-gaussian" else dict(nu=0.3, mu=0.1)
    body = registry.build_body(model, sigma=sigma, **extra)
    with pytest.raises(ModelParameterError, match=r"^max_slip = 0.1 µm is too small") as err:
        ContactLoss(body, 1000.0, 0.1, 850.0)
    text = str(err.value)
    assert "allowed: max_slip >= " in text and f"sigma = {sigma!r}" in text
    g_min = float(text.split("allowed: max_slip >= ")[1].split()[0])
    shallowest = float(np.nextafter(1000.0, 0.0))
    # the bound is the one the path applies: just above it the shallowest reduction runs
    # into no refusal, just below it max_slip is refused again
    ContactLoss(body, 1000.0, g_min * 1.001, shallowest)
    with pytest.raises(ModelParameterError, match="is too small"):
        ContactLoss(body, 1000.0, g_min / 1.001, shallowest)
