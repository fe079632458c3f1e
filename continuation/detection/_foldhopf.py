"""The dynamic codimension-2 points of a fold curve (``fold_curve(..., stability=True)``),
for a problem declared a vector field ``M u' = R(u, p)``:

- **Bogdanov–Takens** (``"bogdanov_takens"``): the fold's zero eigenvalue becomes double
  with one eigenvector (a Jordan block). The test is ``⟨w, M v⟩`` with ``v``, ``w`` the
  right and left null vectors of ``A`` the fold curve's bordered system gives (normalised
  by its borders): at a simple zero eigenvalue ``⟨w, M v⟩ ≠ 0``, at a Jordan block it
  vanishes (MatCont's test on limit-point curves). The determinant test of the fold curve
  (:class:`~._cusp.Codim2Test`) does not see it: with borders refreshed to the null
  vectors its sign stays.
- **zero-Hopf** (``"zero_hopf"``, fold–Hopf): a complex pair crosses the imaginary axis
  beside the zero eigenvalue. The test is ``∏_{i<j} (λ_i + λ_j)`` over the eigenvalues of
  ``(A, M)`` other than the one nearest 0 (:func:`~._eigen.spectrum`: all of them for
  dense problems, the ``nev`` nearest the shift for sparse ones), real (the factors of a
  conjugate pair multiply to ``|·|²``), as a sign and a magnitude relative to its size at
  the fold curve's start. It also vanishes at a real pair ``λ, −λ`` (a neutral saddle):
  such a zero is not reported (returned as no zero, like a pole).

Each is located by regula falsi on the curve's arc (:meth:`~._tests.TestFunction.locate`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .._options import StabilityOptions
from .._outcomes import Kind, PointStatus
from ._bracket import Bracket, Located
from ._eigen import REAL_TOL, spectrum
from ._tests import TestFunction


class BogdanovTakensTest(TestFunction):
    """``⟨w, M v⟩`` of the fold's null vectors: it vanishes at a Bogdanov–Takens point."""

    __slots__ = ("mass",)
    kind = Kind.BOGDANOV_TAKENS

    def __init__(self, mass: Any) -> None:
        super().__init__("bogdanov_takens")
        self.mass = mass

    def value(self, system: Any, z: np.ndarray, t: Any, sdet: Any) -> float:
        _, v, w, _, _ = system.bordered_solve(z)
        mv = v if self.mass is None else self.mass @ v
        return float(w @ mv) / float(np.linalg.norm(w) * np.linalg.norm(v))


class ZeroHopfTest(TestFunction):
    """``∏_{i<j}(λ_i + λ_j)`` over the eigenvalues beside the fold's zero one, relative to
    its size at the curve's start (see the module)."""

    __slots__ = ("mass", "options", "log0")
    kind = Kind.ZERO_HOPF

    def __init__(self, mass: Any, options: StabilityOptions) -> None:
        super().__init__("zero_hopf")
        self.mass = mass
        self.options = options
        self.log0: float | None = None

    def eigenvalues(self, system: Any, z: np.ndarray) -> np.ndarray:
        """The eigenvalues of ``(A, M)`` at ``z`` without the one nearest 0."""
        _, _, _, _, df = system.bordered_solve(z)
        n = system.n
        jac = df[:, :n]
        o = self.options
        lam = spectrum(
            jac, self.mass, nev=o.nev, dense_limit=o.dense_limit, shift=o.shift, verify=False
        ).values
        return np.delete(lam, int(np.argmin(np.abs(lam))))

    def value(self, system: Any, z: np.ndarray, t: Any, sdet: Any) -> float:
        lam = self.eigenvalues(system, z)
        i, j = np.triu_indices(lam.size, k=1)
        sums = lam[i] + lam[j]
        if np.any(sums == 0.0):
            return 0.0
        real = np.abs(sums.imag) <= REAL_TOL * np.maximum(1.0, np.abs(sums))
        sign = -1.0 if np.count_nonzero(sums[real].real < 0.0) % 2 else 1.0
        log = float(np.sum(np.log(np.abs(sums))))
        if self.log0 is None:
            self.log0 = log  # (the first value: the curve's start)
        return sign * float(np.exp(min(log - self.log0, 700.0)))

    def locate(self, br: Bracket, f_a: float, f_b: float) -> Located:
        found = super().locate(br, f_a, f_b)
        lam = self.eigenvalues(br.system, found.z)
        upper = lam[lam.imag > REAL_TOL * np.maximum(1.0, np.abs(lam))]
        if upper.size == 0 or np.min(np.abs(upper.real)) > 1e-6 * np.max(np.abs(upper)):
            # the zero is that of a real pair λ, −λ (a neutral saddle): no special point
            details = {**found.details, "neutral_saddle": True}
            return found._replace(status=PointStatus.POLE, details=details)
        k = int(np.argmin(np.abs(upper.real)))
        return found._replace(details={**found.details, "omega": float(upper[k].imag)})


__all__ = ["BogdanovTakensTest", "ZeroHopfTest"]
