"""
A von Mises truss: a branch point and the branch through it
===========================================================

:func:`cusp.examples.truss_2dof`: a two-bar truss whose apex may also move sideways. The
symmetric path loses stability at a branch point before its limit point; tracing from the
located branch point (a :class:`~cusp.continuation.SpecialPoint` as the start) follows the
other, asymmetric branch. The example's references are the closed forms (branch point at
:math:`y^2 = H^2 - 2L^2`, limit point at :math:`y^2 = H^2/3`, :math:`y = H - v`).
"""

import matplotlib.pyplot as plt

from cusp.examples import truss_2dof

ex = truss_2dof(H=2.0)
br = ex.trace()
bp = br.special("branch_point")[0]
other = ex.trace(u0=bp, bounds={"u": (-1.0, 1.0)})
print(bp)
for ref in ex.references():
    print(ref.kind, dict(ref.values))
(ref_bp,) = [r for r in ex.references() if r.kind == "branch_point"]
assert abs(bp.values["v"] - ref_bp.values["v"]) < 1e-9
assert abs(other["u"]).max() > 0.1  # the switched branch does leave u = 0

fig, ax = plt.subplots(figsize=(5.5, 4))
br.plot("v", "P", ax=ax, label="symmetric path")
other.plot("v", "P", ax=ax, label="asymmetric branch", color="C1")
ax.set_xlabel("apex displacement $v$")
ax.set_ylabel("load $P$")
ax.legend()
plt.show()
