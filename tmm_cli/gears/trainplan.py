"""The velocity picture (kartina lineinykh skorostei) and the angular-velocity plan (plan uglovykh
skorostei) of a drive train, built graphically as on the sheet (Artobolevsky; Popov & Timofeev).

The wheels are drawn with module m = 1 mm; the axes of the train lie on one vertical line y
(the scheme of the train unfolded into one plane).  Every link turning about a fixed axis is a
straight line v(y) through its axis (v = 0) and one known point; a contact point of two wheels
has one velocity, so the picture is built from the motor wheel outward:

* a pair: the contact point P (pitch point) takes v_P from the driving wheel's line; the driven
  wheel's line goes through its axis and P;
* a planetary stage: the contact 1-2 takes v from wheel 1, the satellite's line goes through it
  and through the contact with the fixed wheel (v = 0); the carrier's line through the axis and
  the satellite's centre.

The angular-velocity plan: from a pole at the distance H (mm) below a horizontal line, rays
parallel to the links' lines cut off segments x_i = H tan(psi_i) with tan(psi_i) = omega_i mu_l /
mu_v, so omega_i = x_i mu_omega, mu_omega = mu_v / (H mu_l), and a stage's ratio is the ratio of
its input and output segments -- read off the plan, compared with the analytic one.
"""
from __future__ import annotations

from . import planetary as pl

M_DRAW = 0.001          # module of the drawing, m
H_PLAN = 50.0           # pole distance of the angular-velocity plan, mm
HEIGHT = 120.0          # height of the velocity picture, mm
WIDTH = 60.0            # largest |v| drawn, mm


def _zd(kind, z):
    return {n: int(v) for n, v in zip(pl.SCHEMES[kind]["wheels"], z)}


def velocity_plans(stages: list, shafts: list) -> dict:
    """The velocity plans of a drive train, built as on the sheet.

    Parameters
    ----------
    stages : list of dict
        The stages as in :class:`.train.TrainResult` (type, scheme, z, ratio, speeds).
    shafts : list of float
        The shafts' angular speeds, rad/s (``shafts[0]`` the input).

    Returns
    -------
    dict
        The points and lines of the velocity picture (m, m/s), the rays of the angular-velocity
        plan and the ratios read off it.

    References
    ----------
    Artobolevsky, *Theory of Mechanisms and Machines*; Popov & Timofeev, *Kursovoe
    proektirovanie po TMM*: the velocity plan (Kutzbach's method) of a gear train.
    """
    links = []          # {name, y0 (m), slope (1/s) read from two points}
    points = []         # {name, y (m), v (m/s)}
    axes = []           # {stage, y (m)} of each stage's input axis
    y_c = 0.0
    # the input wheel's line: through its axis with the motor's speed (the only given velocity)
    slope_in = shafts[0]
    links.append({"name": "0", "y0": 0.0, "slope": slope_in, "stage": -1})
    stage_rows = []
    for i, st in enumerate(stages):
        z = st["z"]
        axes.append({"stage": i, "y": y_c})
        if st["type"] == "pair":
            r1, r2 = M_DRAW * z[0] / 2, M_DRAW * z[1] / 2
            if st["internal"]:
                y_p, y_c2 = y_c - r1, y_c - r1 + r2
            else:
                y_p, y_c2 = y_c + r1, y_c + r1 + r2
            v_p = slope_in * (y_p - y_c)
            slope_out = v_p / (y_p - y_c2)
            points += [{"name": f"P{i + 1}", "y": y_p, "v": v_p}, {"name": f"O{i + 2}", "y": y_c2, "v": 0.0}]
            links.append({"name": f"{i + 1}", "y0": y_c2, "slope": slope_out, "stage": i})
            y_out = y_c2
        else:
            kind = st["scheme"]
            pv = pl.velocity_plan(kind, _zd(kind, z), M_DRAW, omega1=slope_in)
            for p in pv["points"][1:]:
                points.append({"name": f"{p['name'].split()[0]}{i + 1}", "y": y_c + p["y"], "v": p["v"]})
            sat = pv["lines"]["satellite"]
            links.append({"name": f"s{i + 1}", "y0": y_c + sat["y0"], "slope": sat["slope"], "stage": i,
                          "satellite": True})
            slope_out = pv["omega_H"]
            links.append({"name": f"H{i + 1}", "y0": y_c, "slope": slope_out, "stage": i})
            y_out = y_c
        stage_rows.append({"stage": i, "slope_in": slope_in, "slope_out": slope_out})
        slope_in = slope_out
        y_c = y_out
    ys = [0.0] + [p["y"] for p in points]
    span_y = max(ys) - min(ys) or M_DRAW
    v_all = [abs(p["v"]) for p in points] + [abs(links[0]["slope"]) * span_y]
    mu_l = span_y / HEIGHT                      # m per mm
    mu_v = max(v_all) / WIDTH or 1.0            # (m/s) per mm
    mu_w = mu_v / (H_PLAN * mu_l)               # (rad/s) per mm
    rays = []
    for ln in links:
        # the line in the drawing: x = v/mu_v, y/mu_l; tan(psi) = dx/dy; segment x = H tan(psi)
        tan_psi = (ln["slope"] * mu_l) / mu_v
        rays.append({"name": ln["name"], "stage": ln["stage"], "x": H_PLAN * tan_psi,
                     "satellite": bool(ln.get("satellite"))})
    seg = {r["name"]: r["x"] for r in rays}
    out_names = []
    for st_i, st in enumerate(stages):
        out_names.append(f"{st_i + 1}" if st["type"] == "pair" else f"H{st_i + 1}")
    ratios = []
    prev = "0"
    for st_i, name in enumerate(out_names):
        ratios.append({"stage": st_i, "ratio_plan": seg[prev] / seg[name], "ratio": stages[st_i]["ratio"],
                       "x_in": seg[prev], "x_out": seg[name]})
        prev = name
    total = seg["0"] / seg[out_names[-1]]
    return {"mu_l": mu_l, "mu_v": mu_v, "mu_omega": mu_w, "H": H_PLAN, "module": M_DRAW,
            "links": links, "points": points, "axes": axes, "rays": rays, "stages": ratios,
            "ratio_plan": total, "omega_plan": [r["x"] * mu_w for r in rays]}
