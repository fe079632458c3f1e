"""The tasks of the work–precision benchmark (`bench_work_precision.py`): for each, the
settings of every tool (coarse to fine, so that a tool whose run grows too long skips the
finer ones), and how the errors of a run are measured against an exact reference.

(a) fold location (cusp normal form, Green truss, FD Bratu N = 999 and 99 999): ours,
    contique, pacopy and the SciPy loop (`tools`); errors: the folds' parameters, and for
    the one-unknown problems the curve between the computed points (joined by straight
    lines, and ours' dense output `Branch.interpolate` where this build has it);
(b) the fold curve of the CO model through its cusp (ours only): the cusp point, the curve.
The contact-loss tasks, (c) and (d), are in `wp_contact.py`."""

from __future__ import annotations

import functools
import importlib.metadata
import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

import cusp.examples as ex
from cusp._scripts.tools import (
    counted,
    fold_errors,
    run_contique,
    run_ours,
    run_pacopy,
    run_scipy,
    trace_problems,
)
from cusp.continuation import Problem, fold_curve, trace
from cusp.examples.chemistry import CO_CUSP, co_quartic

#: ours: every accuracy level the options allow, coarse to fine
RTOLS = tuple(float(f"1e-{k}") for k in range(2, 14))
QUICK_RTOLS = (1e-2, 1e-4, 1e-7, 1e-10)
#: samples per interval between two computed points when a curve's error is measured
PER_SEGMENT = 16


@dataclass
class Setting:
    """One run of one tool: ``run()`` solves and returns the summary function (`tools`);
    ``family``: the runs joined by one line in the figures (a tool at one tolerance)."""

    tool: str
    label: str
    family: str
    run: Callable[[], Callable[[], dict]]


@dataclass
class Task:
    """A problem, the settings of every tool, and ``measure(summary) -> {measure: error}``
    (inf where the run gives no estimate). ``work``: what the f-evals column counts."""

    key: str
    group: str
    name: str
    settings: list[Setting]
    measure: Callable[[dict], dict[str, float]]
    reference: str
    work: str = "residual evaluations"
    notes: list[str] = field(default_factory=list)


# ----------------------------------------------------------------------------- (a) folds

#: settings of the other tools: (contique dmax, tolerances), (pacopy stepsize_max,
#: tolerances), SciPy loop steps; full and quick. The tolerances are absolute (2-norms of
#: the residual): on the Bratu problem the residual's rounding grows like N²√N, so they
#: start higher there.
SMALL_PLANS = {
    "full": dict(
        contique=((0.2, 0.1, 0.05, 0.02, 0.01, 0.005, 0.002), (1e-4, 1e-8, 1e-12)),
        pacopy=((0.5, 0.2, 0.1, 0.05, 0.02, 0.01, 0.005, 0.002, 0.001), (1e-4, 1e-8, 1e-12)),
        scipy=(25, 50, 100, 200, 400, 800, 1600, 3200, 6400),
    ),
    "quick": dict(
        contique=((0.05, 0.01), (1e-8,)), pacopy=((0.5, 0.02), (1e-8,)), scipy=(100, 800)
    ),
}
BRATU_PLANS = {
    "full": dict(
        contique=((0.2, 0.1, 0.05, 0.02, 0.01), (1e-2, 1e-5, 1e-8)),
        pacopy=((0.5, 0.2, 0.1, 0.05, 0.02), (1e-2, 1e-5, 1e-8)),
        scipy=(25, 50, 100, 200, 400),
    ),
    "quick": dict(contique=((0.05,), (1e-5,)), pacopy=((0.1,), (1e-5,)), scipy=(50,)),
}
BRATU_BIG_PLAN = dict(
    contique=((0.1,), (1e-2,)), pacopy=((0.5, 0.1), (1e-1, 1e-3)), scipy=(25, 100)
)


def _cusp_curve(x, b):
    """x³ − x − b and its derivatives in x and b."""
    return x**3 - x - b, 3 * x**2 - 1, -np.ones_like(b)


def _truss_curve(v, P):
    """P − P(v) (the Green truss, EA = L = 1, H = 0.5) and its derivatives in v and P."""
    return (
        P - ex.truss_green_force(v, 1.0, 1.0, 0.5),
        -ex.truss_green_stiffness(v, 1.0, 1.0, 0.5),
        np.ones_like(P),
    )


def bratu_problem(n: int) -> dict:
    """The FD Bratu problem with ``n`` nodes as a problem of `tools`: from u = 0 at λ = 0
    to u(½) = 2 past the fold (the SciPy loop sweeps λ over [0, 4])."""
    example = ex.bratu(n, sparse=True)
    if n == 99_999:
        lam, ref = ex.BRATU_FOLD_N99999, "the stored 40-digit shooting value"
    else:
        lam, ref = ex.bratu_fd_fold(n)[0], "mpmath shooting (`bratu_fd_fold`)"
    mid = n // 2
    return {
        "key": f"bratu{n}",
        "name": f"FD Bratu, N = {n}",
        "example": example,
        "x0": np.zeros(n),
        "lam0": 0.0,
        "lam1": 4.0,
        "folds": [(None, lam)],
        "bounds": dict(example.bounds),
        "stop": lambda x, lam: x[mid] >= 2.0,
        "sparse": True,
        "residual_scale": float((n + 1) ** 2),
        "up": True,
        "reference": f"fold λ* = {lam:.16g}, {ref}",
    }


def small_problems() -> list[dict]:
    """The cusp normal form and the Green truss of `bench_trace`, with their exact curves."""
    cusp, truss = trace_problems()
    cusp.update(
        key="cusp",
        curve=_cusp_curve,
        scales=(abs(cusp["x0"]), 1.0),
        reference="folds b = ±2/(3√3) and the curve x³ − x − b = 0 (exact)",
    )
    truss.update(
        key="truss",
        curve=_truss_curve,
        scales=(1.5, abs(truss["lam0"])),
        reference="limit points v = H(1 ∓ 1/√3) and the curve P = P(v) (exact)",
    )
    return [cusp, truss]


def fold_settings(pb, rtols, plan, contique, pacopy) -> list[Setting]:
    """ours over ``rtols``, and the other tools over the knobs of ``plan``."""
    out = [
        Setting("ours", f"rtol = {r:.0e}", "ours", functools.partial(_ours, pb, r)) for r in rtols
    ]
    if contique is not None:
        dmaxs, tols = plan["contique"]
        for tol in tols:
            for d in dmaxs:
                run = functools.partial(
                    run_contique, pb, True, contique, tol=tol, dmax=d, maxsteps=int(20 / d) + 100
                )
                out.append(
                    Setting(
                        f"contique {contique.__version__}",
                        f"dxmax = dlpfmax = {d:g}, tol = {tol:.0e}",
                        f"tol = {tol:.0e}",
                        run,
                    )
                )
    if pacopy is not None:
        dmaxs, tols = plan["pacopy"]
        for tol in tols:
            for d in dmaxs:
                run = functools.partial(
                    run_pacopy,
                    pb,
                    pacopy,
                    newton_tol=tol,
                    stepsize_max=d,
                    max_steps=int(20 / d) + 100,
                )
                out.append(
                    Setting(
                        f"pacopy {importlib.metadata.version('pacopy')}",
                        f"stepsize_max = {d:g}, newton_tol = {tol:.0e}",
                        f"newton_tol = {tol:.0e}",
                        run,
                    )
                )
    for steps in plan["scipy"]:
        run = functools.partial(run_scipy, pb, True, steps=steps)
        out.append(Setting("SciPy loop", f"{steps} steps", "SciPy loop", run))
    return out


def _ours(pb, rtol):
    return run_ours(pb, True, rtol=rtol, throw=False)


def fold_measure(pb) -> Callable[[dict], dict[str, float]]:
    """The errors of a run on ``pb``: ``fold``, the largest relative error of the exact
    folds' parameters (each against the nearest estimate; inf if a fold has none); for a
    one-unknown problem ``curve``, the largest distance of the computed points joined by
    straight lines to the exact curve, and for ours with dense output ``dense``, that of
    the interpolant (both relative to the typical sizes ``pb["scales"]``)."""

    def measure(summary):
        out = {"fold": _fold_error(summary["folds"], pb["folds"])}
        if "curve" in pb and not summary["ok"]:  # a partial branch: no curve
            out["curve"] = math.inf
        elif "curve" in pb and summary.get("path") is not None and len(summary["path"]) > 1:
            out["curve"] = _distance(pb, polyline(summary["path"]))
            br = summary.get("branch")
            if br is not None:
                cols = br.interpolate(dense_arclengths(br.s))
                free = pb["example"].free
                rows = np.column_stack([cols[pb["example"].unknowns[0]], cols[free]])
                out["dense"] = _distance(pb, rows)
        return out

    return measure


def _fold_error(found, exact) -> float:
    """The largest relative error of the exact folds' parameters (:func:`tools.fold_errors`,
    each against the nearest estimate); inf if there is none."""
    errs = fold_errors(found, exact)
    if any(e is None for e in errs):
        return math.inf
    return max((e / abs(lam) for e, (_, lam) in zip(errs, exact)), default=0.0)


def polyline(path: np.ndarray, per: int = PER_SEGMENT) -> np.ndarray:
    """``per`` samples on each straight segment between consecutive rows of ``path``."""
    t = np.arange(per)[:, None, None] / per
    a, b = path[:-1][None], path[1:][None]
    inner = ((1 - t) * a + t * b).transpose(1, 0, 2).reshape(-1, path.shape[1])
    return np.vstack([inner, path[-1:]])


def dense_arclengths(s: np.ndarray, per: int = PER_SEGMENT) -> np.ndarray:
    """``per`` arclengths on each interval between consecutive points (and the last)."""
    t = np.arange(per)[:, None] / per
    inner = ((1 - t) * s[:-1] + t * s[1:]).T.reshape(-1)
    return np.append(inner, s[-1])


def _distance(pb, rows) -> float:
    """The largest first-order distance |F|/|∇F| of the samples (x, λ) to the exact curve
    F = 0, in units of the typical sizes."""
    sx, sl = pb["scales"]
    f, fx, fl = pb["curve"](rows[:, 0], rows[:, 1])
    return float(np.max(np.abs(f) / np.hypot(fx * sx, fl * sl)))


# ----------------------------------------------------------------------------- (b) CO


def co_run(rtol):
    """The CO model traced at k = 0.4 to its first fold (ds_max = 0.01, BifurcationKit's),
    then that fold's curve in (q2, k) through the cusp to k = 0 and 2.2 (ds_max = 0.05),
    both at ``rtol``; residual and Jacobian evaluations counted over both."""
    example = ex.co_oxidation()
    cnt = {"f": 0, "J": 0}
    prob = Problem(
        counted(example.residual, cnt, "f"),
        unknowns=list(example.unknowns),
        params=example.params,
        jacobian=counted(example.jacobian, cnt, "J"),
        param_jacobian=example.param_jacobian,
    )
    br = trace(prob, example.u0, free="q2", bounds=example.bounds, rtol=rtol, ds_max=0.01,
               throw=False)  # fmt: skip
    folds = [f for f in br.special("fold") if f.status == "converged"]
    fc = None
    if folds:
        fc = fold_curve(prob, folds[0], free=("q2", "k"), bounds={"k": (0.0, 2.2)},
                        ds_max=0.05, rtol=rtol, throw=False)  # fmt: skip

    def summary():
        ok = fc is not None and fc.success
        return {
            "points": 0 if fc is None else len(fc),
            "nfev": cnt["f"],
            "jev": cnt["J"],
            "ok": ok,
            "status": "no fold" if fc is None else fc.status,
            "branch": fc,
        }

    return summary


def co_measure(summary) -> dict[str, float]:
    """``cusp``: the largest relative error of the cusp's x, y, s, q2, k against CO_CUSP;
    ``curve``: the largest distance of the fold curve's points joined by straight lines to
    the exact fold curve (double roots of the quartic), ``dense`` that of the interpolant."""
    fc = summary["branch"]
    if fc is None or not summary["ok"]:
        return {"cusp": math.inf, "curve": math.inf}
    cusps = [c for c in fc.special("cusp") if c.status == "converged"]
    out = {"cusp": math.inf}
    if cusps:
        out["cusp"] = max(
            abs(cusps[0].values[k] - float(v)) / abs(float(v)) for k, v in CO_CUSP.items()
        )
    names = ("x", "q2", "k")
    sizes = [max(float(np.max(np.abs(fc[n]))), 1e-3) for n in names]
    out["curve"] = _co_distance(polyline(np.column_stack([fc[n] for n in names])), sizes)
    cols = fc.interpolate(dense_arclengths(fc.s))
    out["dense"] = _co_distance(np.column_stack([cols[n] for n in names]), sizes)
    return out


def _co_distance(rows, sizes) -> float:
    """Largest first-order distance of the samples (x, q2, k) to the fold curve
    {P = ∂P/∂x = 0} of the quartic P(x; q2, k) (`co_quartic`): |J⁺G| with G = (P, P_x) and
    J its Jacobian in the coordinates scaled by ``sizes`` (parameter derivatives by a
    complex step)."""
    x, q2, k = rows.T

    def g(q2_, k_):  # complex throughout (co_quartic adds in place)
        c = co_quartic(q2_.astype(complex), k_.astype(complex))
        return [_poly(c, x, 0), _poly(c, x, 1), _poly(c, x, 2)]

    p, px, pxx = (v.real for v in g(q2, k))
    h = 1e-30
    dq = [v.imag / h for v in g(q2 + 1j * h, k)[:2]]
    dk = [v.imag / h for v in g(q2, k + 1j * h)[:2]]
    sx, sq, sk = sizes
    jac = np.stack(
        [
            np.stack([px * sx, dq[0] * sq, dk[0] * sk], -1),
            np.stack([pxx * sx, dq[1] * sq, dk[1] * sk], -1),
        ],
        1,
    )  # (m, 2, 3)
    gram = jac @ jac.transpose(0, 2, 1)
    y = np.linalg.solve(gram, np.stack([p, px], -1)[..., None])
    return float(np.max(np.linalg.norm(jac.transpose(0, 2, 1) @ y, axis=(1, 2))))


def _poly(coeffs, x, derivative):
    """The ``derivative``-th derivative of Σ c_i x^i at x (arrays)."""
    total = 0.0
    for i in range(len(coeffs) - 1, derivative - 1, -1):
        factor = math.prod(range(i - derivative + 1, i + 1))
        total = total * x + factor * coeffs[i]
    return total
