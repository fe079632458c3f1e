"""User events: scalar functions of the state whose zeros are located on a branch."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from .._errors import ProblemDefinitionError


@dataclass(frozen=True)
class Event:
    """A zero of ``function(u, p)`` to locate and insert into the branch.

    Parameters
    ----------
    function : callable
        ``function(u, p) -> float`` of the unknowns (shape ``(n,)``) and the parameters.
    direction : {0, 1, -1}, optional
        +1 only upward crossings, −1 only downward, 0 both (default).
    label : str, optional
        The label of the located special points (default ``"event"``).
    terminal : bool, optional
        Whether the branch ends at the located point.

    Raises
    ------
    ProblemDefinitionError
        ``function`` not callable, or another ``direction``.
    """

    function: Callable[[np.ndarray, Mapping[str, float]], float]
    direction: int = 0
    label: str = "event"
    terminal: bool = False

    def __post_init__(self) -> None:
        if not callable(self.function):
            raise ProblemDefinitionError(f"Event function must be callable, got {self.function!r}")
        if self.direction not in (-1, 0, 1):
            raise ProblemDefinitionError(
                f"Event direction must be -1, 0 or +1, got {self.direction!r}"
            )
