"""Generic pseudo-arclength continuation and bifurcation analysis.

Knows nothing of contact mechanics. Imports neither sympy nor matplotlib at import time.
"""
