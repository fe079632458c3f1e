"""A record of what the continuation engine computes, bit for bit, on the example problems.

    python scripts/record_behaviour.py           # write the record (RECORD, below)
    python scripts/record_behaviour.py --check   # compare with it, and name what differs

Every case traces a problem of :mod:`cusp.examples` (the published-problem suite with its
default options, its branch switches, perturbed starts, every catalogue example with each
derivative strategy, option variants, fold curves, loci, failures with ``throw=False``,
dense output and ``points_at``) and reduces the result to:

- the status, message, step count and number of points of each branch;
- every special point: kind, index, status, label, ``with_respect_to``, its values and
  arclength in full ``repr`` (17 significant digits: every bit), a SHA-256 of its tangent's
  float64 bytes and its details (floats in ``repr``, arrays hashed);
- a SHA-256 of the float64 bytes of every column, of the arclengths, the tangents and the
  per-point statistics, in order (so one changed bit anywhere changes it), and the hash of
  each column apart to say where a difference is;
- for a failure that raises: the error's type and message.

The record was made before the engine was restructured (issue 28) and guards that the
restructuring changed nothing: ``tests/continuation/test_behaviour_record.py`` recomputes it
and compares. Bits depend on the platform's floating point and on numpy's, scipy's and
LAPACK's versions; the record stores them (``environment``) and the test compares only in the
same environment.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import platform
import sys
import warnings
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import numpy as np
import scipy

import cusp.examples as ex
from cusp.continuation import (
    Branch,
    ChainPoint,
    ContinuationError,
    Event,
    PointChain,
    Problem,
    ProblemDefinitionError,
    fold_curve,
    locus,
    point_locus,
    points_at,
    trace,
)
from cusp.examples.suite import SUITE, perturbed

ROOT = Path(__file__).resolve().parents[1]
RECORD = ROOT / "tests" / "continuation" / "data" / "behaviour_record.json"
"""Where the record is kept."""


def environment() -> dict[str, str]:
    """What the bits depend on besides the engine."""
    return {
        "python": platform.python_version(),
        "machine": platform.machine(),
        "numpy": np.__version__,
        "scipy": scipy.__version__,
    }


# --------------------------------------------------------------------------- reduction


def _hash(*arrays: Any) -> str:
    h = hashlib.sha256()
    for a in arrays:
        h.update(np.ascontiguousarray(np.asarray(a, dtype=float)).tobytes())
    return h.hexdigest()[:32]


#: keys of ``Branch.info`` newer than the record
_NEWER_INFO = frozenset({"options", "resume"})


def _plain(x: Any) -> Any:
    """``x`` as JSON: floats in repr (every bit), arrays hashed, containers recursed."""
    if isinstance(x, bool) or x is None:
        return x
    if isinstance(x, str):
        return str.__str__(x)  # (a str-valued enumeration as its value)
    if isinstance(x, (int, np.integer)):
        return int(x)
    if isinstance(x, (float, np.floating)):
        return repr(float(x))
    if isinstance(x, np.ndarray):
        return {"array": list(x.shape), "sha": _hash(x)}
    if isinstance(x, dict):
        return {str(k): _plain(v) for k, v in sorted(x.items(), key=lambda kv: str(kv[0]))}
    if isinstance(x, (list, tuple)):
        return [_plain(v) for v in x]
    return repr(x)


def _sorted_values(d: dict[str, float]) -> list[float]:
    return [d[k] for k in sorted(d)]


def reduce_branch(br: Branch) -> dict[str, Any]:
    """The record of one branch (see the module docstring)."""
    keys = sorted(br.keys())
    stats = sorted(br.stats)
    columns = {k: _hash(br[k]) for k in keys}
    every = _hash(*(br[k] for k in keys), br.s, br.tangents, *(br.stats[k] for k in stats))
    specials = []
    for sp in br.special_points:
        specials.append(
            {
                "kind": _plain(sp.kind),
                "index": sp.index,
                "status": _plain(sp.status),
                "label": sp.label,
                "with_respect_to": sp.with_respect_to,
                "s": repr(float(sp.s)),
                "interval": _plain(sp.interval),
                "values": {k: repr(float(v)) for k, v in sp.values.items()},
                "tangent": _hash(sp.tangent),
                "scales": None if sp.scales is None else _hash(*_sorted_values(sp.scales)),
                "details": _plain(sp.details),
            }
        )
    return {
        "status": _plain(br.status),
        "success": br.success,
        "message": br.message,
        "points": len(br),
        "variables": list(br.variables),
        # (the options and the resume data, added to info by issue 31 after the record was
        # made, are left out: they describe the call and the state; the resume tests guard
        # them, tests/continuation/test_resume.py)
        "info": _plain({k: v for k, v in br.info.items() if k not in _NEWER_INFO}),
        "sha": every,
        "columns": columns,
        "s": _hash(br.s),
        "tangents": _hash(br.tangents),
        "stats": {k: _hash(br.stats[k]) for k in stats},
        "special_points": specials,
    }


def reduce(result: Any) -> Any:
    if isinstance(result, Branch):
        return reduce_branch(result)
    if isinstance(result, dict):
        return {str(k): reduce(v) for k, v in result.items()}
    if isinstance(result, (list, tuple)):
        return [reduce(v) for v in result]
    return _plain(result)


def run_case(compute: Callable[[], Any]) -> dict[str, Any]:
    """A case's record: its result reduced, or the error it raised; the warnings it gave."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            out: dict[str, Any] = {"result": reduce(compute())}
        except (ContinuationError, ProblemDefinitionError, ArithmeticError) as exc:
            out = {"error": type(exc).__name__, "message": str(exc)}
    out["warnings"] = [f"{w.category.__name__}: {w.message}" for w in caught]
    return out


# --------------------------------------------------------------------------- the cases


def _suite_cases() -> Iterator[tuple[str, Callable[[], Any]]]:
    for name, factory, kwargs in SUITE:
        yield f"suite/{name}", lambda f=factory, kw=kwargs: f(**kw).trace(throw=False)
        yield (
            f"perturbed/{name}",
            lambda f=factory, kw=kwargs: perturbed(f(**kw), 1e-10, seed=1).trace(throw=False),
        )
        yield f"switch/{name}", lambda f=factory, kw=kwargs: _switches(f(**kw))


def _switches(example: Any) -> list[Any]:
    """Every branch point of the example's branch left in both directions (60 steps)."""
    br = example.trace(throw=False)
    out = []
    for sp in br.special("branch_point"):
        for direction in (1, -1):
            out.append(
                trace(
                    example.problem,
                    sp,
                    free=example.free,
                    bounds=dict(example.bounds),
                    direction=direction,
                    max_steps=60,
                    throw=False,
                )
            )
    return out


def _catalogue_cases() -> Iterator[tuple[str, Callable[[], Any]]]:
    for name, factory in ex.CATALOGUE.items():
        for how in ex.DERIVATIVES:
            yield (
                f"catalogue/{name}/{how}",
                lambda f=factory, how=how: f(derivatives=how).trace(throw=False),
            )


def _variants() -> Iterator[tuple[str, Callable[[], Any]]]:
    cusp = ex.cusp_normal_form
    yield "variant/cusp/secant", lambda: cusp().trace(predictor="secant", throw=False)
    for rtol in (1e-2, 1e-6, 1e-10):
        yield f"variant/cusp/rtol{rtol:g}", lambda r=rtol: cusp().trace(rtol=r, throw=False)
    yield "variant/cusp/direction-1", lambda: cusp().trace(direction=-1, throw=False)
    yield "variant/cusp/scales", lambda: cusp().trace(scales={"x": 10.0, "b": 0.1}, throw=False)
    yield "variant/cusp/ds_max", lambda: cusp().trace(ds_max=0.01, ds=0.01, throw=False)
    yield (
        "variant/cusp/targets-events",
        lambda: cusp().trace(
            targets={"b": [0.1, -0.2], "x": [0.5]},
            events=[
                Event(lambda u, p: u[0] - 0.2, label="x=0.2"),
                Event(lambda u, p: u[0] + 0.9, direction=1, label="x=-0.9"),
            ],
            throw=False,
        ),
    )
    yield (
        "variant/cusp/terminal",
        lambda: cusp().trace(
            events=[Event(lambda u, p: u[0], label="x=0", terminal=True)], throw=False
        ),
    )
    yield "variant/cusp/max_steps", lambda: cusp().trace(max_steps=5, throw=False)
    yield "variant/cusp/no-folds", lambda: cusp().trace(detect_folds=False, throw=False)
    yield (
        "variant/truss/state_weight",
        lambda: ex.truss_green().trace(state_weight=0.3, throw=False),
    )
    yield (
        "variant/truss_2dof/no-bp",
        lambda: ex.truss_2dof().trace(detect_branch_points=False, throw=False),
    )
    yield (
        "variant/truss_2dof/secant",
        lambda: ex.truss_2dof().trace(predictor="secant", throw=False),
    )
    yield "variant/bratu200/sparse", lambda: ex.bratu(200, sparse=True).trace(throw=False)
    yield "variant/bratu60/dense", lambda: ex.bratu(60).trace(throw=False)
    yield "variant/chafee60/sparse", lambda: ex.chafee_infante(60, sparse=True).trace(throw=False)
    yield "variant/step-api", _step_api
    yield "variant/dense-output", _dense_output
    yield "variant/points_at", _points_at


def _step_api() -> list[Any]:
    """The step-level API, and stepping twice from a kept state."""
    from cusp.continuation import Tracer

    e = ex.truss_2dof()
    tracer = Tracer(e.problem, free=e.free, bounds=dict(e.bounds), throw=False)
    state = tracer.init(e.u0)
    kept = None
    while not tracer.done(state):
        state = tracer.step(state)
        if state.steps == 5:
            kept = state
    first = tracer.result(state)
    assert kept is not None
    state = kept
    while not tracer.done(state):
        state = tracer.step(state)
    return [first, tracer.result(state), tracer.result(kept)]


def _dense_output() -> dict[str, Any]:
    br = ex.cusp_normal_form().trace(rtol=1e-6)
    s = np.linspace(br.s[0], br.s[-1], 101)
    mids = br.interpolate(s)
    at = br.interpolate_at("x", np.linspace(-1.2, 1.2, 25))
    arch = ex.shallow_arch().trace()
    arch_mid = arch.interpolate(0.5 * (arch.s[1:] + arch.s[:-1]))
    return {
        "interpolate": {k: _hash(v) for k, v in sorted(mids.items())},
        "interpolate_at": {k: _hash(v) for k, v in sorted(at.items())},
        "arch": {k: _hash(v) for k, v in sorted(arch_mid.items())},
    }


def _points_at() -> dict[str, Any]:
    e = ex.truss_green()
    br = e.trace()
    name = e.free
    lo, hi = float(np.min(br[name])), float(np.max(br[name]))
    cols = points_at(e.problem, br, name, np.linspace(lo, hi, 9)[1:-1])
    return {k: _hash(v) for k, v in sorted(cols.items())}


def _curves() -> Iterator[tuple[str, Callable[[], Any]]]:
    def fold_of(example: Any, second: str, bounds: dict, how: str = "analytic", i: int = 0):
        def run() -> Any:
            e = example(derivatives=how)
            br = e.trace()
            fold = br.special("fold")[i]
            return fold_curve(e.problem, fold, free=(e.free, second), bounds=bounds, throw=False)

        return run

    yield "fold_curve/cusp", fold_of(ex.cusp_normal_form, "a", {"a": (-1.0, 2.0)})
    yield (
        "fold_curve/cusp/central",
        fold_of(ex.cusp_normal_form, "a", {"a": (-1.0, 2.0)}, "central"),
    )
    yield "fold_curve/co", fold_of(ex.co_oxidation, "k", {"k": (0.0, 2.2)})
    yield "fold_curve/co/central", fold_of(ex.co_oxidation, "k", {"k": (0.0, 2.2)}, "central")
    yield "fold_curve/co/forward", fold_of(ex.co_oxidation, "k", {"k": (0.0, 2.2)}, "forward")
    yield "fold_curve/ab", fold_of(ex.ab_reactor, "p3", {"p3": (0.5, 3.0)})
    yield "fold_curve/arch", fold_of(ex.shallow_arch, "e", {"e": (3.0, 7.0)})
    yield "fold_curve/snapback", _snapback_curve
    yield "locus/bound", _bound_locus
    yield "locus/chain", _chain_locus


def _snapback_curve() -> Any:
    """The snap-back of a truss in series with a spring (a fold of the monitored δ) continued
    in the spring's stiffness to its cusp (tests/continuation/test_foldcurve.py)."""
    prob = ex.snapback_monitor(H=0.1, ks=0.005, derivatives="complex").problem
    br = trace(
        prob, [0.0, 0.0], free="P", monitor=["delta"], bounds={"v": (-0.01, 0.25)}, ds_max=0.05
    )
    snap = br.special("fold", with_respect_to="delta")
    return fold_curve(
        prob, snap[0], free=("P", "ks"), bounds={"ks": (0.001, 0.02)}, ds_max=0.05, throw=False
    )


def _bound_locus() -> Any:
    prob = Problem(lambda u, p: [u[0] ** 2 - p["b"] * p["a"]], ["x"], {"a": 1.0, "b": 1.0})
    br = trace(prob, [1.0], free="b", bounds={"b": (0.5, 2.0)})
    end = br.special("endpoint")[-1]
    return point_locus(prob, end, free=("b", "a"), bounds={"a": (1.0, 8.0)}, throw=False)


def _chain_locus() -> Any:
    leg1 = Problem(lambda u, p: [u[0] ** 2 - p["p"] * p["a"]], ["x"], {"p": 0.5, "a": 1.0})
    leg2 = Problem(lambda u, p: [u[0] ** 3 + u[0] - p["xA"] - p["q"]], ["y"], {"q": 0.0, "xA": 1.0})
    chain = PointChain(
        [
            ChainPoint("A", leg1, "p", ("p", 1.0)),
            ChainPoint("B", leg2, "q", ("q", 0.0), links={"xA": ("A", "x")}),
        ]
    )
    return locus(
        chain,
        {"A": {"x": 1.0, "p": 1.0}, "B": {"y": 0.7, "q": 0.0}},
        free="a",
        bounds={"a": (0.25, 9.0)},
        throw=False,
    )


def _failures() -> Iterator[tuple[str, Callable[[], Any]]]:
    def sqrt_edge() -> Any:  # u = √(1 − p): the edge of the domain at p = 1
        prob = Problem(lambda u, p: [u[0] - np.sqrt(1.0 - p["p"])], ["u"], {"p": 0.0})
        return trace(prob, [1.0], free="p", bounds={"p": (-1.0, 2.0)}, throw=False)

    def cube() -> Any:  # x = p³ diverges
        prob = Problem(
            lambda u, p: [u[0] - p["p"] ** 3],
            ["x"],
            {"p": 1.0},
            jacobian=lambda u, p: [[1.0]],
            param_jacobian=lambda u, p, name: [-3.0 * p["p"] ** 2],
        )
        return trace(prob, [1.0], free="p", max_steps=5000, throw=False)

    def kink() -> Any:  # |x| − p: a corner at the origin
        prob = Problem(lambda u, p: [abs(u[0] - 0.3) - p["p"] + 0.1 * u[0]], ["x"], {"p": 1.0})
        return trace(prob, [1.3 / 1.1], free="p", bounds={"x": (-2.0, 2.0)}, throw=False)

    def wrong_jacobian() -> Any:
        prob = Problem(
            lambda u, p: [u[0] ** 3 - u[0] - p["b"]],
            ["x"],
            {"b": -1.0},
            jacobian=lambda u, p: [[3 * u[0] ** 2 + 1.0]],
            param_jacobian=lambda u, p, n: [-1.0],
        )
        return trace(prob, [-1.3247], free="b", bounds={"b": (-1.0, 1.0)}, throw=False)

    def singular_start() -> Any:
        prob = Problem(lambda u, p: [u[0] * (p["p"] - u[0])], ["x"], {"p": 0.0})
        return trace(prob, [0.0], free="p", throw=False)

    def fold_start() -> Any:
        prob = Problem(lambda u, p: [u[0] ** 2 - p["p"]], ["x"], {"p": 0.0})
        return trace(prob, [0.0], free="p", bounds={"p": (-1.0, 1.0)}, throw=False)

    def bad_start() -> Any:
        prob = Problem(lambda u, p: [u[0] ** 2 + 1.0 + p["p"]], ["x"], {"p": 0.0})
        return trace(prob, [0.3], free="p", throw=False)

    def nan_ahead() -> Any:
        def residual(u, p):
            return [u[0] - p["p"] if p["p"] < 0.5 else math.nan]

        prob = Problem(residual, ["x"], {"p": 0.0})
        return trace(prob, [0.0], free="p", bounds={"p": (-1.0, 1.0)}, throw=False)

    def guard() -> Any:  # x³ + x − b whose Jacobian is 0.6 times too small beyond b = 0.5
        prob = Problem(
            lambda u, p: np.array([u[0] ** 3 + u[0] - p["b"]]),
            ["x"],
            {"b": 0.0},
            jacobian=lambda u, p: np.array(
                [[(0.6 if p["b"] > 0.5 else 1.0) * (3 * u[0] ** 2 + 1)]]
            ),
        )
        return trace(prob, [0.0], free="b", bounds={"b": (-1.0, 1.0)}, throw=False)

    def jump() -> Any:  # a jump of the residual at b = 0
        def res(u, p):
            return np.array([u[0] - p["b"] + (1.0 if p["b"] > 0 else 0.0) * (1 + u[0] ** 2)])

        return trace(Problem(res, ["x"], {"b": -1.0}), [-1.0], free="b", max_steps=500, throw=False)

    def stalled() -> Any:  # one corrector solve a step cannot confirm a branch point's step
        prob = ex.lorenz(derivatives="central").problem
        return trace(
            prob.with_params(rho=0.5), [0.0, 0.0, 0.0], free="rho", bounds={"rho": (0.0, 3.0)},
            max_step_solves=1, throw=False,
        )  # fmt: skip

    for name, fn in (
        ("guard", guard),
        ("jump", jump),
        ("stalled", stalled),
        ("sqrt_edge", sqrt_edge),
        ("cube", cube),
        ("kink", kink),
        ("wrong_jacobian", wrong_jacobian),
        ("singular_start", singular_start),
        ("fold_start", fold_start),
        ("bad_start", bad_start),
        ("nan_ahead", nan_ahead),
    ):
        yield f"failure/{name}", fn


def cases() -> Iterator[tuple[str, Callable[[], Any]]]:
    """Every case of the record, by name."""
    yield from _suite_cases()
    yield from _catalogue_cases()
    yield from _variants()
    yield from _curves()
    yield from _failures()


def compute(select: Callable[[str], bool] = lambda name: True) -> dict[str, Any]:
    """The record of every case ``select`` accepts."""
    with np.errstate(all="ignore"):
        return {name: run_case(fn) for name, fn in cases() if select(name)}


def differences(old: Any, new: Any, where: str = "") -> list[str]:
    """Where two records differ (paths into them), the first few of each case."""
    if isinstance(old, dict) and isinstance(new, dict):
        out = []
        for key in sorted(set(old) | set(new)):
            if key not in old or key not in new:
                out.append(f"{where}/{key}: only in the {'new' if key in new else 'old'} record")
            else:
                out += differences(old[key], new[key], f"{where}/{key}")
        return out
    if isinstance(old, list) and isinstance(new, list):
        if len(old) != len(new):
            return [f"{where}: {len(old)} entries, now {len(new)}"]
        out = []
        for i, (a, b) in enumerate(zip(old, new)):
            out += differences(a, b, f"{where}[{i}]")
        return out
    return [] if old == new else [f"{where}: {old!r} -> {new!r}"]


def dumps(record: dict[str, Any]) -> str:
    """The record as JSON text: compact, one case a line (diffs name the cases)."""
    lines = [
        f"{json.dumps(name)}:{json.dumps(case, sort_keys=True, separators=(',', ':'))}"
        for name, case in sorted(record.items())
    ]
    env = json.dumps(environment(), sort_keys=True)
    return '{"environment":' + env + ',"cases":{\n' + ",\n".join(lines) + "\n}}\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--check", action="store_true", help="compare with the stored record")
    ap.add_argument("--out", type=Path, default=RECORD)
    ap.add_argument("--only", default="", help="only the cases whose name contains this")
    args = ap.parse_args(argv)
    record = compute(lambda name: args.only in name)
    if args.check:
        stored = json.loads(args.out.read_text(encoding="utf-8"))
        if stored["environment"] != environment():
            print(f"recorded in {stored['environment']}, this is {environment()}")
        old = {k: v for k, v in stored["cases"].items() if args.only in k}
        diff = differences(old, record)
        print("\n".join(diff[:50]) or f"identical: {len(record)} cases")
        return 1 if diff else 0
    args.out.parent.mkdir(parents=True, exist_ok=True)
    tmp = args.out.with_suffix(".tmp")
    tmp.write_text(dumps(record), encoding="utf-8")
    tmp.replace(args.out)
    print(f"{len(record)} cases written to {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
