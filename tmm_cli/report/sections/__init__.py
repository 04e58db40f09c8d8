"""Report sections, in the order they appear in the report.

Each section is a module ``tmm_cli.report.sections.<name>`` with
``build(ctx) -> str | None``; a module that does not exist (yet) is skipped.
"""
from __future__ import annotations

import importlib
from types import ModuleType

from .. import i18n

ORDER = ("task", "synthesis", "structure", "kinematics", "kinetostatics", "worked", "dynamics", "balancing", "cam", "gears",
         "planetary", "drive_train", "differential", "dof2", "study")


def load(name: str) -> ModuleType | None:
    """Import a section module; None if it is absent.  Registers its I18N table."""
    modname = f"{__name__}.{name}"
    try:
        mod = importlib.import_module(modname)
    except ModuleNotFoundError as exc:
        if exc.name == modname:
            return None
        raise
    table = getattr(mod, "I18N", None)
    if table and not getattr(mod, "_i18n_registered", False):
        i18n.register(table)
        mod._i18n_registered = True
    return mod


def available() -> list[tuple[str, ModuleType]]:
    out = []
    for name in ORDER:
        mod = load(name)
        if mod is not None and hasattr(mod, "build"):
            out.append((name, mod))
    return out
