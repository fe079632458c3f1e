"""Implementation checks: the derived expressions against the float code in :mod:`cusp.models`.

Each derived expression is evaluated by :func:`exact_value` with mpmath at the exact binary
floats the model receives (precision raised until two evaluations agree to 30 digits) and
compared with the model's float result. Inputs used as given get the fixed relative
tolerance :data:`IMPLEMENTATION_RTOL`; inputs the code must combine in floating point (ratios
such as F_T/(mu F_N)) widen it by 4 eps times their condition number.
:func:`check_implementation` runs every comparison.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import mpmath
import sympy as sp

from .catalogue import derivation
from .common import (
    F_N,
    F_N0,
    F_hat,
    F_Np,
    ImplementationVerdict,
    g_A,
    g_T,
    lam,
    lambdify_mpmath,
    mu,
    sigma,
    solve_unique,
    x,
)

#: F_T-hat points where the implementation is compared (extremes of the open interval)
FT_HAT_EXTREMES: tuple[float, ...] = (
    1e-300,
    1e-100,
    1e-14,
    1e-9,
    1.0 - 1e-9,
    1.0 - 2.0**-40,
    1.0 - 2.0**-52,
)
FT_HAT_INTERIOR: tuple[float, ...] = (0.001, 0.05, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99, 0.999999)

#: relative tolerance of the implementation comparison for exactly-representable inputs
IMPLEMENTATION_RTOL = 1e-13


# --------------------------------------------------------------------------------------------
# Exact evaluation


def exact_value(
    expr: sp.Expr,
    symbols: Sequence[sp.Symbol],
    values: Sequence[float],
    *,
    min_dps: int = 50,
    max_dps: int = 6400,
) -> mpmath.mpf:
    """``expr`` at the exact binary values ``values``, to about 30 correct digits.

    The derived expressions are evaluated as derived (e.g. the erf form of Eq 12), which
    cancels catastrophically at the ends of the interval; the precision is therefore doubled
    until two successive evaluations agree to 1e-30 relative, starting high enough that
    1 - v is exact for every input v.
    """
    f = _compiled(expr, tuple(symbols))
    start = min_dps
    for v in values:
        if v != 0 and math.isfinite(v):
            start = max(start, min_dps + int(abs(math.log10(abs(v)))))
            if v != 1:
                start = max(start, min_dps + int(abs(math.log10(abs(1 - v)))) + 20)
    prev = None
    dps = start
    while dps <= max_dps:
        with mpmath.workdps(dps):
            val = f(*[mpmath.mpf(v) for v in values])
            if isinstance(val, mpmath.mpc):
                if abs(val.imag) > abs(val.real) * mpmath.mpf(10) ** (-dps // 2):
                    raise ArithmeticError(f"complex value {val} at {values}")
                val = val.real
            if prev is not None:
                scale = max(abs(val), abs(prev))
                if scale == 0 or abs(val - prev) <= scale * mpmath.mpf(10) ** -30:
                    return +val
            prev = val
        dps *= 2
    raise ArithmeticError(f"no convergence of {expr} at {values} up to {max_dps} digits")


@functools.lru_cache(maxsize=256)
def _compiled(expr: sp.Expr, symbols: tuple[sp.Symbol, ...]) -> Callable:
    return lambdify_mpmath(expr, symbols)


def _condition(expr, inputs, values, which) -> float:
    """Sum over ``which`` of |v df/dv / f| at ``values``: how much rounding the inputs costs."""
    total = 0.0
    for sym in which:
        dexpr = sp.diff(expr, sym) * sym / expr
        try:
            total += abs(float(exact_value(dexpr, inputs, values, min_dps=30)))
        except (ArithmeticError, ZeroDivisionError):
            return math.inf
    return total


# --------------------------------------------------------------------------------------------
# The comparisons


@dataclass(frozen=True)
class _Check:
    """How one derived expression is compared with one model method."""

    equation: str
    name: str  # "ExponentialRoughSurface.stick_force_ratio"
    expr: sp.Expr  # derived, with model parameters substituted
    inputs: tuple[sp.Symbol, ...]
    points: tuple[tuple[float, ...], ...]
    call: Callable[..., float]
    # symbols whose float value the code must combine with rounding (ratios g_T/(mu lambda),
    # F_T/(mu F_N)); their condition numbers widen the tolerance. Empty: inputs are used as is.
    conditioned: tuple[sp.Symbol, ...] = ()
    n_params: int = 0  # trailing model parameters in each point (not shown in messages)


# the rough surface compared: ExponentialRoughSurface(sigma=2.0, nu=0.3, mu=0.1); the
# parameters enter the exact evaluation as the exact binary floats the float code holds
_SIGMA, _NU, _MU = 2.0, 0.3, 0.1
_nu = sp.Symbol("nu", positive=True)
_LAMBDA_OF_NU = {lam: sigma * (2 - _nu) / (2 * (1 - _nu))}
_PAR_SYMS, _PAR_VALS = (mu, sigma, _nu), (_MU, _SIGMA, _NU)


def _ft_hat_points() -> tuple[tuple[float, ...], ...]:
    return tuple((v,) for v in sorted(FT_HAT_INTERIOR + FT_HAT_EXTREMES))


def _ratio_checks(surf: Any, sphere: Any, cylinder: Any, flat: Any) -> list[_Check]:
    """The stick-force and stick-area ratios of every body, as functions of Fhat_T alone."""
    F = _ft_hat_points()
    F_closed = F + ((1.0,),)  # the flat plane's drop at Fhat_T = 1 is part of Eqs 30-31
    rows = (
        ("12", "ExponentialRoughSurface.stick_force_ratio", surf.stick_force_ratio, F),
        ("15", "ExponentialRoughSurface.stick_area_ratio", surf.stick_area_ratio, F),
        ("21", "Sphere.stick_force_ratio", sphere.stick_force_ratio, F),
        ("22", "Sphere.stick_area_ratio", sphere.stick_area_ratio, F),
        ("28", "Cylinder.stick_force_ratio", cylinder.stick_force_ratio, F),
        ("29", "Cylinder.stick_area_ratio", cylinder.stick_area_ratio, F),
        ("30", "FlatPlane.stick_force_ratio", flat.stick_force_ratio, F_closed),
        ("31", "FlatPlane.stick_area_ratio", flat.stick_area_ratio, F_closed),
    )
    return [
        _Check(eq, name, derivation(eq).derived, (F_hat,), points, call)
        for eq, name, call, points in rows
    ]


def _slip_check(surf: Any) -> _Check:
    """The slip part P(5/2, x) of Eq 12 from the model's slip integral at h = 0."""
    xs = tuple(float(-mpmath.log1p(-mpmath.mpf(v))) for (v,) in _ft_hat_points())
    slip_pts = tuple((float(mpmath.mpf(v) * mpmath.mpf(_SIGMA)), _SIGMA) for v in xs)
    return _Check(
        "12 (slip)",
        "ExponentialRoughSurface.slip_load_integral / load_integral",
        derivation("12 (slip)").derived.subs(x, g_T / sigma),
        (g_T, sigma),
        slip_pts,
        lambda g, _s: float(surf.slip_load_integral(0.0, g)) / float(surf.load_integral(0.0)),
        conditioned=(g_T,),
        n_params=1,
    )


def _loading_checks(surf: Any) -> list[_Check]:
    """Eq 9 and its inverse at F_N = 1000 N, at slips/forces spanning the Fhat_T points."""
    FN_f = 1000.0
    mulam = _MU * _SIGMA * (2 - _NU) / (2 * (1 - _NU))
    F = _ft_hat_points()
    g_pts = tuple(
        (float(-mpmath.log1p(-mpmath.mpf(v)) * mpmath.mpf(mulam)), FN_f) + _PAR_VALS for (v,) in F
    )
    ft_pts = tuple((float(mpmath.mpf(v) * _MU * FN_f), FN_f) + _PAR_VALS for (v,) in F)
    eq9 = derivation("9").derived.subs(_LAMBDA_OF_NU)
    F_T = sp.Symbol("F_T", positive=True)
    g_inv = solve_unique(derivation("9").derived - F_T, g_T).subs(_LAMBDA_OF_NU)
    return [
        _Check(
            "9",
            "ExponentialRoughSurface.tangential_force",
            eq9,
            (g_T, F_N) + _PAR_SYMS,
            g_pts,
            lambda g, fn, *_: surf.tangential_force(g, fn),
            conditioned=(g_T,),
            n_params=3,
        ),
        _Check(
            "9",
            "ExponentialRoughSurface.tangential_slip",
            g_inv,
            (F_T, F_N) + _PAR_SYMS,
            ft_pts,
            lambda ft, fn, *_: surf.tangential_slip(ft, fn),
            conditioned=(F_T,),
            n_params=3,
        ),
    ]


def _contact_loss_checks(surf: Any) -> list[_Check]:
    """Section 4 at the Fig 6 data: F_N0 = 1000 N, g_A = 0.34 um, F'_N from 1000 N down."""
    gA_f, FN0_f = 0.34, 1000.0
    fnp = (999.999, 990.0, 950.0, 900.0, 850.0, 800.0, 750.0, 700.0)
    sec4 = tuple((v, FN0_f, gA_f) + _PAR_VALS for v in fnp)

    def md_call(fnp_, fn0, ga, *_):
        return float(surf.tangential_force(ga, fn0)) - _MU * (fn0 - fnp_)

    def ab_call(fnp_, fn0, ga, *_):
        return surf.tangential_slip(md_call(fnp_, fn0, ga), fnp_)

    def asl_call(fnp_, fn0, ga, *_):
        fhat = md_call(fnp_, fn0, ga) / (_MU * fnp_)
        return 1.0 - float(surf.stick_area_ratio(fhat)) + (fn0 - fnp_) / fn0

    loads = (F_Np, F_N0, g_A)
    ins = loads + _PAR_SYMS
    return [
        _Check(
            eq,
            what,
            derivation(eq).derived.subs(_LAMBDA_OF_NU),
            ins,
            sec4,
            call,
            conditioned=loads,
            n_params=3,
        )
        for eq, what, call in (
            ("MD", "ExponentialRoughSurface.tangential_force - mu dF_N", md_call),
            ("AB", "ExponentialRoughSurface.tangential_slip at (F'_T, F'_N)", ab_call),
            ("32", "1 - ExponentialRoughSurface.stick_area_ratio + dF_N/F_N0", asl_call),
        )
    ]


def _model_checks(models: Any) -> list[_Check]:
    """The comparisons, against ``ExponentialRoughSurface``, ``Sphere``, ``Cylinder`` and
    ``FlatPlane`` of ``models`` (the package :mod:`cusp.models`, or a stand-in)."""
    surf = models.ExponentialRoughSurface(sigma=_SIGMA, nu=_NU, mu=_MU)
    sphere, cylinder, flat = models.Sphere(), models.Cylinder(), models.FlatPlane()
    return [
        *_ratio_checks(surf, sphere, cylinder, flat),
        _slip_check(surf),
        *_loading_checks(surf),
        *_contact_loss_checks(surf),
    ]


# --------------------------------------------------------------------------------------------
# Running them


def _run_check(chk: _Check) -> ImplementationVerdict:
    eps = 2.0**-52
    worst, worst_note, worst_ratio = 0.0, "", 0.0
    failures = []
    for pt in chk.points:
        exact = exact_value(chk.expr, chk.inputs, pt)
        try:
            got = float(chk.call(*pt))
        except Exception as exc:  # the model's own error is the finding
            failures.append(f"at {pt}: raised {type(exc).__name__}: {exc}")
            continue
        tol = IMPLEMENTATION_RTOL
        if chk.conditioned:
            tol += 4 * eps * _condition(chk.expr, chk.inputs, pt, chk.conditioned)
        if exact == 0:
            err = 0.0 if got == 0 else math.inf
        else:
            err = float(abs((mpmath.mpf(got) - exact) / exact))
        worst_ratio = max(worst_ratio, err / tol)
        if err >= worst:
            worst, worst_note = err, f" at {pt[: len(pt) - chk.n_params]} (tolerance {tol:.3g})"
        if not err <= tol:
            failures.append(
                f"at {pt}: got {got!r}, exact {mpmath.nstr(exact, 17)}, "
                f"relative error {err:.3g} > tolerance {tol:.3g}"
            )
    ok = not failures
    rule = f"{IMPLEMENTATION_RTOL:g}" + (" + 4 eps x condition" if chk.conditioned else "")
    detail = f"{len(chk.points)} points, max relative error {worst:.3g}{worst_note}; rule {rule}"
    if failures:
        detail += f"; {len(failures)} failing, first: {failures[0]}"
    return ImplementationVerdict(
        chk.equation, chk.name, ok, len(chk.points), worst, detail, tuple(failures), worst_ratio
    )


def check_implementation(models: Any = None) -> dict[str, list[ImplementationVerdict]]:
    """Compare the derived expressions with the float code; equation id -> verdicts.

    ``models`` is the package (default: :mod:`cusp.models`). If the model classes cannot be
    imported, a single verdict under key ``"*"`` says so.
    """
    if models is None:
        import cusp.models as models_pkg

        models = models_pkg
    try:
        checks = _model_checks(models)
    except (AttributeError, ImportError, TypeError) as exc:
        msg = f"models not available: {type(exc).__name__}: {exc}"
        return {"*": [ImplementationVerdict("*", None, False, 0, math.nan, msg)]}
    out: dict[str, list[ImplementationVerdict]] = {}
    for chk in checks:
        out.setdefault(chk.equation, []).append(_run_check(chk))
    return out
