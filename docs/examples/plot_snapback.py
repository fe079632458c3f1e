"""
Snap-back: a truss in series with a spring
==========================================

:func:`cusp.examples.snapback_monitor`: the load–displacement curve of a shallow truss
loaded through a spring turns back in the displacement (a snap-back). Monitoring the
displacement locates its turning points as well as the load's; all four are checked
against the example's references.
"""

import matplotlib.pyplot as plt

from cusp.examples import snapback_monitor

ex = snapback_monitor()
br = ex.trace()
refs = [r for r in ex.references() if r.kind == "fold"]
for sp in br.special("fold"):
    values = {k: round(v, 8) for k, v in sp.values.items()}
    print(sp.kind, "with respect to", sp.with_respect_to, values)
    # the example's references (closed forms): the same turning point, to 1e-9 in v
    assert any(abs(r.values["v"] - sp.values["v"]) < 1e-9 for r in refs), sp
assert len(br.special("fold")) == len(refs) == 4

fig, ax = plt.subplots(figsize=(5.5, 4))
br.plot("delta", "P", ax=ax)
ax.set_xlabel(r"displacement $\delta$ of the spring's end")
ax.set_ylabel("load $P$")
ax.set_title("snap-back of a truss in series with a spring")
plt.show()
