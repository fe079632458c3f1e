"""The contract of a curve system: an underdetermined system ``G(z) = 0``,
``G: R^{m+1} -> R^m``, whose solution set is the curve the tracer follows.

For an ordinary branch ``z = (u, p_free)`` and ``G = R`` (:class:`~._branch.BranchSystem`);
fold curves supply their own ``G`` with the same interface (:class:`~._fold.FoldSystem`), so
every special-point test, event, target and bound works on them unchanged.

A curve system is immutable while it is traced: a system whose equations change along the
curve (a fold curve's bordering vectors, updated at every accepted point) returns a new
system from :meth:`CurveSystem.refreshed`, which the tracer keeps in its state. Stepping
twice from the same state therefore gives the same points, bit for bit.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from .._errors import ProblemDefinitionError
from ..numerics._linalg import bordered, rounding_floor
from ..numerics._scaling import out_of_range


class CurveSystem:
    """The contract of what the tracer follows: ``G(z) = 0``, ``m`` equations in the ``m + 1``
    components of ``z``; stated here once, for every kind of curve (a problem's branch,
    :class:`~._branch.BranchSystem`; a fold curve, :class:`~._fold.FoldSystem`; a system of
    one's own).

    A subclass sets these attributes (in ``__init__``)
        ``names`` (one per component of ``z``), ``dim`` (= m + 1), ``scales`` (each
        component's typical size: updates, tolerances and finite-difference steps are
        relative to ``max(scale, |z_i|)``), ``base_weights`` and ``weights`` (of the
        arclength inner product, ``base_weights / scales²``: arclength in relative terms),
        ``unit_weights``, ``problem`` (the problem it comes from, or None),
        ``fold_components`` (the components whose turning points are detected by default:
        a branch's free parameter);
    and implements
        :meth:`residual` ``G(z)``, :meth:`jacobian` ``∂G/∂z`` (dense or sparse, m × (m+1)),
        :meth:`values` (every unknown and parameter at ``z``, by name);
    and may override
        :meth:`bordered_jacobian`, :meth:`residual_floor`, :meth:`refreshed` (a system whose
        equations change along the curve: set :attr:`refreshes`), :meth:`with_values`,
        :meth:`start_vector`, :meth:`fixed_values`, the float path (:attr:`scalar`,
        :meth:`scalar_residual`, :meth:`scalar_jacobian`, :meth:`checked`) and the flags
        below.

    **Immutable.** A system never changes once made: what differs along a curve (a fold
    curve's bordering vectors, the typical sizes) comes as a new system
    (:meth:`refreshed`, :meth:`with_scales`), which the tracer keeps in its state, so that
    stepping twice from a state gives the same points, bit for bit. (A memo of the last
    evaluation may be kept inside, which changes no result.) The test functions evaluated
    on a curve are the tracer's, not the system's (:meth:`~..stepping._tracer.Tracer.for_system`).
    """

    names: tuple[str, ...]
    dim: int
    scales: np.ndarray
    base_weights: np.ndarray
    weights: np.ndarray
    unit_weights: bool = False
    """True if every weight is exactly 1 (the step then skips the weighted products)."""
    problem: Any = None
    fold_components: tuple[str, ...] = ()
    exact_jacobian: bool = False
    """True if ``jacobian`` is exact to rounding (not differenced): its own differences are
    then accurate enough for forward differencing."""
    supplied_derivatives: bool = False
    """True if the derivatives are the user's own functions, which the tracer checks against
    the residual (:mod:`~._consistency`)."""
    derivatives_exact: bool = False
    """True if the problem's own derivatives are exact (given, or by complex step): Newton's
    update tolerance is then not floored at the differences' accuracy
    (:func:`~._newton.floor_step_tol`)."""
    refreshes: bool = False
    """True if the equations change along the curve, so that :meth:`refreshed` must be
    called after every accepted point (the tracer skips the call otherwise)."""
    scalar: bool = False
    """True if the curve has two components and :meth:`scalar_residual` and
    :meth:`scalar_jacobian` may give its equation in plain floats: the corrector and the
    fold locator then try floats first (:func:`~._newton.newton`), without numpy's and
    LAPACK's per-call costs, which dominate on such tiny systems."""

    def residual(self, z: np.ndarray) -> np.ndarray:  # pragma: no cover - interface
        """``G(z)``, shape (m,)."""
        raise NotImplementedError

    def jacobian(self, z: np.ndarray) -> Any:  # pragma: no cover - interface
        """``∂G/∂z`` at ``z``, shape (m, m + 1), dense or sparse."""
        raise NotImplementedError

    def values(self, z: np.ndarray) -> dict[str, float]:  # pragma: no cover - interface
        """Every unknown and parameter at ``z``, by name."""
        raise NotImplementedError

    def scalar_residual(self, z: np.ndarray) -> float | None:
        """``G(z)`` of a curve of one equation as a float, or None where the float path
        cannot give it (the array path then does)."""
        return None

    def scalar_jacobian(self, z: np.ndarray) -> tuple[float, float] | None:
        """``∂G/∂z`` of a curve of one equation as two floats, or None as
        :meth:`scalar_residual`."""
        return None

    def checked(self, z: np.ndarray) -> CurveSystem:
        """This system after a look at what its functions return at ``z`` (a curve's start):
        one whose float path cannot be used there (its functions return other types) comes
        back with :attr:`scalar` off, so that no call is made twice."""
        return self

    def index(self, name: str) -> int | None:
        try:
            return self.names.index(name)
        except ValueError:
            return None

    def split(self, z: np.ndarray) -> tuple[np.ndarray, dict[str, float]]:
        """The unknowns ``u`` of the problem and every value (unknowns and parameters) at
        ``z``: the arguments of a user's event function."""
        vals = self.values(z)
        problem = self.problem
        u = np.array([vals[name] for name in problem.unknowns]) if problem is not None else z
        return u, vals

    def bordered_jacobian(self, z: np.ndarray, row: np.ndarray) -> Any:
        """The square matrix ``[∂G/∂z; row]``."""
        return bordered(self.jacobian(z), row)

    def residual_floor(self, dg: Any, z: np.ndarray, magnitudes: Any = None) -> float:
        """The residual size attributable to rounding at ``z`` (``dg``: ∂G/∂z there, or a
        nearby one): Newton accepts a tiny update with a residual up to ``max(tol, this)``.
        The last column (a parameter) is left out: a parameter derivative differenced
        across a jump of the residual would inflate it. ``magnitudes``: the components'
        magnitudes there, if known better than by their typical sizes (a located point's
        :func:`~..detection._folds.local_magnitudes`)."""
        return rounding_floor(dg[:, :-1], z, self.scales if magnitudes is None else magnitudes)

    def refreshed(self, z: np.ndarray) -> CurveSystem:
        """The system to use after the accepted point ``z`` (augmented systems update their
        borders there and return a new system; this one is unchanged)."""
        return self

    def with_values(self, values: Mapping[str, float]) -> CurveSystem:
        """This system with its fixed parameters taken from ``values`` where given (starting
        from a special point of another curve)."""
        return self

    def with_scales(self, scales: np.ndarray) -> CurveSystem:
        """This system with the typical sizes ``scales`` (one per component of z, > 0): the
        arclength weights become ``base_weights / scales²`` and a :class:`Problem`'s finite
        differences step relative to them."""
        scales = np.array(scales, dtype=float)
        k = out_of_range(scales)
        if k is not None:  # its square or reciprocal square would overflow
            raise ProblemDefinitionError(
                f"the typical size of {self.names[k]} would be {scales[k]:.3g}, outside "
                f"[1e-150, 1e150] where the arclength metric can be formed: rescale it "
                f"(or give scales=...)"
            )
        new = object.__new__(type(self))
        new.__dict__.update(self.__dict__)
        new.scales = scales
        new.weights = self.base_weights / (scales * scales)
        new.unit_weights = all(w == 1.0 for w in new.weights.tolist())
        new._scaled_problem()
        return new

    def _scaled_problem(self) -> None:
        """Hand the typical sizes to the problem's finite differences (a :class:`Problem`)."""

    def start_vector(self, u: np.ndarray) -> np.ndarray:
        """The curve vector ``z`` of the unknowns ``u`` at the system's parameter values."""
        raise ProblemDefinitionError(
            f"{type(self).__name__} starts from a full curve vector: use Tracer.init_at(z0)"
        )

    def fixed_values(self) -> dict[str, float]:
        """Parameters held fixed on this curve (reported as constant columns)."""
        return {}


def state_weights(n: int, n_params: int, state_weight: float | None) -> np.ndarray:
    """The base arclength weights of ``n`` unknowns and ``n_params`` free parameters: each
    unknown ``state_weight`` (None: ``1/n``, so the state enters as a root-mean-square),
    each parameter 1."""
    w = np.ones(n + n_params)
    w[:n] = (1.0 / n) if state_weight is None else state_weight
    return w
