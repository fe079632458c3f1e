"""Build a :class:`~cusp.continuation.Problem` from sympy expressions, with exact derivatives.

sympy is imported here only, when the helper is first used.

Residuals given as strings are parsed without ``eval`` (sympy's ``sympify`` and
``parse_expr`` evaluate the string as Python: ``"__import__('os').system(...)"`` would run).
:func:`parse_expression` reads the string with Python's :mod:`ast` (which only parses) and
builds the sympy expression itself from a small grammar: numbers, the declared unknowns and
parameters, the constants ``pi`` and ``E``, ``+ - * / **``, parentheses and calls of the
functions in :data:`FUNCTIONS`. Anything else — attribute access, subscripts, strings,
keywords, lambdas, other names — is refused with a :class:`ProblemDefinitionError` naming
it.
"""

from __future__ import annotations

import ast
import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from .._errors import ProblemDefinitionError
from ._problem import Problem


def from_sympy(
    residuals: Sequence,
    unknowns: Sequence,
    params: Mapping,
    *,
    sparse: bool = False,
    name: str | None = None,
) -> Problem:
    """Build a problem whose residual and derivatives are lambdified from sympy.

    The Jacobian and parameter derivatives are exact, differentiated symbolically.
    A residual may be a string, parsed without ``eval`` by :func:`parse_expression` (the
    declared names, numbers, arithmetic and the functions of :data:`FUNCTIONS`; nothing
    else).

    Parameters
    ----------
    residuals : sequence of sympy.Expr or str
        One expression per unknown.
    unknowns : sequence of sympy.Symbol or str
        The unknowns (symbols, or their names).
    params : mapping of sympy.Symbol or str to float
        Every parameter and its value.
    sparse : bool, optional
        Whether the Jacobian is returned as a ``scipy.sparse`` matrix.
    name : str, optional
        The problem's label.

    Returns
    -------
    Problem
        The problem, with ``jacobian`` and ``param_jacobian`` of its own.

    Raises
    ------
    ProblemDefinitionError
        A string that does not parse, a name not declared, or a count of residuals other
        than of unknowns.

    Examples
    --------
    >>> import sympy as sp
    >>> x, a, b = sp.symbols("x a b")
    >>> prob = from_sympy([x**3 - a*x - b], [x], {a: 1.0, b: -1.0})
    >>> prob.jacobian([2.0], {"a": 1.0, "b": 0.0})  # 3x² − a, differentiated by sympy
    array([[11.]])
    """
    import sympy

    def sym(s):
        return sympy.Symbol(s) if isinstance(s, str) else s

    xs = [sym(s) for s in unknowns]
    ps = {sym(k): float(v) for k, v in params.items()}
    exprs = _expressions(residuals, xs, ps)
    residual, jacobian, param_jacobian = _lambdified(exprs, xs, ps, sparse)
    return Problem(
        residual,
        [str(x) for x in xs],
        {str(k): v for k, v in ps.items()},
        jacobian=jacobian,
        param_jacobian=param_jacobian,
        name=name,
    )


def _expressions(residuals: Sequence, xs: list, ps: dict) -> list:
    """The residuals as sympy expressions (strings parsed by :func:`parse_expression`),
    one per unknown, in the declared symbols only."""
    declared = {str(s): s for s in [*xs, *ps]}
    exprs = [
        parse_expression(e, declared) if isinstance(e, str) else _sympify(e) for e in residuals
    ]
    if len(exprs) != len(xs):
        raise ProblemDefinitionError(
            f"from_sympy needs as many residuals as unknowns, got {len(exprs)} and {len(xs)}"
        )
    allowed = set(xs) | set(ps)
    for e in exprs:
        extra = e.free_symbols - allowed
        if extra:
            raise ProblemDefinitionError(
                f"residual {e} has symbols {sorted(map(str, extra))} that are neither unknowns "
                f"nor parameters"
            )
    return exprs


def _lambdified(exprs: list, xs: list, ps: dict, sparse: bool) -> tuple[Any, Any, Any]:
    """The residual, Jacobian and parameter derivative of ``exprs`` as numpy functions of
    ``(u, p)``, the derivatives differentiated symbolically."""
    import sympy

    pnames = [str(p) for p in ps]
    args = xs + list(ps)
    n = len(xs)
    f_res = sympy.lambdify(args, exprs, modules="numpy")
    jac = sympy.Matrix(exprs).jacobian(xs)
    f_jac = sympy.lambdify(args, jac, modules="numpy")
    f_dp = {
        str(p): sympy.lambdify(args, [sympy.diff(e, p) for e in exprs], modules="numpy") for p in ps
    }

    def call(f, u, p):
        return f(*u, *(p[k] for k in pnames))

    def residual(u, p):
        return np.asarray(call(f_res, u, p), dtype=np.result_type(u, float))

    def jacobian(u, p):
        out = np.asarray(call(f_jac, u, p), dtype=float).reshape(n, n)
        if sparse:
            import scipy.sparse

            return scipy.sparse.csr_matrix(out)
        return out

    def param_jacobian(u, p, pname):
        return np.broadcast_to(np.asarray(call(f_dp[pname], u, p), dtype=float), (n,)).copy()

    return residual, jacobian, param_jacobian


def _sympify(e: Any) -> Any:
    """A residual given as a sympy expression or a number (``strict``: never through its
    string, which ``sympify`` would evaluate)."""
    import sympy

    try:
        return sympy.sympify(e, strict=True)
    except sympy.SympifyError:
        raise ProblemDefinitionError(
            f"residual {e!r} ({type(e).__name__}) is neither a sympy expression, a number "
            f"nor a string"
        ) from None


FUNCTIONS = (
    "sin", "cos", "tan", "cot", "sec", "csc", "asin", "acos", "atan", "atan2", "sinh",
    "cosh", "tanh", "asinh", "acosh", "atanh", "exp", "log", "sqrt", "cbrt", "Abs", "abs",
    "sign", "Min", "Max", "erf", "erfc", "gamma", "Heaviside",
)  # fmt: skip
"""The functions a residual string may call (sympy's, ``abs`` as ``Abs``), with ``pi`` and
``E`` the constants it may name."""

_ARITY = {"atan2": (2, 2), "log": (1, 2), "Min": (1, None), "Max": (1, None), "Heaviside": (1, 2)}
"""The number of arguments of the functions taking other than one (``None``: any)."""

_MAX_EXPONENT = 10_000
"""The largest integer exponent of a power of two numbers (``9**9**9`` would be evaluated
exactly by sympy, for ever)."""


def parse_expression(text: str, symbols: Mapping[str, Any]) -> Any:
    """The sympy expression of the residual string ``text`` in the declared ``symbols``
    (by name), built from Python's parse tree without evaluating anything (module
    docstring).

    >>> import sympy
    >>> x, a = sympy.symbols("x a")
    >>> parse_expression("x**3 - a*sin(x) + 2.5", {"x": x, "a": a})
    -a*sin(x) + x**3 + 2.5
    >>> parse_expression("__import__('os').system('echo hacked')", {"x": x})
    Traceback (most recent call last):
    ...
    cusp.continuation.ProblemDefinitionError: residual ...: calling attribute access ...
    """
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except (SyntaxError, ValueError, RecursionError, MemoryError) as exc:
        raise ProblemDefinitionError(f"residual {text!r} is not an expression: {exc}") from None
    try:
        return _Builder(text, symbols).build(tree.body)
    except RecursionError:
        raise ProblemDefinitionError(f"residual {text!r} is nested too deeply") from None


class _Builder:
    """Builds a sympy expression from a parse tree of the grammar of the module docstring."""

    def __init__(self, text: str, symbols: Mapping[str, Any]) -> None:
        import sympy

        self.sympy = sympy
        self.text = text
        self.names = dict(symbols)
        self.constants = {"pi": sympy.pi, "E": sympy.E}
        self.binary = {
            ast.Add: lambda a, b: a + b,
            ast.Sub: lambda a, b: a - b,
            ast.Mult: lambda a, b: a * b,
            ast.Div: lambda a, b: a / b,
            ast.Pow: self._power,
        }

    def refuse(self, what: str) -> ProblemDefinitionError:
        return ProblemDefinitionError(
            f"residual {self.text!r}: {what} is not allowed; a residual string may hold "
            f"numbers, the unknowns and parameters {sorted(self.names)}, pi, E, "
            f"+ - * / ** (not ^), parentheses and the functions {', '.join(FUNCTIONS)}"
        )

    def build(self, node: ast.AST) -> Any:
        if isinstance(node, ast.BinOp) and type(node.op) in self.binary:
            return self.binary[type(node.op)](self.build(node.left), self.build(node.right))
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            operand = self.build(node.operand)
            return -operand if isinstance(node.op, ast.USub) else operand
        value = getattr(node, "value", None)
        if isinstance(node, ast.Constant) and isinstance(value, (int, float)):
            if type(value) is bool or (type(value) is float and not math.isfinite(value)):
                raise self.refuse(f"the constant {value!r}")
            return self.sympy.Integer(value) if type(value) is int else self.sympy.Float(value)
        if isinstance(node, ast.Name):
            return self._name(node.id)
        if isinstance(node, ast.Call):
            return self._call(node)
        raise self.refuse(_describe(node))

    def _name(self, name: str) -> Any:
        if name in self.names:
            return self.names[name]
        if name in self.constants:
            return self.constants[name]
        raise self.refuse(f"the name {name!r} (not a declared unknown or parameter)")

    def _call(self, node: ast.Call) -> Any:
        func = node.func
        if not isinstance(func, ast.Name) or func.id not in FUNCTIONS or func.id in self.names:
            raise self.refuse(f"calling {_describe(func)}")
        if node.keywords or any(isinstance(a, ast.Starred) for a in node.args):
            raise self.refuse(f"keyword or starred arguments of {func.id}")
        low, high = _ARITY.get(func.id, (1, 1))
        if not low <= len(node.args) <= (high or len(node.args)):
            raise self.refuse(f"{func.id} with {len(node.args)} arguments")
        args = [self.build(a) for a in node.args]
        fn = getattr(self.sympy, "Abs" if func.id == "abs" else func.id)
        try:
            return fn(*args)
        except (TypeError, ValueError) as exc:
            raise ProblemDefinitionError(
                f"residual {self.text!r}: {func.id}{tuple(map(str, args))}: {exc}"
            ) from None

    def _power(self, base: Any, exponent: Any) -> Any:
        if (
            base.is_Number
            and exponent.is_Integer
            and abs(int(exponent)) > _MAX_EXPONENT
            and abs(base) != 1
        ):
            raise self.refuse(f"the power of a number with the exponent {exponent}")
        return base**exponent


def _describe(node: ast.AST) -> str:
    """A construct of a parse tree, for a message."""
    if isinstance(node, ast.Attribute):
        return f"attribute access (.{node.attr})"
    if isinstance(node, ast.Name):
        return repr(node.id)
    if isinstance(node, ast.Constant):
        return f"the constant {node.value!r}"
    if isinstance(node, ast.BinOp):
        return f"the operator {type(node.op).__name__}"
    return f"{type(node).__name__}"
