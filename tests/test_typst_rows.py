"""Table rows of a given height in the PDF (typst_pdf._Writer.fixed_rows): a body row whose
cells are one line of text each gets the height an auto row gets, so Typst lays it out once
instead of measuring it first. The claim checked here: the PDF is the same, byte for byte,
as the one compiled with every row auto (the `rows:` arguments taken out of the same
source); rows that could wrap stay auto; and the width bound used for that decision is a
bound of DejaVu Sans's advances (read from the font files)."""
from __future__ import annotations

import re

import pytest

from tmm_cli.report import typst_pdf
from tmm_cli.report.typst_pdf import _em_width, to_typst

typst = pytest.importorskip("typst")

_ROWS = re.compile(r"rows: \([^)]*\), ")


def _compile(src: str, files: dict[str, bytes], tmp_path) -> bytes:
    for name, data in files.items():
        (tmp_path / name).write_bytes(data)
    (tmp_path / "r.typ").write_text(src, encoding="utf-8")
    return typst.compile(str(tmp_path / "r.typ"), root=str(tmp_path),
                         font_paths=typst_pdf._font_dirs(), pdf_tags=False)


def _table(cls: str, head: list[str], body: list[list[str]], caption: str = "") -> str:
    cap = f"<caption>{caption}</caption>" if caption else ""
    th = "".join(f"<th>{h}</th>" for h in head)
    tr = "".join("<tr>" + "".join(f'<td class="num">{c}</td>' for c in r) + "</tr>" for r in body)
    return f'<table class="{cls}">{cap}<thead><tr>{th}</tr></thead><tbody>{tr}</tbody></table>'


def _numbers(rows: int, cols: int, seed: int = 0) -> list[list[str]]:
    import random
    rnd = random.Random(seed)
    return [[str(i)] + [f"{rnd.uniform(-2000, 2000):.5g}" for _ in range(cols - 1)] for i in range(rows)]


HTML = "<html><head><title>t</title></head><body><section><h2>Tables</h2>" + "".join([
    # a long numeric table over pages (compact, shared columns), headers with sub/superscripts
    _table("compact wide", ["Pos.", "φ, °"] + [f"M<sub>Φ{k}</sub>" for k in range(2, 10)], _numbers(90, 10)),
    # cells with sub- and superscripts, bold and a bar over it, in a pair side by side
    '<div class="pair"><div>'
    + _table("compact wide", ["Vector", "Segment", "Length, mm", "Value, m/s²"],
             [[f"a<sub>B{k}</sub><sup>τ</sup>", f"πs₂{k}", "82.2", "4.112"] for k in range(12)]
             + [[f"<b>v</b><sub>{k}</sub>", "<span class='vec'>ab</span>", "1.0", "2"] for k in range(6)])
    + "</div><div>"
    + _table("compact wide", ["Вектор", "Отрезок", "Длина, мм", "Значение"],
             [[f"<i>ω</i><sub>{k}</sub>", "Щ", "-0.5", "1e-05"] for k in range(12)])
    + "</div></div>",
    # a key-value table of text (auto columns)
    '<table class="kv"><tr><th>Title</th><td>Horizontal forging machine</td></tr>'
    '<tr><th>J<sub>n</sub>, kg·m²</th><td>179.853</td></tr><tr><th>δ</th><td>1/18</td></tr></table>',
    # rows that may wrap: a long number in groups of digits in one of 12 shared columns (a
    # number without spaces cannot wrap: its column is made as wide as it), a spanning note row
    _table("compact wide", [f"c{k}" for k in range(12)],
           _numbers(5, 12, 1) + [["1234 5678 9012 3456 7890 12"] + ["1"] * 11] + _numbers(5, 12, 2)),
    '<table class="wide"><thead><tr><th>a</th><th>b</th></tr></thead><tbody>'
    '<tr><td>1</td><td>2</td></tr><tr><td colspan="2">' + "a long note spanning the columns " * 12
    + "</td></tr><tr><td>3</td><td>4</td></tr></tbody></table>",
    # tables in a row (boxes in a line): each is laid out in the whole line's width, so a
    # row of a second table, too long for the line, stays auto (a wrapped cell)
    '<div class="task-groups">'
    + '<table class="kv"><tr><th>' + "first table, wide " * 2 + "</th><td>1</td></tr></table>"
    + '<table class="kv"><tr><th>second</th><td>' + "a long value on one line " * 5
    + "</td></tr><tr><th>x</th><td>2</td></tr></table></div>",
    # a table in a list item (its free width not known): every row auto
    "<ul><li>item " + _table("compact", ["x", "y"], _numbers(4, 2, 3)) + "</li></ul>",
]) + "</section></body></html>"


def test_fixed_rows_leave_the_pdf_byte_identical(tmp_path, monkeypatch):
    monkeypatch.setattr(typst_pdf, "_CHUNK", 0)         # one row a table row
    src, files = to_typst(HTML, "ru")
    tracks = _ROWS.findall(src)
    assert len(tracks) == 6, "the test's tables give rows of a given height"
    auto_src = _ROWS.sub("", src)
    a = _compile(src, files, tmp_path)
    b = _compile(auto_src, files, tmp_path)
    assert a == b


def test_rows_that_may_wrap_stay_auto(monkeypatch):
    monkeypatch.setattr(typst_pdf, "_CHUNK", 0)
    src, _ = to_typst(HTML, "en")
    tables = src.split("#table(")[1:]

    def rows_of(header: str):
        t = next(t for t in tables if header in t[t.find("table.header("):][:120])
        m = _ROWS.match(t[t.find("rows:"):]) if "rows:" in t[:t.find("inset:")] else None
        return m.group(0) if m else None

    long_num = rows_of('"c0"')
    # the header (short bold names) and five rows fixed, the row of the long number auto,
    # then fixed again
    tracks = [x.strip() for x in long_num[len("rows: ("):-len(",), ")].split(",")]
    assert tracks[6] == "auto"
    assert all(t.startswith("0.8em") for t in tracks[:6] + tracks[7:])
    # a header with sub- and superscripts in bold: fixed too
    assert rows_of('"Pos."').startswith("rows: (0.8em")
    # a cell wider than the columns it spans: the table stays auto (how Typst widens the
    # columns under it is not modelled)
    note = rows_of('"a"')
    assert note is None
    assert rows_of('"x"') is None
    # a header in bold, one line in its shared column (the bound of DejaVu Sans Bold's
    # advances), then the body rows
    assert rows_of('"Vector"').startswith("rows: (0.8em")


def test_width_bound_covers_dejavu_sans():
    """Every character of DejaVu Sans and DejaVu Sans Bold (matplotlib's copies, the fonts
    of the PDF) advances no further than the bound says."""
    ft2font = pytest.importorskip("matplotlib.ft2font")
    dirs = typst_pdf._font_dirs()
    if not dirs:
        pytest.skip("matplotlib's DejaVu fonts not found")
    import warnings
    for name, bold in (("DejaVuSans.ttf", False), ("DejaVuSans-Bold.ttf", True)):
        font = ft2font.FT2Font(f"{dirs[0]}/{name}")
        over = []
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            for cp in font.get_charmap():
                adv = font.load_char(cp, flags=ft2font.LoadFlags.NO_SCALE).horiAdvance / font.units_per_EM
                if adv > _em_width(chr(cp), bold):
                    over.append((hex(cp), adv))
        assert not over, f"{name}: {over[:10]}"
    assert _em_width("0.5", False) == pytest.approx(0.64 + 0.40 + 0.64)


# one page of tables: rows merged column by column (_by_columns) next to each kind of row
PAGE = "<html><head><title>t</title></head><body><section>" + "".join([
    # 10 rows: a chunk of 7 and one of 3, equal shared columns (one curve a chunk)
    _table("compact wide", ["Pos.", "φ, °"] + [f"M<sub>Φ{k}</sub>" for k in range(2, 8)], _numbers(10, 8, 4)),
    # a pair of plan tables: markup in the cells (sub/superscripts, a bar), a wrapped header
    '<div class="position"><div class="tables2"><div>'
    + _table("compact", ["Vector", "Segment", "Length of the segment on the drawing, mm", "Value"],
             [[f"a<sub>B{k}</sub><sup>τ</sup>", f"πs₂{k}", "82.2", "4.112"] for k in range(9)],
             caption="Acceleration plan")
    + "</div><div>"
    + _table("compact wide", ["Вектор", "Отрезок", "Длина, мм", "Значение"],
             [[f"<span class='vec'>ab</span><sub>{k}</sub>", "Щ", "-0.5", "1e-05"] for k in range(5)])
    + "</div></div></div>",
    # an auto row (a long number in groups of digits, which wraps) between chunks, not
    # compact; an empty cell splits a run
    _table("wide", [f"c{k}" for k in range(6)],
           _numbers(4, 6, 5) + [["1234567890 1234567890 1234567890 1234567890"] + ["1"] * 5]
           + _numbers(3, 6, 6) + [["", "2", "3", "4", "5", "6"]] + _numbers(2, 6, 7)),
    # text columns (auto width): a curve in each cell
    '<table class="kv"><tr><th>a</th><td>x</td></tr></table>',
    _table("", ["name", "value"], [[f"link {k}", f"{k * 1.5:.2f}"] for k in range(6)]),
]) + "</section></body></html>"


def _pixels(src: str, tmp_path):
    import io

    import numpy as np
    from PIL import Image
    (tmp_path / "p.typ").write_text(src, encoding="utf-8")
    pages = typst.compile(str(tmp_path / "p.typ"), root=str(tmp_path), font_paths=typst_pdf._font_dirs(),
                          format="png", ppi=100)
    pages = pages if isinstance(pages, list) else [pages]
    return [np.asarray(Image.open(io.BytesIO(p)).convert("L"), dtype=int) for p in pages]


def test_rows_by_columns_draw_the_same_page(tmp_path, monkeypatch):
    """The rows merged column by column: the same page, pixel for pixel, as one table row
    a row (rendered by Typst at 100 ppi), but for the anti-aliasing of the rules."""
    src, _ = to_typst(PAGE, "en")
    h = "0.8em + 0.25em + 1.6mm"
    assert f"rows: ({h}, 7 * ({h}), 3 * ({h}),)" in src           # the header, chunks of 7 and 3
    assert "2 * (0.8em + 0.25em + 2.1mm)" in src                  # 2 rows after the empty cell
    assert '"0\\n1\\n2\\n3\\n4\\n5\\n6"' in src          # a column's values one string
    assert src.count("#_rules") > src.count("#let _rules")
    # a header that may wrap in its shared column stays auto, with PREAMBLE's leading
    plan = src[src.index("Acceleration plan"):]
    # (on a page of its own: one chunk, no page to break)
    assert plan[plan.index("rows: ("):].startswith(f"rows: (auto, 9 * ({h}),)")
    assert plan[plan.index("table.header("):].startswith(
        'table.header(table.cell(fill: rgb("#eeeeee"), align: center)[#set par(leading: 0.3em)')
    monkeypatch.setattr(typst_pdf, "_CHUNK", 0)
    rows, _ = to_typst(PAGE, "en")
    assert "_rules" not in rows and "7 * (" not in rows
    a, b = _pixels(src, tmp_path), _pixels(rows, tmp_path)
    assert len(a) == len(b) == 2                                 # the position: a page of its own
    import numpy as np
    d = np.concatenate([abs(x - y).ravel() for x, y in zip(a, b)])
    assert (d > 0).sum() > 0                                     # not the same source
    assert (d > 8).sum() == 0, f"{(d > 8).sum()} pixels differ by more than anti-aliasing"
    assert (d > 0).sum() < 1e-3 * d.size
