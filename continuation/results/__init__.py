"""Results: :class:`Branch` and its special points, dense output and resampling, stability
along a branch, Hopf rows, plotting, and saving to and loading from ``.npz``."""
