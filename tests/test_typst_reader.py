"""The PDF's HTML reader (tmm_cli/report/typst_pdf._read, two regular expressions) gives
the tree Python's html.parser gives, on hand-made HTML with the awkward parts (character
references, quoted '>', comments, void and self-closed elements, stray and missing end
tags, upper case) and on the reports of example tasks in the three languages; and the
Typst source made from either tree is the same."""
from __future__ import annotations

import random
import re
from html.parser import HTMLParser
from pathlib import Path

import pytest

from tmm_cli.report import typst_pdf
from tmm_cli.report.typst_pdf import _VOID, _Node, _read

ROOT = Path(__file__).resolve().parents[1]


class _Reference(HTMLParser):
    """The tree as html.parser builds it (the reader used before)."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.root = _Node("#root", {})
        self.stack = [self.root]

    def handle_starttag(self, tag, attrs):
        node = _Node(tag, dict(attrs))
        self.stack[-1].append(node)
        if tag not in _VOID:
            self.stack.append(node)

    def handle_startendtag(self, tag, attrs):
        self.stack[-1].append(_Node(tag, dict(attrs)))

    def handle_endtag(self, tag):
        for k in range(len(self.stack) - 1, 0, -1):
            if self.stack[k].tag == tag:
                del self.stack[k:]
                return

    def handle_data(self, data):
        self.stack[-1].append(data)


def reference(html: str) -> _Node:
    p = _Reference()
    p.feed(html)
    p.close()
    return p.root


def dump(node) -> object:
    """The tree as plain data; adjacent texts joined (html.parser may split a text)."""
    kids = []
    for c in node:
        if isinstance(c, str):
            if kids and isinstance(kids[-1], str):
                kids[-1] += c
            else:
                kids.append(c)
        else:
            kids.append(dump(c))
    return (node.tag, sorted(node.attrs.items(), key=lambda kv: kv[0]), kids)


HAND = """<!DOCTYPE html><html lang="ru"><head><meta charset="utf-8"><title>A &amp; B</title></head>
<BODY class="x">
<!-- a comment <p>not a tag</p> -->
<h2 id="s1" data-k='a"b'>1. Kinematics &mdash; ω&#8321; &#x3c9; &lt;p&gt;</h2>
<p class="note formula">a < b and c > d, x&nbsp;=&nbsp;5<br/>next<br>line<img data-svg="3" alt=""></p>
<table class="compact"><caption>T</caption><thead><tr><th colspan=2>h</th></tr></thead>
<tbody><tr><td class="num">1.5</td><td title="a > b">x<sub>2</sub></td></tr>
<tr><td>unclosed<td>cells</tr></tbody></table>
<div class="pair"><div><p>one</div></p><span class="frac"><span>1</span><span>2</span></span></div>
<ul><li>a<li>b</ul></span></i>
<p>tail &unknown; &amp</p></BODY></html>"""


# the tag expression as it was (the attributes taken lazily, a character at a time)
_TAG_LAZY = re.compile(r"""<(?:([a-zA-Z][^\s/>]*)((?:[^>"']|"[^"]*"|'[^']*')*?)(/?)>"""
                       r"""|/([a-zA-Z][^\s/>]*)\s*>|!--.*?-->|[!?][^>]*>)""", re.S)


_SVG = re.compile(r"<svg\b.*?</svg>", re.S)


def cut_by_regex(html: str) -> tuple[str, list[str]]:
    """_cut_svgs as the regular expression _SVG does it (the code before)."""
    svgs = []

    def cut(m):
        svgs.append(m.group(0))
        return f'<img data-svg="{len(svgs) - 1}">'

    return _SVG.sub(cut, html), svgs


_SOUP = ["<", ">", "/", "/>", '"', "'", "=", " ", "\n", "a", "b1", "_", "é", "ω", "-", "!", "?", "&amp;",
         "<svg", "<svg>", "<SVG ", "<svgx", "<svg_", "<svgé", "<svg1", "</svg>", "</svg", "svg>", "<!--", "-->",
         "<p", "</p>", "<br/>", '<a href="x>y">', "<td class='n'>", "</td >", "<img data-svg=\"1\"/>",
         '<x a="/>" b=c/>', "<!DOCTYPE html>", "<?pi?>"]


def soup(rng: random.Random) -> str:
    return "".join(rng.choice(_SOUP) for _ in range(rng.randrange(0, 60)))


def test_the_tag_expression_and_the_figure_cut_are_as_before():
    """The possessive tag expression splits as the lazy one did; the figures are cut out by
    str.find where the regular expression _SVG found them (random tag soup)."""
    rng = random.Random(12)
    for _ in range(20000):
        h = soup(rng)
        assert typst_pdf._TAG.split(h) == _TAG_LAZY.split(h), h
        assert typst_pdf._cut_svgs(h) == cut_by_regex(h), h
    assert typst_pdf._TAG.split(HAND) == _TAG_LAZY.split(HAND)


def test_the_reader_is_html_parser_on_awkward_html():
    assert dump(_read(HAND)) == dump(reference(HAND))
    got = dump(_read(HAND))
    assert "A & B" in str(got) and "ω₁ ω <p>" in str(got) and "('title', 'a > b')" in str(got)


@pytest.mark.parametrize("name,lang", [("forging_sixbar", "ru"), ("cam_rocker", "en"),
                                       ("gears_shifted", "uk"), ("planetary_A", "en"),
                                       ("press_drive_train", "en")])
def test_the_reader_on_reports(name, lang, tmp_path, monkeypatch):
    import tmm_cli
    from tmm_cli.report import render_html, _figure_files
    monkeypatch.setenv("TMM_REPORT_JOBS", "1")
    task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
    html, ctx = render_html(tmm_cli.run(task), task, tmp_path, lang)
    html = _figure_files(ctx, html)[0]
    root, svgs = typst_pdf._parse(html)
    assert typst_pdf._cut_svgs(html) == cut_by_regex(html)
    cut = _SVG.sub(lambda m: "<img>", html)
    cut = re.sub(r"<(style|script)\b.*?</\1>", "", cut, flags=re.S | re.I)
    assert typst_pdf._TAG.split(cut) == _TAG_LAZY.split(cut)
    ref = reference(cut)
    # the same tree (the figures' placeholders aside: data-svg numbers)
    strip = re.compile(r"\('data-svg', '\d+'\)")
    assert strip.sub("", str(dump(root))) == str(dump(ref))
    # and the same Typst source from the same tree
    src = typst_pdf.to_typst(html, lang)[0]
    monkeypatch.setattr(typst_pdf, "_read", lambda h: reference(h))
    assert typst_pdf.to_typst(html, lang)[0] == src
    assert len(svgs) > 0 and "#heading" in src
