"""The course's notation in the report is written with real subscripts: M_b, omega_max,
J_red of the catalogues appear as M<sub>b</sub> in report.html (hence subscripts in
report.pdf) and with a lowered subscript in its figures' labels, while the user's own text (the task's title, link and point names, file names,
code such as `r0: 45 mm`, results paths) and the plain-text outputs (CSV headers, the
terminal) keep the underscore as written."""
from __future__ import annotations

import re
import shutil
import subprocess
from html import unescape
from pathlib import Path

import pytest

import tmm_cli
from tmm_cli.report.notation import Term, notation_html, term

from report_langs import report_dir, report_html

ROOT = Path(__file__).resolve().parents[1]
TASKS = sorted(p.stem for p in (ROOT / "tasks").glob("*.yaml"))

# a notation token as a reader sees it: one letter, "_", letters or digits, not inside a word
# or a dotted path (rho_min, cam_profile, balancing.max.F_balanced are names, not notation)
TOKEN = re.compile(r"(?<![\w.`])[^\W\d_]_(?:\{[^{}]*\}|[^\W_]+)(?!_)")


def _visible(html: str, title: str) -> str:
    """The text a reader sees outside figures and scripts, without what the user wrote or
    the program's messages: code, the task's title, the warnings list (messages are the
    terminal's text too) and the failure boxes."""
    html = re.sub(r"<(svg|script|style|code)\b.*?</\1>", " ", html, flags=re.S)
    html = re.sub(r'<ul class="warnings">.*?</ul>', " ", html, flags=re.S)
    html = re.sub(r'<div class="failure".*?</div>', " ", html, flags=re.S)
    text = unescape(re.sub(r"<[^>]+>", " ", html))
    return text.replace(title, " ") if title else text


def _figure_text(html: str) -> str:
    """The labels of the inline figures, each a line (a subscript's tspan joined to its base)."""
    out = []
    for svg in re.findall(r"<svg\b.*?</svg>", html, flags=re.S):
        out += [unescape(re.sub(r"<[^>]+>", "", t)) for t in re.findall(r"<text\b[^>]*>(.*?)</text>", svg, flags=re.S)]
    return "\n".join(out)


def test_notation_html_writes_subscripts():
    assert notation_html("M_b, N·m") == "M<sub>b</sub>, N·m"
    assert notation_html("ω_ср² = ω_max·ω_min") == "ω<sub>ср</sub>² = ω<sub>max</sub>·ω<sub>min</sub>"
    assert notation_html("tg ψ_max,min = (μ_J/μ_T)") == "tg ψ<sub>max</sub>,min = (μ<sub>J</sub>/μ<sub>T</sub>)"
    assert notation_html("J_{red} + m₂l_c²") == "J<sub>red</sub> + m₂l<sub>c</sub>²"
    # names and paths stay as written; the text is escaped
    for plain in ("rho_min", "cam_profile.csv", "balancing.max.F_balanced", "`f_pin`", "F_x_y", "x2_a"):
        assert notation_html(plain) == plain
    assert notation_html("<b>M_b</b> & 'x'") == "&lt;b&gt;M<sub>b</sub>&lt;/b&gt; &amp; &#39;x&#39;"


def test_term_is_the_plain_text_with_html():
    from markupsafe import Markup, escape
    t = Term("M_b, N·m")
    assert t == "M_b, N·m" and str(t) == "M_b, N·m"          # CSV, terminal: as the catalogue writes it
    assert str(escape(t)) == "M<sub>b</sub>, N·m"
    assert str(Markup("<th>") + t) == "<th>M<sub>b</sub>, N·m"
    a, b = Term("by groups M_b = \u0001 N·m").split("\u0001")
    assert str(escape(a)) == "by groups M<sub>b</sub> = "
    # a value put into the catalogue's text keeps its underscore (a link named O_1)
    cat = {"k": "ω_i of {link}, T_{n}"}
    got = term(lambda key, lang, **kw: cat[key].format(**kw), "k", "en", link="O_1", n="3")
    assert got == "ω_i of O_1, T_3"
    assert str(escape(got)) == "ω<sub>i</sub> of O_1, T<sub>3</sub>"
    # ... also where the catalogue's own text has no notation (a stage failure's message put into
    # 'Stage «{stage}» failed: {message}': its z_min kept, not a private-use mark left in its place)
    cat = {"k": "failed: {message}"}
    got = term(lambda key, lang, **kw: cat[key].format(**kw), "k", "en", message="change z_min, z_max")
    assert str(escape(got)) == "failed: change z_min, z_max"


@pytest.mark.parametrize("name", TASKS)
@pytest.mark.parametrize("lang", ["en", "ru", "uk"])
def test_report_has_no_notation_with_underscore(shared_once, name, lang):
    task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
    html = report_html(shared_once, name, lang)
    assert "\ue000" not in html                      # no kept underscore's mark left behind
    assert TOKEN.findall(_visible(html, task.title or "")) == []
    # the figures draw the same catalogue texts with their subscripts lowered
    assert TOKEN.findall(_figure_text(html)) == []


def test_forging_notation_in_subscripts(shared_once):
    """The tokens the forging press's Russian report wrote with an underscore, each now a subscript."""
    html = report_html(shared_once, "forging_sixbar", "ru")
    for base, sub in [("F", "тр"), ("J", "S"), ("J", "Мерцалов"), ("J", "пост"), ("J", "пр"), ("J", "точн"),
                      ("M", "ур"), ("M", "пр"), ("P", "ур"), ("R", "ij"), ("R", "ji"), ("a", "S"), ("μ", "J"),
                      ("μ", "T"), ("ψ", "max"), ("ψ", "min"), ("ω", "i"), ("ω", "ср"), ("ω", "max")]:
        assert f"{base}<sub>{sub}</sub>" in html, (base, sub)
    # the CSV tables keep the plain text
    csv = (report_dir(shared_once, "forging_sixbar", "ru") / "kinetostatics.csv").read_text(encoding="utf-8")
    assert "<sub>" not in csv


@pytest.mark.skipif(not shutil.which("pdftotext"), reason="poppler's pdftotext not installed")
@pytest.mark.parametrize("name,lang", [("forging_sixbar", "ru"), ("engine_slider_crank", "en"),
                                       ("impact_rotor", "uk")])
def test_pdf_has_no_notation_with_underscore(shared_once, tmp_path, name, lang):
    from tmm_cli.report.typst_pdf import pdf_bytes
    html = report_html(shared_once, name, lang)
    html = re.sub(r'<ul class="warnings">.*?</ul>', "", html, flags=re.S)
    pdf = tmp_path / "r.pdf"
    pdf.write_bytes(pdf_bytes(html, lang))
    text = subprocess.run(["pdftotext", str(pdf), "-"], capture_output=True, text=True, check=True).stdout
    title = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml").title or ""
    assert TOKEN.findall(text.replace(title, " ")) == []


def test_figure_label_lowers_a_catalogue_subscript():
    from tmm_cli.report.svgchart import text_body
    # a catalogue's text: the subscript lowered (dy) and smaller, the rest as written
    body = text_body(Term("ΔT, mm (μ_T = 4 J/mm)"), 3.0)
    assert re.fullmatch(r'ΔT, mm \(μ<tspan dy="0\.9" font-size="2\.16">T</tspan><tspan dy="-0\.9"> = 4 J/mm\)</tspan>',
                        body), body
    # any other text (a link or point name given by the task) as written
    assert text_body("O_1", 3.0) == "O_1"
    assert text_body(term(lambda key, lang, **kw: "ω of {n}".format(**kw), "k", "en", n="O_1"), 3.0) == "ω of O_1"
