"""A chain of located points as one problem: the points of a loading program's legs (each
located on its leg by a condition ``z_k = target``, a leg possibly taking parameters from
points of earlier legs) stacked into one :class:`~..problem._problem.ContinuationProblem`
whose branch in a second parameter is the locus of all of them together
(:func:`~._locus.locus`)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._errors import ProblemDefinitionError
from ..problem._problem import as_matrix, as_problem, as_vector, has_exact_jacobian

#: what a condition holds a variable at: a number, a parameter of the chain (by name), or
#: the value of a variable at another point of the chain (``(point, variable)``)
Target = float | str | tuple[str, str]


@dataclass(frozen=True)
class ChainPoint:
    """One point of a :class:`PointChain`.

    Parameters
    ----------
    name : str
        The point's name (its variables are ``"name.variable"`` in the chain).
    problem : Problem or ContinuationProblem
        The leg it lies on.
    control : str
        The leg's free parameter (a variable of the point, beside the problem's unknowns).
    at : tuple of (str, float or str or tuple of (str, str))
        ``(variable, target)``, the condition that locates the point on its leg (the end of
        the leg: its control or any unknown held at the target). The target is a number, a
        parameter of the chain (by name) or another point's variable ``(point, variable)``.
    links : mapping of str to tuple of (str, str), optional
        ``{parameter of the problem: (point, variable)}``: parameters taken from other
        points of the chain (a level frozen at an earlier corner).
    """

    name: str
    problem: Any
    control: str
    at: tuple[str, Target]
    links: Mapping[str, tuple[str, str]] = field(default_factory=dict)


class PointChain:
    """The points of a :class:`ChainPoint` sequence as one continuation problem.

    A :class:`~cusp.continuation.ContinuationProblem` whose unknowns are
    ``"point.variable"`` (each point's problem unknowns, then its control) and whose
    parameters are every parameter of the legs that is neither a control nor linked, plus
    the names conditions hold variables at; the residual stacks each point's ``R`` and its
    condition, and the Jacobian is assembled from the legs' own derivatives.

    Parameters
    ----------
    points : sequence of ChainPoint
        The points, with distinct names.
    params : mapping of str to float, optional
        Values of the chain's parameters overriding the legs' own (required for a
        parameter a condition holds a variable at).

    Raises
    ------
    ProblemDefinitionError
        Repeated point names, a control that is not a parameter of its leg, a condition or
        link naming no variable of the chain, or ``params`` naming no parameter of it.
    """

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
        """Evaluate the stacked residual: each point's ``R`` and its condition.

        Parameters
        ----------
        u : array_like, shape (n,)
            The chain's unknowns, in the order of :attr:`unknowns`.
        p : mapping of str to float
            The chain's parameters.

        Returns
        -------
        numpy.ndarray, shape (n,)
            The residual.
        """
        z = np.asarray(u, dtype=float)
        out: list[Any] = []
        for i in range(len(self.points)):
            ui, q = self._leg_args(i, z, p)
            what = f"the residual of point {self.points[i].name!r}"
            out.append(as_vector(self._legs[i].residual(ui, q), what, q))
            out.append([z[self._layout[i][3]] - self._target(i, z, p)])
        return np.concatenate(out)

    def jacobian(self, u, p) -> np.ndarray:
        """Assemble ``∂R/∂u`` of the chain from the legs' own derivatives.

        Parameters
        ----------
        u : array_like, shape (n,)
            The chain's unknowns.
        p : mapping of str to float
            The chain's parameters.

        Returns
        -------
        numpy.ndarray, shape (n, n)
            The dense Jacobian.
        """
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
        """Evaluate ``∂R/∂p[name]`` of the chain.

        Parameters
        ----------
        u : array_like, shape (n,)
            The chain's unknowns.
        p : mapping of str to float
            The chain's parameters.
        name : str
            The parameter differentiated against.

        Returns
        -------
        numpy.ndarray, shape (n,)
            The derivative.
        """
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
        """Return the chain's unknowns from each point's values.

        Parameters
        ----------
        values : mapping of str to mapping of str to float
            ``{point: {variable: value}}`` for every variable of every point.

        Returns
        -------
        numpy.ndarray, shape (n,)
            The unknowns, in the order of :attr:`unknowns`.

        Raises
        ------
        ProblemDefinitionError
            A variable missing.
        """
        try:
            return np.array(
                [values[pt.name][v] for pt, vs in zip(self.points, self._vars) for v in vs],
                dtype=float,
            )
        except KeyError as err:
            raise ProblemDefinitionError(
                f"the start needs every variable of every point: missing {err}"
            ) from None


class _Renamed(PointChain):
    """A one-point chain whose variables keep their problem's names (no ``"name."``)."""

    def __init__(self, chain: PointChain) -> None:
        self.__dict__.update(chain.__dict__)
        self.unknowns = tuple(u[1:] for u in chain.unknowns)


__all__ = ["ChainPoint", "PointChain", "Target"]
