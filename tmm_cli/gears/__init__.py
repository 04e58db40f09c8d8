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
from .analysis import GearResult, analyze
from .geometry import pair, sliding
from .involute import ainv, inv
from .planetary import SCHEMES, PlanetaryResult, synthesize_planetary, velocity_plan, verify
from .shifts import RULES, blocking_contour
from .tooth import Wheel, mesh_layout, outline_csv, outline_dxf

__all__ = ["analyze", "GearResult", "synthesize_planetary", "PlanetaryResult", "SCHEMES", "RULES",
           "inv", "ainv", "pair", "sliding", "blocking_contour", "Wheel", "mesh_layout",
           "outline_csv", "outline_dxf", "velocity_plan", "verify"]
