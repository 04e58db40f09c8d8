"""Hostile tasks for the escaping tests (issue 10, item 3): every name and free-text field
of a real task replaced by markup that would run script if it reached HTML or SVG raw.

``hostile_task(base)`` returns the task as a dict (load it with ``load_task`` or write it
with ``write_hostile``); ``raw_markup(text)`` lists what of the hostile markup survives
unescaped in an HTML or SVG text."""
from __future__ import annotations

import copy
import re
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parents[1]

# markup that runs script or breaks out of an attribute, plus the characters that need
# escaping; each hostile string carries a unique tag so a test can tell them apart
PAYLOADS = (
    '<script>alert("{k}")</script>',
    "<img src=x onerror=alert('{k}')>",
    '"><svg onload=alert({k})>',
    "<b>&amp;{k}</b> & 'q'",
)

# what must never appear in the output: an opening tag of the payloads (escaped, they read
# `&lt;script`; an attribute broken out of by `">` leaves a raw `<svg onload`)
RAW = re.compile(r"<\s*(script|img\b|svg\s+onload|b>&amp;)", re.I)


def hostile(key: str, n: int = 0) -> str:
    """A hostile string for ``key`` (``n`` picks the payload): starts with the key so names
    stay distinct, ends with markup."""
    return f"{key}" + PAYLOADS[n % len(PAYLOADS)].format(k=key)


def _rename_points(data: dict, names: dict[str, str]) -> None:
    """Rename points and links in a mechanism task, in every place that refers to them."""
    mech = data["mechanism"]
    mech["ground"] = {names.get(k, k): v for k, v in mech["ground"].items()}
    mech["assembly"] = {names.get(k, k): v for k, v in mech.get("assembly", {}).items()}
    links = {}
    for lname, spec in mech["links"].items():
        spec = dict(spec)
        if "points" in spec:
            spec["points"] = [names.get(p, p) for p in spec["points"]]
        if "slider" in spec:
            spec["slider"] = names.get(spec["slider"], spec["slider"])
        if "extra" in spec:
            spec["extra"] = {names.get(k, k): v for k, v in spec["extra"].items()}
        if isinstance(spec.get("com"), str):
            spec["com"] = names.get(spec["com"], spec["com"])
        g = spec.get("guide")
        if isinstance(g, dict):
            g = dict(g)
            for key in ("through", "link"):
                if isinstance(g.get(key), str):
                    g[key] = names.get(g[key], g[key])
            spec["guide"] = g
        links[names.get(lname, lname)] = spec
    mech["links"] = links
    drive = data.get("drive", {})
    if "link" in drive:
        drive["link"] = names.get(drive["link"], drive["link"])
    pos = data.get("positions", {})
    if pos.get("output"):
        pos["output"] = names.get(pos["output"], pos["output"])
    for f in data.get("loads", {}).get("forces", []):
        f["on"] = names.get(f["on"], f["on"])
        if isinstance(f.get("at"), str):
            f["at"] = names.get(f["at"], f["at"])
    ks = data.get("kinetostatics", {})
    if ks.get("balance"):
        ks["balance"] = names.get(ks["balance"], ks["balance"])


def hostile_task(base: str | Path = ROOT / "tasks" / "forging_sixbar.yaml") -> dict:
    """The task at ``base`` with hostile title, variant, student and (for a linkage) every
    point and link name."""
    from tmm_cli.yamlload import load_yaml  # YAML 1.2: the key `on:` stays a string
    data = copy.deepcopy(load_yaml(base)[0])
    data["title"] = hostile("title", 0)
    data["variant"] = hostile("variant", 1)
    data["student"] = {"name": hostile("student", 2), "group": hostile("group", 3)}
    if "mechanism" in data:
        mech = data["mechanism"]
        names: dict[str, str] = {}
        points = set(mech["ground"]) | set(mech.get("assembly", {}))
        for spec in mech["links"].values():
            points |= set(spec.get("points", [])) | set(spec.get("extra", {}))
            if spec.get("slider"):
                points.add(spec["slider"])
        for i, p in enumerate(sorted(points)):
            names[p] = hostile(p, i)
        for i, lname in enumerate(mech["links"]):
            names[lname] = hostile(lname, i + 1)
        _rename_points(data, names)
    return data


def hostile_full_task(base: str | Path = ROOT / "tasks" / "forging_sixbar.yaml") -> dict:
    """``hostile_task(base)`` with the cam, gears and planetary sections of the example tasks
    added, so one run draws every section of the report."""
    from tmm_cli.yamlload import load_yaml
    data = hostile_task(base)
    for name, section in (("cam_rocker", "cam"), ("gears_shifted", "gears"), ("planetary_A", "planetary")):
        data[section] = load_yaml(ROOT / "tasks" / f"{name}.yaml")[0][section]
    return data


def write_hostile(path: Path, data: dict | None = None) -> Path:
    """Write a hostile task (default: ``hostile_full_task()``) as YAML to ``path``."""
    data = hostile_full_task() if data is None else data
    path.write_text(yaml.safe_dump(data, allow_unicode=True, sort_keys=False), encoding="utf-8")
    return path


def raw_markup(text: str) -> list[str]:
    """Every place in ``text`` where hostile markup survived unescaped (with context)."""
    return [text[max(0, m.start() - 60):m.end() + 20] for m in RAW.finditer(text)]
