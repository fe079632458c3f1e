"""The folds of a contact-loss path (:meth:`cusp.models.ContactLoss.run`): the corners A and
B, where the controls g_T (snap-back) and F_T (snap-through) turn, and the turning points the
tracer located inside a leg (g_T, F_T and Â_SL are monitored).

A turning point of Â_SL on a leg along which Â_SL varies by less than the solver resolves
(``resolution``, absolute: Â_SL is a fraction of order one) is rounding noise, not a fold,
and is left out, as is one of any component flat to rounding along its leg
(:func:`~cusp.models._path_guards.flat`): at F_N0 = 1e9 N on the Gaussian scene the slipped
area is e^{−1.6e6} on OA (every summit sticks; d is 1800 σ* below the mean plane) and its
noise was reported as dozens of turning points.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ._path_guards import flat

__all__ = ["path_folds"]

_KINDS = {"g": ("snap-back", "g_T"), "t": ("snap-through", "F_T")}
_NAMES = {"g": "g_T", "t": "F_T", "m": "F_N", "A_SL": "A_SL"}


def _derivatives(br, row: int) -> dict[str, float]:
    """Tangent components (oriented along the direction of travel) at a row of a leg."""
    return dict(zip(br.variables, map(float, br.tangents[row])))


def _corners(legs, points) -> list[dict[str, Any]]:
    out: list[dict[str, Any]] = []
    for point, before, after in (("A", "OA", "AB"), ("B", "AB", "BC")):
        t_before = _derivatives(legs[before], -1)
        t_after = _derivatives(legs[after], 0)
        for var, (kind, control) in _KINDS.items():
            if t_before[var] * t_after[var] < 0.0:
                out.append(
                    {
                        "kind": kind,
                        "control": control,
                        "point": point,
                        "corner": True,
                        "values": points[point],
                        "direction_before": "increasing" if t_before[var] > 0 else "decreasing",
                        "direction_after": "increasing" if t_after[var] > 0 else "decreasing",
                    }
                )
    return out


def path_folds(
    legs, points, physical: Callable[[dict[str, float]], dict[str, float]], resolution: float
) -> list[dict[str, Any]]:
    """The corners and the turning points of the legs (module docstring); ``physical``
    converts a leg's point to physical units."""
    out = _corners(legs, points)
    for leg, br in legs.items():
        a_sl = np.asarray(br["A_SL"], dtype=float)
        flat_a_sl = float(np.ptp(a_sl)) <= resolution * max(1.0, float(np.max(np.abs(a_sl))))
        for sp in br.special("fold"):
            wrt = sp.with_respect_to
            if (wrt == "A_SL" and flat_a_sl) or flat(br, wrt):
                continue  # sign changes of a tangent component that is rounding noise
            label = _KINDS.get(wrt, ("turning point", _NAMES.get(wrt, wrt)))
            out.append(
                {
                    "kind": label[0],
                    "control": label[1],
                    "point": None,
                    "corner": False,
                    "leg": leg,
                    "status": sp.status,
                    "values": physical(sp.values),
                }
            )
    return out
