"""
The Bratu problem: a fold in a discretised PDE
==============================================

:func:`cusp.examples.bratu`: :math:`u'' + \\lambda e^u = 0` on :math:`(0, 1)` with
:math:`u(0) = u(1) = 0`, by second-order finite differences on ``n`` interior nodes, traced
from :math:`u = 0` at :math:`\\lambda = 0` past its fold. The located fold is compared with
the example's reference (an independent mpmath computation of the discrete fold).
"""

import matplotlib.pyplot as plt

from cusp.examples import bratu

ex = bratu(20, sparse=True)  # the analytic Jacobian as a scipy.sparse matrix
br = ex.trace()
(fold,) = br.special("fold")
(ref,) = [r for r in ex.references() if r.kind == "fold"]
print("fold at lam =", fold.values["lam"], " reference", ref.values["lam"])
assert abs(fold.values["lam"] - ref.values["lam"]) < 1e-9 * ref.values["lam"]

mid = f"u{20 // 2}"
fig, ax = plt.subplots(figsize=(5.5, 4))
br.plot("lam", mid, ax=ax)
ax.set_xlabel(r"$\lambda$")
ax.set_ylabel(r"$u$ at the middle node")
ax.set_title("Bratu problem, 20 interior nodes")
plt.show()
