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
  (AUTO-07p ``ab``);
- :mod:`~cusp.examples.auto_demos`: AUTO-07p demos ``pp2`` (predator–prey), ``log``
  (logistic map), ``dd2`` (discrete predator–prey);
- :mod:`~cusp.examples.reactors`: the enzyme model (AUTO-07p ``enz``), a CSTR with Arrhenius
  kinetics;
- :mod:`~cusp.examples.patterns`: Gray–Scott and Brusselator steady states, Lorenz equilibria
  (AUTO-07p ``lrz``);
- :mod:`~cusp.examples.mechanics`: the elastica, a rigid bar with a spring (perfect and
  imperfect);
- :mod:`~cusp.examples.bifurcations`: a pitchfork crossed along its parabola, imperfect
  transcritical and pitchfork bifurcations, a narrow transcritical crossing;
- :mod:`~cusp.examples.symmetric`: symmetric branch points (pitchforks) of u = 0 in
  applications: Lorenz–Stenflo and Chen equilibria, a Hopfield network, the Chafee–Infante
  equation by finite differences (dense or sparse, any N), with :data:`PITCHFORKS` (mode and
  other branch of every branch point);
- :mod:`~cusp.examples.symmetric_cells`: symmetry breaking of two identical coupled cells
  off u = 0: two Brusselator cells (Turing), two exothermic stirred tanks exchanging heat;
- :mod:`~cusp.examples.stress`: badly scaled variants (:func:`rescaled`) and parallel
  branches.

Imports only :mod:`cusp.continuation`, numpy and scipy; mpmath is imported by the reference
functions when they run.
"""

from ._base import DERIVATIVES, Example, Reference
from .auto_demos import PP2_PARAMS, dd2, logistic_map, pp2, pp2_references
from .bifurcations import (
    imperfect_pitchfork,
    imperfect_transcritical,
    narrow_transcritical,
    subcritical_pitchfork,
)
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
from .mechanics import (
    elastica,
    elastica_buckling_loads,
    elastica_names,
    rigid_bar,
    rigid_bar_limit,
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
from .patterns import (
    BRUSSELATOR,
    brusselator,
    brusselator_branch_points,
    brusselator_names,
    gray_scott,
    gray_scott_references,
    lorenz,
)
from .reactors import cstr, cstr_folds, enz, enz_symmetric_points
from .stress import (
    parallel_s_curves,
    rescaled,
    scaled_ab,
    scaled_arch,
    scaled_cusp,
    scaled_truss,
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
from .symmetric import (
    CHEN,
    HOPFIELD_PATTERNS,
    HOPFIELD_STRENGTHS,
    LORENZ_STENFLO,
    Pitchfork,
    chafee_infante,
    chafee_infante_eigenvalue,
    chafee_infante_names,
    chafee_infante_pitchforks,
    chen,
    chen_pitchforks,
    hopfield,
    hopfield_names,
    hopfield_pitchforks,
    hopfield_weights,
    lorenz_stenflo,
    lorenz_stenflo_pitchforks,
)
from .symmetric_cells import (
    BRUSSELATOR_CELLS,
    CSTR_PAIR,
    brusselator_cells,
    brusselator_cells_pitchforks,
    brusselator_cells_point,
    cstr_pair,
    cstr_pair_references,
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
    "pp2": pp2,
    "logistic_map": logistic_map,
    "dd2": dd2,
    "enz": enz,
    "cstr": cstr,
    "gray_scott": gray_scott,
    "brusselator": brusselator,
    "lorenz": lorenz,
    "elastica": elastica,
    "rigid_bar": rigid_bar,
    "rigid_bar_imperfect": lambda **kw: rigid_bar(0.01, **kw),
    "subcritical_pitchfork": subcritical_pitchfork,
    "imperfect_transcritical": imperfect_transcritical,
    "imperfect_pitchfork": imperfect_pitchfork,
    "narrow_transcritical": narrow_transcritical,
    "scaled_cusp": scaled_cusp,
    "scaled_truss": scaled_truss,
    "scaled_ab": scaled_ab,
    "scaled_arch": scaled_arch,
    "parallel_s_curves": parallel_s_curves,
    "lorenz_stenflo": lorenz_stenflo,
    "chen": chen,
    "hopfield": hopfield,
    "chafee_infante": chafee_infante,
    "chafee_infante_sparse": lambda **kw: chafee_infante(11, sparse=True, **kw),
    "brusselator_cells": brusselator_cells,
    "cstr_pair": cstr_pair,
}

#: The symmetric branch points (:class:`Pitchfork`: point, mode, other branch) of the
#: examples of :mod:`~cusp.examples.symmetric` and :mod:`~cusp.examples.symmetric_cells` in
#: the default set-up of their CATALOGUE entry, by CATALOGUE name (functions: the values are
#: computed with mpmath on first call).
PITCHFORKS = {
    "lorenz_stenflo": lorenz_stenflo_pitchforks,
    "chen": chen_pitchforks,
    "hopfield": hopfield_pitchforks,
    "chafee_infante": lambda: chafee_infante_pitchforks(5),
    "chafee_infante_sparse": lambda: chafee_infante_pitchforks(11),
    "brusselator_cells": brusselator_cells_pitchforks,
    "cstr_pair": lambda: cstr_pair_references()[1],
}

__all__ = [
    "ab_cusp",
    "ab_folds",
    "ab_reactor",
    "arch_codim2",
    "arch_references",
    "bratu",
    "bratu_continuum_fold",
    "bratu_fd_fold",
    "bratu_fd_fold_state",
    "BRATU_FOLD_N99999",
    "bratu_names",
    "BRUSSELATOR",
    "brusselator",
    "brusselator_branch_points",
    "BRUSSELATOR_CELLS",
    "brusselator_cells",
    "brusselator_cells_pitchforks",
    "brusselator_cells_point",
    "brusselator_names",
    "CATALOGUE",
    "chafee_infante",
    "chafee_infante_eigenvalue",
    "chafee_infante_names",
    "chafee_infante_pitchforks",
    "CHEN",
    "chen",
    "chen_pitchforks",
    "co_cusp",
    "CO_CUSP",
    "co_folds",
    "CO_FOLDS_K04",
    "co_oxidation",
    "CO_Q",
    "co_quartic",
    "cohesive_bilinear",
    "cohesive_bilinear_kinks",
    "cohesive_bilinear_opening",
    "cohesive_exponential",
    "cohesive_exponential_fold",
    "cstr",
    "cstr_folds",
    "CSTR_PAIR",
    "cstr_pair",
    "cstr_pair_references",
    "cusp_fold_curve",
    "cusp_folds",
    "cusp_normal_form",
    "cusp_real_roots",
    "cusp_start",
    "dd2",
    "DERIVATIVES",
    "elastica",
    "elastica_buckling_loads",
    "elastica_names",
    "enz",
    "enz_symmetric_points",
    "Example",
    "gray_scott",
    "gray_scott_references",
    "hopfield",
    "hopfield_names",
    "HOPFIELD_PATTERNS",
    "hopfield_pitchforks",
    "HOPFIELD_STRENGTHS",
    "hopfield_weights",
    "imperfect_pitchfork",
    "imperfect_transcritical",
    "logistic_map",
    "lorenz",
    "lorenz_stenflo",
    "LORENZ_STENFLO",
    "lorenz_stenflo_pitchforks",
    "narrow_transcritical",
    "parallel_s_curves",
    "Pitchfork",
    "pitchfork",
    "PITCHFORKS",
    "pp2",
    "PP2_PARAMS",
    "pp2_references",
    "Reference",
    "rescaled",
    "rigid_bar",
    "rigid_bar_limit",
    "scaled_ab",
    "scaled_arch",
    "scaled_cusp",
    "scaled_truss",
    "shallow_arch",
    "snapback_control",
    "snapback_cusp",
    "snapback_monitor",
    "snapback_turning_points",
    "subcritical_pitchfork",
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
