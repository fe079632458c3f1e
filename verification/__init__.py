"""The verification layer: the paper's closed forms derived with sympy from their defining
integrals, compared with the printed formulas and with the float implementation in
:mod:`cusp.models`. Importing it loads sympy."""
