"""The title block's signing rows (GOST 2.104, form 1 and 2): what a name becomes in its 23 mm
cell. Used by the drawing sheets (tmm_cli/sheets/frame.py) and the explanatory note's frame
(tmm_cli/report/note.py)."""
from __future__ import annotations


def signer_name(name: str, char_w: float, max_w: float, narrowest: float) -> tuple[str, float]:
    """A name for a signing row: as given where it fits ``max_w`` (mm) with its letters of
    ``char_w`` mm narrowed down to ``narrowest``; else the surname and initials ('Ivanov I. I.'
    of 'Ivanov Ivan Ivanovich': the standard's practice, the row holds the surname); else the
    surname alone. (text, narrowing): 1.0 where it fits as it is, down to ``narrowest``, less
    only for a surname longer than the cell at ``narrowest`` (written narrower still, never
    past the cell)."""
    def narrowing(t: str) -> float:
        return min(1.0, max_w / (char_w * max(len(t), 1)))
    words = name.split()
    if len(words) > 1 and _initial(words[0]):          # 'I. I. Ivanov': the surname last
        words = words[-1:] + words[:-1]
    tries = [name] + ([f"{words[0]} " + " ".join(w if _initial(w) else w[0] + "." for w in words[1:]), words[0]]
                      if len(words) > 1 else [])
    for t in tries:
        if narrowing(t) >= narrowest:
            return t, narrowing(t)
    return tries[-1], narrowing(tries[-1])


def _initial(word: str) -> bool:
    """An initial or two as written ('I.', 'I.I.')."""
    return word.endswith(".") and len(word.replace(".", "")) <= 2
