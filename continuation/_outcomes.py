"""The engine's outcomes as str-valued enumerations: how a branch ended (:class:`Status`), what
a special point is (:class:`Kind`), how well a point was located (:class:`PointStatus`), why
Newton's method stopped (:class:`Convergence`) and which guard rejected a step
(:class:`Guard`).

Each member is a ``str`` equal to its value, so ``branch.status == "bound"`` and
``sp.kind == "fold"`` hold, formatting gives the value (``f"{Status.BOUND}"`` is
``"bound"``), ``repr`` the plain string's (messages that quote an outcome read as they did
when outcomes were plain strings) and JSON writes it as the plain string. (Python 3.10 has
no ``StrEnum``: :class:`Outcome` is its equivalent.) Each member's ``meaning`` says what it
means, in words.

>>> Status.BOUND == "bound", f"{Kind.FOLD}", Kind.FOLD, type(Kind.FOLD).__name__
(True, 'fold', 'fold', 'Kind')
>>> Kind.FOLD.meaning
'a turning point of a component (the free parameter, or a monitored unknown)'
>>> Kind.parse("folds")
Traceback (most recent call last):
...
ValueError: unknown kind of special point 'folds'; the kinds are 'fold', 'branch_point', ...
"""

from __future__ import annotations

from enum import Enum


class Outcome(str, Enum):
    """A str-valued enumeration whose members also carry their ``meaning`` (a phrase); the
    value is what ``str()``, ``format()`` and JSON give (the standard library's ``StrEnum``,
    which Python 3.10 lacks)."""

    meaning: str

    def __new__(cls, value: str, meaning: str = "") -> Outcome:
        member = str.__new__(cls, value)
        member._value_ = value
        member.meaning = meaning
        return member

    def __str__(self) -> str:
        return str.__str__(self)

    def __repr__(self) -> str:
        # (the plain string's: messages and reprs that quote an outcome read as before)
        return str.__repr__(self)

    def __format__(self, spec: str) -> str:
        return str.__format__(str.__str__(self), spec)

    @classmethod
    def parse(cls, value: str, extra: frozenset[str] = frozenset()) -> str:
        """``value`` as a member (or as one of the ``extra`` values a caller also accepts);
        ``ValueError`` naming the allowed values otherwise."""
        if isinstance(value, str):
            for member in cls:
                if member.value == value:
                    return member
            if value in extra:
                return value
        allowed = [m.value for m in cls] + sorted(extra - {m.value for m in cls})
        names = ", ".join(repr(a) for a in allowed)
        what, plural = _WORDS.get(cls.__name__, ("value", "values"))
        raise ValueError(f"unknown {what} {value!r}; the {plural} are {names}")


class Status(Outcome):
    """How a branch ended (``Branch.status``); :attr:`success` for a normal end."""

    RUNNING = "running", "not finished: the result of an unfinished state"
    BOUND = "bound", "the branch reached a bound (a normal end)"
    TERMINAL_EVENT = "terminal_event", "a terminal event occurred (a normal end)"
    MAX_STEPS = "max_steps", "max_steps steps were taken before a bound: incomplete"
    GUARD_FAILURE = "guard_failure", "a guard of the step rejects every step down to ds_min"
    CONVERGENCE_FAILURE = "convergence_failure", "Newton failed on every step down to ds_min"
    NONFINITE_RESIDUAL = (
        "nonfinite_residual",
        "the residual is not finite ahead (its domain's edge)",
    )
    STALLED = "stalled", "a step could not make progress within its work limit"

    @property
    def success(self) -> bool:
        """Whether the branch ended normally (a bound or a terminal event)."""
        return self is Status.BOUND or self is Status.TERMINAL_EVENT


class Kind(Outcome):
    """What a special point is (``SpecialPoint.kind``, ``TestFunction.kind``). Test
    functions of one's own may add kinds of their own (plain strings)."""

    FOLD = "fold", "a turning point of a component (the free parameter, or a monitored unknown)"
    BRANCH_POINT = "branch_point", "a simple branch point, where another branch crosses"
    CUSP = "cusp", "a cusp of a fold curve: two folds meet"
    CODIM2 = "codim2", "a second zero eigenvalue on a fold curve"
    EVENT = "event", "a zero of a user's event function"
    TARGET = "target", "a component at a requested value"
    ENDPOINT = "endpoint", "an end of the branch: its start, a bound hit, or where it stopped"
    HOPF = "hopf", "a complex pair of eigenvalues crosses the imaginary axis (stability)"
    BAUTIN = "bautin", "a Hopf point whose first Lyapunov coefficient vanishes (generalised Hopf)"
    BOGDANOV_TAKENS = (
        "bogdanov_takens",
        "a double zero eigenvalue with one eigenvector: fold and Hopf curves meet",
    )
    ZERO_HOPF = "zero_hopf", "a zero eigenvalue and an imaginary pair (fold-Hopf)"


class PointStatus(Outcome):
    """How well a point inside a step was located (``SpecialPoint.status``; a locator's
    result may also be a pole, which marks no special point)."""

    CONVERGED = "converged", "located to tolerance"
    GUESS = "guess", "only bracketed: the point lies in the record's interval"
    POLE = "pole", "the test changed sign through infinity: no zero, no special point"


class Convergence(Outcome):
    """Why Newton's method stopped (``NewtonResult.reason``)."""

    CONVERGED = "converged", "the residual and the update are within tolerance"
    MAX_ITERATIONS = "max_iterations", "the iteration limit was reached"
    NONFINITE = "nonfinite", "the residual or its Jacobian is not finite"
    SINGULAR = "singular", "the Newton matrix is singular"
    TOO_FAR = "too_far", "the first update is longer than the step allows"
    DIVERGING = "diverging", "the residual grew a thousandfold"
    NOT_CONTRACTING = "not_contracting", "an update was more than half the one before"
    LINE_SEARCH = "line_search", "the damped Newton's line search found no descent"


class Guard(Outcome):
    """The guard of a step that rejected it (``StepGuardError.guard``)."""

    ANGLE = "angle", "the tangent turned more than the limits allow"
    CONTRACTION = "contraction", "Newton's first contraction is too weak"
    DISTANCE = "distance", "the corrector moved too far from the predictor"
    INTERPOLATION = "interpolation", "the step's cubic arc is too far off the curve"


#: how :meth:`Outcome.parse` names the values of each enumeration in its error message
_WORDS = {
    "Status": ("status", "statuses"),
    "Kind": ("kind of special point", "kinds"),
    "PointStatus": ("point status", "point statuses"),
    "Convergence": ("Newton outcome", "outcomes"),
    "Guard": ("guard", "guards"),
}

__all__ = ["Convergence", "Guard", "Kind", "Outcome", "PointStatus", "Status"]
