"""Accuracy against computing time, per stage (`tmm study TASK`, `tmm run --study`).

For every stage present in the task the setting that trades time for accuracy is swept;
each row is compared with a converged reference, and the reference itself is checked by
computing it again at a finer setting (it is refined until two successive references
agree to `REF_TOL`, or the study says it did not converge).  The result, `study.json`:

    {"<stage>": {"setting": NAME, "reference": {<values>, "setting": VALUE},
                 "rows": [{"setting": VALUE, <values>, "error": e, "time_ms": t}],
                 "order": p}}

`error` is the largest relative error of the row's values against the reference; `order`
is the measured convergence order: the slope of log(error) against log(setting) fitted
over the rows whose error is above the rounding floor (null when fewer than three rows
are, or the setting is not a resolution, as for the planetary search).  The timings live
here only: results.json stays deterministic.

Stages and settings:
* flywheel: `resolution` (grid intervals; Gauss-Legendre per interval), values J_n of
  the three methods; the trapezoid (`quadrature: 0`) on the same grids beside it in the
  report's plot (not in study.json);
* curves: `points` of the output's s, v, a curves over a turn; values the stroke,
  max |v|, max |a| read off the curve (maxima at the points: order 2);
* dof2: the integrator's `rtol` (DOP853); values the final speeds and angle;
* planetary: `z_max` of the search; value the best ratio found and its error.
Not swept, as no task setting trades time for accuracy there: kinetostatics (solved
exactly at the task's positions), the cam (r0 and rho_min refined over continuous cam
angle) and the gear blocking contour (a fixed internal grid); the report says so.
"""
from __future__ import annotations

import math
import time
from contextlib import contextmanager
from typing import Callable

import numpy as np

REF_TOL = 1e-10
FLOOR = 1e-13


def _rel(x: float, ref: float) -> float:
    den = abs(ref)
    if den == 0:
        return abs(x)
    return abs(x - ref) / den


def _err(vals: dict, ref: dict) -> float:
    return max(_rel(vals[k], ref[k]) for k in vals)


def fit_order(settings, errors, floor: float = FLOOR, inverse: bool = False) -> float | None:
    """Slope p of error ~ setting^-p (least squares in log-log) over the errors above
    `floor`; None with fewer than three such rows.  inverse: error ~ setting^p (a
    tolerance as the setting)."""
    pts = [(s, e) for s, e in zip(settings, errors) if e is not None and e > floor and s > 0]
    if len(pts) < 3:
        return None
    x = np.log([p[0] for p in pts])
    y = np.log([p[1] for p in pts])
    slope = float(np.polyfit(x, y, 1)[0])
    return round(slope if inverse else -slope, 2)


def _timed(fn: Callable[[], dict], repeat: int = 3) -> tuple[dict, float]:
    best = math.inf
    out = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        best = min(best, time.perf_counter() - t0)
    return out, best * 1e3


def sweep(name: str, values_at: Callable, settings: list, ref_settings: list,
          inverse: bool = False, repeat: int = 3) -> dict:
    """The study of one stage: values_at(setting) -> {name: float}.  The reference is the
    first of ref_settings whose values agree with the next one's to REF_TOL (else the
    last), so that the reference is checked for convergence."""
    ref_vals = values_at(ref_settings[0])
    ref_set = ref_settings[0]
    converged = False
    for nxt in ref_settings[1:]:
        v = values_at(nxt)
        if _err(ref_vals, v) <= REF_TOL:
            converged = True
            break
        ref_vals, ref_set = v, nxt
    from .errors import StageError
    rows = []
    for s in settings:
        try:
            vals, t = _timed(lambda: values_at(s), repeat)
        except StageError:       # e.g. a search range with no solution: no row
            continue
        rows.append({"setting": s, **vals, "error": _err(vals, ref_vals), "time_ms": round(t, 3)})
    order = fit_order([r["setting"] for r in rows], [r["error"] for r in rows], inverse=inverse)
    out = {"setting": name, "reference": {**ref_vals, "setting": ref_set}, "rows": rows,
           "order": order}
    if not converged:
        out["reference"]["converged"] = False
    return out


@contextmanager
def _patched(module, name: str, value):
    old = getattr(module, name)
    setattr(module, name, value)
    try:
        yield
    finally:
        setattr(module, name, old)


# ------------------------------------------------------------------ stages
def flywheel_values(task, linkage, resolution: int, quadrature: int | None = None) -> dict:
    from .linkage import dynamics
    upd = {"resolution": int(resolution)}
    if quadrature is not None:
        upd["quadrature"] = int(quadrature)
    c = dynamics.analyze(linkage, task.flywheel.model_copy(update=upd), accuracy=False).cycle
    return {"J_n": c.J_n[c.method], "J_n_merzalov": c.J_n["merzalov"], "J_n_exact": c.J_n["exact"]}


def study_flywheel(task, linkage, quadrature: int | None = None, repeat: int = 3) -> dict:
    settings = [12, 18, 24, 36, 48, 72, 96, 144, 180, 360]
    refs = [2880, 5760, 11520] if quadrature != 0 else [23040, 46080]
    return sweep("resolution", lambda r: flywheel_values(task, linkage, r, quadrature),
                 settings, refs, repeat=repeat)


def curve_values(linkage, n: int) -> dict:
    from .linkage.kinematics import output_curve
    c = output_curve(linkage, int(n))
    s, v, a = c.s, c.v, c.a
    return {"stroke": float(np.ptp(s)), "v_max": float(np.max(np.abs(v))),
            "a_max": float(np.max(np.abs(a)))}


def study_curves(linkage, repeat: int = 3) -> dict:
    settings = [13, 25, 37, 73, 145, 361, 721, 1441]
    return sweep("points", lambda n: curve_values(linkage, n), settings,
                 [200001, 400001, 800001], repeat=repeat)


def dof2_values(section, rtol: float) -> dict:
    from .dof2 import analysis
    with _patched(analysis, "RTOL", float(rtol)), _patched(analysis, "ATOL", float(rtol) * 1e-2):
        d = analysis.analyze(section).to_dict()
    return {"omega_end": float(d["omega"][-1]), "psi_end": float(d["psi"][-1]),
            "psi_dot_end": float(d["psi_dot"][-1])}


def study_dof2(task, repeat: int = 1) -> dict:
    settings = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10]
    return sweep("rtol", lambda r: dof2_values(task.dof2, r), settings, [1e-12, 1e-13],
                 inverse=True, repeat=repeat)


def planetary_values(section, z_max: int) -> dict:
    from . import gears
    sec = section.model_copy(update={"z_max": int(z_max)})
    d = gears.synthesize_planetary(sec).to_dict()
    return {"ratio": float(d["ratio"]), "ratio_error": abs(float(d["ratio_error"]))}


def study_planetary(task, repeat: int = 1) -> dict:
    z0 = int(task.planetary.z_max)
    settings = sorted({s for s in (30, 40, 60, 80, 100, 120, 150, 200, z0) if s >= task.planetary.z_min})
    out = sweep("z_max", lambda z: planetary_values(task.planetary, z), settings, [z0, 300],
                repeat=repeat)
    out["order"] = None      # a search, not a discretisation: no order
    return out


def run_study(task, progress: Callable[[str], None] | None = None, repeat: int = 3
              ) -> tuple[dict, dict]:
    """(study, trapezoid): the study of every stage present in `task` (see the module
    docstring) and, for the report, the flywheel's trapezoid swept on the same grids."""
    say = progress or (lambda s: None)
    out: dict = {}
    extra: dict = {}
    if task.mechanism is not None:
        from .linkage.context import build
        linkage = build(task)
        say("study: curves")
        out["curves"] = study_curves(linkage, repeat)
        if task.flywheel is not None:
            say("study: flywheel")
            out["flywheel"] = study_flywheel(task, linkage, repeat=repeat)
            tr = study_flywheel(task, linkage, quadrature=0, repeat=1)
            extra["flywheel"] = {"rows": [{k: r[k] for k in ("setting", "J_n", "error")}
                                          for r in tr["rows"]], "order": tr["order"]}
    if task.dof2 is not None:
        say("study: dof2")
        out["dof2"] = study_dof2(task)
    if task.planetary is not None:
        say("study: planetary")
        out["planetary"] = study_planetary(task)
    return out, extra


# ------------------------------------------------------------------ the report section
_W, _H, _L, _B, _T, _R = 520, 320, 64, 44, 16, 150
_COLORS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b")


def svg_loglog(series: list[tuple[str, list[float], list[float]]], xlabel: str,
               ylabel: str = "relative error") -> str:
    """A log-log plot drawn directly as SVG: series of (label, x, y), y > 0 only."""
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
        o.append(f'<text x="{x:.1f}" y="{_T + ph + 14}" text-anchor="middle">1e{k}</text>')
    for k in range(y0, y1 + 1, ystep):
        y = _T + (y1 - k) / (y1 - y0) * ph
        o.append(f'<line x1="{_L}" y1="{y:.1f}" x2="{_L + pw}" y2="{y:.1f}" stroke="#ddd"/>')
        o.append(f'<text x="{_L - 4}" y="{y + 4:.1f}" text-anchor="end">1e{k}</text>')
    o.append(f'<text x="{_L + pw / 2}" y="{_H - 6}" text-anchor="middle">{xlabel}</text>')
    o.append(f'<text x="14" y="{_T + ph / 2}" text-anchor="middle" '
             f'transform="rotate(-90 14 {_T + ph / 2})">{ylabel}</text>')
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
        o.append(f'<text x="{_L + pw + 28}" y="{ly_}">{label}</text>')
    o.append("</svg>")
    return "\n".join(o)


def _fmt(v) -> str:
    if v is None:
        return "—"
    if isinstance(v, float):
        return f"{v:.3g}" if (abs(v) < 1e-3 or abs(v) >= 1e6) and v != 0 else f"{v:.10g}"
    return str(v)


STAGE_TITLES = {"flywheel": "Flywheel (Gauss-Legendre works, extrema located)", "curves": "Output curves s, v, a",
                "dof2": "Two-degree-of-freedom motion (DOP853)", "planetary": "Planetary search"}
NOT_SWEPT = ("Not swept (no setting trades time for accuracy there): kinetostatics is solved exactly at "
             "the task's positions; the cam's r0 and rho_min are refined over continuous cam angle; the gear "
             "blocking contour is traced on a fixed internal grid.")


def html_section(study: dict, trapezoid: dict | None = None) -> str:
    """A report section: per stage the table, the measured order and a log-log plot."""
    import html as h
    parts = ["<section><h2>Accuracy against computing time</h2>",
             "<p>Each row: the setting, the values, the largest relative error against the "
             "reference (itself computed again at a finer setting: they agree to "
             f"{REF_TOL:g}) and the computing time (best of repeats).</p>"]
    for stage, d in study.items():
        rows = d["rows"]
        keys = [k for k in rows[0] if k not in ("setting", "error", "time_ms")]
        parts.append(f"<h3>{h.escape(STAGE_TITLES.get(stage, stage))}</h3>")
        order = d.get("order")
        ref = d["reference"]
        txt = f"setting <code>{h.escape(d['setting'])}</code>; reference at {_fmt(ref['setting'])}: " + \
            ", ".join(f"{k} = {_fmt(ref[k])}" for k in keys)
        txt += f"; measured order {order}" if order is not None else "; no convergence order"
        tr = (trapezoid or {}).get(stage)
        if tr:
            txt += f" (the trapezoid on the same grids: order {tr['order']})"
        parts.append(f"<p>{txt}.</p>")
        head = "".join(f"<th>{h.escape(k)}</th>" for k in ["setting", *keys, "error", "time, ms"])
        body = "".join("<tr>" + "".join(f"<td>{_fmt(r[k])}</td>" for k in ["setting", *keys, "error", "time_ms"])
                       + "</tr>" for r in rows)
        parts.append(f"<table><tr>{head}</tr>{body}</table>")
        series = [(stage, [r["setting"] for r in rows], [r["error"] for r in rows])]
        if tr:
            series.append(("trapezoid", [r["setting"] for r in tr["rows"]], [r["error"] for r in tr["rows"]]))
        parts.append(svg_loglog(series, d["setting"]))
    parts.append(f"<p>{NOT_SWEPT}</p></section>")
    return "\n".join(parts)


def write(study: dict, out, trapezoid: dict | None = None) -> list:
    """study.json and study.html (the section as a page) in the folder `out`."""
    import json
    from pathlib import Path
    from .io import atomic_write
    out = Path(out)
    page = ("<!DOCTYPE html><html><head><meta charset='utf-8'><title>Accuracy study</title>"
            "<style>body{font-family:sans-serif;max-width:60em;margin:1em auto}table{border-collapse:collapse}"
            "td,th{border:1px solid #999;padding:2px 6px;text-align:right}</style></head><body>"
            + html_section(study, trapezoid) + "</body></html>")
    return [atomic_write(out / "study.json", json.dumps(study, indent=1, allow_nan=False)),
            atomic_write(out / "study.html", page)]
