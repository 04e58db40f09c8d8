"""The course's notation in the report's text: ``M_b``, ``omega_max``, ``J_{red}`` of the
catalogues written with a real subscript (M<sub>b</sub>) in the HTML, hence in report.pdf.

:class:`Term` is the text of a catalogue key as the report context's ``t`` returns it: a
plain ``str`` (CSV headers, comparisons, the terminal see the catalogue's text unchanged)
that Jinja's escaping (``{{ ... }}``, ``~``, ``Markup + term``) writes through its
``__html__``: escaped, with every notation token's subscript in ``<sub>``.

A token is one letter (Latin, Greek, Cyrillic), ``_`` and a subscript of letters and digits
(``_{...}`` for one in braces), not preceded by a letter, a digit, ``_``, ``.`` or a backtick
(``rho_min``, ``cam_profile``, ``balancing.max.F_balanced`` and `` `f_pin` `` stay as
written) and not followed by ``_``. Only the catalogue's own text is converted: an
underscore in a value substituted into it (a link name such as ``O_1``, a file name) is
kept as written.
"""
from __future__ import annotations

import re

# a candidate token: one letter, "_", the subscript ({...} or letters/digits, superscripts
# such as the square of omega_m^2 left after it)
_TOKEN = re.compile(r"([^\W\d_])_(\{[^{}]+\}|[^\W_\u00b9\u00b2\u00b3\u2070\u2074-\u2079]+)")
_NOT_BEFORE = frozenset("0123456789_.`")
_KEPT = "\ue000"        # an underscore of a substituted value while the tokens are converted


def _sub(m: re.Match) -> str:
    s, i, j = m.string, m.start(), m.end()
    if i and (s[i - 1].isalpha() or s[i - 1] in _NOT_BEFORE):
        return m.group(0)
    if j < len(s) and s[j] == "_":
        return m.group(0)
    sub = m.group(2)
    if sub[0] == "{":
        sub = sub[1:-1]
    return f"{m.group(1)}<sub>{sub}</sub>"


def kept(text: str) -> str:
    """``text`` with the substituted values' underscores back (see :func:`term`)."""
    return text.replace(_KEPT, "_")


def parts(text: str) -> list[tuple[str, bool]]:
    """``text`` cut into (piece, is a subscript): the figures' labels drawn from a catalogue's
    text lower its notation's subscripts as the HTML does."""
    out: list[tuple[str, bool]] = []
    pos = 0
    for m in _TOKEN.finditer(text):
        html = _sub(m)
        if html == m.group(0):
            continue
        sub = m.group(2)[1:-1] if m.group(2)[0] == "{" else m.group(2)
        out += [(text[pos:m.start()] + m.group(1), False), (sub, True)]
        pos = m.end()
    out.append((text[pos:], False))
    return [(p.replace(_KEPT, "_"), low) for p, low in out if p]


def notation_html(text: str) -> str:
    """``text`` escaped for HTML with its notation tokens' subscripts in ``<sub>``."""
    from markupsafe import escape
    html = str(escape(text))
    if "_" not in html:             # no notation: only the values' kept underscores to put back
        return html.replace(_KEPT, "_")
    return _TOKEN.sub(_sub, html).replace(_KEPT, "_")


class Term(str):
    """A catalogue text: a ``str`` whose HTML (``__html__``) writes the notation with
    subscripts. ``source``: the same text with the substituted values' underscores
    masked (None: there were none)."""

    def __new__(cls, text: str, source: str | None = None):
        obj = super().__new__(cls, text)
        obj._source = source
        return obj

    def __html__(self) -> str:
        return notation_html(self._source if self._source is not None else str(self))

    def split(self, sep=None, maxsplit=-1) -> list:
        """The pieces as terms (a catalogue text split where a value goes in, as the
        sections do to put markup there)."""
        parts = str.split(self, sep, maxsplit)
        src = None if self._source is None else self._source.split(sep, maxsplit)
        if src is not None and len(src) != len(parts):
            src = None
        return [Term(p, None if src is None else s) for p, s in zip(parts, src or [None] * len(parts))]


def term(translate, key: str, lang: str, **kw) -> Term:
    """``translate(key, lang, **kw)`` as a :class:`Term` (the values' underscores kept)."""
    text = translate(key, lang, **kw)
    masked = {k: v.replace("_", _KEPT) for k, v in kw.items() if isinstance(v, str) and "_" in v}
    source = translate(key, lang, **{**kw, **masked}) if masked else None
    return Term(text, source)
