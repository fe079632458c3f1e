"""
Fig 6: the contact-loss path
============================

The paper's Fig 6 (``scenes/fig6.toml``): exponential heights, the normal load reduced from
1000 N to 850 N at the slip 0.34 µm. (a) the path O→A→B→C; (b) the AB region magnified with
the snap-back A→D, the snap-through A→C and the released areas.

The scene runs through the API of ``cusp run`` (:func:`cusp.app.run.run_scene`), which
returns the computed cases and every figure of the scene as PNG and SVG bytes; the figures
are shown here as ``cusp run fig6`` writes them.
"""

import io

import matplotlib.pyplot as plt

from cusp.app.run import resolve_scene, run_scene
from cusp.app.scene import load_scene

path, source = resolve_scene("fig6")
scene = load_scene(path, source=source)
run, figures = run_scene(scene)

for mu, load, res in run.cases:
    energy = {k: res.energy[k] for k in ("snap_back", "snap_through")}
    print(f"mu = {mu}, F'_N = {load} N: energies [N·µm] {energy}")

for name in scene.figures:
    image = plt.imread(io.BytesIO(figures[name]["png"]))
    height, width = image.shape[:2]
    fig = plt.figure(figsize=(width / 150, height / 150), dpi=150)
    fig.figimage(image)
plt.show()
