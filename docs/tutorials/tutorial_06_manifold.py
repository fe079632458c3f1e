"""
The cusp manifold: loci of A, B, C, D
=====================================

The points of the contact-loss path move when the friction coefficient μ (or the reduced
load F'_N) changes: their loci are the edges of the pleat of the catastrophe manifold.
:func:`cusp.models.point_loci` traces them by continuation (not by repeated runs) and
locates two events: the *C boundary*, :math:`F_A = \\mu F'_N`, below which there is no C
(force control ends in gross sliding), and :math:`F'_T = 0`, where B reaches zero force and
the path ends.
"""

import matplotlib.pyplot as plt
import numpy as np

from cusp.models import ContactLoss, ExponentialRoughSurface, point_loci

model = ContactLoss(ExponentialRoughSurface(sigma=2.0, nu=0.3, mu=0.1), 1000.0, 0.34, 850.0)
loci = point_loci(model, "mu", (0.01, 1.0))
cols = loci.columns
print(len(cols["mu"]), "rows")
for message in loci.messages:  # how each locus ended, and what was left out
    print("-", message)

# %%
# The events
# ----------
# Each event carries every column at its parameter value. Check them against their
# definitions: :math:`F_A = \mu F'_N` at the C boundary, :math:`F_B = 0` where
# :math:`F'_T = 0`.
for event in loci.events:
    print(event["event"], "at mu =", event["mu"])
boundary = next(e for e in loci.events if e["event"] == "C boundary")
end = next(e for e in loci.events if e["event"] == "F'_T = 0")
assert abs(boundary["F_A"] - boundary["mu"] * 850.0) < 1e-9 * boundary["F_A"]
assert abs(end["F_B"]) < 1e-9 * end["F_A"]

# %%
# The loci and the energies
# -------------------------
# NaN where a point does not exist (C below the C boundary): matplotlib leaves a gap. The
# energies are integrated at a subset of the rows (the messages say which), so they are
# drawn at the rows where they are finite.
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
for name in "ABCD":
    ax1.plot(cols["mu"], cols[f"g_{name}"], label=name)
ax1.set_xlabel(r"$\mu$")
ax1.set_ylabel(r"slip $g_T$ [µm]")
ax1.set_ylim(0, 2)
ax1.legend()
for key, label in (
    ("snap_back_energy", "snap-back (ABD)"),
    ("snap_through_energy", "snap-through (ABC)"),
):
    ok = np.isfinite(cols[key])
    ax2.plot(cols["mu"][ok], cols[key][ok], "o-", ms=3, label=label)
ax2.axvline(boundary["mu"], color="0.6", ls=":")
ax2.set_xlabel(r"$\mu$")
ax2.set_ylabel(r"energy [N·µm]")
ax2.legend()
plt.show()

# %%
# The snap-back energy grows with μ along the whole locus:
e = cols["snap_back_energy"]
assert np.all(np.diff(e[np.isfinite(e)]) > 0)
