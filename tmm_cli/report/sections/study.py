"""Report section 'study': accuracy against computing time per stage (`tmm run --study`).

Shown only when the report is built with a study (results.json itself never carries it:
the timings would make it non-deterministic); the tables and log-log plots are those of
:func:`html_section` below (study.html, written by :func:`write`, is the same section as a
page), its texts the table below."""
from __future__ import annotations

import math
import re

from ... import locales

I18N = locales.table("study", "words")


def build(ctx) -> str | None:
    st, trap = ctx.results.get("study"), ctx.results.get("study_trapezoid")
    if not st and not (trap or {}).get("left_out"):
        return None
    from markupsafe import Markup
    return Markup(html_section(st or {}, trap, ctx.lang))


_W, _H, _L, _B, _T, _R = 520, 320, 64, 44, 16, 150
_COLORS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b")


def svg_loglog(series: list[tuple[str, list[float], list[float]]], xlabel: str,
               ylabel: str = "relative error", lang: str = "en") -> str:
    """A log-log plot drawn directly as SVG: series of (label, x, y), y > 0 only; the powers of ten
    on the axes written in ``lang`` (1e-3, in ru and uk 1·10⁻³)."""
    from ...numfmt import localize
    pts = [(x, y) for _, xs, ys in series for x, y in zip(xs, ys) if x > 0 and y and y > 0]
    if not pts:
        return ""
    lx = [math.log10(p[0]) for p in pts]
    ly = [math.log10(p[1]) for p in pts]
    x0, x1 = math.floor(min(lx)), math.ceil(max(lx))
    y0, y1 = math.floor(min(ly)), math.ceil(max(ly))
    x1 = x1 if x1 > x0 else x0 + 1
    y1 = y1 if y1 > y0 else y0 + 1
    pw, ph = _W - _L - _R, _H - _T - _B

    def X(v):
        return _L + (math.log10(v) - x0) / (x1 - x0) * pw

    def Y(v):
        return _T + (y1 - math.log10(v)) / (y1 - y0) * ph

    o = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{_W}" height="{_H}" '
         f'viewBox="0 0 {_W} {_H}" font-family="sans-serif" font-size="11">',
         f'<rect x="{_L}" y="{_T}" width="{pw}" height="{ph}" fill="none" stroke="#000"/>']
    ystep = max(1, (y1 - y0) // 8)
    for k in range(x0, x1 + 1):
        x = _L + (k - x0) / (x1 - x0) * pw
        o.append(f'<line x1="{x:.1f}" y1="{_T}" x2="{x:.1f}" y2="{_T + ph}" stroke="#ddd"/>')
        o.append(f'<text x="{x:.1f}" y="{_T + ph + 14}" text-anchor="middle">{localize(f"1e{k}", lang)}</text>')
    for k in range(y0, y1 + 1, ystep):
        y = _T + (y1 - k) / (y1 - y0) * ph
        o.append(f'<line x1="{_L}" y1="{y:.1f}" x2="{_L + pw}" y2="{y:.1f}" stroke="#ddd"/>')
        o.append(f'<text x="{_L - 4}" y="{y + 4:.1f}" text-anchor="end">{localize(f"1e{k}", lang)}</text>')
    o.append(f'<text x="{_L + pw / 2}" y="{_H - 6}" text-anchor="middle">{_svg_text(xlabel)}</text>')
    o.append(f'<text x="14" y="{_T + ph / 2}" text-anchor="middle" '
             f'transform="rotate(-90 14 {_T + ph / 2})">{_svg_text(ylabel)}</text>')
    for i, (label, xs, ys) in enumerate(series):
        c = _COLORS[i % len(_COLORS)]
        p = [(X(x), Y(y)) for x, y in zip(xs, ys) if x > 0 and y and y > 0]
        if not p:
            continue
        o.append(f'<polyline fill="none" stroke="{c}" stroke-width="1.5" points="'
                 + " ".join(f"{a:.1f},{b:.1f}" for a, b in p) + '"/>')
        o.extend(f'<circle cx="{a:.1f}" cy="{b:.1f}" r="2.5" fill="{c}"/>' for a, b in p)
        ly_ = _T + 14 + 16 * i
        o.append(f'<line x1="{_L + pw + 8}" y1="{ly_ - 4}" x2="{_L + pw + 24}" y2="{ly_ - 4}" '
                 f'stroke="{c}" stroke-width="2"/>')
        o.append(f'<text x="{_L + pw + 28}" y="{ly_}">{_svg_text(label)}</text>')
    o.append("</svg>")
    return "\n".join(o)


# the unit of each value (a task file's spelling, written in the language by messages.unit); the
# output's diagrams of a rocker are an angle, omega and epsilon; a slider's balancing is a force
UNITS = {"J_n": "kg*m^2", "J_n_merzalov": "kg*m^2", "J_n_exact": "kg*m^2", "deviation": "m", "rho_min": "m",
         "r0": "m", "step": "deg", "ratio_error": "%", "R_max": "N", "omega_end": "rad/s", "psi_end": "deg",
         "psi_dot_end": "rad/s"}
_KIND_UNITS = {("output", "rocker"): {"stroke": "deg", "v_max": "rad/s", "a_max": "rad/s^2"},
               ("output", "slider"): {"stroke": "m", "v_max": "m/s", "a_max": "m/s^2"},
               ("balancing", "force"): {"M_b_max": "N"}, ("balancing", "moment"): {"M_b_max": "N*m"}}
SCALE = {"ratio_error": 100.0}       # a relative deviation shown in percent


def _unit(d: dict, key: str, lang: str) -> str:
    """The unit of value ``key`` of stage ``d`` in ``lang`` ('' for a number without one)."""
    from ...messages import unit
    u = UNITS.get(key)
    for (field, kind), table in _KIND_UNITS.items():
        if d.get(field) == kind and key in table:
            u = table[key]
    return unit(u, lang) if u else ""


def _fmt(v, key: str = "", lang: str = "en") -> str:
    """A number of the study's page as the report writes it in ``lang`` (the decimal comma and
    8,9·10⁻¹⁶ in ru and uk: numfmt): errors and times to 3 digits, values to 10, a relative
    deviation (SCALE) in percent."""
    from ...numfmt import localize
    if v is None:
        return "—"
    v = v * SCALE[key] if key in SCALE and isinstance(v, (int, float)) else v
    if isinstance(v, float) and (key.startswith(("err", "deviation")) or key in ("time_ms", "ratio_error")):
        return localize(f"{v:.3g}", lang)
    if isinstance(v, float):
        return localize(f"{v:.3g}" if (abs(v) < 1e-3 or abs(v) >= 1e6) and v != 0 else f"{v:.10g}", lang)
    return localize(str(v), lang)


def _svg_text(text: str) -> str:
    """A label of the plot with the notation's subscripts (M_b) lowered, escaped for SVG."""
    from markupsafe import escape
    from ..notation import parts
    return "".join(f'<tspan baseline-shift="sub" font-size="8">{escape(p)}</tspan>' if low else str(escape(p))
                   for p, low in parts(text))


def _error_text(e: float | None) -> str:
    """A relative error in plain words, always in percent (a sentence that gave '10.7 %' and then
    '2e-11' read as one unit): '10.7 %', '0.002 %', below 0.001 % one digit and its power
    ('2e-9 %'), written in the current language."""
    from ...numfmt import localize
    if e is None or not math.isfinite(e):
        return "—"
    p = 100 * e
    if p >= 1e-3:
        return localize(f"{p:.3g} %")
    return localize(re.sub(r"e([-+])0*(\d)", r"e\1\2", f"{p:.1g}")) + " %" if p > 0 else "0 %"


def trade(stage: str, d: dict, lang: str = "en") -> str | None:
    """The stage's trade in one sentence: the coarsest setting's error and time against the
    tool's default setting (else the finest): '12 positions give 10.7 %, 720 give 0.01 %'."""
    from ...numfmt import language, localize
    from .. import i18n
    i18n.register(I18N)
    rows = d.get("rows") or []
    key = f"study.trade.{stage}"
    if len(rows) < 2 or key not in i18n.STRINGS["en"]:
        return None
    a = rows[0]
    dflt = d.get("default")
    b = next((r for r in rows if r["setting"] == dflt), None)
    if b is None or b is a:
        b, dflt_text = rows[-1], ""
    else:
        dflt_text = i18n.translate("study.default", lang)
    with language(lang):
        found = {}
        if stage == "planetary":     # the ratio found and its deviation from the required one, beside
            req = d.get("required")  # the change against the reference search (the row's error)
            found = {"ra": localize(f"{a['ratio']:.4g}"), "rb": localize(f"{b['ratio']:.4g}"),
                     "pa": _error_text(a["ratio_error"]), "pb": _error_text(b["ratio_error"]),
                     "ri": "—" if req is None else localize(f"{req:.4g}"),
                     "zr": localize(f"{d['reference']['setting']:g}")}
        return i18n.translate(key, lang, a=localize(f"{a['setting']:g}"), b=localize(f"{b['setting']:g}"),
                              ea=_error_text(a["error"]), eb=_error_text(b["error"]), dflt=dflt_text,
                              ta=localize(f"{a['time_ms']:.3g}"), tb=localize(f"{b['time_ms']:.3g}"), **found)


def trades(study: dict, lang: str = "en") -> list[str]:
    """The trade sentence of every stage of the study (its order)."""
    return [s for s in (trade(stage, d, lang) for stage, d in study.items()) if s]


def left_out(left: dict, lang: str) -> str:
    """Why the linkage's study is left out (a function generator over its input range)."""
    from .. import i18n
    i18n.register(I18N)
    return i18n.translate("study.left_out_range", lang, start=f"{left['start']:g}", end=f"{left['end']:g}")


def html_section(study: dict, trapezoid: dict | None = None, lang: str = "en") -> str:
    """A report section in `lang`: per stage the table, the measured and the theoretical
    order and a log-log plot (texts: tmm_cli/report/sections/study.py, I18N)."""

    from ...study import REF_TOL
    from ..notation import notation_html as esc      # the course's notation with its subscripts (M_b)
    from .. import i18n
    i18n.register(I18N)

    def t(key, **kw):
        return i18n.translate(f"study.{key}", lang, **kw)

    def own(key, d):
        """The catalogue's ``key``, or a rocker output's own where it has one (omega, not v)."""
        rocker = f"{key}_rocker"
        return rocker if (d or {}).get("output") == "rocker" and rocker in i18n.STRINGS["en"] else key

    def name_of(k, d):
        """The catalogue's name of ``k`` (:func:`own`); ``k`` itself where it has none."""
        key = own(f"study.col.{k}", d)
        return i18n.translate(key, lang) if key in i18n.STRINGS["en"] else k

    def col(k, d=None):
        """The name of a setting or value in ``lang`` (the catalogue's), its unit after a comma."""
        name = name_of(k, d)
        u = _unit(d or {}, k, lang)
        return f"{name}, {u}" if u else name

    def value(d, k, v):
        """'name = value unit' of a reference value (an angle's degree sign without a space)."""
        name = name_of(k, d)
        u = _unit(d, k, lang)
        return f"{name} = {_fmt(v, k, lang)}" + ("" if not u else u if u == "°" else f" {u}")

    parts = [f"<section><h2>{esc(t('title'))}</h2>"]
    short = trades(study, lang)        # the trade first, in plain words; the method after it
    if short:
        parts.append(f"<h3>{esc(t('short'))}</h3><ul class='trade'>"
                     + "".join(f"<li>{esc(x[0].upper() + x[1:])}.</li>" for x in short) + "</ul>")
    parts.append(f"<p>{esc(t('intro', tol=f'{REF_TOL:g}'))}</p>")
    left = (trapezoid or {}).get("left_out")
    if left:
        parts.append(f"<p>{esc(left_out(left, lang))}</p>")
    for stage, d in study.items():
        rows = d["rows"]
        keys = [k for k in rows[0] if k not in ("setting", "error", "time_ms")]
        parts.append(f"<h3>{esc(t('stage.' + stage))}</h3>")
        ref = d["reference"]
        txt = [i18n.translate(own(f"study.note.{stage}", d), lang)]     # a rocker's: swing, omega, epsilon
        rv = ", ".join(value(d, k, ref[k]) for k in ref if k not in ("setting", "check", "converged"))
        txt.append(t("reference_exact" if ref["setting"] == 0 else "reference",
                     setting=_fmt(ref["setting"], lang=lang), values=rv))
        chk = ref.get("check")
        if isinstance(chk, dict):
            key = f"study.check.{stage}"
            txt.append(i18n.translate(key if key in i18n.STRINGS["en"] else "study.check", lang,
                                      setting=_fmt(chk.get("setting"), lang=lang),
                                      diff=_fmt(chk.get("difference"), "err", lang)))
        if ref.get("converged") is False:
            txt.append(t("not_converged"))
        order, theory = d.get("order"), d.get("theory")
        txt.append(t("order", order=order) if order is not None else t("no_order"))
        if theory is not None:
            txt.append(t("theory", theory=theory))
        tr = (trapezoid or {}).get(stage)
        if tr:
            txt.append(t("trapezoid", order=tr["order"]))
        parts.append("<p>" + esc(" ".join(x[0].upper() + x[1:].rstrip(".") + "." for x in txt if x)) + "</p>")
        head = "".join(f"<th>{esc(x)}</th>" for x in [col(d["setting"], d), *(col(k, d) for k in keys), t("error"),
                                                        t("time")])
        body = "".join("<tr>" + "".join(f"<td>{_fmt(r[k], k, lang)}</td>"
                                        for k in ["setting", *keys, "error", "time_ms"])
                       + "</tr>" for r in rows)
        parts.append(f"<table><tr>{head}</tr>{body}</table>")
        xs = [r["setting"] for r in rows]
        series = [(t("series." + stage), xs, [r["error"] for r in rows])]
        if tr:
            series.append((t("series.trapezoid"), [r["setting"] for r in tr["rows"]], [r["error"] for r in tr["rows"]]))
        parts.append(svg_loglog(series, col(d["setting"], d), t("axis"), lang))
    parts.append("</section>")
    return "\n".join(parts)


def write(study: dict, out, trapezoid: dict | None = None, lang: str = "en") -> list:
    """study.json and study.html (the section as a page, in `lang`) in the folder `out`."""
    import json
    from pathlib import Path
    from ...io import atomic_write
    out = Path(out)
    from ..i18n import translate
    section = html_section(study, trapezoid, lang)        # registers the texts
    page = (f"<!DOCTYPE html><html lang='{lang}'><head><meta charset='utf-8'><title>"
            f"{translate('study.title', lang)}</title>"
            "<style>body{font-family:sans-serif;max-width:60em;margin:1em auto}table{border-collapse:collapse}"
            "td,th{border:1px solid #999;padding:2px 6px;text-align:right}</style></head><body>"
            + section + "</body></html>")
    return [atomic_write(out / "study.json", json.dumps(study, indent=1, allow_nan=False)),
            atomic_write(out / "study.html", page)]
