"""Cost of stability along a branch (issue 29): ``trace`` with and without
``stability=True``, best of a few runs each, written to ``docs/benchmarks/stability.md``
(atomically).

Usage (from the repository root): ``python scripts/bench_stability.py [--cells 5000]``

- sparse: the 1D Brusselator with equal diffusion (2·cells unknowns, default 10⁴), b from 4.5
  to 5.5 (two Hopf points: the uniform mode at b = 5 and mode 1);
- dense ring: 25 Brusselator cells coupled in a ring (50 unknowns, analytic dense
  Jacobian), b from 4.5 to 5.5: the uniform mode's Hopf point at b = 5 and the ring's modes
  k at b = 5 + 0.4(1 − cos(2πk/25)); modes k and 25 − k are one double pair (a symmetric
  problem), where the Hopf system is singular: located with their multiplicity, or
  reported as guesses;
- dense chain: the same 25 cells in a chain (free ends), whose modes are simple, b from
  4.5 to 5.5.

Each is timed three ways, interleaved, best of ``--rounds``: the trace alone, with
``stability=StabilityOptions(hopf=False)`` (eigenvalues and ``n_unstable`` at every row),
and with ``stability=True`` (also the Hopf points located, with their Lyapunov
coefficients). The traces are short (the homogeneous branch is a straight line in b: a
handful of steps), so the located Hopf points weigh heavily.

The issue asks for at most "a few times" the trace without stability (sparse) and at most
+50 % (dense ≤ 50 unknowns).
"""

from __future__ import annotations

import argparse
import os
import time

# one BLAS thread: on this shared 2-core machine OpenBLAS's threads made a 152×152 getrf
# take 15-20 ms instead of 0.23 ms, drowning every ratio in contention
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
from pathlib import Path

import numpy as np  # noqa: E402
import scipy.sparse as sp  # noqa: E402

from cusp._scripts.report import commit_and_load, write_report  # noqa: E402
from cusp.continuation import Problem, StabilityOptions, trace  # noqa: E402

A, D = 2.0, 0.01
ROOT = Path(__file__).resolve().parents[1]


def rd_problem(cells: int) -> Problem:
    """The sparse 1D Brusselator (Neumann ends, interleaved x, y; as in the tests)."""
    h = 1.0 / (cells - 1)
    off = np.ones(cells - 1)
    lap = sp.diags([off, -2.0 * np.ones(cells), off], [-1, 0, 1]).tolil()
    lap[0, 1] = lap[cells - 1, cells - 2] = 2.0
    lap = lap.tocsc() * (D / (h * h))
    perm = np.arange(2 * cells).reshape(2, cells).T.ravel()
    big = sp.block_diag([lap, lap]).tocsc()[perm][:, perm]
    return _problem(cells, big, sparse=True)


def ring_problem(cells: int, closed: bool = True) -> Problem:
    """Brusselator cells coupled in a ring (or, ``closed=False``, a chain; dense Jacobian)."""
    ring = -2.0 * np.eye(cells) + np.roll(np.eye(cells), 1, 1) + np.roll(np.eye(cells), -1, 1)
    if not closed:
        ring[0, -1] = ring[-1, 0] = 0.0
        ring[0, 0] = ring[-1, -1] = -1.0
    perm = np.arange(2 * cells).reshape(2, cells).T.ravel()
    big = np.kron(np.eye(2), ring * 0.1)[perm][:, perm]
    return _problem(cells, big, sparse=False)


def _problem(cells: int, coupling, sparse: bool) -> Problem:
    def residual(u, p):
        x, y, b = u[0::2], u[1::2], p["b"]
        out = np.empty_like(u)
        out[0::2] = A - (b + 1) * x + x * x * y
        out[1::2] = b * x - x * x * y
        return out + coupling @ u

    def jacobian(u, p):
        x, y, b = u[0::2], u[1::2], p["b"]
        n2 = 2 * cells
        diag = np.empty(n2)
        diag[0::2], diag[1::2] = -(b + 1) + 2 * x * y, -x * x
        up, lo = np.zeros(n2 - 1), np.zeros(n2 - 1)
        up[0::2], lo[0::2] = x * x, b - 2 * x * y
        local = sp.diags([lo, diag, up], [-1, 0, 1], format="csc")
        return (local + coupling).tocsc() if sparse else local.toarray() + coupling

    def param_jacobian(u, p, name):
        out = np.empty_like(u)
        out[0::2], out[1::2] = -u[0::2], u[0::2]
        return out

    names = [f"{c}{i}" for i in range(cells) for c in "xy"]
    return Problem(residual, names, {"b": 4.5}, jacobian=jacobian,
                   param_jacobian=param_jacobian, mass=True)  # fmt: skip


def measure(prob: Problem, cells: int, rounds: int) -> dict:
    """Times of the three ways (interleaved, best of ``rounds``) and what they found."""
    u0 = np.tile([A, 4.5 / A], cells)
    kw = {"free": "b", "bounds": {"b": (4.5, 5.5)}}
    ways = {
        "plain": lambda: trace(prob, u0, **kw),
        "eig": lambda: trace(prob, u0, stability=StabilityOptions(hopf=False), **kw),
        "stab": lambda: trace(prob, u0, stability=True, **kw),
    }
    times: dict[str, list[float]] = {k: [] for k in ways}
    out = {}
    for _ in range(rounds):
        for key, fn in ways.items():
            t = time.perf_counter()
            out[key] = fn()
            times[key].append(time.perf_counter() - t)
    stab = out["stab"]
    hopf = [round(sp_.values["b"], 10) for sp_ in stab.special("hopf", status="converged")]
    return {
        "n": 2 * cells, "points": len(out["plain"]), "hopf": hopf,
        "guesses": len(stab.special("hopf", status="guess")),
        **{key: min(v) for key, v in times.items()},
    }  # fmt: skip


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--cells", type=int, default=5000)
    ap.add_argument("--rounds", type=int, default=3)
    args = ap.parse_args(argv)
    rows = [
        ("sparse 1D Brusselator", measure(rd_problem(args.cells), args.cells, args.rounds)),
        ("dense Brusselator ring", measure(ring_problem(25), 25, max(args.rounds, 5))),
        ("dense Brusselator chain", measure(ring_problem(25, False), 25, max(args.rounds, 5))),
    ]
    commit, load = commit_and_load()
    lines = [
        "# Stability along a branch: cost",
        "",
        f"`python scripts/bench_stability.py --cells {args.cells}` at {commit} "
        f"(load {load:.1f}; best of {args.rounds}+ interleaved runs in one process, "
        f"OPENBLAS_NUM_THREADS={os.environ['OPENBLAS_NUM_THREADS']}). "
        "`trace(..., stability=...)` against the same trace without it (issue 29: sparse at "
        "most a few times, dense ≤ 50 unknowns at most +50 %). *eigenvalues*: "
        "`StabilityOptions(hopf=False)`, every row's eigenvalues and `n_unstable`; *with "
        "Hopf*: `stability=True`, also the Hopf points located with their first Lyapunov "
        "coefficients.",
        "",
        "| problem | unknowns | points | trace (s) | eigenvalues (s) | ratio | with Hopf (s) "
        "| ratio | Hopf points b (converged) | guesses |",
        "|---|---|---|---|---|---|---|---|---|---|",
    ]
    for name, r in rows:
        lines.append(
            f"| {name} | {r['n']} | {r['points']} | {r['plain']:.3f} | {r['eig']:.3f} | "
            f"{r['eig'] / r['plain']:.2f} | {r['stab']:.3f} | {r['stab'] / r['plain']:.2f} | "
            f"{r['hopf']} | {r['guesses']} |"
        )
    text = "\n".join(lines) + "\n"
    write_report(ROOT / "docs" / "benchmarks" / "stability.md", text)
    print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
