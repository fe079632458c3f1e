"""Typical sizes along a curve (continuation/scaling.py): they grow with a component that
outgrows them, never shrink, and the user's sizes are kept."""

import math

import numpy as np
import pytest

from cusp.continuation import Problem, trace
from cusp.continuation.numerics._scaling import GROWTH, grown_scales


def _exponential():
    """u = e^p: from p = −10 (u = 4.5e-5) to p = 5 (u = 148), a 3e6-fold growth."""
    return Problem(
        lambda u, p: np.array([u[0] - math.exp(p["p"])]),
        ["u"],
        {"p": -10.0},
        jacobian=lambda u, p: np.array([[1.0]]),
        param_jacobian=lambda u, p, name: np.array([-math.exp(p["p"])]),
    )


def test_sizes_follow_a_growing_component():
    br = trace(_exponential(), [math.exp(-10.0)], free="p", bounds={"p": (-10.0, 5.0)})
    assert br.status == "bound" and br["p"][-1] == 5.0
    # closed form on every point; the end's size is within GROWTH of its value
    assert np.allclose(br["u"], np.exp(br["p"]), rtol=1e-10, atol=0)
    assert math.exp(5.0) / GROWTH <= br.info["scales"]["u"] <= math.exp(5.0)
    # in steps of the growing size (with the start's size, 4.5e-5, thousands of steps:
    # ds_max = 0.5 moves u by 2.3e-5 a step)
    assert len(br["p"]) < 200


def test_given_sizes_are_kept():
    br = trace(
        _exponential(),
        [math.exp(-10.0)],
        free="p",
        bounds={"p": (-10.0, -5.0)},
        scales={"u": 1e-4},
    )
    assert br.status == "bound" and br.info["scales"]["u"] == 1e-4


@pytest.mark.parametrize(
    ("scales", "z", "given", "expected"),
    [
        ([1.0, 1e-3], [3.9, -3.9e-3], {}, None),  # within GROWTH: unchanged
        ([1.0, 1e-3], [-4.1, 1.0], {}, [4.1, 1.0]),  # both grow to their magnitudes
        ([1.0, 1e-3], [0.0, 1.0], {1: 1e-3}, None),  # a given size is kept
        ([1.0, 1e-3], [1e-9, 1e-9], {}, None),  # sizes never shrink
    ],
)
def test_grown_scales(scales, z, given, expected):
    out = grown_scales(np.array(scales), np.array(z), given)
    if expected is None:
        assert out is None
    else:
        assert out.tolist() == expected
