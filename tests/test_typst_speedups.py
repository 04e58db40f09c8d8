"""The PDF translator's faster helpers (tmm_cli/report/typst_pdf) give exactly what the
code before them gave: the advance bound of a text by a dict lookup per character."""
from __future__ import annotations

import random
import re

from tmm_cli.report import typst_pdf
from tmm_cli.report.typst_pdf import _ADV, _ADV_BOLD, _BOLD, _em_width


def em_width_before(text: str, bold: bool = False) -> float:
    """_em_width as it was written (a generator over the characters)."""
    if bold:
        return sum(_ADV_BOLD.get(ch) or em_width_before(ch) * _BOLD for ch in text)
    return sum(_ADV.get(ch) or (1.1 if ord(ch) < 0x1C4 or 0x370 <= ord(ch) < 0x460 else 2.0)
               for ch in text)


def test_em_width_is_the_sum_as_before():
    rng = random.Random(5)
    alphabet = (list(_ADV) + list(_ADV_BOLD) + [chr(c) for c in range(0x20, 0x500)]
                + ["中", "😀", "\u2003", "ÿ", "Ǆ", "Ѡ", "\u0460"])
    for _ in range(3000):
        text = "".join(rng.choice(alphabet) for _ in range(rng.randrange(0, 30)))
        for bold in (False, True):
            assert _em_width(text, bold) == em_width_before(text, bold), (text, bold)
    assert _em_width("") == 0 and _em_width("", True) == 0
    # the remembered advances of characters outside the tables are the computed ones
    assert typst_pdf._ADV_ALL["中"] == 2.0 and typst_pdf._ADV_BOLD_ALL["Ϗ"] == 1.1 * _BOLD


# the figure labels' reading as it was: the texts found from the end by slicing, then each
# label by a lazy regular expression (the labels of one style grouped in one text() call,
# the styles in the order of their first label, as typst_pdf groups them)
_LABEL_BEFORE = re.compile(r'<text x="(-?\d+(?:\.\d+)?)" y="(-?\d+(?:\.\d+)?)"([^>]*)>(.*?)</text>\s*'
                           r"|<text\b.*?</text>\s*", re.S)


def place_labels_before(texts: str, k: float, vw: float):
    kept, styles = [], {}
    for m in _LABEL_BEFORE.finditer(texts):
        x, y, attrs, inner = m.groups()
        st = typst_pdf._label_style(attrs, k) if x is not None else None
        body = typst_pdf._label_body(inner, k) if st is not None else None
        if body is None:
            kept.append(m.group(0))
        elif body:
            head, side, frac = st
            styles.setdefault(head, []).append(f"place(top + {side}, dx: {(float(x) - frac * vw) * k:.3f}pt, "
                                               f"dy: {float(y) * k:.3f}pt, {body})")
    placed = [("{" if head == "text(" else head + "{") + "; ".join(p) + ("}" if head == "text(" else "})")
              for head, p in styles.items()]
    return "".join(kept), placed


def label_region_before(svg: str) -> int:
    end = pos = svg.rindex("</svg>")
    start = end
    while True:
        t = svg.rfind("</text>", 0, pos)
        if t < 0 or svg[t + 7:pos].strip():
            break
        o = svg.rfind("<text", 0, t)
        if o < 0 or "<text" in svg[o + 5:t] or "</" in svg[o:t].replace("</tspan>", ""):
            break
        start = pos = o
    return start


_PIECES = ['<text x="10" y="20">A</text>', '<text x="-1.5" y="3.25" font-size="2.47" text-anchor="middle">ω</text>',
           '<text x="5" y="6" fill="#6b7b7c" font-style="italic">G<tspan dy="0.74" font-size="1.78">1</tspan></text>',
           '<text x="5" y="6" font-weight="bold">a &amp; b</text>', '<text x="1" y="2" text-anchor="end"> </text>',
           '<text x="1" y="2" transform="x">no</text>', '<text y="1" x="2">swapped</text>', "<text>plain</text>",
           '<text x="1" y="2"><a>x</a></text>', '<text x="1" y="2">a<</tspan>/b</text>', "<textPath>p</textPath>",
           '<text x="3" y="4">q</tspan></text>', "<</tspan>/", "</", "<text", "</text>", "<tspan>", "</tspan>",
           " ", "\n", "  \t", "<path d='M0 0'/>", "<g>", "</g>", "x", "<", "/", ">"]


def test_figure_labels_read_as_before():
    """_labels' region found in place and _place_labels' possessive expression give what
    the slicing and the lazy expression gave (random label soup)."""
    rng = random.Random(8)
    head = '<svg xmlns="http://www.w3.org/2000/svg" width="100pt" height="50pt" viewBox="0 0 100 50" ' \
           'font-family="DejaVu Sans">'
    for _ in range(6000):
        body = "".join(rng.choice(_PIECES) for _ in range(rng.randrange(0, 14)))
        svg = head + body + "</svg>"
        start = label_region_before(svg)
        end = svg.rindex("</svg>")
        kept, placed = place_labels_before(svg[start:end], 1.0, 100.0)
        want = (svg, "") if not placed else (svg[:start] + kept + svg[end:], "{" + "; ".join(placed) + "}")
        assert typst_pdf._labels(svg, 100.0) == want, svg
        assert typst_pdf._place_labels(body, 1.0, 100.0) == place_labels_before(body, 1.0, 100.0), body
