"""Contact-mechanics models of the stick-slip cusp catastrophe (Carpinteri, Paggi, Zavarise).

Units throughout: lengths in µm, forces in N, energies in N·µm (= µJ), elastic moduli in N/µm².
Each body is a short module; heavy machinery (quadrature, sympy, matplotlib) is imported only
by the modules that need it.
"""
