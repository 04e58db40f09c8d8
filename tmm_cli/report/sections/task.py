"""Report section 'task': title, variant, student and the task data table."""
from __future__ import annotations

import math
from typing import Any

I18N = {
    "en": {"task.sec.mechanism": "Mechanism", "task.sec.drive": "Drive",
           "task.sec.positions": "Positions", "task.sec.loads": "Loads",
           "task.sec.kinetostatics": "Kinetostatics", "task.sec.flywheel": "Flywheel",
           "task.sec.cam": "Cam mechanism", "task.sec.gears": "Gears",
           "task.sec.planetary": "Planetary gear", "task.sec.answers": "Answers",
           "task.sec.tolerance": "Tolerance"},
    "ru": {"task.sec.mechanism": "Механизм", "task.sec.drive": "Привод",
           "task.sec.positions": "Положения", "task.sec.loads": "Нагрузки",
           "task.sec.kinetostatics": "Кинетостатика", "task.sec.flywheel": "Маховик",
           "task.sec.cam": "Кулачковый механизм", "task.sec.gears": "Зубчатая передача",
           "task.sec.planetary": "Планетарный механизм", "task.sec.answers": "Ответы",
           "task.sec.tolerance": "Допуски"},
}

_META = ("schema", "schema_", "title", "variant", "student")


def _dump(task) -> dict:
    if task is None:
        return {}
    if hasattr(task, "model_dump"):
        try:
            return task.model_dump(exclude_none=True)
        except TypeError:
            return task.model_dump()
    if isinstance(task, dict):
        return task
    return {}


def _value(v: Any, fmt) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return fmt(v, 6) if isinstance(v, float) and math.isfinite(v) else str(v)
    if isinstance(v, (list, tuple)):
        if all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in v):
            return "(" + ", ".join(_value(x, fmt) for x in v) + ")"
        return "[" + ", ".join(_value(x, fmt) for x in v) + "]"
    return str(v)


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
                    out.extend(flatten(x, f"{key}[{i}]") if isinstance(x, dict)
                               else [(f"{key}[{i}]", x)])
            else:
                out.append((key, v))
    return out


def build(ctx) -> str | None:
    task = ctx.task
    data = _dump(task)
    info = []
    title = getattr(task, "title", None) or data.get("title")
    if title:
        info.append((ctx.t("task.name"), title))
    variant = getattr(task, "variant", None) if task is not None else None
    if variant is None:
        variant = data.get("variant")
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
    groups = []
    for key, sec in data.items():
        if key in _META or sec in (None, {}, []):
            continue
        rows = [(k, _value(v, ctx.fmt)) for k, v in flatten(sec)] if isinstance(sec, dict) \
            else [(key, _value(sec, ctx.fmt))]
        if rows:
            groups.append({"title": ctx.t(f"task.sec.{key}"), "rows": rows})
    if not info and not groups:
        return None
    return ctx.render("sections/task.html.j2", info=info, groups=groups)
