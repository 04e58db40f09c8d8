"""Two runs on the same task write the same bytes in every output file (report.html and
its figures, report.pdf, the DXF and CSV files, the sheets, batch summaries) when
SOURCE_DATE_EPOCH is set; without it only the dates (days) differ, never an id.

The runs are separate processes with different PYTHONHASHSEED (an order that depends on
string hashing shows), one pair for the whole module: a linkage, a cam and a gear task
with every format, and a small batch."""
from __future__ import annotations

import datetime as dt
import io
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from tmm_cli.io import MANIFEST
from tmm_cli.reproducible import dxf_text, source_date

ROOT = Path(__file__).resolve().parents[1]
TASKS = ["engine_slider_crank", "cam_knife", "gears_auto"]
BATCH = ["cam_knife", "planetary_A"]
EPOCH = 1700000000                                   # 2023-11-14 22:13:20 UTC


def _side(dest: Path, src: Path, seed: str) -> list[subprocess.Popen]:
    env = {**os.environ, "SOURCE_DATE_EPOCH": str(EPOCH), "PYTHONHASHSEED": seed}
    run = [sys.executable, "-m", "tmm_cli"]
    procs = [subprocess.Popen([*run, "run", str(ROOT / "tasks" / f"{t}.yaml"), "--out", str(dest / t),
                               "--format", "json,html,pdf,sheets", "--quiet"], env=env, cwd=ROOT,
                              stdout=subprocess.DEVNULL, stderr=subprocess.PIPE) for t in TASKS]
    procs.append(subprocess.Popen([*run, "batch", str(src), "--out", str(dest / "batch"), "--format", "json,html"],
                                  env=env, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE))
    return procs


@pytest.fixture(scope="module")
def two_runs(tmp_path_factory):
    a, b = tmp_path_factory.mktemp("a"), tmp_path_factory.mktemp("b")
    src = tmp_path_factory.mktemp("batch_in")           # one input folder: its path is in the outputs
    for t in BATCH:
        (src / f"{t}.yaml").write_bytes((ROOT / "tasks" / f"{t}.yaml").read_bytes())
    procs = _side(a, src, "1") + _side(b, src, "4")         # 1 and 4: two orders of a set of str
    for p in procs:
        _, err = p.communicate(timeout=600)
        assert p.returncode in (0, 1), err.decode(errors="replace")[-2000:]
    return a, b


def _files(root: Path) -> dict[str, bytes]:
    # the manifest records each written file's modification time (tmm's own bookkeeping)
    return {p.relative_to(root).as_posix(): p.read_bytes() for p in root.rglob("*")
            if p.is_file() and p.name != MANIFEST}


def test_every_output_file_is_byte_identical(two_runs):
    fa, fb = (_files(r) for r in two_runs)
    assert sorted(fa) == sorted(fb)
    kinds = {Path(k).suffix for k in fa}
    assert {".json", ".html", ".pdf", ".svg", ".dxf", ".csv"} <= kinds        # every kind was compared
    assert any(k.startswith("batch/summary") for k in fa)
    assert [k for k in fa if fa[k] != fb[k]] == []


def test_the_epoch_is_the_report_date_and_the_dxf_date(two_runs):
    a = two_runs[0]
    html = (a / "cam_knife" / "report.html").read_text(encoding="utf-8")
    assert re.search(r'class="report-foot">[^<]*2023-11-14<', html)
    import ezdxf
    from ezdxf.tools.juliandate import calendardate
    text = (a / "cam_knife" / "cam_profile.dxf").read_text(encoding="utf-8")
    stamp = float(re.search(r"\$TDUUPDATE\r?\n\s*40\r?\n([^\r\n]+)", text).group(1))
    assert abs(calendardate(stamp) - dt.datetime(2023, 11, 14)) < dt.timedelta(seconds=1)     # the day
    assert "{00000000-" not in text                                    # GUIDs, not ezdxf's placeholder
    ezdxf.read(io.StringIO(text))                                      # still a DXF ezdxf reads


def test_figures_of_one_report_never_share_an_id(two_runs):
    html = (two_runs[0] / "gears_auto" / "report.html").read_text(encoding="utf-8")
    ids = re.findall(r'\bid="([^"]+)"', html)
    ids = [i for i in ids if re.fullmatch(r"c[0-9a-f]{12}-\d+", i)]      # the charts' clip paths
    assert len(ids) >= 3 and len(ids) == len(set(ids))              # the mesh, the sliding, the contour


def test_dxf_ids_fixed_without_epoch_dates_follow_it(monkeypatch):
    import ezdxf

    def drawing():
        doc = ezdxf.new("R2010", setup=True)
        doc.modelspace().add_line((0, 0), (1, 2))
        return doc

    monkeypatch.delenv("SOURCE_DATE_EPOCH", raising=False)
    guid = re.compile(r"\$(?:FINGERPRINT|VERSION)GUID\r?\n\s*2\r?\n([^\r\n]+)")
    first, second = dxf_text(drawing()), dxf_text(drawing())
    assert guid.findall(first) == guid.findall(second) and len(set(guid.findall(first))) == 2
    monkeypatch.setenv("SOURCE_DATE_EPOCH", str(EPOCH))
    assert dxf_text(drawing()) == dxf_text(drawing())
    assert source_date() == dt.datetime.fromtimestamp(EPOCH, dt.timezone.utc)
    monkeypatch.setenv("SOURCE_DATE_EPOCH", "yesterday")                # not seconds: the clock
    assert abs(source_date() - dt.datetime.now(dt.timezone.utc)) < dt.timedelta(minutes=5)


def test_dxf_created_by_stamp_names_the_zone_of_its_day(monkeypatch):
    """The "created by ezdxf <version> @ <time>" stamp is the day of the run at midnight with that day's own
    UTC offset: +00:00 for SOURCE_DATE_EPOCH (UTC), the local offset for the clock."""
    import time

    import ezdxf

    def stamp():
        doc = ezdxf.new("R2010")
        doc.modelspace().add_line((0, 0), (1, 2))
        return re.search(rf"\n{re.escape(ezdxf.__version__)} @ (\S+)", dxf_text(doc)).group(1)

    monkeypatch.setenv("SOURCE_DATE_EPOCH", str(EPOCH))
    assert stamp() == dt.datetime.fromtimestamp(EPOCH, dt.timezone.utc).date().isoformat() + "T00:00:00+00:00"
    monkeypatch.delenv("SOURCE_DATE_EPOCH")
    monkeypatch.setenv("TZ", "Asia/Kolkata")                           # +05:30 all year
    time.tzset()
    try:
        today = dt.datetime.now().date().isoformat()
        assert stamp() in (today + "T00:00:00+05:30", dt.date.today().isoformat() + "T00:00:00+05:30")
    finally:
        monkeypatch.undo()
        time.tzset()
