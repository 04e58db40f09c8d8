"""Report section 'cam': motion diagrams with scales, the s - ds/dphi diagram with the
tangent lines and the admissible region of cam centres, the cam profile to scale (base
circle, pitch and working profiles, follower and roller every 30 deg), the pressure-angle
diagram and the tables; the profile exported beside the report as CSV and DXF.

Reads only ``results['cam']`` (see tmm_cli/cam/synthesis.py for its keys)."""
from __future__ import annotations

import math

import numpy as np

from ... import locales
from ..notation import Term

I18N = locales.table("cam", "words")

MM = 1e3
PHASE_COLORS = {"rise": "#e8f0fb", "far_dwell": "#f4f4f4", "return": "#fbeee8", "near_dwell": "#ffffff"}


def _loc(lang: str, text: str) -> str:
    """Units in the report's language: deg -> °, and mm and rad as the language spells them
    (messages.unit)."""
    import re
    text = re.sub(r"(?<![A-Za-z])deg(?![A-Za-z])", "°", text)
    from ...messages import unit
    if lang != "en":
        text = re.sub(r"(?<![A-Za-z])mm(?![A-Za-z])", unit("mm", lang), text)
        text = re.sub(r"(?<![A-Za-z])rad(?![A-Za-z])", unit("rad", lang), text)
        text = re.sub(r"(?<![A-Za-z])m/", unit("m", lang) + "/", text)      # the m of a scale's m/mm
    return Term(text)          # a catalogue's name: its notation (r_r) with a subscript in the HTML


def _law_title(L: dict, t) -> str:
    """A motion law's title in the report's language (results.json holds its name and English title)."""
    key = f"cam.law.{L.get('name')}"
    text = t(key)
    return L["title"] if text == key else text


def _units(c, lang: str = "en"):
    """(factor, unit) of s, ds/dphi, d2s/dphi2 for the tables and diagrams."""
    if c["follower"] == "rocker":
        out = (1.0, "deg"), (1.0, "rad/rad"), (1.0, "1/rad")
    else:
        out = (MM, "mm"), (MM, "mm/rad"), (MM, "mm/rad²")
    return tuple((k, _loc(lang, u)) for k, u in out)


def _phase_spans(c):
    ph = c["phases"]
    a = 0.0
    out = []
    for k in ("rise", "far_dwell", "return", "near_dwell"):
        out.append((k, a, a + ph[k]))
        a += ph[k]
    return out


def diagrams_figure(ctx, c):
    fp = ctx.figures
    (ks, us), (kv, uv), (ka, ua) = _units(c, ctx.lang)
    phi = np.asarray(c["phi"] + [360.0])
    series = [(np.asarray(c["s"] + c["s"][:1]) * ks, "s, " + us),
              (np.asarray(c["ds"] + c["ds"][:1]) * kv, "ds/dφ, " + uv),
              (np.asarray(c["d2s"] + c["d2s"][:1]) * ka, "d²s/dφ², " + ua)]
    # 120 mm high (the ordinates' scales chosen for it): with its heading and caption it fits
    # under the main dimensions and the motion laws (at 150 mm it went to a page of its own and
    # left the cam chapter's first page half empty)
    W, H = 170.0, 120.0
    fig, axes = fp.new_figure(W, H, nrows=3, sharex=True)
    left, right, bottom, top, gap = 0.12, 0.97, 0.08, 0.98, 0.05
    fig.subplots_adjust(left=left, right=right, bottom=bottom, top=top, hspace=gap * 3)
    ax_w_mm = (right - left) * W
    mu_phi = fp.nice_scale(360.0 / ax_w_mm)
    scales = [(Term("μ_φ"), _loc(ctx.lang, f"{ctx.fmt(mu_phi)} deg/mm"))]
    for ax, (y, lab) in zip(axes, series):
        for k, a, b in _phase_spans(c):
            if b > a:
                ax.axvspan(a, b, color=PHASE_COLORS[k], lw=0)
        ax.plot(phi, y, color="k", lw=1.0)
        ax.axhline(0, color="0.5", lw=0.5)
        mu = fp.std_axis(ax, float(np.min(y)), float(np.max(y)), pad=0.04)
        ax.set_ylabel(lab)
        ax.grid(True, lw=0.3)
        # the scale as the course writes it: μ with its quantity as the subscript, a unit that is a
        # quotient bracketed before the millimetre ((mm/rad)/mm, not mm/rad/mm)
        sym, u = lab.split(",")[0], lab.split(", ")[1]
        u = f"({u})" if "/" in u and not u.startswith("(") else u
        scales.append((Term(f"μ_{{{sym}}}" if len(sym) > 1 else f"μ_{sym}"), _loc(ctx.lang, f"{ctx.fmt(mu)} {u}/mm")))
    axes[-1].set_xlim(0, mu_phi * ax_w_mm)
    axes[-1].set_xlabel(_loc(ctx.lang, "φ, deg"))
    for x in range(0, 361, 30):
        for ax in axes:
            ax.axvline(x, color="0.85", lw=0.3)
    return fig, scales


def _clip_line(p, d, box):
    """Segment of the line p + t d inside the box (xmin, ymin, xmax, ymax)."""
    xmin, ymin, xmax, ymax = box
    ts = []
    for i, (lo, hi) in enumerate(((xmin, xmax), (ymin, ymax))):
        if abs(d[i]) > 1e-15:
            ts += [(lo - p[i]) / d[i], (hi - p[i]) / d[i]]
    ts = sorted(ts)
    if len(ts) < 4:
        return None
    a, b = ts[1], ts[2]
    return np.array([p + a * d, p + b * d])


def construction_figure(ctx, c):
    fp = ctx.figures
    k = c["construction"]
    box = k["box"]
    lo, hi = np.array(box[:2]) * MM, np.array(box[2:]) * MM
    if k.get("A") is not None:      # a rocker's pivot A and its ground: in the figure too (it was cut off)
        A = np.asarray(k["A"], float) * MM
        pad = 0.06 * float(np.max(hi - lo))
        lo, hi = np.minimum(lo, A - pad), np.maximum(hi, A + pad)
    unit, label = fp.drawing_scale(max((hi - lo)[0] / 134.0, (hi - lo)[1] / 134.0))
    fig, ax = fp.figure_at_scale(lo, hi, unit)
    reg = np.asarray(k.get("region") or [])
    if len(reg) >= 3:
        ax.fill(reg[:, 0] * MM, reg[:, 1] * MM, color="#cfe8cf", lw=0, zorder=0)
    for name, col in (("rise", "tab:blue"), ("return", "tab:red")):
        B = np.asarray(k[f"B_{name}"]) * MM
        D = np.asarray(k[f"D_{name}"]) * MM
        ax.plot(B[:, 0], B[:, 1], color="0.3", lw=0.8)
        ax.plot(D[:, 0], D[:, 1], color=col, lw=1.2, label=ctx.t(f"cam.{name}"))
        step = max(1, len(B) // 8)
        for b, d in zip(B[::step], D[::step]):
            ax.plot([b[0], d[0]], [b[1], d[1]], color=col, lw=0.4)
    for tline in k["tangents"]:
        seg = _clip_line(np.asarray(tline["point"]) * MM, np.asarray(tline["direction"]), (*lo, *hi))
        if seg is not None:
            col = "tab:blue" if tline["phase"] == "rise" else ("tab:red" if tline["phase"] == "return" else "0.4")
            ax.plot(seg[:, 0], seg[:, 1], color=col, lw=0.8, ls="--")
    O = np.zeros(2)
    B0 = np.asarray(k["B0"]) * MM
    ax.plot(*O, "ko", ms=3)
    ax.annotate("O", O, textcoords="offset points", xytext=(4, -8), fontsize=8)
    ax.plot(*B0, "ko", ms=2.5)
    ax.annotate("B0", B0, textcoords="offset points", xytext=(4, -8), fontsize=8)
    ax.plot([O[0], B0[0]], [O[1], B0[1]], color="k", lw=0.6)
    if k.get("A") is not None:
        A = np.asarray(k["A"]) * MM
        fp.draw_ground(ax, A, 3 * unit * MM / MM)
        ax.plot(*A, "ko", ms=3)
        ax.annotate("A", A, textcoords="offset points", xytext=(4, 4), fontsize=8)
        ax.plot([A[0], B0[0]], [A[1], B0[1]], color="0.3", lw=0.8)
    _diagram_axes(ax, B0, lo, hi, ctx)
    # the title 3 mm below the figure's top edge whatever its height (at 0.97 of a short figure
    # its letters reached over the edge)
    ax.set_title(ctx.t("cam.construction_title"), fontsize=9, y=1.0 - 3.0 / (fig.get_figheight() * 25.4), va="top")
    ax.legend(loc="lower left", fontsize=7, frameon=False)
    return fig, unit, label


def _diagram_axes(ax, B0, lo, hi, ctx):
    """Axes of the s - ds/dphi diagram through B0: s along the follower's rise, ds/dphi across."""
    kw = dict(arrowprops=dict(arrowstyle="-|>", lw=0.6, color="k"))
    ax.annotate("", xy=(hi[0] - 0.02 * (hi[0] - lo[0]), B0[1]), xytext=(lo[0], B0[1]), **kw)
    ax.annotate("", xy=(B0[0], hi[1] - 0.02 * (hi[1] - lo[1])), xytext=(B0[0], lo[1]), **kw)
    ax.annotate(_loc(ctx.lang, "ds/dφ, mm"), (hi[0], B0[1]), textcoords="offset points", xytext=(-4, 4),
                ha="right", fontsize=7)
    ax.annotate(_loc(ctx.lang, "s, mm"), (B0[0], hi[1]), textcoords="offset points", xytext=(4, -10),
                fontsize=7)


def profile_figure(ctx, c):
    fp = ctx.figures
    pitch = np.asarray(c["pitch_profile"]) * MM
    work = np.asarray(c["working_profile"]) * MM
    r0, rr = c["r0"] * MM, c["roller"] * MM
    sigma = 1.0 if c["rotation"] == "ccw" else -1.0
    k = c["construction"]
    rocker = c["follower"] == "rocker"
    pts = [pitch]
    A = np.asarray(k["A"]) * MM if rocker else None
    angs = np.radians(np.arange(0, 360, 30))
    if rocker:
        c_, s_ = np.cos(-sigma * angs), np.sin(-sigma * angs)
        A_inv = np.column_stack([c_ * A[0] - s_ * A[1], s_ * A[0] + c_ * A[1]])
        pts.append(A_inv)
    flat = c["follower"] == "flat"
    half = 0.5 * c.get("face_width_symmetric", 0.0) * MM * 1.1 if flat else 0.0
    if flat:
        pts.append(pitch + half)
        pts.append(pitch - half)
    # each position's point B on the pitch profile, the follower's axis u there, its normal n and
    # where the drawn axis starts (a flat face's foot, else B): for the extent and the drawing
    at = []
    for a in angs:
        B = pitch[int(round(math.degrees(a))) % len(pitch)]
        u = np.array([-math.sin(-sigma * a), math.cos(-sigma * a)])
        n = np.array([u[1], -u[0]])
        at.append((B, u, n, B - np.dot(B, n) * n if flat else B))
    if not rocker:       # the follower's axis drawn out from each position's point: in the figure too
        pts += [(foot + u * (0.4 if flat else 0.6) * r0)[None, :] for _, u, _, foot in at]
    allp = np.vstack(pts)
    lo, hi = allp.min(axis=0) - rr, allp.max(axis=0) + rr
    unit, label = fp.drawing_scale(max((hi - lo)[0] / 134.0, (hi - lo)[1] / 154.0))
    fig, ax = fp.figure_at_scale(lo, hi, unit)
    th = np.linspace(0, 2 * np.pi, 361)
    ax.plot(r0 * np.cos(th), r0 * np.sin(th), color="0.5", lw=0.6, ls="-.")
    if rr > 0:
        ax.plot(*np.vstack([pitch, pitch[:1]]).T, color="k", lw=0.8, ls="--")
    ax.plot(*np.vstack([work, work[:1]]).T, color="k", lw=1.6)
    ax.plot(0, 0, "k+", ms=8)
    ax.annotate("O", (0, 0), textcoords="offset points", xytext=(4, 4), fontsize=8)
    for i, (B, u, n, foot) in enumerate(at):
        if flat:
            # the face: perpendicular to the follower's axis through the contact point
            ax.plot([foot[0] - half * n[0], foot[0] + half * n[0]], [foot[1] - half * n[1], foot[1] + half * n[1]],
                    color="tab:blue", lw=0.6)
            ax.plot([foot[0], foot[0] + u[0] * 0.4 * r0], [foot[1], foot[1] + u[1] * 0.4 * r0],
                    color="tab:blue", lw=0.5)
            ax.annotate(str(i), foot, textcoords="offset points", xytext=(3, 3), fontsize=6, color="tab:blue")
            continue
        if rr > 0:
            ax.plot(B[0] + rr * np.cos(th), B[1] + rr * np.sin(th), color="tab:blue", lw=0.5)
        if rocker:
            Ai = A_inv[i]
            ax.plot([Ai[0], B[0]], [Ai[1], B[1]], color="tab:blue", lw=0.5)
            ax.plot(*Ai, "o", color="tab:blue", ms=1.5)
        else:
            ax.plot([B[0], B[0] + u[0] * 0.6 * r0], [B[1], B[1] + u[1] * 0.6 * r0], color="tab:blue", lw=0.5)
        ax.annotate(str(i), B, textcoords="offset points", xytext=(3, 3), fontsize=6, color="tab:blue")
    # direction of rotation
    arc = np.linspace(0.15, 0.75, 20) * sigma
    rr_ = 0.35 * r0
    ax.plot(rr_ * np.cos(arc), rr_ * np.sin(arc), color="k", lw=0.6)
    ax.annotate("", xy=(rr_ * math.cos(arc[-1]), rr_ * math.sin(arc[-1])),
                xytext=(rr_ * math.cos(arc[-3]), rr_ * math.sin(arc[-3])),
                arrowprops=dict(arrowstyle="-|>", lw=0.6, color="k"))
    return fig, unit, label


def pressure_figure(ctx, c):
    fp = ctx.figures
    fig, ax = fp.new_figure(170, 60)
    fig.subplots_adjust(left=0.1, right=0.97, bottom=0.2, top=0.95)
    phi = np.asarray(c["phi"] + [360.0])
    th = np.asarray(c["pressure_angle"] + c["pressure_angle"][:1])
    for k, a, b in _phase_spans(c):
        if b > a:
            ax.axvspan(a, b, color=PHASE_COLORS[k], lw=0)
    ax.plot(phi, th, color="k")
    spans = {k: (a, b) for k, a, b in _phase_spans(c)}
    for k, col in (("rise", "tab:blue"), ("return", "tab:red")):
        a, b = spans[k]
        ax.plot([a, b], [c["pressure_angle_allowed"][k]] * 2, color=col, ls="--", lw=0.8)
    ax.set_xlim(0, 360)
    ax.set_ylim(0, max(c["pressure_angle_allowed"].values()) * 1.15)
    ax.set_xlabel(_loc(ctx.lang, "φ, deg"))
    ax.set_ylabel(_loc(ctx.lang, "θ, deg"))
    ax.grid(True, lw=0.3)
    # both axes at a standard scale, stated in the course's form (μθ, μφ)
    fp.std_graph(fig, [ax], ctx.t("kin.mm"), x_axis=ax)
    return fig


def build(ctx) -> str | None:
    c = (ctx.results or {}).get("cam")
    if not c:
        return None
    f, t = ctx.fmt, ctx.t
    rocker = c["follower"] == "rocker"
    knife = c["follower"] == "knife"
    if c["follower"] == "flat":
        return _build_flat(ctx, c)
    rows = [(t("cam.follower"), t("cam." + c["follower"])),
            (t("cam.rotation"), t("common.ccw") if c["rotation"] == "ccw" else t("common.cw")),
            (_loc(ctx.lang, t("cam.theta_allowed") + ", deg"),
             f"{f(c['pressure_angle_allowed']['rise'])} / {f(c['pressure_angle_allowed']['return'])}"),
            *_size_rows(ctx, c)]
    if rocker:
        rows += [(_loc(ctx.lang, t("cam.center_distance") + ", mm"), f(c["center_distance"] * MM, 6)),
                 (_loc(ctx.lang, t("cam.psi0") + ", deg"), f(c["psi0"], 5)),
                 (t("cam.swing"), t("cam.swing_" + c["swing"]))]
    else:
        rows.append((_loc(ctx.lang, t("cam.offset") + ", mm"), f(c["offset"] * MM, 6)))
    rows += [(_loc(ctx.lang, t("cam.theta_max") + ", deg"),
              f"{f(c['max_pressure_angle_rise'], 5)} / {f(c['max_pressure_angle_return'], 5)}"),
             (_loc(ctx.lang, t("cam.rho_min") + ", mm"), f(c["rho_min"] * MM, 6))]
    if not knife:
        rows.append((_loc(ctx.lang, t("cam.roller") + ", mm"),
                     Term(f"{f(c['roller'] * MM, 5)} "
                          f"({t('cam.roller_given') if c['roller_rule'] == 'given' else t('cam.roller_rule')})")))
    return _render(ctx, c, rows, t("cam.method") + (" " + t("cam.chosen_method") if c.get("r0_given") else ""))


def _size_rows(ctx, c):
    """Rows of the base radius: the exact least one, or the chosen one beside the least."""
    f, t = ctx.fmt, ctx.t
    if c.get("r0_given"):
        return [(_loc(ctx.lang, t("cam.r0_chosen") + ", mm"), f(c["r0"] * MM, 6)),
                (_loc(ctx.lang, t("cam.r0_min") + ", mm"), f(c["r0_min"] * MM, 6) if c["r0_min"] is not None else "—")]
    return [(_loc(ctx.lang, t("cam.r0") + ", mm"), f(c["r0"] * MM, 6)),
            (_loc(ctx.lang, t("cam.r0_design") + ", mm"), f(c["r0_design"] * MM, 6))]


def _build_flat(ctx, c):
    f, t = ctx.fmt, ctx.t
    rows = [(t("cam.follower"), t("cam.flat")),
            (t("cam.rotation"), t("common.ccw") if c["rotation"] == "ccw" else t("common.cw")),
            (_loc(ctx.lang, t("cam.rho_allowed") + ", mm"), f(c["rho_min_allowed"] * MM, 6))]
    if c.get("r0_given"):
        rows += [(_loc(ctx.lang, t("cam.r0_chosen") + ", mm"), f(c["r0"] * MM, 6)),
                 (_loc(ctx.lang, t("cam.r0_flat") + ", mm"), f(c["r0_min"] * MM, 6))]
    else:
        rows += [(_loc(ctx.lang, t("cam.r0_flat") + ", mm"), f(c["r0"] * MM, 6)),
                 (_loc(ctx.lang, t("cam.r0_design") + ", mm"), f(c["r0_design"] * MM, 6))]
    rows += [(_loc(ctx.lang, t("cam.rho_flat") + ", mm"), f(c["rho_min"] * MM, 6)),
             (_loc(ctx.lang, t("cam.face_width") + ", mm"), f(c["face_width"] * MM, 6)),
             (_loc(ctx.lang, t("cam.face_sym") + ", mm"), f(c["face_width_symmetric"] * MM, 6)),
             (_loc(ctx.lang, t("cam.theta_flat") + ", deg"), "0")]
    return _render(ctx, c, rows, t("cam.flat_method"))


def _render(ctx, c, rows, method):
    f, t = ctx.fmt, ctx.t
    flat = c["follower"] == "flat"
    (ks, us), (kv, uv), (ka, ua) = _units(c, ctx.lang)
    law_rows = []
    for k in ("rise", "return"):
        L = c["laws"][k]
        law_rows.append((t(f"cam.{k}"), _law_title(L, t),
                         f(c["phases"][k], 5), f(L["cv"], 5), f(L["ca"], 5) if L["ca"] is not None else "∞",
                         f(L["ds_max"] * kv, 5), f(L["d2s_max"] * ka, 5) if L["d2s_max"] is not None else "∞",
                         t("cam.impact_" + L["impact"])))
    law_header = [t("cam.phase"), t("cam.law"), t("cam.angle"), t("cam.cv"), t("cam.ca"),
                  f"max ds/dφ, {uv}", f"max d²s/dφ², {ua}", t("cam.impact")]
    table_rows = []
    for i in range(0, len(c["phi"]), 15):
        p = c["pitch_profile"][i]
        table_rows.append((f(c["phi"][i], 4), f(c["s"][i] * ks, 5), f(c["ds"][i] * kv, 5),
                           f(c["d2s"][i] * ka, 5), f(c["pressure_angle"][i], 4),
                           f(p[0] * MM, 5), f(p[1] * MM, 5)))
    table_header = [_loc(ctx.lang, h) for h in
                    ["φ, deg", f"s, {us}", f"ds/dφ, {uv}", f"d²s/dφ², {ua}", "θ, deg", "x, mm", "y, mm"]]
    fig, scales = diagrams_figure(ctx, c)
    figs = [(ctx.svg(fig, "cam-motion-law"), t("cam.diagrams_caption"))]
    if c.get("construction"):           # the s - ds/dphi construction (not for a flat follower)
        fig, unit, label = construction_figure(ctx, c)
        cap = t("cam.construction_caption")
        if c.get("r0_given"):
            cap += "; " + t("cam.construction_chosen")
        cap += "; " + t("cam.construction_scale", mu=f(unit, 4), label=label)
        figs.append((ctx.svg(fig, "cam-construction"), cap))
    pcap = {"flat": "cam.profile_flat_caption", "knife": "cam.profile_knife_caption"}.get(c["follower"],
                                                                                          "cam.profile_caption")
    fig, unit, label = profile_figure(ctx, c)
    from ..figures import scale_mark
    # μl in m/mm, as every other drawing of the report states it (unit: model mm per paper mm)
    from ...numfmt import localize
    scale = f"{scale_mark(ctx.lang)} {label}" + _loc(ctx.lang, f" (μl = {localize(f'{unit / 1000.0:g}', ctx.lang)} m/mm)")
    figs.append((ctx.svg(fig, "cam-profile"), t(pcap, scale=scale)))
    if not flat:
        figs.append((ctx.svg(pressure_figure(ctx, c), "cam-pressure-angle"), t("cam.pressure_caption")))
    div = c.get("division_table") or []
    div_rows = [(t(f"cam.{r['phase']}"), r["k"], f(r["phi"], 5), f(r["s"] * ks, 5), f(r["ds"] * kv, 5),
                 f(r["d2s"] * ka, 5), f(r["pressure_angle"], 4)) for r in div]
    div_header = [t("cam.phase"), "k"] + table_header[:5]
    n = sum(1 for r in div if r["phase"] == "rise") - 1
    from tmm_cli.cam.export import profile_csv_rows, profile_dxf
    header, prow = profile_csv_rows(c)
    files = [ctx.write_csv("cam_profile.csv", header, prow).name]
    mhead = ["phi_deg", "s", "ds_dphi", "d2s_dphi2", "pressure_angle_deg"]
    mrows = zip(c["phi"], c["s"], c["ds"], c["d2s"], c["pressure_angle"])
    if c.get("v"):
        mhead += ["v", "a"]
        mrows = zip(c["phi"], c["s"], c["ds"], c["d2s"], c["pressure_angle"], c["v"], c["a"])
    files.append(ctx.write_csv("cam_motion.csv", mhead, mrows).name)
    files.append(ctx.write_file("cam_profile.dxf", profile_dxf(c)).name)
    return ctx.render("sections/cam.html.j2", rows=rows, law_header=law_header, law_rows=law_rows,
                      table_header=table_header, table_rows=table_rows, figs=figs, scales=scales,
                      files=files, method=method, div_header=div_header, div_rows=div_rows,
                      div_caption=t("cam.division_caption", n=n), r0_note=_r0_note(ctx, c))


def _r0_note(ctx, c):
    """With r0 computed (not given): which radius the profile is drawn on -- the exact least
    one, not the rounded design radius printed beside it -- and the task line that builds the
    profile on the rounded one (r0: 45 mm; in ru and uk the Cyrillic "mm", as the task files take it too),
    or None."""
    from markupsafe import Markup, escape
    if c.get("r0_given") or c.get("r0_design") is None:
        return None
    whole = f"{float(c['r0_design']) * MM:.0f}"          # a whole millimetre: a task's YAML value as written
    text = ctx.t("cam.r0_drawn_on", r0=ctx.fmt(c["r0"] * MM, 6), r0d=whole, line="\u0000")
    a, _, b = text.partition("\u0000")
    # the line as the task file takes it, its unit as the language writes it (45 mm, or in Cyrillic)
    return Markup(f"{escape(a)}<code>{escape(str(_loc(ctx.lang, f'r0: {whole} mm')))}</code>{escape(b)}")
