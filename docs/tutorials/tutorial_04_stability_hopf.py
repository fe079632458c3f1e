"""
Stability and Hopf points
=========================

A problem that is a vector field, :math:`u' = R(u, p)`, says so with ``mass=True`` (or a
mass matrix :math:`M` for :math:`M u' = R`). Then ``trace(..., stability=True)`` computes the
eigenvalues of the Jacobian at every point, counts the unstable ones and locates Hopf
points, where a complex pair crosses the imaginary axis.

The Brusselator, :math:`x' = a - (b + 1)x + x^2 y`, :math:`y' = b x - x^2 y`, has the
equilibrium :math:`(a, b/a)`; its Jacobian has trace :math:`b - 1 - a^2` and determinant
:math:`a^2`, so a Hopf point lies at :math:`b = 1 + a^2` with frequency :math:`\\omega = a`.
"""

import matplotlib.pyplot as plt
import numpy as np

from cusp.continuation import Problem, hopf_curve, trace


def brusselator(u, p):
    x, y = u
    return [p["a"] - (p["b"] + 1) * x + x * x * y, p["b"] * x - x * x * y]


prob = Problem(brusselator, ["x", "y"], {"a": 2.0, "b": 3.0}, mass=True)
br = trace(prob, [2.0, 1.5], free="b", bounds={"b": (3, 7)}, stability=True)

# %%
# Eigenvalues and the unstable count
# ----------------------------------
# ``br.eigenvalues[i]``: the eigenvalues at row ``i`` by decreasing real part;
# ``br["n_unstable"]``: how many have a positive real part.
print(br.eigenvalues[0], "->", br.eigenvalues[-1])
print("unstable eigenvalues along the branch:", sorted({int(n) for n in br["n_unstable"]}))

# %%
# The Hopf point
# --------------
# Located by Newton on the extended system; ``details`` carry the frequency and the first
# Lyapunov coefficient (negative: supercritical, a stable limit cycle is born).
(h,) = br.special("hopf")
print(h.values, h.details["omega"], h.details["first_lyapunov"])
assert abs(h.values["b"] - 5.0) < 1e-8 and abs(h.details["omega"] - 2.0) < 1e-8
assert h.details["first_lyapunov"] < 0

# %%
# The Hopf curve
# --------------
# Continue the Hopf point in :math:`(b, a)`; it follows :math:`b = 1 + a^2`.
curve = hopf_curve(prob, h, free=("b", "a"), bounds={"a": (0.5, 2.5)})
err = np.max(np.abs(curve["b"] - 1 - curve["a"] ** 2))
print("largest |b − 1 − a²| on the Hopf curve:", err)
assert err < 1e-8

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.6))
br.plot("b", "x", ax=ax1)  # stable solid, unstable dashed
ax1.set_title("equilibria at $a = 2$")
curve.plot("a", "b", ax=ax2)
ax2.set_title("Hopf curve")
plt.show()
