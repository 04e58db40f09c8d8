"""What a drawing writes in its language: the report's terms (t), its numbers (fmt,
fmt_fixed).  The report's sections hand their context (it has the same three); a sheet
makes Words(lang)."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any


def balance_sub(lang: str) -> str:
    """The subscript of the balancing moment and force in ``lang``: M_b, P_b, and the course's
    in Russian and Ukrainian (the kinetostatics words' ``kst.balance_sub``)."""
    from .. import locales
    return locales.of("kinetostatics", "words", lang).get("kst.balance_sub", "b")


@dataclass(frozen=True)
class Words:
    lang: str

    def __post_init__(self):
        from ..report.sections import load
        load("kinetostatics")                 # registers the terms of the force drawings

    def t(self, key: str, **kw) -> str:
        from ..report.i18n import translate
        return translate(key, self.lang, **kw)

    @staticmethod
    def fmt(x: Any, digits: int = 4) -> str:
        from ..report.context import fmt
        return fmt(x, digits)

    @staticmethod
    def fmt_fixed(x: Any, decimals: int = 2) -> str:
        from ..report.context import fmt_fixed
        return fmt_fixed(x, decimals)
