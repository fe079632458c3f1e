"""Loci of located points: a point of a branch (a bound hit, a target, a smooth fold) or a
chain of such points across the legs of a loading program, continued in a second parameter.

A point located on a branch of ``R(u, p₁) = 0`` by a condition ``c(u, p₁) = 0`` (a bound or
target: ``z_k − value``) is a regular solution of ``[R; c] = 0`` in ``(u, p₁)``; with a second
parameter ``p₂`` free, that system has a curve of solutions: the point's locus. A loading
program is a sequence of legs, each a problem of its own whose end (a corner where the next
leg begins) is such a point; a leg may take parameters from points of earlier legs (say, a
quantity frozen at the end of the leg before). A :class:`PointChain` stacks the points'
systems, linked by those parameters, into one problem whose unknowns are every point's
unknowns and control; its branch in ``p₂`` is the locus of all of them together, traced by
the same tracer as any branch, so bounds, targets, events and monitored turning points work
along it unchanged. Smooth folds are continued by :func:`~.foldcurve.fold_curve` (their
condition is a test function; :func:`point_locus` sends them there).

>>> from cusp.continuation import Problem, trace
>>> prob = Problem(lambda u, p: [u[0]**2 - p["b"] * p["a"]], ["x"], {"a": 1.0, "b": 1.0})
>>> br = trace(prob, [1.0], free="b", bounds={"b": (0.5, 2.0)})
>>> end = br.special("endpoint")[-1]           # the bound hit b = 2, at x = √(2a)
>>> loc = point_locus(prob, end, free=("b", "a"), bounds={"a": (1.0, 8.0)})
>>> round(float(loc["x"][-1]), 12)             # at a = 8: x = √16
4.0
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .branch import Branch, SpecialPoint
from .directions import trace_directions
from .errors import ProblemDefinitionError
from .foldcurve import fold_curve
from .options import ContinuationOptions
from .problem import as_matrix, as_problem, as_vector, has_exact_jacobian
from .state import TracerState
from .tracer import Tracer

#: what a condition holds a variable at: a number, a parameter of the chain (by name), or
#: the value of a variable at another point of the chain (``(point, variable)``)
Target = float | str | tuple[str, str]


@dataclass(frozen=True)
class ChainPoint:
    """One point of a :class:`PointChain`.

    ``name``: the point's name (its variables are ``"name.variable"`` in the chain).
    ``problem``: the leg it lies on. ``control``: the leg's free parameter (a variable of the
    point, beside the problem's unknowns). ``at``: ``(variable, target)``, the condition that
    locates the point on its leg (the end of the leg: its control or any unknown held at the
    target, see :data:`Target`). ``links``: ``{parameter of the problem: (point, variable)}``,
    parameters taken from other points of the chain (a level frozen at an earlier corner)."""

    name: str
    problem: Any
    control: str
    at: tuple[str, Target]
    links: Mapping[str, tuple[str, str]] = field(default_factory=dict)


class PointChain:
    """The points of a :class:`ChainPoint` sequence as one problem (:class:`~.problem.
    ContinuationProblem`): unknowns ``"point.variable"`` (each point's problem unknowns, then
    its control), parameters every parameter of the legs that is neither a control nor
    linked, plus the names conditions hold variables at; the residual stacks each point's
    ``R`` and its condition, and the Jacobian is assembled from the legs' own derivatives."""

    def __init__(self, points: Sequence[ChainPoint], params: Mapping[str, float] | None = None):
        self.points = tuple(points)
        names = [pt.name for pt in self.points]
        if not names or len(set(names)) != len(names):
            raise ProblemDefinitionError(f"a chain needs points with distinct names, got {names}")
        self._legs = [as_problem(pt.problem) for pt in self.points]
        self._vars = [tuple(leg.unknowns) + (pt.control,) for pt, leg in self._zip()]
        self.unknowns = tuple(
            f"{pt.name}.{v}" for pt, vs in zip(self.points, self._vars) for v in vs
        )
        self._col = {name: i for i, name in enumerate(self.unknowns)}
        self.params = self._collect_params(dict(params or {}))
        self.has_jacobian = all(has_exact_jacobian(leg) for leg in self._legs)
        self.name = "chain " + "-".join(names)
        self._check_references()
        # per point, what its evaluation needs: the column of its first unknown, its number of
        # unknowns, its linked parameters' columns, its condition's column and target (a
        # number, a parameter's name or, if linked, another point's column), and whether the
        # target is linked
        self._layout = [
            (
                self._col[f"{pt.name}.{vs[0]}"],
                len(vs) - 1,
                {key: self._column(ref) for key, ref in pt.links.items()},
                self._column((pt.name, pt.at[0])),
                pt.at[1] if not isinstance(pt.at[1], tuple) else self._column(pt.at[1]),
                isinstance(pt.at[1], tuple),
            )
            for pt, vs in zip(self.points, self._vars)
        ]

    def _column(self, ref: tuple[str, str]) -> int:
        return self._col[f"{ref[0]}.{ref[1]}"]

    def _zip(self):
        return zip(self.points, self._legs)

    def _collect_params(self, given: dict[str, float]) -> dict[str, float]:
        out: dict[str, float] = {}
        for pt, leg in self._zip():
            if pt.control not in leg.params:
                raise ProblemDefinitionError(
                    f"point {pt.name!r}: control {pt.control!r} is not a parameter of its "
                    f"problem; parameters are {sorted(leg.params)}"
                )
            for key, value in leg.params.items():
                if key == pt.control or key in pt.links or key in out:
                    continue
                out[key] = float(given.get(key, value))
            target = pt.at[1]
            if isinstance(target, str) and target not in out:
                if target not in given:
                    raise ProblemDefinitionError(
                        f"point {pt.name!r} is held at parameter {target!r}: give its value "
                        "in params"
                    )
                out[target] = float(given[target])
        unknown = set(given) - set(out)
        if unknown:
            raise ProblemDefinitionError(
                f"params names {sorted(unknown)}, not parameters of the chain {sorted(out)}"
            )
        return out

    def _check_references(self) -> None:
        for pt, vs in zip(self.points, self._vars):
            var, target = pt.at
            if var not in vs:
                raise ProblemDefinitionError(
                    f"point {pt.name!r} is located by {var!r}, not one of its variables {vs}"
                )
            refs = list(pt.links.values()) + ([target] if isinstance(target, tuple) else [])
            for ref in refs:
                if f"{ref[0]}.{ref[1]}" not in self._col:
                    raise ProblemDefinitionError(
                        f"point {pt.name!r} refers to {ref!r}, not a variable of the chain"
                    )

    # ---------------------------------------------------------------- evaluation
    def _leg_args(self, i: int, z: np.ndarray, p: Mapping[str, float]):
        """Point ``i``'s unknowns and its parameter values."""
        c0, n, links = self._layout[i][:3]
        pt, leg = self.points[i], self._legs[i]
        q = {k: p[k] if k in p else v for k, v in leg.params.items()}
        q[pt.control] = float(z[c0 + n])
        for key, col in links.items():
            q[key] = float(z[col])
        return z[c0 : c0 + n], q

    def _target(self, i: int, z, p) -> float:
        """The value point ``i``'s condition holds its variable at."""
        target, linked = self._layout[i][4:]
        if linked:
            return float(z[target])
        return float(p[target]) if isinstance(target, str) else float(target)

    def residual(self, u, p) -> np.ndarray:
        z = np.asarray(u, dtype=float)
        out: list[Any] = []
        for i in range(len(self.points)):
            ui, q = self._leg_args(i, z, p)
            what = f"the residual of point {self.points[i].name!r}"
            out.append(as_vector(self._legs[i].residual(ui, q), what, q))
            out.append([z[self._layout[i][3]] - self._target(i, z, p)])
        return np.concatenate(out)

    def jacobian(self, u, p) -> np.ndarray:
        z = np.asarray(u, dtype=float)
        m = z.size
        jac = np.zeros((m, m))
        row = 0
        for i, pt in enumerate(self.points):
            leg = self._legs[i]
            c0, n, links, col, target, linked = self._layout[i]
            ui, q = self._leg_args(i, z, p)
            block = as_matrix(leg.jacobian(ui, q), f"the jacobian of point {pt.name!r}", q)
            jac[row : row + n, c0 : c0 + n] = (
                block.toarray() if hasattr(block, "toarray") else block
            )
            jac[row : row + n, c0 + n] = leg.param_jacobian(ui, q, pt.control)
            for key, lc in links.items():
                jac[row : row + n, lc] += leg.param_jacobian(ui, q, key)
            jac[row + n, col] += 1.0
            if linked:
                jac[row + n, int(target)] -= 1.0
            row += n + 1
        return jac

    def param_jacobian(self, u, p, name: str) -> np.ndarray:
        z = np.asarray(u, dtype=float)
        out = np.zeros(z.size)
        row = 0
        for i, pt in enumerate(self.points):
            n = self._layout[i][1]
            if name in self._legs[i].params and name != pt.control and name not in pt.links:
                ui, q = self._leg_args(i, z, p)
                out[row : row + n] = self._legs[i].param_jacobian(ui, q, name)
            if pt.at[1] == name:
                out[row + n] = -1.0
            row += n + 1
        return out

    def start(self, values: Mapping[str, Mapping[str, float]]) -> np.ndarray:
        """The chain's unknowns from each point's values (``{point: {variable: value}}``)."""
        try:
            return np.array(
                [values[pt.name][v] for pt, vs in zip(self.points, self._vars) for v in vs],
                dtype=float,
            )
        except KeyError as err:
            raise ProblemDefinitionError(
                f"the start needs every variable of every point: missing {err}"
            ) from None


def locus(
    chain: PointChain | Sequence[ChainPoint],
    start: Mapping[str, Mapping[str, float]],
    *,
    free: str,
    params: Mapping[str, float] | None = None,
    direction: str | int = "both",
    options: ContinuationOptions | None = None,
    **kwargs: Any,
) -> Branch:
    """The locus of a chain of points as the parameter ``free`` varies.

    ``start``: each point's values (``{point: {variable: value}}``) at the chain's parameter
    values (corrected by Newton first). ``direction``: ``"both"`` (default; the two halves
    joined at the start, ``info["start_index"]``), +1 or −1. Other keyword arguments
    (``bounds``, ``targets``, ``events``, ``monitor``, ``scales``, ``throw`` and option
    overrides) are those of :func:`~.tracer.trace`, on the chain's names (``"B.g"``) and
    parameters; a turning point of ``free`` along the locus is reported as a fold.
    """
    if not isinstance(chain, PointChain):
        chain = PointChain(chain, params)
    elif params:
        raise ProblemDefinitionError("params go to the PointChain when it is built")
    if free not in chain.params:
        raise ProblemDefinitionError(
            f"free parameter {free!r} is not a parameter of the chain; parameters are "
            f"{sorted(chain.params)}"
        )
    if direction not in ("both", 1, -1):
        raise ProblemDefinitionError(f"direction must be 'both', +1 or -1, got {direction!r}")
    u0 = chain.start(start)

    def begin(d: int) -> tuple[Tracer, TracerState]:
        tracer = Tracer(chain, free=free, direction=d, options=options, **kwargs)
        return tracer, tracer.init(u0)

    return trace_directions(begin, direction)


def point_locus(
    problem: Any, point: SpecialPoint, *, free: tuple[str, str], **kwargs: Any
) -> Branch:
    """The locus of a located point of a branch of ``problem`` as the second parameter of
    ``free = (p1, p2)`` varies (``p1``: the branch's free parameter): a fold by
    :func:`~.foldcurve.fold_curve`, a bound hit or target by holding its variable at its
    value (:func:`locus` of a one-point chain, whose variables keep their problem's names).
    Keyword arguments as for :func:`locus`."""
    if not isinstance(point, SpecialPoint):
        raise ProblemDefinitionError(f"point must be a SpecialPoint of a branch, got {point!r}")
    if point.kind == "fold":
        return fold_curve(problem, point, free=free, **kwargs)
    var = point.with_respect_to
    if point.kind not in ("target", "endpoint") or var is None:
        raise ProblemDefinitionError(
            f"point_locus continues folds, targets and bound hits; got a {point.kind!r} point "
            f"{point.label!r} (for an event or a corner between legs, build a PointChain)"
        )
    problem = as_problem(problem)
    p1, p2 = free
    values = point.values
    fixed = {k: float(values[k]) for k in problem.params if k != p1 and k in values}
    if p2 not in fixed:
        raise ProblemDefinitionError(f"{p2!r} is not a parameter of the problem")
    pt = ChainPoint("", problem, p1, (var, float(values[var])))
    chain = _Renamed(PointChain([pt], fixed))
    start = {"": {v: float(values[v]) for v in tuple(problem.unknowns) + (p1,)}}
    return locus(chain, start, free=p2, **kwargs)


class _Renamed(PointChain):
    """A one-point chain whose variables keep their problem's names (no ``"name."``)."""

    def __init__(self, chain: PointChain) -> None:
        self.__dict__.update(chain.__dict__)
        self.unknowns = tuple(u[1:] for u in chain.unknowns)


__all__ = ["ChainPoint", "PointChain", "locus", "point_locus"]
