"""Exceptions raised by the contact models, and the input checks that raise them.

Every message names the parameter, its value and what is allowed, e.g.
``sigma must be a finite number > 0 [µm], got -1.0``.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "ModelParameterError",
    "NoComplianceLawError",
    "MissingLoadScaleError",
    "GrossSlidingError",
    "check_positive",
    "check_poisson",
    "check_ratio",
    "check_finite_array",
]


class ModelParameterError(ValueError):
    """A model parameter or input value is outside its allowed range (or not finite)."""


class MissingLoadScaleError(ModelParameterError):
    """An absolute quantity (separation, area, …) needs E, radius, density, nominal_area."""


class NoComplianceLawError(NotImplementedError):
    """The body has no load–displacement (compliance) law in the paper."""


class GrossSlidingError(ModelParameterError):
    """The tangential force reached μ F_N: the whole contact slides, no equilibrium slip exists."""


def _show(value) -> str:
    arr = np.asarray(value)
    if arr.ndim == 0:
        return repr(arr.item()) if arr.dtype.kind in "fiub" else repr(value)
    return np.array2string(arr, threshold=6, edgeitems=2)


def _real(value) -> float:
    """``value`` as a float if it is a real number (int, float, a real numpy scalar or 0-d
    array), NaN otherwise: a string ("2.0"), a bool, a complex number or anything else is
    not a number here, even where Python would convert it."""
    if isinstance(value, bool | np.bool_ | str | bytes):
        return float("nan")
    arr = np.asarray(value) if not isinstance(value, int | float) else None
    if arr is not None and (arr.ndim != 0 or arr.dtype.kind not in "iuf"):
        return float("nan")
    try:
        return float(value)
    except (TypeError, ValueError, OverflowError):
        return float("nan")


def _not_a_number(value) -> str:
    """' (a str, not a number)' for a value that Python would convert but is no number."""
    if isinstance(value, bool | np.bool_ | str | bytes | complex | np.complexfloating):
        return f" (a {type(value).__name__}, not a real number)"
    return ""


def check_positive(name: str, value, unit: str = "") -> float:
    """A finite real scalar > 0 (not a string, bool or complex); returns it as float."""
    v = _real(value)
    if not (np.isfinite(v) and v > 0.0):
        u = f" [{unit}]" if unit else ""
        raise ModelParameterError(
            f"{name} must be a finite number > 0{u}, got {_show(value)}{_not_a_number(value)}"
        )
    return v


def check_poisson(value, name: str = "nu") -> float:
    """Poisson's ratio in (−1, 0.5] (a real number, not a string, bool or complex)."""
    v = _real(value)
    if not (np.isfinite(v) and -1.0 < v <= 0.5):
        raise ModelParameterError(
            f"{name} (Poisson's ratio) must be a finite number in (-1, 0.5], got "
            f"{_show(value)}{_not_a_number(value)}"
        )
    return v


def check_finite_array(name: str, value, lower: float | None = None, unit: str = "") -> np.ndarray:
    """A float array of finite real values (≥ lower if given); a ragged, string, bool or
    complex array is refused naming ``name``."""
    try:
        raw = np.asarray(value)
    except ValueError:  # ragged nesting
        raw = None
    if raw is None or raw.dtype.kind not in "iuf":
        kind = "ragged" if raw is None else f"of dtype {raw.dtype}"
        raise ModelParameterError(
            f"{name} must be real numbers (an array of int or float), got a value {kind}: "
            f"{value!r:.80}"
        )
    arr = raw.astype(float)
    if arr.size == 1:  # (a level at a time: the checks in Python floats)
        x = float(arr.flat[0])
        if math.isfinite(x) and (lower is None or x >= lower):
            return arr
    bad = ~np.isfinite(arr)
    if lower is not None:
        bad |= arr < lower
    if np.any(bad):
        u = f" [{unit}]" if unit else ""
        rng = "finite" if lower is None else f"finite and >= {lower:g}"
        first = arr[bad].ravel()[0] if arr.ndim else arr
        raise ModelParameterError(
            f"{name} must be {rng}{u}, got {_show(value)} (first bad value {first!r})"
        )
    return arr


def check_ratio(value, name: str = "FT_hat") -> np.ndarray:
    """A nondimensional force ratio in [0, 1]."""
    arr = np.asarray(value, dtype=float)
    bad = ~(np.isfinite(arr) & (arr >= 0.0) & (arr <= 1.0))
    if np.any(bad):
        first = arr[bad].ravel()[0] if arr.ndim else arr.item()
        raise ModelParameterError(
            f"{name} must be finite and in [0, 1], got {_show(value)} (first bad value {first!r})"
        )
    return arr
