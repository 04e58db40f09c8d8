"""What differs between Linux, macOS and Windows, in one place (docs/platforms.md).

* :func:`start_method`: how ``tmm batch`` starts its workers: ``fork`` where it exists
  (Linux: the workers start warm, with the batch process's modules already imported),
  ``spawn`` elsewhere (Windows; macOS, where forking a process that has used system
  frameworks is not safe). ``TMM_START_METHOD=spawn`` forces spawn on Linux too, so the
  spawn-only platforms' path is tested there; then no second process is forked anywhere
  (the report's helper, a results file written aside: :func:`can_fork`).
* :func:`utf8_console`: stdout/stderr that cannot encode Cyrillic (a Windows console in
  a legacy code page, output redirected under a non-UTF-8 locale) reconfigured to UTF-8,
  unencodable characters replaced rather than a UnicodeEncodeError.
"""
from __future__ import annotations

import os
import sys

START_METHOD_ENV = "TMM_START_METHOD"


def start_method() -> str:
    """``fork`` or ``spawn`` (see the module's text); an unknown or unavailable value of
    TMM_START_METHOD is ignored."""
    import multiprocessing
    methods = multiprocessing.get_all_start_methods()
    asked = os.environ.get(START_METHOD_ENV, "").strip().lower()
    if asked in ("fork", "spawn") and asked in methods:
        return asked
    if "fork" in methods and hasattr(os, "fork") and sys.platform != "darwin":
        return "fork"
    return "spawn"


def can_fork() -> bool:
    """A child process may be forked from this one (``os.fork`` exists and fork is the
    start method in use)."""
    return hasattr(os, "fork") and start_method() == "fork"


def utf8_console() -> None:
    """stdout and stderr write UTF-8 (errors replaced) where their encoding cannot encode
    Cyrillic text; a UTF-8 stream or one that cannot be reconfigured is left as it is."""
    for stream in (sys.stdout, sys.stderr):
        if stream is None or not hasattr(stream, "reconfigure"):
            continue
        enc = getattr(stream, "encoding", None) or "ascii"
        try:
            "\u0416\u0456".encode(enc)     # Cyrillic Zhe, Ukrainian i
            continue
        except (UnicodeEncodeError, LookupError):
            pass
        try:
            stream.reconfigure(encoding="utf-8", errors="replace")
        except (ValueError, OSError, AttributeError):
            pass
