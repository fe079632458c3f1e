"""
Snap-back: a truss in series with a spring
==========================================

:func:`cusp.examples.snapback_monitor`: the load–displacement curve of a shallow truss
loaded through a spring turns back in the displacement (a snap-back). Monitoring the
displacement locates its turning points as well as the load's.
"""

import matplotlib.pyplot as plt

from cusp.examples import snapback_monitor

ex = snapback_monitor()
br = ex.trace()
for sp in br.special("fold"):
    values = {k: round(v, 8) for k, v in sp.values.items()}
    print(sp.kind, "with respect to", sp.with_respect_to, values)

fig, ax = plt.subplots(figsize=(5.5, 4))
br.plot("delta", "P", ax=ax)
ax.set_xlabel(r"displacement $\delta$ of the spring's end")
ax.set_ylabel("load $P$")
ax.set_title("snap-back of a truss in series with a spring")
plt.show()
