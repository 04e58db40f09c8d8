"""Tests of the report (tmm_cli.report): HTML in en/ru, figures, plan scales,
plan segment lengths against an independent closed-form slider-crank, PDF."""
from __future__ import annotations

import math
import re
import shutil
import subprocess

import numpy as np
import pytest

# ----------------------------------------------------------------------------
# An independent closed-form central slider-crank (O on the guide, e = 0):
#   A = r (cos phi, sin phi);  sin beta = -r sin phi / l;  B = (r cos phi + l cos beta, 0)
#   beta'  = -r w cos phi / (l cos beta)
#   beta'' = (r w^2 sin phi + l beta'^2 sin beta) / (l cos beta)
#   v_B = -r w sin phi - l beta' sin beta
#   a_B = -r w^2 cos phi - l beta'' sin beta - l beta'^2 cos beta
# S2 is the midpoint of AB, S1 = O, S3 = B.  Position 0 = inner dead centre
# (phi = 180 deg: the working stroke towards +x starts there), ccw rotation.
# ----------------------------------------------------------------------------
R_CRANK = 0.12
L_ROD = 0.42
RPM = 100.0
OMEGA = math.pi * RPM / 30.0


def slider_crank_state(phi_deg: float, r=R_CRANK, l=L_ROD, w=OMEGA):
    f = math.radians(phi_deg)
    A = np.array([r * math.cos(f), r * math.sin(f)])
    vA = np.array([-r * w * math.sin(f), r * w * math.cos(f)])
    aA = np.array([-r * w * w * math.cos(f), -r * w * w * math.sin(f)])
    beta = math.asin(-r * math.sin(f) / l)
    db = -r * w * math.cos(f) / (l * math.cos(beta))
    ddb = (r * w * w * math.sin(f) + l * db * db * math.sin(beta)) / (l * math.cos(beta))
    B = np.array([r * math.cos(f) + l * math.cos(beta), 0.0])
    vB = np.array([-r * w * math.sin(f) - l * db * math.sin(beta), 0.0])
    aB = np.array([-r * w * w * math.cos(f) - l * ddb * math.sin(beta) - l * db * db * math.cos(beta), 0.0])
    return dict(A=A, vA=vA, aA=aA, B=B, vB=vB, aB=aB, beta=beta, db=db, ddb=ddb, w=w)


def _pt(p, v, a):
    return {"x": float(p[0]), "y": float(p[1]), "vx": float(v[0]), "vy": float(v[1]),
            "v": float(np.hypot(*v)), "ax": float(a[0]), "ay": float(a[1]), "a": float(np.hypot(*a))}


def slider_crank_results(count=12, extra=()):
    z = np.zeros(2)
    entries = []
    phis = [(180.0 + 30.0 * i) % 360.0 for i in range(count)] + list(extra)
    for i, phi in enumerate(phis):
        s = slider_crank_state(phi)
        S2 = (s["A"] + s["B"]) / 2
        vS2 = (s["vA"] + s["vB"]) / 2
        aS2 = (s["aA"] + s["aB"]) / 2
        entries.append({
            "index": i, "phi": phi,
            "points": {"O": _pt(z, z, z), "A": _pt(s["A"], s["vA"], s["aA"]),
                       "B": _pt(s["B"], s["vB"], s["aB"]), "S1": _pt(z, z, z),
                       "S2": _pt(S2, vS2, aS2), "S3": _pt(s["B"], s["vB"], s["aB"])},
            "links": {"crank": {"angle": phi, "omega": OMEGA, "epsilon": 0.0},
                      "rod": {"angle": math.degrees(s["beta"]) % 360.0, "omega": s["db"],
                              "epsilon": s["ddb"]},
                      "slider": {"angle": 0.0, "omega": 0.0, "epsilon": 0.0}},
        })
    return {
        "schema": "tmm-results/1",
        "structure": {"n": 3, "p5": 4, "p4": 0, "W": 1, "class": 2,
                      "groups": [{"links": ["rod", "slider"], "class": 2, "order": 2, "type": "RRP"}],
                      "formula": "I(0,1) -> II(2,3)",
                      "links": [{"name": "crank", "index": 1, "points": ["O", "A"], "kind": "bar"},
                                {"name": "rod", "index": 2, "points": ["A", "B"], "kind": "bar"},
                                {"name": "slider", "index": 3, "points": ["B"], "kind": "slider"}],
                      "joints": [{"kind": "R", "a": 0, "b": 1, "point": "O"},
                                 {"kind": "R", "a": 1, "b": 2, "point": "A"},
                                 {"kind": "R", "a": 2, "b": 3, "point": "B"},
                                 {"kind": "P", "a": 0, "b": 3, "point": None}]},
        "positions": {"phi0": 180.0, "extreme": [180.0, 0.0], "working_stroke_angle": 180.0,
                      "idle_stroke_angle": 180.0, "K": 1.0, "output": "slider"},
        "kinematics": entries,
        "warnings": [],
    }


TASK_DICT = {
    "schema": "tmm/1", "title": "Slider-crank press", "variant": 3,
    "student": {"name": "Ivanov I.I.", "group": "M-21"},
    "mechanism": {"ground": {"O": [0, 0]},
                  "links": {"crank": {"points": ["O", "A"], "length": R_CRANK, "mass": 2},
                            "rod": {"points": ["A", "B"], "length": L_ROD, "mass": 5, "J": 0.08},
                            "slider": {"slider": "B", "guide": {"through": "O", "angle": 0}, "mass": 8}}},
    "drive": {"link": "crank", "speed": f"{RPM} rpm", "direction": "ccw"},
    "positions": {"count": 12, "output": "slider"},
}


def make_task():
    import tmm_cli
    return tmm_cli.load_task(TASK_DICT)


# ----------------------------------------------------------------------------
# A crank-slotted-lever (кулисный механизм): crank O-A (r1), block 2 on A sliding
# along the slotted rocker 3 through the fixed pivot O1.  Closed form:
#   d = A - O1, s = |d|, theta = atan2(d),  s' = d.vA / s,  theta' = (d x vA)/s^2,
#   theta'' = (d x aA)/s^2 - 2 s' theta' / s,   Coriolis |a_k| = 2 |theta'| |s'|.
# ----------------------------------------------------------------------------
O1 = np.array([0.0, -0.30])
R1 = 0.10
C_LEN = 0.55


def _cross2(a, b):
    return float(a[0] * b[1] - a[1] * b[0])


def slotted_state(phi_deg, w=OMEGA):
    f = math.radians(phi_deg)
    A = np.array([R1 * math.cos(f), R1 * math.sin(f)])
    vA = np.array([-R1 * w * math.sin(f), R1 * w * math.cos(f)])
    aA = -w * w * A
    d = A - O1
    s = float(np.linalg.norm(d))
    th = math.atan2(d[1], d[0])
    ds = float(d @ vA) / s
    w3 = _cross2(d, vA) / s ** 2
    e3 = _cross2(d, aA) / s ** 2 - 2 * ds * w3 / s
    u = np.array([math.cos(th), math.sin(th)])
    nrm = np.array([-u[1], u[0]])
    C = O1 + C_LEN * u
    vC = C_LEN * w3 * nrm
    aC = C_LEN * e3 * nrm - C_LEN * w3 * w3 * u
    return dict(A=A, vA=vA, aA=aA, th=th, w3=w3, e3=e3, ds=ds, C=C, vC=vC, aC=aC, s=s)


def slotted_results(count=12):
    z = np.zeros(2)
    entries = []
    for i in range(count):
        phi = 30.0 * i + 15.0
        s = slotted_state(phi)
        entries.append({
            "index": i, "phi": phi,
            "points": {"O": _pt(z, z, z), "O1": _pt(O1, z, z), "A": _pt(s["A"], s["vA"], s["aA"]),
                       "C": _pt(s["C"], s["vC"], s["aC"])},
            "links": {"crank": {"angle": phi, "omega": OMEGA, "epsilon": 0.0},
                      "block": {"angle": math.degrees(s["th"]) % 360, "omega": s["w3"], "epsilon": s["e3"]},
                      "rocker": {"angle": math.degrees(s["th"]) % 360, "omega": s["w3"], "epsilon": s["e3"]}},
        })
    return {
        "schema": "tmm-results/1",
        "structure": {"n": 3, "p5": 4, "p4": 0, "W": 1, "class": 2,
                      "groups": [{"links": ["block", "rocker"], "class": 2, "order": 2, "type": "RPR"}],
                      "formula": "I(0,1) -> II(2,3)",
                      "links": [{"name": "crank", "index": 1, "points": ["O", "A"], "kind": "bar"},
                                {"name": "block", "index": 2, "points": ["A"], "kind": "slider"},
                                {"name": "rocker", "index": 3, "points": ["O1", "C"], "kind": "bar"}],
                      "joints": [{"kind": "R", "a": 0, "b": 1, "point": "O"},
                                 {"kind": "R", "a": 1, "b": 2, "point": "A"},
                                 {"kind": "P", "a": 2, "b": 3, "point": None},
                                 {"kind": "R", "a": 0, "b": 3, "point": "O1"}]},
        "positions": {"phi0": 15.0},
        "kinematics": entries,
        "warnings": [],
    }


# ----------------------------------------------------------------------------
from tmm_cli.report import render, render_html  # noqa: E402
from tmm_cli.report import figures as F  # noqa: E402
from tmm_cli.numfmt import localize  # noqa: E402
from tmm_cli.report.context import fmt  # noqa: E402
from tmm_cli.plans import build_plan, geometry, scales  # noqa: E402


def _pdf_ok():
    try:
        import typst  # noqa: F401
        return True
    except ImportError:
        return False


@pytest.fixture(scope="module")
def task():
    return make_task()


@pytest.fixture(scope="module")
def results():
    return slider_crank_results()


@pytest.fixture(scope="module")
def html_en(results, task, tmp_path_factory):
    return render_html(results, task, tmp_path_factory.mktemp("en"), "en")[0]


@pytest.fixture(scope="module")
def rendered_ru(results, task, tmp_path_factory):
    """One full render (html + pdf when the PDF engine works) in Russian."""
    out = tmp_path_factory.mktemp("ru")
    formats = {"html", "pdf"} if _pdf_ok() else {"html"}
    return out, render(results, task, out, formats, "ru")


@pytest.fixture(scope="module")
def html_ru(rendered_ru):
    return (rendered_ru[0] / "report.html").read_text(encoding="utf-8")


def test_html_headings_en(html_en):
    for text in ("Structural analysis", "Assur groups", "Kinematic analysis", "Velocity plan",
                 "Acceleration plan", "Kinematic diagrams of the output link", "Slider-crank press",
                 "Ivanov I.I.", "Chebyshev"):
        assert text in html_en, text


def test_html_headings_ru(html_ru):
    for text in ("Структурный анализ механизма", "Группы Ассура", "Структурная формула",
                 "План скоростей", "План ускорений", "Кинематические диаграммы", "кривошип", "шатун",
                 "ползун", "Масштабные коэффициенты", "План положений механизма"):
        assert text in html_ru, text
    assert "Structural analysis" not in html_ru


def test_figure_count(html_en):
    # scheme + positions plan + diagrams + one plans figure (v and a) per position
    assert html_en.count("<svg") == 3 + 12
    assert "<?xml" not in html_en and "<!DOCTYPE svg" not in html_en


def test_chebyshev_line(html_en):
    # W = 3*3 - 2*4 - 0 = 1 for the slider-crank
    assert "3·3 − 2·4 − 0 = 1" in html_en
    assert "I(0,1) → II(2,3)" in html_en


def test_scales_hand_computation(results, task, html_en):
    # v_A = omega r = (pi*100/30)*0.12 = 1.256637 m/s; v_A/100 mm = 0.012566 -> standard 0.02
    # a_A = omega^2 r = 10.47198^2 * 0.12 = 13.1595 m/s^2; /100 mm = 0.1316 -> standard 0.2
    geom = geometry(results)
    mu_v, mu_a, vA, aA = scales(results["kinematics"], geom)
    assert vA == pytest.approx(1.2566371, rel=1e-6)
    assert aA == pytest.approx(13.159473, rel=1e-6)
    assert mu_v == 0.02 and mu_a == 0.2
    # the report draws and tabulates the plans at these where every position's plan fits its
    # half of the figure (84 x 86 mm less the title, the scale bar and the margins: 72 x 56 mm);
    # the slider-crank's do not (pa 62.8 mm turning with the crank, πa 65.8 mm): the next standard ones
    from tmm_cli.report.sections.kinematics import drawn_scales
    assert drawn_scales(results, geom)[:2] == (0.025, 0.25)
    assert "1.257 / 50.27 ≈ 0.025" in html_en      # pa = 1.256637/0.025 = 50.265 mm
    assert "13.16 / 52.64 ≈ 0.25" in html_en       # pi-a = 13.1595/0.25 = 52.638 mm


@pytest.mark.parametrize("i", range(12))
def test_plan_segments_closed_form(results, task, i):
    geom = geometry(results)
    e = results["kinematics"][i]
    s = slider_crank_state(e["phi"])
    mu_v, mu_a = 0.015, 0.15
    vp = build_plan("v", e, geom, mu_v)
    segs = {seg: mm for _, seg, mm, _ in vp.rows()}
    assert segs["pa"] == pytest.approx(R_CRANK * OMEGA / mu_v, rel=1e-9)
    assert segs["pb"] == pytest.approx(abs(s["vB"][0]) / mu_v, abs=1e-9)
    # |v_BA| = |omega2| * l_AB
    assert segs["ab"] == pytest.approx(abs(s["db"]) * L_ROD / mu_v, rel=1e-9, abs=1e-9)
    ap = build_plan("a", e, geom, mu_a)
    rows = {seg: mm for _, seg, mm, _ in ap.rows()}
    assert rows["an₂"] == pytest.approx(s["db"] ** 2 * L_ROD / mu_a, rel=1e-9, abs=1e-9)
    assert rows["n₂b"] == pytest.approx(abs(s["ddb"]) * L_ROD / mu_a, rel=1e-9, abs=1e-9)
    assert rows["πb"] == pytest.approx(abs(s["aB"][0]) / mu_a, rel=1e-9, abs=1e-9)
    # the normal component lies along BA (towards A), the tangential one across it
    ab = s["A"] - s["B"]
    n_vec = ap.pts["n₂"] - ap.pts["a"]
    t_vec = ap.pts["b"] - ap.pts["n₂"]
    if np.linalg.norm(n_vec) > 1e-9:
        assert float(n_vec @ ab) / (np.linalg.norm(n_vec) * np.linalg.norm(ab)) == pytest.approx(1.0)
    assert abs(float(t_vec @ ab)) <= 1e-9 * (1 + np.linalg.norm(t_vec))


def _table_after(html, heading):
    """The rows (lists of cell texts) of the first table after `heading`."""
    part = html.split(heading, 1)[1].split("</table>", 1)[0]
    rows = []
    for tr in re.findall(r"<tr>(.*?)</tr>", part, re.S):
        rows.append([re.sub(r"<[^>]+>", "", c).strip() for c in re.findall(r"<t[dh][^>]*>(.*?)</t[dh]>", tr, re.S)])
    return rows


def test_angular_sense_marks(html_ru):
    """omega and epsilon of the rod in the summary tables: value of the closed form and
    its sense (↺ ccw for positive, ↻ cw for negative), explained in words below."""
    html = html_ru
    w_rows = _table_after(html, "Угловые скорости звеньев, рад/с")
    e_rows = _table_after(html, "Угловые ускорения звеньев, рад/с²")
    hdr = w_rows[0]
    col = hdr.index("2 (rod)")
    assert "3 (slider)" not in hdr            # a slider on a fixed guide does not turn
    for wr, er in zip(w_rows[1:], e_rows[1:]):
        s = slider_crank_state(float(wr[1].replace(",", ".")))     # the decimal comma of Russian
        for txt, x in ((wr[col], s["db"]), (er[col], s["ddb"])):
            assert txt.split()[0] == localize(fmt(x), "ru")
            if abs(x) > 1e-9:
                assert txt.endswith("↺" if x > 0 else "↻")
            else:                                   # a dead centre: no sense
                assert txt == fmt(x)
    # position 1: phi = 210 deg, omega2 = -r w cos(210)/(l cos beta) > 0 -> ccw
    assert slider_crank_state(210.0)["db"] > 0 and w_rows[2][col].endswith("↺")
    assert "↺ — против часовой стрелки" in html and "↻ — по часовой стрелке" in html


def test_coriolis_slotted_lever():
    res = slotted_results()
    geom = geometry(res)
    for e in res["kinematics"]:
        st = slotted_state(e["phi"])
        mu_a = 0.1
        ap = build_plan("a", e, geom, mu_a)
        rows = {seg: (mm, val) for _, seg, mm, val in ap.rows()}
        # a_A3A2^k = 2 omega3 x v_A3A2: |.| = 2 |omega3| |s'|, normal to the guide
        mm, val = rows["ak"]
        assert val == pytest.approx(2 * abs(st["w3"] * st["ds"]), rel=1e-9, abs=1e-12)
        assert mm == pytest.approx(val / mu_a, rel=1e-12, abs=1e-12)
        k = ap.pts["k"] - ap.pts["a"]
        u = np.array([math.cos(st["th"]), math.sin(st["th"])])
        assert abs(float(k @ u)) <= 1e-9 * (1 + np.linalg.norm(k))
        # chain a -> k -> a3 closes on pi -> n3 -> a3 (a_A3 = a_O1 + n + t)
        a3_closed = st["e3"] * st["s"] * np.array([-u[1], u[0]]) - st["w3"] ** 2 * st["s"] * u
        assert np.allclose(ap.pts["a₃"] * mu_a, a3_closed, atol=1e-9)
        assert rows["πn₃"][1] == pytest.approx(st["w3"] ** 2 * st["s"], rel=1e-9, abs=1e-12)
        vp = build_plan("v", e, geom, 0.01)
        vrows = {seg: val for _, seg, _, val in vp.rows()}
        assert vrows["aa₃"] == pytest.approx(abs(st["ds"]), rel=1e-9, abs=1e-12)
        assert vrows["pa₃"] == pytest.approx(abs(st["w3"]) * st["s"], rel=1e-9, abs=1e-12)


def test_slotted_report_renders(tmp_path):
    html = render_html(slotted_results(count=4), None, tmp_path, "en")[0]
    assert "slotted link" in html and html.count("<svg") == 3 + 4


def test_geometry_from_the_results_only(results, task):
    """The links, pairs and driving link come from results['structure'] alone: without its
    'links' there is no geometry (and no drawing), whatever the task says."""
    r2 = dict(results)
    r2["structure"] = {k: v for k, v in results["structure"].items() if k not in ("links", "joints")}
    assert geometry(r2) is None
    g = geometry(results)
    assert [(l.name, l.index, l.points, l.kind) for l in g.links] == \
        [("crank", 1, ["O", "A"], "bar"), ("rod", 2, ["A", "B"], "bar"), ("slider", 3, ["B"], "slider")]
    assert g.drive == 1 and g.order[1] == 0          # no 'drive_link' key: link 1 drives
    r3 = dict(results)
    r3["structure"] = {**results["structure"], "drive_link": "rod"}
    assert geometry(r3).drive == 2


def test_csv_tables(rendered_ru):
    tmp_path, paths = rendered_ru
    assert tmp_path / "report.html" in paths and tmp_path / "kinematics.csv" in paths
    import csv
    rows = list(csv.DictReader((tmp_path / "kinematics.csv").open()))
    assert len(rows) == 12
    for row in rows:
        s = slider_crank_state(float(row["phi"]))
        assert float(row["B.v"]) == pytest.approx(abs(s["vB"][0]), abs=1e-12)
        assert float(row["rod.epsilon"]) == pytest.approx(s["ddb"], rel=1e-12)
    plans = list(csv.DictReader((tmp_path / "plans.csv").open()))
    pb = [r for r in plans if r["segment"] == "pb"]
    assert len(pb) == 12
    for r in pb:
        s = slider_crank_state(float(r["phi"]))
        # μv = 0.025 (m/s)/mm: the plans as drawn (test_scales_hand_computation)
        assert float(r["length_mm"]) == pytest.approx(abs(s["vB"][0]) / 0.025, abs=1e-9)


def test_absent_sections(tmp_path):
    html = render_html({"schema": "tmm-results/1", "structure": slider_crank_results()["structure"]},
                       None, tmp_path, "en")[0]
    assert "Structural analysis" in html and "Kinematic analysis" not in html
    assert render({"schema": "tmm-results/1"}, None, tmp_path / "x", {"json"}, "en") == []


def test_fmt_rules():
    assert fmt(None) == "—"
    assert fmt(1.099e-16) == "0"          # round-off of an exact zero
    assert fmt(-0.0) == "0"
    assert fmt(1.2566370614) == "1.257"
    assert fmt(13.159473) == "13.16"
    assert fmt(0.000123456) == "0.0001235"
    assert fmt(12345678.0) == "1.235e+07"


from hypothesis import given, strategies as st  # noqa: E402


@given(st.floats(min_value=1e-9, max_value=1e9))
def test_nice_scale_property(x):
    m = F.nice_scale(x)
    assert m >= x * (1 - 1e-12)
    assert m <= 2.0 * x * (1 + 1e-12)        # largest ratio of 1, 2, 2.5, 4, 5, 10 is 2 (1 -> 2, 5 -> 10)
    mant = m / 10 ** math.floor(math.log10(m) + 1e-12)
    assert any(abs(mant - s) < 1e-9 for s in (1, 2, 2.5, 4, 5, 10))


def pdf_page_count(data: bytes) -> int:
    """Page objects (/Type /Page) of a PDF, also those inside compressed object
    streams (PDF writers may put them there: a search of the raw bytes finds none)."""
    import zlib
    chunks, view = [data], memoryview(data)
    for m in re.finditer(rb"stream\r?\n", data):
        try:
            chunks.append(zlib.decompressobj().decompress(view[m.end():]))
        except zlib.error:
            continue
    return sum(len(re.findall(rb"/Type\s*/Page\b", c)) for c in chunks)


@pytest.mark.skipif(not _pdf_ok(), reason="the PDF engine (typst) is not installed")
def test_pdf(rendered_ru, tmp_path):
    out, paths = rendered_ru
    pdf = out / "report.pdf"
    assert pdf in paths
    data = pdf.read_bytes()
    assert data.startswith(b"%PDF-") and b"%%EOF" in data[-1024:]
    n_pages = pdf_page_count(data)
    if shutil.which("pdfinfo"):
        out = subprocess.run(["pdfinfo", str(pdf)], capture_output=True, text=True).stdout
        assert n_pages == int(re.search(r"Pages:\s+(\d+)", out).group(1))
    # title/task page + structure + kinematics tables + one page per position plan
    assert n_pages >= 3 + 12
    if shutil.which("pdftoppm"):
        subprocess.run(["pdftoppm", "-r", "30", "-png", "-f", "1", "-l", "1", str(pdf),
                        str(tmp_path / "pg")], check=True)
        assert list(tmp_path.glob("pg*.png"))
