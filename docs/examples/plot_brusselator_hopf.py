"""
The Brusselator: stability and a Hopf point
===========================================

:func:`cusp.examples.brusselator`'s kinetics without diffusion,
:math:`x' = a - (b + 1)x + x^2 y`, :math:`y' = b x - x^2 y`: the equilibrium
:math:`(a, b/a)` loses stability at the Hopf point :math:`b = 1 + a^2` with frequency
:math:`\\omega = a`. ``stability=True`` computes the eigenvalues along the branch and
locates the Hopf point with its first Lyapunov coefficient; the plot draws stable parts
solid and unstable ones dashed. The Hopf curve in :math:`(b, a)` follows the parabola.
"""

import matplotlib.pyplot as plt
import numpy as np

from cusp.continuation import Problem, hopf_curve, trace


def brusselator(u, p):
    x, y = u
    return [p["a"] - (p["b"] + 1) * x + x * x * y, p["b"] * x - x * x * y]


prob = Problem(brusselator, ["x", "y"], {"a": 2.0, "b": 3.0}, mass=True)
br = trace(prob, [2.0, 1.5], free="b", bounds={"b": (3, 7)}, stability=True)
(h,) = br.special("hopf")
print("Hopf at b =", h.values["b"], "omega =", h.details["omega"])
print("first Lyapunov coefficient", h.details["first_lyapunov"])
assert abs(h.values["b"] - 5.0) < 1e-8 and abs(h.details["omega"] - 2.0) < 1e-8

curve = hopf_curve(prob, h, free=("b", "a"), bounds={"a": (0.5, 2.5)})
print("largest distance from b = 1 + a²:", np.max(np.abs(curve["b"] - 1 - curve["a"] ** 2)))

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.8))
br.plot("b", "y", ax=ax1)
ax1.set_title("equilibria at $a = 2$")
curve.plot("a", "b", ax=ax2)
ax2.set_title("the Hopf curve $b = 1 + a^2$")
plt.show()
