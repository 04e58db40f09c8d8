"""Reproducible output files: two runs on the same task write the same bytes.

- ``source_date()``: the date written into outputs (the report's footer, the DXF header, a day):
  the time given by ``SOURCE_DATE_EPOCH`` (seconds since 1970, UTC; the reproducible-builds
  convention) when it is set, else now.
- ``dxf_text(doc)``: an ezdxf document as DXF text without the random GUIDs, the clock
  time and the hash-seed order of classes ezdxf writes: the GUIDs are derived from the
  drawing itself (always the same), the dates are the day of ``source_date()``.
"""
from __future__ import annotations

import datetime as _dt
import os
import re

__all__ = ["source_date", "dxf_text"]


def source_date() -> _dt.datetime:
    """SOURCE_DATE_EPOCH as an aware UTC datetime when set (and an integer), else now (local)."""
    raw = os.environ.get("SOURCE_DATE_EPOCH", "").strip()
    if raw:
        try:
            return _dt.datetime.fromtimestamp(int(raw), tz=_dt.timezone.utc)
        except (ValueError, OverflowError, OSError):
            pass                      # not a number of seconds: ignored, as other tools do
    return _dt.datetime.now().astimezone().replace(microsecond=0)


_CONST_GUID = "{00000000-0000-0000-0000-000000000000}"
_DATE_VARS = ("$TDCREATE", "$TDUCREATE", "$TDUPDATE", "$TDUUPDATE")


def dxf_text(doc) -> str:
    """The DXF text of an ezdxf document, the same for the same drawing: ezdxf's fixed
    metadata (its option for comparable files) with the GUIDs a hash of the drawing and the
    creation/update dates the day of ``source_date()``."""
    import hashlib
    import io
    import uuid

    import ezdxf
    from ezdxf.document import CONST_MARKER_STRING, CREATED_BY_EZDXF
    from ezdxf.tools.juliandate import juliandate

    # the date of the run, as in the report's footer (a day: two runs of one day are identical)
    when = source_date()
    day = _dt.datetime.combine(when.date(), _dt.time())
    stamp = _dt.datetime.combine(when.date(), _dt.time(), tzinfo=when.tzinfo).isoformat()
    # "created by ezdxf <version> @ <time>" was stamped with the clock by ezdxf.new()
    doc.ezdxf_metadata()[CREATED_BY_EZDXF] = CONST_MARKER_STRING
    # the CLASSES of the entity types in use come from a set (an order that follows string
    # hashing, different in every process): added now, in the order of their names
    doc.classes.add_required_classes(doc.dxfversion)
    doc.classes.classes = dict(sorted(doc.classes.classes.items()))
    buf = io.StringIO()
    before = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        doc.write(buf)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = before
    text = buf.getvalue()
    digest = hashlib.sha256(text.encode("utf-8")).digest()    # the drawing, without the dates
    guids = ("{" + str(uuid.UUID(bytes=hashlib.sha256(digest + bytes([k])).digest()[:16], version=4)).upper() + "}"
             for k in range(2))
    text = re.sub(re.escape(_CONST_GUID), lambda m: next(guids, _CONST_GUID), text)
    for var in _DATE_VARS:
        text = re.sub(r"(\n\s*9\r?\n" + re.escape(var) + r"\r?\n\s*40\r?\n)[^\r\n]*",
                      lambda m: m.group(1) + repr(juliandate(day)), text, count=1)
    text = text.replace(CONST_MARKER_STRING, f"{ezdxf.__version__} @ {stamp}")
    return text
