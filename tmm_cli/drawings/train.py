"""The gear train of a drive (results' ``drive_train``), drawn by the report and by its A1
sheet alike: the kinematic scheme of the train with the linear-velocity picture beside it on
one length scale (Kutzbach), and the plan of angular velocities (Smirnov), whose segments
give every shaft's speed and every ratio. Each draws onto the canvas ``make(w, h)`` gives
(the report's SVG canvas or a sheet's recording one) and returns it with its scales."""
from __future__ import annotations

from ..messages import unit
from ..report.figures import mu_text

FRAME = 170.0        # mm: the width of a report page's figure
STEP = 22.0          # mm between the stages of the scheme


def _mu_after(sym: str, mu: float, u: str) -> str:
    """' = 0.05 (m/s)/mm' after a μ with its subscript, the unit in the drawing's language."""
    return " = " + mu_text(sym, mu, unit(u), unit("mm")).split(" = ", 1)[1]


def _colors():
    return ["#1f4e9c", "#c0392b", "#1e8449", "#7d3c98", "#d35400", "#117a65", "#884400", "#34495e"]


def scheme_and_picture(make, d: dict, frame: float = FRAME, height: float | None = None,
                       k_max: float = 1.0):
    """The kinematic scheme of the train (left) and the linear-velocity picture (right) on one
    length scale, drawn onto ``make(width, height)`` (a canvas, returned with its scales
    {"mu_l", "mu_v"}): as large as ``frame`` mm wide (and ``height`` high) allow, at most
    ``k_max`` times the results' own μ, each scale reduced to a standard one."""
    vp = d["velocity_plan"]
    mu_l, mu_v = vp["mu_l"], vp["mu_v"]
    st = d["stages"]
    ys = [0.0] + [p["y"] for p in vp["points"]] + [a["y"] for a in vp["axes"]]
    radii = []
    for s, a in zip(st, vp["axes"]):
        if s["type"] == "pair":          # both wheels whole: the driven one beyond (or in) the first
            r1, r2 = (vp["module"] * z / 2 for z in s["z"][:2])
            radii += [a["y"] - r1, a["y"] + r1, a["y"] + (2 * r2 - r1 if s.get("internal") else r1 + 2 * r2)]
        else:          # a planetary stage: the top of its satellites (their labels stay on the canvas)
            z = s["z"]
            aw = (z[0] + z[1] if s["scheme"] != "D" else z[0] - z[1]) * vp["module"] / 2
            radii.append(a["y"] + aw + vp["module"] * max(z[1], z[2] if len(z) > 2 else 0) / 2)
    ys += radii
    y_lo, y_hi = min(ys), max(ys)
    w_scheme = 16 + STEP * len(st) + 14
    vmax = max([abs(p["v"]) for p in vp["points"]] + [1e-300]) / mu_v
    w_pic = 2 * vmax + 24
    k = min(k_max, frame / (w_scheme + w_pic))                  # fit the page: one factor for both
    if height is not None:
        k = min(k, (height - 22.0) / max((y_hi - y_lo) / mu_l, 1e-12))
    # reduced to fit, the lengths and the velocities still at standard scales (the ones stated)
    from ..report import figures
    kl = mu_l / figures.nice_scale(mu_l / k)
    kv = mu_v / figures.nice_scale(mu_v / k)
    H = (y_hi - y_lo) / mu_l * kl + 22
    c = make(w_scheme * k + w_pic * k, H)

    def Y(y):
        return 12 + (y - y_lo) / mu_l * kl

    def r_mm(z):
        return vp["module"] * z / 2 / mu_l * kl
    x = 8 * k
    col = _colors()

    def wheel(xw, y_a, y_b, color):
        """A wheel in the scheme: its pitch diameter, short strokes at both ends."""
        c.line((xw, y_a), (xw, y_b), color=color, width=0.7)
        for yy in (y_a, y_b):
            c.line((xw - 1.2, yy), (xw + 1.2, yy), color=color, width=0.7)
    c.text(x, H - 4, "μ", sub="l", after=_mu_after("l", mu_l / kl, "m"), anchor="start", size=6.5)
    y_shaft = Y(0.0)
    c.line((2, y_shaft), (x + 6 * k, y_shaft), width=0.5)               # motor shaft
    c.text(2, y_shaft + 2.2, "M", anchor="start", size=6.5)
    x_prev = x
    for i, (s, a) in enumerate(zip(st, vp["axes"])):
        xs = x + (i + 0.6) * STEP * k
        yc = Y(a["y"])
        c.line((x_prev, yc), (xs + 3 * k, yc), width=0.5)              # the input shaft of the stage
        color = col[i % len(col)]
        z = s["z"]
        if s["type"] == "pair":
            r1, r2 = r_mm(z[0]), r_mm(z[1])
            wheel(xs, yc - r1, yc + r1, color)
            yc2 = yc - r1 + r2 if s["internal"] else yc + r1 + r2
            if s["internal"]:
                wheel(xs + 2 * k, yc2 - r2, yc2 + r2, color)
                for yy in (yc2 - r2, yc2 + r2):
                    c.line((xs - 1 * k, yy), (xs + 2 * k, yy), color=color, width=0.7)
            else:
                wheel(xs, yc2 - r2, yc2 + r2, color)
            c.text(xs - 2.5, yc + r1 * 0.5, str(z[0]), size=5.5, color=color, anchor="end")
            c.text(xs - 2.5, yc2 + r2 * 0.5, str(z[1]), size=5.5, color=color, anchor="end")
            c.line((xs, yc2), (xs + STEP * k * 0.7, yc2), width=0.5)
            x_prev = xs
        else:
            sch = s["scheme"]
            zd = dict(zip(("z1", "z2", "z3", "z4"), z))
            rr = {kk: r_mm(v) for kk, v in zd.items()}
            aw_mm = {"A": (zd["z1"] + zd["z2"]), "B": (zd["z1"] + zd["z2"]), "C": (zd["z1"] + zd["z2"]),
                     "D": (zd["z1"] - zd["z2"])}[sch] * vp["module"] / 2 / mu_l * kl
            for sgn in (1,):                          # the half above the axis, as on the sheet
                ys_ = yc + sgn * aw_mm
                if sch == "D":
                    c.line((xs, yc + sgn * rr["z1"]), (xs, yc + sgn * rr["z1"] - sgn * 2), color=color, width=0.7)
                    c.line((xs - 3 * k, yc + sgn * rr["z1"]), (xs, yc + sgn * rr["z1"]), color=color, width=0.7)
                wheel(xs, ys_ - rr["z2"], ys_ + rr["z2"], color)                               # satellite 2
                if sch == "A":
                    c.hatch((xs - 1.5, yc + sgn * rr["z3"]), (xs + 1.5, yc + sgn * rr["z3"]), (0, sgn),
                            color=color)
                else:
                    x3 = xs + 5 * k
                    c.line((xs, ys_), (x3, ys_), width=0.5)
                    wheel(x3, ys_ - rr["z3"], ys_ + rr["z3"], color)
                    if sch in ("B", "D"):
                        c.hatch((x3 - 1.5, yc + sgn * rr["z4"]), (x3 + 1.5, yc + sgn * rr["z4"]), (0, sgn),
                                color=color)
                    else:
                        c.hatch((x3 + 1, yc + sgn * 0.8), (x3 + 1, yc + sgn * rr["z4"]), (1, 0), color=color)
                        c.line((x3, yc + sgn * 0.8), (x3, yc + sgn * rr["z4"]), color=color, width=0.7)
                # carrier H: from the output shaft up to the satellite axle
                xh = xs + (9 if sch != "A" else 5) * k
                c.line((xh, yc), (xh, ys_), width=0.6)
                c.line((xs - 2 * k, ys_), (xh, ys_), width=0.6)
            if sch != "D":
                wheel(xs, yc, yc + rr["z1"], color)                                                # sun 1
            c.text(xs - 2.5, yc + aw_mm, sch, size=6, color=color, anchor="end", bold=True)
            c.text(xs + (10 if sch != "A" else 6) * k + 1, yc + aw_mm / 2, "H", size=6, anchor="start")
            c.line((xs + (9 if sch != "A" else 5) * k, yc), (xs + STEP * k * 0.7, yc), width=0.5)
            x_prev = xs
    # the linear-velocity picture
    x0 = w_scheme * k + vmax * k + 10 * k
    c.line((x0, Y(y_lo) - 4), (x0, Y(y_hi) + 4), width=0.3)
    c.text(x0, Y(y_hi) + 7, "y", size=6.5, italic=True)
    c.text(x0 + vmax * k, 4, "μ", sub="v", after=_mu_after("v", mu_v / kv, "m/s"),
           anchor="end", size=6.5)
    for p in vp["points"]:
        yy = Y(p["y"])
        c.line((w_scheme * k - 4, yy), (x0, yy), color="#999", width=0.15, dash="0.8,0.8")
        xv = x0 + p["v"] / mu_v * kv
        c.line((x0, yy), (xv, yy), color="#555", width=0.25)
        c.dot((xv, yy), 0.5)
        c.text(xv + (2 if p["v"] >= 0 else -2), yy - 2, p["name"], size=5, anchor="start" if p["v"] >= 0 else "end",
               color="#555")
    for j, ln in enumerate(vp["links"]):
        # draw each line over the y range of the points of its stage
        pts_y = [Y(ln["y0"])] + [Y(p["y"]) for p in vp["points"]
                                 if abs(ln["slope"] * (p["y"] - ln["y0"]) - p["v"]) <= 1e-9 * (abs(p["v"]) + 1e-12)]
        y_a, y_b = min(pts_y), max(pts_y)
        if y_b - y_a < 2:
            y_b = y_a + 8
        pa = (x0 + ln["slope"] * ((y_a - 12) / kl * mu_l + y_lo - ln["y0"]) / mu_v * kv, y_a)
        pb = (x0 + ln["slope"] * ((y_b - 12) / kl * mu_l + y_lo - ln["y0"]) / mu_v * kv, y_b)
        color = col[(ln["stage"] + 1) % len(col)] if ln["stage"] >= 0 else "#000"
        c.line(pa, pb, color=color, width=0.45, dash="2,1" if ln.get("satellite") else None)
        c.text(pb[0] + 1.5, pb[1] + 1.5, ln["name"], size=6, color=color, anchor="start", halo=True)
    return c, {"mu_l": mu_l / kl, "mu_v": mu_v / kv}


def angular_plan(make, d: dict, frame: float = FRAME, k_max: float = 1.0, height: float | None = None):
    """The plan of angular velocities (Smirnov): from the pole P at the distance H above the
    line, each shaft's ray; its segment on the line is that link's ω at μω. Drawn onto
    ``make(width, height)``, as wide as ``frame`` mm (and its pole's height H as ``height``)
    allows, at most ``k_max`` times the results' own scale (reduced to a standard μω); returns
    (canvas, {"mu_omega", "H"})."""
    vp = d["velocity_plan"]
    rays = vp["rays"]
    xs = [r["x"] for r in rays] + [0.0]
    k = min(k_max, (frame - 30) / max(max(xs) - min(xs), 1e-9))
    if height is not None:                 # the pole, the line and the rays' names below it
        k = min(k, (height - 30.0) / max(vp["H"], 1e-12))
    from ..report import figures
    k = vp["mu_omega"] / figures.nice_scale(vp["mu_omega"] / k)     # reduced to a standard μω
    Hh = vp["H"] * k
    x_lo = min(xs) * k
    # ray names stacked where rays end close together: the canvas leaves room for the stack
    used, lifts = [], []
    for r in rays:
        lifts.append(2.5 + 3.2 * sum(1 for u in used if abs(u - r["x"] * k) < 6))
        used.append(r["x"] * k)
    note = f"H = {vp['H'] * k:.0f} {unit('mm')}, {mu_text('ω', vp['mu_omega'] / k, unit('rad/s'), unit('mm'))}"
    c = make(max((max(xs) - min(xs)) * k + 30, figures.text_size(note, 6.5 * 25.4 / 72.0)[0] + 6.0),
             Hh + 14 + max(lifts + [10.0]) + 2.0)
    px, py = 15 - x_lo, 8.0
    c.dot((px, py), 0.7)
    c.text(px - 2.5, py, "P", size=6.5, anchor="end", italic=True)
    c.line((15 - 4, py + Hh), (15 + (max(xs) - min(xs)) * k + 4, py + Hh), width=0.3)
    c.line((px, py), (px, py + Hh), color="#999", width=0.2, dash="1,1")
    col = _colors()
    for r, lift in zip(rays, lifts):
        q = (px + r["x"] * k, py + Hh)
        color = col[(r["stage"] + 1) % len(col)] if r["stage"] >= 0 else "#000"
        c.line((px, py), q, color=color, width=0.4, dash="2,1" if r["satellite"] else None)
        c.text(q[0], q[1] + lift, r["name"], size=6, color=color, halo=True)
    c.text(2.0, 4, "H = " + f"{vp['H'] * k:.0f} {unit('mm')}, μ", sub="ω",
           after=_mu_after("ω", vp["mu_omega"] / k, "rad/s"), anchor="start", size=6.5)
    return c, {"mu_omega": vp["mu_omega"] / k, "H": vp["H"] * k}
