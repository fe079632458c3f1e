"""Exceptions raised by the contact models, and the input checks that raise them.

Every message names the parameter, its value and what is allowed, e.g.
``sigma must be a finite number > 0 [µm], got -1.0``.
"""

from __future__ import annotations

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


def check_positive(name: str, value, unit: str = "") -> float:
    """A finite scalar > 0; returns it as float."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = float("nan")
    if not (np.isfinite(v) and v > 0.0):
        u = f" [{unit}]" if unit else ""
        raise ModelParameterError(f"{name} must be a finite number > 0{u}, got {_show(value)}")
    return v


def check_poisson(value, name: str = "nu") -> float:
    """Poisson's ratio in (−1, 0.5]."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        v = float("nan")
    if not (np.isfinite(v) and -1.0 < v <= 0.5):
        raise ModelParameterError(
            f"{name} (Poisson's ratio) must be a finite number in (-1, 0.5], got {_show(value)}"
        )
    return v


def check_finite_array(name: str, value, lower: float | None = None, unit: str = "") -> np.ndarray:
    """A float array of finite values (≥ lower if given)."""
    arr = np.asarray(value, dtype=float)
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
