"""Results: a :class:`Branch` of column arrays with a list of :class:`SpecialPoint` records."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from .._outcomes import Kind, PointStatus, Status


@dataclass(frozen=True)
class SpecialPoint:
    """A located point of interest on a branch.

    Records are made by the tracer (read them from :meth:`Branch.special`); the fields are
    its attributes.

    Parameters
    ----------
    kind : str
        A :class:`~.._outcomes.Kind` (equal to its string) or a test function's own kind:
        ``"fold"`` (a turning point with respect to ``with_respect_to``),
        ``"branch_point"``, ``"cusp"``, ``"codim2"``, ``"event"``, ``"target"`` or
        ``"endpoint"``; with stability (``trace(..., stability=True)``) also ``"hopf"``,
        and on Hopf and fold curves ``"bautin"``, ``"bogdanov_takens"`` and
        ``"zero_hopf"``.
    index : int
        Its row in the branch arrays.
    values : dict of str to float
        Every unknown and parameter at the point.
    tangent : numpy.ndarray, shape (n + 1,)
        The unit tangent of the curve there, in the order of ``Branch.variables``.
    status : PointStatus or str, optional
        ``"converged"`` (located to tolerance, the default) or ``"guess"`` (only
        bracketed: the ``interval`` of arclength holds it).
    label : str, optional
        The event's or target's label ("" if none).
    with_respect_to : str or None, optional
        For a fold: the component it turns in (the free parameter or a monitored unknown).
    s : float, optional
        Its pseudo-arclength on the branch (NaN if not known).
    interval : tuple of (float, float) or None, optional
        For a guess: the arclength interval that brackets the point.
    details : dict, optional
        Kind-specific data (test-function values, null vectors, Newton iterations, ...).
    scales : dict of str to float or None, optional
        The typical sizes of the components of the branch it lies on (a branch or fold
        curve started from it uses them).
    """

    kind: str
    index: int
    values: dict[str, float]
    tangent: np.ndarray
    status: PointStatus = PointStatus.CONVERGED
    label: str = ""
    with_respect_to: str | None = None
    s: float = float("nan")
    interval: tuple[float, float] | None = None
    details: dict[str, Any] = field(default_factory=dict)
    scales: dict[str, float] | None = None

    def __repr__(self) -> str:
        vals = ", ".join(f"{k}={v:.10g}" for k, v in list(self.values.items())[:6])
        wrt = f" wrt {self.with_respect_to}" if self.with_respect_to else ""
        lab = f" {self.label!r}" if self.label else ""
        return f"<SpecialPoint {self.kind}{wrt}{lab} #{self.index} [{self.status}]: {vals}>"


class Branch:
    """A traced curve: ``branch[name]`` is the array of an unknown or parameter along it.

    Branches are made by the entry points (:func:`~cusp.continuation.trace`,
    :func:`~cusp.continuation.fold_curve`, ...); the constructor's arguments are kept as
    attributes of the same names. ``len(branch)`` is the number of points ``m``.

    Parameters
    ----------
    columns : dict of str to numpy.ndarray, each shape (m,)
        Every unknown and parameter (and derived columns such as ``"n_unstable"``) along
        the curve, read as ``branch[name]``.
    variables : tuple of str
        The names of the traced components: the unknowns and the free parameter(s).
    s : numpy.ndarray, shape (m,)
        The pseudo-arclength of each point.
    tangents : numpy.ndarray, shape (m, len(variables))
        The unit tangent at each point, in the order of ``variables``.
    special_points : list of SpecialPoint
        The located points, in branch order.
    status : Status or str
        How the curve ended (a :class:`~.._outcomes.Status`, equal to its string):
        ``"bound"``, ``"max_steps"``, ``"terminal_event"``, ``"convergence_failure"``,
        ``"nonfinite_residual"``, ...
    message : str
        The same, as a sentence.
    stats : dict of str to numpy.ndarray, each shape (m,)
        Per-point ``newton_iterations``, ``rejected_steps``, ``residual_norm``, ``ds``
        (a point inserted inside a step, such as a located fold, has ``ds = 0`` and the
        locating method's iterations), ``interpolation_error``.
    info : dict, optional
        Entry-point specific data (e.g. ``direction``, ``start_index``).
    kinds : frozenset of str, optional
        The kinds of special point the curve's test functions report: with every
        :class:`~.._outcomes.Kind` and the kinds on the branch, what :meth:`special`
        accepts.
    eigenvalues : list of numpy.ndarray or None, optional
        Traced with ``stability=True``: per row, the computed eigenvalues of the
        equilibrium by decreasing real part (with the column ``"n_unstable"``); else None.
    """

    def __init__(
        self,
        columns: dict[str, np.ndarray],
        *,
        variables: tuple[str, ...],
        s: np.ndarray,
        tangents: np.ndarray,
        special_points: list[SpecialPoint],
        status: Status | str,
        message: str,
        stats: dict[str, np.ndarray],
        info: dict[str, Any] | None = None,
        kinds: frozenset[str] = frozenset(),
        eigenvalues: list[np.ndarray] | None = None,
    ) -> None:
        self._columns = columns
        self.variables = variables
        self.s = s
        self.tangents = tangents
        self.special_points = special_points
        self.status = status if type(status) is Status else Status(status)
        self.kinds = frozenset(kinds) | {sp.kind for sp in special_points}
        self.message = message
        self.stats = stats
        self.info = dict(info or {})
        self.eigenvalues = eigenvalues

    @property
    def success(self) -> bool:
        """Whether the branch ended normally: at a bound or a terminal event.

        ``"max_steps"`` is no success: the branch stopped short of its bounds.
        """
        return self.status.success

    def __getitem__(self, name: str) -> np.ndarray:
        try:
            return self._columns[name]
        except KeyError:
            raise KeyError(
                f"{name!r} is not on this branch; columns are {sorted(self._columns)}"
            ) from None

    def __contains__(self, name: str) -> bool:
        return name in self._columns

    def __len__(self) -> int:
        return self.s.size

    def keys(self):
        """Return the names of the columns, as ``dict.keys()``.

        Returns
        -------
        collections.abc.KeysView of str
            Every name ``branch[name]`` accepts.
        """
        return self._columns.keys()

    def point(self, i: int) -> dict[str, float]:
        """Return all values at row ``i``.

        Parameters
        ----------
        i : int
            The row (negative counts from the end).

        Returns
        -------
        dict of str to float
            Every column's value at that row.
        """
        return {k: float(v[i]) for k, v in self._columns.items()}

    def special(
        self,
        kind: str | None = None,
        *,
        with_respect_to: str | None = None,
        label: str | None = None,
        status: str | None = None,
    ) -> list[SpecialPoint]:
        """Return the special points of ``kind`` (None: all), in branch order.

        Parameters
        ----------
        kind : str, optional
            ``"fold"``, ``"branch_point"``, ``"hopf"``, ... (any of :attr:`kinds`); None
            selects every kind.
        with_respect_to : str, optional
            Only folds in this component.
        label : str, optional
            Only events or targets with this label.
        status : {"converged", "guess"}, optional
            Only points of this status.

        Returns
        -------
        list of SpecialPoint
            The matching points, in branch order.

        Raises
        ------
        ValueError
            A ``kind`` that is no :class:`~.._outcomes.Kind` and that no test function of
            this branch reports (a typo: ``"folds"``); the message names the kinds.

        Examples
        --------
        >>> from cusp.continuation import Problem, trace
        >>> prob = Problem(lambda u, p: [u[0]**2 - p["p"]], ["x"], {"p": 1.0})
        >>> br = trace(prob, [1.0], free="p", bounds={"p": (-1.0, 2.0)}, direction=-1)
        >>> [abs(sp.values["x"]) < 1e-12 for sp in br.special("fold")]
        [True]
        >>> br.special("folds")
        Traceback (most recent call last):
        ...
        ValueError: unknown kind of special point 'folds'; the kinds are 'fold', ...
        """
        if kind is not None:
            kind = Kind.parse(kind, self.kinds)
        out = [sp for sp in self.special_points if kind is None or sp.kind == kind]
        for key, value in (
            ("with_respect_to", with_respect_to),
            ("label", label),
            ("status", status),
        ):
            if value is not None:
                out = [sp for sp in out if getattr(sp, key) == value]
        return out

    def __repr__(self) -> str:
        kinds: dict[str, int] = {}
        for sp in self.special_points:
            kind = str(sp.kind)
            kinds[kind] = kinds.get(kind, 0) + 1
        status = str(self.status)
        return f"<Branch {len(self)} points, status={status!r}, special points {kinds}>"

    def interpolate(self, s) -> dict[str, np.ndarray]:
        """Evaluate the branch at pseudo-arclengths ``s`` by the solver's interpolant.

        Dense output without Newton: the cubic Hermite arcs between the points, which the
        step control kept within ``rtol`` of the curve (weighted norm, relative to the
        typical sizes; ``stats["interpolation_error"]`` holds each step's measured error).

        Parameters
        ----------
        s : array_like, shape (k,)
            Pseudo-arclengths within ``[self.s[0], self.s[-1]]``.

        Returns
        -------
        dict of str to numpy.ndarray, each shape (k,)
            Every traced component at each ``s``.

        Raises
        ------
        AccuracyError
            A segment whose arc is not within ``rtol`` (then use
            :func:`~cusp.continuation.points_at`, which runs Newton).
        ProblemDefinitionError
            An ``s`` outside the branch or not finite.

        Examples
        --------
        >>> from cusp.continuation import Problem, trace
        >>> prob = Problem(lambda u, p: [u[0]**2 + p["b"]**2 - 1], ["x"], {"b": 0.0})
        >>> br = trace(prob, [1.0], free="b", bounds={"b": (-0.5, 0.5)}, rtol=1e-8)
        >>> mid = br.interpolate([0.5 * (br.s[0] + br.s[-1])])
        >>> bool(abs(mid["x"][0] ** 2 + mid["b"][0] ** 2 - 1) < 1e-8)  # on the circle to rtol
        True
        """
        from ._dense import interpolate

        return interpolate(self, s)

    def interpolate_at(self, name: str, values) -> dict[str, np.ndarray]:
        """Evaluate the branch where component ``name`` takes each of ``values``.

        The interpolant of :meth:`interpolate`, solved for the value on the segment of its
        first crossing in branch order (no Newton on the problem).

        Parameters
        ----------
        name : str
            A traced component (one of :attr:`variables`).
        values : array_like, shape (k,)
            The values wanted, each reached on the branch.

        Returns
        -------
        dict of str to numpy.ndarray, each shape (k,)
            Every traced component at each crossing (``name``'s column is ``values``).

        Raises
        ------
        AccuracyError
            The crossing lies on a segment whose arc is not within ``rtol``.
        ProblemDefinitionError
            ``name`` is not traced, a value is not finite or is not reached.
        """
        from ._dense import interpolate_at

        return interpolate_at(self, name, values)

    def save(self, path) -> Any:
        """Save the branch to one ``.npz`` file, atomically, readable by numpy alone.

        A temporary file beside ``path`` is written, then moved over it; numpy reads it
        alone (``np.load(path, allow_pickle=False)``: the arrays, and ``"metadata.json"``
        with the rest), and :func:`~cusp.continuation.load` reads it back bit for bit
        (docs/continuation.md, "Saving, loading and resuming").

        Parameters
        ----------
        path : str or os.PathLike
            The file to write (replaced atomically if it exists).

        Returns
        -------
        pathlib.Path
            The path written.

        Examples
        --------

        >>> import tempfile, pathlib
        >>> from cusp.continuation import Problem, load, trace
        >>> prob = Problem(lambda u, p: [u[0]**2 - p["p"]], ["x"], {"p": 1.0})
        >>> br = trace(prob, [1.0], free="p", bounds={"p": (0.5, 2.0)})
        >>> path = br.save(pathlib.Path(tempfile.mkdtemp()) / "branch.npz")
        >>> again = load(path)
        >>> bool((again["x"] == br["x"]).all()), [sp.kind for sp in again.special_points]
        (True, ['endpoint', 'endpoint'])
        """
        from ._persist import save_branch

        return save_branch(self, path)

    def to_pandas(self) -> Any:
        """The branch as a :class:`pandas.DataFrame`, one row a point.

        Needs pandas (``pip install 'cusp[pandas]'``).

        Returns
        -------
        pandas.DataFrame
            The columns, ``s``, the statistics (``stats.ds``, ...) and ``special`` (the
            kinds of special point at the row, comma-separated).
        """
        from ._persist import to_pandas

        return to_pandas(self)

    def plot(self, x: str, y: str, ax=None, *, special: bool = True, points: bool = True, **kwargs):
        """Plot column ``y`` against ``x`` along the dense output, the special points marked.

        The curve follows the dense output (:meth:`interpolate`; chords where there is none);
        matplotlib is imported when first used.

        Parameters
        ----------
        x, y : str
            The columns on the horizontal and vertical axes.
        ax : matplotlib.axes.Axes, optional
            Where to draw (default: a new figure's axes).
        special : bool, optional
            Whether to mark the special points by kind (default True).
        points : bool, optional
            Whether to mark the rows as dots (default True).
        **kwargs
            Passed to :meth:`matplotlib.axes.Axes.plot` for the curve.

        Returns
        -------
        matplotlib.axes.Axes
            The axes drawn on.
        """
        from ._plotting import plot_branch

        return plot_branch(self, x, y, ax=ax, special=special, points=points, **kwargs)


def join_halves(
    backward: Branch, forward: Branch, *, start_kind: str | None = None, start_label: str = ""
) -> Branch:
    """One curve from the two halves traced from the same start (``backward`` reversed, then
    ``forward``): the start, mid-curve now, is recorded as a special point of ``start_kind``
    (a fold curve's starting fold) or, if None, not at all. ``info``: ``direction`` "both",
    ``start_index`` and each half's status."""
    nb = len(backward)
    columns = {
        key: np.concatenate([backward[key][::-1], forward[key][1:]]) for key in forward.keys()
    }
    s = np.concatenate([-backward.s[::-1], forward.s[1:]])
    tangents = np.vstack([-backward.tangents[::-1], forward.tangents[1:]])
    specials = []
    for sp_ in backward.special_points:
        if not (sp_.kind == Kind.ENDPOINT and sp_.index == 0):
            specials.append(_reindex(sp_, nb - 1 - sp_.index, -sp_.s, -sp_.tangent))
    for sp_ in forward.special_points:
        moved = _reindex(sp_, nb - 1 + sp_.index, sp_.s, sp_.tangent)
        if sp_.kind == Kind.ENDPOINT and sp_.index == 0:  # the start, mid-curve now
            if start_kind is None:
                continue
            moved = replace(
                moved, kind=start_kind, status=PointStatus.CONVERGED, label=start_label, s=0.0,
                details={"start": True}, scales=None,
            )  # fmt: skip
        specials.append(moved)
    specials.sort(key=lambda q: q.index)
    stats = {
        k: np.concatenate([backward.stats[k][::-1], forward.stats[k][1:]]) for k in forward.stats
    }
    ok = backward.success and forward.success
    status = forward.status if ok or not forward.success else backward.status
    message = f"direction -1: {backward.message}; direction +1: {forward.message}"
    interp = stats.get("interpolation_error")
    if interp is not None:  # each row's entry is the segment ending at it: shift the reversed
        back = backward.stats["interpolation_error"]
        interp[:nb] = np.concatenate([[0.0], back[::-1][:-1]])
    info = {
        "direction": "both",
        "start_index": nb - 1,
        "status_minus": backward.status,
        "status_plus": forward.status,
        **{k: v for k, v in forward.info.items() if k in ("rtol", "scales", "base_weights")},
    }
    return Branch(
        columns,
        variables=forward.variables,
        s=s,
        tangents=tangents,
        special_points=specials,
        status=status,
        message=message,
        stats=stats,
        info=info,
        kinds=backward.kinds | forward.kinds | ({start_kind} if start_kind else set()),
    )


def _reindex(sp_: SpecialPoint, index: int, s: float, tangent) -> SpecialPoint:
    return replace(sp_, index=index, s=s, tangent=tangent, scales=None)
