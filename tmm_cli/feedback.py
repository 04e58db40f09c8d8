"""A one-page feedback per student (HTML, and PDF when asked): their value, the
reference, the error, the verdict, and for a wrong value the step of the course
project it comes from and the steps that step depends on. English, Russian or Ukrainian."""
from __future__ import annotations

import html
import math
import re
from pathlib import Path

from . import locales
from .numfmt import num

# the page's words, and section -> {step, depends}: the course step a quantity comes from and
# what that step depends on (the catalogues' topic feedback)
TEXT = locales.table("feedback", "text")
STEPS = locales.table("feedback", "steps")


def step_for(path: str, lang: str) -> str:
    """The course step a quantity comes from, and what that step depends on."""
    sec = re.split(r"[.\[]", path, 1)[0]
    s = STEPS.get(lang, STEPS["en"]).get(sec) or STEPS["en"].get(sec)
    if not s:
        return ""
    step, dep = s["step"], s["depends"]
    m = re.match(r"^\w+\[(\d+)\]", path)
    if m and sec in ("kinematics", "kinetostatics"):
        step += f" ({TEXT.get(lang, TEXT['en'])['position']} {m.group(1)})"
    return step + (f"; {TEXT[lang]['depends']}: {dep}" if dep else "")


def _num(x, lang: str = "en", fmt: str = ".5g") -> str:
    """A value of the page in ``lang``'s writing (ru, uk: 0,25 and 8,9·10⁻¹⁶; numfmt)."""
    if x is None:
        return "–"
    try:
        v = float(x)
    except (TypeError, ValueError):
        return str(x)
    return num(v, fmt, lang)


def _q(x, unit: str, lang: str = "en", fmt: str = ".5g") -> str:
    """A value with its unit: '16,36°' (the degree sign closed up, as printed), '0,25 m', '12'."""
    text = _num(x, lang, fmt)
    return f"{text}{unit}" if unit == "\u00b0" else f"{text} {unit}".rstrip()


def _pct(share, lang: str) -> str:
    """A share as percent to three digits ('0,0408 %')."""
    return f"{_num(100 * float(share), lang, '.3g')} %"


_NUMBER_HEAD = re.compile(r"^\s*[-+\u2212\u2013]?[\d\s.,\u00a0\u202f]*\d(?:[eE][-+]?\d+)?\s*")


def _in_written_unit(r: dict):
    """The reference in the unit the student wrote (a number, and the unit as written), or None
    where the answer carried no unit or it does not convert. Converted by the reader that read
    the answer (check.answer_value of one such unit), so every spelling it reads converts back:
    the Cyrillic spellings of kN, mm, rpm, and units of paths outside the presets ('160 mm' of
    positions.H)."""
    written, ref = r.get("written"), r.get("reference")
    if not written or ref is None:
        return None
    unit = _NUMBER_HEAD.sub("", written, count=1).strip()
    if not unit:
        return None
    if unit.startswith("\u00b0"):         # 16°22′: degrees and minutes, the reference in degrees
        unit = "\u00b0"
    from .check import answer_value
    try:
        one = answer_value(f"1 {unit}", r["path"])
    except ValueError:
        return None
    if not one or not math.isfinite(one):
        return None
    return float(ref) / one, unit


def _tolerance(r: dict, unit: str, lang: str) -> str:
    """The tolerance in the error column's terms: '±5 %', '±0.5 °', '±2 % (at least 0.001 m/s)', or
    a band's ends ('77.92…162.1 kg·m²')."""
    words = str(r["tolerance"]).split()
    zero = r.get("reference") == 0
    if words and words[0] == "band":           # the interval an answer must lie in (graphical flywheel)
        lo, hi = (float(v) for v in words[1].split(".."))
        return f"{_q(lo, '', lang, '.4g')}…{_q(hi, unit, lang, '.4g')}"
    if len(words) == 1:
        v = float(words[0])
        return f"±{_q(v, unit, lang)}" if zero else f"±{_pct(v, lang)}"
    parts = dict(zip(words[::2], words[1::2]))
    rel, ab = float(parts.get("rel", 0)), float(parts.get("abs", 0))
    from .messages import catalogue
    words = catalogue(lang)["terms"]["grading"]
    least = words["at_least"]
    text = (f"±{_pct(rel, lang)}" + (f" ({least} {_q(ab, unit, lang)})" if ab else "")
            if rel else f"±{_q(ab, unit, lang)}")
    if parts.get("sign") == "any":
        text += " " + words["either_sign"]
    return text


def feedback_html(task, s: dict, lang: str = "en", key: bool = True) -> str:
    """The page; ``key`` False (`--feedback no-key`): no reference values on it."""
    from .forms import local_unit, notation, unit_of
    from .messages import catalogue
    lang = lang if lang in TEXT else "en"
    T = {**TEXT[lang], **catalogue(lang)["terms"]["grading"]}
    from .limits import printable
    e = lambda x: html.escape(printable(str(x)), quote=True)  # noqa: E731  (no control character raw)
    rows = s["rows"]
    n_ok = sum(r["status"] == "ok" for r in rows)
    n_all = sum(r["status"] != "unknown_path" for r in rows)      # a misspelt path answers no quantity
    trs = []
    for r in rows:
        st = r["status"]
        unit = r.get("unit") or unit_of(r["path"]) or ""       # the stroke's own: m, or a rocker's deg
        unit = {"deg": "°", "m or deg": ""}.get(unit, unit)
        unit = local_unit(unit, lang)
        err = "–"
        if r["error"] is not None:
            absolute = "abs" in r["tolerance"] or r["note"] == "absolute error" or r.get("reference") == 0
            err = _q(r["error"], unit, lang, ".3g") if absolute else _pct(r["error"], lang)
        note = r["note"]
        coded = hasattr(note, "to_dict")
        if coded:                            # coded: in the page's language
            from .messages import localize
            note = localize(note.to_dict(), lang)
        step = step_for(r["path"], lang) if st in ("outside", "sign") else (note if st in ("unknown_path", "invalid")
                                                                            else "")
        if st == "outside" and coded:        # a unit slip (98,5 for 0,0985 m): said before the step
            step = f"{note}. {step}"
        colour = {"ok": "#c8e6c9", "outside": "#ffcdd2", "sign": "#e1bee7", "missing": "#fff9c4",
                  "invalid": "#ef9a9a"}.get(st, "#eee")
        conv = _in_written_unit(r)
        if "written" in r:
            value = r["written"]
        elif st == "invalid":
            value = r["answer"]
        else:
            value = _q(r["answer"], unit, lang) if r["answer"] is not None else "–"
        ref = (_q(conv[0], conv[1], lang) if conv else
               (_q(r["reference"], unit, lang) if r["reference"] is not None else "–"))
        tol = _tolerance(r, unit, lang) if st not in ("unknown_path", "not_computed") else "–"
        cells = [f"<code>{e(r['path'])}</code><br><small>{e(notation(r['path'], lang, local_units=True))}</small>",
                 e(value)] + ([e(ref)] if key else []) + [e(err), e(tol)]
        trs.append("<tr>" + "".join(f"<td>{c}</td>" for c in cells)
                   + f"<td style='background:{colour}'>{e(T.get(st, st))}</td><td><small>{e(step)}</small></td></tr>")
    cols = ("quantity", "value") + (("reference",) if key else ()) + ("error", "tolerance", "verdict", "step")
    head = "".join(f"<th>{e(T[c])}</th>" for c in cols)
    who = [(T["student"], s.get("student") or "–"), (T["group"], s.get("group") or "–"),
           (T["variant"], "–" if s.get("variant") in (None, "") else s.get("variant")),
           (T["task"], task.title or task.name), (T["score"], f"{n_ok} / {n_all}")]
    if s.get("answers_file"):
        who.insert(3, (T["file"], s["answers_file"]))
    info = "".join(f"<tr><th>{e(k)}</th><td>{e(v)}</td></tr>" for k, v in who)
    return ("<!DOCTYPE html><html><head><meta charset='utf-8'>"
            f"<title>{e(T['title'])}</title><style>@page{{size:A4;margin:12mm}}body{{font-family:sans-serif;"
            "font-size:12px}table{border-collapse:collapse;margin-bottom:1em}td,th{border:1px solid #999;"
            "padding:3px 6px;text-align:left;vertical-align:top}</style></head><body>"
            f"<h1>{e(T['title'])}</h1><table>{info}</table><table><tr>{head}</tr>{''.join(trs)}</table>"
            "</body></html>\n")


def feedback_name(s: dict) -> str:
    """feedback-<student>-<answers file> ('feedback-Ivanov-ivanov', 'feedback-Petrov-class.csv_5'
    for a table's line 5); without an answers file (the task's own answers) the set's number."""
    from .safepath import safe_name          # no device name, no leading dash

    def safe(x):
        return safe_name(str(x or ""), "").strip("._")
    who = safe(s.get("student")) or "answers"
    src = s.get("answers_file")
    if src:
        src = src[:-5] if src.endswith(".yaml") else (src[:-4] if src.endswith(".yml") else src)
        return f"feedback-{who[:40]}-{safe(src)[:40]}"
    return f"feedback-{who[:40]}-{s['index'] + 1 if s['index'] >= 0 else 0}"


def write_feedback(task, s: dict, folder: Path, lang: str, pdf: bool = False,
                   notes: list[str] | None = None, key: bool = True) -> list[Path]:
    """feedback-<student>-<n>.html (and .pdf) in the variant's folder. The PDF is the page's
    HTML compiled by Typst as report.pdf is (the report's HTML-to-Typst writer,
    tmm_cli.report.typst_pdf); where the typst package cannot be loaded the page is
    written as HTML only, ``notes`` receives one line saying why, and the grading goes on."""
    from .io import atomic_write
    text = feedback_html(task, s, lang, key=key)
    base = feedback_name(s)
    out = [atomic_write(Path(folder) / f"{base}.html", text)]
    if pdf:
        from .report import PdfSkipped, _pdf_bytes
        try:
            data = _pdf_bytes(text, lang)
        except PdfSkipped as exc:
            if notes is not None:
                notes.append(f"feedback pages written as HTML only: {exc}")
            return out
        out.append(atomic_write(Path(folder) / f"{base}.pdf", data))
    return out
