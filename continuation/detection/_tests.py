"""Test functions: scalar functions on a curve whose sign changes mark its special points.

A test function (:class:`TestFunction`) gives

- ``value(system, z, t, sdet)``: its value at a point ``z`` of the curve with unit tangent
  ``t`` (``sdet``: the sign of det [∂G/∂z; (W t)ᵀ], from the corrector's factorization, or
  None when the curve does not track it);
- ``crossed(old, new)``: whether a change between two accepted points counts (a direction of
  crossing, or leaving through a bound one started on);
- ``locate(bracket, f_a, f_b)``: the zero inside an accepted step (a
  :class:`~._bracket.Located`);
- ``record(system, located, interval)``: the special-point :class:`Record` stored on the
  branch, and, for terminal tests, ``ending(located)``: how the branch ends
  (:class:`Ending`).

The generic ones are defined here: the fold (turning point) of any component, the branch
point, targets and bounds of a component, and user events (:func:`generic_tests`); a fold
curve's cusp and codimension-2 tests are in :mod:`._cusp`. The tracer evaluates the generic
tests of its curve and the ones it is given (:meth:`~..stepping._tracer.Tracer.for_system`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from .._errors import NonFiniteResidualError, ProblemDefinitionError
from .._outcomes import Kind, PointStatus, Status
from ..numerics._arc import HermiteArc, parabola_minimum
from ..numerics._linalg import bordered, factor
from ..problem._events import Event
from ..problem._realvalues import real_scalar
from ..systems._curve import CurveSystem
from ._bracket import Bracket, Located, Span, locate_component
from ._branchpoints import locate_branch_point
from ._folds import locate_fold
from ._regula import locate_on_arc
from ._spectrum import SPECTRUM_MAX_DIM, PartialSign, SignWithSpectrum, eigenvalue_crossings
from ._spectrum import split_points as partial_split_points

if TYPE_CHECKING:
    from .._options import ContinuationOptions


@dataclass(frozen=True, slots=True)
class Record:
    """A special point as a test records it on a branch row (built by keyword), turned into a
    :class:`~..results._branch.SpecialPoint` when the branch is assembled."""

    kind: str
    """What it is: a :class:`~.._outcomes.Kind`, or a test function's own kind."""
    label: str
    with_respect_to: str | None
    status: PointStatus
    interval: tuple[float, float] | None
    details: Mapping[str, Any]


class Ending(NamedTuple):
    """How a terminal test ends the branch: its ``status``, ``message`` and the extra
    ``records`` of its end point."""

    status: Status
    message: str
    records: tuple[Record, ...]


class TestFunction:
    """Base class of the test functions (see the module docstring).

    A subclass sets the class attribute ``kind`` (the special point's kind: a
    :class:`~.._outcomes.Kind`, or a string of one's own) and defines :meth:`value`.

    Parameters
    ----------
    label : str
        The located points' name on the branch.
    with_respect_to : str or None, optional
        The component the test concerns (None: none).
    direction : {0, 1, -1}, optional
        +1 only upward crossings count, −1 only downward, 0 both (default).
    terminal : bool, optional
        Whether the branch ends at the located point.
    """

    __slots__ = ("label", "with_respect_to", "direction", "terminal")
    __test__ = False  # not a pytest test class
    kind: str = "test"
    confirm = True
    """A sign change is confirmed before it is located (a jump to another branch changes the
    sign of tests of the curve's geometry; see :func:`~..stepping._confirm.confirm_step`)."""

    def __init__(
        self,
        label: str,
        with_respect_to: str | None = None,
        direction: int = 0,
        terminal: bool = False,
    ) -> None:
        self.label, self.with_respect_to = label, with_respect_to
        self.direction, self.terminal = direction, terminal

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.label!r}>"

    def value(self, system: CurveSystem, z: np.ndarray, t: Any, sdet: Any) -> float:
        """Evaluate the test at a point of the curve (a subclass defines it).

        Parameters
        ----------
        system : CurveSystem
            The curve system valid at the point.
        z : numpy.ndarray, shape (dim,)
            The curve's components at the point.
        t : numpy.ndarray, shape (dim,), or None
            The unit tangent there (None while locating).
        sdet : object or None
            The sign and log-determinant of the bordered Jacobian there, if computed.

        Returns
        -------
        float
            The test's value; its zeros are the special points.
        """
        raise NotImplementedError  # pragma: no cover - interface

    def crossed(self, old: float | None, new: float) -> bool:
        """Return whether the change ``old → new`` between two accepted points counts.

        Parameters
        ----------
        old : float or None
            The value at the earlier point (None: not known).
        new : float
            The value at the later point.

        Returns
        -------
        bool
            True for a sign change in the test's ``direction``.
        """
        if old is None or old == 0.0:
            return False
        if new == 0.0:
            up = old < 0
        elif (old < 0) == (new < 0):
            return False
        else:
            up = new > 0
        if self.direction == 0:
            return True
        return (self.direction > 0) == up

    def splits_on(self, system: CurveSystem) -> bool:
        """Return whether :meth:`split_points` can see anything on curves of ``system``.

        Parameters
        ----------
        system : CurveSystem
            The curve's system.

        Returns
        -------
        bool
            True when the subclass defines :meth:`split_points`.
        """
        return type(self).split_points is not TestFunction.split_points

    def split_points(self, old: float, new: float, span: Span) -> tuple[float, ...]:
        """Return where to split a step in which the test may have more than one zero.

        Two zeros leave no net sign change, three one; the split points separate them.

        Parameters
        ----------
        old, new : float
            The test's values at the step's ends.
        span : Span
            The step's ends, their unit tangents, its pseudo-arclength and the cosine of its
            turn.

        Returns
        -------
        tuple of float
            θ ∈ (0, 1) between the zeros the test sees a sign of, ascending (empty: none
            seen).
        """
        return ()

    def next_split_point(self, samples: list[tuple[float, float]]) -> float | None:
        """Return another θ to sample in a search for zeros, or None (done).

        Asked after the split points were corrected and none shows the other sign.

        Parameters
        ----------
        samples : list of tuple of (float, float)
            ``(θ, value)`` at the step's ends and at every point sampled, ascending.

        Returns
        -------
        float or None
            θ ∈ (0, 1) to sample next, or None.
        """
        return None

    def locate(self, br: Bracket, f_a: float, f_b: float) -> Located:
        """Locate the zero inside a step.

        Parameters
        ----------
        br : Bracket
            The step (or part of one) holding a sign change.
        f_a, f_b : float
            The test's values at its ends.

        Returns
        -------
        Located
            The located point, its status and the locating method's details.
        """

        def f(z: np.ndarray) -> float:
            return self.value(br.system, z, None, None)

        return locate_on_arc(br, f, f_a, f_b)

    def record(self, system: CurveSystem, loc: Located, interval: tuple[float, float]) -> Record:
        """Return the special-point record of a located zero.

        Parameters
        ----------
        system : CurveSystem
            The curve system at the point.
        loc : Located
            The located zero.
        interval : tuple of (float, float)
            The step's pseudo-arclength interval.

        Returns
        -------
        Record
            The record, made a :class:`~cusp.continuation.SpecialPoint` when the branch is
            assembled.
        """
        details = dict(loc.details)
        details["iterations"] = loc.iterations
        return Record(
            kind=self.kind,
            label=self.label,
            with_respect_to=self.with_respect_to,
            status=loc.status,
            interval=interval,
            details=details,
        )

    def ending(self, loc: Located) -> Ending:
        """Return how the branch ends at the located point of a terminal test.

        Parameters
        ----------
        loc : Located
            The located zero.

        Returns
        -------
        Ending
            The status, message and end-point records.
        """
        end = Record(
            kind=Kind.ENDPOINT,
            label=self.label,
            with_respect_to=self.with_respect_to,
            status=loc.status,
            interval=None,
            details={},
        )
        message = f"terminal event {self.label!r} occurred"
        return Ending(status=Status.TERMINAL_EVENT, message=message, records=(end,))


class ComponentTest(TestFunction):
    """``z_k − value``: a component reaching a value."""

    __slots__ = ("k", "value_at")
    confirm = False  # a component's value, wherever the step went

    def __init__(
        self,
        label: str,
        with_respect_to: str,
        k: int,
        value_at: float,
        direction: int = 0,
        terminal: bool = False,
    ) -> None:
        super().__init__(label, with_respect_to, direction, terminal)
        self.k, self.value_at = k, value_at

    def value(self, system, z, t, sdet) -> float:
        return float(z[self.k]) - self.value_at

    def locate(self, br: Bracket, f_a: float, f_b: float) -> Located:
        found = locate_component(br, self.k, self.value_at)
        if found is not None:
            return found
        return locate_on_arc(br, lambda z: z[self.k] - self.value_at, f_a, f_b)


class TargetTest(ComponentTest):
    """A point located exactly at ``z_k = value`` and inserted into the branch."""

    __slots__ = ()
    kind = Kind.TARGET


class BoundTest(ComponentTest):
    """The end of the branch at ``z_k = value`` (``direction`` −1 a lower bound, +1 an upper
    one); ``pair`` is the bound interval it belongs to, ``(low, high)``."""

    __slots__ = ("pair",)
    kind = Kind.ENDPOINT

    def __init__(
        self, name: str, k: int, value_at: float, direction: int, pair: tuple[float, float]
    ) -> None:
        super().__init__(f"bound {name}={value_at:g}", name, k, value_at, direction, True)
        self.pair = pair

    def violated_by(self, z: np.ndarray) -> bool:
        """Is ``z`` on the wrong side of this bound?"""
        v = z[self.k]
        return v < self.value_at if self.direction < 0 else v > self.value_at

    def crossed(self, old: float | None, new: float) -> bool:
        if old == 0.0:
            # starting exactly on a bound: leaving through it ends the branch at once
            return new < 0 if self.direction < 0 else new > 0
        return super().crossed(old, new)

    def ending(self, loc: Located) -> Ending:
        return Ending(status=Status.BOUND, message=f"the branch reached {self.label}", records=())


class FoldTest(TestFunction):
    """The tangent component ``t_k``: a turning point of component ``k`` (a fold with respect
    to the free parameter, or the snap-back of a monitored unknown)."""

    __slots__ = ("k",)
    kind = Kind.FOLD

    def __init__(self, name: str, k: int) -> None:
        super().__init__(f"fold in {name}", name)
        self.k = k

    def value(self, system, z, t, sdet) -> float:
        return float(t[self.k])

    def split_points(self, old: float, new: float, span: Span) -> tuple[float, ...]:
        """Two turning points of component ``k`` within one step, or a dip of its tangent
        component towards them, seen by the step's arc
        (:meth:`~..numerics._arc.HermiteArc.turning_pair` with ``dip=True``): the vertex of
        its derivative. The arc's derivative is a poor guide to the sign of that dip — on
        two folds 1e-6 apart in the parameter its error is ten times the dip's depth — so
        the point there is corrected and the search goes on from the true values
        (:meth:`next_split_point`)."""
        if (old < 0) != (new < 0):
            return ()
        k = self.k
        cos_b = span.cos_b
        tb = float(span.t_b[k]) / cos_b if cos_b > 0.1 else float(span.t_b[k])
        delta = float(span.z_b[k] - span.z_a[k]) / span.h
        theta = HermiteArc.turning_pair(float(span.t_a[k]), tb, delta, dip=True)
        return () if theta is None else (theta,)

    def next_split_point(self, samples: list[tuple[float, float]]) -> float | None:
        """The minimum of the tangent component's magnitude along the step, searched by
        successive parabolas through the true values
        (:func:`~..numerics._arc.parabola_minimum`) while it may cross zero."""
        sign = -1.0 if samples[0][1] < 0 else 1.0
        return parabola_minimum([(theta, sign * v) for theta, v in samples])

    def locate(self, br: Bracket, f_a: float, f_b: float) -> Located:
        return locate_fold(br, self.k, f_a, f_b)


class BranchPointTest(TestFunction):
    """The sign of det [∂G/∂z; (W t)ᵀ]: it changes at a simple branch point (where a second
    curve crosses) and nowhere else on a regular curve."""

    __slots__ = ()
    kind = Kind.BRANCH_POINT

    def __init__(self) -> None:
        super().__init__("branch point")

    def value(self, system, z, t, sdet) -> float:
        if t is None:
            return sdet
        if not self.splits_on(system):  # (one unknown: a single mode, see SPECTRUM_MAX_DIM)
            if sdet is None:
                sdet = factor(bordered(system.jacobian(z), system.weights * t)).sign_det()
            return sdet
        jac = system.jacobian(z) if system.dim <= SPECTRUM_MAX_DIM else None
        if type(jac) is np.ndarray:  # small and dense: the whole spectrum
            m = bordered(jac, system.weights * t)
            if sdet is None:
                sdet = factor(m).sign_det()
            return SignWithSpectrum(sdet, m)
        lu = getattr(sdet, "lu", None)
        if sdet is None:
            lu = factor(bordered(system.jacobian(z) if jac is None else jac, system.weights * t))
            sdet = lu.sign_det()
        return PartialSign(float(sdet), system, z, t, lu)

    def splits_on(self, system) -> bool:
        return system.dim >= 3  # (see SPECTRUM_MAX_DIM)

    def split_points(self, old: float, new: float, span: Span) -> tuple[float, ...]:
        """Several eigenvalues of the bordered matrix [∂G/∂z; (W t)ᵀ] that change sign within
        one step (:func:`eigenvalue_crossings`; partial spectra: :func:`.spectrum.split_points`,
        which also splits a step its spectra do not account for): θ midway between their
        estimated zeros."""
        if isinstance(old, PartialSign) and isinstance(new, PartialSign):
            return partial_split_points(old, new)
        thetas = eigenvalue_crossings(old, new)
        return tuple(0.5 * (a + b) for a, b in zip(thetas[:-1], thetas[1:]))

    def locate(self, br: Bracket, f_a: float, f_b: float) -> Located:
        return locate_branch_point(br, f_a, f_b)

    def record(self, system: CurveSystem, loc: Located, interval: tuple[float, float]) -> Record:
        found = super().record(system, loc, interval)
        details = dict(found.details)
        details["names"] = tuple(system.names)  # the directions need the same components
        return Record(
            kind=found.kind,
            label=found.label,
            with_respect_to=found.with_respect_to,
            status=found.status,
            interval=found.interval,
            details=details,
        )


class EventTest(TestFunction):
    """A user :class:`~..problem._events.Event`: ``function(u, p)`` of the unknowns and
    parameters."""

    __slots__ = ("event",)
    kind = Kind.EVENT
    confirm = False

    def __init__(self, event: Event) -> None:
        super().__init__(event.label, None, event.direction, event.terminal)
        self.event = event

    def value(self, system, z, t, sdet) -> float:
        u, p = system.split(z)
        try:
            out = self.event.function(u, p)
        except KeyError as exc:
            key = exc.args[0] if exc.args else None
            if isinstance(key, str) and key not in p:
                raise ProblemDefinitionError(
                    f"event {self.label!r} reads {key!r}, which is neither an unknown nor a "
                    f"parameter of the problem; it has {sorted(p)}"
                ) from None
            raise
        val = real_scalar(out, f"event {self.label!r}", p)
        if not math.isfinite(val):
            raise NonFiniteResidualError(
                f"event {self.label!r} returned {val} at {system.values(z)}",
                values=system.values(z),
            )
        return val


# --- building the generic tests of a curve


def generic_tests(
    system: CurveSystem,
    options: ContinuationOptions,
    *,
    fold_components: Sequence[str] = (),
    monitor: Sequence[str] = (),
    targets: Mapping[str, Sequence[float]] | None = None,
    bounds: Mapping[str, Sequence[float]] | None = None,
    events: Sequence[Event] = (),
) -> list[TestFunction]:
    """The tests every curve offers, in the order they are evaluated: folds in
    ``fold_components`` (if ``options.detect_folds``) and in the monitored components,
    branch points (if ``options.detect_branch_points``), targets, bounds, events."""
    tests: list[TestFunction] = []
    if options.detect_folds:
        for name in fold_components:
            tests.append(FoldTest(name, _component(system, name, "free parameter")))
    for name in monitor or ():
        k = _component(system, name, "monitor")
        if name not in fold_components:
            tests.append(FoldTest(name, k))
    if options.detect_branch_points:
        tests.append(BranchPointTest())
    tests.extend(_target_tests(system, targets))
    tests.extend(_bound_tests(system, bounds))
    for ev in events or ():
        if not isinstance(ev, Event):
            raise ProblemDefinitionError(f"events must be Event objects, got {ev!r}")
        tests.append(EventTest(ev))
    return tests


def _component(system: CurveSystem, name: str, what: str) -> int:
    k = system.index(name)
    if k is None:
        raise ProblemDefinitionError(
            f"{what} names {name!r}, which is not traced on this curve; it must be one of "
            f"{list(system.names)} (fixed parameters cannot be bounded or monitored)"
        )
    return k


def _target_tests(system, targets) -> list[TestFunction]:
    tests: list[TestFunction] = []
    for name, values in (targets or {}).items():
        k = _component(system, name, "targets")
        for v in np.atleast_1d(np.asarray(values, dtype=float)):
            if not math.isfinite(v):
                raise ProblemDefinitionError(f"targets[{name!r}] must be finite, got {v}")
            tests.append(TargetTest(f"{name}={v:g}", name, k, float(v)))
    return tests


def _bound_tests(system, bounds) -> list[TestFunction]:
    tests: list[TestFunction] = []
    for name, pair in (bounds or {}).items():
        k = _component(system, name, "bounds")
        try:
            lo, hi = (float(x) for x in pair)
        except (TypeError, ValueError):
            raise ProblemDefinitionError(
                f"bounds[{name!r}] must be a pair (low, high), got {pair!r}"
            ) from None
        if not lo < hi or math.isnan(lo) or math.isnan(hi):
            raise ProblemDefinitionError(
                f"bounds[{name!r}] must satisfy low < high, got ({lo}, {hi})"
            )
        if math.isfinite(lo):
            tests.append(BoundTest(name, k, lo, -1, (lo, hi)))
        if math.isfinite(hi):
            tests.append(BoundTest(name, k, hi, +1, (lo, hi)))
    return tests


__all__ = [
    "Ending",
    "BoundTest",
    "BranchPointTest",
    "ComponentTest",
    "EventTest",
    "FoldTest",
    "Record",
    "TargetTest",
    "TestFunction",
    "generic_tests",
]
