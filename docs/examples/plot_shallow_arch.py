"""
A shallow arch: branch points and a limit point
===============================================

:func:`cusp.examples.shallow_arch`: a two-mode Ritz model of a shallow pinned arch of rise
:math:`e = 6` under a central load :math:`p`. On the symmetric path
:math:`\\xi_2 = 0` the load reaches a branch point, where the asymmetric path
:math:`(\\xi_1 - e)^2 + 4\\xi_2^2 = e^2 - 16` leaves (for :math:`e > 4`), before its limit
point. The references are the closed forms of :func:`cusp.examples.arch_references`,
evaluated in mpmath.
"""

import matplotlib.pyplot as plt

from cusp.examples import shallow_arch

ex = shallow_arch()
br = ex.trace()
for sp in br.special_points:
    print(sp.kind, {k: round(v, 8) for k, v in sp.values.items()})
for ref in ex.references():
    print("reference", ref.kind, dict(ref.values))
for sp in br.special_points:  # every located fold and branch point is a reference point
    if sp.kind in ("fold", "branch_point"):
        assert any(
            ref.kind == sp.kind and abs(ref.values["p"] - sp.values["p"]) < 1e-9
            for ref in ex.references()
        ), sp

fig, ax = plt.subplots(figsize=(5.5, 4))
br.plot(ex.unknowns[0], ex.free, ax=ax)
ax.set_title("shallow arch")
plt.show()
