"""Exceptions raised by the continuation package.

Bad input raises subclasses of :class:`ValueError`; numerical failure raises subclasses of
:class:`ContinuationError` that carry the state at which the failure happened.
"""

from __future__ import annotations

from collections.abc import Mapping

from ._outcomes import Guard


class OptionsError(ValueError):
    """An option has a value outside its allowed range (the message names field and value)."""


class ProblemDefinitionError(ValueError):
    """A problem, starting point or call argument is malformed."""


class JacobianError(ProblemDefinitionError):
    """A supplied Jacobian (or parameter derivative) disagrees with the residual.

    Checked against the residual's own differences at a point of the branch: continuation
    with it would report the special points of another problem, so it is refused. The
    arguments are kept as attributes of the same names.

    Parameters
    ----------
    message : str
        What disagrees, where, by how much.
    values : mapping of str to float
        The unknowns and parameters of the point.
    row : int
        The equation that disagrees.
    supplied : float
        Its rate of change along the check's direction, from the supplied Jacobian.
    differenced : float
        The same, from differences of the residual.
    """

    def __init__(
        self,
        message: str,
        *,
        values: Mapping[str, float],
        row: int,
        supplied: float,
        differenced: float,
    ) -> None:
        super().__init__(message)
        self.values = dict(values)
        self.row, self.supplied, self.differenced = row, supplied, differenced


class ContinuationError(RuntimeError):
    """Base class of numerical failures during continuation.

    Parameters
    ----------
    message : str
        What failed, where, and what to try.
    values : mapping of str to float, optional
        The unknowns and parameters at the point of failure (kept as ``values``).
    """

    def __init__(self, message: str, *, values: Mapping[str, float] | None = None) -> None:
        super().__init__(message)
        self.values = dict(values or {})


def format_values(values: Mapping[str, float], limit: int = 6) -> str:
    items = list(values.items())
    text = ", ".join(f"{k}={v:.10g}" for k, v in items[:limit])
    if len(items) > limit:
        text += f", ... ({len(items) - limit} more)"
    return text


class ConvergenceError(ContinuationError):
    """Newton's method (and the fallback corrector) failed to converge.

    The arguments are kept as attributes of the same names (but ``what``, which opens the
    message).

    Parameters
    ----------
    what : str
        What failed to converge, opening the message.
    values : mapping of str to float
        Unknowns and parameters at the last good point.
    ds : float
        The step size at which the corrector gave up.
    iterations : int
        The Newton iterations of the last try.
    residual_norm : float
        The residual's norm when it gave up.
    remedy : str
        What to try, closing the message.
    """

    def __init__(
        self,
        what: str,
        *,
        values: Mapping[str, float],
        ds: float,
        iterations: int,
        residual_norm: float,
        remedy: str,
    ) -> None:
        self.ds = float(ds)
        self.iterations = int(iterations)
        self.residual_norm = float(residual_norm)
        self.remedy = remedy
        message = (
            f"{what} at {format_values(values)} with ds={ds:.3g}: {iterations} iterations, "
            f"residual norm {residual_norm:.3g}. {remedy}"
        )
        super().__init__(message, values=values)


class StepGuardError(ConvergenceError):
    """Newton converged at ``ds_min``, but a guard of the step rejects it.

    The branch cannot be followed safely from the last point (status
    ``"guard_failure"``).

    Parameters
    ----------
    what : str
        What was rejected, opening the message.
    guard : Guard or str
        ``"angle"`` (the tangent turned more than the limits allow), ``"contraction"``
        (Newton's first contraction too weak: the corrector may be converging to another
        branch) or ``"distance"`` (the corrector moved too far from the predictor); a
        :class:`~._outcomes.Guard`, equal to its string.
    values : mapping of str to float
        Unknowns and parameters at the last good point.
    ds : float
        The step size rejected.
    iterations : int
        The Newton iterations of the last try.
    residual_norm : float
        The residual's norm at the rejected point.
    remedy : str
        What to try, closing the message.
    """

    def __init__(
        self,
        what: str,
        *,
        guard: Guard,
        values: Mapping[str, float],
        ds: float,
        iterations: int,
        residual_norm: float,
        remedy: str,
    ) -> None:
        self.guard = guard
        super().__init__(
            what,
            values=values,
            ds=ds,
            iterations=iterations,
            residual_norm=residual_norm,
            remedy=remedy,
        )


class StalledError(ContinuationError):
    """A step could not make progress within its work limit (status ``"stalled"``).

    The limit is ``max_step_solves`` corrector solves (tries, halvings, half steps
    confirming a sign change, corner steps); a branch that crept on for 100 steps far below
    ``ds`` stalls too. The arguments are kept as attributes of the same names.

    Parameters
    ----------
    message : str
        What stalled, where.
    values : mapping of str to float
        The point the step started from.
    ds : float
        The smallest step size tried.
    tried : str
        What was tried, in words.
    """

    def __init__(self, message: str, *, values: Mapping[str, float], ds: float, tried: str):
        self.ds = float(ds)
        self.tried = tried
        super().__init__(message, values=values)


class NonFiniteResidualError(ContinuationError):
    """The residual (or its Jacobian) returned NaN or infinity.

    Parameters
    ----------
    message : str
        What failed, where, and what to try.
    values : mapping of str to float, optional
        The unknowns and parameters at the point of failure (kept as ``values``).
    """


class SingularMatrixError(ContinuationError):
    """A linear system that must be regular was exactly singular.

    Parameters
    ----------
    message : str
        What failed, where, and what to try.
    values : mapping of str to float, optional
        The unknowns and parameters at the point of failure (kept as ``values``).
    """


class SingularPointError(SingularMatrixError):
    """A curve was started at a singular point, where it has no tangent to start along.

    The Jacobian ``∂G/∂z`` (for a branch, ``[∂R/∂u, ∂R/∂p]``) has a null space of
    dimension 2 or more there (a branch point).

    Parameters
    ----------
    message : str
        What failed, where, and what to try.
    values : mapping of str to float, optional
        The unknowns and parameters at the point of failure (kept as ``values``).
    """


class AccuracyError(ContinuationError):
    """A result cannot be given to the requested accuracy.

    Raised for a branch's interpolant across a segment it could not bring within
    ``rtol``, or a branch with no interpolant.

    Parameters
    ----------
    message : str
        What failed, where, and what to try.
    values : mapping of str to float, optional
        The unknowns and parameters at the point of failure (kept as ``values``).
    """


class ResultsFileError(ValueError):
    """A file that :func:`~cusp.continuation.load` cannot read back.

    Not a zip archive (``.npz``), not a cusp results file, truncated or damaged, written in
    a newer format, or holding another type than asked; the message is
    ``"cannot load PATH: REASON"``.

    Parameters
    ----------
    path : object
        The file (kept as the attribute ``path``).
    reason : str
        What is wrong with it (kept as the attribute ``reason``).
    """

    def __init__(self, path: object, reason: str) -> None:
        super().__init__(f"cannot load {str(path)!r}: {reason}")
        self.path, self.reason = path, reason


class MaxStepsWarning(UserWarning):
    """A branch ended because it took ``max_steps`` steps.

    It stopped before reaching a bound or a terminal event: it is incomplete (its status
    ``"max_steps"`` is not a success).
    """


# the public classes are shown as the package's own (tracebacks print
# ``cusp.continuation.ProblemDefinitionError``, not the private module's name)
for _cls in (
    OptionsError,
    ProblemDefinitionError,
    JacobianError,
    ContinuationError,
    ConvergenceError,
    StepGuardError,
    StalledError,
    NonFiniteResidualError,
    SingularMatrixError,
    SingularPointError,
    AccuracyError,
    ResultsFileError,
    MaxStepsWarning,
):
    _cls.__module__ = "cusp.continuation"
