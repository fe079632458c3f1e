"""
CO oxidation: two folds and the cusp where they meet
====================================================

:func:`cusp.examples.co_oxidation` (BifurcationKit's model and start, an analytic
Jacobian): the steady states in :math:`q_2` have two folds; the fold curve in
:math:`(q_2, k)` closes at a cusp. Both are compared with the example's references, an
independent mpmath computation.
"""

import matplotlib.pyplot as plt

from cusp.continuation import fold_curve
from cusp.examples import co_oxidation

ex = co_oxidation()
br = ex.trace(ds_max=0.01)
fc = fold_curve(ex.problem, br.special("fold")[0], free=("q2", "k"), bounds={"k": (0.0, 2.2)})
(cusp,) = fc.special("cusp")
(ref,) = [r for r in ex.references() if r.kind == "cusp"]
print("cusp at k =", cusp.values["k"], " reference", ref.values["k"])
assert abs(cusp.values["k"] - ref.values["k"]) < 1e-9

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.8))
br.plot("q2", "x", ax=ax1)
ax1.set_title("steady states at $k = 0.4$")
fc.plot("q2", "k", ax=ax2)
ax2.set_title("the fold curve and its cusp")
plt.show()
