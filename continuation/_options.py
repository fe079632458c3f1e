"""Options of the continuation algorithms, validated when built."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace
from enum import Enum
from operator import is_, itemgetter
from typing import Any

from ._errors import OptionsError

PREDICTORS = ("tangent", "secant")


def _check(name: str, value, ok: bool, allowed: str) -> None:
    if not ok:
        raise OptionsError(f"option {name!r} must be {allowed}, got {value!r}")


def _positive(name: str, value) -> None:
    _check(
        name,
        value,
        isinstance(value, (int, float))
        and not isinstance(value, bool)
        and math.isfinite(value)
        and value > 0,
        "a finite number > 0",
    )


_DS_MIN_DEFAULT = 1e-10

RTOL_DEFAULT = 1e-3
"""The default of :attr:`ContinuationOptions.rtol` (chosen from the work-precision fronts:
docs/benchmarks/work-precision.md)."""

RTOL_MIN = 1e-13
"""The smallest ``rtol``: below it the branch's own points (at the rounding level of the
residual) are the interpolant's error, whatever the step."""

RTOL_MAX = 1e-2
"""The largest ``rtol``: the step's safety guards are tuned with the interpolation check at
most this loose (at 0.1 the shallow arch's fold and branch point, 0.07 apart in its load,
were stepped over together)."""

#: floors of the derived tolerances: Newton's update and location stop at the rounding level
_POINT_TOL_FLOOR = 1e-16
_LOCATE_TOL_FLOOR = 1e-15
_QUAD_TOL_FLOOR = 1e-14
#: the residual tolerance follows rtol within these: below 1e-12 the residual's own rounding
#: (it is absolute) decides; above 1e-10 Newton may stop, on a loose residual, before its
#: contraction can be measured near a singular point (AUTO's pp2 at its branch point)
_RESIDUAL_TOL_MIN = 1e-12
_RESIDUAL_TOL_MAX = 1e-10

#: the tolerances ``rtol`` sets (a value given explicitly overrides it)
DERIVED = ("tol", "step_tol", "locate_tol")

FROM_RTOL: float = float("nan")
"""The default of the tolerances that follow ``rtol`` (:data:`DERIVED`): a NaN object of its
own, told apart by identity (a NaN given as a tolerance is refused, as any other invalid
value). ``None`` given for one of them means the same."""


def point_tol(rtol: float) -> float:
    """Return the error left in a point placed by Newton for a given ``rtol``.

    A point of the branch, a located special point, a polished point of a loading path: the
    error is ``(rtol/1000)²``, at least 1e-16.

    Newton stops when its update is below ``rtol/1000`` relative to each component's
    magnitude; under its quadratic convergence the error left is about the square of that.
    The points are the nodes of the interpolant and of every quadrature along the branch, so
    they are kept three orders below ``rtol`` and more: squaring costs at most one more
    iteration. At the default ``rtol`` = 1e-3 this is 1e-12, the step tolerance the solver
    has always used.

    Parameters
    ----------
    rtol : float
        The relative accuracy asked for (:attr:`ContinuationOptions.rtol`).

    Returns
    -------
    float
        The relative error left in a point.

    Examples
    --------
    >>> point_tol(1e-3), point_tol(1e-13)
    (1e-12, 1e-16)
    """
    # (rounded to 12 digits: the default is exactly 1e-12, not 1.0000000000000004e-12)
    return max(float(f"{(1e-3 * rtol) ** 2:.12g}"), _POINT_TOL_FLOOR)


def quadrature_tol(rtol: float) -> float:
    """Return the relative tolerance of quadratures along a branch for a given ``rtol``.

    Quadratures along a branch or a loading path (energies, loci) are asked for a tenth of
    :func:`point_tol` (1e-13 at the default), at least 1e-14.

    Parameters
    ----------
    rtol : float
        The relative accuracy asked for (:attr:`ContinuationOptions.rtol`).

    Returns
    -------
    float
        The relative tolerance of the quadratures.

    Examples
    --------
    >>> quadrature_tol(1e-3), quadrature_tol(1e-13)
    (1e-13, 1e-14)
    """
    return max(float(f"{0.1 * point_tol(rtol):.12g}"), _QUAD_TOL_FLOOR)


@dataclass(frozen=True)
class ContinuationOptions:
    """Numerical settings of the continuation (:func:`~cusp.continuation.trace`, ...).

    The settings of :func:`~cusp.continuation.trace`, :func:`~cusp.continuation.fold_curve`
    and the other entry points. Step sizes are pseudo-arclengths measured in the weighted norm
    ``||dz||² = state_weight·Σ du_i² + Σ dp_j²`` (``state_weight`` defaults to 1/n, so the
    state enters as a root-mean-square and large discretisations take the same steps as
    small ones), relative to the components' typical sizes.

    **Accuracy: one knob, ``rtol``.** It sets, consistently:

    - the curve tolerance: the branch's interpolant (its cubic Hermite arcs between points,
      :meth:`Branch.interpolate`) is within ``rtol`` of the true curve (weighted norm,
      relative to the typical sizes), measured at every step;
    - the Newton tolerances: updates below ``rtol/1000`` relative, so the error left in a
      point is about ``step_tol = (rtol/1000)²`` (:func:`point_tol`), and a residual
      max-norm ``tol = 100·step_tol`` within [1e-12, 1e-10];
    - the location tolerance of special points, ``locate_tol = (rtol/1000)²``;
    - the quadrature tolerance of energies and loci along a path (:func:`quadrature_tol`).

    The default, 1e-3, keeps the solver's accuracy as it always was (points and special
    points to 1e-12, quadratures to 1e-13, the same steps) and puts the interpolant within
    1e-3 of the curve, enough for any figure; below 1e-5 the steps shrink like
    ``rtol^(1/4)`` (see docs/continuation.md, "Accuracy"). ``tol``, ``step_tol`` and
    ``locate_tol`` may still be given one by one: a value given overrides what ``rtol``
    sets. The other guards of the step (``target_*``, ``curve_tol``, ``max_angle``) keep
    the steps on their branch; they are safety settings, not accuracy ones, and do not
    follow ``rtol``.

    Each field is validated when the options are built; the attribute of the same name
    documents it in full.

    Parameters
    ----------
    rtol : float, optional
        Relative accuracy of everything the solver reports, in ``[1e-13, 1e-2]``
        (default 1e-3).
    ds : float, optional
        Initial step size, within ``[ds_min, ds_max]``.
    ds_min : float, optional
        Smallest step size tried before the fallback corrector and then failure.
    ds_max : float, optional
        Largest step size.
    max_steps : int, optional
        Accepted steps after which the branch ends, incomplete (status ``"max_steps"``).
    tol : float, optional
        Newton's residual max-norm tolerance (default from ``rtol``).
    step_tol : float, optional
        Newton's relative update tolerance (default from ``rtol``: :func:`point_tol`).
    max_step_solves : int, optional
        Corrector solves one step may take before the branch ends as ``"stalled"``.
    max_newton_iterations : int, optional
        Newton iterations per corrector solve.
    target_newton_iterations : int, optional
        The Newton iterations the step size aims at.
    max_angle : float, optional
        Degrees: a step whose tangent turns further is rejected, below 180.
    target_angle : float, optional
        Degrees: the nominal tangent turn per step, at most ``max_angle``.
    target_contraction : float, optional
        Nominal first contraction of the corrector (Deuflhard).
    target_distance : float, optional
        Nominal predictor-to-corrector distance, as a fraction of ``ds``.
    curve_tol : float, optional
        Nominal predictor-to-corrector distance in the weighted norm.
    growth : float, optional
        Largest factor by which ``ds`` may grow in one step, at least 1.
    predictor : {"tangent", "secant"}, optional
        The predictor of each step.
    state_weight : float or None, optional
        Weight of each unknown in the arclength norm; None means ``1/n``.
    detect_folds : bool, optional
        Whether folds are detected and located.
    detect_branch_points : bool, optional
        Whether branch points are detected and located.
    locate_tol : float, optional
        Relative tolerance to which special points are located (default from ``rtol``).
    max_locate_iterations : int, optional
        Iterations allowed to locate one special point.

    Raises
    ------
    OptionsError
        A field outside its allowed range (the message names it, its value and what is
        allowed).

    Examples
    --------
    >>> ContinuationOptions(rtol=1e-4).step_tol  # (rtol/1000)²
    1e-14
    """

    rtol: float = RTOL_DEFAULT
    """Relative accuracy of everything the solver reports (see above), in
    ``[1e-13, 1e-2]``."""

    ds: float = 0.05
    """Initial step size."""
    ds_min: float = _DS_MIN_DEFAULT
    """Smallest step size tried before the fallback corrector and then failure."""
    ds_max: float = 0.5
    """Largest step size."""
    max_steps: int = 5000
    """Accepted steps after which the branch ends, incomplete: status ``"max_steps"`` (not a
    success) and a :class:`~._errors.MaxStepsWarning`."""
    tol: float = FROM_RTOL
    """Newton converges when the max-norm of the residual is below ``tol`` (default from
    ``rtol``: ``100·step_tol``, 1e-10 at the default)..."""
    step_tol: float = FROM_RTOL
    """... and the error left after the last update, about its square, is below ``step_tol``
    (default from ``rtol``: :func:`point_tol`, 1e-12 at the default)
    relative to each component's magnitude ``max(typical size, |z_i|)``. Located special
    points are polished until the update itself is that small (with differenced derivatives,
    whose error keeps Newton from getting much further, until it is below 1e-10)."""
    max_step_solves: int = 200
    """Corrector solves one step may take (its tries, halvings, half steps confirming a sign
    change, corner steps and steps aimed at a bound together; each at most
    ``max_newton_iterations`` iterations): a step that needs more cannot make progress and
    ends the branch with status ``"stalled"`` (:class:`~._errors.StalledError`). A normal step
    takes 1 to 5."""
    max_newton_iterations: int = 10
    target_newton_iterations: int = 5
    """The step size is scaled by ``target_newton_iterations / iterations`` (within
    ``[0.5, growth]``): it grows while Newton needs fewer iterations, shrinks when more."""
    max_angle: float = 30.0
    """Degrees: a step whose tangent turns further is rejected (guard against branch jumping)."""
    target_angle: float = 15.0
    """Degrees: the nominal tangent turn per step (a step turning more than twice this is
    rejected, and the step size aims at it)."""
    target_contraction: float = 0.05
    """Nominal first contraction ‖Δz₂‖/‖Δz₁‖ of the corrector (Deuflhard): a step whose
    contraction exceeds four times this is rejected, and the step size aims at it."""
    target_distance: float = 0.2
    """Nominal distance from the predictor to the corrected point, as a fraction of ds (how
    much the curve bends away from its tangent within a step): a step whose distance exceeds
    twice this fraction of ds is rejected."""
    curve_tol: float = 0.02
    """Nominal distance from the predictor to the corrected point, in the weighted norm
    (relative to the components' typical sizes): a step whose distance exceeds four times
    this is rejected. A guard against stepping over special points, tuned with the others
    on the published-problem suite; the accuracy of the curve between points is ``rtol``'s
    (the step's interpolant is measured against it)."""
    growth: float = 2.0
    """Largest factor by which ds may grow in one step."""
    predictor: str = "tangent"
    """``"tangent"`` (from the bordered system) or ``"secant"``."""
    state_weight: float | None = None
    """Weight of each unknown in the arclength norm; None means 1/n."""
    detect_folds: bool = True
    detect_branch_points: bool = True
    locate_tol: float = FROM_RTOL
    """Relative tolerance to which special points are located (default from ``rtol``:
    ``(rtol/1000)²``, 1e-12 at the default)."""
    max_locate_iterations: int = 40
    _from_rtol: frozenset[str] = field(default=frozenset(), init=False, repr=False, compare=False)
    """The tolerances that were not given and so follow ``rtol``."""
    _saved: dict[str, Any] | None = field(default=None, init=False, repr=False, compare=False)
    """:meth:`as_dict`, once computed."""

    @property
    def quad_tol(self) -> float:
        """Relative tolerance of quadratures along a path: :func:`quadrature_tol` of ``rtol``.

        Used for the energies and the loci.
        """
        return quadrature_tol(self.rtol)

    def _follow_rtol(self) -> None:
        """Set the tolerances that were not given from ``rtol`` (see the class)."""
        _positive("rtol", self.rtol)
        _check(
            "rtol",
            self.rtol,
            RTOL_MIN <= self.rtol <= RTOL_MAX,
            f"within [{RTOL_MIN:g}, {RTOL_MAX:g}]",
        )
        eps = point_tol(self.rtol)
        derived = {
            "tol": min(max(float(f"{100.0 * eps:.12g}"), _RESIDUAL_TOL_MIN), _RESIDUAL_TOL_MAX),
            "step_tol": eps,
            "locate_tol": max(eps, _LOCATE_TOL_FLOOR),
        }
        unset = frozenset(name for name in DERIVED if _not_given(getattr(self, name)))
        for name in unset:
            object.__setattr__(self, name, derived[name])
        object.__setattr__(self, "_from_rtol", unset)

    def __post_init__(self) -> None:
        self._follow_rtol()
        for name in _POSITIVE:
            _positive(name, getattr(self, name))
        self._check_step_sizes()
        for name in _COUNTS:
            value = getattr(self, name)
            _check(
                name,
                value,
                isinstance(value, int) and not isinstance(value, bool) and value >= 1,
                "an integer >= 1",
            )
        self._check_guards()
        _check("predictor", self.predictor, self.predictor in PREDICTORS, f"one of {PREDICTORS}")
        if self.state_weight is not None:
            _positive("state_weight", self.state_weight)
        for name in ("detect_folds", "detect_branch_points"):
            value = getattr(self, name)
            _check(name, value, isinstance(value, bool), "True or False")

    def _check_step_sizes(self) -> None:
        """``ds_min <= ds <= ds_max``, naming the one the user moved."""
        if self.ds_min > self.ds_max:
            # name the one the user moved: ds_min at its default means ds_max went below it
            if self.ds_min == _DS_MIN_DEFAULT:
                raise OptionsError(
                    f"option 'ds_max' ({self.ds_max!r}) must be >= 'ds_min' "
                    f"({self.ds_min!r}, the default); for steps that small set ds_min below "
                    "it too"
                )
            raise OptionsError(
                f"option 'ds_min' ({self.ds_min!r}) must not exceed 'ds_max' ({self.ds_max!r})"
            )
        _check(
            "ds",
            self.ds,
            self.ds_min <= self.ds <= self.ds_max,
            f"within [ds_min, ds_max] = [{self.ds_min!r}, {self.ds_max!r}]",
        )

    def _check_guards(self) -> None:
        """The angles and the growth factor of the step's guards."""
        _check("max_angle", self.max_angle, self.max_angle < 180.0, "< 180 degrees")
        _check(
            "target_angle",
            self.target_angle,
            self.target_angle <= self.max_angle,
            f"<= max_angle ({self.max_angle!r})",
        )
        _check(
            "growth",
            self.growth,
            isinstance(self.growth, (int, float))
            and math.isfinite(self.growth)
            and self.growth >= 1.0,
            "a finite number >= 1",
        )

    def as_dict(self) -> dict[str, Any]:
        """The fields as a dict, a tolerance that follows ``rtol`` as None.

        ``ContinuationOptions(**options.as_dict())`` equals ``options`` (a saved branch's
        ``info["options"]``).

        Returns
        -------
        dict of str to object
            The options by field name.
        """
        saved = self._saved
        if saved is None:  # (once per options object: every trace records them)
            saved = {
                name: None if name in self._from_rtol else getattr(self, name)
                for name in OPTION_KEYWORDS
            }
            object.__setattr__(self, "_saved", saved)
        return dict(saved)

    def replace(self, **changes) -> ContinuationOptions:
        """Return a copy with some fields changed (validated again).

        Tolerances that followed ``rtol`` still follow it unless given now.

        Parameters
        ----------
        **changes
            New values of fields, by name.

        Returns
        -------
        ContinuationOptions
            The copy.

        Raises
        ------
        OptionsError
            An unknown field, or a value outside its allowed range.
        """
        names = {f.name for f in fields(self) if f.init}
        unknown = set(changes) - names
        if unknown:
            allowed = sorted(names)
            raise OptionsError(f"unknown option(s) {sorted(unknown)}; allowed: {allowed}")
        if "ds" not in changes:  # keep the default initial step inside new bounds
            lo = changes.get("ds_min", self.ds_min)
            hi = changes.get("ds_max", self.ds_max)
            if isinstance(lo, (int, float)) and isinstance(hi, (int, float)) and lo <= hi:
                changes["ds"] = min(max(self.ds, lo), hi)
        for name in self._from_rtol:  # still following rtol unless given now
            changes.setdefault(name, FROM_RTOL)
        return replace(self, **changes)


@dataclass(frozen=True, kw_only=True)
class StabilityOptions:
    """How ``trace(..., stability=...)`` computes stability.

    ``stability=True`` is ``StabilityOptions()``.

    Parameters
    ----------
    nev : int, optional
        The eigenvalues computed nearest ``shift`` on sparse problems (shift-invert
        Arnoldi); at least 2 (default 8).
    dense_limit : int, optional
        Sparse Jacobians of at most this many unknowns get all their eigenvalues densely
        (default 400).
    shift : float, optional
        The real shift of the sparse computation (default 0: the eigenvalues nearest the
        origin).
    hopf : bool, optional
        Whether to locate the Hopf points (False: eigenvalues and ``n_unstable`` only).

    Raises
    ------
    OptionsError
        A field outside its allowed range.

    Examples
    --------
    >>> StabilityOptions(nev=1)
    Traceback (most recent call last):
    ...
    cusp.continuation.OptionsError: option 'nev' must be an integer >= 2, got 1
    """

    nev: int = 8
    dense_limit: int = 400
    shift: float = 0.0
    hopf: bool = True

    def __post_init__(self) -> None:
        whole = lambda v: isinstance(v, int) and not isinstance(v, bool)  # noqa: E731
        _check("nev", self.nev, whole(self.nev) and self.nev >= 2, "an integer >= 2")
        _check(
            "dense_limit",
            self.dense_limit,
            whole(self.dense_limit) and self.dense_limit >= 0,
            "an integer >= 0",
        )
        finite = isinstance(self.shift, (int, float)) and not isinstance(self.shift, bool)
        _check("shift", self.shift, finite and math.isfinite(self.shift), "a finite number")
        _check("hopf", self.hopf, isinstance(self.hopf, bool), "True or False")


class Keep(Enum):
    """The default of the option keywords of the entry points (``trace(..., ds_max=...)``):
    not given, the field of ``options`` is kept."""

    KEEP = "keep"


KEEP = Keep.KEEP
"""See :class:`Keep`."""


def with_overrides(
    options: ContinuationOptions | None,
    default: ContinuationOptions,
    arguments: Mapping[str, Any],
) -> ContinuationOptions:
    """``options`` (None: ``default``) with the fields given by keyword to an entry point,
    validated as any options (:meth:`ContinuationOptions.replace`). ``arguments``: the entry
    point's arguments by name (its ``locals()``), among them every option keyword
    (:data:`OPTION_KEYWORDS`), :data:`KEEP` where not given."""
    base = default if options is None else options
    values = _option_values(arguments)
    if all(map(is_, values, _KEEPS)):  # (the common case, none given: read in C)
        return base
    changes = {name: v for name, v in zip(OPTION_KEYWORDS, values) if v is not KEEP}
    return base.replace(**changes)


def _not_given(value: object) -> bool:
    """Whether a tolerance that follows ``rtol`` was left to it (:data:`FROM_RTOL` or None)."""
    return value is FROM_RTOL or value is None


OPTION_KEYWORDS = (
    "rtol",
    "ds",
    "ds_min",
    "ds_max",
    "max_steps",
    "tol",
    "step_tol",
    "max_step_solves",
    "max_newton_iterations",
    "target_newton_iterations",
    "max_angle",
    "target_angle",
    "target_contraction",
    "target_distance",
    "curve_tol",
    "growth",
    "predictor",
    "state_weight",
    "detect_folds",
    "detect_branch_points",
    "locate_tol",
    "max_locate_iterations",
)
"""The fields of :class:`ContinuationOptions` that the entry points (``trace``,
``fold_curve``, ``locus``, ``point_locus``, :class:`~.stepping._tracer.Tracer`) take by
keyword, overriding their ``options`` (every field there is)."""
_option_values = itemgetter(*OPTION_KEYWORDS)
_KEEPS = (KEEP,) * len(OPTION_KEYWORDS)


#: the options that must be finite numbers > 0, in the order they are checked
_POSITIVE = (
    "ds",
    "ds_min",
    "ds_max",
    "tol",
    "step_tol",
    "max_angle",
    "target_angle",
    "target_contraction",
    "target_distance",
    "curve_tol",
    "locate_tol",
)

#: the options that must be integers >= 1, in the order they are checked
_COUNTS = (
    "max_steps",
    "max_step_solves",
    "max_newton_iterations",
    "target_newton_iterations",
    "max_locate_iterations",
)
