"""Special points: test functions and their sign changes, the fold and branch-point
locators, spectra, stability, Hopf points and the first Lyapunov coefficient, the
codimension-2 points of fold and Hopf curves."""
