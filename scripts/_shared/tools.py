"""The continuation tools the benchmark scripts compare, each run on one problem and counted:
ours (`trace`), contique, pacopy 0.1.x and a SciPy natural-parameter loop; and the timing
helpers (timeit-style best of interleaved rounds); and the problems of `bench_trace.py`
(:func:`trace_problems`). Shared by `bench_trace.py` (the tools at their default settings),
`bench_work_precision.py` (the tools over their accuracy knobs) and `bench_ab.py`.

A problem ``pb`` is a dict: ``name``; ``example`` (an example of `cusp.examples`, whose own
residual and derivatives every tool calls); ``x0`` (the start state, a number or an array),
``lam0`` (the free parameter there) and ``lam1`` (the end of the parameter range: a tool
stops at the first point past it, and the SciPy loop sweeps up to it); ``folds``, the exact
folds ``[(x, lam), ...]`` in path order. Optional: ``bounds`` (ours; default the parameter
range), ``stop(x, lam)`` (the end of the branch when it is not the parameter range: the other
tools stop at the first point where it holds), ``sparse`` (the Jacobian is scipy.sparse:
pacopy and the SciPy loop solve with SuperLU), ``residual_scale`` (the size of the
residual's terms, 1 by default: the SciPy loop's acceptance of hybr's answer is relative to
it), ``up`` (whether the parameter increases at the start; default: ``lam1 > lam0``).

Each runner solves and returns a function that summarises the run as dict(points, newton
(total or None), nfev, jev (Jacobian evaluations), folds=[lam estimate], located, ok, and
``path``: the points (x..., lam) as rows, kept for problems of at most 8 unknowns): the
timings cover the solve only, not the summary (which for contique scans every point)."""

from __future__ import annotations

import contextlib
import importlib
import importlib.metadata
import io
import math
import time
from typing import Any

import numpy as np
import scipy.optimize
import scipy.sparse.linalg as spla
from scipy.linalg import lapack

import cusp.examples as ex
from cusp.continuation import Problem, trace

TOL = 1e-10
#: problems with at most this many unknowns keep their points (for the curve's error)
PATH_UNKNOWNS = 8


def functions(pb):
    """The example's residual, Jacobian and parameter derivative, its free parameter's name,
    and its parameters at the start (a fresh dict)."""
    example = pb["example"]
    params = dict(example.params)
    params[example.free] = pb["lam0"]
    return example.residual, example.jacobian, example.param_jacobian, example.free, params


def start(pb) -> np.ndarray:
    """The start state as a fresh float array."""
    return np.array(np.atleast_1d(pb["x0"]), dtype=float)


def past_end(pb):
    """``done(x, lam)``: whether the point is at or past the end of the branch."""
    if "stop" in pb:
        return pb["stop"]
    lam1 = pb["lam1"]
    if lam1 > pb["lam0"]:
        return lambda x, lam: lam >= lam1
    return lambda x, lam: lam <= lam1


def counted(fn, counter, key):
    def wrapped(*a):
        counter[key] += 1
        return fn(*a)

    return wrapped


def run_ours(pb, analytic, api=None, **options):
    """``trace`` on problem ``pb`` with ``options`` (``rtol=...``, ``throw=False``, ...);
    ``api``: the module providing ``Problem`` and ``trace`` (default: this checkout's
    ``continuation``; `bench_ab.py` passes other revisions)."""
    problem_cls, trace_fn = (Problem, trace) if api is None else (api.Problem, api.trace)
    cnt = {"f": 0, "J": 0}
    res, jac, pjac, free, params = functions(pb)
    unknowns = list(pb["example"].unknowns)
    residual = counted(res, cnt, "f")
    if analytic:
        prob = problem_cls(
            residual,
            unknowns=unknowns,
            params=params,
            jacobian=counted(jac, cnt, "J"),
            param_jacobian=pjac,
        )
    else:
        prob = problem_cls(residual, unknowns=unknowns, params=params, derivatives="central")
    bounds = pb.get("bounds") or {free: tuple(sorted((pb["lam0"], pb["lam1"])))}
    br = trace_fn(prob, u0=start(pb), free=free, bounds=bounds, **options)

    def summary():
        folds = [
            sp.values[free]
            for sp in br.special_points
            if sp.kind == "fold" and sp.status == "converged"
        ]
        n = len(unknowns)
        ended = "bounds" in pb or br[free][-1] == pb["lam1"]
        return {
            "points": len(br[free]),
            "newton": int(np.sum(br.stats["newton_iterations"])),
            "nfev": cnt["f"],
            "jev": cnt["J"],
            "folds": folds,
            "located": "refined (Newton)",
            "ok": bool(br.success) and ended,
            "status": br.status,
            "branch": br,
            "max_turn_deg": _max_turn(br.tangents),
            "path": (
                np.column_stack([br[u] for u in unknowns] + [br[free]])
                if n <= PATH_UNKNOWNS
                else None
            ),
        }

    return summary


def _max_turn(tangents) -> float:
    """The largest angle (degrees) between consecutive tangents of a branch."""
    if len(tangents) < 2:
        return 0.0
    t = tangents / np.linalg.norm(tangents, axis=1)[:, None]
    return float(np.degrees(np.arccos(np.clip(np.sum(t[:-1] * t[1:], axis=1), -1.0, 1.0))).max())


def run_contique(pb, analytic, contique, *, tol=TOL, dmax=0.05, maxsteps=2000):
    """`contique.solve` on problem ``pb``: residual tolerance ``tol`` (on its 2-norm),
    largest increment ``dmax`` of every unknown and of the parameter (its ``dxmax`` and
    ``dlpfmax``; its default 0.05); stopped at the end."""
    cnt = {"f": 0, "J": 0}
    res, jac_u, pjac, free, p = functions(pb)

    def fun(x, lpf):
        cnt["f"] += 1
        p[free] = lpf
        return res(x, p)

    jac = None
    if analytic:

        def jac_x(x, lpf, *_):
            cnt["J"] += 1
            p[free] = lpf
            return jac_u(x, p)

        def jac_lpf(x, lpf, *_):
            p[free] = lpf
            return pjac(x, p, free)

        # contique calls the Jacobian parts with its `args` (default (None,)) appended
        jac = (jac_x, jac_lpf)
    done = past_end(pb)
    keep = start(pb).size <= PATH_UNKNOWNS
    lams, path, newton, reached = [], [], 0, False
    with contextlib.redirect_stdout(io.StringIO()):
        for res_ in contique.solve(
            fun,
            x0=start(pb),
            lpf0=pb["lam0"],
            jac=jac,
            tol=tol,
            dxmax=dmax,
            dlpfmax=dmax,
            maxsteps=maxsteps,
        ):
            lams.append(res_.x[-1])
            if keep:
                path.append(res_.x.copy())
            newton += res_.niterations
            if done(res_.x[:-1], res_.x[-1]):
                reached = True
                break

    return lambda: _bracketed_summary(lams, path, newton, cnt, reached)


def _bracketed_summary(lams, path, newton, cnt, reached):
    """The summary of a tool that does not locate folds (contique, pacopy): its parameter
    values ``lams`` along the branch, folds bracketed where the parameter turns."""
    return {
        "points": len(lams),
        "newton": newton,
        "nfev": cnt["f"],
        "jev": cnt["J"],
        "folds": bracketed_folds(np.asarray(lams)),
        "located": "bracketed (extreme point)",
        "ok": reached,
        "status": "end" if reached else "stopped short",
        "path": np.array(path) if path else None,
    }


class _PacopyStop(Exception):
    """Raised by our callback to end `pacopy.euler_newton` once the branch passes the end."""


def _pacopy_problem(pb, pacopy, cnt):
    """pacopy 0.1.x's problem interface (inner, norm2_r, f, df_dlmbda, jacobian_solver) on
    the example's functions; the inner product of the states is the mean over the unknowns
    (the plain product for one unknown), as ours weighs them."""
    res, jac_u, pjac, free, p = functions(pb)
    gesv = lapack.dgesv
    solver_error = pacopy.JacobianSolverError
    weight = 1.0 / start(pb).size
    sparse = pb.get("sparse", False)

    class PacopyProblem:
        def inner(self, a, b):
            return a.dot(b) * weight

        def norm2_r(self, a):
            return a.dot(a)

        def f(self, u, lmbda):
            cnt["f"] += 1
            p[free] = lmbda
            return res(u, p)

        def df_dlmbda(self, u, lmbda):
            p[free] = lmbda
            return pjac(u, p, free)

        def jacobian_solver(self, u, lmbda, rhs):
            cnt["J"] += 1
            p[free] = lmbda
            if sparse:
                x = spla.spsolve(jac_u(u, p), rhs)
                if not np.all(np.isfinite(x)):
                    raise solver_error
                return x
            _, _, x, info = gesv(jac_u(u, p), rhs)
            if info:
                raise solver_error  # pacopy halves the step
            return x

    return PacopyProblem()


def run_pacopy(pb, pacopy, *, newton_tol=TOL, stepsize_max=0.5, max_steps=2000):
    """`pacopy.euler_newton` (0.1.x) on problem ``pb`` with the analytic Jacobian:
    ``newton_tol`` (on the 2-norm of the residual and the arclength equation) and
    ``stepsize_max``, otherwise its defaults (see bench_trace's docstring); stopped by a
    callback at the end."""
    cnt = {"f": 0, "J": 0}
    problem = _pacopy_problem(pb, pacopy, cnt)
    done = past_end(pb)
    keep = start(pb).size <= PATH_UNKNOWNS
    lams, path, newton, last, reached = [], [], 0, [0], [False]

    def callback(k, lmbda, u):
        nonlocal newton
        lams.append(lmbda)
        if keep:
            path.append(np.append(u, lmbda))
        newton += last[0]  # the corrector that produced this (accepted) point
        last[0] = 0
        if done(u, lmbda):
            reached[0] = True
            raise _PacopyStop

    module: Any = importlib.import_module("pacopy.euler_newton")  # (a private name, patched)
    corrector = module._newton_corrector

    def counted_corrector(*a):
        out = corrector(*a)
        last[0] = out[2]  # num_newton_steps
        return out

    up = pb.get("up", pb["lam1"] > pb["lam0"])
    newton_error = importlib.import_module("pacopy.newton").NewtonConvergenceError
    gave_up = (pacopy.JacobianSolverError, newton_error)
    module._newton_corrector = counted_corrector
    try:
        with contextlib.redirect_stdout(io.StringIO()), contextlib.suppress(_PacopyStop):
            pacopy.euler_newton(
                problem,
                start(pb),  # pacopy updates u in place
                pb["lam0"],
                callback,
                max_steps=max_steps,
                max_num_retries=50,
                verbose=False,
                newton_tol=newton_tol,
                stepsize0=min(0.5, stepsize_max) if up else -min(0.5, stepsize_max),
                stepsize_max=stepsize_max,
            )
    except gave_up:  # the branch stops short (so does running out of retries)
        pass
    finally:
        module._newton_corrector = corrector

    return lambda: _bracketed_summary(lams, path, newton, cnt, reached[0])


def import_pacopy():
    """pacopy if version 0.1.x is installed, else None, and a note for the report."""
    try:
        import pacopy
    except ImportError:
        return None, "pacopy is not installed: no rows."
    version = importlib.metadata.version("pacopy")
    if not version.startswith("0.1."):
        return None, f"pacopy {version} is installed, but this script drives the 0.1.x API."
    return pacopy, None


def import_contique():
    """contique if installed, else None."""
    try:
        import contique
    except ImportError:
        return None
    return contique


def bracketed_folds(lams):
    d = np.diff(lams)
    out = []
    for i in range(1, d.size):
        if d[i - 1] != 0 and d[i] != 0 and np.sign(d[i]) != np.sign(d[i - 1]):
            out.append(lams[i])  # the extreme parameter value among the computed points
    return out


def _hybr(pb, analytic, cnt, tol):
    """``solve(lam, guess) -> (x, good)`` by `scipy.optimize.root` (hybr)."""
    res, jac_u, _, free, params = functions(pb)
    floor = 1e-9 * pb.get("residual_scale", 1.0)

    def solve(lam, guess):
        p = dict(params)
        p[free] = lam

        def fun(z):
            cnt["f"] += 1
            return res(z, p)

        def jac(z):
            cnt["J"] += 1
            return jac_u(z, p)

        sol = scipy.optimize.root(fun, guess, jac=jac if analytic else None, method="hybr", tol=tol)
        good = sol.success and float(np.max(np.abs(res(sol.x, p)))) <= floor
        return sol.x, good

    return solve


def _sparse_newton(pb, cnt, tol, max_iter=20):
    """``solve(lam, guess) -> (x, good)`` by Newton with SuperLU (`scipy.sparse.linalg`),
    converged when the update is below ``sqrt(tol)`` relative (the error left is then about
    ``tol``, Newton converging quadratically); it gives up after ``max_iter`` iterations or
    three without halving the residual."""
    res, jac_u, _, free, params = functions(pb)
    step_tol = math.sqrt(tol)

    def solve(lam, guess):
        p = dict(params)
        p[free] = lam
        z = np.array(guess, dtype=float)
        cnt["f"] += 1
        r = res(z, p)
        best, stalled = float(np.max(np.abs(r))), 0
        for _ in range(max_iter):
            cnt["J"] += 1
            dz = spla.splu(jac_u(z, p)).solve(-r)
            z = z + dz
            cnt["f"] += 1
            r = res(z, p)
            rn = float(np.max(np.abs(r)))
            if not math.isfinite(rn):
                return z, False
            if np.max(np.abs(dz)) <= step_tol * (1.0 + np.max(np.abs(z))):
                return z, True
            stalled = stalled + 1 if rn >= 0.5 * best else 0
            best = min(best, rn)
            if stalled >= 3:
                break
        return z, False

    return solve


def run_scipy(pb, analytic, *, steps=200):
    """Natural-parameter continuation at ``steps`` equal steps of the parameter range
    (`scipy.optimize.root`, hybr; on a sparse problem Newton with SuperLU), forward and then
    backward from the end state (a hysteresis sweep). Past a fold the solver fails (hybr
    stalls at the residual minimum, which is the fold itself): the fold is detected by that
    failure and estimated by the midpoint of the last converged parameter and the failed
    one; the loop then jumps to the other sheet by retrying from guesses further along the
    last direction of motion of x, and ends if there is none (past the fold of the Bratu
    problem: no solution at all)."""
    cnt = {"f": 0, "J": 0}
    solve = _sparse_newton(pb, cnt, TOL) if pb.get("sparse") else _hybr(pb, analytic, cnt, TOL)
    lam_grid = np.linspace(pb["lam0"], pb["lam1"], steps + 1)
    folds, points, ok = [], 0, True
    x = start(pb)
    for grid in (lam_grid, lam_grid[::-1]):
        x_prev, lam_prev, step = x, grid[0], np.zeros_like(x)
        for lam in grid:
            x, good = solve(lam, x_prev)
            if not good:
                folds.append(0.5 * (lam_prev + lam))
                x, good = _jump(solve, lam, x_prev, step)
                if not good:
                    ok = False
                    break
            step = x - x_prev
            x_prev, lam_prev = x, lam
            points += 1
        if not ok:
            break
    return lambda: {
        "points": points,
        "newton": None,
        "nfev": cnt["f"],
        "jev": cnt["J"],
        "folds": folds,
        "located": f"failure (Δ = 1/{steps} of range)",
        "ok": ok,
        "status": "end" if ok else "stopped at a fold",
        "path": None,  # its sheets only, joined across the jumps: not the branch
    }


def _jump(solve, lam, x_prev, step):
    """A solution at ``lam`` on another sheet: guesses 0.5, 1, 2 and 4 times max(1, |x|)
    further along the last direction of motion ``step`` (else +1)."""
    size = float(np.max(np.abs(step)))
    direction = step / size if size else np.ones_like(x_prev)
    reach = max(1.0, float(np.max(np.abs(x_prev))))
    for jump in (0.5, 1.0, 2.0, 4.0):
        x, good = solve(lam, x_prev + direction * jump * reach)
        if good:
            return x, True
    return x, False


# ----------------------------------------------------------------------------- timing


def autorange(fn):
    """timeit-style loop count: the smallest 1, 10, 100, ... giving >= 0.05 s."""
    number = 1
    while True:
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        if time.perf_counter() - t0 >= 0.05 or number >= 1000:
            return number
        number *= 10


def best_times(fns, repeat, numbers=None):
    """Best per-call time of each function over `repeat` rounds of `numbers[i]` calls each
    (default: autoranged). The rounds are interleaved (every function once per round) so
    that load from other jobs on a shared machine hits all tools alike and the ratios stay
    fair."""
    numbers = numbers or [autorange(fn) for fn in fns]
    best = [math.inf] * len(fns)
    for _ in range(repeat):
        for i, (fn, number) in enumerate(zip(fns, numbers, strict=True)):
            t0 = time.perf_counter()
            for _ in range(number):
                fn()
            best[i] = min(best[i], (time.perf_counter() - t0) / number)
    return best


def fold_errors(found, exact):
    """Error of each exact fold's parameter vs the nearest reported estimate (None if none)."""
    errs: list[float | None] = []
    for _, lam in exact:
        if not found:
            errs.append(None)
            continue
        errs.append(min(abs(v - lam) for v in found))
    return errs


# ----------------------------------------------------------------------------- problems
# Each problem: an example of `cusp.examples` with one unknown x and one free parameter lam
# (its other parameters fixed), the start (x0, lam0), the end lam1, and the exact folds
# [(x, lam), ...] in path order (the example's mpmath references). Every tool calls the
# example's own residual and derivatives.


def _cusp():
    # mpmath, 40 digits: r = 1/sqrt(3), b = 2 r^3 = 2/(3 sqrt 3), correctly rounded (in float
    # arithmetic 2*(1/sqrt(3))**3 is 2 ulp high); x0 = -1.324717957244746, the root of
    # x^3 - x + 1 (minus the plastic number)
    return {
        "name": "cusp x³ − x − b, b ∈ [−1, 1]",
        "example": ex.cusp_normal_form(a=1.0, b=-1.0),
        "x0": ex.cusp_start(1.0, -1.0),
        "lam0": -1.0,
        "lam1": 1.0,
        "folds": list(ex.cusp_folds(1.0)),
    }


def _truss():
    H = 0.5
    # mpmath, 40 digits: v = H(1 -+ 1/sqrt 3), P = K v (H - v)(2H - v), correctly rounded
    return {
        "name": "Green truss (EA = L = 1, H = 0.5), v ∈ [−0.5, 1.5]",
        "example": ex.truss_green(EA=1.0, L=1.0, H=H),
        "x0": -0.5,
        "lam0": ex.truss_green_force(-0.5, 1.0, 1.0, H),
        "lam1": ex.truss_green_force(1.5, 1.0, 1.0, H),
        "folds": list(ex.truss_green_limits(1.0, 1.0, H)),
    }


def trace_problems() -> list[dict]:
    """The problems of ``scripts/bench_trace.py`` (also timed by ``scripts/bench_ab.py`` and
    the work–precision benchmark): the cusp normal form and the Green truss, built afresh."""
    return [_cusp(), _truss()]
