"""Options of the continuation algorithms, validated when built."""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace

from .errors import OptionsError

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


@dataclass(frozen=True)
class ContinuationOptions:
    """Numerical settings of :func:`~cusp.continuation.trace` and
    :func:`~cusp.continuation.fold_curve`.

    Step sizes are pseudo-arclengths measured in the weighted norm
    ``||dz||² = state_weight·Σ du_i² + Σ dp_j²`` (``state_weight`` defaults to 1/n, so the
    state enters as a root-mean-square and large discretisations take the same steps as
    small ones).
    """

    ds: float = 0.05
    """Initial step size."""
    ds_min: float = _DS_MIN_DEFAULT
    """Smallest step size tried before the fallback corrector and then failure."""
    ds_max: float = 0.5
    """Largest step size."""
    max_steps: int = 5000
    """Accepted steps after which the branch ends, incomplete: status ``"max_steps"`` (not a
    success) and a :class:`~.errors.MaxStepsWarning`."""
    tol: float = 1e-10
    """Newton converges when the max-norm of the residual is below ``tol``..."""
    step_tol: float = 1e-12
    """... and the error left after the last update, about its square, is below ``step_tol``
    relative to each component's magnitude ``max(typical size, |z_i|)``. Located special
    points are polished until the update itself is that small (with differenced derivatives,
    whose error keeps Newton from getting much further, until it is below 1e-10)."""
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
    """Nominal first contraction |Δz₂|/|Δz₁| of the corrector (Deuflhard): a step whose
    contraction exceeds four times this is rejected, and the step size aims at it."""
    target_distance: float = 0.1
    """Nominal distance from the predictor to the corrected point, as a fraction of ds (how
    much the curve bends away from its tangent within a step): a step whose distance exceeds
    twice this fraction of ds is rejected."""
    curve_tol: float = 0.02
    """Nominal distance from the predictor to the corrected point, in the weighted norm
    (relative to the components' typical sizes): a step whose distance exceeds four times
    this is rejected. The one number that sets how closely the steps follow the curve."""
    growth: float = 2.0
    """Largest factor by which ds may grow in one step."""
    predictor: str = "tangent"
    """``"tangent"`` (from the bordered system) or ``"secant"``."""
    state_weight: float | None = None
    """Weight of each unknown in the arclength norm; None means 1/n."""
    detect_folds: bool = True
    detect_branch_points: bool = True
    locate_tol: float = 1e-12
    """Relative tolerance to which special points are located."""
    max_locate_iterations: int = 40

    def __post_init__(self) -> None:
        for name in (
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
        ):
            _positive(name, getattr(self, name))
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
        for name in (
            "max_steps",
            "max_newton_iterations",
            "target_newton_iterations",
            "max_locate_iterations",
        ):
            value = getattr(self, name)
            _check(
                name,
                value,
                isinstance(value, int) and not isinstance(value, bool) and value >= 1,
                "an integer >= 1",
            )
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
        _check("predictor", self.predictor, self.predictor in PREDICTORS, f"one of {PREDICTORS}")
        if self.state_weight is not None:
            _positive("state_weight", self.state_weight)
        for name in ("detect_folds", "detect_branch_points"):
            value = getattr(self, name)
            _check(name, value, isinstance(value, bool), "True or False")

    def replace(self, **changes) -> ContinuationOptions:
        """A copy with some fields changed (validated again)."""
        unknown = set(changes) - {f.name for f in fields(self)}
        if unknown:
            allowed = sorted(f.name for f in fields(self))
            raise OptionsError(f"unknown option(s) {sorted(unknown)}; allowed: {allowed}")
        if "ds" not in changes:  # keep the default initial step inside new bounds
            lo = changes.get("ds_min", self.ds_min)
            hi = changes.get("ds_max", self.ds_max)
            if isinstance(lo, (int, float)) and isinstance(hi, (int, float)) and lo <= hi:
                changes["ds"] = min(max(self.ds, lo), hi)
        return replace(self, **changes)
