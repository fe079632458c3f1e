"""
Fig 7: force against the slipped area
=====================================

The paper's Fig 7 (``scenes/fig7.toml``): the path of Fig 6 against the total slipped area
Â_SL (Eq 32 as printed), single-valued along AB.

The scene runs through the API of ``cusp run`` (:func:`cusp.app.run.run_scene`), which
returns the computed cases and every figure of the scene as PNG and SVG bytes; the figures
are shown here as ``cusp run fig7`` writes them.
"""

import io

import matplotlib.pyplot as plt

from cusp.app.run import resolve_scene, run_scene
from cusp.app.scene import load_scene

path, source = resolve_scene("fig7")
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
