"""The problem and its derivatives: the residual protocol (:class:`Problem`), finite
differences and complex steps, user events, sympy-built problems, real-valued returns."""
