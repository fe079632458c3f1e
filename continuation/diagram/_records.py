"""The records of a whole bifurcation diagram: :class:`Diagram`, its branches
(:class:`DiagramBranch`) and the branch points linking them (:class:`DiagramPoint`); saving
a diagram, and :func:`load` of any results file (the format of
:mod:`~..results._persist`)."""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .._errors import ResultsFileError
from ..results._branch import Branch, SpecialPoint
from ..results._persist import Writer, decode_results, read_results, write_results
from ._deflation import Deflation


@dataclass(frozen=True)
class DiagramBranch:
    """One branch of a :class:`Diagram`.

    Parameters
    ----------
    branch : Branch
        The traced branch (both ways from its start, unless ``closed``).
    depth : int
        0 for the start's branch and branches started from deflated solutions, one more
        than its parent's for a branch switched into.
    origin : {"start", "branch_point", "deflation"}
        How the branch was found.
    source : int or None
        The index in ``Diagram.points`` of the branch point it leaves (None otherwise).
    closed : bool
        Whether it returned to its start (an isola, or a loop).
    ends : tuple of str
        How each half ended (the minus half's status, then the plus half's;
        ``("closed",)`` for a closed branch).
    """

    branch: Branch
    depth: int
    origin: str
    source: int | None
    closed: bool
    ends: tuple[str, ...]


@dataclass(frozen=True)
class DiagramPoint:
    """A branch point of a :class:`Diagram`, once however many branches located it.

    Parameters
    ----------
    point : SpecialPoint
        The first located record of it (values, tangents and switching data).
    on : tuple of int
        The indices of the branches it lies on (those that located it, and the branches
        that leave it).
    leaving : tuple of int
        The branches switched into from it (traced from it, or recognised as already
        traced).
    notes : tuple of str
        What was done at it, one sentence per branch that located it (switched,
        recognised, not switched and why).
    """

    point: SpecialPoint
    on: tuple[int, ...]
    leaving: tuple[int, ...]
    notes: tuple[str, ...]


@dataclass(frozen=True)
class Diagram:
    """A whole bifurcation diagram (:func:`~cusp.continuation.diagram`).

    ``len(diagram)`` is the number of branches.

    Parameters
    ----------
    branches : tuple of DiagramBranch
        The distinct branches.
    points : tuple of DiagramPoint
        The distinct branch points linking them.
    free : str
        The free parameter.
    tol : float
        The distance (weighted, relative to the typical sizes) within which two branches
        or points are the same.
    recognised : tuple of str
        One sentence per branch found again and not kept (before tracing, from a branch
        point whose other branch is known; or after, a traced branch lying on a known one;
        or a deflated solution on a known branch).
    deflation : tuple of Deflation
        The deflation runs, one per parameter value.
    traces : int
        The branches traced (kept or not).
    """

    branches: tuple[DiagramBranch, ...]
    points: tuple[DiagramPoint, ...]
    free: str
    tol: float
    recognised: tuple[str, ...]
    deflation: tuple[Deflation, ...]
    traces: int

    def __len__(self) -> int:
        return len(self.branches)

    def __repr__(self) -> str:
        closed = sum(b.closed for b in self.branches)
        return (
            f"<Diagram {len(self.branches)} branches ({closed} closed), "
            f"{len(self.points)} branch points, {len(self.recognised)} recognised, "
            f"{self.traces} traces>"
        )

    def save(self, path: Any) -> Any:
        """Save the diagram to one ``.npz`` file, atomically, readable by numpy alone.

        As :meth:`Branch.save <cusp.continuation.Branch.save>`; read it back with
        :func:`~cusp.continuation.load`.

        Parameters
        ----------
        path : str or os.PathLike
            The file to write (replaced atomically if it exists).

        Returns
        -------
        pathlib.Path
            The path written.
        """
        return save_diagram(self, path)

    def plot(self, x: str, y: str, ax: Any = None, *, points: bool = True) -> Any:
        """Draw every branch (``y`` against ``x``) and the branch points.

        matplotlib is imported when first used. A branch carrying a column ``n_unstable``
        is drawn solid where it is 0 and dashed elsewhere.

        Parameters
        ----------
        x, y : str
            The columns on the horizontal and vertical axes.
        ax : matplotlib.axes.Axes, optional
            Where to draw (default: a new figure's axes).
        points : bool, optional
            Whether to mark the branch points (default True).

        Returns
        -------
        matplotlib.axes.Axes
            The axes drawn on.
        """
        from ._plot import plot_diagram

        return plot_diagram(self, x, y, ax=ax, points=points)


# ---------------------------------------------------------------- files

#: the records a diagram file may hold, by name
_CLASSES: dict[str, type] = {
    cls.__name__: cls
    for cls in (Branch, SpecialPoint, Diagram, DiagramBranch, DiagramPoint, Deflation)
}
#: what :func:`load` reads, by the file's ``type``
_TYPES = {"Branch": "a branch (Branch.save)", "Diagram": "a diagram (Diagram.save)"}


def save_diagram(diagram: Diagram, path: str | os.PathLike[str]) -> Path:
    """:meth:`Diagram.save <._records.Diagram.save>`."""
    w = Writer(Branch)
    return write_results(path, "Diagram", w.encode(diagram, "diagram"), w)


def load(path: str | os.PathLike[str]) -> Any:
    """Load a results file written by :meth:`Branch.save` or :meth:`Diagram.save`.

    Parameters
    ----------
    path : str or os.PathLike
        The ``.npz`` file (a branch, a fold or Hopf curve, a locus, or a whole diagram).

    Returns
    -------
    Branch or Diagram
        The object as it was saved, bit for bit.

    Raises
    ------
    ResultsFileError
        A file that is not a zip archive, not a cusp results file, truncated or damaged,
        or written in a newer format (the message names the path and what is wrong).
    FileNotFoundError
        No file at ``path``.
    """
    meta, arrays = read_results(path)
    kind = meta.get("type")
    if kind not in _TYPES:
        raise ResultsFileError(
            path, f"it holds {kind!r}; this cusp loads {', '.join(_TYPES.values())}"
        )
    return decode_results(path, meta, arrays, _CLASSES)


__all__ = ["Diagram", "DiagramBranch", "DiagramPoint", "load", "save_diagram"]
