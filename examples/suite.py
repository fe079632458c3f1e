"""The published-problem suite of the continuation engine, and how a traced branch is judged.

:data:`SUITE` lists the problems (name, factory, keyword arguments): AUTO-07p demos,
chemistry, mechanics, bifurcations in normal form and stress variants of this package; their
references are computed independently of the engine (closed forms, sympy, mpmath at 40
digits; provenance in each example's docstring and in docs/test-problems.md §7–§12).

:func:`check` judges a branch traced from a problem's start: every reference fold and branch
point of its free parameter is found, of the same kind, matched by the variable that turns
(the free parameter, or the monitored unknown of a snap-back) to :data:`PARAM_RTOL` and by
every other variable to :data:`STATE_RTOL` relative to its size; nothing else is reported;
the branch ends normally; and, for the jump risks of :data:`ON_BRANCH`, every point lies on
the branch through the start. The tests (tests/suite) and the step-control measurements
(scripts/tune_guards.py) both use it.

:func:`perturbed` is the suite's perturbed-start mode: a copy of a problem whose start carries
seeded relative noise, judged by :func:`check` exactly as the problem itself (the sizes of
the unperturbed start) and by :func:`compare_ends` against the branch from the unperturbed
start. :func:`watchdog` ends a trace that does not return in time (a hang fails instead of
hanging); :func:`branch_point_problems` names the problems with a reference branch point.

>>> from cusp.examples.suite import check, problem
>>> ex = problem("cusp")
>>> check(ex, ex.trace())
[]
"""

from __future__ import annotations

import signal
import threading
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from cusp.continuation import Branch

from ._base import Example, Reference
from .auto_demos import dd2, logistic_map, pp2
from .bifurcations import (
    imperfect_pitchfork,
    imperfect_transcritical,
    narrow_transcritical,
    subcritical_pitchfork,
)
from .bratu import bratu
from .chemistry import ab_reactor, co_oxidation
from .mechanics import elastica, rigid_bar
from .normal_forms import cusp_normal_form, pitchfork, transcritical
from .patterns import brusselator, gray_scott, lorenz
from .reactors import cstr, enz
from .stress import parallel_s_curves, scaled_ab, scaled_arch, scaled_cusp, scaled_truss
from .structures import shallow_arch
from .symmetric import chafee_infante, chen, hopfield, lorenz_stenflo
from .symmetric_cells import brusselator_cells, cstr_pair
from .trusses import snapback_monitor, truss_2dof, truss_green, truss_rotated

KINDS = ("fold", "branch_point")
PARAM_RTOL = 1e-10
"""Relative tolerance on the variable that turns at a special point (absolute where it is 0)."""
STATE_RTOL = 1e-8
"""Tolerance on every other variable, relative to its size."""

#: (name, factory, keyword arguments): one problem each. A rescaled variant is a problem of
#: its own.
SUITE: list[tuple[str, Callable[..., Example], dict[str, Any]]] = [
    # AUTO-07p demos
    ("pp2", pp2, {}),
    ("ab", ab_reactor, {}),
    ("enz", enz, {}),
    ("lrz", lorenz, {}),
    ("log", logistic_map, {}),
    ("dd2", dd2, {}),
    ("cusp", cusp_normal_form, {}),
    # chemistry and patterns
    ("co_oxidation", co_oxidation, {}),
    ("cstr_arrhenius", cstr, {}),
    ("gray_scott", gray_scott, {}),
    ("brusselator_n4", brusselator, {"n": 4}),
    ("bratu_n10", bratu, {"n": 10}),
    ("bratu_n31_sparse", bratu, {"n": 31, "sparse": True}),
    # mechanics
    ("truss_green", truss_green, {}),
    ("truss_rotated", truss_rotated, {}),
    ("truss_2dof_h2", truss_2dof, {"H": 2.0}),
    ("truss_2dof_h1.8", truss_2dof, {"H": 1.8}),
    ("arch_e6", shallow_arch, {"e": 6.0}),
    ("arch_e4.8", shallow_arch, {"e": 4.8}),
    ("arch_e3", shallow_arch, {"e": 3.0}),
    ("elastica_n10", elastica, {"n": 10}),
    ("rigid_bar", rigid_bar, {}),
    ("rigid_bar_imperfect", rigid_bar, {"theta0": 0.01}),
    ("snapback_monitor", snapback_monitor, {}),
    # bifurcations
    ("transcritical", transcritical, {}),
    ("pitchfork", pitchfork, {}),
    ("subcritical_pitchfork", subcritical_pitchfork, {}),
    ("imperfect_transcritical", imperfect_transcritical, {"eps": 5e-4}),
    ("imperfect_transcritical_passing", imperfect_transcritical, {"eps": -3e-3}),
    ("imperfect_pitchfork", imperfect_pitchfork, {}),
    ("narrow_transcritical", narrow_transcritical, {}),
    # stress: tight pairs, parallel branches, scales
    ("cusp_a1e-4", cusp_normal_form, {"a": 1e-4}),
    ("ab_p3_2.45", ab_reactor, {"p3": 2.45}),
    ("parallel_s_curves", parallel_s_curves, {}),
    ("cusp_b_x1e8", scaled_cusp, {"scale": 1e8}),
    ("truss_v_x1e6", scaled_truss, {"scale": 1e6}),
    ("truss_v_x1e-6", scaled_truss, {"scale": 1e-6}),
    ("ab_u1_x1e6_u2_x1e-6", scaled_ab, {}),
    ("arch_p_x1e8", scaled_arch, {"scale": 1e8}),
    # symmetric branch points of applications (docs/test-problems.md §13)
    ("lorenz_stenflo", lorenz_stenflo, {}),
    ("chen", chen, {}),
    ("hopfield", hopfield, {}),
    ("chafee_infante_n10", chafee_infante, {"n": 10}),
    ("chafee_infante_n11_sparse", chafee_infante, {"n": 11, "sparse": True}),
    ("brusselator_cells", brusselator_cells, {}),
    ("cstr_pair", cstr_pair, {}),
]

#: Jump risks: every traced point must lie on the branch through the start (a description
#: and a predicate on the branch's columns, true at every point).
ON_BRANCH: dict[str, tuple[str, Callable[[Branch], np.ndarray]]] = {
    "imperfect_transcritical": ("x < 0 (the arm of the start)", lambda br: br["x"] < 0),
    "imperfect_transcritical_passing": ("x > 0 (the arm of the start)", lambda br: br["x"] > 0),
    "imperfect_pitchfork": ("x > 0 (the arm of the start)", lambda br: br["x"] > 0),
    "rigid_bar_imperfect": ("theta > 0 (the tilt of the imperfection)", lambda br: br["theta"] > 0),
    "parallel_s_curves": (  # the second curve has x³ − x − b = −δ = −0.02
        "|x³ − x − b| < δ/2 (nearer the first curve than the second)",
        lambda br: np.abs(br["x"] ** 3 - br["x"] - br["b"]) < 0.01,
    ),
}


def problem(name: str) -> Example:
    """The suite's problem called ``name``."""
    for entry, factory, kwargs in SUITE:
        if entry == name:
            return factory(**kwargs)
    raise KeyError(f"no suite problem {name!r}; known: {[n for n, _, _ in SUITE]}")


def expected_points(example: Example) -> list[Reference]:
    """The references a trace of the example's branch must report: folds and branch points
    of its free parameter (not cusps or codimension-2 points of a fold curve)."""
    return [r for r in example.references() if r.kind in KINDS and r.free[0] == example.free]


def _turning(example: Example, kind: str, wrt: str | None) -> str | None:
    """The variable a point is matched by: the one that turns at a fold, the free parameter
    at a branch point."""
    return (wrt or example.free) if kind == "fold" else None


def _sizes(example: Example, refs: list[Reference]) -> dict[str, float]:
    """Each variable's size: its largest magnitude at the start and at the references (the
    unperturbed start of a :class:`Perturbed` example)."""
    start = {**dict(zip(example.unknowns, nominal_start(example))), **example.params}
    return {k: max([abs(float(start[k]))] + [abs(r.values[k]) for r in refs]) for k in start}


def compare(example: Example, br: Branch) -> list[str]:
    """Everything wrong with the branch's folds and branch points, in sentences."""
    refs = expected_points(example)
    sizes = _sizes(example, refs)
    pool = [sp for sp in br.special_points if sp.kind in KINDS]
    wrong = []
    for ref in refs:
        key = _turning(example, ref.kind, ref.with_respect_to)
        var = key or example.free
        same = [
            sp
            for sp in pool
            if sp.kind == ref.kind and _turning(example, sp.kind, sp.with_respect_to) == key
        ]
        label = f"{ref.kind} at {var} = {ref.values[var]!r}"
        if not same:
            wrong.append(f"missing: {label}")
            continue
        sp = min(same, key=lambda s: abs(s.values[var] - ref.values[var]))
        tol = PARAM_RTOL * abs(ref.values[var]) or PARAM_RTOL
        if abs(sp.values[var] - ref.values[var]) > tol:
            wrong.append(f"missing: {label} (nearest reported {sp.values[var]!r})")
            continue
        pool.remove(sp)
        state_size = max(abs(ref.values[k]) for k in example.unknowns) or 1.0
        for k in (*example.unknowns, example.free):
            if k == var:
                continue
            err = abs(sp.values[k] - ref.values[k])
            if err > STATE_RTOL * (sizes[k] or state_size):
                wrong.append(f"{label}: {k} = {sp.values[k]!r}, reference {ref.values[k]!r}")
    for sp in pool:
        var = sp.with_respect_to or example.free
        wrong.append(
            f"unexpected: {sp.kind} ({sp.status}) at {var} = {sp.values[var]!r}, "
            f"point {sp.index} of {len(br)}"
        )
    return wrong


def check(example: Example, br: Branch, name: str | None = None) -> list[str]:
    """Everything wrong with a branch traced from the example's start, in sentences: its
    special points (:func:`compare`), an abnormal end, and (for a problem ``name`` of
    :data:`ON_BRANCH`) the points off the branch through the start."""
    wrong = [] if br.success else [f"ended abnormally: {br.status}: {br.message}"]
    wrong += compare(example, br)
    if name in ON_BRANCH:
        what, on = ON_BRANCH[name]
        off = np.flatnonzero(~on(br))
        if off.size:
            wrong.append(f"left its branch ({what}) at {off.size} of {len(br)} points")
    return wrong


# ---------------------------------------------------------------------------------------------
# Perturbed starts
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Perturbed(Example):
    """A suite example whose start ``u0`` carries relative noise (:func:`perturbed`):
    ``nominal_u0`` is the unperturbed start (its sizes are those :func:`check` judges by),
    ``rel`` the noise level, ``seed`` the seed of the draw (None for noise given directly)."""

    nominal_u0: np.ndarray | None = None
    rel: float = 0.0
    seed: int | None = None


def nominal_start(example: Example) -> np.ndarray:
    """The example's start without noise: ``u0``, or a :class:`Perturbed` one's nominal."""
    if isinstance(example, Perturbed) and example.nominal_u0 is not None:
        return example.nominal_u0
    return example.u0


def perturbed(
    example: Example, rel: float, seed: int | None = 0, *, noise: Sequence[float] | None = None
) -> Perturbed:
    """A copy of ``example`` started from its start with seeded relative noise.

    Component i of the start becomes ``u0_i + rel·m_i·n_i``: ``n_i`` drawn from N(0, 1) by
    ``numpy.random.default_rng(seed)`` (one draw per unknown, in order), or given as
    ``noise``; ``m_i = max(|u0_i|, size_i)``, ``size_i`` the component's size by which
    :func:`check` judges (its largest magnitude at the start and at the references, as in
    :func:`compare`), and 1 where that is 0 — so a component that is exactly 0 gets noise too,
    of size ``rel·m_i`` (elsewhere a draw can round away: at ``rel`` = 1e-14 the noise
    is 45–90 ulps of ``m_i``, and a draw below 0.01 in magnitude less than half of one).
    Everything else (problem, free parameter, bounds, monitored unknowns, references) is the
    example's; a perturbed example is perturbed from its nominal start again. :func:`check`
    judges its branch with the unperturbed start's sizes.

    >>> from cusp.examples.suite import perturbed, problem
    >>> p = perturbed(problem("lrz"), 1e-10, seed=1)
    >>> bool(p.u0.any()), p.nominal_u0.tolist()
    (True, [0.0, 0.0, 0.0])
    """
    u0 = nominal_start(example)
    sizes = _sizes(example, expected_points(example))
    m = np.maximum(np.abs(u0), [sizes[k] or 1.0 for k in example.unknowns])
    if noise is None:
        n = np.random.default_rng(seed).standard_normal(u0.size)
    else:
        n, seed = np.asarray(noise, dtype=float), None
        if n.shape != u0.shape:
            raise ValueError(f"noise must have {u0.size} values, one per unknown, got {n.shape}")
    base = {f.name: getattr(example, f.name) for f in fields(Example)}
    base["u0"] = u0 + rel * m * n
    return Perturbed(**base, nominal_u0=u0.copy(), rel=float(rel), seed=seed)


def compare_ends(example: Example, reference: Branch, br: Branch) -> list[str]:
    """Everything in which ``br`` (traced from a perturbed start of ``example``) ends
    otherwise than ``reference`` (from its unperturbed start), in sentences: a different
    status, or a variable of the last point off by more than :data:`STATE_RTOL` relative to
    its size. The size is :func:`compare`'s (the largest magnitude at the start and the
    references; where that is 0, the state's: the largest of any unknown there, or 1), and
    at least the magnitude at the reference's end."""
    if br.status != reference.status:
        return [f"ends with status {br.status!r}, unperturbed {reference.status!r}: {br.message}"]
    sizes = _sizes(example, expected_points(example))
    state = max([sizes[k] for k in example.unknowns]) or 1.0
    wrong = []
    for k in reference.variables:
        end, ref = float(br[k][-1]), float(reference[k][-1])
        size = max(sizes[k] or state, abs(ref))
        if not abs(end - ref) <= STATE_RTOL * size:
            wrong.append(f"ends at {k} = {end!r}, unperturbed {ref!r}")
    return wrong


def branch_point_problems() -> list[str]:
    """The suite problems with a reference branch point on their branch (computed from the
    references)."""
    return [
        name
        for name, _, _ in SUITE
        if any(r.kind == "branch_point" for r in expected_points(problem(name)))
    ]


# ---------------------------------------------------------------------------------------------
# Watchdog
# ---------------------------------------------------------------------------------------------


class Hang(BaseException):
    """A computation did not return within its :func:`watchdog`'s time. A BaseException,
    like KeyboardInterrupt: no ``except Exception`` of the engine or of a user's callback
    can take it for a failure of its own and go on."""


def watchdog_available() -> bool:
    """Whether :func:`watchdog` can run here: SIGALRM exists (POSIX) and this is the main
    thread (where Python runs signal handlers)."""
    return hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread()


@contextmanager
def watchdog(seconds: float, what: str = "the computation") -> Iterator[None]:
    """Raise :class:`Hang` in the body if it runs longer than ``seconds`` (wall time).

    A one-shot ``ITIMER_REAL`` timer whose SIGALRM handler raises: the engine is pure Python,
    so the handler runs between bytecodes (after the LAPACK call in progress, if any). The
    previous handler is restored and the timer cancelled on the way out; not nestable, and
    only where :func:`watchdog_available` (else RuntimeError)."""
    if not watchdog_available():
        raise RuntimeError("the watchdog needs SIGALRM and the main thread")

    def expire(signum: int, frame: Any) -> None:
        raise Hang(f"{what} did not return within {seconds:g} s")

    previous = signal.signal(signal.SIGALRM, expire)
    try:
        signal.setitimer(signal.ITIMER_REAL, seconds)
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        signal.signal(signal.SIGALRM, previous)


__all__ = [
    "KINDS", "ON_BRANCH", "PARAM_RTOL", "STATE_RTOL", "SUITE", "Hang", "Perturbed",
    "branch_point_problems", "check", "compare", "compare_ends", "expected_points",
    "nominal_start", "perturbed", "problem", "watchdog", "watchdog_available",
]  # fmt: skip
