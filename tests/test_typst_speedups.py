"""The PDF translator's faster helpers (tmm_cli/report/typst_pdf) give exactly what the
code before them gave: the advance bound of a text by a dict lookup per character."""
from __future__ import annotations

import random

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
