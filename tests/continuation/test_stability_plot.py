"""``Branch.plot`` of a branch traced with stability (issue 29 point 6): stable parts solid,
unstable ones dashed, drawn along the dense output (the Hermite arcs), not the chords; and
(issue 32 point 5) every traced branch drawn along its dense output, its rows marked."""

from __future__ import annotations

import math

import numpy as np
import pytest

from cusp.continuation import Problem, trace

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")


def test_stable_solid_unstable_dashed_along_the_dense_output():
    import matplotlib.pyplot as plt

    # x' = b + x − x³: equilibria b = x³ − x, stable where 1 − 3x² < 0, i.e. |x| > 1/√3;
    # folds at x = ±1/√3 (b = ∓2/(3√3))
    prob = Problem(lambda u, p: [p["b"] + u[0] - u[0] ** 3], ["x"], {"b": -1.0}, mass=True)
    br = trace(prob, [-1.3247179572447], free="b", bounds={"b": (-1.0, 1.0)}, stability=True)
    fig, ax = plt.subplots()
    try:
        br.plot("b", "x", ax=ax, special=False, points=False)
        lines = ax.get_lines()
        styles = [line.get_linestyle() for line in lines]
        assert styles == ["-", "--", "-"]  # stable, unstable between the folds, stable
        assert len({line.get_color() for line in lines}) == 1
        edge = 1 / math.sqrt(3)
        for line, unstable in zip(lines, (False, True, False)):
            b, x = np.asarray(line.get_xdata()), np.asarray(line.get_ydata())
            # the arcs, not the chords: many more points than rows, all on b = x³ − x (within
            # the dense output's rtol = 1e-3, relative to the sizes ~1)
            assert np.max(np.abs(b - (x**3 - x))) < 1e-3
            inside = np.abs(x) < edge + 1e-9
            assert np.all(inside) if unstable else np.all(np.abs(x) >= edge - 1e-9)
        assert sum(len(line.get_xdata()) for line in lines) > 4 * len(br)
        # the chord of a segment would be off the curve: check one long segment's middle
        i = int(np.argmax(np.diff(br.s)))
        chord_mid = 0.5 * (br["x"][i] + br["x"][i + 1]), 0.5 * (br["b"][i] + br["b"][i + 1])
        assert abs(chord_mid[1] - (chord_mid[0] ** 3 - chord_mid[0])) > 1e-3
    finally:
        plt.close(fig)


def test_a_branch_without_stability_is_drawn_along_its_dense_output_its_rows_marked():
    import matplotlib.pyplot as plt

    # the same S-curve b = x³ − x (folds at x = ±1/√3), traced without stability
    prob = Problem(lambda u, p: [p["b"] + u[0] - u[0] ** 3], ["x"], {"b": -1.0})
    br = trace(prob, [-1.3247179572447], free="b", bounds={"b": (-1.0, 1.0)})
    fig, ax = plt.subplots()
    try:
        br.plot("b", "x", ax=ax, special=False)
        curve, rows = ax.get_lines()
        assert curve.get_linestyle() == "-" and rows.get_linestyle() == "None"
        assert rows.get_marker() == "." and rows.get_color() == curve.get_color()
        np.testing.assert_array_equal(rows.get_xdata(), br["b"])
        np.testing.assert_array_equal(rows.get_ydata(), br["x"])
        b, x = np.asarray(curve.get_xdata()), np.asarray(curve.get_ydata())
        # the arcs between the rows (SAMPLES points each), on b = x³ − x within rtol = 1e-3
        assert len(b) > 4 * len(br)
        assert np.max(np.abs(b - (x**3 - x))) < 1e-3
        i = int(np.argmax(np.diff(br.s)))  # the longest segment's chord is off the curve
        chord_mid = 0.5 * (br["x"][i] + br["x"][i + 1]), 0.5 * (br["b"][i] + br["b"][i + 1])
        assert abs(chord_mid[1] - (chord_mid[0] ** 3 - chord_mid[0])) > 1e-3
    finally:
        plt.close(fig)
