"""Sheet 1 carries its own lengths: its plans are drawn at the sheet's μ (not the report's),
so the sheet has its own segment tables -- the velocity plans' segments of every position at
the one μv, each acceleration plan's at its μa, the μ stated above each table.

For every example task with a linkage, in en, ru and uk, the sheet's SVG is read as a
student reads the printed sheet, with a ruler: the tables' texts are read back from the
SVG (their title, the μ line, the header of positions, a row per segment), every arrow of
each plan is measured in the SVG (1 unit = 1 mm: the sheet is 841 mm wide), and

* every segment of the table of at least 1 mm is drawn in its plan at that length
  (±0.5 mm, from its start to the tip of its head);
* the table's μ is the one the plan states beside it;
* a segment from the pole (an absolute velocity or acceleration) times μ is the speed or
  the acceleration of its point in results.json, and a velocity plan's segment between two
  points times μv is the magnitude of the two points' velocity difference there (±0.05 mm
  of rounding, read at μ)."""
from __future__ import annotations

import html as html_mod
import math
import re
from pathlib import Path

import pytest

from test_plan_scales import _NUM, _num, _paths

ROOT = Path(__file__).resolve().parents[1]
# the linkages, given or synthesised (a synthesis task draws its mechanism's sheet 1 too)
LINKAGES = sorted(p.stem for p in (ROOT / "tasks").glob("*.yaml")
                  if re.search(r"^(mechanism|synthesis):", p.read_text(encoding="utf-8"), re.M))


def _texts(svg: str) -> list[tuple[float, float, str]]:
    """(x, y, plain text) of every text of the SVG (y down, as the SVG has it)."""
    out = []
    for x, y, body in re.findall(r'<text x="([\d.]+)" y="([\d.]+)"[^>]*>(.*?)</text>', svg, re.S):
        out.append((float(x), float(y), html_mod.unescape(re.sub(r"<[^>]+>", "", body))))
    return out


def _vectors_in(svg: str, box) -> list[float]:
    """The lengths (mm) of the arrows whose tip is inside box (x0, y0, x1, y1): a shaft from
    its start to the tip of the head whose base it reaches (tests/test_plan_scales.py)."""
    x0, y0, x1, y1 = box
    segs, heads = _paths(svg)
    out = []
    for col, tip, lft, rgt in heads:
        if not (x0 <= tip[0] <= x1 and y0 <= tip[1] <= y1):
            continue
        base = ((lft[0] + rgt[0]) / 2, (lft[1] + rgt[1]) / 2)
        hl = math.dist(tip, base)
        best = None
        for c, s, e in segs:
            if c == col and math.dist(e, base) <= 0.1 * hl + 0.03 and math.dist(s, tip) > math.dist(e, tip):
                L = math.dist(s, tip)
                best = L if best is None else min(best, L)
        if best is not None:
            out.append(best)
    return out


def _mu(texts, x, y) -> float:
    """The μ of the line 'μv = 0.02 ...' just under (x, y)."""
    for tx, ty, s in texts:
        if abs(tx - x) < 0.05 and 0 < ty - y < 6.5:
            m = re.match(rf"μ[va] = ({_NUM}) ", s)
            if m:
                return _num(m.group(1))
    raise AssertionError(f"no μ under {(x, y)}")


def _rows_below(texts, y_head, x_first, x_last, pitch_max=5.0):
    """The rows of a table under its header line y_head: {y: [(x, text)]} in its x range,
    row after row while they follow at most pitch_max apart."""
    ys = sorted({round(ty, 2) for tx, ty, s in texts if ty > y_head + 0.1 and x_first - 0.1 <= tx <= x_last + 0.1})
    rows, last = [], y_head
    for y in ys:
        if y - last > pitch_max:
            break
        rows.append(y)
        last = y
    return {y: sorted((tx, s) for tx, ty, s in texts if abs(ty - y) < 0.05 and x_first - 0.1 <= tx <= x_last + 0.1)
            for y in rows}


def read_tables(svg: str, lang: str):
    """The sheet's segment tables as printed: (velocity {position: {segment: mm}}, μv),
    [(the acceleration plan's title (x, y), {segment: mm}, μa)]."""
    from tmm_cli.sheets.segments import WORDS
    W = WORDS[lang]
    texts = _texts(svg)
    (xv, yv), = [(x, y) for x, y, s in texts if s == W["seg.velocity"] + ":"]
    mu_v = _mu(texts, xv, yv)
    head = [(x, y) for x, y, s in texts if s == W["seg.pos"] and y > yv]
    (xp, yp), = head
    cols = sorted((x, s) for x, y, s in texts if abs(y - yp) < 0.05 and x > xp)
    vel: dict[str, dict[str, float]] = {}
    for y, cells in _rows_below(texts, yp, xp, cols[-1][0]).items():
        seg = cells[0][1]
        for x, s in cells[1:]:
            col = min(cols, key=lambda c: abs(c[0] - x))
            assert abs(col[0] - x) < 0.05
            vel.setdefault(col[1].rstrip("*"), {})[seg] = _num(s)      # (an extra position: 13*)
    acc = []
    for xa, ya, s in texts:
        if s != W["seg.acceleration"]:
            continue
        mu_a = _mu(texts, xa, ya)
        (xm, ym), = [(x, y) for x, y, t in texts if t == W["seg.mm"] and 0 < y - ya < 15 and 0 < x - xa < 60]
        rows = {}
        for y, cells in _rows_below(texts, ym, xa, xm).items():
            (_, seg), (_, val) = cells
            rows[seg] = _num(val)
        acc.append(((xa, ya), rows, mu_a))
    return vel, mu_v, acc


def _plan_titles(texts, word: str) -> dict[str, tuple[float, float]]:
    """{position: (x, y)} of the plans titled 'word (position i)'."""
    out = {}
    for x, y, s in texts:
        m = re.fullmatch(rf"{re.escape(word)} \(\w+ (\d+)\*?\)", s)      # an extra: 13*
        if m:
            out[m.group(1)] = (x, y)
    return out


def _check_drawn(svg, box, rows: dict, where) -> int:
    drawn = _vectors_in(svg, box)
    n = 0
    for seg, L in rows.items():
        if L >= 1.0:
            assert any(abs(d - L) <= 0.5 for d in drawn), (where, seg, L, sorted(round(d, 1) for d in drawn))
            n += 1
    return n


def _point_of(label: str, entry: dict):
    from tmm_cli.plans import plan_label
    return next((p for p in entry["points"] if plan_label(p) == label), None)


@pytest.mark.parametrize("name", LINKAGES)
def test_sheet1_measures_what_its_tables_say(name, shared_once):
    # the results tmm run computes and every example's sheets, made once (tests/test_sheets.py)
    from pdf_extent import results
    from test_sheets import example_sheets

    from tmm_cli.sheets.sheet1 import TXT
    from tmm_cli.sheets.writers import to_svg
    _, res = results(shared_once, name)
    by_index = {str(e["index"]): e for e in res.get("kinematics") or []}
    for lang, sheets in example_sheets(name, shared_once).items():
        sheet = [cv for cv, info in sheets if info["number"] == 1]
        if not sheet:
            pytest.skip("no sheet 1")
        svg = to_svg(sheet[0])
        assert 'viewBox="0 0 841 594"' in svg and 'width="841mm"' in svg       # 1 unit = 1 mm
        texts = _texts(svg)
        vel, mu_v, acc = read_tables(svg, lang)
        # the velocity plans: a cell each, on a grid; the table has a column for each
        titles = _plan_titles(texts, TXT[lang]["vplan"])
        assert set(titles) == set(vel), (sorted(titles), sorted(vel))
        xs, ys = sorted({round(x, 2) for x, _ in titles.values()}), sorted({round(y, 2) for _, y in titles.values()})
        dx = min((b - a for a, b in zip(xs, xs[1:])), default=400.0)
        dy = min((b - a for a, b in zip(ys, ys[1:])), default=120.0)
        measured = 0
        for i, (x, y) in titles.items():
            assert _mu(texts, x, y) == mu_v          # the plan states the table's μv
            measured += _check_drawn(svg, (x - 1.5, y - 3.0, x - 1.5 + dx, y - 3.0 + dy), vel[i], (lang, "v", i))
            e = by_index[i]
            for seg, L in vel[i].items():
                q = _point_of(seg[1:], e) if seg.startswith("p") else None
                if q:                                   # from the pole: the point's speed
                    want = float(e["points"][q]["v"])
                else:
                    # a segment between two points' ends: |v_q - v_p|
                    pq = [(seg[:k], seg[k:]) for k in range(1, len(seg))]
                    pq = [(_point_of(s, e), _point_of(t, e)) for s, t in pq]
                    pq = [(s, t) for s, t in pq if s and t]
                    if not pq:
                        continue
                    s, t = (e["points"][q] for q in pq[0])
                    want = math.hypot(float(t["vx"]) - float(s["vx"]), float(t["vy"]) - float(s["vy"]))
                assert abs(L * mu_v - want) <= 0.051 * mu_v + 1e-6 * want, (lang, i, seg, L, mu_v, want)
        # the acceleration plans: their tables right of them
        atitles = _plan_titles(texts, TXT[lang]["aplan"])
        assert len(atitles) == len(acc) >= 1
        for (xa, ya), rows, mu_a in acc:
            i, (x, y) = max(((i, p) for i, p in atitles.items() if p[0] < xa), key=lambda t: t[1][0])
            assert _mu(texts, x, y) == mu_a
            measured += _check_drawn(svg, (x - 1.5, y - 3.0, xa - 0.5, y + 140.0), rows, (lang, "a", i))
            e = by_index[i]
            for seg, L in rows.items():
                q = _point_of(seg[1:], e) if seg.startswith("π") else None
                if q:
                    want = float(e["points"][q]["a"])
                    assert abs(L * mu_a - want) <= 0.051 * mu_a + 1e-6 * want, (lang, i, seg, L, mu_a, want)
        assert measured >= 3 * len(titles)


def test_the_reader_sees_a_wrong_length():
    """The check above fails on a table whose length is not the one drawn."""
    from tmm_cli.pipeline import run
    from tmm_cli.sheets import build_sheets
    from tmm_cli.sheets.writers import to_svg
    from tmm_cli.task import load_task
    task = load_task(ROOT / "tasks" / "crank_rocker_fourbar.yaml")
    res = run(task)
    cv, _ = build_sheets(res, task, "en")[0]
    svg = to_svg(cv)
    vel, mu_v, acc = read_tables(svg, "en")
    i = next(iter(vel))
    seg, L = max(vel[i].items(), key=lambda t: t[1])
    texts = _texts(svg)
    from tmm_cli.sheets.sheet1 import TXT
    x, y = _plan_titles(texts, TXT["en"]["vplan"])[i]
    box = (x - 1.5, y - 3.0, x + 100.0, y + 120.0)
    assert _check_drawn(svg, box, {seg: L}, "ok") == 1
    with pytest.raises(AssertionError):
        _check_drawn(svg, box, {seg: L * 1.05 + 0.6}, "wrong")
