"""Terminal output with rich: the run summary and the check table."""
from __future__ import annotations

from pathlib import Path


def _console():
    from rich.console import Console
    return Console(stderr=False, highlight=False)


def _f(x, digits=5) -> str:
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, (int,)) and not isinstance(x, bool):
        return str(x)
    try:
        return f"{float(x):.{digits}g}"
    except (TypeError, ValueError):
        return str(x)


def print_summary(results: dict, paths: list[Path]) -> None:
    from rich.table import Table

    con = _console()
    t = Table(title=f"tmm: {results.get('task', {}).get('title') or ''}", show_header=True)
    t.add_column("quantity")
    t.add_column("value", justify="right")
    st = results.get("structure")
    if st:
        t.add_row("W = 3n - 2p5 - p4", f"{st['W']} (n={st['n']}, p5={st['p5']}, p4={st['p4']})")
        t.add_row("structure formula", str(st.get("formula")))
    pos = results.get("positions")
    if pos:
        t.add_row("phi0, deg", _f(pos.get("phi0")))
        if pos.get("K") is not None:
            t.add_row("K (mean speed increase)", _f(pos.get("K")))
    if results.get("singular"):
        t.add_row("singular crank angles, deg", ", ".join(_f(s, 7) for s in results["singular"]))
    fw = results.get("flywheel")
    if fw:
        t.add_row("flywheel J, kg*m^2", _f(fw.get("J")))
        t.add_row("flywheel D x b, m", f"{_f(fw.get('diameter'))} x {_f(fw.get('width'))}")
    cam = results.get("cam")
    if cam:
        t.add_row("cam r0, m", _f(cam.get("r0")))
        if cam.get("r0_given"):
            t.add_row("cam r0_min, m", _f(cam.get("r0_min")))
            t.add_row("cam max pressure angle, deg", _f(cam.get("max_pressure_angle")))
    g = results.get("gears")
    if g:
        t.add_row("gears a_w, m", _f(g.get("aw")))
        t.add_row("contact ratio", _f(g.get("eps_alpha")))
    pl = results.get("planetary")
    if pl:
        t.add_row("planetary z", ", ".join(f"{k}={v}" for k, v in (pl.get("z") or {}).items()))
        t.add_row("planetary ratio", _f(pl.get("ratio")))
    dt = results.get("drive_train")
    if dt:
        t.add_row("drive train z", " | ".join("/".join(str(v) for v in s["z"]) for s in dt.get("stages", [])))
        t.add_row("drive train ratio", _f(dt.get("ratio")))
        if dt.get("motor_power_computed"):
            t.add_row("motor power, W", _f(dt.get("motor_power")))
    con.print(t)
    for w in results.get("warnings", []):
        con.print(f"[yellow]warning:[/yellow] {w}")
    for p in paths:
        con.print(f"wrote {p}")


def print_check(rows: list[dict], source) -> None:
    from rich.table import Table

    con = _console()
    t = Table(title=f"check: {source}")
    t.add_column("quantity", overflow="fold", min_width=16)
    for c, j in (("student", "right"), ("reference", "right"),
                 ("rel. error", "right"), ("tolerance", "right")):
        t.add_column(c, justify=j, no_wrap=True)
    t.add_column("verdict", overflow="fold", min_width=7)
    for r in rows:
        v = r["verdict"]
        style = {"ok": "green", "wrong": "red"}.get(v, "yellow")
        err = "-" if r["rel_error"] is None else f"{100 * r['rel_error']:.2f} %"
        t.add_row(r["quantity"], _f(r["student"]), _f(r["reference"]), err, f"{100 * r['tolerance']:.1f} %",
                  f"[{style}]{v}[/{style}]" + (f" ({r['note']})" if r.get("note") else ""))
    con.print(t)
    n_ok = sum(r["verdict"] == "ok" for r in rows)
    con.print(f"{n_ok} of {len(rows)} answers within tolerance")
