"""Drawing data of the gears stage: pure functions of its result (``GearResult.to_dict()``,
i.e. ``results["gears"]``), for the report, the drawing sheets and the exported outlines.

The report draws only what the results hold; what is too bulky to store (the tooth
outlines, some thousand points per wheel) is made here, by the stage that owns the
tooth generation, from the numbers the results hold (m, z, x, alpha, ha, c, ra, rho_f):

    wheels(g) -> (Wheel, Wheel)           the two rack-generated wheels of the result
    mesh(g, teeth=3) -> [{centre, axis, x, y}] x 2
                                           wheel 1 at the origin, wheel 2 at (0, a_w), the
                                           teeth in mesh at the pole (tooth of 1 facing a
                                           space of 2); outlines in metres
    outlines(g, teeth=3) -> [(x, y), (x, y)]
                                           the exported outlines: each wheel's teeth about its
                                           own centre (middle tooth pointing up)
    outline_csv(x, y), outline_dxf(polylines)
                                           file formats of the outlines

The admissible region of the blocking contour is stored in the result itself
(``blocking_contour["region"]``, see :func:`region_polygons`)."""
from __future__ import annotations

import numpy as np

from .tooth import Wheel, mesh_layout, outline_csv, outline_dxf

__all__ = ["wheels", "mesh", "outlines", "region_polygons", "outline_csv", "outline_dxf"]


def wheels(g: dict) -> tuple[Wheel, Wheel]:
    """The two rack-generated wheels of a gears result.

    Parameters
    ----------
    g : dict
        The results.json ``gears`` section (m, z, x, alpha, ha, c, rho_f, ra).

    Returns
    -------
    tuple of Wheel
        Wheels 1 and 2 (lengths in m).
    """
    return tuple(Wheel(g["m"], g["z"][i], g["x"][i], g["alpha"], g["ha"], g["c"], g["ra"][i], g.get("rho_f"))
                 for i in (0, 1))


def mesh(g: dict, teeth: int = 3) -> list[dict]:
    """The two wheels in mesh at the pole, for the report's drawing.

    Parameters
    ----------
    g : dict
        The results.json ``gears`` section.
    teeth : int
        Consecutive teeth drawn of each wheel.

    Returns
    -------
    list of dict
        Per wheel: its centre (m), the axis angle of the middle tooth (rad) and the closed
        outline (x, y, m) of ``teeth`` teeth.
    """
    w = wheels(g)
    out = []
    for (c, ax_ang), wheel in zip(mesh_layout(w, g["aw"], 0.0), w):
        x, y = wheel.outline(axis_angle=ax_ang, teeth=teeth, centre=c)
        out.append({"centre": (float(c[0]), float(c[1])), "axis": float(ax_ang), "x": x, "y": y})
    return out


def outlines(g: dict, teeth: int = 3) -> list[tuple[np.ndarray, np.ndarray]]:
    """The outlines written beside the report.

    Parameters
    ----------
    g : dict
        The results.json ``gears`` section.
    teeth : int
        Teeth per wheel.

    Returns
    -------
    list of tuple of numpy.ndarray
        Each wheel's (x, y) of ``teeth`` teeth about its own centre (middle tooth pointing
        up), m.
    """
    return [wheel.outline(teeth=teeth) for wheel in wheels(g)]


def region_polygons(x1, x2, ok) -> list[list[list[list[float]]]]:
    """The admissible region of the blocking contour as polygons.

    Parameters
    ----------
    x1, x2 : numpy.ndarray
        The grid's shift coefficients of wheels 1 (columns) and 2 (rows).
    ok : numpy.ndarray
        The mask (len(x2), len(x1)): every check holds.

    Returns
    -------
    list
        Polygons [outer ring, hole rings...], a ring being [[x1, x2], ...] closed (the first
        point again at the end): the boundary of the admissible cells traced at the 0.5 level
        of the mask (marching squares, contourpy).
    """
    import contourpy  # lazy (marching squares; a dependency of its own)

    ok = np.asarray(ok, bool)
    if not ok.any():
        return []
    gen = contourpy.contour_generator(np.asarray(x1, float), np.asarray(x2, float), ok.astype(float),
                                      fill_type=contourpy.FillType.OuterOffset)
    points, offsets = gen.filled(0.5, 1.5)
    polys = []
    for pts, offs in zip(points, offsets):
        rings = [[[float(a), float(b)] for a, b in pts[s:e]] for s, e in zip(offs[:-1], offs[1:])]
        polys.append([r for r in rings if len(r) >= 4])
    return [p for p in polys if p]
