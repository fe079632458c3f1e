"""Test functions: scalar functions on a curve whose sign changes mark its special points.

A test function is an object with

- ``value(system, z, t, sdet)``: its value at a point ``z`` of the curve with unit tangent
  ``t`` (``sdet``: the sign of det [∂G/∂z; (W t)ᵀ], from the corrector's factorization, or
  None when the curve does not track it);
- ``crossed(old, new)``: whether a change between two accepted points counts (a direction of
  crossing, or leaving through a bound one started on);
- ``locate(bracket, f_a, f_b)``: the zero inside an accepted step (a :class:`~._bracket.Located`);
- ``record(system, located, bracket, weights, interval)``: the special-point record stored on
  the branch, and, for terminal tests, ``ending(located)``: the branch's status, message and
  extra records.

The generic ones are defined here: the fold (turning point) of any component, the branch
point, targets and bounds of a component, and user events. A curve system owns the tests
that belong to it (:meth:`~..systems._curve.CurveSystem.test_functions`): an ordinary branch brings
the fold in its free parameter, a fold curve brings its cusp and codimension-2 tests (in
:mod:`.foldcurve`); the tracer only evaluates whatever tests its system gives it.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from scipy.linalg import lapack

from .._errors import NonFiniteResidualError, ProblemDefinitionError
from ..numerics._linalg import bordered, factor
from ..problem._events import Event
from ..problem._problem import has_exact_jacobian
from ..problem._realvalues import real_scalar
from ..systems._curve import CurveSystem
from ._bracket import (
    Bracket,
    Located,
    hermite_turning_pair,
    locate_component,
    parabola_minimum,
    tangent_at,
)
from ._branchpoints import locate_branch_point
from ._folds import locate_fold
from ._regula import locate_on_arc
from ._spectrum import PartialSign
from ._spectrum import split_points as partial_split_points

if TYPE_CHECKING:
    from .._options import ContinuationOptions


#: a special-point record on a branch row: (kind, label, with_respect_to, status, interval,
#: details), turned into a :class:`~..results._branch.SpecialPoint` when the branch is assembled
Record = tuple[str, str, "str | None", str, "tuple[float, float] | None", dict]


class TestFunction:
    """Base class of the test functions (see the module docstring).

    ``kind``: the special point's kind (``"fold"``, ``"branch_point"``, ...); ``label``: its
    name on the branch; ``wrt``: the component it concerns (or None); ``direction``: +1 only
    upward crossings count, −1 only downward, 0 both; ``terminal``: the branch ends at the
    located point.
    """

    __slots__ = ("label", "wrt", "direction", "terminal")
    __test__ = False  # not a pytest test class
    kind = "test"
    confirm = True
    """A sign change is confirmed before it is located (a jump to another branch changes the
    sign of tests of the curve's geometry; see :func:`~..stepping._confirm.confirm_step`)."""

    def __init__(
        self, label: str, wrt: str | None = None, direction: int = 0, terminal: bool = False
    ) -> None:
        self.label, self.wrt = label, wrt
        self.direction, self.terminal = direction, terminal

    def __repr__(self) -> str:
        return f"<{type(self).__name__} {self.label!r}>"

    def value(self, system: CurveSystem, z: np.ndarray, t: Any, sdet: Any) -> float:
        raise NotImplementedError  # pragma: no cover - interface

    def crossed(self, old: float | None, new: float) -> bool:
        """Does the change ``old → new`` between two accepted points count?"""
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
        """Whether :meth:`split_points` can see anything on curves of ``system``."""
        return type(self).split_points is not TestFunction.split_points

    def split_points(self, old: float, new: float, br_data: tuple[Any, ...]) -> tuple[float, ...]:
        """Where to split a step in which the test may have more than one zero (two, which
        leave no net sign change, or three): θ ∈ (0, 1) between the zeros the test sees a
        sign of, ascending (empty: none seen). ``br_data``: the step's ends, their unit
        tangents, its pseudo-arclength and the cosine of its turn,
        ``(z_a, t_a, z_b, t_b, h, cos_b)``."""
        return ()

    def next_split_point(self, samples: list[tuple[float, float]]) -> float | None:
        """After the split points were corrected and none shows the other sign: another
        θ ∈ (0, 1) to sample in a search for the zeros they suggest, or None (done).
        ``samples``: (θ, value) at the step's ends and at every point sampled, ascending."""
        return None

    def locate(self, br: Bracket, f_a: float, f_b: float) -> Located:
        """The zero inside the step ``br`` (``f_a``, ``f_b``: the values at its ends)."""

        def f(z: np.ndarray) -> float:
            return self.value(br.system, z, None, None)

        return locate_on_arc(br, f, f_a, f_b)

    def record(
        self,
        system: CurveSystem,
        loc: Located,
        br: Bracket | None,
        weights: np.ndarray,
        interval: tuple[float, float],
    ) -> Record:
        """The special-point record of a located zero."""
        details = dict(loc.details)
        details["iterations"] = loc.iterations
        return (self.kind, self.label, self.wrt, loc.status, interval, details)

    def ending(self, loc: Located) -> tuple[str, str, tuple[Record, ...]]:
        """For a terminal test: the branch's status and message, and extra records."""
        return (
            "terminal_event",
            f"terminal event {self.label!r} occurred",
            (("endpoint", self.label, self.wrt, loc.status, None, {}),),
        )


class ComponentTest(TestFunction):
    """``z_k − value``: a component reaching a value."""

    __slots__ = ("k", "value_at")
    confirm = False  # a component's value, wherever the step went

    def __init__(
        self,
        label: str,
        wrt: str,
        k: int,
        value_at: float,
        direction: int = 0,
        terminal: bool = False,
    ) -> None:
        super().__init__(label, wrt, direction, terminal)
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
    kind = "target"


class BoundTest(ComponentTest):
    """The end of the branch at ``z_k = value`` (``direction`` −1 a lower bound, +1 an upper
    one); ``pair`` is the bound interval it belongs to, ``(low, high)``."""

    __slots__ = ("pair",)
    kind = "bound"

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

    def record(self, system, loc, br, weights, interval) -> Record:
        kind, label, wrt, status, interval, details = super().record(
            system, loc, br, weights, interval
        )
        return ("endpoint", label, wrt, status, interval, details)

    def ending(self, loc: Located) -> tuple[str, str, tuple[Record, ...]]:
        return "bound", f"the branch reached {self.label}", ()


class FoldTest(TestFunction):
    """The tangent component ``t_k``: a turning point of component ``k`` (a fold with respect
    to the free parameter, or the snap-back of a monitored unknown)."""

    __slots__ = ("k",)
    kind = "fold"

    def __init__(self, name: str, k: int) -> None:
        super().__init__(f"fold in {name}", name)
        self.k = k

    def value(self, system, z, t, sdet) -> float:
        return float(t[self.k])

    def split_points(self, old, new, br_data) -> tuple[float, ...]:
        """Two turning points of component ``k`` within one step, or a dip of its tangent
        component towards them, seen by the step's cubic Hermite interpolant
        (:func:`~._bracket.hermite_turning_pair` with ``dip=True``): the vertex of its
        derivative. The interpolant's derivative is a poor guide to the sign of that dip —
        on two folds 1e-6 apart in the parameter its error is ten times the dip's depth — so
        the point there is corrected and the search goes on from the true values
        (:meth:`next_split_point`)."""
        if (old < 0) != (new < 0):
            return ()
        z_a, t_a, z_b, t_b, h, cos_b = br_data
        k = self.k
        tb = float(t_b[k]) / cos_b if cos_b > 0.1 else float(t_b[k])
        theta = hermite_turning_pair(float(t_a[k]), tb, float(z_b[k] - z_a[k]) / h, dip=True)
        return () if theta is None else (theta,)

    def next_split_point(self, samples: list[tuple[float, float]]) -> float | None:
        """The minimum of the tangent component's magnitude along the step, searched by
        successive parabolas through the true values (:func:`~._bracket.parabola_minimum`)
        while it may cross zero."""
        sign = -1.0 if samples[0][1] < 0 else 1.0
        return parabola_minimum([(theta, sign * v) for theta, v in samples])

    def locate(self, br: Bracket, f_a: float, f_b: float) -> Located:
        return _check_fold_resolution(self._locate(br, f_a, f_b), br)

    def _locate(self, br: Bracket, f_a: float, f_b: float) -> Located:
        found = locate_fold(br, self.k)
        if found is not None:
            return found

        def tangent_k(z):
            return tangent_at(br.system, z, br.row, br.weights)[self.k]

        # a poor start (a long step, or two folds close together): bracket the fold
        # coarsely by regula falsi and restart Newton from there
        rough = locate_on_arc(br, tangent_k, f_a, f_b, rtol=1e-3)
        start_tangent = tangent_at(br.system, rough.z, br.row, br.weights)
        found = locate_fold(br, self.k, start=rough.z, tangent=start_tangent)
        if found is not None:
            method = "minimally augmented Newton (after regula falsi)"
            return found._replace(details={**found.details, "method": method})
        # Newton failed: regula falsi on the tangent component. The fold system has no
        # regular solution here (a kink, or derivatives too rough to locate it): the point
        # is a bracketed estimate only
        found = locate_on_arc(br, tangent_k, f_a, f_b)
        details = {**found.details, "method": "Illinois on the tangent component (Newton failed)"}
        ends = details.get("test_values", (0.0, 0.0))
        if min(abs(ends[0]), abs(ends[1])) > 1e-6:
            # the tangent component jumps instead of passing through zero
            details["non_smooth"] = True
        return found._replace(status="guess", details=details)


def _check_fold_resolution(found: Located, br: Bracket) -> Located:
    """With finite-difference derivatives, a fold whose radius of curvature is within 100
    difference steps cannot be told from a kink smoothed by the stencil: it is then reported
    as a bracketed guess."""
    problem = getattr(br.system, "problem", None)
    if problem is None or has_exact_jacobian(problem):
        return found
    method = getattr(problem, "derivatives", "central")
    # the difference step, relative to the components' magnitudes; arclength is measured
    # in the same relative terms (the weights are 1/scale²)
    h_fd = np.finfo(float).eps ** (1 / 3 if method == "central" else 1 / 2)
    cos = float(br.t_a @ (br.weights * br.t_b))
    turn = math.acos(max(-1.0, min(1.0, cos)))
    if turn > 0 and abs(br.h) / turn < 100 * h_fd:
        reason = (
            f"radius of curvature {abs(br.h) / turn:.2g} is within 100 finite-difference "
            f"steps ({h_fd:.2g}): possibly a kink; supply a jacobian to decide"
        )
        details = {**found.details, "non_smooth": True, "reason": reason}
        return found._replace(status="guess", details=details)
    return found


_geev = lapack.dgeev

SPECTRUM_MAX_DIM = 50
"""Dense curve systems of 3 to this many components carry the whole spectrum of the
branch-point test's matrix at every point (one LAPACK eigendecomposition a step), which shows
two or more branch points of different modes inside one step. Larger or sparse ones carry a
partial spectrum, its few eigenvalues nearest zero computed only when a step asks for them
(:mod:`.spectrum`). Curves with one unknown (2 components) carry none: their matrix holds one
row of the Jacobian, one mode, and two branch points in one step are one eigenvalue crossing
zero and back, which the spectra at the step's ends cannot show either."""


class SignWithSpectrum(float):
    """The branch-point test's value (the sign of det M, M = [∂G/∂z; (W t)ᵀ]) that also
    carries M's spectrum from LAPACK's dgeev: ``spectrum`` = (real parts, imaginary parts,
    unit real eigenvectors; a complex pair j, j + 1 has the vectors Re v, Im v), or None."""

    spectrum: tuple[list[float], list[float], np.ndarray] | None

    def __new__(cls, sign: float, m: np.ndarray) -> SignWithSpectrum:
        self = super().__new__(cls, sign)
        if not np.all(np.isfinite(m)):  # LAPACK's xerbla would print to stdout
            self.spectrum = None
            return self
        wr, wi, _, vr, info = _geev(m, compute_vl=0, compute_vr=1)
        if info != 0 or not np.all(np.isfinite(vr)):
            self.spectrum = None
        else:
            norms = np.sqrt(np.einsum("ij,ij->j", vr, vr))
            self.spectrum = (wr.tolist(), wi.tolist(), vr / np.where(norms > 0, norms, 1.0))
        return self


def eigenvalue_crossings(old: Any, new: Any) -> list[float]:
    """Where eigenvalues of the branch-point matrix change sign between two points (values
    :class:`SignWithSpectrum`), as estimates θ ∈ (0, 1), ascending; empty when either point
    carries no spectrum.

    Each eigenvector at the first point is matched to the one at the second most parallel
    to it (greedily, best match first); matched eigenvalues and complex-conjugate pairs form
    groups (a complex pair may turn into two real eigenvalues inside the step and one of
    them cross zero). A group whose product of eigenvalues changes sign holds a crossing,
    estimated where the linear interpolant of that product vanishes, θ = P_a/(P_a − P_b).

    Two modes crossing zero in opposite directions within one step leave the determinant's
    sign (and the count of negative eigenvalues) unchanged: only following each eigenvalue
    shows them (a Turing window of the Brusselator, where one mode destabilises as another
    restabilises)."""
    sa, sb = getattr(old, "spectrum", None), getattr(new, "spectrum", None)
    if sa is None or sb is None or len(sa[0]) != len(sb[0]):
        return []
    n = len(sa[0])
    parent = list(range(2 * n))  # union-find: eigenvalue i of a is i, j of b is n + j

    def root(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    flat = np.argsort(-np.abs(sa[2].T @ sb[2]), axis=None).tolist()
    free_a, free_b = [True] * n, [True] * n
    for f in flat:
        i, j = divmod(f, n)
        if free_a[i] and free_b[j]:
            free_a[i] = free_b[j] = False
            parent[root(i)] = root(n + j)
    # products of each group at each end: a complex pair contributes |λ|² (> 0) once
    factors = []
    for offset, (wr, wi, _) in ((0, sa), (n, sb)):
        for i in range(n):
            if wi[i] > 0.0:  # the first of a pair (LAPACK: positive imaginary part first)
                parent[root(offset + i + 1)] = root(offset + i)
                factors.append((offset + i, wr[i] * wr[i] + wi[i] * wi[i]))
            elif wi[i] == 0.0:
                factors.append((offset + i, wr[i]))
    products: dict[int, list[float]] = {}
    for k, value in factors:
        pair = products.setdefault(root(k), [1.0, 1.0])
        pair[k >= n] *= value
    out = []
    for a, b in products.values():
        if a != 0.0 and b != 0.0 and (a < 0) != (b < 0):
            out.append(a / (a - b))
    return sorted(out)


class BranchPointTest(TestFunction):
    """The sign of det [∂G/∂z; (W t)ᵀ]: it changes at a simple branch point (where a second
    curve crosses) and nowhere else on a regular curve."""

    __slots__ = ()
    kind = "branch_point"

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

    def split_points(self, old, new, br_data) -> tuple[float, ...]:
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

    def record(self, system, loc, br, weights, interval) -> Record:
        kind, label, wrt, status, interval, details = super().record(
            system, loc, br, weights, interval
        )
        details["names"] = tuple(system.names)  # the directions need the same components
        return (kind, label, wrt, status, interval, details)


class EventTest(TestFunction):
    """A user :class:`~..problem._events.Event`: ``function(u, p)`` of the unknowns and
    parameters."""

    __slots__ = ("event",)
    kind = "event"
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
    bounds: Mapping[str, tuple[float, float]] | None = None,
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
