"""The contact-loss path is unaffected by stability (issue 29): its residual is an
equilibrium of forces, not a vector field, so its problems declare no mass matrix, the path
computes no eigenvalues, and asking for stability on one of its legs is refused."""

from __future__ import annotations

import pytest

import cusp.continuation.stepping._trace as trace_module
from cusp.continuation import ProblemDefinitionError, trace
from cusp.models import ExponentialRoughSurface
from cusp.models.contact_loss import ContactLoss

FIG6 = (2.0, 0.3, 0.1, 1000.0, 0.34, 850.0)  # as tests/models/test_contact_loss.py


def test_contact_loss_path_computes_no_eigenvalues(monkeypatch):
    calls = []
    real = trace_module.with_stability
    monkeypatch.setattr(
        trace_module, "with_stability", lambda *a, **k: calls.append(1) or real(*a, **k)
    )
    before = ContactLoss(ExponentialRoughSurface(*FIG6[:3]), *FIG6[3:]).run()
    assert calls == []
    assert before.points["A"] is not None and before.points["B"] is not None


def test_stability_refused_on_a_contact_loss_leg():
    model = ContactLoss(ExponentialRoughSurface(*FIG6[:3]), *FIG6[3:])
    prob, branch, _ = model._loading_leg(model_options())
    assert getattr(prob, "mass", None) is None
    u0 = [branch[name][0] for name in prob.unknowns]
    with pytest.raises(ProblemDefinitionError, match="stability needs a vector field"):
        trace(prob, u0, free=branch.variables[-1], stability=True, max_steps=3)


def model_options():
    from cusp.models.contact_loss import DEFAULT_OPTIONS

    return DEFAULT_OPTIONS
