"""The sympy closed forms of the exponential contact-loss path (``contact_loss_path``) and of
its manifold's events (``manifold_events``), from :mod:`cusp.verification`, evaluated at the
exact binary inputs with λ = σ*(2 − ν)/(2(1 − ν)) as the model forms it in floats. Defaults:
the Fig 6 scene (σ* = 2 µm, ν = 0.3, F_N0 = 1000 N, g_A = 0.34 µm)."""

from __future__ import annotations


def closed_form(key, mu, F_Np, *, sigma=2.0, nu=0.3, F_N0=1000.0, g_A=0.34, event=False):
    """The closed form ``key`` (an event's if ``event``) at μ = ``mu``, F'_N = ``F_Np``."""
    from cusp import verification

    S = verification.SYMBOLS
    syms = (S["sigma"], S["mu"], S["lambda"], S["F_N0"], S["g_A"], S["Fp_N"])
    lam = sigma * (2.0 - nu) / (2.0 * (1.0 - nu))
    forms = verification.manifold_events() if event else verification.contact_loss_path()
    return float(verification.exact_value(forms[key], syms, (sigma, mu, lam, F_N0, g_A, F_Np)))
