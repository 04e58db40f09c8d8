"""One scale per drawing: what the report prints measures what its tables say.

For every example task with a linkage, in en, ru and uk, the report's HTML is read as a
student reads the page, with a ruler:

* each velocity / acceleration plan is measured in its SVG (1 unit = 1 mm: the figure's
  width in pt is its viewBox's in mm): every vector of the segment table of at least
  1 mm is drawn, from its start to the tip of its head, at the tabulated length
  (±0.5 mm); the table's values are its lengths times the μ the drawing states; the
  scale bar is 20 mm long and reads 20 μ;
* the scale factors table states the μv, μa of the drawn plans and the μl of the plan of
  positions, whose label M 1:k is that μl; the link lengths on the drawing are l / μl;
* the worked section's μv, μa are the plans', its lever's μv the lever drawing's.

In the PDF (poppler's pdftotext -bbox) the two scale bars' legends of a plan figure
stand as far apart as in the SVG: the figure is printed at 100 %.

The plans were once drawn at a quarter of the tabulated length (drawn at μ = 0.04,
tabulated at 0.01) and the plan of positions labelled M 1:15 beside μl = 0.004."""
from __future__ import annotations

import html as html_mod
import math
import re
from pathlib import Path

import pytest

from pdf_extent import report_out

ROOT = Path(__file__).resolve().parents[1]
LINKAGES = sorted(p.stem for p in (ROOT / "tasks").glob("*.yaml")
                  if re.search(r"^mechanism:", p.read_text(encoding="utf-8"), re.M))
MM = 72 / 25.4

_NUM = r"[−-]?\d+(?:[.,]\d+)?"


def _num(s: str) -> float:
    return float(s.replace("−", "-").replace(",", ".").replace("\u202f", "").replace("\xa0", ""))


# ---------------------------------------------------------------- the SVG measured
def _paths(svg: str):
    """(stroke segments [(colour, (x0, y0), (x1, y1))], filled triangles [(colour, tip, l, r)])."""
    segs, heads = [], []
    for d, fill, stroke in re.findall(r'<path d="([^"]+)" fill="([^"]+)" stroke="([^"]+)"', svg):
        if fill == "none":
            for a, b, c, e in re.findall(rf"M({_NUM}) ({_NUM}) L({_NUM}) ({_NUM})(?= M|$)", d):
                segs.append((stroke, (float(a), float(b)), (float(c), float(e))))
        else:
            for t in re.findall(r"M([^Z]+)Z", d):
                xy = [float(v) for v in re.findall(_NUM, t)]
                if len(xy) == 6:
                    heads.append((fill, (xy[0], xy[1]), (xy[2], xy[3]), (xy[4], xy[5])))
    return segs, heads


def _vectors(svg: str, x0: float, x1: float) -> list[float]:
    """The lengths (mm) of the arrows between x0 and x1: a shaft from its start to the tip
    of the head whose base it reaches."""
    segs, heads = _paths(svg)
    out = []
    for col, tip, lft, rgt in heads:
        if not x0 <= tip[0] <= x1:
            continue
        base = ((lft[0] + rgt[0]) / 2, (lft[1] + rgt[1]) / 2)
        hl = math.dist(tip, base)
        best = None
        for c, s, e in segs:
            if c != col:
                continue
            # the shaft ends a tenth of the head's length inside it, on the tip's line
            if math.dist(e, base) <= 0.1 * hl + 0.03 and math.dist(s, tip) > math.dist(e, tip):
                L = math.dist(s, tip)
                best = L if best is None else min(best, L)
        if best is not None:
            out.append(best)
    return out


def _stated_mu(svg: str, x0: float, x1: float) -> tuple[float, float, float]:
    """(μ of the title line, the bar's legend 'B mm = V unit' as (B, V)) of the plan in x0..x1."""
    mu = bar = None
    for x, body in re.findall(r'<text x="([\d.]+)"[^>]*>(.*?)</text>', svg):
        if not x0 <= float(x) <= x1:
            continue
        text = html_mod.unescape(re.sub(r"<[^>]+>", "", body))
        m = re.match(rf"μ[va] = ({_NUM}) ", text)
        if m:
            mu = _num(m.group(1))
        m = re.match(rf"({_NUM}) \S+ = ({_NUM}) ", text)
        if m:
            bar = (_num(m.group(1)), _num(m.group(2)))
    assert mu is not None and bar is not None
    return mu, bar[0], bar[1]


def _bar_length(svg: str, x0: float, x1: float) -> float:
    segs, _ = _paths(svg)
    for d in re.findall(r'<path d="(M[^"]+)" fill="none" stroke="#000000" stroke-width="0.3"', svg):
        pts = [(float(a), float(b)) for a, b in re.findall(rf"[ML]({_NUM}) ({_NUM})", d)]
        for k in range(0, len(pts) - 3, 4):          # ⊔-shaped: up, along, down
            a, b, c, e = pts[k:k + 4]
            if x0 <= a[0] <= x1 and abs(b[1] - c[1]) < 1e-6:
                return abs(c[0] - b[0])
    raise AssertionError("no scale bar")


def _tables(block: str) -> list[list[tuple[str, float, str]]]:
    """The segment tables of a position: [(segment, length mm, value text)] each."""
    out = []
    for body in re.findall(r"<tbody>(.*?)</tbody>", block, re.S):
        rows = []
        for tr in re.findall(r"<tr>(.*?)</tr>", body, re.S):
            cells = [html_mod.unescape(re.sub(r"<[^>]+>", "", c)) for c in re.findall(r"<td[^>]*>(.*?)</td>", tr, re.S)]
            rows.append((cells[1], _num(cells[2]), cells[3]))
        out.append(rows)
    return out


def _value(text: str) -> float | None:
    t = text.replace("−", "-").replace(",", ".").replace("·10", "e").replace(" ", "")
    sup = str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789")
    try:
        return float(t.translate(sup))
    except ValueError:
        return None


def _section(html: str, anchor: str) -> str:
    i = html.index(f'id="{anchor}"')
    return html[i:html.index("</section>", i)]


def check_plans(html: str) -> tuple[float, float]:
    """Every plan of the kinematics section measured against its tables; returns the
    (μv, μa) they are drawn at (one for every position)."""
    kin = _section(html, "kinematics")
    blocks = re.findall(r'<div class="position">(.*?)</div>\s*</div>\s*</div>', kin, re.S)
    assert blocks
    mus = set()
    for block in blocks:
        svg = re.search(r"<svg.*?</svg>", block, re.S).group(0)
        w_pt = float(re.search(r'width="([\d.]+)pt"', svg).group(1))
        vb = [float(v) for v in re.search(r'viewBox="([^"]+)"', svg).group(1).split()]
        assert abs(w_pt / MM - vb[2]) < 0.1, "the figure is not drawn at 1 unit = 1 mm"
        half = vb[2] / 2
        tables = _tables(block)
        assert len(tables) == 2
        stated = []
        for (x0, x1), rows in zip(((0, half), (half, vb[2])), tables):
            mu, bar_mm, bar_val = _stated_mu(svg, x0, x1)
            stated.append(mu)
            assert abs(_bar_length(svg, x0, x1) - bar_mm) < 0.05
            assert math.isclose(bar_val, bar_mm * mu, rel_tol=1e-6), (bar_mm, bar_val, mu)
            drawn = _vectors(svg, x0, x1)
            for seg, L, val in rows:
                v = _value(val)
                if v is not None and L >= 1.0:
                    # the table's value is its length at the drawing's μ (the length rounded to 0.1 mm)
                    assert abs(abs(v) - L * mu) <= 0.051 * mu + 1e-3 * abs(v), (seg, L, val, mu)
                if L >= 1.0:
                    assert any(abs(d - L) <= 0.5 for d in drawn), (seg, L, sorted(round(d, 1) for d in drawn))
        mus.add(tuple(stated))
    assert len(mus) == 1, f"the plans of the positions are drawn at different scales: {mus}"
    return mus.pop()


def check_scale_table(html: str, mu_v: float, mu_a: float) -> None:
    kin = _section(html, "kinematics")
    i = kin.index("μ<sub>l</sub>")
    rows = re.findall(r"<tr><th>(.*?)</th><td>(.*?)</td></tr>", kin[i - 200:i + 3000], re.S)[:3]
    mu_l = _num(re.match(_NUM, re.sub(r"<[^>]+>", "", rows[0][1])).group(0))
    assert _num(re.findall(rf"≈ ({_NUM})", rows[1][1])[0]) == mu_v
    assert _num(re.findall(rf"≈ ({_NUM})", rows[2][1])[0]) == mu_a
    # the plan of positions: its μl and M 1:k, the table's μl
    svg = re.search(r"<svg.*?</svg>", kin, re.S).group(0)
    title = html_mod.unescape(re.sub(r"<[^>]+>", "", re.search(r"<text[^>]*>(μ(?:l|<tspan[^>]*>l).*?)</text>",
                                                                svg).group(1)))
    m = re.search(rf"= ({_NUM}) .*\(\w (\d+(?:[.,]\d+)?):(\d+(?:[.,]\d+)?)\)", title)
    assert m, title
    drawn = _num(m.group(1))
    assert drawn == mu_l, (title, mu_l)
    assert math.isclose(drawn * 1000, _num(m.group(3)) / _num(m.group(2)), rel_tol=1e-9), title
    # the link lengths on the drawing
    j = kin.find("<caption>", i)
    body = re.search(r"<tbody>(.*?)</tbody>", kin[j:], re.S).group(1)
    for tr in re.findall(r"<tr>(.*?)</tr>", body, re.S):
        cells = [re.sub(r"<[^>]+>", "", c) for c in re.findall(r"<td[^>]*>(.*?)</td>", tr, re.S)]
        assert abs(_num(cells[1]) / mu_l - _num(cells[2])) <= 0.051 + 5e-4 * _num(cells[2]), cells


def check_worked(html: str, mu_v: float, mu_a: float) -> None:
    if 'id="worked"' not in html:
        return
    sec = _section(html, "worked")
    tagged = dict(re.findall(r'<span class="mn" data-k="([^"]+)">([^<]*)</span>', sec))
    if "mu_v" in tagged:
        assert _num(tagged["mu_v"]) == mu_v and _num(tagged["mu_a"]) == mu_a
    if "mu_lev" in tagged:
        n = int(tagged["pos"])
        stated = None
        for blk in re.findall(r'<div class="position">(.*?)</div>', _section(html, "kinetostatics"), re.S):
            head = re.sub(r"<[^>]+>", "", blk.split("</h4>")[0])
            if int(re.search(r"\d+", head).group(0)) == n:          # the worked position's lever
                txt = html_mod.unescape(re.sub(r"<[^>]+>", "", re.findall(r"<svg.*?</svg>", blk, re.S)[-1]))
                stated = _num(re.search(rf"μv = ({_NUM})", txt).group(1))
                break
        assert stated is not None and _num(tagged["mu_lev"]) == stated


@pytest.mark.parametrize("lang", ["en", "ru", "uk"])
@pytest.mark.parametrize("name", LINKAGES)
def test_drawings_measure_what_their_tables_say(shared_once, name, lang):
    # `tmm run --format html,pdf --lang <lang>`'s folder, made once per session (tests/test_pdf_extent.py
    # measures the same report's PDF)
    out = report_out(shared_once, name, lang)
    html = (out / "report.html").read_text(encoding="utf-8")
    if 'id="kinematics"' not in html:
        pytest.skip("no kinematics")
    mu_v, mu_a = check_plans(html)
    check_scale_table(html, mu_v, mu_a)
    check_worked(html, mu_v, mu_a)


@pytest.mark.parametrize("name", ["forging_sixbar", "shaper_slotted_lever"])
def test_pdf_prints_the_plans_at_full_size(shared_once, name):
    """The scale bars' legends of a plans figure: as far apart on the PDF page as in the
    SVG (86 mm), so the printed figure measures what its table says."""
    import shutil
    import subprocess
    if not shutil.which("pdftotext"):
        pytest.skip("poppler's pdftotext not installed")
    out = report_out(shared_once, name, "en")
    html = (out / "report.html").read_text(encoding="utf-8")
    kin = _section(html, "kinematics")
    svg = re.search(r'<div class="position">.*?(<svg.*?</svg>)', kin, re.S).group(1)
    xs = [float(x) for x, body in re.findall(r'<text x="([\d.]+)"[^>]*>(.*?)</text>', svg)
          if re.match(rf"{_NUM} mm = ", body)]
    assert len(xs) == 2
    want = abs(xs[1] - xs[0])
    bbox = subprocess.run(["pdftotext", "-bbox", str(out / "report.pdf"), "-"], capture_output=True,
                          text=True, check=True).stdout
    pages = re.findall(r"<page [^>]*>(.*?)</page>", bbox, re.S)
    seen = 0
    for p in pages:
        words = re.findall(r'<word xMin="([\d.]+)" yMin="([\d.]+)" xMax="[\d.]+" yMax="[\d.]+">(.*?)</word>', p)
        # a legend: "20" followed by "mm" and "=" on one line
        starts = [float(x) for k, (x, y, w) in enumerate(words[:-2])
                  if w == "20" and words[k + 1][2] == "mm" and words[k + 2][2] == "="
                  and abs(float(words[k + 1][1]) - float(y)) < 1]
        if len(starts) == 2 and "plan" in p.lower():
            got = abs(starts[1] - starts[0]) / MM
            assert abs(got - want) <= 0.5, (got, want)
            seen += 1
    assert seen >= 12


WITH_FLYWHEEL = sorted(p.stem for p in (ROOT / "tasks").glob("*.yaml")
                       if re.search(r"^flywheel:", p.read_text(encoding="utf-8"), re.M))


@pytest.mark.parametrize("name", WITH_FLYWHEEL)
def test_the_energy_mass_diagram_is_drawn_at_its_scale(shared_once, name):
    """The energy-mass (Wittenbauer) diagram's axes are in millimetres of the drawing: a tick
    label's value is its distance in mm on the page (both axes; it was stretched to its figure,
    23 mm a 20-mm step), and the segment kl is as long as the caption says, so J = kl mu_T /
    (omega_m^2 delta) can be measured with a ruler."""
    out = report_out(shared_once, name, "en")
    svg_path = out / "figures" / "energy-mass.svg"
    if not svg_path.exists():
        pytest.skip("no energy-mass diagram (another flywheel method)")
    svg = svg_path.read_text(encoding="utf-8")
    w_pt, vb_w = float(re.search(r'width="([\d.]+)pt"', svg).group(1)), float(re.search(r'viewBox="0 0 ([\d.]+)', svg).group(1))
    assert w_pt / MM == pytest.approx(vb_w, abs=0.05)                      # one unit a millimetre
    ticks = [(float(x), float(y), _num(v)) for x, y, v in
             re.findall(r'<text x="([\d.]+)" y="([\d.]+)" font-size="[\d.]+" text-anchor="(?:middle|end)">(' + _NUM + r')</text>', svg)]
    for axis in (0, 1):                    # x: the labels along one y; y: along one x
        other = 1 - axis
        line = [t for t in ticks if abs(t[other] - ticks[0 if axis == 0 else -1][other]) < 1e-6]
        assert len(line) >= 3, (axis, ticks)
        for a, b in zip(line, line[1:]):
            step = abs(b[axis] - a[axis])
            assert step == pytest.approx(abs(b[2] - a[2]), abs=0.02), (axis, a, b)
    k = re.search(r'<path d="M([\d.]+) ([\d.]+)L([\d.]+) ([\d.]+)" fill="none" stroke="#1e8449"', svg)
    drawn = abs(float(k.group(4)) - float(k.group(2)))
    page = html_mod.unescape((out / "report.html").read_text(encoding="utf-8"))
    said = _num(re.search(r"kl = (" + _NUM + ") mm", page).group(1))
    assert drawn == pytest.approx(said, abs=0.06)


@pytest.mark.parametrize("lang,middle", [("en", "the midpoint"), ("ru", "\u0441\u0435\u0440\u0435\u0434\u0438\u043d\u0430 \u0437\u0432\u0435\u043d\u0430")])
def test_the_input_table_says_a_default_centre_of_mass(shared_once, lang, middle):
    """The report's table of links gives each centre of mass, the defaults too (a blank read as
    the middle of the crank while the crank's S is its pivot): the crank's pivot O, a bar's
    midpoint, a slider's pin (the press's links give no `com`)."""
    page = html_mod.unescape((report_out(shared_once, "press_offset_slider_crank", lang) / "report.html")
                             .read_text(encoding="utf-8"))
    rows = {m.group(1): m.group(2) for m in re.finditer(
        r'<tr><td class="num">\d+</td><td>(\w+)</td><td>[^<]*</td>(?:<td[^>]*>[^<]*</td>){3}<td>([^<]*)</td>',
        page)}
    assert rows["crank"] == "O" and rows["rod"] == middle and rows["ram"] == "B", rows
