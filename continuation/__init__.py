"""Generic pseudo-arclength continuation and bifurcation analysis.

Knows nothing of contact mechanics, and imports neither sympy nor matplotlib at import time
(:func:`from_sympy` and plotting import them when first used).

>>> from continuation import Problem, trace
>>> prob = Problem(lambda u, p: [u[0]**3 - p["a"]*u[0] - p["b"]], ["x"], {"a": 1.0, "b": -1.0})
>>> br = trace(prob, [-1.3247], free="b", bounds={"b": (-1.0, 1.0)})
>>> [round(sp.values["b"], 12) for sp in br.special_points if sp.kind == "fold"]
[0.3849001794598, -0.3849001794598]
"""

from .branch import Branch, SpecialPoint
from .derivatives import JacobianCheck, check_jacobian
from .errors import (
    ContinuationError,
    ConvergenceError,
    NonFiniteResidualError,
    OptionsError,
    ProblemDefinitionError,
    SingularMatrixError,
)
from .events import Event
from .foldcurve import fold_curve
from .options import ContinuationOptions
from .problem import ContinuationProblem, Problem
from .resample import points_at
from .tracer import Tracer, TracerState, trace

__all__ = [
    "Branch",
    "ContinuationError",
    "ContinuationOptions",
    "ContinuationProblem",
    "ConvergenceError",
    "Event",
    "JacobianCheck",
    "NonFiniteResidualError",
    "OptionsError",
    "Problem",
    "ProblemDefinitionError",
    "SingularMatrixError",
    "SpecialPoint",
    "Tracer",
    "TracerState",
    "check_jacobian",
    "fold_curve",
    "points_at",
    "from_sympy",
    "trace",
]


def __getattr__(name):  # lazy: sympy is imported only when the helper is used
    if name == "from_sympy":
        from .symbolic import from_sympy

        return from_sympy
    raise AttributeError(f"module 'continuation' has no attribute {name!r}")
