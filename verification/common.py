"""Shared by every verification job: the sympy symbols, the records, two sympy helpers.

The symbols are all positive (``xi`` real), so that sympy picks the principal branches the
physics needs; :data:`SYMBOLS` names the ones a user needs to build a printed form.
:class:`Derivation` is one closed form (the paper's formula as read and the expression sympy
derived); :class:`PrintedVerdict` and :class:`ImplementationVerdict` are the two verdicts
(:mod:`cusp.verification.printed`, :mod:`cusp.verification.implementation`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import sympy as sp

# --------------------------------------------------------------------------------------------
# Symbols. All positive: sympy then picks the principal branches the physics needs.
z, d, t = sp.symbols("z d t", positive=True)
sigma = sp.Symbol("sigma", positive=True)  # composite rms roughness sigma*
g_T = sp.Symbol("g_T", positive=True)  # tangential slip
mu = sp.Symbol("mu", positive=True)  # friction coefficient
lam = sp.Symbol("lambda", positive=True)  # lambda = sigma* (2 - nu) / [2 (1 - nu)]
K = sp.Symbol("K", positive=True)  # (4/3) E* sqrt(rho*) n_s A_n
F_N = sp.Symbol("F_N", positive=True)
F_hat = sp.Symbol("Fhat_T", positive=True)  # F_T / (mu F_N), in (0, 1)
x = sp.Symbol("x", positive=True)  # g_T / (mu lambda) = g_N0 / sigma*
w = sp.Symbol("w", positive=True)  # 1 - Fhat_T, in (0, 1)
r, rho = sp.symbols("r rho", positive=True)
a, c = sp.symbols("a c", positive=True)  # contact radius / half-width, stick radius
ca = sp.Symbol("c_over_a", positive=True)  # c / a, in (0, 1)
xi = sp.Symbol("xi", real=True)  # coordinate across the cylinder strip
g_A = sp.Symbol("g_A", positive=True)  # slip at point A
F_N0 = sp.Symbol("F_N0", positive=True)  # normal load on O -> A
F_Np = sp.Symbol("Fp_N", positive=True)  # reduced normal load F'_N

#: name -> symbol, for users building their own printed forms
SYMBOLS: dict[str, sp.Symbol] = {
    s.name: s for s in (sigma, g_T, mu, lam, F_N, F_hat, x, w, ca, g_A, F_N0, F_Np)
}

HALF3 = sp.Rational(3, 2)


# --------------------------------------------------------------------------------------------
# Records


@dataclass(frozen=True)
class Derivation:
    """One closed form: the paper's formula as read, and the expression sympy derived.

    ``variables`` maps each free symbol to its open domain (lo, hi), used for the numeric
    fallback check. ``change_of_variable`` optionally maps a variable to an expression of a
    new positive symbol that is a bijection of the domain (e.g. Fhat_T = 1 - exp(-x)); the
    symbolic check is also attempted after it. ``steps`` says, in words, what was derived.
    """

    equation: str
    title: str
    printed: sp.Expr
    derived: sp.Expr
    variables: tuple[tuple[sp.Symbol, tuple[float, float]], ...]
    steps: tuple[str, ...] = ()
    role: str = "paper"  # "paper" or "alternative reading"
    change_of_variable: tuple[tuple[sp.Symbol, sp.Expr], ...] = ()

    @property
    def expected_agreement(self) -> bool:
        return self.role == "paper"


@dataclass(frozen=True)
class PrintedVerdict:
    equation: str
    agrees: bool
    method: str  # "symbolic" or "numeric, N points at D digits"
    detail: str


@dataclass(frozen=True)
class ImplementationVerdict:
    equation: str
    # e.g. "ExponentialRoughSurface.stick_force_ratio"; None: no counterpart in models/
    implementation: str | None
    agrees: bool
    points: int
    max_rel_error: float
    detail: str
    failures: tuple[str, ...] = field(default=())
    #: max over points of (relative error / tolerance at that point); <= 1 means agreement
    max_error_over_tolerance: float = math.nan


# --------------------------------------------------------------------------------------------
# Helpers


def solve_unique(equation: sp.Expr, unknown: sp.Symbol) -> sp.Expr:
    """The one root of ``equation = 0`` in ``unknown``; an error if sympy finds more or none."""
    roots = sp.solve(equation, unknown)
    if len(roots) != 1:
        raise RuntimeError(f"expected one root for {unknown}, sympy found {roots}")
    return roots[0]


def lambdify_mpmath(expr: sp.Expr, symbols: Sequence[sp.Symbol]) -> Callable:
    """``expr`` as a function of ``symbols`` evaluated by mpmath (at its working precision)."""
    return sp.lambdify(list(symbols), expr, modules="mpmath")
