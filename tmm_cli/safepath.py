"""Safe output paths: a file tmm writes stays inside its output folder and names itself
in every error.

* :func:`inside` refuses to write through a symbolic link to a folder *inside* the output
  folder (``out/figures -> /elsewhere``): following it would overwrite the files of
  whatever it points to. The output folder itself may be a link (the user chose it).
* :func:`safe_stem` makes a file name of user text (no path, no hidden file, no option).
* :func:`target_error` turns an OSError met while writing a file (through its temporary
  file) into one that names the file the user asked for, never the temporary file, and
  never nothing (a full disk fails in ``write``, whose error carries no file name).
"""
from __future__ import annotations

import errno
import os
from pathlib import Path


def safe_stem(raw: str, default: str) -> str:
    """A file or folder name made from user text (a variant, a task file's stem): letters,
    digits, '.', '_' and '-' kept, anything else '_'; no leading dot (a hidden file) and no
    leading dash (a name a command reads as an option: `-1_1.yaml`): such a name gets 'v_'
    before it. ``default`` for nothing left."""
    import re
    name = re.sub(r"[^\w.-]", "_", raw).lstrip(".") or default
    return "v_" + name if name.startswith("-") else name


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
