"""The published-problem suite of the continuation engine.

Every problem of :data:`SUITE` is an example of :mod:`cusp.examples` (AUTO-07p demos,
chemistry, mechanics, bifurcations in normal form and stress variants); its references are
computed independently of the engine (closed forms, sympy, mpmath at 40 digits; provenance in
each example's docstring and in docs/test-problems.md §7–§12). Each problem is traced with
the engine's DEFAULT options — only its start, free parameter, bounds and monitored unknowns
(``example.trace()``) — and:

- every reference special point of kind fold or branch point on that branch is found, of the
  same kind (a fold with respect to the same variable), matched by the value of the variable
  that turns (the free parameter, or the monitored unknown of a snap-back): that value to
  10⁻¹⁰ relative (10⁻¹⁰ absolute when it is 0), every other unknown and parameter to 10⁻⁸
  relative to its size (the largest magnitude it takes at the start and at the references;
  where that is 0, the size of the reference's state);
- no fold or branch point is reported that is not in the references;
- the branch ends normally (``br.success``);
- where a problem is a jump risk (parallel or passing branches), every traced point lies on
  the branch through the start (:data:`ON_BRANCH`).

For problems with a simple branch point, :func:`test_switch_branch` switches branch from the
located point (``trace(problem, sp, free=...)``) and checks that the new branch is the other
one: its points satisfy the other branch's closed form (or leave the first branch, where the
other has none), and its tangent at the start differs from the first branch's.

Cases the current engine fails are marked ``xfail(strict=True)`` with what goes wrong: when
the engine is fixed they turn into errors, and the mark must go. Run with ``-s`` to see the
time of every trace and the total (:func:`test_suite_timing`).
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np
import pytest

import cusp.examples as ex
from cusp.continuation import Branch, MaxStepsWarning, SpecialPoint, trace
from cusp.examples.suite import ON_BRANCH, SUITE, check, expected_points, problem

#: What the current engine gets wrong, per problem (strict: a fixed case fails until its mark
#: is removed).
XFAIL: dict[str, str] = {}

TIMES: dict[str, float] = {}


def _cases(xfail: dict[str, str]) -> list[Any]:
    out = []
    for name, factory, kwargs in SUITE:
        marks = [pytest.mark.xfail(strict=True, reason=xfail[name])] if name in xfail else []
        out.append(pytest.param(name, factory, kwargs, id=name, marks=marks))
    return out


# ---------------------------------------------------------------------------------------------
# The suite
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize(("name", "factory", "kwargs"), _cases(XFAIL))
def test_special_points(name, factory, kwargs):
    example = factory(**kwargs)
    start = time.perf_counter()
    try:
        br = example.trace()
    finally:
        TIMES[name] = time.perf_counter() - start
    wrong = check(example, br, name)
    assert not wrong, "\n".join(wrong)


def test_suite_is_large_and_distinct():
    names = [name for name, _, _ in SUITE]
    assert len(names) >= 30 and len(set(names)) == len(names)
    assert set(XFAIL) <= set(names) and set(ON_BRANCH) <= set(names)
    for name in names:  # every problem has something to find, or a jump to avoid
        assert expected_points(problem(name)) or name in ON_BRANCH, name


# ---------------------------------------------------------------------------------------------
# Branch switching
# ---------------------------------------------------------------------------------------------


class Switch(NamedTuple):
    """Switching from the branch point of a suite problem at ``at`` (the free parameter's
    reference value) with ``bounds``: ``other`` gives residuals of the other branch's closed
    form at every point of the new branch (None where it has none), ``away`` the distance
    from the first branch at every point (its maximum must exceed :data:`AWAY`), ``tangent``
    (optional) the other branch's tangent at the branch point in closed form."""

    at: float
    bounds: dict[str, tuple[float, float]]
    other: Callable[[Branch], list[np.ndarray]] | None
    away: Callable[[Branch], np.ndarray]
    tangent: Callable[[ex.Example], np.ndarray] | None = None


AWAY = 1e-2
ANGLE = math.radians(0.5)  # smallest angle between the two branches' tangents here: 2.9°


def _pp2_coexistence(br):  # u1 = 1/3, u2 = 2 − 3 p1 (1 − e^{−5/3})
    return [br["u1"] - 1 / 3, br["u2"] - (2 - 3 * br["p1"] * (1 - math.exp(-5 / 3)))]


def _arch_asymmetric(e):  # (ξ1 − e)² + 4ξ2² = e² − 16, p = 8e − 6ξ1
    return lambda br: [
        (br["xi1"] - e) ** 2 + 4 * br["xi2"] ** 2 - (e**2 - 16),
        br["p"] - (8 * e - 6 * br["xi1"]),
    ]


def _truss_asymmetric(H):  # u² + y² = H² − 2L², P = 2 EA L² y/l0³ (EA = L = 1)
    return lambda br: [
        br["u"] ** 2 + (H - br["v"]) ** 2 - (H**2 - 2),
        br["P"] - 2 * (H - br["v"]) / (1 + H**2) ** 1.5,
    ]


def _brusselator_mode(k):
    """The null vector of the uniform state's Jacobian for mode k (n = 4): x-part
    sin(kπ i h), y-part −(B − 1 − Dx m)/A² times it, m = λ_k/L² at the branch point; no L
    component (a pitchfork: the reflection i → n + 1 − i maps the mode to minus itself)."""

    def tangent(example):
        c, n = ex.BRUSSELATOR, 4
        h = 1 / (n + 1)
        L = next(L for L, kk in ex.brusselator_branch_points(n) if kk == k)
        m = 4 / h**2 * math.sin(k * math.pi * h / 2) ** 2 / L**2
        s = np.sin(k * math.pi * h * np.arange(1, n + 1))
        return np.concatenate([s, -(c["B"] - 1 - c["Dx"] * m) / c["A"] ** 2 * s, [0.0]])

    return tangent


SWITCHES: dict[str, list[Switch]] = {
    "pp2": [
        Switch(
            0.8219043453739908,
            {"p1": (0.0, 1.0), "u2": (-1.0, 3.0)},
            _pp2_coexistence,
            lambda br: np.abs(br["u2"]),
        ),
        Switch(
            0.6,
            {"p1": (0.0, 1.0)},
            lambda br: [br["u1"], br["u2"]],
            lambda br: np.abs(br["p1"] - 0.6),
        ),
    ],
    "enz": [
        Switch(
            34.22288654419019,
            {"s0": (0.0, 40.0), "s1": (0.6, 6.0)},
            None,
            lambda br: np.abs(br["s1"] - br["s2"]),
        )
    ],
    "lrz": [
        Switch(
            1.0,
            {"rho": (0.0, 30.0)},
            lambda br: [
                br["x"] - br["y"],
                br["z"] - (br["rho"] - 1),
                br["x"] ** 2 - 8 / 3 * br["z"],
            ],
            lambda br: np.abs(br["x"]),
        )
    ],
    "log": [
        Switch(
            1.0,
            {"mu": (0.5, 3.6)},
            lambda br: [br["x"] - (1 - 1 / br["mu"])],
            lambda br: np.abs(br["x"]),
        )
    ],
    "dd2": [
        Switch(
            1.0,
            {"p1": (0.4, 4.0)},
            lambda br: [br["u1"], br["u2"]],
            lambda br: np.abs(1 - 1 / br["p1"]),
        ),
        Switch(
            2.0,
            {"p1": (0.4, 4.0)},
            lambda br: [br["u1"] - 0.5, br["u2"] - (0.5 * br["p1"] - 1) / 0.2],
            lambda br: np.abs(br["u2"]),
        ),
    ],
    "gray_scott": [
        Switch(
            -0.04,
            {"k": (-0.1, 0.1)},
            lambda br: [br["u"] - 1, br["v"]],
            lambda br: np.abs(br["k"] + 0.04),
        )
    ],
    "brusselator_n4": [
        Switch(
            ex.brusselator_branch_points(4)[1][0],  # mode 2, L = 0.1494
            {"L": (0.1, 1.0), "x1": (1.5, 2.5)},
            None,
            lambda br: np.abs(br["x1"] - 2.0),
            _brusselator_mode(2),
        )
    ],
    "elastica_n10": [
        Switch(
            ex.elastica_buckling_loads(10)[0],
            {"P": (0.0, 30.0)},
            None,
            lambda br: np.abs(br["theta10"]),
            lambda example: np.concatenate([np.sin(math.pi / 2 * np.arange(1, 11) / 10), [0.0]]),
        )
    ],
    "rigid_bar": [
        Switch(
            1.0,
            {"theta": (-1.0, 1.4), "P": (-1.0, 1.5)},
            lambda br: [br["P"] - np.cos(br["theta"])],
            lambda br: np.abs(br["theta"]),
        )
    ],
    "truss_2dof_h2": [
        Switch(
            0.2529822128134703,
            {"u": (-1.0, 1.0)},
            _truss_asymmetric(2.0),
            lambda br: np.abs(br["u"]),
        )
    ],
    "truss_2dof_h1.8": [
        Switch(
            ex.truss_2dof_references(1.0, 1.0, 1.8)["bp_P"],
            {"u": (-1.0, 1.0)},
            _truss_asymmetric(1.8),
            lambda br: np.abs(br["u"]),
        )
    ],
    "arch_e6": [
        Switch(
            ex.arch_references(6.0)["bp"][0][1],
            {"xi2": (-1.0, 1.0)},
            _arch_asymmetric(6.0),
            lambda br: np.abs(br["xi2"]),
        )
    ],
    "arch_e4.8": [
        Switch(
            ex.arch_references(4.8)["bp"][0][1],
            {"xi2": (-1.0, 1.0)},
            _arch_asymmetric(4.8),
            lambda br: np.abs(br["xi2"]),
        )
    ],
    "transcritical": [
        Switch(0.0, {"p": (-1.0, 1.0)}, lambda br: [br["x"] - br["p"]], lambda br: np.abs(br["x"]))
    ],
    "pitchfork": [
        Switch(
            0.0,
            {"p": (-1.0, 1.0), "x": (-0.9, 0.9)},
            lambda br: [br["p"] - br["x"] ** 2],
            lambda br: np.abs(br["x"]),
        )
    ],
    "subcritical_pitchfork": [
        Switch(0.0, {"p": (-0.5, 1.0)}, lambda br: [br["x"]], lambda br: np.abs(br["p"]))
    ],
    "narrow_transcritical": [
        Switch(
            0.0,
            {"p": (-1.0, 1.0)},
            lambda br: [br["x"] - 0.05 * br["p"]],
            lambda br: np.abs(br["x"]),
        )
    ],
}

#: Switching cases the current engine fails, by (problem, index in SWITCHES[problem]).
SWITCH_XFAIL: dict[tuple[str, int], str] = {}


def _switch_cases() -> list[Any]:
    out = []
    for name, switches in SWITCHES.items():
        for i, _ in enumerate(switches):
            reason = SWITCH_XFAIL.get((name, i))
            marks = [pytest.mark.xfail(strict=True, reason=reason)] if reason else []
            out.append(pytest.param(name, i, id=f"{name}-{i}", marks=marks))
    return out


def _angle(a: np.ndarray, b: np.ndarray) -> float:
    c = abs(float(a @ b)) / (np.linalg.norm(a) * np.linalg.norm(b))
    return math.acos(min(1.0, c))


@pytest.mark.parametrize(("name", "i"), _switch_cases())
def test_switch_branch(name, i):
    example, sw = problem(name), SWITCHES[name][i]
    br = example.trace()
    located = [
        sp
        for sp in br.special("branch_point")
        if abs(sp.values[example.free] - sw.at) <= 1e-3 * max(1.0, abs(sw.at))
    ]
    # (how accurately it is located is test_special_points' business)
    assert located, f"no branch point near {example.free} = {sw.at} on the first branch"
    sp: SpecialPoint = located[0]
    other = trace(example.problem, sp, free=example.free, bounds=sw.bounds)
    assert other.success, f"{other.status}: {other.message}"
    assert np.max(sw.away(other)) > AWAY, "the new branch does not leave the first one"
    if sw.other is not None:  # beyond the start, which is the first branch's located point
        worst = max(float(np.max(np.abs(r[1:]))) for r in sw.other(other))
        assert worst <= 1e-8, f"the new branch is off the other branch's closed form by {worst}"
    start = other.tangents[0]
    assert _angle(start, np.asarray(sp.tangent)) > ANGLE, "the new branch leaves along the first"
    if sw.tangent is not None:
        expected = sw.tangent(example)
        assert _angle(start, expected) < 1e-6, "the new branch leaves along the wrong direction"


# ---------------------------------------------------------------------------------------------
# Timing
# ---------------------------------------------------------------------------------------------


def test_suite_timing():
    """The time of every suite trace (from :func:`test_special_points` where it ran, traced
    here otherwise) and the total; printed, never asserted (run with ``-s``)."""
    rows = []
    for name, factory, kwargs in SUITE:
        if name not in TIMES:
            example = factory(**kwargs)
            start = time.perf_counter()
            try:
                example.trace(throw=False)
            except Exception:  # a failure is the other tests' business
                pass
            TIMES[name] = time.perf_counter() - start
        rows.append((name, TIMES[name]))
    width = max(len(name) for name, _ in rows)
    print()
    for name, seconds in rows:
        print(f"  {name:<{width}}  {seconds:8.3f} s")
    print(
        f"  {'total (' + str(len(rows)) + ' problems)':<{width}}  {sum(t for _, t in rows):8.3f} s"
    )


# ---------------------------------------------------------------------------------------------
# Switching at the symmetric branch points of applications (§13)
# ---------------------------------------------------------------------------------------------

#: suite name → its pitchforks (point, mode, other branch's closed form where there is one;
#: mpmath at 40 digits, cusp.examples.symmetric and symmetric_cells)
PITCHFORK_CASES: dict[str, Callable[[], tuple]] = {
    "lorenz_stenflo": ex.lorenz_stenflo_pitchforks,
    "chen": ex.chen_pitchforks,
    "hopfield": ex.hopfield_pitchforks,
    "chafee_infante_n10": lambda: ex.chafee_infante_pitchforks(10),
    "chafee_infante_n11_sparse": lambda: ex.chafee_infante_pitchforks(11),
    "brusselator_cells": ex.brusselator_cells_pitchforks,
    "cstr_pair": lambda: ex.cstr_pair_references()[1],
}


def _pitchfork_cases() -> list[Any]:
    return [
        pytest.param(name, i, direction, id=f"{name}-{i}-{'+' if direction > 0 else '-'}")
        for name, pitchforks in PITCHFORK_CASES.items()
        for i, _ in enumerate(pitchforks())
        for direction in (1, -1)
    ]


@pytest.mark.parametrize(("name", "i", "direction"), _pitchfork_cases())
def test_switch_at_symmetric_branch_points(name, i, direction):
    """Each pitchfork located on the symmetric branch is left in both directions along its
    mode (the tangent (mode, 0) to 1e-6 rad: the free parameter is stationary), onto the
    other branch's closed form (to 1e-8, where there is one). The asymmetric branch of the
    two tanks is a closed loop through both of its branch points: 60 steps of it suffice."""
    example = problem(name)
    pf = PITCHFORK_CASES[name]()[i]
    free = example.free
    br = example.trace()
    at = pf.values[free]
    located = [
        sp for sp in br.special("branch_point") if abs(sp.values[free] - at) <= 1e-8 * abs(at)
    ]
    assert len(located) == 1, f"no branch point at {free} = {at} on the symmetric branch"
    with warnings.catch_warnings():  # (the loop's 60 steps end with a MaxStepsWarning)
        warnings.simplefilter("ignore", MaxStepsWarning)
        other = trace(
            example.problem,
            located[0],
            free=free,
            bounds=dict(example.bounds),
            direction=direction,
            max_steps=60,
            throw=False,
        )
    assert other.status in ("bound", "max_steps"), other.message
    mode = np.concatenate([np.asarray(pf.mode, dtype=float), [0.0]])
    assert _angle(other.tangents[0], mode) < 1e-6, "leaves along another direction"
    amplitude = max(float(np.max(np.abs(other[u] - pf.values[u]))) for u in example.unknowns)
    assert amplitude > AWAY, "the new branch does not leave the first one"
    if pf.other is not None:
        worst = max(float(np.max(np.abs(np.asarray(r)[1:]))) for r in pf.other(other))
        assert worst <= 1e-8, f"off the other branch's closed form by {worst}"
