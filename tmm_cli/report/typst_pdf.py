"""report.pdf through Typst: the report's HTML (the one source of its content) is
translated element by element into Typst markup and compiled in-process by the
``typst`` package (a compiled Rust library: ~40x faster than laying out and painting
the same pages with weasyprint's Python engine).

The HTML of the report uses a small vocabulary (see templates/): headings h1-h4,
paragraphs, tables with th/td (td.num right-aligned numbers), caption, figure with an
inline <svg> and figcaption, sub/sup/b/i/code/br/span/a, ol/ul/li and a few <div>
classes (position: a page of its own; tables2/pair: side by side; failure: a red box;
task-groups: tables in a row), and a table cell's own background colour (a style
``background:#rrggbb``: the verdicts of the feedback pages, tmm_cli.feedback, whose PDF is
made by this writer too).  Anything else is rendered as its text content, so
nothing of the report is lost.  The figures stay vector graphics (Typst embeds SVG as
PDF drawing operators) and the text keeps DejaVu Sans (Cyrillic, Greek).
"""
from __future__ import annotations

import json
import math
import re
from contextlib import contextmanager
from functools import lru_cache
from pathlib import Path

__all__ = ["to_typst", "pdf_bytes"]

# ---------------------------------------------------------------- a small DOM
_VOID = {"meta", "br", "img", "hr", "input", "link", "col", "wbr"}


class _Node(list):
    """An element: its children (_Node | str) are its items."""
    __slots__ = ("tag", "attrs", "classes")

    def __init__(self, tag, attrs, classes=None):
        super().__init__()
        self.tag = tag
        self.attrs = attrs
        self.classes: frozenset[str] = (frozenset((attrs.get("class") or "").split())
                                        if classes is None else classes)

    def text(self) -> str:
        if len(self) == 1 and self[0].__class__ is str:
            return self[0]
        return "".join(c if isinstance(c, str) else c.text() for c in self)


_new_node = list.__new__

# a start tag (name, attributes, "/" of a self-closed one), an end tag, or a comment /
# declaration / processing instruction (skipped); the rest is text.  The attributes are
# runs of characters other than > " ' /, quoted values and a / not before >, taken
# possessively (no backtracking: each character can be read one way only)
_TAG = re.compile(r"""<(?:([a-zA-Z][^\s/>]*)((?:[^>"'/]++|"[^"]*+"|'[^']*+'|/(?!>))*+)(/?)>"""
                  r"""|/([a-zA-Z][^\s/>]*)\s*>|!--.*?-->|[!?][^>]*>)""", re.S)
# an attribute: its name, "=value" when it has one, the value (double-, single- or unquoted)
_ATTR = re.compile(r"""([^\s"'>/=]+)(\s*=\s*(?:"([^"]*)"|'([^']*)'|([^\s>]+)))?""")


def _table_parts(n: _Node, head: bool, rows: list) -> list[_Node]:
    """The rows of table ``n`` appended to ``rows`` in order, as (in the head, its td/th cells),
    through its thead, tbody and tfoot; its captions returned.  (A function of the module, not
    one nested in the writer's method: a nested one that calls itself is a reference cycle.)"""
    captions = []
    for c in n:
        if not isinstance(c, _Node):
            continue
        if c.tag == "caption":
            captions.append(c)
        elif c.tag == "thead":
            captions += _table_parts(c, True, rows)
        elif c.tag in ("tbody", "tfoot"):
            captions += _table_parts(c, False, rows)
        elif c.tag == "tr":
            rows.append((head, [k for k in c if isinstance(k, _Node) and k.tag in ("td", "th")]))
    return captions


def _read(html: str) -> _Node:
    """The element tree of the report's HTML (which tmm's templates write: well formed, no
    <script>/<style> left, no <svg>), read by two regular expressions: element names and
    attribute names lower-cased, character references resolved, void elements and
    self-closed ones without children, an end tag closing up to the nearest open element
    of its name (a stray one ignored) -- what html.parser gives, several times faster.
    The text is split at the tags in one call (text, then each tag's groups and the text
    after it); the elements with the same attribute text share one attribute dict and
    class set (read only); the nodes are made without calling __init__."""
    from html import unescape
    root = _Node("#root", {})
    stack = [root]
    kids = root                         # the open element (stack[-1])
    it = iter(_TAG.split(html))
    text = next(it)
    if text:
        kids.append(unescape(text) if "&" in text else text)
    seen: dict[str, tuple[dict, frozenset]] = {}
    low: dict[str, str] = {}            # element name -> lower case
    new, void = _new_node, _VOID
    for name, attrs, selfclose, end, text in zip(it, it, it, it, it):
        if name:
            tag = low.get(name)
            if tag is None:
                tag = low[name] = name.lower()
                if tag == "svg":              # kept whole, as text: cut out by _parse
                    raise AssertionError("svg must be cut out before parsing")
            got = seen.get(attrs)
            if got is None:
                at = {}
                if attrs and not attrs.isspace():
                    for a, eq, v2, v3, v4 in _ATTR.findall(attrs):
                        if eq:
                            v = v2 or v3 or v4
                            at[a.lower()] = unescape(v) if "&" in v else v
                        else:
                            at[a.lower()] = None
                got = seen[attrs] = (at, frozenset((at.get("class") or "").split()))
            node = new(_Node)
            node.tag = tag
            node.attrs, node.classes = got
            kids.append(node)
            if not selfclose and tag not in void:
                stack.append(node)
                kids = node
        elif end:
            tag = end if end == kids.tag else (low.get(end) or end.lower())
            if kids.tag == tag:               # the open element (never the root: "#root")
                stack.pop()
                kids = stack[-1]
            else:
                for k in range(len(stack) - 2, 0, -1):
                    if stack[k].tag == tag:
                        del stack[k:]
                        kids = stack[-1]
                        break
        if text:
            kids.append(unescape(text) if "&" in text else text)
    return root


_WPT = re.compile(r'\bwidth="([0-9.]+)pt"')


_STYLE = re.compile(r"<(style|script)\b.*?</\1>", re.S | re.I)


def _cut_svgs(html: str) -> tuple[str, list[str]]:
    """(the HTML with each inline <svg> element replaced by ``<img data-svg="k">``, the
    SVG texts): each ``<svg`` at a word's end up to the first ``</svg>`` after it (what
    the regular expression ``<svg\b.*?</svg>`` matches), found by ``str.find`` (the lazy regex steps through the
    figures' ~0.6 MB a character at a time)."""
    svgs: list[str] = []
    parts = []
    find = html.find
    pos = 0
    at = find("<svg")
    while at >= 0:
        nxt = html[at + 4:at + 5]
        if nxt and (nxt.isalnum() or nxt == "_"):       # not at a word's end (\b)
            at = find("<svg", at + 1)
            continue
        end = find("</svg>", at + 4)
        if end < 0:
            break
        end += 6
        parts.append(html[pos:at])
        parts.append(f'<img data-svg="{len(svgs)}">')
        svgs.append(html[at:end])
        pos = end
        at = find("<svg", end)
    if not svgs:
        return html, svgs
    parts.append(html[pos:])
    return "".join(parts), svgs


def _parse(html: str) -> tuple[_Node, list[str]]:
    html, svgs = _cut_svgs(html)
    html = _STYLE.sub("", html)
    return _read(html), svgs


# ---------------------------------------------------------------- markup
def _s(text: str) -> str:
    """A Typst string literal inserted into markup (no markup escaping to get wrong)."""
    return '#"' + text.replace("\\", "\\\\").replace('"', '\\"') + '"'


_WS = re.compile(r"\s+")
# inline elements that wrap their content in a Typst function
_WRAP = {"sub": "#sub", "sup": "#super", "b": "#strong", "strong": "#strong", "i": "#emph", "em": "#emph"}
_MM = 72 / 25.4                             # pt
# a table's text size (pt) and cell insets (mm: x, y), compact or not
_TABLE_STYLE = {False: (8.5, 1.8, 1.05), True: (7.5, 1.2, 0.8)}
_STRING = re.compile(r'#"(?:[^"\\]|\\.)*"')
# markup that keeps a line of text one line of the table's height (the line edges are fixed
# lengths: sub- and superscripts, bold, italics and a bar over it do not make it taller)
_LINE_MARKUP = re.compile(r"#(?:sub|super|strong|emph|overline)\[|\]")
# advances of DejaVu Sans in em, rounded up, by kind of character; any other Latin, Greek or
# Cyrillic one 1.1 (the widest, the capital shcha, is 1.094), the rest of Unicode 2.0; DejaVu Sans Bold
# within _BOLD times these (tests/test_typst_rows.py reads both fonts)
_ADV = {**dict.fromkeys("0123456789", 0.64), **dict.fromkeys(".,:;' |il", 0.40),
        **dict.fromkeys("-()[]/!", 0.42), **dict.fromkeys("+−×=<>", 0.84),
        **dict.fromkeys("abcdeghknopqsuvxyz", 0.64), **dict.fromkeys("fjrt", 0.42)}
_BOLD = 1.25
# DejaVu Sans Bold's advances of ASCII, Greek, Cyrillic and a few signs, in em rounded up to
# 0.01 (a header's cells; tests/test_typst_rows.py reads the font): data, dejavu_sans_bold.json
_ADV_BOLD = {ch: float(adv) for adv, chars in json.loads(
    (Path(__file__).with_name("dejavu_sans_bold.json")).read_text(encoding="utf-8"))["advances"].items() for ch in chars}


class _Advances(dict):
    """A character's advance bound, em (see _em_width): the given ones, any other by
    ``other(ch)``, remembered."""
    __slots__ = ("other",)

    def __init__(self, given, other):
        super().__init__(given)
        self.other = other

    def __missing__(self, ch):
        adv = self[ch] = self.other(ch)
        return adv


_ADV_ALL = _Advances(_ADV, lambda ch: 1.1 if ord(ch) < 0x1C4 or 0x370 <= ord(ch) < 0x460 else 2.0)
_ADV_BOLD_ALL = _Advances(_ADV_BOLD, lambda ch: _ADV_ALL[ch] * _BOLD)


def _em_width(text: str, bold: bool = False) -> float:
    """A bound of the advance of ``text`` in DejaVu Sans (regular or bold), in em: the sum of
    its characters' advances (_ADV, any other Latin, Greek or Cyrillic one 1.1, the rest
    2.0; bold ones _ADV_BOLD, any other _BOLD times the regular bound), in order."""
    return sum(map((_ADV_BOLD_ALL if bold else _ADV_ALL).__getitem__, text))

# the report's Typst preamble, in named parts (the explanatory note takes the parts it shares)
PREAMBLE_DOC = r"""#set document(title: TITLE, date: none)
"""  # the document's metadata
PREAMBLE_PAGE = r"""#set page(paper: "a4", margin: (top: 15mm, right: 14mm, bottom: 16mm, left: 18mm),
  footer: context align(right, text(size: 8pt, fill: rgb("#555555"),
    counter(page).display("1 / 1", both: true))))
"""  # the report's page: A4, margins, the page number in the footer
PREAMBLE_STYLE = r"""#set text(font: ("DejaVu Sans",), size: 9.5pt, fill: rgb("#111111"), lang: LANG, hyphenate: false)
#set par(leading: 0.42em, spacing: 0.55em, justify: false)
#set heading(numbering: (..n) => if n.pos().len() <= 2 { numbering("1.1.", ..n) })
#show heading: set block(sticky: true)
#show heading.where(level: 1): it => block(above: 6mm, below: 2mm, width: 100%,
  stroke: (bottom: 0.6pt + rgb("#888888")), inset: (bottom: 1.2pt), text(size: 13pt, it))
#show heading.where(level: 2): it => block(above: 4mm, below: 1.5mm, text(size: 11pt, it))
#show heading.where(level: 3): it => block(above: 3mm, below: 1mm, text(size: 10pt, it.body))
#set table(stroke: 0.5pt + rgb("#999999"))
#show table: set text(top-edge: 0.8em, bottom-edge: -0.25em)
#show math.equation: set text(top-edge: "bounds")
#show table: set par(leading: 0.3em)
#let num(x) = align(right, x)
#let note(x) = text(size: 8.5pt, fill: rgb("#444444"), x)
"""  # type, paragraphs, headings, tables, the small helpers
PREAMBLE_CAP = r"""#let cap(x) = block(below: 1mm, sticky: true, strong(x))
"""  # a table's caption (the note numbers its own)
PREAMBLE_KEEP = r"""#let keep(x) = block(sticky: true, above: 0.55em, below: 0.55em, x)
"""  # a block kept with what follows
PREAMBLE_WF = r"""#let wf(x) = block(above: 0.8em, below: 0.8em, x)
"""  # a worked formula (the note numbers its own)
PREAMBLE_BREAK = r"""#let section-break = { block(breakable: false, height: 50%, above: 4mm, below: 0pt); v(-50%) }
"""  # a section's break: a new page when less than half of one is left
PREAMBLE_FIG = r"""#let fig(file, w, c, labels: none) = block(above: 2mm, below: 3mm, breakable: false, width: 100%,
  align(center, { if labels == none { layout(size => image(file, width: if type(w) == length { calc.min(w, size.width) } else { w })) } else {
    block(width: w, { image(file, width: w); set text(top-edge: "baseline", bottom-edge: "baseline"); labels }) }
    if c != none { v(1mm, weak: true); text(size: 8.5pt, fill: rgb("#333333"), c) } }))
"""  # a figure with its caption (the note numbers its own)
PREAMBLE = "\n" + "".join((PREAMBLE_DOC, PREAMBLE_PAGE, PREAMBLE_STYLE, PREAMBLE_CAP, PREAMBLE_KEEP, PREAMBLE_WF,
                               PREAMBLE_BREAK, PREAMBLE_FIG))
# the page's text width (A4 less the margins of PREAMBLE), pt
_TEXT_WIDTH = (210 - sum(map(float, re.search(r"right: ([\d.]+)mm, bottom: [\d.]+mm, left: ([\d.]+)mm",
                                              PREAMBLE).groups()))) * _MM
# and its height, pt
_TEXT_HEIGHT = (297 - sum(map(float, re.search(r"margin: \(top: ([\d.]+)mm, right: [\d.]+mm, bottom: ([\d.]+)mm",
                                               PREAMBLE).groups()))) * _MM
_HPT = re.compile(r'\bheight="([0-9.]+)pt"')
# a heading's markup and the space above it (PREAMBLE's show rules), by its level
_ABOVE = re.compile(r"#heading\(level: (\d)")
_HEADING_ABOVE = dict(re.findall(r"heading\.where\(level: (\d)\): it => block\(above: ([\d.]+mm)", PREAMBLE))


class _Writer:
    def __init__(self, svgs: list[str], fig_dir: Path | None):
        self.svgs = svgs
        self.fig_dir = fig_dir
        self.files: dict[str, bytes] = {}
        self.after_section = False
        self.led = False                    # a div.position led by a heading: no page break of its own
        self.math_done = False              # a worked formula written from its MathML: skip its HTML copy
        self.in_pair = 0
        self.whole = False                  # inside a block kept on one page (not breakable)
        self.width: float | None = _TEXT_WIDTH   # pt free for a block here; None: not known
        self.texts: dict[str, str] = {}     # a text node's markup (see _text)
        self.cells: dict[str, tuple[str, str]] = {}     # a table cell's one text: stripped, markup
        self.ems: dict[str, float] = {}     # _em_width of a (regular) cell text

    @contextmanager
    def _inside(self, narrower=None):
        """``self.width`` for the blocks made inside: ``narrower(width)``, or not known
        (None) where ``narrower`` is None; put back after."""
        width = self.width
        self.width = narrower(width) if narrower is not None and width is not None else None
        try:
            yield
        finally:
            self.width = width

    def _text(self, text: str) -> str:
        """The markup of a text node (white space runs one space; "" for ""), remembered."""
        m = self.texts.get(text)
        if m is None:
            t = _WS.sub(" ", text)
            m = self.texts[text] = _s(t) if t else ""
        return m

    # inline content -> markup
    def inline(self, node) -> str:
        """The markup of an element's children (or of any sequence of nodes)."""
        out = []
        texts = self.texts
        for c in node:
            if isinstance(c, str):
                m = texts.get(c)
                out.append(self._text(c) if m is None else m)
                continue
            tag = c.tag
            wrap = _WRAP.get(tag)
            if wrap is not None:
                out.append(f"{wrap}[{self.inline(c)}]")
            elif tag == "code":
                out.append(f"#raw({_s(c.text())[1:]})")
            elif tag == "br":
                out.append("#linebreak()")
            elif tag == "span" and "mml" in c.classes:
                # a worked formula: its MathML as Typst mathematics (spaced as mathematics is)
                m = next((k for k in c if isinstance(k, _Node) and k.tag == "math"), None)
                if m is not None:
                    out.append(f"#text(size: 11pt)[$display({_math(m)})$]")
                    self.math_done = True
            elif tag == "span" and "mfb" in c.classes and self.math_done:
                self.math_done = False      # its HTML copy (print of the browser): the mathematics is above
            elif tag == "span" and "mo" in c.classes and c.text() in _MO:
                t = c.text()            # an operator between words: spaced (',' and ';' after)
                out.append(f"{t} " if t in ",;" else f" {self._text(t)} ")
            elif tag == "span" and "frac" in c.classes:
                num, den = (k for k in c if isinstance(k, _Node))
                out.append(f"$display(frac(#[{self.inline(num)}], #[{self.inline(den)}]))$")
            elif tag == "span" and "vec" in c.classes:
                out.append(f"#overline[{self.inline(c)}]")
            elif tag == "span" and "formula" in c.classes:
                out.append(f'#text(font: "DejaVu Serif", size: 11pt)[{self.inline(c)}]')
            elif tag == "img" and "data-svg" in c.attrs:
                out.append(self.figure_image(int(c.attrs["data-svg"]), None))
            elif tag in ("table", "div", "p", "ul", "ol"):
                with self._inside():                        # in a cell or an item: not known
                    out.append("\n" + self.block(c) + "\n")
            else:
                out.append(self.inline(c))
        return "".join(out)

    def _drawn_height(self, node) -> float:
        """A bound of the height of a block's figures with their captions and a heading,
        pt (the figures' heights in pt, the captions' lines at 8.5 pt from their
        characters' advance bounds)."""
        h = 12 * _MM                                             # the heading
        for c in node:
            if not isinstance(c, _Node):
                continue
            if c.tag == "img" and "data-svg" in c.attrs:
                m = _HPT.search(self.svgs[int(c.attrs["data-svg"])][:400])
                h += (float(m.group(1)) if m else _TEXT_HEIGHT) + 5 * _MM      # with the block's spacing
            elif c.tag == "figcaption":
                h += (_em_width(c.text()) * 8.5 // _TEXT_WIDTH + 1) * 8.5 * 1.25 + _MM
            else:
                h += self._drawn_height(c) - 12 * _MM
        return h

    def figure_image(self, k: int, caption: str | None) -> str:
        svg = self.svgs[k]
        if "xmlns=" not in svg[:300]:
            svg = svg.replace("<svg", '<svg xmlns="http://www.w3.org/2000/svg"', 1)
        name = f"fig-{k:03d}.svg"
        w = _WPT.search(svg[:400])
        width = f"{w.group(1)}pt" if w else "100%"
        labels = ""
        if w and self.width is not None and float(w.group(1)) <= self.width - 1:
            svg, labels = _labels(svg, float(w.group(1)))     # drawn at its width: labels placed
        self.files[name] = svg.encode("utf-8")
        return f'#fig("{name}", {width}, {caption if caption else "none"}{", labels: " + labels if labels else ""})'

    # block content
    def block(self, node) -> str:
        tag, cls = node.tag, node.classes
        if tag in ("h1", "h2", "h3", "h4"):
            body = self.inline(node).strip()
            if tag == "h1":
                return f"#block(below: 2mm, text(size: 16pt, weight: \"bold\")[{body}])"
            level = int(tag[1]) - 1
            numbering = ", numbering: none" if ("nonum" in cls or level == 3) else ""
            outlined = ", outlined: false" if level >= 2 else ""
            return f"#heading(level: {level}{numbering}{outlined})[{body}]"
        if tag == "p":
            body = self.inline(node).strip()
            if "formula" in cls:
                return f'#pad(left: 6mm, text(font: "DejaVu Serif", size: 11pt)[{body}])'
            if "note" in cls:
                return f"#note[{body}]"
            if "sub" in cls:
                return f'#text(fill: rgb("#444444"))[{body}]'
            if "what" in cls:
                return f'#text(weight: "bold", fill: rgb("#8e2a20"))[{body}]'
            return f"#par[{body}]"
        if tag == "table":
            return self.table(node)
        if tag == "figure":
            cap = next((c for c in node if isinstance(c, _Node) and c.tag == "figcaption"), None)
            imgs = [c for c in node if isinstance(c, _Node) and c.tag == "img" and "data-svg" in c.attrs]
            capm = f"[{self.inline(cap).strip()}]" if cap is not None else None
            parts = [self.figure_image(int(im.attrs["data-svg"]), capm if i == len(imgs) - 1 else None)
                     for i, im in enumerate(imgs)]
            return "\n".join(parts)
        if tag in ("ol", "ul"):
            items = [c for c in node if isinstance(c, _Node) and c.tag == "li"]
            fn = "enum" if tag == "ol" else "list"
            with self._inside():                            # indented: not known
                return f"#{fn}(" + ", ".join(f"[{self.inline(li).strip()}]" for li in items) + ")"
        if tag == "section":
            body = self.blocks(node)
            # a section starts a new page unless the last one's tail would leave it nearly empty
            brk = "#section-break\n" if self.after_section else ""
            self.after_section = True
            return brk + body
        if tag == "div" and "position" in cls:
            # a position on a page of its own; where its drawings are taller than a page
            # (the groups of a six-bar and Zhukovsky's lever) it breaks between them: each
            # figure stays whole, the heading with the first
            fits = self._drawn_height(node) <= _TEXT_HEIGHT
            led, self.led = self.led, False
            whole, self.whole = self.whole, fits
            body = self.blocks(node)
            self.whole = whole
            brk = "" if led else "#pagebreak(weak: true)\n"
            return brk + f"#block(breakable: {'false' if fits else 'true'})[\n" + body + "\n]"
        if tag == "div" and ("tables2" in cls or "pair" in cls):
            kids = [c for c in node if isinstance(c, _Node)]
            n = max(len(kids), 1)
            self.in_pair += 1
            with self._inside(lambda w: (w - _MM * 3 * (n - 1)) / n):
                parts = [self.blocks(k) if k.tag == 'div' else self.block(k) for k in kids]
            self.in_pair -= 1
            if self.whole:
                # on one page: side by side in a stack, each laid out once (a grid's auto row
                # lays its cells out twice, measured first); the same page as the grid's
                width = f"(100% - {3 * (n - 1)}mm) / {n}"
                return "#stack(dir: ltr, spacing: 3mm, " + ", ".join(f"block(width: {width})[{p}]" for p in parts) + ")"
            return f"#grid(columns: ({', '.join(['1fr'] * n)}), gutter: 3mm, {', '.join(f'[{p}]' for p in parts)})"
        if tag == "div" and "task-groups" in cls:
            kids = [c for c in node if isinstance(c, _Node)]
            # boxes in a line: each is laid out in the width of the line, less its inset
            with self._inside(lambda w: w - 4 * _MM):
                return "".join(f"#box(inset: (right: 4mm))[{self.block(k)}]" for k in kids)
        if tag == "div" and "wf" in cls:           # a line of worked formulas: room for fractions
            return f"#wf[{self.blocks(node)}]"
        if tag == "div" and "failure" in cls:
            with self._inside(lambda w: w - 8 * _MM - 1.5):
                body = self.blocks(node)
            return (f'#block(stroke: 1.5pt + rgb("#b03a2e"), fill: rgb("#fdf2f0"), inset: (x: 4mm, y: 3mm), '
                    f'width: 100%)[{body}]')
        if tag == "footer":
            # in the bottom margin of the page the text ends on, level with the page number: it
            # takes no room in the flow (as a line after the last figure it was left alone on a
            # page of its own when that figure filled the page)
            return (f'#place(bottom + left, dy: 6.95mm, text(size: 8pt, fill: rgb("#666666"))'
                    f'[{self.blocks(node)}])')
        if tag in ("div", "header", "nav", "body", "html", "#root", "main", "article", "li"):
            return self.blocks(node)
        if tag in ("head", "title", "meta", "style", "script"):
            return ""
        return f"#par[{self.inline(node).strip()}]"

    def blocks(self, node) -> str:
        """Children of a block element: runs of inline content become paragraphs.  A heading
        and the paragraphs after it stick to the next block (a figure, a table, a position's
        page): a heading never ends a page."""
        out, run = [], []
        led = False                                     # after a heading, paragraphs only since
        led_at = 0                                      # where in out that heading is

        def flush():
            body = "".join(run).strip()
            if body and body.replace('#" "', "").strip():
                out.append(f"#keep[#par[{body}]]" if led else f"#par[{body}]")
            run.clear()

        for c in node:
            if isinstance(c, str):
                if run or (c and not c.isspace()):      # (\s is str.isspace)
                    run.append(self._text(c))
                continue
            if c.tag in ("sub", "sup", "b", "strong", "i", "em", "code", "br", "span", "a"):
                run.append(self.inline((c,)))
                continue
            if c.tag == "img" and "data-svg" in c.attrs:
                flush()
                out.append(self.figure_image(int(c.attrs["data-svg"]), None))
                led = False
                continue
            flush()
            self.led = led and c.tag == "div" and "position" in c.classes
            b = self.block(c)
            self.led = False
            if b and led and c.tag == "p":
                b = f"#keep[{b}]"
            else:
                if b and led and c.tag == "table" and "breakable: false)" in b[:200]:
                    # a short table kept whole: its heading and the paragraphs under that in
                    # its block (Typst's sticky heading stays behind when an unbreakable block
                    # after it goes to the next page), the block spaced above as the heading
                    lead = _ABOVE.match(out[led_at]) if led_at < len(out) else None
                    above = f", above: {_HEADING_ABOVE[lead.group(1)]}" if lead else ""
                    b = (f"#block(breakable: false, width: 100%{above})[\n" + "\n".join(out[led_at:] + [b])
                         + "\n]")
                    del out[led_at:]
                if c.tag in ("h2", "h3", "h4") or (b and c.tag != "p"):
                    led = c.tag in ("h2", "h3", "h4")
                    led_at = len(out)
            if b:
                out.append(b)
        flush()
        return "\n".join(out)

    @staticmethod
    def widths(rows, ncols: int) -> list[str]:
        """Columns of a full-width table: text columns (a cell of more than a few words)
        share the free width, the others fit their content (as a browser lays out
        `width: 100%`); all equal when there is no text column.  ``rows``: per row its
        cells' (node, colspan, rowspan, stripped text, markup or None)."""
        text = [False] * ncols
        for r in rows:
            for j, (c, _, _, t, _) in enumerate(r[:ncols]):
                if len(t) > 14 and "num" not in c.classes:
                    text[j] = True
        if not any(text):
            return ["1fr"] * ncols
        return ["1fr" if t else "auto" for t in text]

    def fit(self, rows, nhead: int, ncols: int, compact: bool, kinds: list[str]
            ) -> tuple[tuple[float, float, float], list[str]]:
        """The table's (font size pt, x inset mm, y inset mm) and its columns: its style and
        ``kinds`` where its body cells (numbers, which do not wrap) fit the free width side
        by side; else the columns each as wide as its cells ("auto": equal shares would
        leave the widest numbers too little) and, where even that does not fit, the font
        and insets smaller (never below 0.6 of the style). A table of 19 columns of loads
        per position had its numbers overrun their cells into the next ones. ``rows`` as in
        :meth:`fixed_rows`."""
        style = _TABLE_STYLE[compact]
        size, ix, iy = style
        if self.width is None or nhead >= len(rows):
            return style, kinds
        need = [0.0] * ncols                # em of each column's widest one-column body cell
        for i, r in enumerate(rows):
            j = 0
            for c, span, _, t, _ in r:
                if span == 1 and j < ncols and t:
                    # a header's longest word (bold) too: the Russian "guide," once ran out of its column
                    need[j] = max(need[j], self.unbroken(t) if i >= nhead else
                                  max(_em_width(w, True) for w in t.split()))
                j += span
        free = self.width * 0.97
        pad = 2 * ix * _MM
        if all(k == "1fr" for k in kinds):
            if ncols * (max(need) * size + pad) <= free:
                return style, kinds
            kinds = ["auto"] * ncols
        fixed = [n for n, k in zip(need, kinds) if k == "auto"]
        total = sum(fixed) * size + len(fixed) * pad
        if total <= free:
            return style, kinds
        k = max(free / total, 0.6)
        return (math.floor(size * k * 10) / 10, round(ix * k, 2), iy), kinds

    def fixed_rows(self, rows, nhead: int, one_line: list[bool], ncols: int, kinds: list[str],
                   style: tuple[float, float, float]) -> str:
        """The ``rows:`` argument giving each row (header or body) that is one line of text
        in every cell its height outright: Typst then lays its cells out once instead of measuring them
        first (an auto row), ~0.2 s of the forging report's compilation. The height is the
        one an auto row gets (the table's line edges 0.8em + 0.25em and the cell insets);
        a row is fixed only where no cell of it can wrap, i.e. where a bound of the
        table's width (DejaVu Sans advances, rounded up; bold ones for a header's cells)
        fits the width free for it.
        ``rows``: per row its cells' (node, colspan, rowspan, stripped text, markup or None).
        The tracks, one a row ("auto" or the height); None when no row qualifies or the
        free width is not known here."""
        if self.width is None or nhead >= len(rows) or not any(one_line[nhead:]):
            return None
        size, ix, iy = style
        pad = 2 * ix * _MM
        need = [0.0] * ncols                # a bound of each column's natural width, pt
        spans = []
        est = []                            # per row: (first column, last + 1, bound) of its cells
        ems = self.ems
        for r in rows:
            j, row = 0, []
            for c, span, rspan, t, _ in r:
                if rspan > 1:
                    return None
                if not t:
                    w = 0.0
                elif c.tag == "th":
                    w = _em_width(t, True) * size + pad
                else:
                    em = ems.get(t)
                    if em is None:
                        em = ems[t] = _em_width(t)
                    w = em * size + pad
                if span == 1 and j < ncols:
                    need[j] = max(need[j], w)
                else:
                    spans.append((j, min(j + span, ncols), w))
                row.append((j, min(j + span, ncols), w))
                j += span
            est.append(row)
        for a, b, w in spans:               # a spanning cell widens its last column
            if b > a and w > sum(need[a:b]):
                need[b - 1] += w - sum(need[a:b])
        free = self.width * 0.97            # strokes and rounding
        auto = sum(n for n, k in zip(need, kinds) if k == "auto")
        nfr = sum(1 for k in kinds if k == "1fr")
        if auto > free or (nfr and auto >= free):
            return None                     # auto columns would be shrunk: cells may wrap
        share = (free - auto) / nfr if nfr else 0.0
        # an auto column is at least as wide as its widest cell, a shared one as wide as its
        # share whatever its cells (a header may wrap in it)
        col = [n if k == "auto" else share for n, k in zip(need, kinds)]
        h = f"0.8em + 0.25em + {2 * iy}mm"   # as Typst sums an auto row
        out = []
        for i, row in enumerate(est):
            ok = (one_line[i] and any(w for _, _, w in row)
                  and all(w <= sum(col[a:b]) for a, b, w in row))
            out.append(h if ok else "auto")
        return out if h in out else None

    def unbroken(self, t: str) -> float:
        """em of the widest part of ``t`` that cannot wrap (its longest word; a number is
        one word)."""
        em = self.ems.get(t)
        if em is None:
            em = self.ems[t] = _em_width(t)
        if " " in t:
            return min(em, max(_em_width(w) for w in t.split()))
        return em

    def split_wide(self, node) -> list | None:
        """A table of one-cell columns (no spans) too wide for the page at 0.8 of its style's
        font (a per-position table of ~20 columns of numbers): its columns in parts that fit
        at its style, each part a table repeating the leading columns (the position and its
        angle for a table of 12 columns or more, else the first); None when it fits (then
        :meth:`fit` sizes it) or is not such a table."""
        if self.width is None:
            return None
        head, body, other = [], [], []
        for c in node:
            if not isinstance(c, _Node):
                continue
            if c.tag in ("thead", "tbody", "tfoot"):
                for tr in c:
                    if isinstance(tr, _Node) and tr.tag == "tr":
                        (head if c.tag == "thead" else body).append(tr)
            elif c.tag == "tr":
                body.append(c)
            else:
                other.append(c)
        cells = [[k for k in tr if isinstance(k, _Node) and k.tag in ("td", "th")] for tr in head + body]
        if not body or not cells or any(k.attrs.get("colspan") or k.attrs.get("rowspan") for r in cells for k in r):
            return None
        ncols = len(cells[0])
        if ncols < 4 or any(len(r) != ncols for r in cells):
            return None
        size, ix, _ = _TABLE_STYLE["compact" in node.classes]
        need = [0.0] * ncols
        for r in cells[len(head):]:
            for j, k in enumerate(r):
                need[j] = max(need[j], self.unbroken(k.text().strip()))
        free = self.width * 0.97
        col = [n * size + 2 * ix * _MM for n in need]          # at the style
        if sum(col) * 0.8 <= free:          # fits at 0.8 of the font or more: one table
            return None
        keep = 2 if ncols >= 12 else 1
        groups, cur, w0 = [], [], sum(col[:keep])
        for j in range(keep, ncols):
            if cur and w0 + sum(col[i] for i in cur) + col[j] > free:
                groups.append(cur)
                cur = []
            cur.append(j)
        groups.append(cur)
        # as many parts as that takes, of about equal widths (not 15 columns and then 4)
        target = sum(col[keep:]) / len(groups)
        even, cur = [], []
        for j in range(keep, ncols):
            w = sum(col[i] for i in cur)
            if cur and len(even) < len(groups) - 1 and w + col[j] / 2 > target:
                even.append(cur)
                cur = []
            cur.append(j)
        even.append(cur)
        if len(even) == len(groups) and all(w0 + sum(col[i] for i in g) <= free for g in even):
            groups = even
        parts = []
        for g, cols in enumerate(groups):
            take = list(range(keep)) + cols
            t = _Node("table", node.attrs, node.classes)
            if g == 0:
                t.extend(other)
            for tag, trs in (("thead", head), ("tbody", body)):
                if not trs:
                    continue
                sec = _Node(tag, {}, frozenset())
                for tr in trs:
                    row = _Node("tr", tr.attrs, tr.classes)
                    ks = [k for k in tr if isinstance(k, _Node) and k.tag in ("td", "th")]
                    row.extend(ks[i] for i in take)
                    sec.append(row)
                t.append(sec)
            parts.append(t)
        return parts

    def table(self, node) -> str:
        parts = self.split_wide(node)
        if parts is not None:
            return "\n".join(self.table(t) for t in parts)
        rows, caption = [], None
        compact = "compact" in node.classes
        kv = "kv" in node.classes
        wide = "wide" in node.classes or self.in_pair > 0
        for c in _table_parts(node, False, rows):
            caption = self.inline(c).strip()
        # per row: its cells' (node, colspan, rowspan, stripped text, markup of a cell that is
        # one text, else None), that of one text remembered (numbers recur from table to table)
        info = []
        known = self.cells
        for _, r in rows:
            row = []
            for c in r:
                at = c.attrs
                span, rspan = at.get("colspan"), at.get("rowspan")
                if len(c) == 1 and c[0].__class__ is str:
                    x = c[0]
                    got = known.get(x)
                    if got is None:             # (inline(c).strip() is the text's markup)
                        got = known[x] = (x.strip(), self._text(x))
                    row.append((c, int(span) if span else 1, int(rspan) if rspan else 1) + got)
                else:
                    row.append((c, int(span) if span else 1, int(rspan) if rspan else 1, c.text().strip(), None))
            info.append(row)
        ncols = max((sum(x[1] for x in r) for r in info), default=1)
        nhead = 0
        for head, r in rows:
            if head or all(c.tag == "th" for c in r):
                nhead += 1
            else:
                break
        # columns whose body cells are all numbers (or empty) are right-aligned as a whole:
        # a plain cell is cheaper to lay out than a table.cell with its own alignment
        right = [True] * ncols
        for r in info[nhead:]:
            for j, (c, _, _, t, _) in enumerate(r[:ncols]):
                if c.tag != "td" or (t and "num" not in c.classes):
                    right[j] = False
        if not rows[nhead:]:
            right = [False] * ncols
        cells = []          # per row: its cells' markup
        bare = []           # per row: the same where each cell is plain text of one column
        one_line = []       # per row: every cell one line of text (or empty)
        with self._inside():                    # in a cell: the width not known
            for i, r in enumerate(info):
                plain = True
                row, row_bare = [], len(r) == ncols
                for j, (c, span, rspan, _, body) in enumerate(r):
                    if body is None:
                        body = self.inline(c).strip()
                    args = []
                    if span > 1:
                        args.append(f"colspan: {span}")
                    if rspan > 1:
                        args.append(f"rowspan: {rspan}")
                    if c.tag == "th":
                        if kv and i >= nhead:
                            args.append('fill: rgb("#f4f4f4")')
                        else:
                            args.append('fill: rgb("#eeeeee"), align: center')
                            body = f"#strong[{body}]"
                    elif "num" in c.classes and not (j < ncols and right[j]):
                        args.append("align: right")
                    if "style" in c.attrs:     # a cell's own colour (the feedback page's verdicts)
                        bg = _BACKGROUND.search(c.attrs["style"] or "")
                        if bg:
                            args.append(f'fill: rgb("{bg.group(1)}")')
                    if body.startswith('#"') and body.endswith('"') and body.count('#"') == 1:
                        cell = body[1:]                 # a plain string: no markup to parse
                    else:
                        cell = f"[{body}]"
                        plain = plain and not _LINE_MARKUP.sub("", _STRING.sub("", body))
                    row.append(f"table.cell({', '.join(args)}){cell if cell[0] == '[' else f'[#{cell}]'}"
                               if args else cell)
                    row_bare = row_bare and not args and bool(body) and cell != '""'
                cells.append(row)
                bare.append(row if row_bare else None)
                one_line.append(plain)
        nhead_cells = sum(len(r) for r in cells[:nhead])
        kinds = self.widths(info[nhead:], ncols) if wide else ["auto"] * ncols
        style, kinds = self.fit(info, nhead, ncols, compact, kinds)
        pt, ix, iy = style
        size = f"{pt}pt"
        inset = f"(x: {ix}mm, y: {iy}mm)"
        cols = f"({', '.join(kinds)})" if wide else str(ncols)
        tracks = self.fixed_rows(info, nhead, one_line, ncols, kinds, style)
        rules = ""
        # a short table is never split: it goes whole to the next page, its caption (and a
        # heading before it, sticky) with it; a long one breaks between its rows (by chunks,
        # at least _EDGE rows on either side where its rows are merged), its header repeated
        short = len(rows) - nhead <= _SHORT
        # (not around a table in a cell: the leading set for the table's paragraphs would be its too)
        if tracks is not None and _CHUNK > 1 and not any("#table(" in c for r in cells for c in r):
            equal = len(set(kinds)) == 1 and kinds[0] == "1fr"
            # on a page of its own (a block not broken) the table's rows are one chunk
            tracks, cells, rules = _by_columns(tracks, cells, bare, nhead, ix, iy, len(kinds) if equal else 0,
                                               len(rows) if self.whole else _CHUNK)
        cells = [c for r in cells for c in r]
        rows_arg = ""
        if tracks is not None:
            while len(tracks) > 1 and tracks[-1] == tracks[-2]:
                tracks.pop()                    # the last track repeats
            rows_arg = f"rows: ({', '.join(tracks)},), "
        header = f"table.header({', '.join(cells[:nhead_cells])}), " if nhead_cells else ""
        body = ", ".join(cells[nhead_cells:])
        align = ""
        if any(right):
            align = "align: (" + ", ".join("right" if x else "left" for x in right) + ",), "
        tbl = f"{rules}#table(columns: {cols}, {rows_arg}inset: {inset}, {align}{header}{body})"
        if caption:
            tbl = f"#cap[{caption}]\n{tbl}"
        keep = ", breakable: false" if short else ""
        return f"#block(above: 1.5mm, below: 3mm, width: {'100%' if wide else 'auto'}{keep})[#text(size: {size})[{tbl}]]"


# a table cell's background colour in its style attribute (#rrggbb)
_BACKGROUND = re.compile(r"(?:^|;)\s*background(?:-color)?\s*:\s*(#[0-9a-fA-F]{6})\s*(?:;|$)")
# body rows merged into one table row, column by column (see _by_columns)
_CHUNK = 7                                  # (0 or 1: rows not merged)
# a table of up to _SHORT body rows is kept on one page; a longer one's merged rows leave at
# least _EDGE rows on either side of a page break (the last chunk of a run made that long)
_SHORT = 15
_EDGE = 3
# the tables' stroke (PREAMBLE's `set table`) and its width, pt
_RULE = re.search(r"#set table\(stroke: (.+)\)\n", PREAMBLE).group(1)
_RULE_W = float(re.match(r"([0-9.]+)pt \+ ", _RULE).group(1))


def _by_columns(tracks: list[str], cells: list[list[str]], bare: list, nhead: int,
                ix: float, iy: float, equal: int, chunk: int) -> tuple[list[str], list[list[str]], str]:
    """(tracks, cells per row, Typst markup to put before the table) with each run of body
    rows of the given height whose cells are plain text of one column each (no fill, span
    or alignment of their own, none empty) merged by chunks of up to ``chunk`` rows into one
    row: each column's values one cell, a line each, the row the chunk's height.  Typst
    lays out a table's cells one by one (each padded, each its own paragraph): 7 rows of
    10 columns are then 10 cells instead of 70.  The lines' pitch is the row pitch: the
    table's paragraphs get the leading of the cell insets (the cells of an auto row, which
    may wrap, keep PREAMBLE's); the rules between a chunk's rows are a curve placed in each
    of its cells over the cell's width, or in its first cell over the table's width where
    the table's ``equal`` (> 0) columns are all 1fr.  A page may break only between chunks."""
    h = next(t for t in tracks if t != "auto")
    out_t, out_c, sizes = [], [], set()
    i, n = 0, len(cells)
    while i < n:
        j = i
        if i >= nhead and tracks[i] == h and bare[i] is not None:
            e = i                                   # the run of such rows
            while e < n and tracks[e] == h and bare[e] is not None:
                e += 1
            j = min(e, i + chunk)
            if 0 < e - j < _EDGE and e - i > _EDGE:     # its last chunk would be short: made _EDGE rows
                j = e - _EDGE
        if j - i < 2:
            row = cells[i]
            if tracks[i] == "auto":             # may wrap: the leading of PREAMBLE
                row = [_leading(c) for c in row]
            out_t.append(tracks[i])
            out_c.append(row)
            i += 1
            continue
        k = j - i
        sizes.add(k)
        row = []
        for m, col in enumerate(zip(*bare[i:j])):
            rule = f"#_rules{k}\n" if m == 0 or not equal else ""
            if all(c[0] == '"' for c in col):
                text = "\\n".join(c[1:-1] for c in col)
                row.append(f'[{rule}#"{text}"]' if rule else f'"{text}"')
            else:
                lines = "#linebreak()".join(f"#{c}" if c[0] == '"' else c[1:-1] for c in col)
                row.append(f"[{rule}{lines}]")
        out_t.append(f"{k} * ({h})")
        out_c.append(row)
        i = j
    if not sizes:
        return tracks, cells, ""
    width = f"{equal} * (100% + {2 * ix}mm)" if equal else f"100% + {2 * ix}mm"
    defs = f"#show table: set par(leading: {2 * iy}mm)\n"
    for k in sorted(sizes):
        # each rule over the vertical lines' half width beyond the ends, as Typst draws them
        segs = ", ".join(f"curve.move((-{_RULE_W / 2}pt, {m} * ({h}))), "
                         f"curve.line(({width} + {_RULE_W / 2}pt, {m} * ({h})))" for m in range(1, k))
        defs += f"#let _rules{k} = place(dx: -{ix}mm, dy: -{iy}mm, curve(stroke: {_RULE}, {segs}))\n"
    return out_t, out_c, defs


def _leading(cell: str) -> str:
    """A table cell's markup with PREAMBLE's leading of table paragraphs set in it."""
    set_ = "#set par(leading: 0.3em)\n"
    if cell.startswith("table.cell("):
        at = cell.index(")[") + 2
        return cell[:at] + set_ + cell[at:]
    if cell[0] == "[":
        return "[" + set_ + cell[1:]
    return f"[{set_}#{cell}]"


# ---------------------------------------------------------------- figure labels
# An SVG <text> costs Typst's SVG reader (usvg) a shaping face of the font for each of its
# spans, each span shaping the whole text again, and an outline of each glyph: the report's
# ~1,800 labels were ~30 % of the compilation.  The labels a figure draws last (over all
# else, outside any group) are placed by Typst itself over the image instead: the same
# font, sizes, baselines, anchors, colours and styles, the same text in the PDF.
_SVG_TAG = re.compile(r"<svg\b([^>]*)>")
_XATTR = re.compile(r'\s+([a-zA-Z:-]+)="([^"]*)"')
_TSPAN = re.compile(r"<tspan\b([^>]*)>([^<]*)</tspan>|([^<]+)|(<)")
_SVG_ROOT_KEYS = {"xmlns", "class", "width", "height", "viewBox", "font-family"}
_TEXT_KEYS = {"x", "y", "font-size", "text-anchor", "fill", "font-style", "font-weight"}
_SPAN_KEYS = {"dy", "font-size", "font-style", "fill", "font-weight"}
_NUM = re.compile(r"-?(?:\d+\.?\d*|\.\d+)")
_COLOR = re.compile(r"#[0-9a-fA-F]{6}")
_ANCHOR = {"start": ("left", 0.0), "middle": ("center", 0.5), "end": ("right", 1.0)}


# MathML operators of the worked formulas as Typst mathematics
_MO = {"=": "=", "+": "+", "−": "-", "-": "-", "·": "dot.op", "/": "slash", "(": "\\(", ")": "\\)",
       "⊥": "perp", "∥": "parallel", ",": ",", ";": ";", "×": "times", "¯": "macron"}


def _mstr(t: str) -> str:
    """A text in Typst mathematics: quoted (upright, as written)."""
    return '"' + t.replace("\\", "\\\\").replace('"', '\\"') + '"'


def _math(node) -> str:
    """Typst mathematics of a MathML element of the worked formulas (math, mrow, mi, mn, mo,
    mtext, mspace, msub, msup, msubsup, mover with a bar, mfrac, msqrt)."""
    tag = node.tag
    kids = [k for k in node if isinstance(k, _Node)]
    text = "".join(k for k in node if isinstance(k, str))
    if tag in ("math", "mrow"):
        return " ".join(_math(k) for k in kids) or '""'
    if tag == "mi":
        if not text:
            return '""'
        if node.attrs.get("mathvariant") == "normal" or len(text) > 1:
            return f"upright({_mstr(text)})"
        return text if text.isalpha() else _mstr(text)
    if tag == "mn":
        return _mstr(text.strip())
    if tag == "mo":
        t = text.strip()
        return _MO.get(t, _mstr(t))
    if tag == "mtext":
        return _mstr(text.replace("\u00a0", " "))
    if tag == "mspace":
        return "thin"
    if tag in ("msub", "msup", "msubsup") and len(kids) >= 2:
        base = _math(kids[0])
        if tag == "msub":
            return f"attach({base}, b: {_math(kids[1])})"
        if tag == "msup":
            return f"attach({base}, t: {_math(kids[1])})"
        return f"attach({base}, b: {_math(kids[1])}, t: {_math(kids[2])})"
    if tag == "mover" and kids:
        return f"overline({_math(kids[0])})"
    if tag == "mfrac" and len(kids) == 2:
        return f"frac({_math(kids[0])}, {_math(kids[1])})"
    if tag == "msqrt":
        return "sqrt(" + " ".join(_math(k) for k in kids) + ")"
    return " ".join(_math(k) for k in kids) or (_mstr(text) if text else '""')


def _pt(v: float) -> str:
    return f"{v:.3f}".rstrip("0").rstrip(".") + "pt"


def _text_args(at: dict, k: float) -> list[str] | None:
    """Typst text() arguments of an SVG text's or tspan's font size (user units, ``k`` pt
    each), fill, style and weight; None where one is not of the plain kind tmm writes."""
    args = []
    fs = at.get("font-size")
    if fs is not None:
        if not _NUM.fullmatch(fs):
            return None
        args.append(f"size: {_pt(float(fs) * k)}")
    fill = at.get("fill")
    if fill is not None:
        if not _COLOR.fullmatch(fill):
            return None
        args.append(f'fill: rgb("{fill}")')
    for key, name, values in (("font-style", "style", ("normal", "italic")),
                              ("font-weight", "weight", ("normal", "bold"))):
        v = at.get(key)
        if v is not None:
            if v not in values:
                return None
            args.append(f'{name}: "{v}"')
    return args


@lru_cache(maxsize=4096)
def _label_style(attrs: str, k: float) -> tuple[str, str, float] | None:
    """(the opening ``text(...,`` of a label, its place() side, the fraction of the figure's
    width that side is at) of an SVG text's attributes other than x and y; None where one
    is not of the plain kind tmm writes."""
    at = dict(_XATTR.findall(attrs))
    if set(at) - _TEXT_KEYS or at.get("text-anchor", "start") not in _ANCHOR:
        return None
    args = _text_args(at, k)
    if args is None:
        return None
    side, frac = _ANCHOR[at.get("text-anchor", "start")]
    return f"text({', '.join(args)}, " if args else "text(", side, frac


@lru_cache(maxsize=4096)
def _label_body(inner: str, k: float) -> str | None:
    """The Typst content of an SVG text's content (``k`` pt per user unit): its runs, the
    tspans shifting the baseline (dy) or changing the size, colour or style; "" when it has
    no text, None where it holds anything else."""
    from html import unescape
    if "<" not in inner:                # plain text: its white space as below
        t = _WS.sub(" ", unescape(inner) if "&" in inner else inner).strip()
        return _s(t)[1:] if t else ""
    parts, shift = [], 0.0              # (text() arguments, text) of each run
    for sattrs, stext, plain, lt in _TSPAN.findall(inner):
        if lt:
            return None                 # an element other than a plain tspan
        if plain:
            if shift:
                return None
            parts.append(("", plain))
            continue
        sat = dict(_XATTR.findall(sattrs))
        if set(sat) - _SPAN_KEYS or not _NUM.fullmatch(sat.get("dy", "0")):
            return None
        shift += float(sat.pop("dy", "0"))
        sargs = _text_args(sat, k)
        if sargs is None:
            return None
        if abs(shift) > 1e-9:
            sargs.append(f"baseline: {_pt(shift * k)}")
        parts.append((", ".join(sargs), stext))
    # white space as SVG collapses it (xml:space default): runs to one space, the ends trimmed
    texts = [_WS.sub(" ", unescape(t) if "&" in t else t) for _, t in parts]
    if texts:
        texts[0] = texts[0].lstrip()
        texts[-1] = texts[-1].rstrip()
    runs = [f"text({a}, {_s(t)[1:]})" if a else _s(t)[1:] for (a, _), t in zip(parts, texts) if t]
    if not runs:
        return ""
    return runs[0] if len(runs) == 1 else "{" + "; ".join(runs) + "}"


# a label as tmm writes it (x and y first), or any other text element: the whole, then x, y,
# the other attributes and the content of a label ("" for another element); the content up
# to the first </text>, taken possessively
_LABEL = re.compile(r'(<text x="(-?\d+(?:\.\d+)?)" y="(-?\d+(?:\.\d+)?)"([^>]*)>((?:[^<]++|<(?!/text>))*+)</text>\s*'
                    r"|<text\b(?:[^<]++|<(?!/text>))*+</text>\s*)", re.S)


def _place_labels(texts: str, k: float, vw: float) -> tuple[str, list[str]]:
    """(the SVG text elements of ``texts`` left in the figure, the Typst calls placing the
    others over it): each at its baseline (x, y user units, ``k`` pt each; the figure ``vw``
    wide) by its anchor (the styles and contents alike read once: cached).  The labels of
    one style share one text() call around their place() calls, the styles in the order of
    their first label: ~90 k instructions less to evaluate and to lay out for each text()
    call saved (a set rule instead nests the styles: dearer).  A label of one style is then
    drawn after one of another style that the figure drew later: the page is the same where
    labels do not overlap (tmm's labels are placed apart)."""
    kept, styles = [], {}
    for whole, x, y, attrs, inner in _LABEL.findall(texts):
        got = _label_parts(attrs, inner, k) if x else None
        if got is None:
            kept.append(whole)
        elif got:
            head, pre, frac, post = got
            styles.setdefault(head, []).append(
                f"{pre}{(float(x) - frac * vw) * k:.3f}pt, dy: {float(y) * k:.3f}pt, {post}")
    return "".join(kept), [_styled(head, places) for head, places in styles.items()]


def _styled(head: str, places: list[str]) -> str:
    """Typst content of ``places`` in the text style ``head`` (an opening ``text(...,``)."""
    inner = "; ".join(places)
    return f"{head}{{{inner}}})" if head != "text(" else f"{{{inner}}}"


@lru_cache(maxsize=4096)
def _label_parts(attrs: str, inner: str, k: float) -> tuple[str, str, float, str] | str | None:
    """A label's text style and place() call but its position: (the style's opening
    ``text(...,``, the text before dx, the fraction of the figure's width its anchor is at,
    the text after dy); "" for a label without text, None for one left in the figure (see
    _label_style, _label_body)."""
    st = _label_style(attrs, k)
    body = _label_body(inner, k) if st is not None else None
    if body is None:
        return None
    if not body:
        return ""
    head, side, frac = st
    return head, f"place(top + {side}, dx: ", frac, f"{body})"


_SPACE = re.compile(r"\s*")
# an end tag other than </tspan>, or one that removing the </tspan> tags would make ("<" and
# "/" around them): where ``"</" in text.replace("</tspan>", "")``
_OTHER_END = re.compile(r"</(?!tspan>)|<(?:</tspan>)+/")


def _labels(svg: str, width_pt: float) -> tuple[str, str]:
    """(the SVG less the labels that Typst places, Typst content placing them over the
    figure drawn ``width_pt`` wide, or "" when none is)."""
    m = _SVG_TAG.match(svg)
    if not m:
        return svg, ""
    root = dict(_XATTR.findall(m.group(1)))
    vb = (root.get("viewBox") or "").split()
    h = re.fullmatch(r"([0-9.]+)pt", root.get("height", ""))
    if (set(root) - _SVG_ROOT_KEYS or root.get("font-family") != "DejaVu Sans" or len(vb) != 4
            or vb[:2] != ["0", "0"] or not h or not all(_NUM.fullmatch(v) for v in vb)):
        return svg, ""
    vw, vh = float(vb[2]), float(vb[3])
    k = width_pt / vw if vw > 0 else 0.0
    if not (k > 0 and vh > 0 and abs(float(h.group(1)) / vh - k) <= 1e-3 * k):
        return svg, ""                  # not a uniform scale: the viewBox is fitted otherwise
    # the texts after the last other element, outside any group: from the end, each
    # "<text ...</text>" with only white space after it and no end tag in it but </tspan>
    # (read in place, without slicing the figure)
    end = pos = svg.rindex("</svg>")
    start = end
    rfind, space, other_end = svg.rfind, _SPACE.fullmatch, _OTHER_END.search
    while True:
        t = rfind("</text>", 0, pos)
        if t < 0 or not space(svg, t + 7, pos):
            break
        o = rfind("<text", 0, t)
        if o < 0 or svg.find("<text", o + 5, t) >= 0 or other_end(svg, o, t):
            break
        start = pos = o
    kept, placed = _place_labels(svg[start:end], k, vw)
    if not placed:
        return svg, ""
    return svg[:start] + kept + svg[end:], "{" + "; ".join(placed) + "}"


def to_typst(html: str, lang: str = "en") -> tuple[str, dict[str, bytes]]:
    """(Typst source, {file name: bytes}) of the report's HTML."""
    root, svgs = _parse(html)
    w = _Writer(svgs, None)
    title = ""
    for n in _iter(root):
        if n.tag == "title":
            title = n.text().strip()
            break
    body = w.block(root)
    src = PREAMBLE.replace("TITLE", _s(title)[1:]).replace("LANG", f'"{lang}"') + "\n" + body + "\n"
    return src, w.files


def _iter(node):
    for c in node:
        if isinstance(c, _Node):
            yield c
            yield from _iter(c)


def _font_dirs() -> list[str]:
    """matplotlib's copy of the DejaVu fonts (a dependency of the report, found without
    importing it): the PDF gets DejaVu Sans/Serif even where the system has no such font."""
    import importlib.util
    spec = importlib.util.find_spec("matplotlib")
    for base in (spec.submodule_search_locations or []) if spec else []:
        d = Path(base) / "mpl-data" / "fonts" / "ttf"
        if (d / "DejaVuSans.ttf").exists():
            return [str(d)]
    return []


def _font_links(into: Path) -> list[str]:
    """The font directories for a compilation, with matplotlib's only DejaVu files in
    them: links to them in ``into`` (a new directory), the whole of matplotlib's directory
    where links cannot be made.  Typst reads every font file of its directories for its
    coverage (~1.4 M instructions a file); matplotlib's other 28 (STIX, Computer Modern,
    LastResort) are never used by the report (its text is DejaVu Sans and Serif, its
    mathematics Typst's own New Computer Modern Math) and cost ~0.06 G of the forging
    report's ~2.0 G.  The fonts Typst chooses are the same ones, so the PDF is the same
    bytes."""
    dirs = _font_dirs()
    if not dirs:
        return dirs
    try:
        into.mkdir()
        for f in sorted(Path(dirs[0]).glob("DejaVu*.ttf")):
            (into / f.name).symlink_to(f)
    except OSError:
        return dirs
    return [str(into)]


def compile_file(typ: Path, fonts: list[str]) -> bytes:
    """PDF bytes of the Typst file ``typ`` (its folder the root), with the fonts of ``fonts``
    (:func:`_font_links`, :func:`_font_dirs`) and Typst's own, never the system's: the PDF is the
    same on every machine (a Linux with fonts-dejavu had its own DejaVu Sans chosen over
    matplotlib's copy; the text and the pages are the same, the embedded font file not), and
    Typst does not read every system font for each PDF (~10 ms here with 38 fonts, more where a
    system holds hundreds).  Where matplotlib's fonts are not found, the system's are used.
    Untagged, as weasyprint wrote it: a third of the size (0.4 MB against 1.1 MB for the forging
    report) and no complaint from poppler's tools about the structure tree."""
    import typst
    return typst.compile(str(typ), root=str(typ.parent), font_paths=fonts, ignore_system_fonts=bool(fonts),
                         pdf_tags=False)


def pdf_bytes(html: str, lang: str = "en") -> bytes:
    """Compile the report's HTML to PDF bytes (the figures are files of a temporary
    directory that Typst reads)."""
    import tempfile
    src, files = to_typst(html, lang)
    with tempfile.TemporaryDirectory(prefix="tmm-typst-") as tmp:
        d = Path(tmp)
        for name, data in files.items():
            (d / name).write_bytes(data)
        (d / "report.typ").write_text(src, encoding="utf-8")
        return compile_file(d / "report.typ", _font_links(d / "fonts"))
