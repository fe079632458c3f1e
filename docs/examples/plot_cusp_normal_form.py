"""
The cusp normal form
====================

:func:`cusp.examples.cusp_normal_form`: :math:`x^3 - a x - b = 0` traced in :math:`b`,
its two folds, and the fold curve in :math:`(b, a)` closing at the cusp.
"""

import matplotlib.pyplot as plt

from cusp.continuation import fold_curve
from cusp.examples import cusp_normal_form

ex = cusp_normal_form()
br = ex.trace()
fc = fold_curve(ex.problem, br.special("fold")[0], free=("b", "a"), bounds={"a": (-1.0, 2.0)})
print(fc.special("cusp"))

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(8, 3.5))
br.plot("b", "x", ax=ax1)
fc.plot("b", "a", ax=ax2)
plt.show()
