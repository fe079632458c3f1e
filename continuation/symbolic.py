"""Build a :class:`~cusp.continuation.Problem` from sympy expressions, with exact derivatives.

sympy is imported here only, when the helper is first used.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from .errors import ProblemDefinitionError
from .problem import Problem


def from_sympy(
    residuals: Sequence,
    unknowns: Sequence,
    params: Mapping,
    *,
    sparse: bool = False,
    name: str | None = None,
) -> Problem:
    """A problem whose residual, Jacobian and parameter derivatives are lambdified from
    sympy expressions (derivatives exact, differentiated symbolically).

    ``unknowns`` are sympy symbols (or names); ``params`` maps symbols (or names) to values.

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
    exprs = [sympy.sympify(e) for e in residuals]
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

    return Problem(
        residual,
        [str(x) for x in xs],
        {str(k): v for k, v in ps.items()},
        jacobian=jacobian,
        param_jacobian=param_jacobian,
        name=name,
    )
