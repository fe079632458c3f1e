"""Where the pleat closes (issue 16, point 4), exponential heights (the Fig 6 scene): as
d = ΔF_N/F_N0 → 0 the widths of the pleat vanish like d and the released energies like d²,
with the exponents and leading coefficients of the series of the sympy closed forms, and the
locus of B in F'_N meets the (fixed) point A at a finite angle: the pleat closes in a
corner, not in a cusp (a cusp's width vanishes like d^{3/2}, tangentially).

The measurements are those of ``scripts/pleat_closure.py`` (its functions, at fewer d).
Every expected number comes from the series in d of :func:`cusp.verification.
contact_loss_path`, printed beside it as sympy gives it, from (about 8 s, so not rerun here)::

    import sympy as sp
    from cusp.verification import SYMBOLS as S, contact_loss_path

    P = contact_loss_path()
    d, x_A = sp.symbols("d x_A", positive=True)
    sub = {S["Fp_N"]: S["F_N0"] * (1 - d), S["g_A"]: x_A * S["lambda"] * S["mu"]}

    def series(expr):  # terms up to d**3
        s = sp.series(sp.expand_log(expr.subs(sub), force=True), d, 0, 4).removeO()
        return sp.collect(sp.expand(s), d, sp.factor)
"""

from __future__ import annotations

import math

import numpy as np
import pytest

SIGMA, NU, MU, F_N0, G_A = 2.0, 0.3, 0.1, 1000.0, 0.34  # scenes/fig6.toml
LAM = SIGMA * (2.0 - NU) / (2.0 * (1.0 - NU))  # λ = σ*(2 − ν)/(2(1 − ν)), the model's float
X_A = G_A / (MU * LAM)  # x_A = g_A/(μλ) = 1.4

#: quantity -> (exponent, leading coefficient, next coefficient / leading one)
SERIES = {
    # series(S["g_A"] - P["g_B"])
    #   -> d**3*lambda*mu/3 + d**2*lambda*mu/2 + d*lambda*mu
    "dg": (1, LAM * MU, 0.5),
    # series(P["F_A"] - P["F_B"]) -> F_N0*d*mu  (exact: the Mindlin-Deresiewicz rule)
    "dF": (1, F_N0 * MU, 0.0),
    # series(P["F_A"] - P["F_D"]) -> F_N0*d*mu*(exp(x_A) - 1)*exp(-x_A)  (exact)
    "drop": (1, F_N0 * MU * (1.0 - math.exp(-X_A)), 0.0),
    # series(P["g_C"] - S["g_A"])
    #   -> d**3*lambda*mu*(exp(x_A) - 1)*(exp(2*x_A) + exp(x_A) + 1)/3
    #      + d**2*lambda*mu*(exp(x_A) - 1)*(exp(x_A) + 1)/2 + d*lambda*mu*(exp(x_A) - 1)
    "jump": (1, LAM * MU * (math.exp(X_A) - 1.0), (math.exp(X_A) + 1.0) / 2.0),
    # series(P["snap_back"])
    #   -> F_N0*d**3*lambda*mu**2*(exp(x_A) - 2)*exp(-x_A)/6
    #      + F_N0*d**2*lambda*mu**2*(exp(x_A) - 1)*exp(-x_A)/2
    "ABD": (
        2,
        F_N0 * LAM * MU**2 * (1.0 - math.exp(-X_A)) / 2.0,
        (math.exp(X_A) - 2.0) / (3.0 * (math.exp(X_A) - 1.0)),
    ),
    # series(P["snap_through"])
    #   -> F_N0*d**3*lambda*mu**2*(exp(2*x_A) - 2)/6 + F_N0*d**2*lambda*mu**2*(exp(x_A) - 1)/2
    "ABC": (
        2,
        F_N0 * LAM * MU**2 * (math.exp(X_A) - 1.0) / 2.0,
        (math.exp(2.0 * X_A) - 2.0) / (3.0 * (math.exp(X_A) - 1.0)),
    ),
}
#: one run per decade; below 1e-8 the runs lose digits like ε/d (the script's table)
D_FIT = (1e-4, 1e-5, 1e-6, 1e-7, 1e-8)


@pytest.fixture(scope="module")
def script(load_script):
    """``scripts/pleat_closure.py`` as a module."""
    return load_script("pleat_closure")


@pytest.fixture(scope="module")
def case(script):
    case = script.scene_case("exponential")
    assert case["params"] == {"sigma": SIGMA, "nu": NU, "mu": MU}
    assert (case["F_N0"], case["g_A"]) == (F_N0, G_A)
    return case


@pytest.fixture(scope="module")
def runs(script, case):
    ds, rows = [], []
    for d in D_FIT:
        F_Np = F_N0 * (1.0 - d)
        ds.append((F_N0 - F_Np) / F_N0)
        rows.append(script.measure(case, F_Np))
    return np.array(ds), rows


def test_exponents_are_those_of_the_series(script, runs):
    ds, rows = runs
    for key, (power, _, ratio) in SERIES.items():
        f = script.fit(ds, [r[key] for r in rows])
        # the next term of the series, 1 + ratio·d, tilts the local slopes by less than
        # ratio·d <= 2.6e-4 (d <= 1e-4); the runs' rounding (<= 2e-8 relative) by far less
        assert abs(f["p"] - power) <= ratio * ds.max() + 1e-6, (key, f)
        assert f["first"] == pytest.approx(power, abs=1e-5), (key, f)  # local, at d <= 1e-7
        assert abs(f["p"] - 1.5) > 0.4  # never the cusp's 3/2


def test_leading_coefficients_are_those_of_the_series(runs):
    ds, rows = runs
    i = 2  # d = 1e-6: the next term is ratio·d <= 2.6e-6 relative, the run's error 2.5e-10
    for key, (power, coeff, ratio) in SERIES.items():
        want = coeff * ds[i] ** power * (1.0 + ratio * ds[i])
        assert rows[i][key] == pytest.approx(want, rel=1e-8), key


def test_energies_are_the_areas_of_straight_triangles(runs):
    # the leading coefficients multiply: ABD ~ (1/2)(g_A - g_B)(F_A - F_D), ABC ~
    # (1/2)(g_C - g_B)(F_A - F_D) (SERIES: F_N0 λ μ²(1 − e^{−x_A})/2 = (1/2)·λμ·F_N0 μ(1 − e^{−x_A})
    # and F_N0 λ μ²(e^{x_A} − 1)/2 = (1/2)·λμ e^{x_A}·F_N0 μ(1 − e^{−x_A})): a corner
    ds, rows = runs
    r = rows[2]
    assert r["ABD"] / (0.5 * r["dg"] * r["drop"]) == pytest.approx(1.0, rel=1e-5)
    assert r["ABC"] / (0.5 * (r["dg"] + r["jump"]) * r["drop"]) == pytest.approx(1.0, rel=1e-5)


def test_locus_of_b_crosses_the_point_a_at_a_finite_angle(script, case):
    # the locus in F'_N, traced through F'_N = F_N0, ends with B = D = A; the slopes there
    # (implicit function theorem on the chain of A, B, D) are the first coefficients of
    # SERIES: d(g_A − g_B)/dd = λμ, d(F_A − F_B)/dd = μF_N0, d(F_A − F_D)/dd =
    # μF_N0(1 − e^{−x_A}), all non-zero; A does not move with F'_N
    slopes = script.closure_slopes(case)
    assert slopes["n_B"] == 1.0
    assert slopes["gap"] <= 1e-13 and slopes["residual"] <= 1e-14
    assert slopes["A.g"] == 0.0
    for key in ("dg", "dF", "drop"):
        assert slopes[key] == pytest.approx(SERIES[key][1], rel=1e-14), key
