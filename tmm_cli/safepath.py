"""Safe output paths: a file tmm writes stays inside its output folder and names itself
in every error.

* :func:`inside` refuses to write through a symbolic link to a folder *inside* the output
  folder (``out/figures -> /elsewhere``): following it would overwrite the files of
  whatever it points to. The output folder itself may be a link (the user chose it).
* :func:`safe_stem` makes a file name of user text (no path, no hidden file, no option).
* :func:`target_error` turns an OSError met while writing a file (through its temporary
  file) into one that names the file the user asked for, never the temporary file, and
  never nothing (a full disk fails in ``write``, whose error carries no file name).
* :func:`safe_name` and :class:`UniqueNames`: the names tmm makes from what users wrote
  (a task file's stem, a variant, a student's name) as every system accepts them: no
  character Windows refuses, no Windows device name (CON, PRN, AUX, NUL, COM1-9, LPT1-9,
  with any extension), no trailing dot or space (Windows drops them), and unique as
  Windows and macOS compare names (case and Unicode normalisation folded: ``v1`` and
  ``V1`` are one folder there).
"""
from __future__ import annotations

import errno
import os
import re
import unicodedata
from pathlib import Path
from typing import Iterable

# Windows's device names: a file named so (whatever the case, whatever follows the first
# dot: "con", "Com1.yaml", "nul.form.yaml") cannot be made, or is the device
DEVICE_NAMES = frozenset({"CON", "PRN", "AUX", "NUL", "CONIN$", "CONOUT$"}
                         | {f"{p}{d}" for p in ("COM", "LPT") for d in "123456789\u00b9\u00b2\u00b3"})
_UNSAFE = re.compile(r"[^\w.-]")


def safe_name(raw: str, default: str = "file") -> str:
    """``raw`` as a file or folder name every system takes as written: anything but
    letters, digits, '.', '_' and '-' replaced by '_', no leading dot (hidden), no trailing
    dot (Windows drops it), no leading dash ('v_' before it: a command would read it as an
    option), ``default`` for nothing left, and a Windows device name (see DEVICE_NAMES) behind
    a '_' ("CON" -> "_CON", "nul.txt" -> "_nul.txt")."""
    name = _UNSAFE.sub("_", str(raw).strip()).lstrip(".").rstrip(".") or default
    if name.startswith("-"):          # a name a command reads as an option (`-1_1.yaml`)
        name = "v_" + name
    if name.split(".", 1)[0].upper() in DEVICE_NAMES:
        name = "_" + name
    return name


def fold(name: str) -> str:
    """``name`` as Windows and macOS compare names: case and Unicode normalisation aside."""
    return unicodedata.normalize("NFC", name).casefold()


class UniqueNames:
    """Names unique as :func:`fold` compares them: :meth:`take` gives ``name``, or, when a
    name of the same fold was taken, ``name{sep}2``, ``name{sep}3``... (``sep`` "": the
    name with ``suffix`` added until free)."""

    def __init__(self, taken: Iterable[str] = ()):
        self.used = {fold(n) for n in taken}

    def free(self, name: str) -> bool:
        return fold(name) not in self.used

    def take(self, name: str, sep: str = "-", suffix: str = "") -> str:
        out, k = name, 2
        while not self.free(out):
            if sep:
                out, k = f"{name}{sep}{k}", k + 1
            else:
                out += suffix
        self.used.add(fold(out))
        return out


def safe_stem(raw: str, default: str) -> str:
    """A file or folder name made from user text (a variant, a task file's stem): as
    :func:`safe_name` makes it (no leading dash either)."""
    return safe_name(raw, default)


class SymlinkedFolder(OSError):
    """A folder inside the output folder is a symbolic link."""


def inside(root: str | os.PathLike, name: str | os.PathLike) -> Path:
    """``root / name`` after checking that it stays inside ``root`` and that no folder
    between them is a symbolic link; the missing folders are created (and checked again,
    so a link put in place meanwhile is still refused)."""
    root = Path(root)
    rel = Path(name)
    if rel.is_absolute() or ".." in rel.parts:
        raise SymlinkedFolder(errno.EINVAL, "the file name leaves the output folder", str(root / rel))
    folder = root
    for part in rel.parts[:-1]:
        folder = folder / part
        for attempt in (0, 1):
            if os.path.islink(folder):
                raise SymlinkedFolder(
                    errno.ELOOP, f"{folder} is a symbolic link to {os.readlink(folder)}; tmm does not write "
                                 f"through a linked folder inside the output folder (remove the link)",
                    str(root / rel))
            if attempt == 0:
                try:
                    folder.mkdir(exist_ok=True)
                except FileExistsError:  # a file in the way: the write reports it
                    break
    return root / rel


def target_error(exc: OSError, target: str | os.PathLike) -> OSError:
    """``exc`` (same class and errno) naming ``target`` as the file that failed."""
    if exc.filename is not None and Path(exc.filename) == Path(target):
        return exc
    if exc.errno is None:
        return OSError(errno.EIO, str(exc) or type(exc).__name__, str(target))
    return type(exc)(exc.errno, exc.strerror or os.strerror(exc.errno), str(target))
