"""Report section 'structure': Chebyshev's formula, the kinematic scheme at
position 0, links and pairs, Assur groups, structure formula, class.

Follows docs/methods.md §1 (Artobolevsky's classification)."""
from __future__ import annotations

import numpy as np

from ...plans import geometry

ROMAN = {1: "I", 2: "II", 3: "III", 4: "IV", 5: "V", 6: "VI"}
# the kind of an Assur group by its pairs in the letters of the kinematic pairs table: R and P
# as the language writes them (the words `struct.pair_letters`; Russian and Ukrainian write
# the revolute pair's letter of their own words)


def group_kind(typ, lang: str) -> str:
    """'RRP' in the report's language (the letters of `struct.pair_letters`); other kinds as given."""
    from ..i18n import translate
    s = str(typ)
    letters = translate("struct.pair_letters", lang)
    if letters == "RP" or len(letters) != 2 or not s or set(s) - set("RP"):
        return s
    return s.translate(str.maketrans("RP", letters))


def link_kind(geom, link) -> str:
    """crank | rocker | rod | slider | block | slotted (kulisa), by the pairs of the link: a
    slider on a moving link's guide is the block of a slotted link (the course's kamen' kulisy)."""
    if link.kind == "slider":
        on_moving = any(j.kind == "P" and link.index in (j.a, j.b) and 0 not in (j.a, j.b) for j in geom.joints)
        return "block" if on_moving else "slider"
    for j in geom.joints:
        if j.kind == "P" and link.index in (j.a, j.b):
            return "slotted"
    if link.index == geom.drive:
        return "crank"
    if any(p in geom.ground for p in link.points):
        return "rocker"
    return "rod"


def scheme_svg(ctx, geom, entries, entry, width_mm=150.0):
    from .. import figures as F
    lo, hi = F.mechanism_extent([entry])
    ranges = F.slider_ranges(entries, geom)
    for a, b in ranges.values():
        lo, hi = np.minimum(lo, np.minimum(a, b)), np.maximum(hi, np.maximum(a, b))
    view, unit, title = F.figure_for_box(lo, hi, width_mm, min_h=45.0, max_h=140.0, margin_mm=10.0,
                                         lang=ctx.lang)
    F.draw_mechanism(view, geom, entry, unit, ranges=ranges, taken=[title])
    return ctx.svg(view, "scheme")


def build(ctx) -> str | None:
    st = ctx.results.get("structure")
    if not st:
        return None
    geom = geometry(ctx.results)
    entries = ctx.results.get("kinematics") or []
    n, p5, p4 = st.get("n"), st.get("p5"), st.get("p4", 0)
    W = st.get("W")
    fig = None
    links_rows, pair_rows = [], []
    if geom is not None:
        if entries:
            e0 = next((e for e in entries if e.get("index") == 0), entries[0])
            fig = scheme_svg(ctx, geom, entries, e0)
        e0 = entries[0] if entries else None
        for l in geom.links:
            kind = link_kind(geom, l)
            length = None
            if e0 is not None and l.kind == "bar" and len(l.points) >= 2 and \
                    all(p in e0["points"] for p in l.points[:2]):
                a, b = (np.array([e0["points"][p]["x"], e0["points"][p]["y"]], float)
                        for p in l.points[:2])
                length = float(np.linalg.norm(b - a))
            links_rows.append((str(l.index), l.name, ctx.t(f"link.{kind}"),
                               ", ".join(l.points), ctx.fmt(length)))
        for j in geom.joints:
            name = j.point or "—"
            kind = ctx.t("struct.revolute") if j.kind == "R" else ctx.t("struct.prismatic")
            pair_rows.append((name, kind, f"{j.a}–{j.b}", "V"))
    names = ctx.link_names()
    idx = {nm: i + 1 for i, nm in enumerate(names)}
    group_rows = []
    drive = geom.drive if geom is not None else 1
    group_rows.append((ctx.t("struct.primary"), f"0, {drive}", "I", "—", "—"))
    for k, g in enumerate(st.get("groups") or [], start=1):
        lk = ", ".join(f"{idx.get(x, x)} ({x})" for x in g.get("links", []))
        group_rows.append((f"{ctx.t('struct.group')} {k}", lk,
                           ROMAN.get(g.get("class"), str(g.get("class"))),
                           str(g.get("order", "—")), group_kind(g.get("type", "—"), ctx.lang)))
    klass = st.get("class")
    formula = str(st.get("formula", "")).replace("->", "→")
    return ctx.render("sections/structure.html.j2", st=st, formula=formula, n=n, p5=p5, p4=p4, W=W,
                      fig=fig, links_rows=links_rows, pair_rows=pair_rows,
                      group_rows=group_rows, klass=ROMAN.get(klass, klass))
