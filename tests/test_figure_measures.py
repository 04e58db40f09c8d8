"""The report's scale drawings measure what its tables say, read back from the SVG files
beside the report (figures/*.svg) and the tables of report.html:

- the mesh of a gear pair: each grey circle of the drawing (circles fitted to the points of
  its path) is about one of the two wheel centres, the centres are a_w apart, and the five
  radii about each centre are the table's r_f, r_b, r, r_w, r_a at the scale stated under the
  drawing; the pitch and base radii are also the closed forms m z / 2 and m z / 2 cos 20°;
- the profile of a cam with a knife-edge translating follower: every (x, y) of the table of
  the profile lies on the drawn profile at the stated scale μl, and the drawing's radius in
  the direction of that point is the closed form sqrt(e² + (s0 + s)²), s0 = sqrt(r0² - e²),
  of the table's s, (exact) r0 and e."""
from __future__ import annotations

import html as html_mod
import math
import re
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]


def _report(name: str, out: Path) -> Path:
    import tmm_cli
    from tmm_cli.report import render
    task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
    render(tmm_cli.run(task), task, out, {"html"}, "en")
    return out


def _num(s: str) -> float:
    return float(html_mod.unescape(s).replace("\u2212", "-").strip())


def _row(html: str, label: str) -> list[float]:
    """The numbers of the table row whose first cell contains ``label`` (as written in the HTML)."""
    m = re.search(r"<tr><td>[^<]*" + re.escape(label) + r"</td>(.*?)</tr>", html)
    assert m, label
    return [_num(v) for v in re.findall(r'<td class="num">([^<]*)</td>', m.group(1))]


def _th(html: str, label: str) -> float:
    """The number of the two-column table row headed by a cell ending in ``label``."""
    m = re.search(r"<tr><th>[^<]*" + re.escape(label) + r"</th><td>([^<]*)</td>", html)
    assert m, label
    return _num(m.group(1))


def _paths(svg: str, **attrs) -> list[np.ndarray]:
    """The points (mm, y down) of the <path> elements with the given attribute values."""
    out = []
    for el in re.findall(r"<path [^>]*>", svg):
        if all(f'{k.replace("_", "-")}="{v}"' in el for k, v in attrs.items()):
            d = re.search(r'd="([^"]*)"', el).group(1)
            out.append(np.array([[float(a), float(b)] for a, b in
                                 re.findall(r"[ML](-?[\d.]+) (-?[\d.]+)", d)]))
    return out


def _circle_fit(P: np.ndarray) -> tuple[float, float, float]:
    """Least-squares circle through the points (Kasa): centre x, centre y, radius."""
    A = np.column_stack([2 * P[:, 0], 2 * P[:, 1], np.ones(len(P))])
    b = (P ** 2).sum(axis=1)
    cx, cy, c = np.linalg.lstsq(A, b, rcond=None)[0]
    return float(cx), float(cy), float(math.sqrt(c + cx * cx + cy * cy))


@pytest.mark.parametrize("name", ["gears_shifted", "gears_zero"])
def test_gear_mesh_circles_are_the_tables_radii(name, tmp_path):
    out = _report(name, tmp_path)
    html = (out / "report.html").read_text(encoding="utf-8")
    svg = (out / "figures" / "gear-mesh.svg").read_text(encoding="utf-8")
    scale = re.search(r"scale (\d+(?:\.\d+)?):(\d+(?:\.\d+)?)<", svg)
    k = float(scale.group(1)) / float(scale.group(2))          # paper mm per real mm
    circles = [_circle_fit(P) for P in _paths(svg, stroke="#666666") if len(P) >= 5]
    assert len(circles) == 10
    # the two centres: wheel 1 below (y down: the larger y), a_w apart
    lo_y = min(c[1] for c in circles)
    top = [c[1] for c in circles if c[1] < lo_y + 1.0]
    low = [c[1] for c in circles if c[1] >= lo_y + 1.0]
    assert len(top) == len(low) == 5
    ys = [float(np.mean(top)), float(np.mean(low))]
    aw = _th(html, "a<sub>w</sub>, mm")
    assert (ys[1] - ys[0]) / k == pytest.approx(aw, abs=0.02)
    import tmm_cli
    task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
    m_mm = float(task.gears.m) * 1000.0
    z = [int(v) for v in task.gears.z]
    table = {key: _row(html, label) for key, label in
             (("rf", "r<sub>f</sub>, mm"), ("rb", "r<sub>b</sub>, mm"), ("r", "pitch radius, r, mm"),
              ("rw", "r<sub>w</sub>, mm"), ("ra", "r<sub>a</sub>, mm"))}
    for i, yc in enumerate((ys[1], ys[0])):
        mine = sorted(c for c in circles if abs(c[1] - yc) < 0.5)
        assert len(mine) == 5
        for cx, cy, _ in mine:                  # concentric, on the axis of the drawing
            assert cx == pytest.approx(mine[0][0], abs=0.02) and cy == pytest.approx(mine[0][1], abs=0.02)
        radii = sorted(c[2] / k for c in mine)
        want = sorted(table[key][i] for key in table)
        assert radii == pytest.approx(want, abs=0.02 / k + 1e-4 * max(want))
        # the pitch and base circles: the closed forms
        r = m_mm * z[i] / 2
        assert table["r"][i] == pytest.approx(r, rel=1e-5)
        assert table["rb"][i] == pytest.approx(r * math.cos(math.radians(20.0)), rel=1e-5)
        assert min(abs(R - r) for R in radii) < 0.02 / k + 1e-4 * r


def test_few_teeth_pair_fills_its_axes(tmp_path):
    """z = 5 and 8 (m = 4 mm): the whole pair is drawn at a standard scale large enough that its
    tip circles span most of the axes (it was 1:1, a fifth of them), and inside them; the
    drawing still measures the table's centre distance at the stated scale."""
    import tmm_cli
    from tmm_cli.report import render
    from tmm_cli.report.sections.gears import AX_H, AX_W
    f = tmp_path / "g58.yaml"
    f.write_text("schema: tmm/1\ntitle: few teeth\ngears:\n  m: 4 mm\n  z: [5, 8]\n  x: [0, 0]\n", encoding="utf-8")
    task = tmm_cli.load_task(f)
    res = tmm_cli.run(task)
    render(res, task, tmp_path / "out", {"html"}, "en")
    svg = (tmp_path / "out" / "figures" / "gear-mesh.svg").read_text(encoding="utf-8")
    scale = re.search(r"scale (\d+(?:\.\d+)?):(\d+(?:\.\d+)?)<", svg)
    k = float(scale.group(1)) / float(scale.group(2))
    assert k == 2.0
    g = res["gears"]
    ra1, ra2, aw = (1000 * g["ra"][0], 1000 * g["ra"][1], 1000 * g["aw"])
    assert (aw + ra1 + ra2) * k > 0.8 * AX_H and 2 * max(ra1, ra2) * k < AX_W
    circles = [_circle_fit(P) for P in _paths(svg, stroke="#666666") if len(P) >= 5]
    ys = sorted({round(c[1], 1) for c in circles})
    assert len(ys) == 2 and (ys[1] - ys[0]) / k == pytest.approx(aw, abs=0.02)
    # every tip circle inside the axes' frame (paper mm: the axes' box in the SVG)
    tops = [c[1] - c[2] for c in circles]
    bottoms = [c[1] + c[2] for c in circles]
    assert max(bottoms) - min(tops) < AX_H


def _table_after(html: str, header: str) -> list[list[str]]:
    """The body rows (cell texts) of the first table whose header row contains ``header``."""
    i = html.index(header)
    body = html[i:html.index("</table>", i)]
    return [[re.sub(r"<[^>]+>", "", c) for c in re.findall(r"<td[^>]*>(.*?)</td>", tr)]
            for tr in re.findall(r"<tr>(.*?)</tr>", body, re.S)[1:]]


def _seg_dist(P: np.ndarray, q: np.ndarray) -> float:
    """Distance from the point q to the polyline P."""
    a, b = P[:-1], P[1:]
    d = b - a
    t = np.clip(((q - a) * d).sum(axis=1) / np.maximum((d * d).sum(axis=1), 1e-300), 0.0, 1.0)
    return float(np.min(np.hypot(*(a + d * t[:, None] - q).T)))


def _ray_hit(P: np.ndarray, o: np.ndarray, u: np.ndarray) -> float:
    """Distance from o along the unit direction u to the farthest crossing of the polyline P."""
    best = 0.0
    for a, b in zip(P[:-1], P[1:]):
        d = b - a
        M = np.array([[u[0], -d[0]], [u[1], -d[1]]])
        if abs(np.linalg.det(M)) < 1e-12:
            continue
        t, s = np.linalg.solve(M, a - o)
        if t > 0 and -1e-9 <= s <= 1 + 1e-9:
            best = max(best, float(t))
    return best


def test_cam_profile_is_the_tables_profile(tmp_path):
    out = _report("cam_knife", tmp_path)
    html = (out / "report.html").read_text(encoding="utf-8")
    svg = (out / "figures" / "cam-profile.svg").read_text(encoding="utf-8")
    text = html_mod.unescape(re.sub(r"<[^>]+>", "", html))
    unit = 1000.0 * float(re.search(r"μl = ([\d.]+) m/mm", text).group(1))   # real mm per paper mm (stated in m/mm)
    # (the profile is that of the exact least base radius; the design radius is the one rounded up)
    r0 = _th(html, "Minimum base radius of the pitch profile r0 (exact; the profile is built on it), mm")
    e = _th(html, "Offset e (positive: lowers the rise pressure angle), mm")
    # the centre O: the '+' mark (two strokes of 8 pt) -- the middle of its horizontal stroke
    plus = re.search(r'<path d="M(-?[\d.]+) (-?[\d.]+)h([\d.]+)M', svg)
    O = np.array([float(plus.group(1)) + float(plus.group(3)) / 2, float(plus.group(2))])
    (P,) = _paths(svg, stroke="#000000", stroke_width="0.56")               # the profile, 1.6 pt
    rows = _table_after(html, "x, mm")
    assert len(rows) >= 12
    s0 = math.sqrt(r0 * r0 - e * e)
    for row in rows:
        phi, s, x, y = _num(row[0]), _num(row[1]), _num(row[5]), _num(row[6])
        R = math.hypot(x, y)
        assert R == pytest.approx(math.hypot(e, s0 + s), abs=2e-4 * r0), phi       # the table's geometry
        q = O + np.array([x, -y]) / unit                                       # on the drawn profile
        assert _seg_dist(P, q) < 0.03, phi
        u = np.array([x, -y]) / R
        assert _ray_hit(P, O, u) * unit == pytest.approx(math.hypot(e, s0 + s), abs=0.02 * unit + 1e-3 * R), phi


@pytest.mark.parametrize("values, low", [([300.0, 15000.0, 12000.0], "zero"), ([-40.0, -900.0], "top"),
                                         ([-300.0, 140.0], "centred")])
def test_a_magnitudes_axis_starts_at_zero(values, low):
    """|R| over the cycle was drawn on an axis running down to -2500 (the data centred in the
    standard scale's span): values of one sign now start the axis at 0 (end it at 0 when all are
    negative), values of both signs stay centred; the span is still the standard μ times the
    axis' length."""
    from tmm_cli.report import figures
    from tmm_cli.report.svgchart import subplots
    fig, ax = subplots(170, 60)
    ax.plot([0, 1, 2][:len(values)], values)
    ax.set_ylabel("|R|, N")
    fig.subplots_adjust(left=0.1, right=0.9, top=0.9, bottom=0.1)
    mu = figures.std_axis(ax, min(values), max(values))
    lo, hi = ax.get_ylim()
    pos = ax.get_position()
    assert hi - lo == pytest.approx(mu * pos.height * fig.get_figheight() * 25.4)
    if low == "zero":
        assert lo == 0.0 and hi >= max(values)
    elif low == "top":
        assert hi == 0.0 and lo <= min(values)
    else:
        assert lo < min(values) and hi > max(values) and (lo + hi) / 2 == pytest.approx((min(values) + max(values)) / 2)
