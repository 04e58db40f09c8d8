"""Gears stage: involute spur pair with profile shift (GOST 16532-70) and planetary synthesis.

Public API::

    analyze(task.gears) -> GearResult           # the typed `gears` section (GearsSection)
    synthesize_planetary(task.planetary) -> PlanetaryResult
    inv(a), ainv(v)                             # involute function and its inverse (radians)
    Wheel(m, z, x, alpha, ha, c, ra)            # rack-generated tooth profiles and outlines
    blocking_contour(...), outline_csv(...), outline_dxf(...)

See :mod:`.geometry` (formulas and checks), :mod:`.shifts` (``x: auto`` rules and the
blocking contour), :mod:`.tooth` (generation by the rack) and :mod:`.planetary` (schemes).
"""
# made on first use: the task model imports the `gears` and `planetary` sections
# (gears/spec.py) without the stage
_LAZY = {"GearResult": "analysis", "analyze": "analysis", "pair": "geometry", "sliding": "geometry",
         "ainv": "involute", "inv": "involute", "SCHEMES": "planetary", "PlanetaryResult": "planetary",
         "synthesize_planetary": "planetary", "velocity_plan": "planetary", "verify": "planetary",
         "RULES": "shifts", "blocking_contour": "shifts", "Wheel": "tooth", "mesh_layout": "tooth",
         "outline_csv": "tooth", "outline_dxf": "tooth"}


def __getattr__(name):
    if name in _LAZY:
        import importlib
        return getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["analyze", "GearResult", "synthesize_planetary", "PlanetaryResult", "SCHEMES", "RULES",
           "inv", "ainv", "pair", "sliding", "blocking_contour", "Wheel", "mesh_layout",
           "outline_csv", "outline_dxf", "velocity_plan", "verify"]
