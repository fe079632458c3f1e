"""Regenerate ``reference_values.json`` (run from the repository root; ~2 min, one core).

    python tests/models/reference/make_reference.py

Each value comes from :mod:`mp_reference` (mpmath, dps 50 for the four bodies, 40 for the
Gaussian), evaluated at the exact binary float stored beside it (as float.hex).
"""

from __future__ import annotations

import json
import pathlib

# (run as a script, its own folder comes first on the import path: mp_reference, its
# sibling, imports by name)
import mp_reference as ref
import numpy as np

HERE = pathlib.Path(__file__).parent

EXTREMES = [
    1e-300,
    1e-100,
    1e-14,
    1e-9,
    1e-6,
    1e-3,
    0.01,
    0.1,
    0.2,
    0.3,
    0.4,
    0.5,
    0.6,
    0.7,
    0.8,
    0.9,
    0.99,
    0.999,
    1 - 1e-6,
    1 - 1e-9,
    1 - 2.0**-40,
    1 - 2.0**-52,
    1.0,
    0.0,
]
DENSE = (
    list(np.linspace(0.0, 1.0, 81)[1:-1])
    + list(np.geomspace(1e-12, 0.5, 25))
    + list(1.0 - np.geomspace(1e-15, 0.5, 25))
)
GAUSS_T = [6.0, 3.0, 0.0, -3.0]
GAUSS_F = [1e-9, 1e-3, 0.1, 0.3, 0.5, 0.7, 0.9, 0.999, 1 - 1e-9]
GAUSS_LOADING = [
    (6.0, 1e-12),
    (6.0, 0.05),
    (3.0, 0.3),
    (0.0, 1e-6),
    (0.0, 1.0),
    (-3.0, 0.01),
    (-3.0, 2.5),
]


PROVENANCE = {
    "generator": (
        "tests/models/reference/make_reference.py (mpmath; functions in mp_reference.py)"
    ),
    "inputs": (
        "every F_hat_T / delta is stored as float.hex: the exact binary value the code receives"
    ),
    "bodies": (
        "[F.hex(), stick_force_ratio, stick_area_ratio]: mp_reference.<body>(F), dps >= "
        "50 (50 + |log10 F| for sphere/cylinder so k = c/a keeps 50 digits); defining "
        "integrals: exponential Eq 7/Eq 11 and Eq 14/Eq 13 over e^-v, sphere and cylinder"
        " Mindlin stick traction integrated over the stick zone, flat Eqs 30-31"
    ),
    "gaussian": (
        "[t = d/sigma*, F.hex(), stick_force_ratio, stick_area_ratio]: "
        "mp_reference.gaussian(t, F), dps 40, bisection of J(t+delta) = (1-F) J(t)"
    ),
    "gaussian_loading": (
        "[t, delta.hex() (= g_N0/sigma*), F_hat_T]: mp_reference.gaussian_force_ratio(t, "
        "delta), dps 40"
    ),
    "gaussian_JA": (
        "[t, J(t), A(t)] in units of sigma*: mp_reference.gaussian_J/gaussian_A, dps 40"
    ),
}


def s(x):
    return ref.mp.nstr(x, 30)


def main() -> None:
    out = {"provenance": PROVENANCE, "bodies": {}, "gaussian": [], "gaussian_loading": []}
    out["gaussian_JA"] = []
    grid = sorted(set(float(f) for f in EXTREMES + DENSE))
    for name, fn in ref.BODIES.items():
        rows = []
        for F in grid:
            st, ar = fn(F)
            rows.append([F.hex(), s(st), s(ar)])
        out["bodies"][name] = rows
        print(name, len(rows), flush=True)
    for t in GAUSS_T:
        for F in GAUSS_F:
            st, ar = ref.gaussian(t, F)
            out["gaussian"].append([t, F.hex(), s(st), s(ar)])
        print("gaussian", t, flush=True)
    for t, d in GAUSS_LOADING:
        out["gaussian_loading"].append([t, d.hex(), s(ref.gaussian_force_ratio(t, d))])
    with ref.mp.workdps(40):
        for t in [-3.0, -1.0, 0.0, 2.0, 4.0, 6.0]:
            out["gaussian_JA"].append([t, s(ref.gaussian_J(t)), s(ref.gaussian_A(t))])
    (HERE / "reference_values.json").write_text(json.dumps(out, indent=0))


if __name__ == "__main__":
    main()
