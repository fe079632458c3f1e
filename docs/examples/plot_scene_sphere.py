"""
Two elastic spheres
===================

``scenes/sphere.toml``: the contact-loss path of two elastic spheres (Hertz–Mindlin with the
Mindlin–Deresiewicz unloading).

The scene runs through the API of ``cusp run`` (:func:`cusp.app.run.run_scene`), which
returns the computed cases and every figure of the scene as PNG and SVG bytes; the figures
are shown here as ``cusp run sphere`` writes them.
"""

import io

import matplotlib.pyplot as plt

from cusp.app.run import resolve_scene, run_scene
from cusp.app.scene import load_scene

path, source = resolve_scene("sphere")
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
