"""The sympy closed forms of the exponential contact-loss path and of its manifold's events,
evaluated exactly (:func:`cusp.verification.oracles.exponential_closed_form`, which the
benchmark scripts use too). Defaults: the Fig 6 scene (σ* = 2 µm, ν = 0.3, F_N0 = 1000 N,
g_A = 0.34 µm)."""

from __future__ import annotations

from cusp.verification.oracles import exponential_closed_form as closed_form

__all__ = ["closed_form"]
