"""
The contact-loss path and its energies, from a scene
====================================================

A scene (TOML; units µm and N) describes one computation of ``cusp run``: a rough surface
loaded tangentially at :math:`F_{N0}` up to the slip :math:`g_A` (O→A), the normal load
reduced to :math:`F'_N` (A→B, the Mindlin–Deresiewicz rule), the tangential force raised
again (B→C). Under displacement control the path snaps back from A to D, under force
control it snaps through from A to C; the released energies are the areas ABD and ABC.
Here the paper's Fig 6 scene, written out, run from Python.
"""

from cusp.app.run import run_scene
from cusp.app.scene import parse_scene

TOML = """
[scene]
name = "my-fig6"

[surface]
model = "rough-exponential"
sigma = 2.0                   # composite rms roughness σ* [µm]
nu = 0.3
mu = 0.1

[loading]
normal_load = 1000.0          # F_N0 [N]
max_slip = 0.34               # g_A [µm]
reduced_normal_load = 850.0   # F'_N [N]
"""

scene = parse_scene(TOML, source="my-fig6.toml")
run, figures = run_scene(scene, plots=False)  # numbers only: matplotlib is not imported
((mu, load, res),) = run.cases

# %%
# The points and the energies
# ---------------------------
# ``res.points``: A, B, C, D with their slip g_T [µm], forces F_T, F_N [N], slipped area
# and the surface's levels; ``res.energy``: the snap-back (ABD) and snap-through (ABC)
# energies [N·µm]; ``res.energy_error``: bounds on their errors.
for name in "ABCD":
    point = res.points[name]
    print(name, {k: round(point[k], 6) for k in ("g_T", "F_T", "F_N")})
print("energies [N·µm]:", res.energy)
print("error bounds [N·µm]:", res.energy_error)

# %%
# What the mechanics says, checked
# --------------------------------
# On AB the stick zone is frozen, so :math:`F_T(B) = F_A - \mu (F_{N0} - F'_N)`
# (Mindlin–Deresiewicz); D lies at the slip of A, C at the force of A.
A, B, C, D = (res.points[k] for k in "ABCD")
assert abs(B["F_T"] - (A["F_T"] - mu * (1000.0 - load))) < 1e-10 * A["F_T"]
assert abs(D["g_T"] - A["g_T"]) < 1e-12 and abs(C["F_T"] - A["F_T"]) < 1e-10 * A["F_T"]
assert 0 < res.energy["snap_back"] < res.energy["snap_through"]

# %%
# Draw the path
# -------------
# ``res.dense(leg)`` is a smooth corrected curve of each traced leg (for plots), and the
# snap-back area ABD lies between the legs AB and BD.
import matplotlib.pyplot as plt
import numpy as np

fig, ax = plt.subplots(figsize=(6, 4.2))
for leg, style in (("OA", "-"), ("AB", "--"), ("BC", "-")):
    d = res.dense(leg)
    ax.plot(d["g_T"], d["F_T"], style, color="C0")
ab, bc = res.dense("AB"), res.dense("BC")
g = np.linspace(B["g_T"], A["g_T"], 100)
upper = np.interp(g, ab["g_T"][::-1], ab["F_T"][::-1])
lower = np.interp(g, bc["g_T"], bc["F_T"])
ax.fill_between(g, lower, upper, color="C1", alpha=0.4, label="snap-back energy (ABD)")
for name in "OABCD":
    p = res.points[name]
    if p is not None:
        ax.annotate(name, (p["g_T"], p["F_T"]), textcoords="offset points", xytext=(4, -12))
ax.set_xlabel(r"slip $g_T$ [µm]")
ax.set_ylabel(r"tangential force $F_T$ [N]")
ax.legend(loc="lower right")
plt.show()

# %%
# The same from the command line: ``cusp run my-fig6.toml --out out/my-fig6`` writes
# ``summary.json`` (these numbers), ``branch.csv`` and the figures.
