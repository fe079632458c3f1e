"""
Branch points and switching
===========================

Where two branches cross, the Jacobian of the curve is rank deficient: a branch point.
The tracer locates it on the branch it traces, and a trace started *from* the located point
follows the other branch. The example: the pitchfork normal form
:math:`x(p - x^2) = 0`, whose trivial branch :math:`x = 0` meets the parabola
:math:`p = x^2` at the origin.
"""

import matplotlib.pyplot as plt

from cusp.continuation import Problem, diagram, trace

prob = Problem(lambda u, p: [u[0] * (p["p"] - u[0] ** 2)], unknowns=["x"], params={"p": -1.0})

# %%
# Trace the trivial branch
# ------------------------
# From :math:`x = 0` at :math:`p = -1`, up to :math:`p = 1`. The branch point is found by a
# sign change of the determinant of the curve's Jacobian and located by Newton.
trivial = trace(prob, [0.0], free="p", bounds={"p": (-1.0, 1.0)})
(bp,) = trivial.special("branch_point")
print(bp)
assert abs(bp.values["p"]) < 1e-10 and abs(bp.values["x"]) < 1e-10

# %%
# Switch branches
# ---------------
# Pass the located point as the start: the tracer takes the other branch's tangent from the
# algebraic bifurcation equation. ``direction`` picks the half-branch (here :math:`x > 0` or
# :math:`x < 0`).
upper = trace(prob, bp, free="p", bounds={"p": (-1.0, 1.0)}, direction=+1)
lower = trace(prob, bp, free="p", bounds={"p": (-1.0, 1.0)}, direction=-1)
for half in (upper, lower):
    x, p = half["x"], half["p"]
    print(f"{len(half)} points, x from {x.min():+.3f} to {x.max():+.3f}, max |p - x²| =",
          abs(p - x**2).max())  # fmt: skip
    assert abs(p - x**2).max() < 1e-9

# %%
# All of it at once
# -----------------
# :func:`~cusp.continuation.diagram` does this recursively: it traces the branch through the
# start both ways and, at every branch point it locates, the other branch, each branch once.
d = diagram(prob, [0.0], free="p", bounds={"p": (-1.0, 1.0)})
print(len(d.branches), "branches,", len(d.points), "branch point")

fig, ax = plt.subplots(figsize=(5, 3.5))
d.plot("p", "x", ax=ax)
ax.set_title("pitchfork $x(p - x^2) = 0$")
plt.show()

# %%
# Starting *at* a branch point is refused (there is no tangent to start along): start on
# the branch you want, or trace through the point and switch as above.
from cusp.continuation import SingularPointError

try:
    trace(prob, [0.0], free="p", params={"p": 0.0}, bounds={"p": (-1.0, 1.0)})
except SingularPointError as err:
    print("refused:", str(err)[:120], "...")
