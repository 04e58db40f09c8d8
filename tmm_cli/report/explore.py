"""The explorable mechanism of report.html: a crank-angle slider with play/pause that
moves the linkage through the turn and redraws the mechanism, its velocity and
acceleration plans and a table of v, a, omega, epsilon for the angle shown.

With kinetostatics, also the force polygon of each Assur group (loads first, then the
reactions of the removed links, as the report's drawings: sections/kinetostatics.py
``group_forces``) and Zhukovsky's lever (the velocity plan turned by +90 deg, each load
at the end of its point's turned velocity, P_b at the crank pin), and in the table the
reactions |R_ij| and the balancing moment M_b (or force P_b) by the groups and by the
lever.  Those numbers come from the kinetostatics stage's ``analyze_task`` (the
pipeline's own call) at the same fine grid.

HTML only: ``inject(ctx, html)`` adds the widget (templates ``explore.html.j2`` and
``explore.js``, the data as JSON in a ``<script type="application/json">``) to the
HTML text written to report.html; the PDF is made from the HTML without it.  The
data come from the stage function ``tmm_cli.linkage.kinematics.explore.explore_grid``."""
from __future__ import annotations

import json

import numpy as np

from .context import templates_dir

I18N = {
    "en": {"explore.title": "The mechanism in motion", "explore.play": "Play", "explore.pause": "Pause",
           "explore.angle": "Crank turn from position 0", "explore.mech": "Mechanism",
           "explore.vplan": "Velocity plan", "explore.aplan": "Acceleration plan",
           "explore.point": "Point", "explore.link": "Link", "explore.pos": "position",
           "explore.v": "v, m/s", "explore.a": "a, m/s²", "explore.w": "ω, 1/s", "explore.e": "ε, 1/s²",
           "explore.polygon": "Force polygon", "explore.group": "group", "explore.crank": "input link",
           "explore.lever": "Zhukovsky lever", "explore.pair": "Pair", "explore.R": "|R|, N",
           "explore.mb": "M_b, N·m", "explore.pb": "P_b, N", "explore.by_groups": "by the groups",
           "explore.by_lever": "by the lever",
           "explore.hint": "Drag the slider (the marks are the course positions: the slider snaps to them "
                           "within 3°) or press Play. Values at the angle shown."},
    "ru": {"explore.title": "Механизм в движении", "explore.play": "Пуск", "explore.pause": "Пауза",
           "explore.angle": "Поворот кривошипа от положения 0", "explore.mech": "Механизм",
           "explore.vplan": "План скоростей", "explore.aplan": "План ускорений",
           "explore.point": "Точка", "explore.link": "Звено", "explore.pos": "положение",
           "explore.v": "v, м/с", "explore.a": "a, м/с²", "explore.w": "ω, 1/с", "explore.e": "ε, 1/с²",
           "explore.polygon": "План сил", "explore.group": "группа", "explore.crank": "входное звено",
           "explore.lever": "Рычаг Жуковского", "explore.pair": "Пара", "explore.R": "|R|, Н",
           "explore.mb": "M_b, Н·м", "explore.pb": "P_b, Н", "explore.by_groups": "по группам",
           "explore.by_lever": "по рычагу",
           "explore.hint": "Передвиньте ползунок (метки — положения проекта: ползунок притягивается к ним "
                           "в пределах 3°) или нажмите «Пуск». Значения для показанного угла."},
    "uk": {"explore.title": "Механізм у русі", "explore.play": "Пуск", "explore.pause": "Пауза",
           "explore.angle": "Поворот кривошипа від положення 0", "explore.mech": "Механізм",
           "explore.vplan": "План швидкостей", "explore.aplan": "План прискорень",
           "explore.point": "Точка", "explore.link": "Ланка", "explore.pos": "положення",
           "explore.v": "v, м/с", "explore.a": "a, м/с²", "explore.w": "ω, 1/с", "explore.e": "ε, 1/с²",
           "explore.polygon": "План сил", "explore.group": "група", "explore.crank": "вхідна ланка",
           "explore.lever": "Важіль Жуковського", "explore.pair": "Пара", "explore.R": "|R|, Н",
           "explore.mb": "M_b, Н·м", "explore.pb": "P_b, Н", "explore.by_groups": "за групами",
           "explore.by_lever": "за важелем",
           "explore.hint": "Пересуньте повзунок (позначки — положення проєкту: повзунок притягується до них "
                           "у межах 3°) або натисніть «Пуск». Значення для показаного кута."},
}


def data_json(data: dict) -> str:
    """JSON safe inside <script>: no '<', '>' or '&' at all (written as \\u003c ...), so
    user text (point and link names) can neither end the element nor open a tag."""
    s = json.dumps(data, separators=(",", ":"), ensure_ascii=True, allow_nan=False)
    return s.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


def _vec_rows(items: dict, digits: int) -> list:
    """name -> (kind, [F (2,) | None per row]) -> [{name, kind, x, y}] (rounded)."""
    from ..linkage.kinematics.explore import round_sig
    out = []
    for name, (kind, sym, col) in items.items():
        arr = np.array([[np.nan, np.nan] if F is None else F for F in col], float)
        out.append({"name": name, "sym": sym[0], "sub": sym[1], "kind": kind,
                    "x": round_sig(arr[:, 0], digits), "y": round_sig(arr[:, 1], digits)})
    return out


def forces_grid(task, results: dict, phi, lang: str = "en") -> dict | None:
    """The kinetostatics of the task at the crank angles ``phi`` (deg) for the widget:
    per Assur group (from the last attached to the input link) the vectors of its force
    polygon, the loads for Zhukovsky's lever (force and the velocity of its point), the
    reactions and the balancing moment (force).  None without kinetostatics."""
    if getattr(task, "kinetostatics", None) is None or not results.get("kinetostatics") \
            or getattr(task, "mechanism", None) is None:
        return None
    from ..linkage import kinematics, kinetostatics, structure
    from ..linkage.drive_speed import with_speed
    from ..linkage.kinematics.explore import round_sig
    from ..linkage.mechanism import build_mechanism
    from ..pipeline import find_positions
    from .sections.kinetostatics import group_forces, label_parts
    omega1 = float(results["drive"]["omega"])
    task = with_speed(task, omega1)
    mech = build_mechanism(task)
    st = structure.analyze(mech)
    positions = find_positions(task, mech)
    dyn = None
    if task.kinetostatics.motion is True and task.flywheel is not None:
        from ..linkage import dynamics
        dyn = dynamics.analyze_task(mech, task, positions, accuracy=False)
    phi = np.asarray(phi, float)
    kin = kinematics.solve(mech, phi, omega1)
    res = kinetostatics.analyze_task(mech, st, task, positions, phi, kin, dyn=dyn,
                                     singular=results.get("singular"))
    d = res.to_dict(detail=True)
    entries = d["entries"]
    N = len(entries)
    index_by_name = {lk.name: lk.index for lk in mech.links}
    groups = [list(g) for g in d["groups"]]
    order = list(reversed(groups[:-1])) + [groups[-1]]
    force_bal = d["balance_kind"] == "force"
    bjoint = None
    if force_bal:
        bi = index_by_name[d["balance"]]
        bjoint = next(k for k, j in enumerate(mech.joints) if j.kind == "P" and j.slider == bi)
    out_groups = []
    for k, g in enumerate(order):
        gi = {index_by_name[n] for n in g}
        items: dict = {}
        for i, e in enumerate(entries):
            fs = group_forces(e, d, gi, index_by_name)
            if force_bal and d["balance"] in g and e.get("balancing_force") is not None:
                fs.append(("P\u0000b", None, float(e["balancing_force"]) * res.geo.jdir[bjoint][i], "balance"))
            for name, _, F, kind in fs:
                if name not in items:
                    items[name] = (kind, label_parts(name, lang), [None] * N)
                items[name][2][i] = F
        # the polygon's order: loads, then reactions (as the report's drawings)
        items = dict(sorted(items.items(), key=lambda t: t[1][0] == "reaction"))
        last = k == len(order) - 1
        out_groups.append({"links": [index_by_name[n] for n in g], "crank": last,
                           "vecs": _vec_rows(items, 5)})
    lever = {}
    for i, e in enumerate(entries):
        for f in e.get("loads", []):
            if f["name"] not in lever:
                lever[f["name"]] = (f["kind"], label_parts(f["name"], lang), [None] * N, [None] * N)
            lever[f["name"]][2][i] = f["F"]
            lever[f["name"]][3][i] = f["v"]
    lev = []
    for name, (kind, sym, F, v) in lever.items():
        row = _vec_rows({name: (kind, sym, F)}, 5)[0]
        vv = np.array([[np.nan, np.nan] if x is None else x for x in v], float)
        row["vx"], row["vy"] = round_sig(vv[:, 0], 5), round_sig(vv[:, 1], 5)
        lev.append(row)
    key = "balancing_force" if force_bal else "balancing_moment"
    zkey = "zhukovsky_force" if force_bal else "zhukovsky_moment"
    reactions = []
    for j in d["joints"]:
        R = [e["reactions"][j["key"]]["R"] for e in entries]
        reactions.append({"key": j["key"], "sym": label_parts(j["key"], lang)[0],
                          "sub": label_parts(j["key"], lang)[1],
                          "R": round_sig([np.nan if r is None else r for r in R])})
    pin = None
    drive = mech.link(mech.drive)
    if not force_bal and d["balance"] == drive.name:
        pin = mech.crank_pin
    return {"kind": "force" if force_bal else "moment", "balance": d["balance"], "pin": pin,
            "omega1": omega1, "groups": out_groups, "lever": lev, "reactions": reactions,
            "Mb": round_sig([np.nan if e[key] is None else e[key] for e in entries]),
            "Mzh": round_sig([np.nan if e[zkey] is None else e[zkey] for e in entries])}


def fragment(ctx) -> str | None:
    from ..linkage.kinematics.explore import explore_grid
    if ctx.task is None or not ctx.results.get("kinematics"):
        return None
    try:
        data = explore_grid(ctx.task, ctx.results)
    except Exception:          # the static report stays whole if the dense grid cannot be made
        return None
    if not data:
        return None
    try:
        forces = forces_grid(ctx.task, ctx.results, data["phi"], ctx.lang)
    except Exception:          # the kinematics stay shown if the forces cannot be made
        forces = None
    if forces:
        from .sections.kinetostatics import KIND_COLOR
        data["forces"] = forces
        data["colors"] = KIND_COLOR
    tr = I18N.get(ctx.lang, I18N["en"])
    from markupsafe import Markup
    js = (templates_dir() / "explore.js").read_text(encoding="utf-8")
    return ctx.render("explore.html.j2", tr=tr, data=Markup(data_json(data)),
                      labels=Markup(data_json(tr)), forces=forces, js=Markup(js.replace("</", "<\\/")))


def inject(ctx, html: str) -> str:
    """The HTML with the widget before the kinematics section (else before </body>)."""
    frag = fragment(ctx)
    if not frag:
        return html
    at = html.find('<section class="section" id="kinematics"')
    if at < 0:
        at = html.rfind("</body>")
    if at < 0:
        return html + frag
    return html[:at] + frag + html[at:]
