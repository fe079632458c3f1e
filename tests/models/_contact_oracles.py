"""The independent mpmath references of the contact-loss path (Gaussian heights, spheres),
kept in :mod:`cusp.verification.oracles` (the benchmark scripts use them too)."""

from __future__ import annotations

from cusp.verification.oracles import DPS, gaussian_path, gw, sphere_path

__all__ = ["DPS", "gaussian_path", "gw", "sphere_path"]
