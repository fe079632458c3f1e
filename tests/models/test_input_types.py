"""Numbers must be real numbers (issue 17, point 5): a string, a bool or a complex number is
refused by every body's constructor, naming the parameter, even where Python would convert it
(``float("2.0")``, ``float(True)``); arrays that are ragged, of strings, bools or complex
numbers are refused naming the array."""

from __future__ import annotations

import numpy as np
import pytest

from cusp.models import ExponentialRoughSurface, GaussianRoughSurface, Sphere
from cusp.models.errors import ModelParameterError

BODIES = {
    "exponential": (ExponentialRoughSurface, dict(sigma=2.0, nu=0.3, mu=0.1)),
    "gaussian": (
        GaussianRoughSurface,
        dict(sigma=2.0, nu=0.3, mu=0.1, E=0.2, radius=10.0, density=0.01, nominal_area=1e6),
    ),
    "sphere": (Sphere, dict(radius=1000.0, E=0.2, nu=0.3, mu=0.1)),
}
NOT_NUMBERS = ["2.0", True, False, 1 + 0j, b"1", [1.0]]  # (None: "not given", where optional)


@pytest.mark.parametrize("body", sorted(BODIES))
@pytest.mark.parametrize("bad", NOT_NUMBERS, ids=repr)
def test_parameters_must_be_real_numbers(body, bad):
    cls, params = BODIES[body]
    for key in params:
        with pytest.raises(ModelParameterError, match=key):
            cls(**{**params, key: bad})


@pytest.mark.parametrize("body", sorted(BODIES))
def test_numpy_and_integer_numbers_are_numbers(body):
    cls, params = BODIES[body]
    converted = {k: (np.float32(v) if k == "nu" else np.float64(v)) for k, v in params.items()}
    assert cls(**converted).mu == pytest.approx(0.1)
    assert cls(**{**params, "mu": 1}).mu == 1.0


@pytest.mark.parametrize(
    "bad, what",
    [([[0.1, 0.2], [0.3]], "ragged"), (["0.1"], "dtype <U"), ([True], "bool"), ([0.1j], "complex")],
)
def test_arrays_must_be_real_and_rectangular(bad, what):
    surf = ExponentialRoughSurface(2.0, 0.3, 0.1)
    with pytest.raises(ModelParameterError, match=rf"g_T must be real numbers.*{what}"):
        surf.force_ratio(bad)
