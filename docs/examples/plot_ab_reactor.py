"""
The A → B reactor (AUTO-07p demo ``ab``)
========================================

:func:`cusp.examples.ab_reactor`: a stirred tank with an exothermic first-order reaction.
Its S-shaped steady-state curve in the Damköhler number has two folds, located and compared
with the example's references.
"""

import matplotlib.pyplot as plt

from cusp.examples import ab_reactor

ex = ab_reactor()
br = ex.trace()
refs = [r for r in ex.references() if r.kind == "fold"]
for sp in br.special("fold"):
    print("fold", {k: round(v, 10) for k, v in sp.values.items()})
for ref in refs:
    print("reference", dict(ref.values))
assert len(br.special("fold")) == len(refs) == 2
for sp, ref in zip(br.special("fold"), refs):  # closed forms in mpmath, in path order
    assert abs(sp.values["p1"] - ref.values["p1"]) < 1e-9 * ref.values["p1"]

fig, ax = plt.subplots(figsize=(5.5, 4))
br.plot(ex.free, ex.unknowns[0], ax=ax)
ax.set_title("A → B reactor: steady states")
plt.show()
