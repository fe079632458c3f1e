"""Helpers of the continuation tests: the derivative strategies a test is parametrised over,
the tolerance on a refined fold's state per strategy, and checks of a branch against an
example's own residual (never the solver's).

The problems and their references are in :mod:`cusp.examples`.
"""

from __future__ import annotations

import numpy as np

#: Derivative strategies a test can be parametrised over: the hand-written Jacobian or one of
#: the solver's finite-difference fallbacks.
STRATEGIES = ("analytic", "central", "forward", "complex")

#: Tolerance on the *state* of a refined fold (its parameter is always compared to 1e-12
#: relative: at a fold the parameter is stationary, so a state error δ perturbs it by O(δ²)).
#: A forward-difference Jacobian is itself only accurate to ~sqrt(eps) ~ 1.5e-8, which moves
#: the zero of det J, hence the fold's state, by about that much.
STATE_RTOL = {"analytic": 1e-9, "complex": 1e-9, "central": 1e-8, "forward": 1e-6}


def branch_residual_norms(case, br):
    """max-norm of the example's own residual at every point of a branch (from br's columns)."""
    u = np.column_stack([np.asarray(br[name], dtype=float) for name in case.unknowns])
    out = np.empty(u.shape[0])
    for i in range(u.shape[0]):
        p = {name: float(br[name][i]) for name in case.params}
        out[i] = np.max(np.abs(case.residual(u[i].copy(), p)))
    return out


def special(br, kind, with_respect_to=None):
    """Special points of one kind (optionally a fold w.r.t. one variable), in branch order."""
    pts = [
        sp
        for sp in br.special_points
        if sp.kind == kind and (with_respect_to is None or sp.with_respect_to == with_respect_to)
    ]
    return sorted(pts, key=lambda sp: sp.index)


def assert_special_points_consistent(case, br):
    """Every special point's values are the branch's columns at its index, bit for bit."""
    n = len(br[case.unknowns[0]])
    for name in [*case.unknowns, *case.params]:
        assert len(br[name]) == n, name
    for sp in br.special_points:
        assert 0 <= sp.index < n, sp
        assert sp.status in ("converged", "guess"), sp
        for name in [*case.unknowns, *case.params]:
            assert br[name][sp.index] == sp.values[name], (sp.kind, sp.label, name)


def first_fold_step(problem, u0, free: str = "b", bounds=(-1.0, 1.0), monitor=()):
    """Step ``problem`` (free parameter ``free`` within ``bounds``, from ``u0``) until a step
    crosses a fold: the tracer, the state before that step, the step (a Trial), its bracket
    and the fold's crossing (a ``Crossing``: the test, its values before and after)."""
    from cusp.continuation import Tracer
    from cusp.continuation.stepping._advance import advance
    from cusp.continuation.stepping._crossings import evaluate, step_bracket
    from cusp.continuation.stepping._work import StepWork

    tracer = Tracer(problem, free=free, bounds={free: bounds}, monitor=monitor)
    state = tracer.init(u0)
    while True:
        trial = advance(tracer._rules, state, StepWork(tracer.options.max_step_solves))
        crossings = evaluate(tracer.tests, tracer._has_bp, state, trial).crossings
        folds = [c for c in crossings if c.test.kind == "fold"]
        if folds:
            br = step_bracket(tracer.options, state.system, state.last, trial)
            return tracer, state, trial, br, folds[0]
        state = tracer.step(state)


def same_bits(a, b, where: str = "") -> None:
    """Assert that ``a`` and ``b`` are the same bit for bit: arrays of one dtype and shape
    with the same bytes, floats with the same bits (``-0.0`` is not ``0.0``; a NaN equals
    itself), containers of the same type holding such values, dataclasses of one type with
    such fields, branches (:class:`~cusp.continuation.Branch`) in every attribute."""
    import dataclasses
    import struct

    from cusp.continuation import Branch

    assert type(a) is type(b), (where, type(a), type(b))
    if isinstance(a, np.ndarray):
        assert (a.dtype, a.shape) == (b.dtype, b.shape), (where, a.dtype, b.dtype)
        assert a.tobytes() == b.tobytes(), where
    elif isinstance(a, float):
        assert struct.pack("<d", a) == struct.pack("<d", b), (where, a, b)
    elif isinstance(a, complex):
        assert struct.pack("<dd", a.real, a.imag) == struct.pack("<dd", b.real, b.imag), where
    elif isinstance(a, np.generic):
        same_bits(np.asarray(a), np.asarray(b), where)
    elif isinstance(a, dict):
        assert list(a) == list(b), (where, list(a), list(b))
        for k in a:
            same_bits(a[k], b[k], f"{where}/{k}")
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b), (where, len(a), len(b))
        for i, (x, y) in enumerate(zip(a, b)):
            same_bits(x, y, f"{where}/{i}")
    elif isinstance(a, Branch):
        for name in ("variables", "s", "tangents", "special_points", "status", "message"):
            same_bits(getattr(a, name), getattr(b, name), f"{where}.{name}")
        same_bits(a.stats, b.stats, f"{where}.stats")
        same_bits(a.info, b.info, f"{where}.info")
        same_bits(a.eigenvalues, b.eigenvalues, f"{where}.eigenvalues")
        same_bits({k: a[k] for k in a.keys()}, {k: b[k] for k in b.keys()}, f"{where}[]")
        assert a.kinds == b.kinds, where
    elif dataclasses.is_dataclass(a):
        for f in dataclasses.fields(a):
            same_bits(getattr(a, f.name), getattr(b, f.name), f"{where}.{f.name}")
    else:
        assert a == b, (where, a, b)
