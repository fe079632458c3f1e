"""`from_sympy` parses residual strings without evaluating them (issue 17).

Before, strings went through `sympy.sympify`, which evaluates them as Python: the string
below would have run a shell command. The expected derivatives are written out by hand
(closed form) beside each check.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from cusp.continuation import ProblemDefinitionError, from_sympy, trace


def test_code_in_a_string_is_refused_and_not_run(tmp_path):
    canary = tmp_path / "hacked"
    attacks = [
        "__import__('os').system('echo hacked')",
        f"__import__('pathlib').Path({str(canary)!r}).touch()",
        "x.__class__.__bases__[0].__subclasses__()",
        "(lambda: x)()",
        "exec('import os')",
        "x; import os",
    ]
    for text in attacks:
        with pytest.raises(ProblemDefinitionError, match="residual"):
            from_sympy([text], ["x"], {"a": 1.0})
    assert not canary.exists()


@pytest.mark.parametrize(
    "text, what",
    [
        ("x.real", r"attribute access \(\.real\)"),
        ("sin.__globals__", r"attribute access \(\.__globals__\)"),
        ("x**2 - c", "the name 'c'"),
        ("__builtins__", "the name '__builtins__'"),
        ("x^2 - a", "BitXor"),
        ("x[0]", "Subscript"),
        ("'x'", "the constant 'x'"),
        ("1j*x", "the constant 1j"),
        ("sqrt(x, 3)", "sqrt with 2 arguments"),
        ("sin(x=1)", "keyword or starred"),
        ("9**9**9", "the exponent 387420489"),  # 9**9 = 387420489, evaluated for ever
    ],
)
def test_disallowed_constructs_are_named(text, what):
    with pytest.raises(ProblemDefinitionError, match=what):
        from_sympy([text], ["x"], {"a": 1.0})


def test_ordinary_strings_give_exact_derivatives():
    """x³ − a·x − b: ∂/∂x = 3x² − a, ∂/∂a = −x, ∂/∂b = −1 (closed form)."""
    prob = from_sympy(["x**3 - a*x - b"], ["x"], {"a": 1.0, "b": -1.0})
    u, p = np.array([2.0]), {"a": 1.0, "b": 0.5}
    assert prob.residual(u, p).tolist() == [8.0 - 2.0 - 0.5]
    assert prob.jacobian(u, p).tolist() == [[3.0 * 4.0 - 1.0]]
    assert prob.param_jacobian(u, p, "a").tolist() == [-2.0]
    assert prob.param_jacobian(u, p, "b").tolist() == [-1.0]
    # the folds of the cusp at a = 1: b = ±2/(3√3) (closed form)
    br = trace(prob, [-1.3247], free="b", bounds={"b": (-1.0, 1.0)})
    folds = sorted(sp.values["b"] for sp in br.special("fold"))
    assert np.allclose(folds, [-2 / (3 * math.sqrt(3)), 2 / (3 * math.sqrt(3))], atol=1e-12)


def test_functions_constants_and_unary_signs():
    """exp(x) − a·sin(x) + sqrt(b)·pi − E − (−x): ∂/∂x = exp(x) − a·cos(x) + 1."""
    prob = from_sympy(["exp(x) - a*sin(x) + sqrt(b)*pi - E - (-x)"], ["x"], {"a": 2.0, "b": 4.0})
    u, p = np.array([0.5]), {"a": 2.0, "b": 4.0}
    r = math.exp(0.5) - 2.0 * math.sin(0.5) + 2.0 * math.pi - math.e + 0.5
    assert prob.residual(u, p)[0] == pytest.approx(r, rel=1e-15)
    j = math.exp(0.5) - 2.0 * math.cos(0.5) + 1.0
    assert prob.jacobian(u, p)[0, 0] == pytest.approx(j, rel=1e-15)


def test_objects_are_not_converted_through_their_string():
    """sympify would parse str(obj), evaluating it; strict conversion refuses the object."""

    class Sneaky:
        def __str__(self):
            return "__import__('os').system('echo hacked')"

    with pytest.raises(ProblemDefinitionError, match="neither a sympy expression"):
        from_sympy([Sneaky()], ["x"], {"a": 1.0})
