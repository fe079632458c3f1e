"""Generic pseudo-arclength continuation and bifurcation analysis.

Knows nothing of contact mechanics, imports nothing else of :mod:`cusp`, and imports neither
sympy nor matplotlib at import time (:func:`from_sympy` and plotting import them when first
used).

>>> from cusp.continuation import Problem, trace
>>> prob = Problem(lambda u, p: [u[0]**3 - p["a"]*u[0] - p["b"]], ["x"], {"a": 1.0, "b": -1.0})
>>> br = trace(prob, [-1.3247], free="b", bounds={"b": (-1.0, 1.0)})
>>> [round(sp.values["b"], 10) for sp in br.special("fold")]  # ±2/(3√3) = ±0.38490017945975
[0.3849001795, -0.3849001795]

The pieces: a problem (:class:`Problem`, or any object following
:class:`ContinuationProblem`) defines ``R(u, p) = 0``; a curve system
(:class:`CurveSystem`: an ordinary branch, a fold curve) turns it into an underdetermined
``G(z) = 0``; test functions (:class:`TestFunction`) mark its special points by their sign
changes; the :class:`Tracer` steps along the curve through immutable
:class:`TracerState` records; :func:`trace` (with ``stability=True``: eigenvalues and
Hopf points), :func:`fold_curve`, :func:`hopf_curve` and :func:`locus` (loci of located
points, or of a chain of corners across the legs of a loading program) are the
entry points, returning a :class:`Branch`.
"""

from ._errors import (
    AccuracyError,
    ContinuationError,
    ConvergenceError,
    JacobianError,
    MaxStepsWarning,
    NonFiniteResidualError,
    OptionsError,
    ProblemDefinitionError,
    ResultsFileError,
    SingularMatrixError,
    SingularPointError,
    StalledError,
    StepGuardError,
)
from ._options import (
    RTOL_DEFAULT,
    RTOL_MAX,
    RTOL_MIN,
    ContinuationOptions,
    StabilityOptions,
    point_tol,
    quadrature_tol,
)
from .detection._tests import TestFunction
from .diagram._deflation import Deflation, deflate
from .diagram._diagram import DeflationStarts, diagram
from .diagram._records import Diagram, DiagramBranch, DiagramPoint, load
from .loci._chain import ChainPoint, PointChain
from .loci._foldcurve import fold_curve
from .loci._hopfcurve import hopf_curve
from .loci._locus import locus, point_locus
from .problem._derivatives import JacobianCheck, check_jacobian
from .problem._events import Event
from .problem._problem import ContinuationProblem, Problem
from .results._branch import Branch, SpecialPoint
from .results._resample import points_at
from .stepping._state import TracerState
from .stepping._trace import trace
from .stepping._tracer import Tracer
from .systems._branch import BranchSystem
from .systems._curve import CurveSystem

__all__ = [
    "AccuracyError",
    "Branch",
    "ChainPoint",
    "BranchSystem",
    "ContinuationError",
    "ContinuationOptions",
    "ContinuationProblem",
    "CurveSystem",
    "Deflation",
    "DeflationStarts",
    "Diagram",
    "DiagramBranch",
    "DiagramPoint",
    "ConvergenceError",
    "MaxStepsWarning",
    "Event",
    "JacobianCheck",
    "JacobianError",
    "NonFiniteResidualError",
    "OptionsError",
    "PointChain",
    "Problem",
    "ProblemDefinitionError",
    "ResultsFileError",
    "SingularMatrixError",
    "SingularPointError",
    "StepGuardError",
    "SpecialPoint",
    "StabilityOptions",
    "StalledError",
    "TestFunction",
    "Tracer",
    "TracerState",
    "check_jacobian",
    "deflate",
    "diagram",
    "fold_curve",
    "hopf_curve",
    "load",
    "locus",
    "point_locus",
    "point_tol",
    "points_at",
    "quadrature_tol",
    "RTOL_DEFAULT",
    "RTOL_MAX",
    "RTOL_MIN",
    "from_sympy",
    "trace",
]


def __getattr__(name):  # lazy: sympy is imported only when the helper is used
    if name == "from_sympy":
        from .problem._symbolic import from_sympy

        return from_sympy
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
