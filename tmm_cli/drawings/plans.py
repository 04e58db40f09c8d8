"""A velocity or acceleration plan drawn at its scale with its title, μ and a 20 mm scale bar
(draw_plan): the report's plans figure and sheet 1 draw it."""
from __future__ import annotations

import numpy as np

COLORS = {"abs": "#000000", "rel": "#595959", "n": "#1f5fbf", "t": "#c0392b", "k": "#1e8449", "r": "#8e44ad"}
PLAN_MARGIN, PLAN_TOP, PLAN_BAR = 6.0, 11.0, 7.0     # mm: round a plan, its title lines, its scale bar


def plan_room(w: float, h: float) -> tuple[float, float]:
    """The room (mm) for a plan in a box w x h of draw_plan."""
    return w - 2 * PLAN_MARGIN, h - PLAN_TOP - PLAN_BAR - 2 * PLAN_MARGIN


def draw_plan(cv, plan, box, title, unit_txt, si_unit="m/s", mm="mm", note=None):
    """One plan inside box = (x0, y0, w, h) mm of the canvas `cv`.

    A plan the position cannot have (``plan.undefined``: a null velocity next to a change
    point) is its title and ``note`` (which quantities have no limit), wrapped to the box:
    no point, no segment, no scale.

    The plan's coordinates are millimetres at its scale mu (the segment table's
    lengths); the drawing is that plan reduced by a factor k <= 1 to fit the box, so
    that it stands at a standard scale mu / k (1, 2, 2.5, 4, 5 x 10^k), the one stated,
    with a 20 mm scale bar.  Returns k."""
    from ..report import figures as F
    x0, y0, w, h = box
    if plan.undefined:
        import textwrap
        cv.text(x0 + 1.5, y0 + h - 3.2, title, size=7, anchor="start", bold=True)
        per_line = max(12, int((w - 3.0) / (0.6 * cv.font_mm(6))))       # F.text_size's width a letter
        for i, line in enumerate(textwrap.wrap(note or ", ".join(plan.undefined), per_line)):
            cv.text(x0 + 1.5, y0 + h - 8.0 - 3.0 * i, line, size=6, anchor="start")
        return 1.0
    top = PLAN_TOP                      # title and scale lines
    bar_h = PLAN_BAR                    # the scale bar at the bottom
    pts = plan.pts
    xy = np.array(list(pts.values()))
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    span = np.maximum(hi - lo, 1e-9)
    room = plan_room(w, h)
    k = min(1.0, room[0] / span[0], room[1] / span[1])
    mu_drawn = F.nice_scale(plan.mu / k)      # reduced to fit: still at a standard μ, the one stated
    k = plan.mu / mu_drawn
    c = np.array([x0 + w / 2, y0 + bar_h + (h - top - bar_h) / 2]) - (lo + hi) / 2 * k

    # the plan's points on the paper at once (row by row c + p k), in plain floats
    names = list(pts)
    on_paper = c + xy * k
    mp = dict(zip(names, on_paper.tolist()))
    row = {name: i for i, name in enumerate(names)}
    segs = []
    vecs = plan.vecs
    if vecs:                 # the vectors' lengths on the paper (np.hypot of all at once, as one by one)
        d = on_paper[[row[v.end] for v in vecs]] - on_paper[[row[v.start] for v in vecs]]
        lengths = np.hypot(d[:, 0], d[:, 1]).tolist()
    for v, L in zip(vecs, lengths if vecs else ()):
        p, q = mp[v.start], mp[v.end]
        segs.append((p, q))
        if L < 0.15:
            continue
        if v.kind == "abs":
            cv.arrow(p, q, COLORS["abs"], 0.45, head=2.4, z=4)
        elif v.kind == "rel":
            cv.arrow(p, q, COLORS["rel"], 0.35, head=2.0, z=3)
        else:
            cv.arrow(p, q, COLORS[v.kind], 0.4, head=2.1, z=3,
                     dash="1.6 0.8" if v.kind in ("n", "k") else None)
    # labels: coincident points share one label
    groups: list[tuple[list, list[str], int]] = []
    # the points' distances to each other (np.hypot of the differences, as one by one)
    ex, ey = on_paper[:, 0], on_paper[:, 1]
    apart = np.hypot(ex[:, None] - ex, ey[:, None] - ey).tolist()
    for j, name in enumerate(names):
        for g in groups:
            if apart[g[2]][j] < 1.0:
                g[1].append(name)
                break
        else:
            groups.append((mp[name], [name], j))
    pole = c + np.zeros(2) * k
    # title, scale, scale bar first: the point labels keep clear of them
    taken = []

    def fixed(x, y, text, pt, **kw):
        cv.text(x, y, text, size=pt, **kw)
        tw, th = F.text_size(text, cv.font_mm(pt))
        taken.append((x, y - th / 2, x + tw, y + th / 2))

    fixed(x0 + 1.5, y0 + h - 3.2, title, 7, anchor="start", bold=True)
    cv.text(x0 + 1.5, y0 + h - 7.2, "μ", size=6.5, anchor="start", sub=plan.kind,
            after=f" = {mu_drawn:g} {unit_txt}")
    tw, th = F.text_size(f"μ{plan.kind} = {mu_drawn:g} {unit_txt}", cv.font_mm(6.5))
    taken.append((x0 + 1.5, y0 + h - 7.2 - th / 2, x0 + 1.5 + tw, y0 + h - 7.2 + th / 2))
    bar = 20.0                               # mm of the drawing, at the stated scale
    bx, by = x0 + 2.0, y0 + 2.5
    cv.polyline([(bx, by + 0.8), (bx, by), (bx + bar, by), (bx + bar, by + 0.8)], "#000", 0.3)
    fixed(bx + bar + 1.5, by + 0.3, f"{bar:g} {mm} = {float(f'{bar * mu_drawn:.6g}'):g} {si_unit}", 6,
          anchor="start")
    taken.append((bx, by - 0.5, bx + bar, by + 1.0))
    anchors, texts, sizes = [], [], []
    d = on_paper[[g[2] for g in groups]] - pole           # (the anchors' offsets from the pole)
    from_pole = np.hypot(d[:, 0], d[:, 1]).tolist()
    for (q, names, _), dq, r in zip(groups, d.tolist(), from_pole):
        anchors.append((q[0], q[1], tuple(dq) if r > 0.5 else (-1.0, -1.0)))
        texts.append(", ".join(sorted(names, key=lambda s: (s != plan.pole, s))))
        sizes.append(F.text_size(texts[-1], cv.font_mm(7)))
    pos = F.place_labels(anchors, 60.0, avoid=[g[0] for g in groups], step=2.6, segments=segs, sizes=sizes,
                         taken=taken, bounds=(x0 + 0.5, y0 + 0.5, x0 + w - 0.5, y0 + h - 0.5))
    for (q, names, _), text, (x, y) in zip(groups, texts, pos):
        aux = plan.pole not in names and min(names, key=lambda s: (s != plan.pole, s)).startswith(("n", "k"))
        cv.text(x, y, text, size=7, italic=True, color="#444" if aux else "#000", halo=True)
    cv.dot(pole, 0.6, z=6)
    return k
