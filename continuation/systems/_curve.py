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
    """The contract of what the tracer follows: ``G(z) = 0``, ``m`` equations in ``m + 1``.

    ``G`` has ``m`` equations in the ``m + 1`` components of ``z``; the contract is stated
    here once, for every kind of curve (a problem's branch,
    :class:`~cusp.continuation.BranchSystem`; a fold curve, :class:`~._fold.FoldSystem`; a
    system of one's own).

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
        """Evaluate ``G(z)``.

        Parameters
        ----------
        z : numpy.ndarray, shape (m + 1,)
            The curve's components.

        Returns
        -------
        numpy.ndarray, shape (m,)
            The residual.
        """
        raise NotImplementedError

    def jacobian(self, z: np.ndarray) -> Any:  # pragma: no cover - interface
        """Evaluate ``∂G/∂z`` at ``z``.

        Parameters
        ----------
        z : numpy.ndarray, shape (m + 1,)
            The curve's components.

        Returns
        -------
        numpy.ndarray or scipy.sparse matrix, shape (m, m + 1)
            The Jacobian, dense or sparse.
        """
        raise NotImplementedError

    def values(self, z: np.ndarray) -> dict[str, float]:  # pragma: no cover - interface
        """Return every unknown and parameter at ``z``, by name.

        Parameters
        ----------
        z : numpy.ndarray, shape (m + 1,)
            The curve's components.

        Returns
        -------
        dict of str to float
            The values, fixed parameters included.
        """
        raise NotImplementedError

    def scalar_residual(self, z: np.ndarray) -> float | None:
        """Evaluate ``G(z)`` of a curve of one equation as a float.

        Parameters
        ----------
        z : numpy.ndarray, shape (m + 1,)
            The curve's components.

        Returns
        -------
        float or None
            The residual, or None where the float path cannot give it (the array path then
            does).
        """
        return None

    def scalar_jacobian(self, z: np.ndarray) -> tuple[float, float] | None:
        """Evaluate ``∂G/∂z`` of a curve of one equation as two floats.

        Parameters
        ----------
        z : numpy.ndarray, shape (m + 1,)
            The curve's components.

        Returns
        -------
        tuple of (float, float) or None
            The two derivatives, or None as :meth:`scalar_residual`.
        """
        return None

    def checked(self, z: np.ndarray) -> CurveSystem:
        """Return this system after a look at what its functions return at ``z``.

        Called at a curve's start: a system whose float path cannot be used there (its
        functions return other types) comes back with :attr:`scalar` off, so that no call
        is made twice.

        Parameters
        ----------
        z : numpy.ndarray, shape (m + 1,)
            The curve's components.

        Returns
        -------
        CurveSystem
            This system, or a copy with the float path off.
        """
        return self

    def index(self, name: str) -> int | None:
        """Return the index of a component in ``z``.

        Parameters
        ----------
        name : str
            A component's name.

        Returns
        -------
        int or None
            Its index in ``names``, or None if it is not a component.
        """
        try:
            return self.names.index(name)
        except ValueError:
            return None

    def split(self, z: np.ndarray) -> tuple[np.ndarray, dict[str, float]]:
        """Return the problem's unknowns and every value at ``z``.

        These are the arguments of a user's event function.

        Parameters
        ----------
        z : numpy.ndarray, shape (m + 1,)
            The curve's components.

        Returns
        -------
        u : numpy.ndarray, shape (n,)
            The unknowns of the problem (``z`` itself without a problem).
        values : dict of str to float
            Every unknown and parameter, by name.
        """
        vals = self.values(z)
        problem = self.problem
        u = np.array([vals[name] for name in problem.unknowns]) if problem is not None else z
        return u, vals

    def bordered_jacobian(self, z: np.ndarray, row: np.ndarray) -> Any:
        """Return the square matrix ``[∂G/∂z; row]``.

        Parameters
        ----------
        z : numpy.ndarray, shape (m + 1,)
            The curve's components.
        row : numpy.ndarray, shape (m + 1,)
            The bordering row.

        Returns
        -------
        numpy.ndarray or scipy.sparse matrix, shape (m + 1, m + 1)
            The bordered Jacobian.
        """
        return bordered(self.jacobian(z), row)

    def residual_floor(self, dg: Any, z: np.ndarray, magnitudes: Any = None) -> float:
        """Return the residual size attributable to rounding at ``z``.

        Newton accepts a tiny update with a residual up to ``max(tol, this)``. The last
        column (a parameter) is left out: a parameter derivative differenced across a jump
        of the residual would inflate it.

        Parameters
        ----------
        dg : numpy.ndarray or scipy.sparse matrix, shape (m, m + 1)
            ∂G/∂z at ``z``, or at a nearby point.
        z : numpy.ndarray, shape (m + 1,)
            The curve's components.
        magnitudes : numpy.ndarray, shape (m + 1,), optional
            The components' magnitudes there, if known better than by their typical sizes
            (a located point's :func:`~..detection._folds.local_magnitudes`).

        Returns
        -------
        float
            The rounding floor of the residual's max-norm.
        """
        return rounding_floor(dg[:, :-1], z, self.scales if magnitudes is None else magnitudes)

    def refreshed(self, z: np.ndarray) -> CurveSystem:
        """Return the system to use after the accepted point ``z``.

        Augmented systems update their borders there and return a new system; this one is
        unchanged.

        Parameters
        ----------
        z : numpy.ndarray, shape (m + 1,)
            The curve's components.

        Returns
        -------
        CurveSystem
            The system valid beyond ``z``.
        """
        return self

    def with_values(self, values: Mapping[str, float]) -> CurveSystem:
        """Return this system with its fixed parameters taken from ``values`` where given.

        Used when starting from a special point of another curve.

        Parameters
        ----------
        values : mapping of str to float
            Values by name (unknowns and parameters).

        Returns
        -------
        CurveSystem
            The system with those parameter values.
        """
        return self

    def with_scales(self, scales: np.ndarray) -> CurveSystem:
        """Return this system with the typical sizes ``scales``.

        The arclength weights become ``base_weights / scales²`` and a
        :class:`~cusp.continuation.Problem`'s finite differences step relative to them.

        Parameters
        ----------
        scales : numpy.ndarray, shape (m + 1,)
            One typical size per component of ``z``, > 0.

        Returns
        -------
        CurveSystem
            The rescaled copy (this system is left as it is).

        Raises
        ------
        ProblemDefinitionError
            A size outside [1e-150, 1e150], where the arclength metric cannot be formed.
        """
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
        """Return the curve vector ``z`` of the unknowns ``u`` at the system's parameters.

        Parameters
        ----------
        u : numpy.ndarray, shape (n,)
            The problem's unknowns.

        Returns
        -------
        numpy.ndarray, shape (m + 1,)
            The curve vector.

        Raises
        ------
        ProblemDefinitionError
            For a system that starts only from a full curve vector (this base class).
        """
        raise ProblemDefinitionError(
            f"{type(self).__name__} starts from a full curve vector: use Tracer.init_at(z0)"
        )

    def fixed_values(self) -> dict[str, float]:
        """Return the parameters held fixed on this curve.

        Returns
        -------
        dict of str to float
            Their values, reported as constant columns of the branch.
        """
        return {}


def state_weights(n: int, n_params: int, state_weight: float | None) -> np.ndarray:
    """The base arclength weights of ``n`` unknowns and ``n_params`` free parameters: each
    unknown ``state_weight`` (None: ``1/n``, so the state enters as a root-mean-square),
    each parameter 1."""
    w = np.ones(n + n_params)
    w[:n] = (1.0 / n) if state_weight is None else state_weight
    return w
