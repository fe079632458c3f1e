"""Printed against derived: does the paper's formula, as read, equal the derived one?

:func:`check_printed` first tries sympy (``simplify(printed - derived) == 0``, also after
``expand_func``/``expand_log`` and after the derivation's change of variable); where
simplification stalls it evaluates the difference with mpmath at seeded points of the domain
at high precision. The :class:`~cusp.verification.PrintedVerdict` says which method decided.
"""

from __future__ import annotations

import functools
import random
from collections.abc import Sequence

import mpmath
import sympy as sp

from .common import Derivation, PrintedVerdict, lambdify_mpmath


def check_printed(der: Derivation, *, points: int = 40, dps: int = 50) -> PrintedVerdict:
    """Does the printed form equal the derived one?

    First ``simplify(printed - derived) == 0`` (also after expand_func, and after the
    derivation's change of variable); where simplification stalls, the difference is
    evaluated with mpmath at ``points`` points of the domain at ``dps`` digits and must be
    below 10^-(dps-10) relative. The verdict says which method decided.
    """
    if points < 1 or dps < 20:
        raise ValueError(f"need points >= 1 and dps >= 20, got points={points}, dps={dps}")
    return _check_printed(der, points, dps)


@functools.lru_cache(maxsize=128)
def _check_printed(der: Derivation, points: int, dps: int) -> PrintedVerdict:
    diff = der.printed - der.derived
    declared = {sym for sym, _ in der.variables}
    if not diff.free_symbols <= declared:
        extra = ", ".join(sorted(str(sym) for sym in diff.free_symbols - declared))
        raise ValueError(f"Eq {der.equation}: symbols {extra} have no declared domain")
    return _symbolic_verdict(der, diff) or _numeric_verdict(der, points, dps)


# --------------------------------------------------------------------------------------------
# Symbolic


def _is_zero_symbolically(expr: sp.Expr) -> bool:
    for attempt in (
        lambda e: sp.simplify(e),
        lambda e: sp.simplify(sp.expand_func(e)),
        lambda e: sp.simplify(sp.expand_log(sp.expand_func(e), force=True)),
    ):
        if attempt(expr) == 0:
            return True
    return False


def _symbolic_verdict(der: Derivation, diff: sp.Expr) -> PrintedVerdict | None:
    """Agreement proved by sympy, directly or after the change of variable; None: stalled."""
    if _is_zero_symbolically(diff):
        return PrintedVerdict(der.equation, True, "symbolic", "simplify(printed - derived) == 0")
    if der.change_of_variable:
        sub = dict(der.change_of_variable)
        if _is_zero_symbolically(diff.subs(sub)):
            names = ", ".join(f"{k} = {v}" for k, v in der.change_of_variable)
            return PrintedVerdict(
                der.equation, True, "symbolic", f"simplify(printed - derived) == 0 after {names}"
            )
    return None


# --------------------------------------------------------------------------------------------
# Numeric


def _sample_points(
    variables: Sequence[tuple[sp.Symbol, tuple[float, float]]], n: int, seed: int = 5
) -> list[dict[sp.Symbol, mpmath.mpf]]:
    rng = random.Random(seed)
    pts = []
    for _ in range(n):
        pt = {}
        for sym, (lo, hi) in variables:
            # avoid the end points, where the closed forms are singular or 0/0
            u = 0.02 + 0.96 * rng.random()
            pt[sym] = mpmath.mpf(lo) + (mpmath.mpf(hi) - mpmath.mpf(lo)) * mpmath.mpf(u)
        pts.append(pt)
    return pts


def _numeric_verdict(der: Derivation, points: int, dps: int) -> PrintedVerdict:
    """The worst relative difference at ``points`` seeded points, at ``dps`` digits."""
    syms = [sym for sym, _ in der.variables]
    f_p = lambdify_mpmath(der.printed, syms)
    f_d = lambdify_mpmath(der.derived, syms)
    worst = mpmath.mpf(0)
    worst_at = None
    with mpmath.workdps(dps):
        tol = mpmath.mpf(10) ** (-(dps - 10))
        for pt in _sample_points(der.variables, points):
            args = [pt[s] for s in syms]
            vp, vd = f_p(*args), f_d(*args)
            err = abs(vp - vd) / max(abs(vd), mpmath.mpf(1e-30))
            if err > worst or worst_at is None:
                worst, worst_at = err, (args, vp, vd)
        agrees = worst <= tol
    assert worst_at is not None  # points >= 1
    args, vp, vd = worst_at
    where = ", ".join(f"{s}={mpmath.nstr(v, 8)}" for s, v in zip(syms, args, strict=True))
    detail = (
        f"max relative difference {mpmath.nstr(worst, 3)} (tolerance 1e-{dps - 10}); "
        f"worst at {where}: printed {mpmath.nstr(vp, 12)}, derived {mpmath.nstr(vd, 12)}"
    )
    return PrintedVerdict(
        der.equation, bool(agrees), f"numeric, {points} points at {dps} digits", detail
    )
