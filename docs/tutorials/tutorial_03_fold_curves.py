"""
Fold curves and cusps
=====================

A fold (turning point) in one parameter moves when a second parameter changes: it traces a
fold curve. Where two folds of a branch meet and annihilate, the fold curve has a cusp.
For the cusp normal form :math:`x^3 - a x - b = 0` the folds lie on :math:`x^2 = a/3`,
:math:`b = -2x^3`, i.e. :math:`27 b^2 = 4 a^3`, and the cusp is the origin.
"""

import matplotlib.pyplot as plt
import numpy as np

from cusp.continuation import Problem, fold_curve, trace

prob = Problem(lambda u, p: [u[0] ** 3 - p["a"] * u[0] - p["b"]], ["x"], {"a": 1.0, "b": -1.0})
br = trace(prob, [-1.3247], free="b", bounds={"b": (-1.0, 1.0)})
fold = br.special("fold")[0]
print(fold)

# %%
# Continue the fold in :math:`(b, a)`
# -----------------------------------
# ``free=(p1, p2)``: the fold's own parameter first, then the new one. The curve is traced
# both ways from the fold on the minimally augmented system and joined.
fc = fold_curve(prob, fold, free=("b", "a"), bounds={"a": (-1.0, 2.0)})
print(fc)
residual = np.abs(27 * fc["b"] ** 2 - 4 * fc["a"] ** 3)
print("largest |27 b² − 4 a³| on the curve:", residual.max())
assert residual.max() < 1e-8

# %%
# The cusp
# --------
# Located where the fold's normal-form coefficient changes sign.
(cusp,) = fc.special("cusp")
print(cusp.values)
assert max(abs(cusp.values[k]) for k in ("x", "a", "b")) < 1e-8

fig, ax = plt.subplots(figsize=(5, 3.8))
fc.plot("b", "a", ax=ax)
b = np.linspace(-0.6, 0.6, 201)
ax.plot(b, np.cbrt(27 * b**2 / 4), ":", color="0.5", label=r"$27 b^2 = 4 a^3$")
ax.legend()
ax.set_title("the fold curve of $x^3 - a x - b$")
plt.show()

# %%
# On a model with a published cusp
# --------------------------------
# The same two calls on the CO-oxidation model (:func:`cusp.examples.co_oxidation`), whose
# references come from an independent mpmath computation.
from cusp.examples import co_oxidation

ex = co_oxidation()
br = ex.trace(ds_max=0.01)
fc = fold_curve(ex.problem, br.special("fold")[0], free=("q2", "k"), bounds={"k": (0.0, 2.2)})
(found,) = fc.special("cusp")
(ref,) = [r for r in ex.references() if r.kind == "cusp"]
print("k at the cusp:", found.values["k"], "reference:", ref.values["k"])
assert abs(found.values["k"] - ref.values["k"]) < 1e-9
