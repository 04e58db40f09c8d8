"""The explorable mechanism in report.html (tmm_cli.report.explore): a crank-angle slider
that moves the linkage and redraws it, its plans and the table of v, a, omega, epsilon.

Checked in a real browser (headless Chromium through playwright; skipped like
tests/test_browser.py where it cannot run): moving the slider changes the drawing; the
values shown at three angles equal an independent solve of the kinematics at exactly
those crank angles (and, for the crank pin, v_A = omega1 r, a_A = omega1^2 r) to the
four digits shown; the slider snaps to the course positions, whose values equal
results.json; the widget is hidden in print and absent from the PDF's HTML; the file is
self-contained and under 2 MB."""
from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
TASK = ROOT / "tasks" / "forging_sixbar.yaml"


@pytest.fixture(scope="module")
def run(shared_once):
    # the folder `tmm run --format html,pdf` writes for the forging machine, made once per session
    # (tests/pdf_extent.py: the explorer's labels and the report's pages are checked on the same)
    from pdf_extent import report_out
    return report_out(shared_once, TASK.stem, "en")


@pytest.fixture(scope="module")
def page(browser, run):
    pg = browser.new_page(viewport={"width": 1300, "height": 900})
    errors = []
    pg.on("pageerror", lambda e: errors.append(str(e)))
    pg.goto((run / "report.html").as_uri())
    assert errors == []
    yield pg
    pg.close()


def _shown(pg) -> dict[str, tuple[float, float]]:
    rows = pg.eval_on_selector_all(
        "#ex-table tr[data-point], #ex-table tr[data-link]",
        "rs => rs.map(r => [r.dataset.point || r.dataset.link, r.cells[1].textContent, r.cells[2].textContent])")
    return {n: (float(a), float(b)) for n, a, b in rows if a != "—" and b != "—"}


def _close(shown: float, true: float) -> bool:
    """Equal to the 4 significant digits displayed: half a unit of the last digit, plus the
    rounding of the embedded data to 7 significant digits (a double rounding)."""
    if abs(true) < 1e-9:
        return abs(shown) < 1e-9
    half = 0.5 * 10 ** (math.floor(math.log10(abs(true))) - 3)
    return abs(shown - true) <= half + 5e-7 * abs(true) + 1e-12


def _set(pg, k: int) -> None:
    pg.locator("#ex-angle").fill(str(k))


def test_file_self_contained_and_small(run):
    html = (run / "report.html").read_text(encoding="utf-8")
    assert len(html.encode("utf-8")) < 2_000_000
    start = html.index('id="explore"')
    widget = html[start:html.index("</section>", start)]
    assert not re.search(r"""(src|href)\s*=\s*["']?https?:""", widget)
    assert "<svg" not in widget        # drawn by the script: the report's figure tools see only figures
    data = re.search(r'<script type="application/json" id="ex-data">(.*?)</script>', widget, re.S).group(1)
    d = json.loads(data)
    assert len(d["turn"]) == 360 and d["step"] == 1.0
    assert [m["index"] for m in d["positions"]] == list(range(12))


def test_json_cannot_close_the_script():
    from tmm_cli.report.explore import data_json
    s = data_json({"a": "</script><!--x"})
    assert "<" not in s and ">" not in s and "&" not in s
    assert json.loads(s) == {"a": "</script><!--x"}


def test_values_at_three_angles_equal_an_independent_solve(page, run):
    from tmm_cli.linkage.kinematics import solve
    from tmm_cli.linkage.mechanism import build_mechanism
    from tmm_cli.task import load_task
    res = json.loads((run / "results.json").read_text())
    task = load_task(TASK)
    mech = build_mechanism(task)
    w = res["drive"]["omega"]
    phi0 = res["positions"]["phi0"]
    sign = 1.0 if w > 0 else -1.0
    before = page.inner_html("#ex-mech")
    for turn in (47, 133, 250):
        _set(page, turn)
        assert page.inner_html("#ex-mech") != before           # the drawing moved
        before = page.inner_html("#ex-mech")
        phi = (phi0 + sign * turn) % 360.0
        kin = solve(mech, np.array([phi]), w)
        shown = _shown(page)
        for p in kin.points:
            if p in mech.ground:
                continue
            v = float(np.hypot(*kin.vel(p)[0]))
            a = float(np.hypot(*kin.acc(p)[0]))
            assert _close(shown[p][0], v) and _close(shown[p][1], a), (turn, p, shown[p], v, a)
        for link in kin.links:
            om = float(np.broadcast_to(kin.omega(link), (1,))[0])
            ep = float(np.broadcast_to(kin.epsilon(link), (1,))[0])
            assert _close(shown[link][0], om) and _close(shown[link][1], ep), (turn, link, shown[link], om, ep)
        # the crank pin by hand: v_A = |omega1| r, a_A = omega1^2 r (constant crank speed)
        rA = math.hypot(*(np.asarray(kin.pos["A"][0]) - np.asarray(kin.pos["O"][0])))
        assert _close(shown["A"][0], abs(w) * rA) and _close(shown["A"][1], w * w * rA)


def test_snaps_to_course_positions_with_results_json_values(page, run):
    res = json.loads((run / "results.json").read_text())
    _set(page, 32)                      # within 3 deg of position 1 (turn 30)
    assert page.input_value("#ex-angle") == "30"
    assert page.text_content("#ex-readout").rstrip().endswith("1")
    entry = next(e for e in res["kinematics"] if e["index"] == 1)
    shown = _shown(page)
    for p, q in entry["points"].items():
        if p in shown:
            assert _close(shown[p][0], q["v"]) and _close(shown[p][1], q["a"]), (p, shown[p], q)
    for name, q in entry["links"].items():
        assert _close(shown[name][0], q["omega"]) and _close(shown[name][1], q["epsilon"])
    _set(page, 35)                      # 5 deg away: no snap
    assert page.input_value("#ex-angle") == "35"
    _set(page, 358)                     # across 360: snaps to position 0
    assert page.input_value("#ex-angle") == "0"


def test_play_moves_and_pause_stops(page):
    _set(page, 100)
    page.click("#ex-play")
    page.wait_for_function("document.getElementById('ex-angle').value !== '100'", timeout=5000)
    page.click("#ex-play")
    k = page.input_value("#ex-angle")
    page.wait_for_timeout(300)
    assert page.input_value("#ex-angle") == k


def test_hidden_in_print_and_absent_from_the_pdf_html(page, run, tmp_path):
    page.emulate_media(media="print")
    assert not page.is_visible("#explore")
    page.emulate_media(media="screen")
    assert page.is_visible("#explore")
    from tmm_cli.report import render_html
    from tmm_cli.task import load_task
    res = json.loads((run / "results.json").read_text())
    html, _ = render_html(res, load_task(TASK), tmp_path / "pdfhtml")
    assert 'id="ex-data"' not in html


def test_round_off_zero_shown_as_zero(page):
    """At position 0 of the forging machine the slider is at rest (v_D = 0 exactly in
    theory, ~1e-16 in floating point): the table shows 0, as the report's tables do."""
    _set(page, 0)
    cells = page.eval_on_selector_all("#ex-table td", "cs => cs.map(c => c.textContent)")
    assert not [c for c in cells if re.fullmatch(r"-?[\d.]+e-1\d", c.strip())], cells
    assert _shown(page)["D"][0] == 0.0


def _forces_shown(pg) -> tuple[dict[str, float], tuple[float, float]]:
    rows = pg.eval_on_selector_all(
        "#ex-table tr[data-pair]", "rs => rs.map(r => [r.dataset.pair, r.cells[1].textContent])")
    mb = pg.eval_on_selector("#ex-table tr[data-mb]", "r => [r.cells[1].textContent, r.cells[2].textContent]")
    return {k: float(v) for k, v in rows}, (float(mb[0]), float(mb[1]))


def _drawings(pg) -> list[str]:
    return pg.eval_on_selector_all("[id^=ex-poly-], #ex-lever", "es => es.map(e => e.innerHTML)")


def test_forces_at_three_course_positions_equal_results_json(page, run):
    """Moving the slider to the course positions 2, 5 and 9: the reactions |R_ij| and the
    balancing moment (by the groups and by Zhukovsky's lever) shown equal results.json
    there, and the force polygons of the three groups and the lever are redrawn."""
    res = json.loads((run / "results.json").read_text())
    by_index = {e["index"]: e for e in res["kinetostatics"]}
    assert page.eval_on_selector_all("[id^=ex-poly-]", "es => es.length") == 3     # (4,5), (2,3), crank
    before = _drawings(page)
    for turn, index in ((60, 2), (150, 5), (270, 9)):
        _set(page, turn)
        assert page.text_content("#ex-readout").rstrip().endswith(str(index))
        now = _drawings(page)
        assert all(a != b for a, b in zip(now, before)), turn      # every polygon and the lever moved
        assert all("<line" in d for d in now)
        before = now
        e = by_index[index]
        R, (mb, mzh) = _forces_shown(page)
        assert set(R) == set(e["reactions"])
        for key, r in e["reactions"].items():
            assert _close(R[key], r["R"]), (index, key, R[key], r["R"])
        assert _close(mb, e["balancing_moment"]) and _close(mzh, e["zhukovsky_moment"]), (index, mb, e)


def test_headings_in_the_courses_notation(page):
    """The forces table's heading writes the catalogue's M_b as the report does: M with b lowered
    (a <sub>), no underscore left in any heading of the panel."""
    _set(page, 60)
    heads = page.eval_on_selector_all("#ex-table th", "hs => hs.map(h => [h.textContent, h.innerHTML])")
    assert heads and not [t for t, _ in heads if "_" in t]
    assert ["Mb, N·m", "<span>M</span><sub>b</sub><span>, N·m</span>"] in [list(h) for h in heads]


def test_numbers_with_the_decimal_comma_in_russian(browser, page, shared_once):
    """The panel's numbers as the Russian report's tables write them: 0,7854, 1,2·10⁴, −0,5 (the
    minus sign), never a decimal point, an e-exponent or a hyphen for minus; the same values as
    the English panel's."""
    from pdf_extent import report_out
    out = report_out(shared_once, TASK.stem, "ru")      # as tmm run --lang ru writes it, once a session
    pg = browser.new_page(viewport={"width": 1300, "height": 900})
    try:
        pg.goto((out / "report.html").as_uri())
        _set(pg, 60)
        cells = pg.eval_on_selector_all("#ex-table td", "ts => ts.map(t => t.textContent)")
        readout = pg.text_content("#ex-readout")
    finally:
        pg.close()
    nums = [c for c in cells if re.fullmatch(r"\u2212?[\d,]+(·10[⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+)?", c)]
    assert len(nums) > 20 and any("," in c for c in nums)
    assert any(c.startswith("\u2212") for c in nums) and not [c for c in cells if re.match(r"-\d", c)], cells
    assert not [c for c in cells if re.search(r"\d\.\d|\de[-+]?\d", c)], cells
    assert "," in readout and not re.search(r"\d\.\d", readout), readout

    def value(c):
        m = re.fullmatch(r"(\u2212?[\d,]+)(?:·10([⁻⁰¹²³⁴⁵⁶⁷⁸⁹]+))?", c)
        e = m.group(2) or "0"
        return float(m.group(1).replace(",", ".").replace("\u2212", "-")) * 10 ** int(e.translate(str.maketrans("⁻⁰¹²³⁴⁵⁶⁷⁸⁹", "-0123456789")))
    _set(page, 60)                                      # the English panel at the same angle
    en = [c for c in page.eval_on_selector_all("#ex-table td", "ts => ts.map(t => t.textContent)")
          if re.fullmatch(r"-?[\d.]+(e[-+]\d+)?", c)]
    assert [value(c) for c in nums] == pytest.approx([float(c) for c in en], rel=1e-12)


def test_polygon_closes_in_the_browser(page):
    """The drawn force polygon closes: the end of its last vector is its start (the
    group is in equilibrium), read from the drawn SVG of each group."""
    _set(page, 100)
    for gi in range(3):
        lines = page.eval_on_selector_all(f"#ex-poly-{gi} line", "ls => ls.map(l => [+l.getAttribute('x1'), "
                                          "+l.getAttribute('y1'), +l.getAttribute('x2'), +l.getAttribute('y2')])")
        assert len(lines) >= 3
        start, end = lines[0][:2], lines[-1][2:]
        assert math.hypot(start[0] - end[0], start[1] - end[1]) < 0.5, (gi, start, end)
        for a, b in zip(lines, lines[1:]):            # head to tail
            assert math.hypot(a[2] - b[0], a[3] - b[1]) < 1e-6


def test_widget_json_reads_back_the_same_values():
    """The widget's JSON (made by orjson, as results.json is) reads back to the same
    values, every float bit for bit (shortest forms such as 0.00001 and 2.5e-7, -0.0
    kept), text in any script as it is, and no '<', '>' or '&' outside the escapes."""
    import random
    import struct
    from tmm_cli.report.explore import data_json

    def bits(v):
        return [struct.pack("<d", x) if isinstance(x, float) else x for x in v]

    rng = random.Random(12)
    texts = ["a", "0.00001", "e-5", 'q"u', "b\\", "\x00\x1f\x7f", "é", "ж", "\U0001F600", "</x>&"]
    fixed = [1e-05, -1.5e-05, 9.9999e-05, 0.0001, 2.5e-07, 1e-10, 10.00001, 1e16, -0.0, 0, 2 ** 70]
    for _ in range(400):
        vals = [struct.unpack("<d", struct.pack("<Q", rng.getrandbits(64)))[0] for _ in range(10)]
        vals = [v for v in vals if v == v and abs(v) != float("inf")] + fixed
        rng.shuffle(vals)
        d = {rng.choice(texts): vals, "n": [None, True, rng.choice(texts)], rng.choice(texts): {"k": vals[:3]}}
        s = data_json(d)
        assert "<" not in s and ">" not in s and "&" not in s
        back = json.loads(s)
        assert back == d
        for k, v in d.items():
            if isinstance(v, list):
                assert bits(back[k]) == bits(v)


def _centres_drawn(pg) -> tuple[dict[str, tuple[float, float]], dict[str, tuple[float, float]], str]:
    """The drawn instant centres (key -> pixel), the drawn points (name -> pixel), the note."""
    cs = pg.eval_on_selector_all("#ex-mech circle[data-centre]",
                                 "cs => cs.map(c => [c.dataset.centre, +c.getAttribute('cx'), +c.getAttribute('cy')])")
    ps = pg.eval_on_selector_all("#ex-mech circle[data-point]",
                                 "cs => cs.map(c => [c.dataset.point, +c.getAttribute('cx'), +c.getAttribute('cy')])")
    return {k: (x, y) for k, x, y in cs}, {k: (x, y) for k, x, y in ps}, page_note(pg)


def page_note(pg) -> str:
    return pg.text_content("#ex-centres-note") or ""


def test_instant_centres_toggle_and_zero_relative_velocity(page, run):
    """The box "instant centres" draws P_ij on the mechanism at the angle the slider shows.
    Each drawn centre, read back from the drawing's pixels (the scale fixed by the drawn pins
    O and D of an independent solve at exactly that crank angle), is the point where the two
    links' velocities are equal, v_i(P) = v_A + omega_i k x (P - A) for a point A of link i
    (0 for the frame), to the drawing's round-off; the slider (link 5) translates on the
    frame: P_05 is at infinity, listed under the drawing and not drawn.  Unticked: none."""
    from tmm_cli.linkage.kinematics import solve
    from tmm_cli.linkage.mechanism import build_mechanism
    from tmm_cli.task import load_task
    res = json.loads((run / "results.json").read_text())
    mech = build_mechanism(load_task(TASK))
    w, phi0 = res["drive"]["omega"], res["positions"]["phi0"]
    links = [l.name for l in mech.links]
    n = len(links)
    assert page.eval_on_selector_all("#ex-mech circle[data-centre]", "cs => cs.length") == 0
    page.check("#ex-centres")
    try:
        far_seen = 0
        for turn in (5, 47, 133, 250):
            _set(page, turn)
            drawn, pts, note = _centres_drawn(page)
            kin = solve(mech, np.array([(phi0 + turn) % 360.0]), w)
            pos = {p: np.asarray(kin.pos[p][0], float) for p in kin.points}
            # the drawing's map: pixel = c + s (x, -y), from O and D
            (ox, oy), (dx, dy) = pts["O"], pts["D"]
            s = math.hypot(dx - ox, dy - oy) / float(np.linalg.norm(pos["D"] - pos["O"]))

            def world(px, py):
                return pos["O"] + np.array([(px - ox) / s, -(py - oy) / s])

            def vel(i, P):                    # link i's velocity at the point P (0: the frame)
                if i == 0:
                    return np.zeros(2)
                link = mech.links[i - 1]
                a = next(q for q in link.local if q in pos)
                om = float(np.broadcast_to(kin.omega(links[i - 1]), (1,))[0])
                r = P - pos[a]
                return np.asarray(kin.vel(a)[0], float) + om * np.array([-r[1], r[0]])

            size = max(float(np.linalg.norm(p - pos["O"])) for p in pos.values())
            om = [0.0] + [float(np.broadcast_to(kin.omega(l), (1,))[0]) for l in links]
            assert "P05" in note.replace(" ", "") and "0-5" not in drawn
            listed = note.count("P")
            assert len(drawn) + listed == n * (n + 1) // 2, (turn, sorted(drawn), note)
            assert len(drawn) >= 12
            for key, (px, py) in drawn.items():
                i, j = map(int, key.split("-"))
                P = world(px, py)
                dv = float(np.linalg.norm(vel(i, P) - vel(j, P)))
                # the drawing's round-off: 1e-6 of the size per pixel coordinate, times |w_i - w_j|
                assert dv <= 1e-5 * abs(om[i] - om[j]) * size + 1e-12, (turn, key, dv)
            # those beyond the drawing, listed with their coordinates to 4 digits
            for i, j, x, y in re.findall(r"P(\d)(\d) \((-?[\d.]+); (-?[\d.]+)\)", note):
                i, j, P = int(i), int(j), np.array([float(x), float(y)])
                dv = float(np.linalg.norm(vel(i, P) - vel(j, P)))
                assert dv <= 1e-3 * abs(om[i] - om[j]) * float(np.linalg.norm(P)), (turn, i, j, dv)
                far_seen += 1
        assert far_seen >= 1                  # at 5 deg P_04 lies 1.7 m off, beyond the drawing
    finally:
        page.uncheck("#ex-centres")
    assert page.eval_on_selector_all("#ex-mech circle[data-centre]", "cs => cs.length") == 0
    assert page_note(page) == ""


def test_centres_data_are_the_results_centres(run):
    """The explorer's instant centres at the course positions are results.json's
    ``instant_centres`` there (one computation): a pin's by its point, null at infinity."""
    res = json.loads((run / "results.json").read_text())
    html = (run / "report.html").read_text(encoding="utf-8")
    d = json.loads(re.search(r'<script type="application/json" id="ex-data">(.*?)</script>', html, re.S).group(1))
    n = len(d["turn"])
    by_index = {e["index"]: e for e in res["kinematics"]}
    for m in d["positions"]:
        k = round(m["turn"] / d["step"]) % n
        ic = by_index[m["index"]]["instant_centres"]
        assert set(ic) == set(d["centres"])
        for key, xy in ic.items():
            c = d["centres"][key]
            if "pin" in c:
                got = [d["points"][c["pin"]]["x"][k], d["points"][c["pin"]]["y"][k]]
            else:
                got = None if c["x"][k] is None else [c["x"][k], c["y"][k]]
            if xy is None:
                assert got is None, (m, key)
            else:
                assert got == pytest.approx(xy, rel=1e-6, abs=1e-9), (m, key, got, xy)
