"""What tmm keeps between runs beside Python's bytecode: a file of two pickles, a stamp (what
the kept value depends on: versions, the sizes and times of its sources) and the value.

Read back only while the stamp is the one asked for; written only where Python writes bytecode
(not with ``PYTHONDONTWRITEBYTECODE``), whole or not at all (a temporary file put in place); a
file that cannot be read or written is no kept value, never an error.  The task model's
validator (:mod:`tmm_cli.schemacache`) and the catalogues (:mod:`tmm_cli.locales`) use it.
Standard library only: the modules that use it are loaded before anything else of tmm's.
"""
from __future__ import annotations

import os
import pickle
import sys
from pathlib import Path

MISSING = object()
"""What :func:`read` gives where nothing is kept for the stamp."""


def read(path: Path, stamp):
    """The value kept at ``path`` with ``stamp``, else :data:`MISSING` (none, another stamp, or a
    file that cannot be read)."""
    try:
        with open(path, "rb") as fh:
            if pickle.load(fh) != stamp:
                return MISSING
            return pickle.load(fh)
    except Exception:  # noqa: BLE001 - a kept file that cannot be read is none: the caller makes the value
        return MISSING


def write(path: Path, stamp, value=MISSING, *, pickled: bytes | None = None) -> None:
    """Keep ``value`` (or its pickle ``pickled``, already made) at ``path`` with ``stamp``;
    nothing where bytecode is not written or the file cannot be."""
    if sys.dont_write_bytecode:
        return
    tmp = path.with_name(f"{path.name}.{os.getpid()}.tmp")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        with open(tmp, "wb") as fh:
            pickle.dump(stamp, fh, protocol=pickle.HIGHEST_PROTOCOL)
            if pickled is not None:
                fh.write(pickled)
            else:
                pickle.dump(value, fh, protocol=pickle.HIGHEST_PROTOCOL)
        os.replace(tmp, path)
    except Exception:  # noqa: BLE001 - a value that cannot be kept is none: the next run makes it again
        try:
            tmp.unlink(missing_ok=True)
        except OSError:
            pass
