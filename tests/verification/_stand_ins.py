"""Stand-in model packages for the implementation comparison (``check_implementation``).

``fake_models(GoodRough)`` is a correct implementation of every compared method, computed
with mpmath at 1200 digits and rounded once; ``fake_models(NaiveRough)`` evaluates Eq 12 in
plain floats with the erf form, which cancels catastrophically as F_T-hat -> 1. Used by
``tests/verification/test_implementation.py`` and ``tests/app/test_cli_verify.py``.
"""

from __future__ import annotations

import math
import types

import mpmath


def _mp(fn):
    def wrapped(self, *args):
        with mpmath.workdps(1200):
            return float(fn(self, *[mpmath.mpf(a) for a in args]))

    return wrapped


class GoodRough:
    def __init__(self, sigma, nu, mu):
        self.mu = mpmath.mpf(mu)
        self.sigma = mpmath.mpf(sigma)
        self.lam = mpmath.mpf(sigma) * (2 - mpmath.mpf(nu)) / (2 * (1 - mpmath.mpf(nu)))

    @_mp
    def stick_force_ratio(self, f):
        return f - mpmath.gammainc(2.5, 0, -mpmath.log1p(-f), regularized=True)

    @_mp
    def stick_area_ratio(self, f):
        return (1 - f) * (1 - mpmath.log1p(-f))

    @_mp
    def load_integral(self, h):
        return mpmath.gamma(2.5) * self.sigma**1.5 * mpmath.exp(-h / self.sigma)

    @_mp
    def slip_load_integral(self, h, g):
        j = mpmath.gamma(2.5) * self.sigma**1.5 * mpmath.exp(-h / self.sigma)
        return j * mpmath.gammainc(2.5, 0, g / self.sigma, regularized=True)

    @_mp
    def tangential_force(self, g, fn):
        return self.mu * fn * -mpmath.expm1(-g / (self.mu * self.lam))

    @_mp
    def tangential_slip(self, ft, fn):
        return -self.mu * self.lam * mpmath.log1p(-ft / (self.mu * fn))


class GoodSphere:
    @_mp
    def stick_force_ratio(self, f):
        return f - (1 - (1 - f) ** (mpmath.mpf(2) / 3)) ** 1.5

    @_mp
    def stick_area_ratio(self, f):
        return (1 - f) ** (mpmath.mpf(2) / 3)


class GoodCylinder:
    @_mp
    def stick_force_ratio(self, f):
        return 2 / mpmath.pi * (mpmath.sqrt(f * (1 - f)) + mpmath.acos(mpmath.sqrt(f))) + f - 1

    @_mp
    def stick_area_ratio(self, f):
        return mpmath.sqrt(1 - f)


class GoodFlat:
    @staticmethod
    def stick_force_ratio(f):
        return f if f < 1.0 else 0.0

    @staticmethod
    def stick_area_ratio(f):
        return 1.0 if f < 1.0 else 0.0


class NaiveRough(GoodRough):
    """Eq 12 in plain floats with the erf form: cancels catastrophically as Fhat -> 1."""

    def stick_force_ratio(self, f):
        x = -math.log1p(-f)
        P = math.erf(math.sqrt(x)) - math.exp(-x) * (4 * x**1.5 + 6 * math.sqrt(x)) / (
            3 * math.sqrt(math.pi)
        )
        return f - P


def fake_models(rough: type) -> types.SimpleNamespace:
    """A stand-in for :mod:`cusp.models` with this rough-surface class and correct others."""
    return types.SimpleNamespace(
        ExponentialRoughSurface=rough,
        Sphere=GoodSphere,
        Cylinder=GoodCylinder,
        FlatPlane=GoodFlat,
    )
