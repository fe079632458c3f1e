"""Contact-mechanics models of the stick-slip cusp catastrophe (Carpinteri, Paggi, Zavarise).

Units throughout: lengths in µm, forces in N, energies in N·µm (= µJ), elastic moduli in N/µm².
Each body is a short module; heavy machinery (quadrature, sympy, matplotlib) is imported only
by the modules that need it.

Public names are imported lazily (module-level ``__getattr__``): ``import cusp.models``
loads nothing heavy, an exponential surface never loads quadrature or the Gaussian machinery.
"""

from __future__ import annotations

import importlib

#: public name -> submodule that defines it
_EXPORTS = {
    "RoughSurface": "rough",
    "ExponentialRoughSurface": "exponential",
    "GaussianRoughSurface": "gaussian",
    "GeneralRoughSurface": "density",
    "HeightDensity": "density",
    "Sphere": "sphere",
    "Cylinder": "cylinder",
    "FlatPlane": "flat",
    "ContactLoss": "contact_loss",
    "ContactLossResult": "contact_loss",
    "Loci": "manifold",
    "point_loci": "manifold",
    "trace_loci": "manifold",
    "RegimeMap": "regimes",
    "regime_map": "regimes",
    "RegimeBoundaries": "regimes",
    "regime_boundaries": "regimes",
    "ContactLevels": "protocol",
    "PathBody": "protocol",
    "Parameter": "registry",
    "register_body": "registry",
    "unregister_body": "registry",
    "registered_body": "registry",
    "weibull_surface": "density",
    "gw_integral": "gw",
    "log_gw_integral": "gw",
    "gw_difference": "gw",
    "ModelParameterError": "errors",
    "MissingLoadScaleError": "errors",
    "NoComplianceLawError": "errors",
    "GrossSlidingError": "errors",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str):
    try:
        module = _EXPORTS[name]
    except KeyError:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}") from None
    value = getattr(importlib.import_module(f".{module}", __name__), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))
