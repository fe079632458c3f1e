"""The latest evaluations of a function of a point, kept by the point's exact bits."""

from __future__ import annotations

from collections.abc import Callable, Hashable
from typing import Any

__all__ = ["Latest"]


class Latest:
    """``f(key)`` for the latest ``size`` keys, each computed once while it is kept.

    The engine asks a problem for its residual, its Jacobian and a parameter column at one
    point, and a locus's chain evaluates two points of one leg in turn: keyed by the point's
    bits (``ndarray.tobytes()`` and the parameters), an evaluation that yields all three is
    made once per point — the same numbers, bit for bit. Callers must not change the values
    (copy what they hand out)."""

    __slots__ = ("_f", "_size", "_kept")

    def __init__(self, f: Callable[[Hashable], Any], size: int) -> None:
        self._f, self._size = f, size
        self._kept: dict[Hashable, Any] = {}

    def __call__(self, key: Hashable) -> Any:
        out = self._kept.get(key)
        if out is None:
            out = self._f(key)
            if len(self._kept) >= self._size:
                del self._kept[next(iter(self._kept))]
            self._kept[key] = out
        return out
