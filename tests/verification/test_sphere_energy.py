"""The sphere's released energies in closed form (cusp.verification.sphere_energy) and their
float evaluation in cusp.models.sphere.SphereLevels.leg_areas."""

from __future__ import annotations

from fractions import Fraction

import mpmath as mp
import pytest

sp = pytest.importorskip("sympy")

from cusp.models import Sphere  # noqa: E402
from cusp.models import sphere as sphere_module  # noqa: E402
from cusp.verification import sphere_energy as se  # noqa: E402

SPHERE = dict(radius=1000.0, E=0.2, nu=0.3, mu=0.1)  # the sphere of test_contact_loss.py


def test_leg_polynomials_are_the_levels_relations():
    # T = (F_N/F_N0) F̂_T and s/κ as SphereLevels evaluates them, at a few (p, q)
    T, G = se.leg_polynomials()
    x, y = sp.symbols("x y", positive=True)
    assert sp.expand(T - (x**3 - y**3)) == 0 and sp.expand(G - (x**2 - y**2)) == 0
    lv = Sphere(**SPHERE).contact_levels(1000.0, 1.0)
    for p, q in ((0.0, 0.3), (0.1, 0.25), (-0.2, 0.9), (1e-9, 3e-9)):
        n = mp.e ** lv.log_normal_load(p)[0]
        at = {x: 1 - mp.mpf(p), y: 1 - mp.mpf(q)}
        t_ref, g_ref = float(T.subs(at)), float(G.subs(at))
        assert float(n * lv.tangential_ratio(p, q)[0]) == pytest.approx(t_ref, rel=1e-14)
        assert lv.slip(p, q)[0] / lv.kappa == pytest.approx(g_ref, rel=1e-14)


def test_closed_forms_equal_the_loop_integrals_symbolically():
    # closed form − ∮ T dG − (the term that vanishes on the path: G_D = G_A, T_C = T_A)
    # expands to the zero polynomial in the levels p_A, q_A, p_B, q_D, q_C
    assert se.identity_residuals() == {"ABD": 0, "DC": 0}


def test_closed_forms_have_positive_coefficients_and_match_the_model():
    tables = se.sphere_released_areas()["tables"]
    runtime = {
        "AB": sphere_module._AREA_AB,
        "BD": sphere_module._AREA_BD,
        "DC": sphere_module._AREA_DC,
    }
    for leg, table in tables.items():
        assert all(c > 0 for c, _ in table), leg  # no cancellation between terms
        mine = sorted((Fraction(num, den), ks) for num, den, ks in runtime[leg])
        assert mine == sorted(table), leg


def _exact_path(f: float) -> tuple[dict, dict]:
    """Float levels of A, B (q_A at slip f·g_lim, p_B at the reduction F_A/(2μ)) and D, C
    solved from them at 50 digits (G_D = G_A, T_C = T_A); the areas there by the loop
    integrals of cusp.verification (no closed form used)."""
    cf = se.sphere_released_areas()
    T, G = se.leg_polynomials()
    x, y = sp.symbols("x y", positive=True)
    t_of, g_of = sp.lambdify((x, y), T, "mpmath"), sp.lambdify((x, y), G, "mpmath")
    with mp.workdps(50):
        q_A = float(1 - mp.sqrt(1 - mp.mpf(f)))  # G_A = f (p_A = 0): g_A = f·g_lim
        p_B = float(1 - mp.cbrt(1 - t_of(1, 1 - mp.mpf(q_A)) / 2))  # n_B = 1 − T_A/2
        x_B = 1 - mp.mpf(p_B)
        G_A, T_A = g_of(1, 1 - mp.mpf(q_A)), t_of(1, 1 - mp.mpf(q_A))
        q_D = 1 - mp.sqrt(x_B**2 - G_A)
        q_C = 1 - mp.cbrt(x_B**3 - T_A)
        levels = {"p_A": 0.0, "q_A": q_A, "p_B": p_B, "q_D": q_D, "q_C": q_C}
        syms = {str(s): s for s in (se.p_A, se.q_A, se.p_B, se.q_D, se.q_C)}
        at = {syms[k]: mp.mpf(v) for k, v in levels.items()}
        ref = {k: sp.N(cf[f"loop {k}"].subs(at), 40) for k in ("ABD", "DC")}
    return levels, ref


@pytest.mark.parametrize("f", [0.3, 1e-2, 1e-5, 1e-8, 1e-9, 1e-12])
def test_leg_areas_match_the_loop_integrals_with_honest_bounds(f):
    # the float closed form at the float levels (D and C rounded to floats) against the
    # loop integrals at the exact levels: within its own error bound, which is below 1e-12
    # relative (the levels' own error taken as 64 ε, as the path's polished points)
    levels, ref = _exact_path(f)
    lv = Sphere(**SPHERE).contact_levels(1000.0, 1.0)
    eps = 2.0**-52
    args = [float(levels[k]) for k in ("p_A", "q_A", "p_B", "q_D", "q_C")]
    (abd, abd_err), (dc, dc_err) = lv.leg_areas(*args, 64.0 * eps)
    abd_ref, dc_ref = float(ref["ABD"]) * lv.kappa, float(ref["DC"]) * lv.kappa
    assert abs(abd - abd_ref) <= abd_err <= 1e-12 * abd_ref
    assert abs(dc - dc_ref) <= dc_err
    assert abs(abd + dc - abd_ref - dc_ref) <= abd_err + dc_err <= 1e-12 * (abd_ref + dc_ref)
