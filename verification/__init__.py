"""The verification layer: the paper's closed forms derived with sympy from their defining
integrals, compared with the printed formulas and with the float implementation in
:mod:`cusp.models`. Importing it loads sympy (``import cusp.models`` does not).

Every closed form is *derived*, never typed in: sympy integrates the Greenwood-Williamson
integrals (Eqs 7, 8, 10, 11, 13, 14) with the exponential density (Eq 1), the
Cattaneo-Mindlin tractions of spheres (Eqs 17-18, 20) and cylinders (Eqs 24-25, 27), and
solves the resulting relations. Each result is a :class:`Derivation` holding the paper's
formula as we read it (``docs/verification.md``), the derived expression, and how they are
to be compared; :func:`check_printed` gives the verdict and
:func:`check_implementation` compares the derived expression, evaluated with mpmath at high
precision, with the float code in ``models``.

One module per job:

- :mod:`~cusp.verification.common`: the sympy symbols (:data:`SYMBOLS`), the records
  (:class:`Derivation`, :class:`PrintedVerdict`, :class:`ImplementationVerdict`);
- :mod:`~cusp.verification.exponential`: the rough surface with exponential heights
  (Sec. 2, Eqs 9-15) and its contact-loss path (Sec. 4: :func:`contact_loss_path`, ids
  ``"MD"``, ``"AB"``, ``"32"``; the events of its manifold: :func:`manifold_events`);
- :mod:`~cusp.verification.smooth`: sphere, cylinder and flat planes (Sec. 3, Eqs 18-31);
- :mod:`~cusp.verification.sphere_energy`: the sphere's released energies in closed form,
  written in the small differences between the levels of A, B, C, D
  (:func:`sphere_released_areas`), and their identity with the loop integrals;
- :mod:`~cusp.verification.catalogue`: all records in paper order (:func:`derive_all`,
  :func:`derivation`);
- :mod:`~cusp.verification.printed`: printed against derived (:func:`check_printed`);
- :mod:`~cusp.verification.implementation`: derived against the float models
  (:func:`exact_value`, :func:`check_implementation`);
- :mod:`~cusp.verification.oracles`: independent references of the whole contact-loss path,
  the test oracles of the models (the exponential closed forms evaluated exactly, the
  Gaussian and sphere paths in mpmath).

Equation ids are the paper's numbers ("9", "12", ...) plus ``"MD"``, ``"AB"`` and ``"32"``
for Section 4; ids of the form ``"12 (reading b)"`` are alternative readings of a garbled
printed formula, expected to disagree.
"""

from .catalogue import derivation, derive_all
from .common import SYMBOLS, Derivation, ImplementationVerdict, PrintedVerdict
from .exponential import contact_loss_path, manifold_events
from .implementation import (
    FT_HAT_EXTREMES,
    FT_HAT_INTERIOR,
    IMPLEMENTATION_RTOL,
    check_implementation,
    exact_value,
)
from .printed import check_printed
from .sphere_energy import sphere_released_areas

__all__ = [
    "Derivation",
    "PrintedVerdict",
    "ImplementationVerdict",
    "derive_all",
    "derivation",
    "check_printed",
    "check_implementation",
    "SYMBOLS",
    "FT_HAT_EXTREMES",
    "FT_HAT_INTERIOR",
    "IMPLEMENTATION_RTOL",
    "exact_value",
    "contact_loss_path",
    "manifold_events",
    "sphere_released_areas",
]
