"""The catalogue of derivations: every record, in paper order, and look-up by equation id.

Equation ids are the paper's numbers ("9", "12", ...) plus three ids for Section 4: ``"MD"``
(Mindlin-Deresiewicz force F'_T along AB), ``"AB"`` (the slip g'_T along AB) and ``"32"``
(the total slipped area along AB). Ids of the form ``"12 (reading b)"`` are alternative
readings of a garbled printed formula; they are expected to disagree.
"""

from __future__ import annotations

import functools

from .common import Derivation
from .exponential import exponential_derivations
from .smooth import smooth_derivations

#: the paper's order; alternative readings follow the equation they read
_ORDER: tuple[str, ...] = ("9", "10", "12 (x)", "12 (slip)", "12", "15", "18", "19", "20")
_ORDER += ("21", "22", "25", "26", "27", "28", "29", "30", "31", "MD", "AB", "32")


@functools.lru_cache(maxsize=1)
def _all() -> tuple[Derivation, ...]:
    return tuple(exponential_derivations() + smooth_derivations())


def derive_all() -> list[Derivation]:
    """All derivations, in paper order (computed once per process, ~seconds)."""
    recs = _all()
    key = {eq: i for i, eq in enumerate(_ORDER)}
    return sorted(
        recs, key=lambda rec: (key.get(rec.equation.split(" (reading")[0], 99), rec.equation)
    )


def derivation(equation: str) -> Derivation:
    """The derivation with this id (e.g. ``"12"``)."""
    for rec in _all():
        if rec.equation == equation:
            return rec
    known = ", ".join(rec.equation for rec in _all())
    raise KeyError(f"no derivation for equation {equation!r}; known: {known}")
