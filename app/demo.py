"""``cusp demo``: trace the cusp normal form x³ − a·x − b = 0 over b ∈ [−1, 1] at fixed a and
print the folds, compared with the closed form b = ∓2(a/3)^{3/2}."""

from __future__ import annotations

import math
import time


def add_arguments(parser) -> None:
    parser.add_argument("--a", type=float, default=1.0, help="fixed parameter a > 0 (default 1)")


def main(args) -> int:
    from cusp.continuation import trace
    from cusp.examples import cusp_normal_form

    a = args.a
    if not (math.isfinite(a) and a > 0):
        print(f"cusp demo: --a must be a finite number > 0, got {a!r}")
        return 2
    exact = 2.0 * (a / 3.0) ** 1.5
    bmax = max(1.0, 2.0 * exact)  # wide enough to hold both folds
    # analytic derivatives; u0 the leftmost real root at b = -bmax; bounds b in [-bmax, bmax]
    example = cusp_normal_form(a=a, b=-bmax)
    start = time.perf_counter()
    # the folds are printed to 15 decimals: located to that (the default is 1e-12 relative)
    br = trace(example.problem, example.u0, free="b", bounds=example.bounds, locate_tol=1e-15)
    elapsed = time.perf_counter() - start
    print(f"cusp normal form x^3 - a x - b = 0, a = {a:g}: traced b in [{-bmax:g}, {bmax:g}]")
    print(f"  {len(br)} points, status {br.status!r}: {br.message} ({elapsed * 1e3:.2f} ms)")
    print(f"  {'kind':<10}{'x':>22}{'b':>22}{'|b| - 2(a/3)^1.5':>20}  status")
    for sp in br.special_points:
        if sp.kind != "fold":
            continue
        err = abs(sp.values["b"]) - exact
        print(
            f"  {sp.kind:<10}{sp.values['x']:>22.15f}{sp.values['b']:>22.15f}{err:>20.2e}  "
            f"{sp.status}"
        )
    return 0 if br.success else 1
