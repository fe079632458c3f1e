"""
A shallow arch: snap-through
============================

:func:`cusp.examples.shallow_arch`: a two-mode Ritz model of a shallow arch under a central
load; the load passes a limit point (snap-through). The references are closed forms.
"""

import matplotlib.pyplot as plt

from cusp.examples import shallow_arch

ex = shallow_arch()
br = ex.trace()
for sp in br.special_points:
    print(sp.kind, {k: round(v, 8) for k, v in sp.values.items()})
for ref in ex.references():
    print("reference", ref.kind, dict(ref.values))

fig, ax = plt.subplots(figsize=(5.5, 4))
br.plot(ex.unknowns[0], ex.free, ax=ax)
ax.set_title("shallow arch")
plt.show()
