"""AUTO-07p demos with algebraic steady states (the demo files ``demos/<name>/<name>.f90`` and
``c.<name>`` of the auto-07p repository, described in its manual ``doc/auto.tex``).

- :func:`pp2`: the predator–prey model with harvesting (demo ``pp2``): on the prey branch a
  fold, then two transcritical branch points, all in closed form or 1-D mpmath roots;
- :func:`logistic_map`: fixed points of the logistic map (demo ``log``): a transcritical
  branch point at μ = 1;
- :func:`dd2`: fixed points of a discrete predator–prey map (demo ``dd2``): the prey-only
  branch crosses the trivial branch and the coexistence branch.

The demo ``ab`` is :func:`~cusp.examples.chemistry.ab_reactor`, ``enz`` is
:func:`~cusp.examples.reactors.enz`, ``lrz`` is :func:`~cusp.examples.patterns.lorenz` and
``cusp`` is :func:`~cusp.examples.normal_forms.cusp_normal_form`.
"""

from __future__ import annotations

import functools

import numpy as np

from ._base import DPS, Example, Reference, make_example

# ---------------------------------------------------------------------------------------------
# pp2: predator-prey with harvesting
# ---------------------------------------------------------------------------------------------

#: The fixed parameters of demo pp2 (its STPNT): p2 = p4 = 3, p3 = 5.
PP2_PARAMS = {"p2": 3.0, "p3": 5.0, "p4": 3.0}


def pp2(*, derivatives: str = "analytic") -> Example:
    """AUTO-07p demo ``pp2``, a predator–prey model with harvesting::

        p2 u1 (1 − u1) − u1 u2 − p1 (1 − e^{−p3 u1}) = 0
        −u2 + p4 u1 u2                                = 0

    Unknowns ``u1`` (prey), ``u2`` (predator); parameters ``p1`` (quota) and the demo's
    ``p2 = p4 = 3``, ``p3 = 5``. Start: u = (1, 0) at p1 = 0 (the prey's carrying capacity;
    the demo itself starts at u = 0 and reaches this branch by switching); free ``p1``; bounds
    p1 ∈ [0, 1] (the demo's) and u1 ∈ [−0.5, 1.5].

    On the prey branch u2 = 0, ``p1 = g(u1) = p2 u1 (1 − u1)/(1 − e^{−p3 u1})``; from u1 = 1
    the trace runs down in u1 through (:func:`pp2_references`):

    - a fold where g′(u1) = 0: u1 = 0.41116156075107249, p1 = 0.83292932223415686;
    - a branch point at u1 = 1/p4 = 1/3, p1 = (2/3)/(1 − e^{−5/3}) = 0.82190434537399081,
      where the coexistence branch u1 = 1/3, u2 = 2 − 3 p1 (1 − e^{−5/3}) crosses;
    - a branch point at u1 = 0, p1 = p2/p3 = 0.6 (the limit of g), where the trivial branch
      u = 0 crosses;

    and ends on u1 = −0.5 (p1 = 0.2012). The manual (section "pp2: A 2D Predator-Prey Model")
    shows these points in its bifurcation diagram without printing their values.
    """

    def residual(u, p):
        u1, u2 = u[0], u[1]
        return np.array(
            [
                p["p2"] * u1 * (1 - u1) - u1 * u2 - p["p1"] * (1 - np.exp(-p["p3"] * u1)),
                -u2 + p["p4"] * u1 * u2,
            ]
        )

    def jacobian(u, p):
        u1, u2 = u[0], u[1]
        e = np.exp(-p["p3"] * u1)
        return np.array(
            [
                [p["p2"] * (1 - 2 * u1) - u2 - p["p1"] * p["p3"] * e, -u1],
                [p["p4"] * u2, -1 + p["p4"] * u1],
            ]
        )

    def param_jacobian(u, p, name):
        u1, u2 = u[0], u[1]
        e = np.exp(-p["p3"] * u1)
        return {
            "p1": np.array([-(1 - e), 0.0]),
            "p2": np.array([u1 * (1 - u1), 0.0]),
            "p3": np.array([-p["p1"] * u1 * e, 0.0]),
            "p4": np.array([0.0, u1 * u2]),
        }[name]

    def references():
        out = []
        for kind, u1, p1v in pp2_references():
            out.append(Reference(kind, {"u1": u1, "u2": 0.0, "p1": p1v, **PP2_PARAMS}, ("p1",)))
        return out

    return make_example(
        "predator-prey (AUTO-07p pp2)",
        residual,
        ["u1", "u2"],
        {"p1": 0.0, **PP2_PARAMS},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[1.0, 0.0],
        free="p1",
        bounds={"p1": (0.0, 1.0), "u1": (-0.5, 1.5)},
        references=references,
    )


@functools.lru_cache
def pp2_references() -> tuple[tuple[str, float, float], ...]:
    """The special points of the prey branch of :func:`pp2` from u1 = 1 down to u1 = −0.5,
    as (kind, u1, p1) in path order (mpmath, 40 digits).

    On u2 = 0 the Jacobian is triangular, det = ∂F1/∂u1 · (p4 u1 − 1), and
    ∂F1/∂u1 = −(1 − e^{−p3 u1}) g′(u1) with g = N/D, N = p2 u1 (1 − u1), D = 1 − e^{−p3 u1}:
    the fold is the root of N′D − N D′ (the numerator of g′; ``findroot`` from 0.4, and it
    changes sign once on [−0.5, 1], checked on a grid of step 10⁻³), the branch points are
    u1 = 1/p4 and u1 = 0 (p1 = p2/p3, the limit of g).
    """
    import mpmath as mp

    with mp.workdps(DPS):
        p2, p3, p4 = (mp.mpf(PP2_PARAMS[k]) for k in ("p2", "p3", "p4"))

        def g(u):
            return p2 * u * (1 - u) / (1 - mp.exp(-p3 * u))

        def slope(u):  # numerator of g'(u)
            e = mp.exp(-p3 * u)
            return p2 * (1 - 2 * u) * (1 - e) - p2 * u * (1 - u) * p3 * e

        uf = mp.findroot(slope, mp.mpf("0.4"))
        grid = [mp.mpf(k) / 1000 for k in range(-500, 1001)]
        changes = sum(1 for a, b in zip(grid, grid[1:]) if (slope(a) < 0) != (slope(b) < 0))
        if changes != 1:  # pragma: no cover - the reference itself is wrong
            raise RuntimeError(f"pp2: {changes} folds on the prey branch, expected 1")
        ub = 1 / p4
        return (
            ("fold", float(uf), float(g(uf))),
            ("branch_point", float(ub), float(g(ub))),
            ("branch_point", 0.0, float(p2 / p3)),
        )


# ---------------------------------------------------------------------------------------------
# log: fixed points of the logistic map
# ---------------------------------------------------------------------------------------------


def logistic_map(mu: float = 0.0, *, derivatives: str = "analytic") -> Example:
    """Fixed points of the logistic map x ↦ μ x (1 − x) (AUTO-07p demo ``log``, whose map
    this is; a fixed point solves ``μ x (1 − x) − x = 0``).

    Unknown ``x``, parameter ``mu``. Start: the demo's x = 0 at μ = 0; free ``mu``; bounds
    μ ∈ [0, 3.6] (the demo's UZSTOP). The trivial branch x = 0 meets the branch
    x = 1 − 1/μ in a transcritical branch point at μ = 1, x = 0 (exact: ∂F/∂x = μ − 1 there);
    the period doubling at μ = 3 is a bifurcation of the map, not of its fixed-point
    equation.
    """

    def residual(u, p):
        x = u[0]
        return np.array([p["mu"] * x * (1 - x) - x])

    def jacobian(u, p):
        return np.array([[p["mu"] * (1 - 2 * u[0]) - 1]])

    def param_jacobian(u, p, name):
        return np.array([u[0] * (1 - u[0])])

    return make_example(
        "logistic map fixed points (AUTO-07p log)",
        residual,
        ["x"],
        {"mu": mu},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[0.0],
        free="mu",
        bounds={"mu": (0.0, 3.6)},
        references=lambda: (Reference("branch_point", {"x": 0.0, "mu": 1.0}, ("mu",)),),
    )


# ---------------------------------------------------------------------------------------------
# dd2: fixed points of a discrete predator-prey map
# ---------------------------------------------------------------------------------------------


def dd2(p1: float = 0.5, *, derivatives: str = "analytic") -> Example:
    """Fixed points of the discrete predator–prey map of AUTO-07p demo ``dd2``::

        u1 ↦ p1 u1 (1 − u1) − p2 u1 u2,    u2 ↦ (1 − p3) u2 + p2 u1 u2

    with the demo's p2 = 0.2, p3 = 0.1; a fixed point solves map(u) − u = 0, i.e.
    ``p1 u1 (1 − u1) − p2 u1 u2 − u1 = 0`` and ``u2 (p2 u1 − p3) = 0``.

    Unknowns ``u1``, ``u2``, parameters ``p1`` (free), ``p2``, ``p3``. Start on the prey-only
    branch u2 = 0, u1 = 1 − 1/p1 at p1 = 0.5 (u1 = −1); bounds p1 ∈ [0.4, 4]. That branch
    has two transcritical branch points (exact): at p1 = 1, u1 = 0, where the trivial branch
    u = 0 crosses, and where u1 = p3/p2 = 1/2, i.e. p1 = 1/(1 − p3/p2) = 2, where the
    coexistence branch u1 = p3/p2, u2 = (p1 (1 − p3/p2) − 1)/p2 crosses. The demo reaches
    the same points from u = 0 by branch switching (it also continues period doublings,
    which are not steady states).
    """

    def residual(u, p):
        u1, u2 = u[0], u[1]
        return np.array(
            [p["p1"] * u1 * (1 - u1) - p["p2"] * u1 * u2 - u1, u2 * (p["p2"] * u1 - p["p3"])]
        )

    def jacobian(u, p):
        u1, u2 = u[0], u[1]
        return np.array(
            [
                [p["p1"] * (1 - 2 * u1) - p["p2"] * u2 - 1, -p["p2"] * u1],
                [p["p2"] * u2, p["p2"] * u1 - p["p3"]],
            ]
        )

    def param_jacobian(u, p, name):
        u1, u2 = u[0], u[1]
        return {
            "p1": np.array([u1 * (1 - u1), 0.0]),
            "p2": np.array([-u1 * u2, u1 * u2]),
            "p3": np.array([0.0, -u2]),
        }[name]

    fixed = {"p2": 0.2, "p3": 0.1}

    def references():
        return (
            Reference("branch_point", {"u1": 0.0, "u2": 0.0, "p1": 1.0, **fixed}, ("p1",)),
            Reference("branch_point", {"u1": 0.5, "u2": 0.0, "p1": 2.0, **fixed}, ("p1",)),
        )

    return make_example(
        "discrete predator-prey fixed points (AUTO-07p dd2)",
        residual,
        ["u1", "u2"],
        {"p1": p1, **fixed},
        jacobian,
        param_jacobian,
        derivatives=derivatives,
        u0=[1 - 1 / p1, 0.0],
        free="p1",
        bounds={"p1": (0.4, 4.0)},
        references=references,
    )
