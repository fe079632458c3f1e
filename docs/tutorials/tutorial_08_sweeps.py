"""
Sweeps: one scene, many cases
=============================

A ``[sweep]`` section turns a scene into many cases: the same scene with some of its fields
varied by their dotted names (``"surface.mu"``, ``"loading.reduced_normal_load"``, ...),
every combination of the values given. ``cusp sweep SCENE.toml --out DIR`` runs them on
local worker processes (or a Dask cluster, ``--scheduler``), writes one Parquet row a case
(a refused or failing case is a row with its status and message) and, killed and run again,
computes only the missing cases. Here a grid of friction coefficients and reduced loads on
the exponential surface of Fig 6, run in this process and read with pandas (``pip install
'cusp[sweep]' pandas``).
"""

import pathlib
import tempfile

import pandas as pd

from cusp.app.scene import parse_scene
from cusp.app.sweep import sweep

TOML = """
[scene]
name = "grid"

[surface]
model = "rough-exponential"
sigma = 2.0                   # σ* [µm]
nu = 0.3
mu = 0.1

[loading]
normal_load = 1000.0          # F_N0 [N]
max_slip = 0.34               # g_A [µm]
reduced_normal_load = 850.0   # F'_N [N]

[sweep]
"surface.mu" = [0.1, 0.2, 0.3]
"loading.reduced_normal_load" = { start = 700.0, stop = 950.0, num = 6 }
"""

out = pathlib.Path(tempfile.mkdtemp()) / "grid"
summary = sweep(parse_scene(TOML, source="grid.toml"), out)  # workers=0: this process
print(summary["cases"], "cases,", summary["computed"], "computed:", summary["statuses"])

# %%
# The results table
# -----------------
# One row a case: the varied fields by their dotted names, ``status`` and ``message``, the
# points and energies under the column names of ``loci.csv`` (``F_A``, ``g_C``,
# ``snap_through_energy``, ... in N, µm, N·µm) with their error bounds (``..._error``).
df = pd.read_parquet(out / "results.parquet").sort_values("index")
table = df.pivot(index="loading.reduced_normal_load", columns="surface.mu", values="F_C")
print(table)  # the force at C [N]; empty where the block slides (no C)

# %%
# Checked against the mechanics
# -----------------------------
# C exists where the force at A is below μF'_N (else the block slides under force control:
# no C, no snap-through energy, and the message says so); B lies at F_A − μ(F_N0 − F'_N).
for _, row in df.iterrows():
    mu, load = row["surface.mu"], row["loading.reduced_normal_load"]
    assert row["status"] == "ok"
    assert abs(row["F_B"] - (row["F_A"] - mu * (1000.0 - load))) < 1e-9 * row["F_A"]
    has_c = row["F_A"] < mu * load
    assert pd.isna(row["F_C"]) != has_c
    if not has_c:
        assert "gross sliding" in row["message"]

# %%
# Run again: nothing to do
# ------------------------
# The results are written a chunk at a time; a second run (or one after a kill) computes
# only the cases missing from the table, so no row appears twice.
again = sweep(parse_scene(TOML, source="grid.toml"), out)
assert again["computed"] == 0 and again["done_before"] == len(df)

# %%
# Draw the snap-through energy over the grid
# ------------------------------------------
import matplotlib.pyplot as plt

fig, ax = plt.subplots(figsize=(6, 4.2))
for mu, rows in df.groupby("surface.mu"):
    ax.plot(rows["loading.reduced_normal_load"], rows["snap_through_energy"], "o-",
            label=rf"$\mu = {mu:g}$")  # fmt: skip
ax.set_xlabel(r"reduced normal load $F'_N$ [N]")
ax.set_ylabel(r"snap-through energy [N$\cdot$µm]")
ax.legend()
plt.show()
