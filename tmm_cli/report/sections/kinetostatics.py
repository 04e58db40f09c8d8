"""Report section 'kinetostatics' (METHODS 3): conventions, the load diagrams with the
positions marked, per position the free-body diagram of every Assur group and of the
crank with loads and reactions to scale (mu_F), their force polygons and Zhukovsky's
lever (velocity plan turned by 90 deg) with the forces at the ends of the turned
velocities and their arms; tables of loads, reactions, balancing moment by the three
methods, efficiency; M_b and the reactions over the cycle. Writes
``kinetostatics.csv`` beside the report. Reads numbers only from results.
"""
from __future__ import annotations

import math

import numpy as np

I18N = {
    "en": {"kst.title": "Kinetostatics", "kst.convention": "Sign convention",
           "kst.conv_text": "R_ij is the force exerted by link i on link j (i < j; R_ji = −R_ij); "
                            "moments and couples are counter-clockwise positive. The balancing moment M_b is the "
                            "couple the drive applies to the balance link to keep the prescribed motion; "
                            "P_b = M_b / l is the balancing force at the end of its arm l. A prismatic pair's "
                            "normal force N acts along the guide normal (the guide direction turned +90°) at the "
                            "distance x = M/N from the slider's pin.",
           "kst.balance": "Balance link", "kst.arm": "arm l, m", "kst.singular": "Singular positions",
           "kst.singular_none": "none: the equilibrium equations are regular over the whole turn",
           "kst.singular_text": "crank angles where the equations are singular for this balance link (deg)",
           "kst.diagrams": "Load diagrams", "kst.mb_table": "Balancing moment by three methods",
           "kst.position": "Pos.", "kst.mb": "M_b (groups), N·m", "kst.zh": "M_b (Zhukovsky), N·m",
           "kst.vp": "M_b (virtual power), N·m", "kst.mx": "M_b (matrix), N·m",
           "kst.pb": "P_b, N", "kst.disc": "Δ, %", "kst.eff": "η", "kst.near": "near singular",
           "kst.fb": "P_b (groups), N", "kst.fzh": "P_b (Zhukovsky), N", "kst.fvp": "P_b (virtual power), N",
           "kst.fmx": "P_b (matrix), N",
           "kst.reactions": "Reactions in the pairs, N", "kst.cycle": "Balancing moment and reactions over the cycle",
           "kst.position_n": "Position {i}, φ = {phi:.2f}°", "kst.loads": "Loads",
           "kst.name": "Load", "kst.kind": "kind", "kst.fbd_caption": "Free-body diagrams of the groups "
           "(solved from the last group to the crank), force polygons (scale μF = {mu} N/mm) and "
           "Zhukovsky's lever on the velocity plan turned by 90° (μv = {mv} (m/s)/mm).",
           "kst.lever": "Zhukovsky lever", "kst.polygon": "force polygon", "kst.group": "group",
           "kst.crank": "crank", "kst.pair": "pair", "kst.prismatic": "N, N; x = M/N, m",
           "kst.csv_note": "All numbers: kinetostatics.csv.", "kst.rotation": "crank rotation from position 0, deg",
           "kst.null": "— : singular to working precision (no finite value).",
           "kst.s_axis": "s/H", "kst.phi_axis": "φ from position 0, deg", "kst.force_axis": "F, N",
           "kst.moment_axis": "M, N·m", "kst.efficiency": "Instantaneous efficiency η = 1 − P_f / P_d",
           "kst.pf": "P_f, W", "kst.pd": "P_d, W"},
    "ru": {"kst.title": "Кинетостатика", "kst.convention": "Правило знаков",
           "kst.conv_text": "R_ij — сила, с которой звено i действует на звено j (i < j; R_ji = −R_ij); "
                            "моменты и пары сил положительны против часовой стрелки. Уравновешивающий момент M_b — "
                            "пара, которую привод прикладывает к звену приведения для обеспечения заданного "
                            "движения; P_b = M_b / l — уравновешивающая сила на конце плеча l. Нормальная сила N "
                            "поступательной пары направлена по нормали к направляющей (направление направляющей, "
                            "повёрнутое на +90°) и приложена на расстоянии x = M/N от шарнира ползуна.",
           "kst.balance": "Звено приведения", "kst.arm": "плечо l, м", "kst.singular": "Особые положения",
           "kst.singular_none": "нет: уравнения равновесия невырождены на всём обороте",
           "kst.singular_text": "углы кривошипа, при которых уравнения вырождены для этого звена (град)",
           "kst.diagrams": "Диаграммы нагрузок", "kst.mb_table": "Уравновешивающий момент тремя методами",
           "kst.position": "Пол.", "kst.mb": "M_b (по группам), Н·м", "kst.zh": "M_b (Жуковский), Н·м",
           "kst.vp": "M_b (мощности), Н·м", "kst.mx": "M_b (матрица), Н·м",
           "kst.pb": "P_b, Н", "kst.disc": "Δ, %", "kst.eff": "η", "kst.near": "вблизи особого",
           "kst.fb": "P_b (по группам), Н", "kst.fzh": "P_b (Жуковский), Н", "kst.fvp": "P_b (мощности), Н",
           "kst.fmx": "P_b (матрица), Н",
           "kst.reactions": "Реакции в кинематических парах, Н",
           "kst.cycle": "Уравновешивающий момент и реакции за цикл",
           "kst.position_n": "Положение {i}, φ = {phi:.2f}°", "kst.loads": "Нагрузки",
           "kst.name": "Нагрузка", "kst.kind": "вид", "kst.fbd_caption": "Группы Ассура с нагрузками и "
           "реакциями (расчёт от последней группы к кривошипу), планы сил (масштаб μF = {mu} Н/мм) и "
           "рычаг Жуковского на повёрнутом на 90° плане скоростей (μv = {mv} м/(с·мм)).",
           "kst.lever": "Рычаг Жуковского", "kst.polygon": "план сил", "kst.group": "группа",
           "kst.crank": "кривошип", "kst.pair": "пара", "kst.prismatic": "N, Н; x = M/N, м",
           "kst.csv_note": "Все числа: kinetostatics.csv.", "kst.rotation": "поворот кривошипа от положения 0, град",
           "kst.null": "— : вырождено с рабочей точностью (конечного значения нет).",
           "kst.s_axis": "s/H", "kst.phi_axis": "φ от положения 0, град", "kst.force_axis": "F, Н",
           "kst.moment_axis": "M, Н·м", "kst.efficiency": "Мгновенный КПД η = 1 − P_тр / P_дв",
           "kst.pf": "P_тр, Вт", "kst.pd": "P_дв, Вт"},
}

KIND_COLOR = {"resistance": "#c0392b", "driving": "#1e8449", "load": "#8e44ad", "gravity": "#7f8c8d",
              "inertia": "#1f5fbf", "friction": "#d68910", "reaction": "k"}
MAX_FIG_POSITIONS = 12       # free-body figures for at most this many positions (time, size)


def _xy(d):
    return np.array([float(d["x"]), float(d["y"])])


def _links(results):
    st = results.get("structure") or {}
    return {l["name"]: l for l in st.get("links") or []}


def _draw_links(ax, kin_e, links, names, lw=1.6):
    pts = kin_e["points"]
    for n in names:
        lk = links.get(n)
        if lk is None:
            continue
        ps = [p for p in lk["points"] if p in pts]
        if lk["kind"] == "slider":
            if ps:
                c = _xy(pts[ps[0]])
                ax.plot([c[0]], [c[1]], "s", ms=9, mfc="white", mec="k", zorder=4)
            continue
        xy = np.array([_xy(pts[p]) for p in ps])
        if len(xy) >= 3:
            ax.fill(xy[:, 0], xy[:, 1], fc="0.92", ec="k", lw=lw, zorder=2)
        elif len(xy) == 2:
            ax.plot(xy[:, 0], xy[:, 1], "k-", lw=lw, zorder=2)
        for p in xy:
            ax.plot([p[0]], [p[1]], "o", ms=3.5, mfc="white", mec="k", zorder=5)


def _group_forces(e, info, group_idx: set[int], links_by_index):
    """Forces on a group: its loads and the reactions of the bodies outside it."""
    out = []
    for f in e.get("loads", []):
        li = links_by_index.get(f["link"])
        if li in group_idx:
            out.append((f["name"], np.array(f["point"]), np.array(f["F"]), f["kind"]))
    for j in info["joints"]:
        a, b = j["a"], j["b"]
        if (a in group_idx) == (b in group_idx):
            continue
        r = e["reactions"][j["key"]]
        if r.get("x") is None:
            continue
        F = np.array([r["x"], r["y"]])
        pt = r.get("point") or r.get("pin")
        if b in group_idx:
            out.append((f"R{a}{b}", np.array(pt), F, "reaction"))
        else:
            out.append((f"R{b}{a}", np.array(pt), -F, "reaction"))
    return out


def _fig_position(ctx, e, kin_e, info, links, mu_v):
    """One axes in paper millimetres: row 1 the free-body diagrams (groups from the last
    to the crank) with the forces at mu_F, row 2 their force polygons, right the lever."""
    from .. import figures
    plt = figures.plt()
    index_by_name = {n: l["index"] for n, l in links.items()}
    groups = [list(g) for g in info["groups"]]
    order = list(reversed(groups[:-1])) + [groups[-1]]
    ncol = len(order) + 1
    W, H = 180.0, 100.0
    cw, rh = W / ncol, H / 2
    fig = plt.figure(figsize=(W * figures.MM, H * figures.MM))
    ax = fig.add_axes([0, 0, 1, 1])
    ax.set_xlim(0, W)
    ax.set_ylim(0, H)
    ax.set_aspect("equal")
    ax.set_axis_off()
    allF = [np.linalg.norm(f["F"]) for f in e.get("loads", [])]
    allF += [r["R"] for r in e["reactions"].values() if r.get("R") is not None]
    Fmax = max(allF + [1e-9])
    mu_F = figures.nice_scale(Fmax / 16.0)          # N per mm: the largest force <= 16 mm

    def arrow(p, q, kind, label):
        col = KIND_COLOR.get(kind, "k")
        figures.arrow(ax, p, q, color=col, lw=0.7, head=4)
        ax.text(q[0], q[1], label, fontsize=5, color=col)

    for c, g in enumerate(order):
        gi = {index_by_name[n] for n in g}
        forces = _group_forces(e, info, gi, index_by_name)
        pts = np.array([_xy(kin_e["points"][p]) for n in g for p in links[n]["points"] if p in kin_e["points"]])
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        span = np.maximum(hi - lo, 1e-6)
        k = min((cw - 22) / span[0], (rh - 22) / span[1])      # mm per metre, room for arrows
        centre = np.array([c * cw + cw / 2, rh + rh / 2 - 2])

        def m(p):
            return centre + (np.asarray(p, float) - (lo + hi) / 2) * k
        for n in g:
            lk = links[n]
            ps = [m(_xy(kin_e["points"][p])) for p in lk["points"] if p in kin_e["points"]]
            if lk["kind"] == "slider":
                if ps:
                    figures.draw_block(ax, ps[0], float(kin_e["links"][n]["angle"] or 0.0), 7, 4, lw=0.8)
                continue
            xy = np.array(ps)
            if len(xy) >= 3:
                ax.fill(xy[:, 0], xy[:, 1], fc="0.92", ec="k", lw=1.0, zorder=2)
            elif len(xy) == 2:
                ax.plot(xy[:, 0], xy[:, 1], "k-", lw=1.2, zorder=2)
            for p in xy:
                ax.plot([p[0]], [p[1]], "o", ms=2.5, mfc="white", mec="k", zorder=5)
        for name, p, F, kind in forces:
            p0 = m(p)
            arrow(p0, p0 + F / mu_F, kind, name)
        title = (ctx.t("kst.crank") if c == len(order) - 1 else ctx.t("kst.group")) + " " + \
            ",".join(str(index_by_name[n]) for n in g)
        ax.text(c * cw + 2, H - 4, title, fontsize=6.5)
        # force polygon: head to tail, closes to zero
        vecs = [F for _, _, F, _ in forces]
        tips = np.cumsum([np.zeros(2)] + vecs, axis=0)
        plo, phi_ = tips.min(axis=0), tips.max(axis=0)
        mu_p = figures.nice_scale(max(float(np.max(phi_ - plo)), 1e-9) / (min(cw, rh) - 14))
        pc = np.array([c * cw + cw / 2, rh / 2]) - (plo + phi_) / 2 / mu_p
        for (name, _, F, kind), a, b in zip(forces, tips[:-1], tips[1:]):
            arrow(pc + a / mu_p, pc + b / mu_p, kind, name)
        ax.text(c * cw + 2, rh - 4, f"{ctx.t('kst.polygon')}, μF = {mu_p:g} N/mm", fontsize=5.5)
    # Zhukovsky lever: velocity plan turned by +90 deg, forces at the ends of rot90(v)
    x0 = (ncol - 1) * cw
    ends, items = [np.zeros(2)], []
    for f in e.get("loads", []):
        v = np.array(f["v"])
        F = np.array(f["F"])
        if np.linalg.norm(F) == 0:
            continue
        end = np.array([-v[1], v[0]]) / mu_v
        items.append((f, end, F))
        ends.append(end)
    E = np.array(ends)
    elo, ehi = E.min(axis=0), E.max(axis=0)
    sc = min(1.0, (cw - 16) / max(ehi[0] - elo[0], 1e-9), (H - 30) / max(ehi[1] - elo[1], 1e-9))
    pole = np.array([x0 + cw / 2, H / 2]) - (elo + ehi) / 2 * sc
    for f, end, F in items:
        col = KIND_COLOR.get(f["kind"], "k")
        q = pole + end * sc
        ax.plot([pole[0], q[0]], [pole[1], q[1]], color="0.7", lw=0.5)
        nF = F / np.linalg.norm(F)
        foot = q - nF * float(np.dot(q - pole, nF))           # arm h: pole to the line of action
        ax.plot([pole[0], foot[0]], [pole[1], foot[1]], ls=":", color=col, lw=0.5)
        arrow(q, q + F / mu_F, f["kind"], f["name"])
    ax.plot([pole[0]], [pole[1]], "ko", ms=2.5)
    ax.text(pole[0] + 1, pole[1] + 1, "p", fontsize=6)
    ax.text(x0 + 2, H - 4, ctx.t("kst.lever"), fontsize=6.5)
    return ctx.svg(fig), mu_F


def _diagrams_fig(ctx, info, entries, grid_n):
    from .. import figures
    ld = [d for d in info.get("load_diagrams", []) if d.get("type") == "force" and d.get("curve")]
    if not ld:
        return None
    fig, axes = figures.new_figure(170, 55 * len(ld), nrows=len(ld), squeeze=False)
    for ax, d in zip(axes[:, 0], ld):
        cur = d["curve"]
        ax.plot(cur["x"], cur["value"], "k-", lw=1.0)
        xs, ys, labels = [], [], []
        for e in entries:
            dd = e.get("diagram", {}).get(d["name"])
            if not dd or dd.get("x") is None or not dd.get("active", True):
                continue
            xs.append(dd["x"])
            val = dd.get("value")
            # the diagram value (magnitude for a stroke load, signed for a phi-diagram)
            ys.append(abs(val) if d["abscissa"] == "s" and d["kind"] in ("resistance", "driving") else val)
            labels.append(str(e["index"]))
        ax.plot(xs, ys, "o", ms=3.5, color="#c0392b")
        for x, y, l in zip(xs, ys, labels):
            ax.annotate(l, (x, y), fontsize=6, xytext=(2, 3), textcoords="offset points")
        ax.set_xlabel(ctx.t("kst.s_axis") if d["abscissa"] == "s" else ctx.t("kst.phi_axis"))
        ax.set_ylabel(ctx.t("kst.force_axis"))
        ax.set_title(f"{d['name']}: {d['link']} ({d['kind']}, {d['stroke']})", fontsize=8)
        ax.grid(True, lw=0.3)
    fig.tight_layout()
    return ctx.svg(fig)


def _cycle_fig(ctx, entries, phi0, sign, info):
    from .. import figures
    rows = []
    for e in entries:
        q = ((e["phi"] - phi0) * sign) % 360.0
        rows.append((q, e))
    rows.sort(key=lambda r: r[0])
    if len(rows) < 2:
        return None
    key = "balancing_moment" if info["balance_kind"] == "moment" else "balancing_force"
    fig, (a1, a2) = figures.new_figure(170, 110, nrows=2, sharex=True)
    q = [r[0] for r in rows]
    a1.plot(q, [np.nan if r[1][key] is None else r[1][key] for r in rows], "k.-")
    a1.set_ylabel(ctx.t("kst.moment_axis") if key == "balancing_moment" else ctx.t("kst.force_axis"))
    a1.grid(True, lw=0.3)
    a1.set_title("M_b" if key == "balancing_moment" else "P_b", fontsize=8)
    for j in info["joints"]:
        vals = [np.nan if r[1]["reactions"][j["key"]]["R"] is None else r[1]["reactions"][j["key"]]["R"]
                for r in rows]
        a2.plot(q, vals, ".-", label=j["key"], lw=0.8)
    a2.legend(ncol=6, fontsize=6)
    a2.set_ylabel("|R|, N")
    a2.set_xlabel(ctx.t("kst.rotation"))
    a2.grid(True, lw=0.3)
    fig.tight_layout()
    return ctx.svg(fig)


def build(ctx) -> str | None:
    entries = ctx.results.get("kinetostatics")
    info = ctx.results.get("kinetostatics_info")
    if not entries or not info:
        return None
    fmt = ctx.fmt
    links = _links(ctx.results)
    kin = {k["index"]: k for k in ctx.results.get("kinematics") or []}
    pos = ctx.results.get("positions") or {}
    phi0 = float(pos.get("phi0") or 0.0)
    sign = 1.0 if pos.get("direction", "ccw") == "ccw" else -1.0
    force_bal = info["balance_kind"] == "force"
    # balancing moment table
    if force_bal:
        hdr = [ctx.t("kst.position"), "φ, °", ctx.t("kst.fb"), ctx.t("kst.fzh"), ctx.t("kst.fvp"),
               ctx.t("kst.fmx"), ctx.t("kst.disc"), ctx.t("kst.eff"), ctx.t("kst.near")]
        keys = ("balancing_force", "zhukovsky_force", "virtual_power_force", "matrix_force")
    else:
        hdr = [ctx.t("kst.position"), "φ, °", ctx.t("kst.mb"), ctx.t("kst.zh"), ctx.t("kst.vp"), ctx.t("kst.mx"),
               ctx.t("kst.pb"), ctx.t("kst.disc"), ctx.t("kst.eff"), ctx.t("kst.near")]
        keys = ("balancing_moment", "zhukovsky_moment", "virtual_power_moment", "matrix_moment", "balancing_force")
    mb_rows = []
    csv_rows = []
    for e in entries:
        disc = None if e.get("discrepancy") is None else 100.0 * e["discrepancy"]
        mb_rows.append([e["index"], ctx.fmt_fixed(e["phi"], 2)] + [fmt(e.get(k), 6) for k in keys]
                       + [fmt(disc, 2), fmt(e.get("efficiency"), 4), "✓" if e.get("near_singular") else ""])
        row = [e["index"], e["phi"]] + [e.get(k) for k in keys] + [e.get("discrepancy"), e.get("efficiency")]
        for j in info["joints"]:
            r = e["reactions"][j["key"]]
            row += [r.get("x"), r.get("y"), r.get("R")]
        csv_rows.append(row)
    csv_hdr = ["index", "phi"] + list(keys) + ["discrepancy", "efficiency"]
    for j in info["joints"]:
        csv_hdr += [f"{j['key']}_x", f"{j['key']}_y", f"{j['key']}_R"]
    ctx.write_csv("kinetostatics.csv", csv_hdr, csv_rows)
    # reactions table
    r_hdr = [ctx.t("kst.position")] + [j["key"] for j in info["joints"]]
    r_rows = []
    for e in entries:
        row = [e["index"]]
        for j in info["joints"]:
            r = e["reactions"][j["key"]]
            if j["kind"] == "P":
                off = r.get("offset")
                row.append(f"{fmt(r.get('N'), 5)}; x = {fmt(off, 4)}" if r.get("N") is not None else "—")
            else:
                row.append(fmt(r.get("R"), 5))
        r_rows.append(row)
    # friction table
    eff_rows = None
    if any(e.get("friction_power") is not None for e in entries):
        eff_rows = [[e["index"], ctx.fmt_fixed(e["phi"], 2), fmt(e.get("friction_power"), 5),
                     fmt(e.get("driving_power"), 5), fmt(e.get("efficiency"), 4)] for e in entries]
    # per position figures and load tables
    positions = []
    vmax = 0.0
    for e in entries:
        for f in e.get("loads", []):
            vmax = max(vmax, math.hypot(*f["v"]))
    from .. import figures
    mu_v = figures.nice_scale(vmax / 50.0) if vmax > 0 else 1.0
    for e in entries[:MAX_FIG_POSITIONS]:
        if "loads" not in e or e["index"] not in kin:
            continue
        if e.get("balancing_moment") is None and e.get("balancing_force") is None:
            fig, mu_F = None, None
        else:
            fig, mu_F = _fig_position(ctx, e, kin[e["index"]], info, links, mu_v)
        lrows = [[f["name"], f["link"], f["kind"], fmt(f["F"][0], 5), fmt(f["F"][1], 5),
                  fmt(math.hypot(*f["F"]), 5), ""] for f in e["loads"]]
        lrows += [[c["name"], c["link"], c["kind"], "", "", "", fmt(c["M"], 5)] for c in e.get("couples", [])]
        positions.append({"index": e["index"], "phi": e["phi"], "fig": fig, "mu_F": mu_F, "rows": lrows,
                          "caption": ctx.t("kst.fbd_caption", mu=f"{mu_F:g}" if mu_F else "—", mv=f"{mu_v:g}")})
    sing = ctx.results.get("singular") or []
    return ctx.render("sections/kinetostatics.html.j2", info=info, mb_hdr=hdr, mb_rows=mb_rows,
                      r_hdr=r_hdr, r_rows=r_rows, eff_rows=eff_rows, positions=positions,
                      fig_diagrams=_diagrams_fig(ctx, info, entries, len(entries)),
                      fig_cycle=_cycle_fig(ctx, entries, phi0, sign, info),
                      singular=", ".join(ctx.fmt_fixed(s, 6) for s in sing))
