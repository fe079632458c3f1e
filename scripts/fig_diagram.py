"""Draw a whole bifurcation diagram in one call: the discretised Chafee–Infante equation
u'' + λ(u − u³) = 0 on (0, π), u(0) = u(π) = 0 (n = 40 nodes, λ ∈ [0, 20]): the trivial
branch, its four pitchforks at λ_k = (4/h²) sin²(kh/2) ≈ k², and the branch of each mode,
each traced once; plus the isola x((x − 3)² + (λ − 2)² − 1) = 0 found by deflation.

    python scripts/fig_diagram.py [--out docs/figures/diagram.png]
"""

from __future__ import annotations

import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from cusp._scripts.report import save_figure  # noqa: E402
from cusp.continuation import Problem, diagram  # noqa: E402
from cusp.examples.symmetric import chafee_infante  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[1]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=str(ROOT / "docs" / "figures" / "diagram.png"))
    args = ap.parse_args(argv)
    ex = chafee_infante(40, lam_max=20.0)
    d = diagram(ex.problem, ex.u0, free="lam", bounds={"lam": (0.0, 20.0)})
    isola = Problem(
        lambda u, p: [u[0] * ((u[0] - 3.0) ** 2 + (p["lam"] - 2.0) ** 2 - 1.0)],
        ["x"], {"lam": 0.0},
    )  # fmt: skip
    di = diagram(isola, [0.0], free="lam", bounds={"lam": (0.0, 5.0), "x": (-1.0, 6.0)},
                 deflation={"at": [2.0], "guesses": [[1.0]]})  # fmt: skip
    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4))
    d.plot("lam", "u10", ax=a)  # u at x = 10π/41, a quarter of the way
    a.set_ylabel("u(10π/41)")
    a.set_title(f"Chafee–Infante, n = 40: {len(d.branches)} branches, {len(d.points)} points")
    a.legend(fontsize=7)
    di.plot("lam", "x", ax=b)
    b.set_title("an isola found by deflation at λ = 2")
    b.legend(fontsize=7)
    fig.tight_layout()
    print(d, di)
    print(f"wrote {save_figure(fig, args.out)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
