"""
Fig 9: the catastrophe manifold in μ
====================================

The paper's Fig 9 (``scenes/fig9.toml``): the path at μ = 0.1 and 0.5, and, from its
``[manifold]`` section, the loci of A, B, C, D in μ: the response surface, the loci in the
control planes, the energies along them and the regime map.

The scene runs through the API of ``cusp run`` (:func:`cusp.app.run.run_scene`), which
returns the computed cases and every figure of the scene as PNG and SVG bytes; the figures
are shown here as ``cusp run fig9`` writes them.
"""

import io

import matplotlib.pyplot as plt

from cusp.app.run import resolve_scene, run_scene
from cusp.app.scene import load_scene

path, source = resolve_scene("fig9")
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
