"""Export of the cam profile for the report: CSV rows and DXF text (ezdxf, imported lazily)."""
from __future__ import annotations

import math

import numpy as np

from ..reproducible import dxf_text

CSV_HEADER = ["phi_deg", "pitch_x_m", "pitch_y_m", "working_x_m", "working_y_m"]


def _arrays(result):
    if isinstance(result, dict):
        return (np.asarray(result["phi"], dtype=float), np.asarray(result["pitch_profile"], dtype=float),
                np.asarray(result["working_profile"], dtype=float), float(result["r0"]),
                float(result["roller"]))
    return result.phi, result.pitch, result.working, result.r0, result.roller


def profile_csv_rows(result) -> tuple[list[str], list[list[float]]]:
    """Header and rows of the cam profile's CSV file.

    Parameters
    ----------
    result : CamResult or dict
        The cam stage's result or its ``to_dict()``.

    Returns
    -------
    header : list of str
        The column names.
    rows : list of list of float
        (phi, deg; pitch x, y, m; working x, y, m) at every degree of the cycle.
    """
    phi, pitch, working, _, _ = _arrays(result)
    rows = [[float(p), float(a[0]), float(a[1]), float(b[0]), float(b[1])]
            for p, a, b in zip(phi, pitch, working)]
    return list(CSV_HEADER), rows


def profile_dxf(result, units_mm: bool = True) -> str:
    """DXF (R2010) text of the cam profile.

    Parameters
    ----------
    result : CamResult or dict
        The cam stage's result or its ``to_dict()``.
    units_mm : bool
        True: coordinates in millimetres (the default); False: in metres.

    Returns
    -------
    str
        The pitch and working profiles as closed polylines, the base circle and the cam
        centre, on the layers PITCH, WORKING and BASE.
    """
    import ezdxf  # lazy: heavy import

    phi, pitch, working, r0, roller = _arrays(result)
    k = 1000.0 if units_mm else 1.0
    doc = ezdxf.new("R2010")
    doc.units = ezdxf.units.MM if units_mm else ezdxf.units.M
    for name, color in (("PITCH", 1), ("WORKING", 5), ("BASE", 8)):
        doc.layers.add(name, color=color)
    msp = doc.modelspace()
    msp.add_lwpolyline([(float(x) * k, float(y) * k) for x, y in pitch], close=True,
                       dxfattribs={"layer": "PITCH"})
    msp.add_lwpolyline([(float(x) * k, float(y) * k) for x, y in working], close=True,
                       dxfattribs={"layer": "WORKING"})
    msp.add_circle((0.0, 0.0), r0 * k, dxfattribs={"layer": "BASE"})
    msp.add_point((0.0, 0.0), dxfattribs={"layer": "BASE"})
    if math.isfinite(roller) and roller > 0:
        x0, y0 = pitch[0]
        msp.add_circle((float(x0) * k, float(y0) * k), roller * k, dxfattribs={"layer": "WORKING"})
    return dxf_text(doc)
