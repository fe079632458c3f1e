"""Stepping: :func:`trace` and the step-level :class:`Tracer` (the start, the predictor and
corrector, step control and its guards, confirming and locating crossings, the state and
its assembly into a branch)."""
