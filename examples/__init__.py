"""Example problems, written once: each a function returning a ready :class:`Example` (a
:class:`~cusp.continuation.Problem` with hand-written derivatives, a start point, the free
parameter and bounds that show its special points, and :meth:`Example.references`: the known
special points in closed form or from an independent mpmath computation).

>>> from cusp.examples import cusp_normal_form
>>> ex = cusp_normal_form()                 # x**3 - a*x - b = 0, a = 1, from b = -1
>>> br = ex.trace()                          # trace(ex.problem, ex.u0, free="b", bounds=...)
>>> [round(sp.values["b"], 12) for sp in br.special("fold")]
[0.38490017946, -0.38490017946]

Every example takes ``derivatives="analytic"`` (default: the hand-written Jacobian and
parameter derivatives) or ``"central"``, ``"forward"``, ``"complex"`` (the solver's
fallbacks). The modules, by family:

- :mod:`~cusp.examples.normal_forms`: the cusp x³ − a x − b, transcritical, pitchfork;
- :mod:`~cusp.examples.trusses`: von Mises trusses (Green and rotated strain, two degrees of
  freedom with a branch point, snap-back with a spring);
- :mod:`~cusp.examples.bratu`: the finite-difference Bratu problem (dense or sparse, any N);
- :mod:`~cusp.examples.structures`: the shallow arch (two-mode Ritz), cohesive bars;
- :mod:`~cusp.examples.chemistry`: CO oxidation (BifurcationKit), the A → B reactor
  (AUTO-07p ``ab``).

Imports only :mod:`cusp.continuation`, numpy and scipy; mpmath is imported by the reference
functions when they run.
"""

from ._base import DERIVATIVES, Example, Reference
from .bratu import (
    BRATU_FOLD_N99999,
    bratu,
    bratu_continuum_fold,
    bratu_fd_fold,
    bratu_fd_fold_state,
    bratu_names,
)
from .chemistry import (
    CO_CUSP,
    CO_FOLDS_K04,
    CO_Q,
    ab_cusp,
    ab_folds,
    ab_reactor,
    co_cusp,
    co_folds,
    co_oxidation,
    co_quartic,
)
from .normal_forms import (
    cusp_fold_curve,
    cusp_folds,
    cusp_normal_form,
    cusp_real_roots,
    cusp_start,
    pitchfork,
    transcritical,
)
from .structures import (
    arch_codim2,
    arch_references,
    cohesive_bilinear,
    cohesive_bilinear_kinks,
    cohesive_bilinear_opening,
    cohesive_exponential,
    cohesive_exponential_fold,
    shallow_arch,
)
from .trusses import (
    snapback_control,
    snapback_cusp,
    snapback_monitor,
    snapback_turning_points,
    truss_2dof,
    truss_2dof_references,
    truss_green,
    truss_green_force,
    truss_green_limits,
    truss_green_stiffness,
    truss_rotated,
    truss_rotated_limits,
)

#: Every example constructor with the arguments of its default set-up, by name (what the
#: self-tests of the package run through).
CATALOGUE = {
    "cusp_normal_form": cusp_normal_form,
    "transcritical": transcritical,
    "pitchfork": pitchfork,
    "bratu": lambda **kw: bratu(10, **kw),
    "bratu_sparse": lambda **kw: bratu(10, sparse=True, **kw),
    "truss_green": truss_green,
    "truss_rotated": truss_rotated,
    "truss_2dof": truss_2dof,
    "snapback_monitor": snapback_monitor,
    "snapback_control": snapback_control,
    "shallow_arch": shallow_arch,
    "cohesive_exponential": cohesive_exponential,
    "cohesive_bilinear": cohesive_bilinear,
    "cohesive_bilinear_opening": cohesive_bilinear_opening,
    "co_oxidation": co_oxidation,
    "ab_reactor": ab_reactor,
}

__all__ = [
    "BRATU_FOLD_N99999",
    "CATALOGUE",
    "CO_CUSP",
    "CO_FOLDS_K04",
    "CO_Q",
    "DERIVATIVES",
    "Example",
    "Reference",
    "ab_cusp",
    "ab_folds",
    "ab_reactor",
    "arch_codim2",
    "arch_references",
    "bratu",
    "bratu_continuum_fold",
    "bratu_fd_fold",
    "bratu_fd_fold_state",
    "bratu_names",
    "co_cusp",
    "co_folds",
    "co_oxidation",
    "co_quartic",
    "cohesive_bilinear",
    "cohesive_bilinear_kinks",
    "cohesive_bilinear_opening",
    "cohesive_exponential",
    "cohesive_exponential_fold",
    "cusp_fold_curve",
    "cusp_folds",
    "cusp_normal_form",
    "cusp_real_roots",
    "cusp_start",
    "pitchfork",
    "shallow_arch",
    "snapback_control",
    "snapback_cusp",
    "snapback_monitor",
    "snapback_turning_points",
    "transcritical",
    "truss_2dof",
    "truss_2dof_references",
    "truss_green",
    "truss_green_force",
    "truss_green_limits",
    "truss_green_stiffness",
    "truss_rotated",
    "truss_rotated_limits",
]
