"""What a body must provide to follow the contact-loss path (:mod:`cusp.models.contact_loss`).

This module is the reference for adding a body. A body is any object with

* ``mu`` — its friction coefficient μ (> 0, dimensionless);
* ``tangential_force(g_T, F_N)`` — F_T [N] on its loading curve at slip g_T [µm] under the
  normal load F_N [N]. The path uses it only to check the depth of the reduction before
  tracing (F'_N ≥ F_N0 − F_A/μ); the traced path never calls it;
* ``contact_levels(normal_load, max_slip)`` — its :class:`ContactLevels` for the path with
  F_N0 = ``normal_load`` [N] and g_A = ``max_slip`` [µm]. A body without a compliance law
  raises :class:`~cusp.models.errors.NoComplianceLawError` here, saying what it lacks (the
  cylinder and the flat planes do, see :func:`no_compliance_law`).

That is :class:`PathBody`. The levels are two numbers that locate the state of the contact:
the contact level p and the stick level q (a rough surface: the mean-plane separation d and
the stick-threshold level d0 = d + g_N0, Eq 5; a sphere: the contact radius a and the stick
radius c, measured from a0 as below). In them the equilibrium of the contact is four
relations, the same on every leg of the path (μ the friction coefficient, F_N0 the normal
load on OA):

* normal equilibrium      log(F_N/F_N0) = ``log_normal_load(p)``    (Eq 11; Hertz for a sphere)
* tangential equilibrium  F_T/(μF_N) = ``tangential_ratio(p, q)``   (Eq 9; Eq 19)
* compliance              g_T = μ ``slip(p, q)``                     (Eqs 4–5; Eq 2)
* slipped area            Â_SL = (1 − ``stick_area(p, q)``) + (1 − ``area_ratio(p)``)  (Eq 32)

(the last line is the printed reading of Eq 32, ΔA_r/A_r = 1 − A'_r/A_r; the consistent
reading is Â_SL = 1 − ``area_ratio(p)`` · ``stick_area(p, q)``). The path adds one
constraint per leg: F_N = F_N0 on OA, q frozen at its value at A on AB (the
Mindlin–Deresiewicz rule: the stick zone of every asperity is kept while the tractions are
removed from the lost annulus), F_N = F'_N on BC.

Every relation is a method returning its value and its partial derivatives with respect to
the levels, ``(value, d/dp)`` or ``(value, d/dp, d/dq)``, at float arguments; the
derivatives enter the analytic Jacobian of the continuation problem, so they must be exact
(the tests of a body should compare them with finite differences). The levels are
nondimensional: ``scale`` [µm] converts them to lengths (the path reports p·scale and
q·scale in µm under the column names ``names``), and a good scale keeps q − p of order one
at A. Along the path p and q stay within the domain where the relations hold (for a body
that slides as a whole, ``slip_limit`` tells the path where the stick zone vanishes, at
q = 0 unless the levels say otherwise, below).

Two optional members let a body measure its levels from a reference, so that small
differences near it keep their digits (the sphere's levels are 1 − a/a0 and 1 − c/a0: at
small slips c, a and a0 agree to 1e-8 and more, and a − c must not be formed from them):

* ``lengths(p, q)`` — the levels as the lengths the path reports [µm] (arrays in, arrays
  out); without it, p·scale and q·scale;
* ``stick_bounds`` — (low, high), the range of q in which a stick zone exists; the end that
  is finite is the stick level of gross sliding. Without it, (0, inf).

Two optional members give the slipped area without cancellation, for a body whose Â_ST and
area ratio are within rounding of 1 at small slips or small reductions (the sphere's:
Â_ST = (c/a)² ≈ 1 − g_A/g_lim, so 1 − Â_ST formed from it keeps only ~ε over its size):

* ``slip_area(p, q)`` — 1 − Â_ST and its derivatives ``(value, d/dp, d/dq)``, the slipped
  share of the current real contact area, evaluated without forming Â_ST (the sphere's:
  (a² − c²)/a² from q − p);
* ``area_loss(p)`` — 1 − A_r(p)/A_r(p0) and d/dp, evaluated without forming the ratio.

With either, Â_SL is (1 − Â_ST) + (1 − A_r/A_r0) as printed and
(1 − A_r/A_r0) + (A_r/A_r0)(1 − Â_ST) in the consistent reading, a sum of the two
(:func:`slipped_area`); the member that is absent is formed as 1 − ``stick_area`` or
1 − ``area_ratio``. Without both, Â_SL is formed from ``stick_area`` and ``area_ratio`` as
above. The derivatives enter the Jacobian like the others, and must be exact.

One optional member gives the released energies in closed form, for a body whose legs are
explicit enough (the sphere's: polynomials in its levels):

* ``leg_areas(p_A, q_A, p_B, q_D, q_C, level_rtol)`` — the areas ABD and ABC − ABD as
  ∫ T ds between the legs [µm], T = exp(``log_normal_load``)·``tangential_ratio`` (F_T over
  μF_N0) and s = ``slip``, from the levels of the points A, B, D and C (``q_C`` NaN when
  there is no C), each with an error bound: ``((abd, abd_error), (abc_minus_abd, error))``,
  the second (NaN, NaN) without C. ``level_rtol`` is the points' own error (the tolerance
  they were converged to), relative to each level's own size; a ``leg_areas`` that takes
  the keyword ``errors`` is given the absolute errors of (p_A, q_A, p_B, q_D, q_C) instead
  (the bounds of the polished chain, :mod:`cusp.models._point_errors`), and ``quad_tol``
  where it integrates. Without it, the energies are
  integrated along the legs by Gauss–Legendre (:mod:`cusp.models._loci_energy`), whose
  accuracy is limited to about ε over the relative gap between the legs.

To add a body: write its module (the body class with ``mu``, ``tangential_force`` and
``contact_levels``, and its levels class), then register it with one line,
:func:`cusp.models.registry.register_body`, so that scenes can name it.

Units: lengths µm, forces N, energies N·µm.
"""

from __future__ import annotations

import math
from typing import Any, Protocol, runtime_checkable

import numpy as np

from .errors import ModelParameterError, NoComplianceLawError

__all__ = [
    "ContactLevels",
    "PathBody",
    "require_path_body",
    "require_levels",
    "no_compliance_law",
    "level_lengths",
    "stick_bounds",
    "sliding_level",
    "slipped_area",
    "RESERVED_COLUMNS",
]

#: column names of the path that the level names must not shadow
RESERVED_COLUMNS = ("g_T", "F_T", "F_N", "A_SL")


@runtime_checkable
class ContactLevels(Protocol):
    """The equilibrium of a body in its contact level p and stick level q (module docstring).

    Attributes
    ----------
    names : tuple of (str, str)
        The physical names of (p, q), e.g. ``("d", "d0")`` or ``("a", "c")``: the column
        names of the levels in the path's points, ``path()`` and ``branch.csv``.
    scale : float
        µm per unit of level: p·scale and q·scale are the levels as lengths [µm].
    p0 : float
        The contact level under the normal load F_N0 of the path, so that
        ``log_normal_load(p0) == 0``; the path starts at p = q = p0 (no slip, O).
    """

    names: tuple[str, str]
    scale: float
    p0: float

    def log_normal_load(self, p: float) -> tuple[float, float]:
        """Return ℓ(p) = log(F_N/F_N0) and dℓ/dp: the normal equilibrium.

        Eq 11 for a rough surface, the log of Hertz's F_N ∝ a³ for a sphere.

        Parameters
        ----------
        p : float
            The contact level (dimensionless; ``p·scale`` in µm).

        Returns
        -------
        value : float
            ℓ(p) (dimensionless).
        d_dp : float
            Its derivative in p.
        """
        ...

    def tangential_ratio(self, p: float, q: float) -> tuple[float, float, float]:
        """Return F̂_T = F_T/(μF_N) and its derivatives: the tangential equilibrium.

        Eq 9, 1 − J(d0)/J(d), for a rough surface; Eq 19, 1 − (c/a)³, for a sphere.

        Parameters
        ----------
        p : float
            The contact level (dimensionless; ``p·scale`` in µm).
        q : float
            The stick level (dimensionless; ``q·scale`` in µm).

        Returns
        -------
        value : float
            F̂_T (dimensionless, in [0, 1]; 0 at q = p: no slip).
        d_dp : float
            Its derivative in p.
        d_dq : float
            Its derivative in q.
        """
        ...

    def slip(self, p: float, q: float) -> tuple[float, float, float]:
        """Return s(p, q) with g_T = μ s, and its derivatives: the compliance law.

        Eqs 4–5, (λ/σ*)(d0 − d), for a rough surface; Eq 2 with Hertz, κ(a² − c²), for a
        sphere.

        Parameters
        ----------
        p : float
            The contact level (dimensionless; ``p·scale`` in µm).
        q : float
            The stick level (dimensionless; ``q·scale`` in µm).

        Returns
        -------
        value : float
            s [µm].
        d_dp : float
            Its derivative in p.
        d_dq : float
            Its derivative in q.
        """
        ...

    def stick_area(self, p: float, q: float) -> tuple[float, float, float]:
        """Return Â_ST = A_ST/A_r, the stick share of the real contact area, and derivatives.

        Eq 14 over Eq 13 for a rough surface; (c/a)² for a sphere.

        Parameters
        ----------
        p : float
            The contact level (dimensionless; ``p·scale`` in µm).
        q : float
            The stick level (dimensionless; ``q·scale`` in µm).

        Returns
        -------
        value : float
            Â_ST (dimensionless, in [0, 1]; 1 at q = p).
        d_dp : float
            Its derivative in p.
        d_dq : float
            Its derivative in q.
        """
        ...

    def area_ratio(self, p: float) -> tuple[float, float]:
        """Return A_r(p)/A_r(p0), the real contact area over the one under F_N0, and d/dp.

        It enters the slipped area of Eq 32 as ΔA_r/A_r = 1 − area_ratio.

        Parameters
        ----------
        p : float
            The contact level (dimensionless; ``p·scale`` in µm).

        Returns
        -------
        value : float
            A_r(p)/A_r(p0) (dimensionless).
        d_dp : float
            Its derivative in p.
        """
        ...

    def slip_limit(self, p: float) -> float:
        """Return s(p, q_slide), the slip at which the stick zone vanishes at level p.

        q_slide is the stick level of gross sliding (0, or the finite end of
        ``stick_bounds``): μ times the result is the slip g_T at which the body slides as a
        whole under that load (κ(a/a0)² for a sphere, Eq 2); inf if it never does at finite
        slip (a rough surface). The path refuses g_A ≥ μ·slip_limit(p0); when it is finite
        the reloading leg is bounded at q_slide (the stick zone gone).

        Parameters
        ----------
        p : float
            The contact level (dimensionless; ``p·scale`` in µm).

        Returns
        -------
        float
            s(p, q_slide) [µm], or inf.
        """
        ...


@runtime_checkable
class PathBody(Protocol):
    """A body that can follow the contact-loss path (module docstring).

    Its attribute ``mu`` is the friction coefficient μ > 0.
    """

    mu: Any

    def tangential_force(self, g_T: Any, F_N: Any) -> Any:
        """Return F_T on the loading curve.

        Parameters
        ----------
        g_T : array_like
            Tangential slip [µm].
        F_N : array_like
            Normal load [N].

        Returns
        -------
        numpy.ndarray
            F_T [N].
        """
        ...

    def contact_levels(self, normal_load: float, max_slip: float) -> ContactLevels:
        """Return the body's levels for the contact-loss path.

        Parameters
        ----------
        normal_load : float
            F_N0 [N].
        max_slip : float
            g_A [µm].

        Returns
        -------
        ContactLevels
            The levels.

        Raises
        ------
        NoComplianceLawError
            For a body without a compliance law.
        ModelParameterError
            For one missing a parameter the path needs.
        """
        ...


_BODY_MEMBERS = ("mu", "tangential_force", "contact_levels")
_LEVEL_MEMBERS = (
    "names",
    "scale",
    "p0",
    "log_normal_load",
    "tangential_ratio",
    "slip",
    "stick_area",
    "area_ratio",
    "slip_limit",
)


def level_lengths(levels: Any, p: Any, q: Any) -> tuple[np.ndarray, np.ndarray]:
    """The levels ``p``, ``q`` (arrays) as lengths [µm] (module docstring: a body's
    ``lengths``, else p·scale and q·scale)."""
    lengths = getattr(levels, "lengths", None)
    if lengths is not None:
        a, b = lengths(np.asarray(p, dtype=float), np.asarray(q, dtype=float))
        return np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return np.asarray(p, dtype=float) * levels.scale, np.asarray(q, dtype=float) * levels.scale


def stick_bounds(levels: Any) -> tuple[float, float]:
    """The range of the stick level q in which a stick zone exists (module docstring)."""
    lo, hi = getattr(levels, "stick_bounds", (0.0, math.inf))
    return float(lo), float(hi)


def sliding_level(levels: Any) -> float:
    """The stick level of gross sliding: the finite end of :func:`stick_bounds`."""
    lo, hi = stick_bounds(levels)
    return lo if math.isfinite(lo) else hi


def slipped_area(levels: Any, p: float, q: float, reading: str) -> tuple[float, float, float]:
    """Â_SL (Eq 32) at the levels ``p``, ``q`` and its derivatives in p and q, ``reading``
    ``"printed"`` or ``"consistent"`` (module docstring): from the body's ``slip_area`` and
    ``area_loss`` where it has them, else from ``stick_area`` and ``area_ratio``."""
    slip_area = getattr(levels, "slip_area", None)
    area_loss = getattr(levels, "area_loss", None)
    if slip_area is None and area_loss is None:
        ast, dast_p, dast_q = levels.stick_area(p, q)
        r, dr_p = levels.area_ratio(p)
        if reading == "printed":
            return 2.0 - ast - r, -(dast_p + dr_p), -dast_q
        return 1.0 - r * ast, -(dr_p * ast + r * dast_p), -r * dast_q
    if slip_area is not None:
        sa, dsa_p, dsa_q = slip_area(p, q)
    else:
        ast, dast_p, dast_q = levels.stick_area(p, q)
        sa, dsa_p, dsa_q = 1.0 - ast, -dast_p, -dast_q
    if area_loss is not None:
        al, dal_p = area_loss(p)
    else:
        r, dr_p = levels.area_ratio(p)
        al, dal_p = 1.0 - r, -dr_p
    if reading == "printed":
        return sa + al, dsa_p + dal_p, dsa_q
    r, dr_p = levels.area_ratio(p)
    return al + r * sa, dal_p + dr_p * sa + r * dsa_p, r * dsa_q


def require_path_body(body: object) -> PathBody:
    """``body`` if it satisfies :class:`PathBody`; else a ModelParameterError naming its type,
    what is missing and what the protocol requires."""
    if isinstance(body, PathBody):
        return body
    missing = [m for m in _BODY_MEMBERS if not hasattr(body, m)]
    raise ModelParameterError(
        f"body must follow the contact-loss protocol cusp.models.protocol.PathBody (attribute "
        f"mu, methods tangential_force(g_T, F_N) and contact_levels(normal_load, max_slip)), "
        f"got {type(body).__name__}, which lacks {', '.join(missing)}; a rough surface or a "
        f"Sphere follows it"
    )


def require_levels(levels: object, body: object) -> ContactLevels:
    """The levels ``body.contact_levels`` returned, if they satisfy :class:`ContactLevels`
    with two distinct level names that do not shadow a path column; else a
    ModelParameterError naming the body's type and what is wrong."""
    where = f"{type(body).__name__}.contact_levels() returned {type(levels).__name__}"
    if not isinstance(levels, ContactLevels):
        missing = [m for m in _LEVEL_MEMBERS if not hasattr(levels, m)]
        raise ModelParameterError(
            f"{where}, which lacks {', '.join(missing)}; it must follow "
            f"cusp.models.protocol.ContactLevels ({', '.join(_LEVEL_MEMBERS)})"
        )
    names = levels.names
    ok = (
        isinstance(names, tuple)
        and len(names) == 2
        and all(isinstance(n, str) and n for n in names)
        and names[0] != names[1]
        and not set(names) & set(RESERVED_COLUMNS)
    )
    if not ok:
        raise ModelParameterError(
            f"{where} with names = {names!r}; names must be two distinct non-empty strings "
            f"other than {', '.join(RESERVED_COLUMNS)}"
        )
    return levels


def no_compliance_law(name: str) -> NoComplianceLawError:
    """The error a body without a compliance law raises from ``contact_levels`` (``name``:
    the body's class name)."""
    return NoComplianceLawError(
        f"a {name} cannot follow the contact-loss path: the paper gives it no compliance "
        f"law (no load-displacement relation g_T(F_T, F_N)), so there is no O-A-B-C path "
        f"to trace; use a rough surface or a sphere"
    )
