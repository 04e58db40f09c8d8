"""Report section 'task': title, variant, student and the task data.

The mechanism is shown as an instructor writes the data of a variant: a table of
the fixed points, a table of the links (points, length, mass, moment of inertia,
centre of mass, guide) and the assembly hints; every other section of the task
file as 'parameter — value with its unit' (SI, angles in degrees, as the task
model stores them).  Lists of numbers are written '0; 0.7; 0.9', coordinates
'(0.5, 0.37) m'."""
from __future__ import annotations

import math
import re
from typing import TYPE_CHECKING, Any

from ... import locales
from ...messages import unit as spelt
from ...numfmt import localize
from ..notation import Term

if TYPE_CHECKING:
    from ...task import Task

I18N = locales.table("task", "words")

_META = ("schema", "schema_", "title", "variant", "student", "course")

# the names of the task file's parameters (by the key without list indices), the names of a
# list's items, the words of its word values and the units of its numbers (SI; angles in
# degrees) by the key's last part: the catalogues' topic `task`
PARAMS = locales.table("task", "params")
ITEMS = locales.table("task", "items")
WORDS = locales.table("task", "values")
_UNITS = locales.table("task", "units")
# the metre in every language's spelling (a pair of numbers in metres is a point)
_METRES = tuple(_UNITS[lang]["length"] for lang in _UNITS)


def _dump(task: Task | None) -> dict:
    if task is None:
        return {}
    try:
        # the model's serializer made from the cached schema (as its validator is):
        # model_dump would build the whole model first (~40 ms)
        from ...schemacache import serializer
        return serializer(type(task)).to_python(task, exclude_none=True, by_alias=True)
    except TypeError:
        return task.model_dump()


def num(v: float) -> str:
    """A task number as written: 6 significant digits, no trailing zeros (the decimal
    comma in ru and uk)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if not math.isfinite(v):
        return str(v)
    if v == 0:
        return "0"
    if 1e-4 <= abs(v) < 1e10:
        import numpy as np
        s = np.format_float_positional(float(f"{v:.6g}"), trim="-")
    else:
        mant, ex = f"{v:.5e}".split("e")
        s = f"{mant.rstrip('0').rstrip('.')}·10{str(int(ex)).translate(_SUP)}"
    return localize(s).replace("-", "−")


_SUP = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def _is_num(x) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def _value(v: Any, unit: str = "") -> str:
    """A leaf value in words: coordinates '(0.5, 0.37) m', a list '0; 0.7; 0.9',
    names 'O, A', a number with its unit."""
    u = f" {unit}" if unit else ""
    if isinstance(v, bool):
        return "true" if v else "false"
    if _is_num(v):
        return num(v) + ("" if unit == "°" else " ") + unit if unit else num(v)
    if isinstance(v, (list, tuple)):
        if len(v) == 2 and all(_is_num(x) for x in v) and unit in _METRES:
            return f"({num(v[0])}, {num(v[1])}){u}"
        if all(_is_num(x) for x in v):
            return "; ".join(num(x) for x in v) + (u if v else "")
        if v and all(isinstance(x, (list, tuple)) and x and all(_is_num(y) for y in x) for x in v):
            return ", ".join("(" + "; ".join(num(y) for y in x) + ")" for x in v) + u     # points
        return ", ".join(str(x) for x in v)
    return _quantity(str(v))


_WRITTEN = re.compile(r"^([-+]?(?:\d+(?:[.,]\d*)?|\.\d+)(?:[eE][-+]?\d+)?)\s*([^\d\s].*?)\s*$")


def _quantity(text: str) -> str:
    """A value the task gives as a number with its unit ('1.2 rad/s', '0.4 m/s') in the
    report's language: its number as the language writes it, the unit in its spelling."""
    m = _WRITTEN.match(text)
    if not m:
        return text
    unit = spelt(m.group(2))
    return localize(m.group(1).replace(",", ".")) + ("" if unit == "°" else " ") + unit


def flatten(d: Any, prefix: str = "") -> list[tuple[str, Any]]:
    """Nested dict -> [(dotted.key, leaf)], lists of scalars stay leaves."""
    out: list[tuple[str, Any]] = []
    if isinstance(d, dict):
        for k, v in d.items():
            key = f"{prefix}.{k}" if prefix else str(k)
            if v is None or v == {} or v == []:
                continue
            if isinstance(v, dict):
                out.extend(flatten(v, key))
            elif isinstance(v, (list, tuple)) and any(isinstance(x, dict) for x in v):
                for i, x in enumerate(v):
                    out.extend(flatten(x, f"{key}[{i + 1}]") if isinstance(x, dict)
                               else [(f"{key}[{i + 1}]", x)])
            else:
                out.append((key, v))
    return out


def _unit(key: str, lang: str, context: dict | None = None) -> str:
    units = _UNITS.get(lang, _UNITS["en"])
    last = key.split(".")[-1].split("[")[0]
    if last == "value" and ".diagram" in key:
        # a load diagram's ordinate: N, or Pa for a pressure (the force has an area)
        return spelt("Pa", lang) if (context or {}).get("area") else spelt("N", lang)
    if last == "magnitude" and (context or {}).get("area"):
        return spelt("Pa", lang)
    if last == "s" and ".diagram" in key:
        return ""
    if last == "stroke" and isinstance((context or {}).get("stroke"), (int, float)):
        return units["angle"] if (context or {}).get("follower") == "rocker" else units["length"]
    if last == "m" and not key.startswith(("gears", "planetary", "differential")):
        return ""
    if key.startswith("balancing.counterweights.radius."):
        return ""                  # `rocker` here names a link, not the synthesis' rocker length (m)
    return units.get(last, "")


def _param(plain: str, lang: str, prefix: str = "task.param") -> str | None:
    """A parameter's name from a section's own word table (``task.param.<path>``), if it has one."""
    from ..i18n import translate
    from . import available
    available()                     # every section's word table registered
    key = f"{prefix}.{plain}"
    text = translate(key, lang)
    return None if text == key else text


def param_name(plain: str, lang: str) -> str | None:
    """The name the task data table gives the field ``plain`` (``cam.stroke``), or None."""
    return PARAMS.get(lang, {}).get(plain) or _param(plain, lang)


def word_of(plain: str, value: str, lang: str) -> str | None:
    """How the task data table writes the word ``value`` of the field ``plain``: a section's own
    word for that field (``task.word.<path>.<value>``), else the common table, else None."""
    own = _param(f"{plain}.{value}", lang, prefix="task.word")
    return own if own is not None else WORDS.get(lang, {}).get(value)


# the cam fields that only a rocker follower has, and the ones it has not (its stroke is a swing)
_ROCKER_ONLY = ("cam.swing", "cam.rocker_length", "cam.center_distance")
_TRANSLATING_ONLY = ("cam.offset",)


def _rows(key: str, sec: Any, lang: str) -> list[tuple[str, str]]:
    if not isinstance(sec, dict):
        return [(key, _value(sec))]
    rows = []
    for k, v in flatten(sec):
        ctx = dict(sec)
        # the dicts holding this leaf (for the units of a force with an area, a cam's stroke)
        parts = k.replace("]", "").split(".")
        node: Any = sec
        for p in parts[:-1]:
            name, _, idx = p.partition("[")
            node = node.get(name) if isinstance(node, dict) else None
            if idx and isinstance(node, list):
                node = node[int(idx) - 1]
            if isinstance(node, dict):
                ctx.update(node)
        plain = re.sub(r"\[\d+\]", "", f"{key}.{k}")
        rocker = key == "cam" and sec.get("follower") == "rocker"
        if (plain in _ROCKER_ONLY and not rocker) or (plain in _TRANSLATING_ONLY and rocker):
            continue                     # a rocker's default ('swing: auto') says nothing of another follower
        # a field given as a list may have a name of its own ('task.param.synthesis.points[]': path points)
        label = (isinstance(v, list) and _param(plain + "[]", lang)) or param_name(plain, lang)
        if rocker and plain == "cam.stroke":        # a rocker's stroke is its swing, in degrees
            label = param_name("cam.stroke_rocker", lang) or label
        if key == "synthesis":          # a field named by the type ('rocker': a crank-rocker's or a slotted link)
            label = PARAMS.get(lang, {}).get(f"{plain}.{sec.get('type')}") or label
        # a catalogue's name: its notation with subscripts in the HTML; a path of the task as written
        label = Term(label) if label else k.replace(".", " · ")
        idx = re.findall(r"(\w+)\[(\d+)\]", k)
        if idx and plain in PARAMS.get(lang, {}):
            item = ITEMS.get(lang, {}).get(idx[-1][0], idx[-1][0])
            label = Term(f"{item} {idx[-1][1]}: {label}")
        val = _value(v, _unit(f"{key}.{k}", lang, ctx))
        if plain == "flywheel.delta" and isinstance(v, float):
            from ...units import fraction_text
            frac = fraction_text(v)
            val = f"{frac} = {_value(v)}" if frac.startswith("1/") else val
        if isinstance(v, (str, bool)):    # a word agreeing with its label's noun ('key=value') first
            words = WORDS.get(lang, {})
            val = words.get(f"{plain}={val}") or (word_of(plain, val, lang) if isinstance(v, str) else None) \
                or words.get(val, val)
        rows.append((label, val))
    return rows


def _mechanism(ctx, mech: dict):
    """(ground rows, link rows, assembly text) of the mechanism section."""
    t = ctx.t
    ground = [(p, num(xy[0]), num(xy[1])) for p, xy in (mech.get("ground") or {}).items()]
    drive = ((ctx.task.drive.link if ctx.task is not None and ctx.task.drive is not None else None)
             if ctx.task is not None else None)
    links = []
    for i, (name, spec) in enumerate((mech.get("links") or {}).items(), start=1):
        pts = list(spec.get("points") or [])
        other = []
        if spec.get("slider"):
            pts = [spec["slider"]]
        g = spec.get("guide") or {}
        if g:
            gd = []
            if g.get("link"):
                gd.append(t("task.guide_link", l=g["link"]))
            if g.get("through") is not None:
                th = g["through"]
                gd.append(t("task.guide_through", p=_value(th, spelt("m", ctx.lang))
                            if not isinstance(th, str) else th))
            if g.get("angle") is not None and not g.get("link"):
                gd.append(t("task.guide_angle", a=num(g["angle"])))
            elif g.get("angle") is not None and g.get("angle") != 0:
                gd.append(t("task.guide_angle", a=num(g["angle"])))
            if g.get("offset"):
                gd.append(t("task.guide_offset", o=num(g["offset"])))
            other.append(t("task.guide_word") + " " + ", ".join(gd))
        if spec.get("extra"):
            other.append(t("task.extra", p=", ".join(f"{p} ({num(xy[0])}, {num(xy[1])})"
                                                     for p, xy in spec["extra"].items())))
        com = spec.get("com")
        com_txt = f"({num(com[0])}, {num(com[1])})" if isinstance(com, (list, tuple)) else \
            (str(com) if com else "")
        if not com_txt:                   # the default, said (a crank's S at its pivot is no blank)
            pivots = [p for p in pts if p in (mech.get("ground") or {})]
            com_txt = (pivots[0] if name == drive and pivots else pts[0] if spec.get("slider") and pts
                       else t("task.com_middle") if len(pts) == 2 else "")
        links.append((str(i), name, ", ".join(pts), num(spec["length"]) if spec.get("length") is not None else "",
                       num(spec["mass"]) if spec.get("mass") is not None else "",
                       num(spec["J"]) if spec.get("J") is not None else "", com_txt, "; ".join(other)))
    m = spelt("m", ctx.lang)
    assembly = ", ".join(f"{p} ({num(xy[0])}, {num(xy[1])})" for p, xy in (mech.get("assembly") or {}).items())
    return ground, links, (assembly + f" {m}") if assembly else ""


def build(ctx) -> str | None:
    task = ctx.task
    data = _dump(task)
    info = []
    title = task.title if task is not None else None
    if title:
        info.append((ctx.t("task.name"), title))
    variant = task.variant if task is not None else None
    if variant is not None:
        info.append((ctx.t("task.variant"), str(variant)))
    student = data.get("student") or {}
    if isinstance(student, dict):
        if student.get("name"):
            info.append((ctx.t("task.student"), str(student["name"])))
        if student.get("group"):
            info.append((ctx.t("task.group"), str(student["group"])))
        for k, v in student.items():
            if k not in ("name", "group") and v not in (None, ""):
                info.append((str(k), str(v)))
    elif student:
        info.append((ctx.t("task.student"), str(student)))
    mech = None
    groups = []
    for key, sec in data.items():
        if key in _META or sec in (None, {}, []):
            continue
        if key == "mechanism" and isinstance(sec, dict):
            mech = _mechanism(ctx, sec)
            continue
        rows = _rows(key, sec, ctx.lang)
        if rows:
            groups.append({"title": ctx.t(f"task.sec.{key}"), "rows": rows})
    if not info and not groups and mech is None:
        return None
    return ctx.render("sections/task.html.j2", info=info, groups=groups, mech=mech,
                      J_head=ctx.t("task.J"))
