"""
Choosing ``rtol``
=================

One knob sets the accuracy of everything the solver reports: ``rtol``, the relative
accuracy of the curve between its points (default 1e-3, allowed [1e-13, 1e-2]). Points
that Newton places (folds, branch points, the points A–D, energies) are converged far below
``rtol`` at every level, because one more Newton iteration is nearly free; what a smaller
``rtol`` buys is a denser curve, and that costs steps. This tutorial measures both on the
cusp normal form, whose folds are known in closed form, and on the Fig 6 path.
"""

import math

import matplotlib.pyplot as plt

from cusp.continuation import Problem, trace

prob = Problem(lambda u, p: [u[0] ** 3 - p["a"] * u[0] - p["b"]], ["x"], {"a": 1.0, "b": -1.0})
exact = 2 / (3 * math.sqrt(3))  # the folds at b = ±2/(3√3)

rows = []
for rtol in (1e-2, 1e-3, 1e-6, 1e-9):
    br = trace(prob, [-1.3247], free="b", bounds={"b": (-1.0, 1.0)}, rtol=rtol)
    err = max(abs(abs(sp.values["b"]) - exact) for sp in br.special("fold"))
    rows.append((rtol, len(br), err))
    print(f"rtol = {rtol:.0e}: {len(br):4d} points, fold error {err:.1e}")
    assert err < 1e-12  # folds at rounding level, whatever rtol

# %%
# Fewer points, same folds
# ------------------------
# The number of points grows as ``rtol`` falls; the folds' error does not follow it.
fig, ax = plt.subplots(figsize=(5, 3.5))
ax.loglog([r[0] for r in rows], [r[1] for r in rows], "o-")
ax.set_xlabel("rtol")
ax.set_ylabel("points on the branch")
ax.invert_xaxis()
plt.show()
assert rows[0][1] <= rows[-1][1]

# %%
# The contact-loss path
# ---------------------
# A model's ``run`` takes options; ``DEFAULT_OPTIONS.replace(rtol=...)`` changes the one
# knob (a scene says ``[solver] rtol``, the command ``cusp run --rtol``). The energies agree
# to far below ``rtol``.
from cusp.models import ContactLoss, ExponentialRoughSurface
from cusp.models.contact_loss import DEFAULT_OPTIONS

model = ContactLoss(ExponentialRoughSurface(sigma=2.0, nu=0.3, mu=0.1), 1000.0, 0.34, 850.0)
coarse = model.run(DEFAULT_OPTIONS.replace(rtol=1e-2))
default = model.run()
for key in ("snap_back", "snap_through"):
    diff = abs(coarse.energy[key] - default.energy[key]) / default.energy[key]
    print(f"{key}: {default.energy[key]:.15f} N·µm, relative difference at rtol 1e-2: {diff:.1e}")
    assert diff < 1e-10
