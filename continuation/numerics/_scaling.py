"""Typical sizes of the components of a curve: what makes the engine independent of units.

Every component ``z_i`` (an unknown or a free parameter) gets a typical size ``s_i > 0``.
The arclength weights are ``base_weight_i / s_i²``, Newton's update test and the location
tolerances compare updates with ``max(s_i, |z_i|)``, and finite differences step relative to
it, so that rescaling an unknown or a parameter by 1e±8 traces the same curve in the same
steps and finds the same special points (to their relative tolerance).

Unless the user gives a component's size (``scales={"x": 1e6}`` in
:func:`~cusp.continuation.trace`), it is taken at the start of the curve, in this order:

1. ``|z_i|`` at the starting point, and the bounds of the component (the width of a finite
   interval, else the largest finite end), whichever is larger. A value at the rounding
   level of the equations it enters (``|∂G_r/∂z_i · z_i|`` below 1000 ε of the size of the
   terms of every such equation ``G_r``, such as the 2e-16 left of an area that should be
   0) counts as 0; starting from a point of another curve (a branch point, a fold), a
   component below a millionth of its size on that curve takes that size;
2. for components still of size 0 (they start at 0, or at a rounding-level value such as
   1e-16, and have no bounds), the start tangent: the components of known size move at the
   relative rates ``|t_j|/s_j``; with ``r`` their median, a component moving by ``|t_i|``
   gets the size ``|t_i| / r`` (what it changes while a typical component changes by its
   typical size; the median keeps one odd component from setting the rate). A tangent
   component below 1e-12 of the largest moves if the Jacobian shows it in an equation
   (:func:`_moving_in_equations`); with finite differences the tangent is taken again with
   the steps of the new sizes (:func:`settled_by_motion`);
3. for components that do not move either (identically 0 on this curve), 1: nothing on
   this curve tells their size (give it in ``scales`` if 1 is far off).

Along the curve a size only grows: when a component exceeds :data:`GROWTH` times its size,
its size becomes its magnitude there (:func:`grown_sizes`; not for sizes the user gave). A
concentration that starts at 1e-3 and climbs to 0.1 would otherwise be followed in steps
of its starting size, thousands of them.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any, NamedTuple

import numpy as np
import scipy.sparse as sp

from .._errors import ProblemDefinitionError


def given_scales(names: Sequence[str], scales: Mapping[str, float] | None) -> dict[int, float]:
    """The user's scales (``scales=``) by component index, ``names`` the curve's components
    (checked: traced names, numbers in [1e-150, 1e150])."""
    out: dict[int, float] = {}
    for name, value in (scales or {}).items():
        if name not in names:
            raise ProblemDefinitionError(
                f"scales names {name!r}, which is not traced on this curve; it must be one of "
                f"{list(names)}"
            )
        k = list(names).index(name)
        try:
            v = float(value)
        except (TypeError, ValueError):
            v = math.nan
        if isinstance(value, bool) or not (1.0 / MAX_SCALE <= v <= MAX_SCALE):
            raise ProblemDefinitionError(
                f"scales[{name!r}] must be a number in [1e-150, 1e150] (a typical size), "
                f"got {value!r}"
            )
        out[k] = v
    return out


GROWTH = 4.0
"""Factor by which a component must exceed its typical size before the size follows it."""

MAX_SCALE = 1e150
"""The largest typical size (and 1/MAX_SCALE the smallest): its square and the reciprocal of
its square stay normal floats (1e±300), so that the arclength weights ``base/s²`` and the
weighted products can be formed. A component that grows beyond it diverges: the branch
stops there (:func:`diverged`)."""


_MIN_SCALE = 1.0 / MAX_SCALE


def out_of_range(scales: np.ndarray) -> int | None:
    """The index of a typical size outside ``[1/MAX_SCALE, MAX_SCALE]`` (or NaN), else None.
    Plain Python on the few components of most problems."""
    if scales.size <= 8:
        for k, v in enumerate(scales.tolist()):
            if not _MIN_SCALE <= v <= MAX_SCALE:
                return k
        return None
    bad = ~((scales >= _MIN_SCALE) & (scales <= MAX_SCALE))
    return int(np.argmax(bad)) if bad.any() else None


def diverged(names: Sequence[str], z: np.ndarray, k: int) -> str:
    """The message of a branch stopped because component ``k`` outgrew :data:`MAX_SCALE`."""
    return (
        f"the branch diverges: {names[k]} reached {z[k]:.3g}, beyond ±{MAX_SCALE:g}, where the "
        f"squares in the arclength metric overflow; the branch stops at the last point "
        f"before. Give a bound on {names[k]!r} (bounds=...) to end it earlier"
    )


def grown_scales(
    scales: np.ndarray, z: np.ndarray, given: Mapping[int, float]
) -> np.ndarray | None:
    """The sizes after the curve reached ``z`` (see the module docstring), or None if none
    grew. ``given``: the user's sizes by component index (kept).

    >>> grown_scales(np.array([1.0, 1e-3]), np.array([2.0, 5e-3]), {})
    array([1.   , 0.005])
    >>> grown_scales(np.array([1.0, 1e-3]), np.array([2.0, 5e-3]), {1: 1e-3}) is None
    True
    """
    if z.size <= 8:  # plain Python on the few components of most problems (a tenth the cost)
        for v, s in zip(z.tolist(), scales.tolist()):
            if not abs(v) <= GROWTH * s:  # (NaN too)
                break
        else:
            return None
    mag = np.abs(z)
    grown = mag > GROWTH * scales
    if not grown.any():
        return None
    for k in given:
        grown[k] = False
    if not grown.any():
        return None
    return np.where(grown, mag, scales)


class StartScales(NamedTuple):
    """The scales of a curve's components at its start (:func:`start_scales`): ``scales``,
    and whether they are ``settled`` (no component was of scale 0 or suspiciously small, so
    the tangent and the Jacobian cannot change them)."""

    scales: np.ndarray
    settled: bool


def start_scales(
    z0: np.ndarray,
    given: Mapping[int, float],
    bounds: Sequence[tuple[int, tuple[float, float]]] = (),
    tangent: np.ndarray | None = None,
    jacobian: Any = None,
    inherited: Mapping[int, float] | None = None,
    guess: bool = False,
) -> StartScales:
    """The typical size of every component (module docstring), and whether they are settled
    (no component was of size 0 or suspiciously small, so the tangent and the Jacobian
    cannot change them); ``bounds`` are the curve's bounds as ``(component index, (low,
    high))``, ``tangent`` the start tangent (any normalisation) or
    None before it is known (the sizes still 0 are then provisionally 1), ``jacobian`` a
    function giving ∂G/∂z at ``z0`` (to recognise values at rounding level; called only if
    some component is a millionth of the largest or less), ``inherited`` the sizes on a
    curve the start lies on (a branch point's or a fold's branch), taken by the components
    whose size here is below a millionth of them (0 up to rounding at a branch point says
    nothing of a component's size; its branch does). ``guess``: ``z0`` is a guess, not yet
    corrected: a component of it a millionth or less of the largest magnitude around (the
    guess's, the bounds', the given sizes) counts as 0 (a guess of 1e-14 for a state that is
    0 is noise, and its size would make Newton's update test demand 1e-30 of it; the
    corrected point's sizes are taken after). Plain Python: it runs once per curve, on the
    few components of most problems."""
    s = [abs(v) for v in np.asarray(z0, dtype=float).tolist()]
    largest = max(s)
    noise = False
    if guess:
        around = max([largest, *given.values(), *(_bound_scale(pair) for _, pair in bounds)])
        for i, x in enumerate(s):
            if 0.0 < x <= 1e-6 * around and i not in given:
                s[i], noise = 0.0, True
        largest = max(s)
    small = noise or any(0.0 < x <= 1e-6 * largest for x in s)
    if jacobian is not None and small:
        # the given sizes count as the components' magnitudes here: a component the user
        # sized 1 but whose value is a rounding 0 still makes the terms of its equations
        mags = list(s)
        for k, v in given.items():
            mags[k] = v
        for i in _at_rounding_level(jacobian(), mags):
            if i not in given:
                s[i] = 0.0
    for k, pair in bounds:
        s[k] = max(s[k], _bound_scale(pair))
    for k, v in (inherited or {}).items():
        if s[k] < 1e-6 * v:
            s[k] = v
    for k, v in given.items():
        s[k] = v
    unknown = [not (0.0 < x < math.inf) for x in s]
    settled = not small and not any(unknown)
    if tangent is not None and any(unknown):
        t = np.abs(np.asarray(tangent, dtype=float)).tolist()
        _size_by_motion(s, unknown, t, given, jacobian)
    # (a value below the range where the metric can be formed sizes it at the range's end;
    # one above it cannot be measured, and is refused by the caller)
    scales = [1.0 if u else max(x, _MIN_SCALE) for x, u in zip(s, unknown)]
    return StartScales(scales=np.array(scales), settled=settled)


def _bound_scale(pair: tuple[float, float]) -> float:
    """The size a bound interval gives its component: its width if both ends are finite,
    else its largest finite end."""
    lo, hi = pair
    ends = [abs(v) for v in (lo, hi) if math.isfinite(v)]
    return hi - lo if len(ends) == 2 else max(ends)


def _size_by_motion(
    s: list[float],
    unknown: list[bool],
    t: list[float],
    given: Mapping[int, float],
    jacobian: Any = None,
) -> None:
    """Step 2 of the module docstring, in place: the components of unknown size that move
    get ``|t_i| / r``, ``r`` the median relative rate of the components of known size.

    A tangent component below 1e-12 of the largest moves too if the Jacobian (``jacobian()``,
    if given) shows it taking part in an equation (:func:`_moving_in_equations`): a
    concentration of 1e-9 mol beside a population of 1e6 moves at 1e-15 of its rate."""
    tmax = max(t)
    moving = [ti > 1e-12 * tmax for ti in t]  # below rounding of the largest: not moving
    faint = [i for i, ti in enumerate(t) if unknown[i] and 0.0 < ti and not moving[i]]
    if faint and jacobian is not None:
        for i in _moving_in_equations(jacobian(), t, faint):
            moving[i] = True
    rates = sorted(t[i] / s[i] for i in range(len(s)) if not unknown[i] and moving[i])
    if not rates:
        return
    half = len(rates) // 2
    rate = rates[half] if len(rates) % 2 else 0.5 * (rates[half - 1] + rates[half])
    if not (0.0 < rate < math.inf):
        return
    for i in range(len(s)):
        if unknown[i] and moving[i] and i not in given:
            s[i] = t[i] / rate
            unknown[i] = False


def _moving_in_equations(jacobian: Any, t: list[float], candidates: list[int]) -> list[int]:
    """The ``candidates`` whose tangent term ``|∂G_r/∂z_i|·|t_i|`` in some equation ``G_r``
    is above 1000 ε of that equation's terms ``T_r = Σ_j |∂G_r/∂z_j|·|t_j|`` and balanced by
    the others (at most twice their sum: along the tangent the terms cancel, which a term
    made of rounding noise alone does not)."""
    level = 1000.0 * float(np.finfo(float).eps)
    mags = np.asarray(t)
    a = abs(sp.csc_matrix(jacobian)) if sp.issparse(jacobian) else None
    if a is None:
        a = sp.csc_matrix(np.abs(np.asarray(jacobian, dtype=float)))
    terms = np.asarray(a @ mags).ravel()
    out = []
    for i in candidates:
        rows = a.indices[a.indptr[i] : a.indptr[i + 1]]
        own = a.data[a.indptr[i] : a.indptr[i + 1]] * mags[i]
        total = terms[rows]
        if bool(np.any((own > level * total) & (own <= 2.0 * (total - own)))):
            out.append(i)
    return out


def _at_rounding_level(jacobian: Any, magnitudes: list[float]) -> list[int]:
    """The components whose contribution ``|∂G_r/∂z_i|·|z_i|`` to every equation they enter
    is below 1000 ε of that equation's terms ``Σ_j |∂G_r/∂z_j|·|z_j|``."""
    level = 1000.0 * float(np.finfo(float).eps)
    mags = np.asarray(magnitudes)
    a = abs(sp.csc_matrix(jacobian)) if sp.issparse(jacobian) else None
    if a is None:
        rows = np.abs(np.asarray(jacobian, dtype=float)).tolist()
        terms = [sum(x * m for x, m in zip(r, magnitudes)) for r in rows]
        out = []
        for i, m in enumerate(magnitudes):
            col = [(r[i], tr) for r, tr in zip(rows, terms) if r[i] > 0.0]
            if m > 0.0 and col and all(x * m <= level * tr for x, tr in col):
                out.append(i)
        return out
    sizes = np.asarray(a @ mags).ravel()
    found = []
    for i, m in enumerate(magnitudes):
        rows_i = a.indices[a.indptr[i] : a.indptr[i + 1]]
        vals = a.data[a.indptr[i] : a.indptr[i + 1]]
        if m > 0.0 and rows_i.size and bool(np.all(vals * m <= level * sizes[rows_i])):
            found.append(i)
    return found


__all__ = [
    "GROWTH",
    "MAX_SCALE",
    "StartScales",
    "diverged",
    "given_scales",
    "grown_scales",
    "out_of_range",
    "start_scales",
]
