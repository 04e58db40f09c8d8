"""The gear train of a drive (results' ``drive_train``), drawn by the report and by its A1
sheet alike: the kinematic scheme of the train with the linear-velocity picture beside it on
one length scale (Kutzbach), and the plan of angular velocities (Smirnov), whose segments
give every shaft's speed and every ratio. Each draws onto the canvas ``make(w, h)`` gives
(the report's SVG canvas or a sheet's recording one) and returns it with its scales."""
from __future__ import annotations

from ..messages import unit
from ..report import figures
from ..report.figures import mu_text

FRAME = 170.0        # mm: the width of a report page's figure
STEP = 22.0          # mm between the stages of the scheme


def _mu_after(sym: str, mu: float, u: str) -> str:
    """' = 0.05 (m/s)/mm' after a μ with its subscript, the unit in the drawing's language."""
    return " = " + mu_text(sym, mu, unit(u), unit("mm")).split(" = ", 1)[1]


def _colors():
    return ["#1f4e9c", "#c0392b", "#1e8449", "#7d3c98", "#d35400", "#117a65", "#884400", "#34495e"]


def _line_color(col, stage: int, satellite: bool) -> str:
    """A picture line's or a plan ray's colour: a satellite in its stage's colour (as the scheme
    draws its wheels), a shaft in the colour of the stage its wheel drives next, the motor's
    black."""
    if stage < 0:
        return "#000"
    return col[(stage if satellite else stage + 1) % len(col)]


def _aw(scheme: str, z, m: float) -> float:
    """A planetary stage's centre distance (m): the sun and satellite 2's, or in scheme D ring
    1's and satellite 2's (internal)."""
    return (z[0] - z[1] if scheme == "D" else z[0] + z[1]) * m / 2


def layout(d: dict, frame: float = FRAME, height: float | None = None, k_max: float = 1.0) -> dict:
    """Where the scheme and the picture go and at which scales: the scheme's factor ``k`` (its
    x spacing), its standard length scale ``mu_l`` (m/mm), the picture's standard velocity
    scale ``mu_v`` ((m/s)/mm) -- the fastest point about ``vh`` mm from the axis, in the room the
    scheme leaves -- and the heights ``y_lo``, ``y_hi`` (m) the figure spans."""
    vp = d["velocity_plan"]
    st = d["stages"]
    m = vp["module"]
    ys = [0.0] + [p["y"] for p in vp["points"]] + [a["y"] for a in vp["axes"]]
    for s, a in zip(st, vp["axes"]):
        z = s["z"]
        if s["type"] == "pair":          # both wheels whole: the driven one beyond (or in) the first
            r1, r2 = (m * q / 2 for q in z[:2])
            ys += [a["y"] - r1, a["y"] + r1, a["y"] + (2 * r2 - r1 if s.get("internal") else r1 + 2 * r2)]
        else:          # a planetary stage: the top of its satellites (A: one wheel; B-D: the pair 2-3)
            aw = _aw(s["scheme"], z, m)
            sat = z[1] if s["scheme"] == "A" else max(z[1], z[2])
            ys += [a["y"] + aw + m * sat / 2, a["y"] + (m * z[0] / 2 if s["scheme"] == "D" else 0.0)]
    y_lo, y_hi = min(ys), max(ys)
    w_scheme = 16 + STEP * len(st) + 14
    k = min(k_max, 0.55 * frame / w_scheme)
    if height is not None:
        k = min(k, (height - 22.0) / max((y_hi - y_lo) / vp["mu_l"], 1e-12))
    mu_l = figures.nice_scale(vp["mu_l"] / k)             # reduced to a standard scale (the one stated)
    vmax = max([abs(p["v"]) for p in vp["points"]] + [1e-300])
    vh = min(90.0, max(15.0, (frame - w_scheme * k - 24.0) / 2))
    mu_v = figures.nice_scale(vmax / vh)
    return {"k": k, "mu_l": mu_l, "mu_v": mu_v, "vh": vmax / mu_v, "w_scheme": w_scheme * k,
            "y_lo": y_lo, "y_hi": y_hi}


def scheme_and_picture(make, d: dict, frame: float = FRAME, height: float | None = None,
                       k_max: float = 1.0):
    """The kinematic scheme of the train (left) and the linear-velocity picture (right) on one
    length scale, drawn onto ``make(width, height)`` (a canvas, returned with its scales
    {"mu_l", "mu_v"}): as large as ``frame`` mm wide (and ``height`` high) allow, at most
    ``k_max`` times the results' own μl (:func:`layout`), each scale a standard one."""
    vp = d["velocity_plan"]
    st = d["stages"]
    L = layout(d, frame, height, k_max)
    k, mu_l, mu_v, vh, y_lo, y_hi = L["k"], L["mu_l"], L["mu_v"], L["vh"], L["y_lo"], L["y_hi"]
    w_scheme = L["w_scheme"]
    H = (y_hi - y_lo) / mu_l + 22
    c = make(w_scheme + 2 * vh + 24, H)

    def Y(y):
        return 12 + (y - y_lo) / mu_l

    def r_mm(z):
        return vp["module"] * z / 2 / mu_l
    x = 8 * k
    col = _colors()

    def wheel(xw, y_a, y_b, color):
        """A wheel in the scheme: its pitch diameter, short strokes at both ends."""
        c.line((xw, y_a), (xw, y_b), color=color, width=0.7)
        for yy in (y_a, y_b):
            c.line((xw - 1.2, yy), (xw + 1.2, yy), color=color, width=0.7)
    c.text(x, H - 4, "μ", sub="l", after=_mu_after("l", mu_l, "m"), anchor="start", size=6.5)
    y_shaft = Y(0.0)
    c.line((2, y_shaft), (x + 6 * k, y_shaft), width=0.5)               # motor shaft
    c.text(2, y_shaft + 2.2, "M", anchor="start", size=6.5)
    x_prev = x
    for i, (s, a) in enumerate(zip(st, vp["axes"])):
        xs = x + (i + 0.6) * STEP * k
        yc = Y(a["y"])
        color = col[i % len(col)]
        z = s["z"]
        if s["type"] == "pair":
            c.line((x_prev, yc), (xs + 3 * k, yc), width=0.5)          # the input shaft of the stage
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
            aw_mm = _aw(sch, z, vp["module"]) / mu_l
            xh = xs + (9 if sch != "A" else 5) * k        # the carrier's arm, its output shaft from there
            # the input shaft to the sun 1 (to ring 1's disc in scheme D): it ends there; the
            # carrier's shaft, not wheel 1's, goes on to the next stage
            c.line((x_prev, yc), ((xs - 3 * k) if sch == "D" else (xs + 3 * k), yc), width=0.5)
            for sgn in (1,):                          # the half above the axis, as on the sheet
                ys_ = yc + sgn * aw_mm
                if sch == "D":                        # ring 1 (internal, the input): its rim and its disc
                    c.line((xs, yc + sgn * rr["z1"]), (xs, yc + sgn * rr["z1"] - sgn * 2), color=color, width=0.7)
                    c.line((xs - 3 * k, yc + sgn * rr["z1"]), (xs, yc + sgn * rr["z1"]), color=color, width=0.7)
                    c.line((xs - 3 * k, yc), (xs - 3 * k, yc + sgn * rr["z1"]), color=color, width=0.7)
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
                c.line((xh, yc), (xh, ys_), width=0.6)
                c.line((xs - 2 * k, ys_), (xh, ys_), width=0.6)
            if sch != "D":
                wheel(xs, yc, yc + rr["z1"], color)                                                # sun 1
            c.text(xs - 2.5, yc + aw_mm, sch, size=6, color=color, anchor="end", bold=True)
            c.text(xh + 1 * k + 1, yc + aw_mm / 2, "H", size=6, anchor="start")
            c.line((xh, yc), (xs + STEP * k * 0.7, yc), width=0.5)
            x_prev = xh
    # the linear-velocity picture: its axis vh mm right of the scheme's room plus 10
    x0 = w_scheme + vh + 10
    c.line((x0, Y(y_lo) - 4), (x0, Y(y_hi) + 4), width=0.3)
    c.text(x0, Y(y_hi) + 7, "y", size=6.5, italic=True)
    c.text(x0 + vh, 4, "μ", sub="v", after=_mu_after("v", mu_v, "m/s"), anchor="end", size=6.5)
    for p in vp["points"]:
        yy = Y(p["y"])
        c.line((w_scheme - 4, yy), (x0, yy), color="#999", width=0.15, dash="0.8,0.8")
        xv = x0 + p["v"] / mu_v
        c.line((x0, yy), (xv, yy), color="#555", width=0.25)
        c.dot((xv, yy), 0.5)
        c.text(xv + (2 if p["v"] >= 0 else -2), yy - 2, p["name"], size=5, anchor="start" if p["v"] >= 0 else "end",
               color="#555")
    named: list[tuple[float, float]] = []     # where the lines' names went: none on another
    for ln in vp["links"]:
        # draw each line over the y range of the points of its stage
        pts_y = [ln["y0"]] + [p["y"] for p in vp["points"]
                              if abs(ln["slope"] * (p["y"] - ln["y0"]) - p["v"]) <= 1e-9 * (abs(p["v"]) + 1e-12)]
        y_a, y_b = min(pts_y), max(pts_y)
        if (y_b - y_a) / mu_l < 2:
            y_b = y_a + 8 * mu_l
        pa = (x0 + ln["slope"] * (y_a - ln["y0"]) / mu_v, Y(y_a))
        pb = (x0 + ln["slope"] * (y_b - ln["y0"]) / mu_v, Y(y_b))
        color = _line_color(col, ln["stage"], bool(ln.get("satellite")))
        c.line(pa, pb, color=color, width=0.45, dash="2,1" if ln.get("satellite") else None)
        at = (pb[0] + 1.5, pb[1] + 1.5)
        while any(abs(at[0] - u) < 4.0 and abs(at[1] - v) < 2.6 for u, v in named):
            at = (at[0], at[1] - 2.8)          # two lines ending at one point ('0' and 's1' at A1)
        named.append(at)
        c.text(at[0], at[1], ln["name"], size=6, color=color, anchor="start", halo=True)
    return c, {"mu_l": mu_l, "mu_v": mu_v}


def angular_plan(make, d: dict, frame: float = FRAME, height: float | None = None, scales: dict | None = None,
                 h_max: float = 60.0):
    """The plan of angular velocities (Smirnov) built on the picture: from the pole P at the
    distance H from the line, each shaft's ray parallel to its line in the picture, so that it
    cuts the line at x = H ω μl/μv and ω = μω x with μω = μv/(H μl) (μl, μv the picture's:
    ``scales``, else :func:`layout`'s for ``frame``), μω a standard scale and H what it gives,
    as large as ``frame`` mm wide and ``height`` (else ``h_max``) high allow. Drawn onto ``make(width, height)``;
    returns (canvas, {"mu_omega", "H"})."""
    vp = d["velocity_plan"]
    rays = vp["rays"]
    sc = scales or layout(d, frame)
    per = sc["mu_l"] / sc["mu_v"]                       # mm of x per mm of H per rad/s
    omegas = [r["x"] * vp["mu_omega"] for r in rays]      # each ray's ω (rad/s): x μω of the results
    span = (max(omegas + [0.0]) - min(omegas + [0.0])) * per
    room = min(h_max if height is None else height - 30.0, (frame - 30.0) / max(span, 1e-12))
    # μω from the standard series, the smallest whose H = μv/(μω μl) fits the room: every scale
    # stated a standard one, H what the three give (a whole or half millimetre, written exactly)
    mu_w = figures.nice_scale(sc["mu_v"] / (max(room, 5.0) * sc["mu_l"]))
    Hh = sc["mu_v"] / (mu_w * sc["mu_l"])
    xs = [w / mu_w for w in omegas] + [0.0]
    x_lo = min(xs)
    # ray names stacked where rays end close together: the canvas leaves room for the stack
    used, lifts = [], []
    for x in xs[:-1]:
        lifts.append(2.5 + 3.2 * sum(1 for u in used if abs(u - x) < 6))
        used.append(x)
    # the note "H = 120 mm, μω = 0.05 (rad/s)/mm": measured as it is written (ω the subscript)
    head, after = f"H = {Hh:.4g} {unit('mm')}, μ", _mu_after("ω", mu_w, "rad/s")
    c = make(max(max(xs) - x_lo + 30, figures.text_size(head + after, 6.5 * 25.4 / 72.0, sub="ω")[0] + 6.0),
             Hh + 14 + max(lifts + [10.0]) + 2.0)
    px, py = 15 - x_lo, 8.0
    c.dot((px, py), 0.7)
    c.text(px - 2.5, py, "P", size=6.5, anchor="end", italic=True)
    c.line((15 - 4, py + Hh), (15 + max(xs) - x_lo + 4, py + Hh), width=0.3)
    c.line((px, py), (px, py + Hh), color="#999", width=0.2, dash="1,1")
    col = _colors()
    for r, x, lift in zip(rays, xs, lifts):
        q = (px + x, py + Hh)
        color = _line_color(col, r["stage"], r["satellite"])
        c.line((px, py), q, color=color, width=0.4, dash="2,1" if r["satellite"] else None)
        c.text(q[0], q[1] + lift, r["name"], size=6, color=color, halo=True)
    c.text(2.0, 4, head, sub="ω", after=after, anchor="start", size=6.5)
    return c, {"mu_omega": mu_w, "H": Hh}
