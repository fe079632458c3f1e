"""Von Mises trusses: two bars from the supports (±L, 0) to the apex (0, H), axial stiffness EA,
a load P pushing the apex down by v.

- :func:`truss_green`: one degree of freedom, Green–Lagrange strain (a cubic load path, two
  limit points);
- :func:`truss_rotated`: one degree of freedom, rotated engineering strain;
- :func:`truss_2dof`: the apex also free sideways (u): a branch point onto an asymmetric path
  before or after the limit point;
- :func:`snapback_monitor` and :func:`snapback_control`: the Green truss in series with a
  spring k_s, under load or displacement control: a snap-back, whose two turning points meet
  in a cusp at k_s = K H².
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ._base import DPS, Example, Reference, make_example

# ---------------------------------------------------------------------------------------------
# Green-Lagrange strain, one degree of freedom
# ---------------------------------------------------------------------------------------------


def truss_green_force(v: Any, EA: float = 1.0, L: float = 1.0, H: float = 0.5) -> Any:
    """Load of the Green-strain truss at apex deflection v (a float, an array, or a complex or
    mpmath number): ``P = (EA/l0³) v (H − v)(2H − v)``, ``l0² = L² + H²``."""
    return EA / (L**2 + H**2) ** 1.5 * v * (H - v) * (2 * H - v)


def truss_green_stiffness(v: Any, EA: float = 1.0, L: float = 1.0, H: float = 0.5) -> Any:
    """dP/dv of :func:`truss_green_force`: ``(EA/l0³)(2H² − 6Hv + 3v²)``."""
    return EA / (L**2 + H**2) ** 1.5 * (2 * H**2 - 6 * H * v + 3 * v**2)


def truss_green(
    EA: float = 1.0, L: float = 1.0, H: float = 0.5, *, derivatives: str = "analytic"
) -> Example:
    """Von Mises truss, Green–Lagrange strain: ``P − (EA/l0³) v (H − v)(2H − v) = 0``.

    Unknown ``v`` (apex deflection), parameter ``P`` (load). Start v = 0, P = 0; free ``P``;
    bounds v ∈ [−H, 3H] (H = 0.5: [−0.5, 1.5]).

    Special points (:func:`truss_green_limits`): limit points at ``v = H(1 ∓ 1/√3)``,
    ``P = ±(2/(3√3)) EA H³/l0³``.
    """
    k = EA / (L**2 + H**2) ** 1.5

    def residual(u, p):
        v = u[0]
        return np.array([p["P"] - k * v * (H - v) * (2 * H - v)])

    def jacobian(u, p):
        v = u[0]
        return np.array([[-k * (2 * H**2 - 6 * H * v + 3 * v**2)]])

    def param_jacobian(u, p, name):
        return np.array([1.0])

    def references():
        return tuple(
            Reference("fold", {"v": v, "P": P}, ("P",)) for v, P in truss_green_limits(EA, L, H)
        )

    return make_example(
        "von Mises truss (Green strain)",
        residual,
        ["v"],
        {"P": 0.0},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[0.0],
        free="P",
        bounds={"v": (-H, 3 * H)},
        references=references,
    )


def truss_green_limits(
    EA: float = 1.0, L: float = 1.0, H: float = 0.5
) -> tuple[tuple[float, float], ...]:
    """Limit points v = H(1 -+ 1/sqrt 3), P = +-(2/(3 sqrt 3)) EA H^3/l0^3, in mpmath
    (40 digits). Returns ((v, P), (v, P)) in path order."""
    import mpmath as mp

    with mp.workdps(DPS):
        EA, L, H = mp.mpf(EA), mp.mpf(L), mp.mpf(H)
        k = EA / (L**2 + H**2) ** mp.mpf(1.5)
        out = []
        for s in (-1, 1):
            v = H * (1 + s / mp.sqrt(3))
            out.append((float(v), float(k * v * (H - v) * (2 * H - v))))
        return tuple(out)


# ---------------------------------------------------------------------------------------------
# Rotated engineering strain, one degree of freedom
# ---------------------------------------------------------------------------------------------


def truss_rotated(
    EA: float = 1.0, L: float = 1.0, H: float = 1.0, *, derivatives: str = "analytic"
) -> Example:
    """Von Mises truss, rotated engineering strain: ``P − 2EA y (1/l − 1/l0) = 0`` with
    ``y = H − v``, ``l = √(L² + y²)``, ``l0 = √(L² + H²)``.

    Unknown ``v``, parameter ``P``. Start v = 0, P = 0; free ``P``; bounds v ∈ [−H/2, 5H/2].

    Special points (:func:`truss_rotated_limits`): limit points where ``l³ = L² l0``,
    ``y = ±√((L² l0)^{2/3} − L²)`` (EA = L = H = 1: y = ±√(2^{1/3} − 1) = ±0.5097955...).
    """
    l0 = (L**2 + H**2) ** 0.5

    def residual(u, p):
        y = H - u[0]
        return np.array([p["P"] - 2 * EA * y * (1 / (L**2 + y**2) ** 0.5 - 1 / l0)])

    def jacobian(u, p):
        y = H - u[0]
        return np.array([[2 * EA * (L**2 / (L**2 + y**2) ** 1.5 - 1 / l0)]])

    def param_jacobian(u, p, name):
        return np.array([1.0])

    def references():
        return tuple(
            Reference("fold", {"v": v, "P": P}, ("P",)) for v, P in truss_rotated_limits(EA, L, H)
        )

    return make_example(
        "von Mises truss (rotated strain)",
        residual,
        ["v"],
        {"P": 0.0},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[0.0],
        free="P",
        bounds={"v": (-0.5 * H, 2.5 * H)},
        references=references,
    )


def truss_rotated_limits(
    EA: float = 1.0, L: float = 1.0, H: float = 1.0
) -> tuple[tuple[float, float], ...]:
    """Limit where l^3 = L^2 l0, i.e. y = +-sqrt((L^2 l0)^(2/3) - L^2), in mpmath (40 digits).
    Returns ((v, P), (v, P)) in path order."""
    import mpmath as mp

    with mp.workdps(DPS):
        EA, L, H = mp.mpf(EA), mp.mpf(L), mp.mpf(H)
        l0 = mp.sqrt(L**2 + H**2)
        lc = mp.cbrt(L**2 * l0)
        out = []
        for y in (mp.sqrt(lc**2 - L**2), -mp.sqrt(lc**2 - L**2)):
            out.append((float(H - y), float(2 * EA * y * (1 / lc - 1 / l0))))
        return tuple(out)


# ---------------------------------------------------------------------------------------------
# Two degrees of freedom: branch point onto the asymmetric path
# ---------------------------------------------------------------------------------------------


def truss_2dof(
    EA: float = 1.0, L: float = 1.0, H: float = 2.0, *, derivatives: str = "analytic"
) -> Example:
    """Von Mises truss with the apex free sideways: the gradient of
    ``Π = (EA l0/2)(e1² + e2²) − P v`` in (u, v), Green strains
    ``e1,2 = ((L ± u)² + (H − v)² − l0²)/(2 l0²)``.

    Unknowns ``u`` (sideways), ``v`` (down), parameter ``P``. Start u = v = 0, P = 0; free
    ``P``; bounds v ∈ [−0.5, 1].

    Special points (:func:`truss_2dof_references`), with y = H − v on the symmetric path
    u = 0, P = EA y (H² − y²)/l0³: a branch point at ``y² = H² − 2L²`` and a limit point at
    ``y² = H²/3``; the branch point comes first iff H > √3 L. The asymmetric path is
    ``u² + y² = H² − 2L²``, ``P = 2 EA L² y/l0³``.
    """
    l02 = L**2 + H**2
    l0 = l02**0.5

    def strains(u, v):
        y = H - v
        e1 = ((L + u) ** 2 + y**2 - l02) / (2 * l02)
        e2 = ((L - u) ** 2 + y**2 - l02) / (2 * l02)
        return y, e1, e2

    def residual(q, p):
        u, v = q[0], q[1]
        y, e1, e2 = strains(u, v)
        return np.array(
            [EA * (e1 * (L + u) - e2 * (L - u)) / l0, -EA * y * (e1 + e2) / l0 - p["P"]]
        )

    def jacobian(q, p):
        u, v = q[0], q[1]
        y, e1, e2 = strains(u, v)
        juu = EA / l0 * ((L + u) ** 2 / l02 + e1 + (L - u) ** 2 / l02 + e2)
        juv = -EA * 2 * y * u / (l0 * l02)
        jvv = EA / l0 * (e1 + e2 + 2 * y**2 / l02)
        return np.array([[juu, juv], [juv, jvv]])

    def param_jacobian(q, p, name):
        return np.array([0.0, -1.0])

    def references():
        ref = truss_2dof_references(EA, L, H)
        return (
            Reference("branch_point", {"u": 0.0, "v": ref["bp_v"], "P": ref["bp_P"]}, ("P",)),
            Reference("fold", {"u": 0.0, "v": ref["lp_v"], "P": ref["lp_P"]}, ("P",)),
        )

    return make_example(
        "von Mises truss, 2 dof",
        residual,
        ["u", "v"],
        {"P": 0.0},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[0.0, 0.0],
        free="P",
        bounds={"v": (-0.5, 1.0)},
        references=references,
    )


def truss_2dof_references(EA: float = 1.0, L: float = 1.0, H: float = 2.0) -> dict[str, float]:
    """Branch point y^2 = H^2 - 2L^2 and limit point y^2 = H^2/3 on the symmetric path
    P = EA y (H^2 - y^2)/l0^3; on the asymmetric path u^2 + y^2 = H^2 - 2L^2 and
    P = 2 EA L^2 y / l0^3 (from dPi/du = u (A + 2L^2)/l0^2 with A = L^2 + u^2 + y^2 - l0^2).
    In mpmath (40 digits); keys ``bp_v``, ``bp_P``, ``lp_v``, ``lp_P``."""
    import mpmath as mp

    with mp.workdps(DPS):
        EA, L, H = mp.mpf(EA), mp.mpf(L), mp.mpf(H)
        l03 = (L**2 + H**2) ** mp.mpf(1.5)
        yb = mp.sqrt(H**2 - 2 * L**2)
        yl = H / mp.sqrt(3)
        return {
            "bp_v": float(H - yb),
            "bp_P": float(EA * yb * (H**2 - yb**2) / l03),
            "lp_v": float(H - yl),
            "lp_P": float(EA * yl * (H**2 - yl**2) / l03),
        }


# ---------------------------------------------------------------------------------------------
# Snap-back: the Green truss in series with a spring k_s
# ---------------------------------------------------------------------------------------------


def snapback_monitor(
    EA: float = 1.0,
    L: float = 1.0,
    H: float = 0.1,
    ks: float = 0.005,
    *,
    derivatives: str = "analytic",
) -> Example:
    """Truss + spring under load control: ``P = P_truss(v)``, ``δ = v + P/k_s``.

    Unknowns ``v`` (truss deflection) and ``delta`` (end displacement), parameters ``P`` and
    ``ks``; by default EA = L = 1, H = 0.1, k_s = 0.005 < K H² = 0.00985 (a snap-back).
    Start v = δ = 0, P = 0; free ``P``, monitor ``delta``; bounds v ∈ [−0.05, 0.25].

    Special points: the limit points of the truss in P (:func:`truss_green_limits`), and the
    snap-back: two turning points with respect to the unknown δ
    (:func:`snapback_turning_points`), which meet in a cusp at k_s = K H², v = H
    (:func:`snapback_cusp`).
    """

    def residual(q, p):
        v, d = q[0], q[1]
        return np.array([p["P"] - truss_green_force(v, EA, L, H), d - v - p["P"] / p["ks"]])

    def jacobian(q, p):
        return np.array([[-truss_green_stiffness(q[0], EA, L, H), 0.0], [-1.0, 1.0]])

    def param_jacobian(q, p, name):
        if name == "P":
            return np.array([1.0, -1.0 / p["ks"]])
        if name == "ks":
            return np.array([0.0, p["P"] / p["ks"] ** 2])
        raise KeyError(name)

    def references():
        out = [
            Reference("fold", {"v": v, "delta": v + P / ks, "P": P, "ks": ks}, ("P",))
            for v, P in truss_green_limits(EA, L, H)
        ]
        out += [
            Reference("fold", {"v": v, "delta": d, "P": P, "ks": ks}, ("P",), "delta")
            for v, d, P in snapback_turning_points(EA, L, H, ks)
        ]
        c = snapback_cusp(EA, L, H)
        out.append(Reference("cusp", c, ("P", "ks"), "delta"))
        return out

    return make_example(
        "truss + spring, load control",
        residual,
        ["v", "delta"],
        {"P": 0.0, "ks": ks},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[0.0, 0.0],
        free="P",
        bounds={"v": (-0.05, 0.25)},
        monitor=["delta"],
        references=references,
    )


def snapback_control(
    EA: float = 1.0,
    L: float = 1.0,
    H: float = 0.1,
    ks: float = 0.005,
    *,
    derivatives: str = "analytic",
) -> Example:
    """Truss + spring under displacement control: ``v + P_truss(v)/k_s − δ = 0``.

    Unknown ``v``, parameters ``delta`` (the controlled end displacement) and ``ks``. Start
    v = 0, δ = 0; free ``delta``; bounds v ∈ [−0.05, 0.25]. The snap-back points are ordinary
    folds in δ (:func:`snapback_turning_points`).
    """

    def residual(q, p):
        v = q[0]
        return np.array([v + truss_green_force(v, EA, L, H) / p["ks"] - p["delta"]])

    def jacobian(q, p):
        return np.array([[1.0 + truss_green_stiffness(q[0], EA, L, H) / p["ks"]]])

    def param_jacobian(q, p, name):
        if name == "delta":
            return np.array([-1.0])
        if name == "ks":
            return np.array([-truss_green_force(q[0], EA, L, H) / p["ks"] ** 2])
        raise KeyError(name)

    def references():
        return tuple(
            Reference("fold", {"v": v, "delta": d, "ks": ks}, ("delta",))
            for v, d, _ in snapback_turning_points(EA, L, H, ks)
        )

    return make_example(
        "truss + spring, displacement control",
        residual,
        ["v"],
        {"delta": 0.0, "ks": ks},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[0.0],
        free="delta",
        bounds={"v": (-0.05, 0.25)},
        references=references,
    )


def snapback_turning_points(
    EA: float = 1.0, L: float = 1.0, H: float = 0.1, ks: float = 0.005
) -> tuple[tuple[float, float, float], ...]:
    """delta-turning points t = -+sqrt((H^2 - k_s/K)/3), t = v - H, K = EA/l0^3, in mpmath.
    Returns ((v1, delta1, P1), (v2, delta2, P2)) in path order."""
    import mpmath as mp

    with mp.workdps(DPS):
        EA, L, H, ks = (mp.mpf(str(x)) for x in (EA, L, H, ks))
        K = EA / (L**2 + H**2) ** mp.mpf(1.5)
        out = []
        for s in (-1, 1):
            v = H + s * mp.sqrt((H**2 - ks / K) / 3)
            P = K * v * (H - v) * (2 * H - v)
            out.append((float(v), float(v + P / ks), float(P)))
        return tuple(out)


def snapback_cusp(EA: float = 1.0, L: float = 1.0, H: float = 0.1) -> dict[str, float]:
    """The cusp where the two δ-turning points meet: dδ/dv = 1 + (K/k_s)(3t² − H²) = 0 has the
    double root t = v − H = 0 at k_s = K H², K = EA/l0³; there P = 0 and δ = v = H. In mpmath
    (40 digits); keys ``v``, ``delta``, ``P``, ``ks``."""
    import mpmath as mp

    with mp.workdps(DPS):
        EA, L, H = (mp.mpf(str(x)) for x in (EA, L, H))
        K = EA / (L**2 + H**2) ** mp.mpf(1.5)
        return {"v": float(H), "delta": float(H), "P": 0.0, "ks": float(K * H**2)}
