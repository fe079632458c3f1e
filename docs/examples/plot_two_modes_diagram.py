"""
A whole bifurcation diagram in one call
=======================================

:func:`cusp.continuation.diagram` on two interacting modes,
:math:`x(\\lambda - 1 - x^2 - y^2/2) = 0`, :math:`y(\\lambda - 2 - y^2 - x^2/2) = 0`
(:func:`cusp.examples.diagrams.two_modes`): from the trivial branch it switches at every
located branch point (:math:`\\lambda = 1, 2` on the trivial branch, :math:`\\lambda = 3` on
the x-branch) and traces each branch once.
"""

import matplotlib.pyplot as plt

from cusp.continuation import diagram
from cusp.examples.diagrams import two_modes

d = diagram(two_modes(), [0.0, 0.0], free="lam", bounds={"lam": (0.0, 6.0)})
for point in sorted(d.points, key=lambda p: p.point.values["lam"]):
    print("branch point at lam =", round(point.point.values["lam"], 10))
print(len(d.branches), "branches")
found = sorted(round(p.point.values["lam"], 9) for p in d.points)
assert found == [1.0, 2.0, 3.0, 3.0] and len(d.branches) == 5  # the closed forms

fig, ax = plt.subplots(figsize=(5.5, 4))
d.plot("lam", "x", ax=ax)
ax.set_xlabel(r"$\lambda$")
plt.show()
