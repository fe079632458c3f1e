"""Results: a :class:`Branch` of column arrays with a list of :class:`SpecialPoint` records."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from .._outcomes import Kind, PointStatus, Status


@dataclass(frozen=True)
class SpecialPoint:
    """A located point of interest on a branch.

    ``kind`` (a :class:`~.._outcomes.Kind`, equal to its string, or a test function's own
    kind): ``"fold"`` (a turning point with respect to ``with_respect_to``),
    ``"branch_point"``, ``"cusp"``, ``"codim2"``, ``"event"``, ``"target"`` or
    ``"endpoint"``; with stability (``trace(..., stability=True)``) also ``"hopf"``, and on
    Hopf and fold curves ``"bautin"``, ``"bogdanov_takens"`` and ``"zero_hopf"``.
    ``index``: its row in the branch arrays. ``values``: every unknown and
    parameter. ``status`` (a :class:`~.._outcomes.PointStatus`): ``"converged"`` (located
    to tolerance) or ``"guess"`` (only bracketed: the ``interval`` of arclength holds it).
    ``details``: kind-specific data (test-function values, null vectors, Newton iterations,
    ...). ``scales``: the typical sizes of the components of the branch it lies on (a
    branch or fold curve started from it uses them).
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

    Attributes: ``s`` (arclength), ``tangents`` (rows, in the order of ``variables``),
    ``special_points``, ``status`` (a :class:`~.._outcomes.Status`, equal to its string:
    ``"bound"``, ``"max_steps"``, ``"terminal_event"``, ``"convergence_failure"``,
    ``"nonfinite_residual"``, ...), ``success``,
    ``message`` (a sentence), ``stats`` (per-point arrays ``newton_iterations``,
    ``rejected_steps``, ``residual_norm``, ``ds``; a point inserted inside a step, such as a
    located fold, has ``ds = 0`` and the locating method's iterations), ``variables`` (the
    names of the traced components, i.e. the unknowns and the free parameter(s)),
    ``kinds`` (the kinds of special point the curve's test functions report: with every
    :class:`~.._outcomes.Kind` and the kinds on the branch, what :meth:`special` accepts),
    ``eigenvalues`` (traced with ``stability=True``: per row, the computed eigenvalues of
    the equilibrium by decreasing real part, and the column ``"n_unstable"``; else None).
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
        """Whether the branch ended normally: a bound or a terminal event (``"max_steps"``
        is no success: the branch stopped short of its bounds)."""
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
        return self._columns.keys()

    def point(self, i: int) -> dict[str, float]:
        """All values at row ``i``."""
        return {k: float(v[i]) for k, v in self._columns.items()}

    def special(
        self,
        kind: str | None = None,
        *,
        with_respect_to: str | None = None,
        label: str | None = None,
        status: str | None = None,
    ) -> list[SpecialPoint]:
        """The special points of ``kind`` (None: all), in branch order; ``with_respect_to``,
        ``label`` and ``status`` filter further.

        A ``kind`` that is no :class:`~.._outcomes.Kind` and that no test function of this
        branch reports (a typo: ``"folds"``) raises ``ValueError`` naming the kinds.

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
        """Dense output: the branch at pseudo-arclengths ``s`` (within ``self.s``), by the
        solver's interpolant, without Newton: the cubic Hermite arcs between its points,
        which the step control kept within ``rtol`` of the curve (weighted norm, relative
        to the typical sizes; ``stats["interpolation_error"]`` holds each step's measured
        error). Returns ``{column: array}``. Raises
        :class:`~cusp.continuation.AccuracyError` on a segment whose arc is not within
        ``rtol`` (then use :func:`~cusp.continuation.points_at`, which runs Newton).

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
        """Dense output where component ``name`` takes each of ``values`` (the first
        crossing in branch order): the interpolant of :meth:`interpolate`, solved for the
        value on its segment (no Newton on the problem)."""
        from ._dense import interpolate_at

        return interpolate_at(self, name, values)

    def save(self, path) -> Any:
        """Save the branch to one ``.npz`` file at ``path`` (atomically: a temporary file
        beside it, then moved over it), readable by numpy alone
        (``np.load(path, allow_pickle=False)``: its arrays, and ``"metadata.json"`` with
        the rest); :func:`~cusp.continuation.load` reads it back bit for bit. Returns the
        path (a :class:`pathlib.Path`). See docs/continuation.md, "Saving, loading and
        resuming".

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
        """The branch as a :class:`pandas.DataFrame`: one row a point; its columns, ``s``,
        the statistics (``stats.ds``, ...) and ``special`` (the kinds of special point at
        the row, comma-separated). Needs pandas (``pip install 'cusp[pandas]'``)."""
        from ._persist import to_pandas

        return to_pandas(self)

    def plot(self, x: str, y: str, ax=None, *, special: bool = True, points: bool = True, **kwargs):
        """Plot column ``y`` against ``x`` along the dense output (:meth:`interpolate`; the
        chords where there is none), the rows marked as dots (``points``) and the special
        points by kind (matplotlib imported lazily); returns the Axes."""
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
