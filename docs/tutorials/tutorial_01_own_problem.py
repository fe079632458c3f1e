"""
Trace your own problem
======================

From a Python function to its located folds and a plot. The problem here is an equilibrium
of a bar on a spring, written as one residual; any function ``residual(u, p)`` returning as
many residuals as there are unknowns will do.
"""

# %%
# Write the residual
# ------------------
# The residual takes the unknowns ``u`` (a float array) and the parameters ``p`` (a dict by
# name), and returns one number per unknown. Here: the cusp normal form
# :math:`x^3 - a x - b = 0`, whose folds lie on :math:`4 a^3 = 27 b^2`.
from cusp.continuation import Problem, trace


def residual(u, p):
    x = u[0]
    return [x**3 - p["a"] * x - p["b"]]


prob = Problem(residual, unknowns=["x"], params={"a": 1.0, "b": -1.0})

# %%
# Trace a branch
# --------------
# Start at a point on the curve (here :math:`x_0` solves :math:`x^3 - x + 1 = 0`; the
# tracer corrects a rough start by Newton's method), name the free parameter and its
# bounds. Derivatives not supplied are computed by central differences.
br = trace(prob, u0=[-1.3247], free="b", bounds={"b": (-1.0, 1.0)})
print(br)

# %%
# The located folds
# -----------------
# Turning points are located to the tolerance of the options (``rtol``, default 1e-3,
# keeps located points to about 1e-12 relative). At :math:`a = 1` the closed form is
# :math:`b = \pm 2/(3\sqrt{3})`, :math:`x = \mp 1/\sqrt{3}`.
import math

for sp in br.special("fold"):
    print(sp.kind, {k: round(v, 12) for k, v in sp.values.items()})
exact = 2 / (3 * math.sqrt(3))
folds = sorted(sp.values["b"] for sp in br.special("fold"))
assert all(abs(abs(b) - exact) < 1e-10 for b in folds)

# %%
# Plot it
# -------
# :meth:`~cusp.continuation.Branch.plot` draws a column against another and marks the
# special points; it returns the matplotlib axes.
import matplotlib.pyplot as plt

fig, ax = plt.subplots(figsize=(5, 3.5))
br.plot("b", "x", ax=ax)
ax.set_title("$x^3 - a x - b = 0$ at $a = 1$")
plt.show()

# %%
# Give the derivatives (optional)
# -------------------------------
# Hand-written derivatives make each step cheaper and exact to rounding.
# :func:`~cusp.continuation.check_jacobian` compares them with finite differences before
# you trust them.
import numpy as np

from cusp.continuation import check_jacobian


def jacobian(u, p):
    return np.array([[3 * u[0] ** 2 - p["a"]]])


def param_jacobian(u, p, name):
    return np.array([-u[0] if name == "a" else -1.0])


prob2 = Problem(
    residual,
    unknowns=["x"],
    params={"a": 1.0, "b": -1.0},
    jacobian=jacobian,
    param_jacobian=param_jacobian,
)
print(check_jacobian(prob2, np.array([0.3]), {"a": 1.0, "b": 0.2}))
br2 = trace(prob2, u0=[-1.3247], free="b", bounds={"b": (-1.0, 1.0)})
print(len(br2), "points;", len(br.special("fold")), "folds as before")
