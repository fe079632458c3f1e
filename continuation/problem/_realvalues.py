"""What user functions return, as real arrays: complex results are refused, never cut.

``np.asarray(x, dtype=float)`` drops the imaginary part of numpy complex values (with a
``ComplexWarning``, or silently where warnings are ignored) and raises a bare ``TypeError``
on Python complex numbers: a residual that went complex (a square root of a negative
number) would be followed as its real part. :func:`real_array` takes a complex result only
when its imaginary part is exactly 0 (nothing is lost: a residual written for complex-step
derivatives and called with real input) and otherwise raises
:class:`~.._errors.ProblemDefinitionError` naming the function and the point.

Callers keep their fast path (``type(x) is np.ndarray and x.dtype == float``) and call this
only for anything else.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

import numpy as np
import scipy.sparse as sp

from .._errors import ProblemDefinitionError, format_values

Where = Callable[[], Any] | Mapping[str, float] | str | None
"""The point of an evaluation, for the message: its values by name (or a function giving
them, called only to write the message), or a description."""


def real_array(x: Any, what: str, where: Where = None) -> np.ndarray:
    """``x`` (returned by the user function ``what``, evaluated at ``where``) as a float
    array; complex values with a nonzero imaginary part are refused (module docstring)."""
    a = np.asarray(x)
    kind = a.dtype.kind
    if kind == "f":
        return a if a.dtype == float else a.astype(float)
    if kind == "O":  # e.g. sympy numbers, or Python complex among floats
        try:
            return a.astype(float)
        except TypeError:
            a = a.astype(complex)
            kind = "c"
    if kind == "c":
        _refuse_imaginary(a.imag, what, where)
        return a.real.astype(float)
    return a.astype(float)


def real_matrix(x: Any, what: str, where: Where = None) -> Any:
    """A Jacobian returned by ``what``: :func:`real_array`, sparse matrices kept sparse."""
    if sp.issparse(x):
        if x.dtype.kind == "c":
            _refuse_imaginary(x.data.imag, what, where)
            return x.real.astype(float)
        return x
    return real_array(x, what, where)


def real_scalar(x: Any, what: str, where: Where = None) -> float:
    """A scalar returned by ``what`` (an event function) as a float."""
    if type(x) is float:
        return x
    return float(real_array(x, what, where))


def _refuse_imaginary(imag: np.ndarray, what: str, where: Where) -> None:
    worst = float(np.max(np.abs(imag))) if imag.size else 0.0
    if worst == 0.0:
        return
    raise ProblemDefinitionError(
        f"{what} returned complex values at {describe(where)} (imaginary part up to "
        f"{worst:.3g}): the engine works in real numbers and does not drop the imaginary "
        f"part. Return real values there (a square root, logarithm or fractional power of a "
        f"negative number is complex in numpy's complex types, cmath and sympy)"
    )


def describe(where: Where) -> str:
    """The point ``where`` as text."""
    if callable(where):
        where = where()
    if isinstance(where, Mapping):
        return format_values(where)
    if where is None:
        return "the point evaluated"
    return str(where)


__all__ = ["real_array", "real_matrix", "real_scalar"]
