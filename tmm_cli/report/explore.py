"""The explorable mechanism of report.html: a crank-angle slider with play/pause that
moves the linkage through the turn and redraws the mechanism, its velocity and
acceleration plans and a table of v, a, omega, epsilon for the angle shown.

With kinetostatics, also the force polygon of each Assur group (loads first, then the
reactions of the removed links, as the report's drawings: sections/kinetostatics.py
``group_forces``) and Zhukovsky's lever (the velocity plan turned by +90 deg, each load
at the end of its point's turned velocity, P_b at the crank pin), and in the table the
reactions |R_ij| and the balancing moment M_b (or force P_b) by the groups and by the
lever.  Those numbers are the results' ``kinetostatics_explore``: the kinetostatics
stage's ``analyze_at`` (the stage at other crank angles) at the same fine grid, made by the
pipeline for the HTML report only.

HTML only: ``inject(ctx, html)`` adds the widget (templates ``explore.html.j2`` and
``explore.js``, the data as JSON in a ``<script type="application/json">``) to the
HTML text written to report.html; the PDF is made from the HTML without it.  The
data are the results' ``kinematics_explore`` (made by the pipeline with the stage
function ``tmm_cli.linkage.kinematics.explore.explore_grid``)."""
from __future__ import annotations

import math

import numpy as np

from .. import locales
from ..results import one_line
from ..tables import round_sig
from .context import templates_dir

I18N = locales.table("explore", "text")


def data_json(data: dict) -> str:
    """JSON safe inside <script>: no '<', '>' or '&' at all (written as \\u003c ...), so
    user text (point and link names) can neither end the element nor open a tag."""
    s = one_line(data)
    return s.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


def _vec_rows(items: dict, digits: int) -> list:
    """name -> (kind, (symbol, subscript), [(x, y) | None per row]) -> [{name, sym, sub, kind, x, y}]."""
    return [{"name": name, "sym": sym[0], "sub": sym[1], "kind": kind,
             "x": round_sig(_column(col, 0), digits), "y": round_sig(_column(col, 1), digits)}
            for name, (kind, sym, col) in items.items()]


def _column(col, j: int) -> list[float]:
    """Coordinate j of each vector of col (None: no vector) as a float, NaN where there is
    none (what a float array of them holds: a None coordinate is NaN too)."""
    nan = math.nan
    try:
        return [nan if F is None else float(F[j]) for F in col]
    except TypeError:
        return [nan if F is None or F[j] is None else float(F[j]) for F in col]


def _negated(F) -> tuple[float, float]:
    """-F of a vector (x, y) as floats (a None coordinate: NaN)."""
    return tuple(math.nan if c is None else -float(c) for c in F[:2])


def forces_grid(results: dict, lang: str = "en") -> dict | None:
    """The widget's forces from the results' ``kinetostatics_explore`` (the kinetostatics
    stage at the fine grid, made by the pipeline for the HTML report): per Assur group
    (from the last attached to the input link) the vectors of its force polygon, the
    loads for Zhukovsky's lever (force and the velocity of its point), the reactions and
    the balancing moment (force).  None without them."""
    d = results.get("kinetostatics_explore")
    st = results.get("structure") or {}
    if not d or not d.get("entries") or not st.get("links"):
        return None
    from ..drawings.forces import group_force_data, label_parts
    entries = d["entries"]
    N = len(entries)
    links = {l["name"]: l for l in st["links"]}
    index_by_name = {n: l["index"] for n, l in links.items()}
    groups = [list(g) for g in d["groups"]]
    order = list(reversed(groups[:-1])) + [groups[-1]]
    force_bal = d["balance_kind"] == "force"
    guide = None
    if force_bal:               # a balancing force along a fixed guide (its direction is constant)
        g = links[d["balance"]].get("guide") or {}
        if g.get("link") is None and g.get("angle") is not None:
            a = np.radians(float(g["angle"]))
            guide = np.array([np.cos(a), np.sin(a)])
    out_groups = []
    for k, g in enumerate(order):
        gi = {index_by_name[n] for n in g}
        items: dict = {}
        for i, e in enumerate(entries):
            fs = group_force_data(e, d, gi, index_by_name)
            if guide is not None and d["balance"] in g and e.get("balancing_force") is not None:
                fs.append(("P\u0000b", None, float(e["balancing_force"]) * guide, False, "balance"))
            for name, _, F, flip, kind in fs:
                if name not in items:
                    items[name] = (kind, label_parts(name, lang), [None] * N)
                items[name][2][i] = _negated(F) if flip else F
        # the polygon's order: loads, then reactions (as the report's drawings)
        items = dict(sorted(items.items(), key=lambda t: t[1][0] == "reaction"))
        out_groups.append({"links": [index_by_name[n] for n in g], "crank": k == len(order) - 1,
                           "vecs": _vec_rows(items, 5)})
    lever: dict = {}
    for i, e in enumerate(entries):
        for f in e.get("loads", []):
            if f["name"] not in lever:
                lever[f["name"]] = (f["kind"], label_parts(f["name"], lang), [None] * N, [None] * N)
            lever[f["name"]][2][i] = f["F"]
            lever[f["name"]][3][i] = f["v"]
    lev = []
    for name, (kind, sym, F, v) in lever.items():
        row = _vec_rows({name: (kind, sym, F)}, 5)[0]
        row["vx"], row["vy"] = round_sig(_column(v, 0), 5), round_sig(_column(v, 1), 5)
        lev.append(row)
    key = "balancing_force" if force_bal else "balancing_moment"
    zkey = "zhukovsky_force" if force_bal else "zhukovsky_moment"
    reactions = []
    for j in d["joints"]:
        sym, sub = label_parts(j["key"], lang)
        reactions.append({"key": j["key"], "sym": sym, "sub": sub,
                          "R": round_sig([e["reactions"][j["key"]]["R"] for e in entries])})
    pin = None
    drive = links.get(st.get("drive_link"))
    ground = set(st.get("ground") or {})
    if not force_bal and drive is not None and d["balance"] == drive["name"]:
        pin = next((p for p in drive["points"] if p not in ground), None)
    return {"kind": "force" if force_bal else "moment", "balance": d["balance"], "pin": pin,
            "omega1": float(results["drive"]["omega"]), "groups": out_groups, "lever": lev,
            "reactions": reactions, "Mb": round_sig([e[key] for e in entries]),
            "Mzh": round_sig([e[zkey] for e in entries])}


def fragment(ctx) -> str | None:
    from markupsafe import Markup
    data = ctx.results.get("kinematics_explore")
    if not data:                # no linkage, or results made without the fine grid
        return None
    forces = forces_grid(ctx.results, ctx.lang)
    fdata = None
    if forces:                  # a script element of its own: ex-data is the results' grid as it is
        from ..drawings.forces import KIND_COLOR
        fdata = Markup(data_json({**forces, "colors": KIND_COLOR}))
    tr = I18N.get(ctx.lang, I18N["en"])
    # the instant centres: the worked position's figure's notes and colour (sections/worked.py)
    from ..numfmt import comma_langs
    from .sections.worked import CENTRE_COLOR, CENTRE_ROOM
    labels = {**tr, **{k: ctx.t(k) for k in ("worked.centres_inf", "worked.centres_far")},
              "centre_color": CENTRE_COLOR, "centre_room": CENTRE_ROOM,
              # the numbers as the report's tables write them: the decimal comma in ru and uk
              "decimal": "," if ctx.lang in comma_langs() else "."}
    js = (templates_dir() / "explore.js").read_text(encoding="utf-8")
    return ctx.render("explore.html.j2", tr=tr, data=Markup(data_json(data)),
                      labels=Markup(data_json(labels)), forces=forces, fdata=fdata, js=Markup(js.replace("</", "<\\/")),
                      centres=bool(data.get("centres")))


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
