"""Dense output of a traced branch: points at given values of any component, corrected onto
the curve.

A branch holds the points its step control chose. Quadrature along a branch, tables at
round values of a control and comparisons with reference data need points at values chosen
afterwards; interpolating the stored points is only as accurate as their spacing allows.
:func:`points_at` interpolates to get a start and then solves the problem again with the
named component held at the value (Newton on ``[R(z); z_k − value] = 0``, polished to the
update tolerance), so every returned point is on the curve to the corrector's tolerance
whatever the spacing of the branch.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .._errors import ConvergenceError, ProblemDefinitionError
from .._options import ContinuationOptions
from ..problem._problem import as_problem
from ..systems._branch import BranchSystem
from ..systems._curve import CurveSystem
from ..systems._newton import correct
from ._branch import Branch
from ._dense import crossing_segment

__all__ = ["points_at"]


def points_at(
    problem,
    branch: Branch,
    name: str,
    values: ArrayLike,
    *,
    options: ContinuationOptions | None = None,
) -> dict[str, np.ndarray]:
    """The points of ``branch`` where component ``name`` takes each of ``values``.

    Each point is corrected by Newton from the branch's interpolant (unlike
    :meth:`Branch.interpolate_at`, which does not run Newton).

    Parameters
    ----------
    problem : Problem or ContinuationProblem
        The problem the branch was traced from (with the same parameter values).
    branch : Branch
        A branch from :func:`~cusp.continuation.trace` (one free parameter).
    name : str
        An unknown or the free parameter of the branch.
    values : array_like, shape (k,)
        Where to put the points; each must lie within the range the branch covers. When
        the component is not monotone along the branch the first crossing (in branch
        order) is used.
    options : ContinuationOptions, optional
        The Newton settings (default: ``ContinuationOptions()``).

    Returns
    -------
    dict of str to numpy.ndarray, each shape (k,)
        Every unknown and parameter, one entry per value.

    Raises
    ------
    ProblemDefinitionError
        ``name`` is not traced on the branch, the branch does not come from ``problem``, or
        a value lies outside the range the branch covers.
    ConvergenceError
        Newton failed from the interpolated start (the branch is too coarse there).
    """
    problem = as_problem(problem)
    variables = tuple(branch.variables)
    if variables[:-1] != tuple(problem.unknowns) or variables[-1] not in problem.params:
        raise ProblemDefinitionError(
            f"the branch traces {list(variables)}, which are not the unknowns "
            f"{list(problem.unknowns)} plus one parameter of this problem"
        )
    free = variables[-1]
    params = {k: float(branch[k][0]) for k in problem.params if k in branch}
    o = options or ContinuationOptions()
    system: CurveSystem = BranchSystem(problem, free, params, o.state_weight)
    scales = branch.info.get("scales")  # the typical sizes the branch was traced with
    if scales is not None and set(scales) >= set(variables):
        system = system.with_scales(np.array([scales[v] for v in variables], dtype=float))
    k = system.index(name)
    if k is None:
        raise ProblemDefinitionError(
            f"name {name!r} is not traced on this branch; it must be one of {list(variables)}"
        )
    Z = np.column_stack([branch[v] for v in variables])
    x = Z[:, k]
    vals = np.atleast_1d(np.asarray(values, dtype=float))
    if not np.all(np.isfinite(vals)):
        raise ProblemDefinitionError(f"values must be finite, got {vals!r}")
    out = np.empty((vals.size, Z.shape[1]))
    e_k = np.zeros(Z.shape[1])
    e_k[k] = 1.0
    for i, v in enumerate(vals.tolist()):
        j = crossing_segment(x, name, v)
        d = x - v
        span = d[j] - d[j + 1]
        frac = d[j] / span if span != 0.0 else 0.0
        z0 = Z[j] + frac * (Z[j + 1] - Z[j])
        z0[k] = v
        res = correct(system, z0, e_k, v, o, budget=2, strict=True)
        if not res.converged:
            raise ConvergenceError(
                f"Newton failed ({res.reason}) placing the point {name} = {v!r}",
                values=system.values(z0),
                ds=0.0,
                iterations=res.iterations,
                residual_norm=res.residual_norm,
                remedy="Trace the branch with a smaller ds_max so that interpolation between "
                "its points gives a better start.",
            )
        out[i] = res.z
    columns = {v: out[:, i].copy() for i, v in enumerate(variables)}
    for key, value in params.items():
        if key != free:
            columns[key] = np.full(vals.size, value)
    return columns
