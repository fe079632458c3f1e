"""The contact-loss path O→A→B→C (Sec. 4, Figs 6–8), traced by the continuation solver.

Loading protocol (docs/physics.md §7):

* O→A: normal load held at F_N0, tangential slip g_T raised from 0 to g_A;
* A→B: normal load reduced to F'_N with the Mindlin–Deresiewicz rule F'_T = F_A − μΔF_N;
* B→C: F'_N held, the tangential force raised again until F_T = F_A (C); D is the point of
  this reloading curve at g_T = g_A.

Under displacement control the path snaps back from A to D (releasing the area ABD), under
force control it snaps through from A to C (area ABC). If F_A ≥ μF'_N there is no C: force
control ends in gross sliding.

Formulation
-----------
A body is described by two levels: the contact level p and the stick level q (for a rough
surface the mean-plane separation d and the stick-threshold level d0 = d + g_N0, in units of
σ*; for a sphere 1 − a/a0 and 1 − c/a0, a and c the contact and stick radii and a0 the
Hertz radius at F_N0, measured from a0 so that a − c keeps its digits at small slips). In
these the equilibrium of the contact reads, for every state on the path,

* normal equilibrium        log1p(−m) = ℓ(p), m = 1 − F_N/F_N0 (Eq 11; Hertz for a sphere)
* tangential equilibrium    F_T/(μF_N) = F̂_T(p, q)            (Eq 9; Eq 19)
* compliance                g_T = μ s(p, q)                     (Eqs 4–5; Eq 2)
* slipped area              Â_SL = (1 − Â_ST(p, q)) + ΔA_r/A_r (Eq 32)

The body supplies ℓ, F̂_T, s, Â_ST and A_r(p)/A_r(p0), with their derivatives, through the
protocol of :mod:`cusp.models.protocol` (``body.contact_levels(F_N0, g_A)`` returns a
:class:`~cusp.models.protocol.ContactLevels`); this module knows no body by name. The
exponential surface's levels are in :mod:`cusp.models.exponential`, those of any other
height density in :mod:`cusp.models.rough`, the sphere's in :mod:`cusp.models.sphere`.

plus one constraint for the leg: m = 0 (OA), the frozen stick zone q = q_A (AB) or m = m_B
(BC). Mindlin and Deresiewicz freeze the stick zone of every asperity while the
tractions are removed from the lost annulus; summed over the contact this is their rule
F'_T = F_A − μΔF_N (μF_N − F_T = μ K J(d0) for a rough surface, μ(4E*/3R*)c³ for a sphere,
is kept). The frozen-level form is the residual because it stays well conditioned when F̂_T(A)
is within rounding of 1, where F_T no longer resolves q; the force form is checked on every
traced row in the tests. Each leg is a :class:`cusp.continuation.Problem` in the unknowns

    g = g_T/g_A,  t = F_T/(μ0 F_N0),  m = 1 − F_N/F_N0,  A_SL,  p,  q

(μ0 the friction coefficient of the body; μ a parameter ``mu``), the control of the leg as
the free parameter: g on OA, the reduction m on AB (0 to m_B), g on BC. Order-one unknowns
make the arclength metric meaningful (F_T in N and g_T in µm differ by 10³); the reduction m,
not F_N/F_N0, keeps a tiny reduction's digits: m_B = (F_N0 − F'_N)/F_N0 is exact where
F'_N ≥ F_N0/2 (Sterbenz), rounded once otherwise; F_N = F_N0 (1 − m).

The released energies are the areas between the legs, ∫ (F_AB − F_BC) dg over [g_B, g_A]
(ABD) plus ∫ (F_A − F_BC) dg over [g_A, g_C] (ABC − ABD). On AB the stick level is frozen
and on BC the contact level is fixed by F'_N, so between the traced points each leg is an
explicit curve in its other level: Gauss–Legendre in g, the level at each node found from g
by safeguarded Newton (:mod:`cusp.models._loci_energy`, shared with the loci of
:mod:`cusp.models.manifold`), nodes doubled until two rules agree to the options'
``quad_tol`` (1e-13 relative at the default ``rtol``), the points first Newton-polished to
rounding. The error bound adds the rounding of the gap and of the points (the area shrinks
like ΔF_N², the rounding like ΔF_N: a message beyond 1e-8). The options' ``rtol`` sets the
accuracy of everything else too: the legs' steps and Newton tolerances, and the points A,
B, C, D, polished on their legs to the options' ``step_tol``; their other settings
(``ds_max`` = 0.05, ...) are the path's own.
No closed form is evaluated to trace the path; those of the exponential surface
(docs/physics.md §7) are test oracles only.

Â_SL (Eq 32): ``"printed"`` (default) normalises Â_ST by the current real contact area, as
printed, so Â_SL = (1 − A_ST/A'_r) + (A_r − A'_r)/A_r; ``"consistent"`` measures the stick
area against the area before the reduction, Â_SL = 1 − A_ST/A_r. They agree on OA.

Units: lengths µm, forces N, energies N·µm (= µJ).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from cusp.continuation import Branch, ContinuationOptions, Problem, point_tol, points_at

from . import _path_guards as guards
from ._loci_energy import path_energies, path_points
from ._path_folds import path_folds
from ._path_guards import PathError
from ._path_records import (
    VARIABLES,
    gross_sliding_messages,
    leg_stats,
    physical_point,
    point_rows,
    to_physical,
)
from ._point_errors import point_bounds, point_messages, underflow_messages
from .errors import ModelParameterError, check_positive
from .protocol import (
    ContactLevels,
    PathBody,
    require_levels,
    require_path_body,
    slipped_area,
    stick_bounds,
)

__all__ = [
    "ContactLoss",
    "ContactLossResult",
    "PathError",
    "AREA_READINGS",
    "VARIABLES",
    "LEG_CONTROLS",
]

#: leg -> its control (the free parameter of the leg problem)
LEG_CONTROLS = {"OA": "g", "AB": "m", "BC": "g"}
_MEMO = 4  # evaluations a leg's problem keeps (its latest points)
AREA_READINGS = ("printed", "consistent")

#: default solver settings for the legs (nondimensional arclength; the default ``rtol``)
DEFAULT_OPTIONS = ContinuationOptions(ds=0.02, ds_max=0.05)


# ------------------------------------------------------------------------------------------
# Results


@dataclass(frozen=True)
class ContactLossResult:
    """Outcome of :meth:`ContactLoss.run`.

    Parameters
    ----------
    points : dict of str to dict of str to float or None
        ``"O"`` … ``"D"`` → ``{"g_T" [µm], "F_T" [N], "F_N" [N], "A_SL", the two levels
        (d, d0 or a, c [µm])}``, or None for a point that does not exist.
    energy, energy_error : dict of str to float or None
        ``snap_back`` (area ABD) and ``snap_through`` (area ABC) [N·µm] and their error
        bounds [N·µm], None when the landing point does not exist.
    folds : list of dict
        Turning points of the controls g_T (snap-back) and F_T (snap-through) along the
        path (the corners A and B, and any smooth fold located inside a leg).
    legs : dict of str to Branch
        The traced legs ``"OA"``, ``"AB"``, ``"BC"`` (nondimensional, see the module).
    gross_sliding : dict of str to bool
        Which control ends in gross sliding.
    messages : list of str
        What the path has to say (gross sliding, underflow, error bounds above 1e-12).
    level_names : tuple of (str, str)
        The names of the two levels (``("d", "d0")`` or ``("a", "c")``).
    scales : dict of str to float
        The scales of the nondimensional variables (µm, N).
    problems, point_rows, stats : dict, optional
        Per leg: its problem, its work (``stats``: points, Newton iterations, rejected
        steps); ``point_rows``: where each named point is a row of the legs.
    levels : ContactLevels, optional
        The body's levels (:meth:`PathBody.contact_levels`).
    point_errors : dict of str to dict of str to float, optional
        Bounds on the absolute errors of the points' quantities, in their units.
    """

    points: dict[str, dict[str, float] | None]
    energy: dict[str, float | None]
    energy_error: dict[str, float | None]
    folds: list[dict[str, Any]]
    legs: dict[str, Branch]
    gross_sliding: dict[str, bool]
    messages: list[str]
    level_names: tuple[str, str]
    scales: dict[str, float]
    problems: dict[str, Problem] = field(default_factory=dict)
    point_rows: dict[str, tuple[str, int]] = field(default_factory=dict)
    stats: dict[str, dict[str, Any]] = field(default_factory=dict)
    levels: Any = None
    point_errors: dict[str, dict[str, float]] = field(default_factory=dict)

    def path(self, leg: str | None = None) -> dict[str, np.ndarray]:
        """Return the physical columns along the whole path (or one leg).

        Consecutive legs share their junction point, which appears once in each leg.

        Parameters
        ----------
        leg : {"OA", "AB", "BC"}, optional
            One leg (default: all).

        Returns
        -------
        dict of str to numpy.ndarray
            g_T [µm], F_T [N], F_N [N], A_SL, the two levels [µm] and a ``leg`` label.
        """
        legs = [leg] if leg is not None else list(self.legs)
        parts = [self._physical(self.legs[name]) for name in legs]
        out = {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}
        out["leg"] = np.concatenate([np.full(len(self.legs[name]), name) for name in legs])
        return out

    def dense(self, leg: str, points: int = 100) -> dict[str, np.ndarray]:
        """Return the physical columns of one leg at evenly spread values of its control.

        Each is corrected onto the branch (:func:`cusp.continuation.points_at`): exact at
        every point whatever the step sizes were.

        Parameters
        ----------
        leg : {"OA", "AB", "BC"}
            The leg.
        points : int, optional
            The number of points (default 100).

        Returns
        -------
        dict of str to numpy.ndarray, each shape (points,)
            g_T [µm], F_T [N], F_N [N], A_SL and the two levels [µm].
        """
        br = self.legs[leg]
        control = LEG_CONTROLS[leg]
        ends = br[control][[0, -1]]
        values = np.linspace(ends[0], ends[1], points)
        return self._physical(points_at(self.problems[leg], br, control, values))

    def _physical(self, columns) -> dict[str, np.ndarray]:
        return to_physical(columns, self.scales, self.level_names, self.levels)


# ------------------------------------------------------------------------------------------
# The model


class ContactLoss:
    """The contact-loss loading path O→A→B→C (and D) of a body.

    Parameters
    ----------
    body : PathBody
        A rough surface, sphere, or any body that follows the protocol: an
        :class:`~cusp.models.ExponentialRoughSurface`,
        :class:`~cusp.models.GaussianRoughSurface`,
        :class:`~cusp.models.GeneralRoughSurface` (these two need the load scale: E, radius,
        density, nominal_area), a :class:`~cusp.models.Sphere` with all four parameters, or
        a body of your own. Cylinders and flat planes raise
        :class:`~cusp.models.NoComplianceLawError` (no compliance law); an object that does
        not follow the protocol raises :class:`~cusp.models.ModelParameterError`.
    normal_load : float
        F_N0 [N], held on OA.
    max_slip : float
        g_A [µm], the slip at A.
    reduced_normal_load : float
        F'_N [N] at B, with F_N0 − F_A/μ ≤ F'_N < F_N0 (deeper reductions would make F'_T
        negative).
    area_reading : {"printed", "consistent"}, optional
        Eq 32 as printed (default) or consistent (see the module docstring). A value out of
        range raises :class:`~cusp.models.ModelParameterError` naming it.
    """

    def __init__(
        self,
        body: PathBody,
        normal_load: float,
        max_slip: float,
        reduced_normal_load: float,
        *,
        area_reading: str = "printed",
    ) -> None:
        self.F_N0 = check_positive("normal_load", normal_load, "N")
        self.g_A = check_positive("max_slip", max_slip, "µm")
        self.F_Np = check_positive("reduced_normal_load", reduced_normal_load, "N")
        self.m_B = (self.F_N0 - self.F_Np) / self.F_N0
        if area_reading not in AREA_READINGS:
            raise ModelParameterError(
                f"area_reading must be one of {AREA_READINGS}, got {area_reading!r}"
            )
        self.area_reading = area_reading
        self.body: PathBody = require_path_body(body)
        self.levels: ContactLevels = require_levels(body.contact_levels(self.F_N0, self.g_A), body)
        self.mu0 = check_positive("mu", body.mu)
        if self.F_Np >= self.F_N0:
            raise ModelParameterError(
                f"reduced_normal_load must be < normal_load = {self.F_N0!r} N (a reduction), "
                f"got {self.F_Np!r} N"
            )
        g_lim = self.mu0 * self.levels.slip_limit(self.levels.p0)
        if self.g_A >= g_lim:
            raise ModelParameterError(
                f"max_slip must be < {g_lim!r} µm, the slip at which this body slides under "
                f"normal_load = {self.F_N0!r} N (gross sliding, no point A), got {self.g_A!r} µm"
            )
        # F_A from the loading curve, only to validate the reduction (the path is traced)
        F_A = float(body.tangential_force(self.g_A, self.F_N0))
        if not 0.0 <= F_A < math.inf:
            raise ModelParameterError(
                f"max_slip = {self.g_A!r} µm and normal_load = {self.F_N0!r} N are beyond what "
                f"this body represents in floating point: its tangential force at A is F_A = "
                f"{F_A!r} N (its contact integrals leave the float range); allowed: a body and "
                f"loading whose F_A is a finite number"
            )
        empty = guards.empty_range(self, F_A, g_lim)
        if empty is not None:
            raise ModelParameterError(empty)
        floor = self.F_N0 - F_A / self.mu0
        # (a reduction a rounding below the floor, F'_T = 0 located on a locus and evaluated
        # again here, is the floor: F'_T is 0 to rounding there, which the path takes)
        if guards.refused_reduction(self, F_A, self.F_Np):
            raise ModelParameterError(
                f"reduced_normal_load = {self.F_Np!r} N is too deep: F'_T = F_A - mu*dF_N = "
                f"{F_A - self.mu0 * (self.F_N0 - self.F_Np)!r} N would be negative; allowed: "
                f"{floor!r} N <= reduced_normal_load < {self.F_N0!r} N"
            )
        self.scales = {
            "g": self.g_A,
            "t": self.mu0 * self.F_N0,
            "F_N": self.F_N0,
            "level": self.levels.scale,
        }

    # -------------------------------------------------------------- residual and Jacobian
    def _equations(self, x, mu: float, leg: str, consts) -> tuple[np.ndarray, np.ndarray]:
        """Residual (5) and its derivatives with respect to (g, t, m, A_SL, p, q, mu)."""
        g, t, red, a_sl, p, q = x
        n = 1.0 - red  # F_N/F_N0
        L = self.levels
        ell, dell = L.log_normal_load(p)
        F, dF_p, dF_q = L.tangential_ratio(p, q)
        s, ds_p, ds_q = L.slip(p, q)
        a, da_p, da_q = slipped_area(L, p, q, self.area_reading)
        k = self.mu0 / mu
        m = mu / self.g_A
        R = np.empty(5)
        J = np.zeros((5, 7))
        if leg == "OA":  # F_N = F_N0 (m = 0 below): the contact level is p0, exactly (a
            # level of rounding noise made Â_SL, 0 to 1e-700000 at F_N0 = 1e9 N, turn 50 times)
            R[0] = p - L.p0
            J[0, 4] = 1.0
        else:  # (a trial point may have m >= 1: non-finite, its step is shortened)
            R[0] = (math.log1p(-red) if red < 1.0 else math.nan) - ell
            J[0, 2] = -1.0 / n
            J[0, 4] = -dell
        R[1] = k * t - n * F
        J[1, 1] = k
        J[1, 2] = F
        J[1, 4] = -n * dF_p
        J[1, 5] = -n * dF_q
        J[1, 6] = -k * t / mu
        R[2] = g - m * s
        J[2, 0] = 1.0
        J[2, 4] = -m * ds_p
        J[2, 5] = -m * ds_q
        J[2, 6] = -s / self.g_A
        R[3] = a_sl - a  # Eq 32 (protocol.slipped_area: without cancellation where it can)
        J[3, 3] = 1.0
        J[3, 4] = -da_p
        J[3, 5] = -da_q
        if leg == "OA":
            R[4] = red
            J[4, 2] = 1.0
        elif leg == "AB":
            R[4] = q - consts  # the stick zone is frozen (Mindlin-Deresiewicz)
            J[4, 5] = 1.0
        else:
            R[4] = red - consts
            J[4, 2] = 1.0
        return R, J

    def problem(
        self, leg: str, *, start: float, constant: float | None = None, mu: float | None = None
    ) -> Problem:
        """Return the continuation problem of one leg (nondimensional; see the module).

        Its parameters are the control, ``mu`` and the leg constant (``q_A`` or ``m_B``).

        Parameters
        ----------
        leg : {"OA", "AB", "BC"}
            The leg.
        start : float
            The value of the leg's control (:data:`LEG_CONTROLS`).
        constant : float, optional
            q_A (the stick level at A) on AB, m_B (1 − F'_N/F_N0) on BC.
        mu : float, optional
            The friction coefficient (default: the body's).

        Returns
        -------
        Problem
            The leg's equations with their exact derivatives.
        """
        if leg not in LEG_CONTROLS:
            raise ModelParameterError(f"leg must be one of {list(LEG_CONTROLS)}, got {leg!r}")
        control = LEG_CONTROLS[leg]
        ci = VARIABLES.index(control)
        unknowns = [v for v in VARIABLES if v != control]
        params = {control: float(start), "mu": self.mu0 if mu is None else float(mu)}
        const_name = {"OA": None, "AB": "q_A", "BC": "m_B"}[leg]
        if const_name is not None:
            if constant is None:
                raise ModelParameterError(f"leg {leg} needs constant={const_name}")
            params[const_name] = float(constant)
        cols = [i for i in range(6) if i != ci]

        # residual, Jacobian and parameter column come from one evaluation, kept for the
        # latest points by their bits (C and D share the reloading leg); callers get copies
        @functools.lru_cache(maxsize=_MEMO)
        def evaluated_at(bits: bytes, at: float, mu: float, c):
            x = list(np.frombuffer(bits))  # (the unknowns, float64 scalars, as np.insert
            x.insert(ci, np.float64(at))  # gave them, at a tenth of its cost)
            return self._equations(x, mu, leg, c)

        def evaluated(u, p):
            c = p[const_name] if const_name else None
            return evaluated_at(np.asarray(u, dtype=float).tobytes(), p[control], p["mu"], c)

        def residual(u, p):
            return evaluated(u, p)[0].copy()

        def jacobian(u, p):
            return evaluated(u, p)[1][:, cols]

        def param_jacobian(u, p, name):
            J = evaluated(u, p)[1]
            if name == control:
                return J[:, ci].copy()
            if name == "mu":
                return J[:, 6].copy()
            col = np.zeros(5)
            col[4] = -1.0  # d/d q_A (AB) and d/d m_B (BC) of the leg constraint
            return col

        return Problem(
            residual,
            unknowns,
            params,
            jacobian=jacobian,
            param_jacobian=param_jacobian,
            name=f"contact-loss leg {leg}",
        )

    # -------------------------------------------------------------- the path
    def run(self, options: ContinuationOptions | None = None) -> ContactLossResult:
        """Trace O→A→B→C (and D), locate the folds and integrate the released energies.

        Parameters
        ----------
        options : ContinuationOptions, optional
            Of the legs (default :data:`DEFAULT_OPTIONS`; for another accuracy,
            ``DEFAULT_OPTIONS.replace(rtol=...)``: its ``rtol`` sets the legs' tolerances,
            the polish of the points and the quadrature of the energies).

        Returns
        -------
        ContactLossResult
            The points, energies [N·µm], folds and legs.

        Raises
        ------
        PathError
            A leg could not be traced (the message says where and why).
        """
        o = options or DEFAULT_OPTIONS
        L = self.levels
        prob, oa, A = self._loading_leg(o)
        # A -> B: normal load reduced, Mindlin-Deresiewicz
        prob_ab = self.problem("AB", start=A["m"], constant=A["q"])
        ab = guards.trace_leg(
            self,
            "AB",
            prob_ab,
            [A[v] for v in prob_ab.unknowns],
            "F_N = reduced_normal_load",
            free="m",
            bounds={"m": (-math.inf, self.m_B)},
            monitor=["g", "t", "A_SL"],
            options=o,
        )
        B = guards.polish(self, "B", prob_ab, ab, "m", self.m_B, o)
        # B -> C: reloading at F'_N
        c_exists = A["t"] < 1.0 - self.m_B  # F_A < mu F'_N (t = F_T/(mu0 F_N0), mu = mu0)
        d_exists = self.mu0 * L.slip_limit(B["p"]) > self.g_A
        bounds: dict[str, tuple[float, float]] = {}
        targets = {}
        if c_exists:
            bounds["t"] = (-math.inf, A["t"])
            targets["g"] = [1.0]  # D, as a row of the branch
        elif d_exists:
            bounds["g"] = (-math.inf, 1.0)
        if math.isfinite(L.slip_limit(B["p"])):
            bounds["q"] = stick_bounds(L)  # e.g. a sphere: the stick zone vanishes at gross slip
        prob_bc = self.problem("BC", start=B["g"], constant=B["m"])
        what = "F_T = F_A (point C)" if c_exists else "g_T = max_slip (point D)"
        bc = guards.trace_leg(
            self,
            "BC",
            prob_bc,
            [B[v] for v in prob_bc.unknowns],
            what,
            partial=True,
            free="g",
            bounds=bounds,
            targets=targets,
            monitor=["t", "A_SL"],
            options=o,
        )
        C, D = self._reloading_points(prob_bc, bc, B, A["t"], (c_exists, d_exists), what, o)
        legs = {"OA": oa, "AB": ab, "BC": bc}
        problems = {"OA": prob, "AB": prob_ab, "BC": prob_bc}
        return self._result(legs, problems, {"A": A, "B": B, "C": C, "D": D}, o)

    def _result(self, legs, problems, named, o: ContinuationOptions) -> ContactLossResult:
        """The result of :meth:`run` from its traced legs and their named points (``named``:
        A, B, C, D nondimensional, None where missing): the points polished together and
        their error bounds (:mod:`._point_errors`), the energies, the folds, the messages."""
        L = self.levels
        c_exists, d_exists = named["C"] is not None, named["D"] is not None
        messages = gross_sliding_messages(self, named["A"]["t"], c_exists, d_exists)
        messages += guards.near_sliding_messages(self)
        _, row, errors = path_points(self, *(named[x] for x in "ABCD"))
        energy, error, notes = path_energies(self, row, errors, o.quad_tol)
        raw = {"O": legs["OA"].point(0)} | {
            x: None if pt is None else {v: row[f"{x}.{v}"] for v in VARIABLES}
            for x, pt in named.items()
        }
        points = {
            k: None if v is None else physical_point(v, self.scales, L.names, L)
            for k, v in raw.items()
        }
        point_err = {
            x: point_bounds(self, v, {k: errors[f"{x}.{k}"] for k in VARIABLES})
            for x, v in raw.items()
            if v is not None and x != "O"
        }
        floors = dict.fromkeys(L.names, float(L.scale))  # the levels: against their unit
        messages += point_messages(points, point_err, max(point_tol(o.rtol), 1e-12), floors)
        messages += underflow_messages(points)
        messages += notes
        return ContactLossResult(
            points=points,
            energy=energy,
            energy_error=error,
            folds=path_folds(legs, points, self._physical_point, 100.0 * o.step_tol),
            legs=legs,
            gross_sliding={"force_control": not c_exists, "displacement_control": not d_exists},
            messages=messages,
            level_names=L.names,
            scales=self.scales,
            problems=problems,
            point_rows=point_rows(legs, c_exists, d_exists),
            stats={name: leg_stats(br) for name, br in legs.items()},
            levels=L,
            point_errors=point_err,
        )

    def _physical_point(self, values: dict[str, float]) -> dict[str, float]:
        return physical_point(values, self.scales, self.levels.names, self.levels)

    def _loading_leg(self, o: ContinuationOptions) -> tuple[Problem, Branch, dict[str, float]]:
        """O -> A: the slip raised at F_N0; the leg's problem, branch and the point A.

        A body whose stick zone vanishes at a finite slip (a sphere: q = 1 at g_lim) has its
        loading curve turn there (g_T is largest at gross sliding): with g_A within a step of
        g_lim a step can cross g = 1 twice, past the fold, and the leg would run on along the
        unphysical side (c < 0) forever. The stick bound ends it at the fold; A is then found
        between the last row below g_A and the fold, where the slip is monotone in q
        (:func:`~cusp.models._path_guards.loading_end`)."""
        L = self.levels
        prob = self.problem("OA", start=0.0)
        bounds = {"g": (-math.inf, 1.0)}
        if math.isfinite(L.slip_limit(L.p0)):
            bounds["q"] = stick_bounds(L)
        oa = guards.trace_leg(
            self,
            "OA",
            prob,
            [0.0, 0.0, 0.0, L.p0, L.p0],
            "g_T = max_slip (point A)",
            free="g",
            bounds=bounds,
            # p stays at p0 (its first equation on OA is p = p0): sized 1, not by its start
            scales={"p": 1.0},
            monitor=["t", "A_SL"],
            options=o,
        )
        if guards.ended_at(oa) != "q":
            return prob, oa, guards.polish(self, "A", prob, oa, "g", 1.0, o)
        return prob, oa, guards.loading_end(self, oa)

    def _reloading_points(self, prob, bc, B, t_A: float, exist, what: str, o):
        """C and D (None where they do not exist) on the reloading leg ``bc``: polished on
        it, or, where the leg ended at gross sliding (the stick bound) or stopped short of
        them (:func:`~cusp.models._path_guards.leg_end`), explicit in the stick level."""
        c_exists, d_exists = exist
        ended = bc.status == "bound"
        if not ended and not c_exists:
            raise guards.stopped(self, "BC", bc, what)
        points: list[dict[str, float] | None] = []
        for name, var, value, wanted in (("C", "t", t_A, c_exists), ("D", "g", 1.0, d_exists)):
            reached = float(np.max(bc[var])) >= value
            if not wanted:
                points.append(None)
            elif name == "D" and guards.ended_at(bc) == "q":  # (at gross sliding, past D)
                points.append(guards.loading_end(self, bc, B["p"], B["m"]))
            elif ended or reached:
                points.append(guards.polish(self, name, prob, bc, var, value, o))
            else:
                try:
                    points.append(guards.leg_end(self, bc, B["p"], B["m"], var, value))
                except ArithmeticError as exc:
                    raise guards.stopped(self, "BC", bc, what) from exc
        return points[0], points[1]
