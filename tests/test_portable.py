"""Windows and macOS: what differs from Linux (docs/platforms.md), tested on Linux by
taking Linux's extras away."""
from __future__ import annotations


def test_spawn_forced_means_no_fork_anywhere(monkeypatch):
    """TMM_START_METHOD=spawn: the batch spawns its workers, and neither the report's
    helper nor a results file written aside forks (as where fork does not exist)."""
    from tmm_cli import io, portable
    monkeypatch.setenv("TMM_START_METHOD", "spawn")
    monkeypatch.delenv("TMM_REPORT_JOBS", raising=False)
    assert portable.start_method() == "spawn" and not portable.can_fork()
    assert not io.workers_wanted()
    assert io.Aside.start("/nonexistent-dir/x.json", lambda w: w(b"x")) is None
    monkeypatch.setenv("TMM_START_METHOD", "fork")
    assert portable.start_method() == "fork" and portable.can_fork()


def test_fork_unavailable_falls_back_to_spawn(monkeypatch):
    import multiprocessing

    from tmm_cli import portable
    monkeypatch.delenv("TMM_START_METHOD", raising=False)
    monkeypatch.setattr(multiprocessing, "get_all_start_methods", lambda: ["spawn"])
    assert portable.start_method() == "spawn"
    monkeypatch.setenv("TMM_START_METHOD", "fork")                 # asked for, but not there
    assert portable.start_method() == "spawn"


def _held(monkeypatch, times: int):
    """os.replace fails with PermissionError ``times`` times (Windows: the file is open in
    a viewer), then works; the waits between tries skipped. Returns the calls made."""
    import os

    from tmm_cli import io
    real, calls = os.replace, []

    def replace(src, dst):
        calls.append(dst)
        if len(calls) <= times:
            raise PermissionError(13, "Access is denied", str(dst))
        return real(src, dst)
    monkeypatch.setattr(os, "replace", replace)
    monkeypatch.setattr(io.time, "sleep", lambda s: None)
    return calls


def test_replace_over_a_held_file_is_tried_again(tmp_path, monkeypatch):
    from tmm_cli.io import REPLACE_TRIES, atomic_write
    (tmp_path / "report.pdf").write_bytes(b"old")
    calls = _held(monkeypatch, REPLACE_TRIES - 1)
    atomic_write(tmp_path / "report.pdf", b"new")
    assert (tmp_path / "report.pdf").read_bytes() == b"new" and len(calls) == REPLACE_TRIES
    assert [p.name for p in tmp_path.iterdir()] == ["report.pdf"]


def test_a_kept_search_answer_is_written_once_or_not_at_all(tmp_path, monkeypatch):
    """The path synthesis's kept answer (a cache): a file another program holds is tried once
    (atomic_write's tries=1), not waited for, and the run goes on; no temporary file is left."""
    import numpy as np

    from tmm_cli.linkage import synthesis_path as S
    calls = _held(monkeypatch, 10 ** 6)
    found = (np.arange(10.0), np.arange(5.0), 0.5)
    S._keep(tmp_path / "a.npz", found)
    assert len(calls) == 1 and list(tmp_path.iterdir()) == []
    monkeypatch.undo()
    S._keep(tmp_path / "a.npz", found)
    got = S._kept(tmp_path / "a.npz", 5)
    assert got[0].tobytes() == found[0].tobytes() and got[1].tobytes() == found[1].tobytes() and got[2] == 0.5


def test_a_file_held_for_good_is_named_no_traceback_no_temporary_left(tmp_path, monkeypatch):
    """`tmm run` whose results.json stays held: exit 3, the file named and why, the old
    file as it was, no temporary file left in the folder."""
    from typer.testing import CliRunner

    from tmm_cli.cli import app
    from tmm_cli.io import REPLACE_TRIES
    out = tmp_path / "out"
    out.mkdir()
    (out / "results.json").write_text("old")
    calls = _held(monkeypatch, 10 ** 6)
    task = __import__("pathlib").Path(__file__).resolve().parent.parent / "tasks" / "gears_zero.yaml"
    res = CliRunner().invoke(app, ["run", str(task), "--out", str(out), "--format", "json"])
    assert res.exit_code == 3, res.output
    assert f"cannot write {out / 'results.json'}: the file is open in another program" in res.output
    assert "Traceback" not in res.output and len(calls) == REPLACE_TRIES
    assert sorted(p.name for p in out.iterdir()) == ["results.json"]
    assert (out / "results.json").read_text() == "old"


# ------------------------------------------------------------------ file names
GEARS = """schema: tmm/1
title: gears
variant: {v}
gears: {{m: 4 mm, z: [14, 30], x: [0.3, 0.1]}}
"""


def test_safe_name_windows_and_macos_take():
    from tmm_cli.safepath import UniqueNames, safe_name
    assert [safe_name(n) for n in ("CON", "nul", "Aux.txt", "com1", "LPT9.form", "COM10", "console")] == \
        ["_CON", "_nul", "_Aux.txt", "_com1", "_LPT9.form", "COM10", "console"]
    assert [safe_name(n) for n in ("v1.", "v1. ", " v2 ", "a:b*c?", "..hidden", "...", "")] == \
        ["v1", "v1", "v2", "a_b_c_", "hidden", "file", "file"]
    names = UniqueNames(["Summary"])
    assert [names.take(n) for n in ("v1", "V1", "v1", "summary", "e\u0301", "\u00e9")] == \
        ["v1", "V1-2", "v1-3", "summary-2", "e\u0301", "\u00e9-2"]      # case and Unicode forms folded


def test_batch_folders_are_names_windows_takes(tmp_path):
    """Task files named as Windows devices, with a trailing dot, or differing only in case
    get folders Windows and macOS can make, one each."""
    from typer.testing import CliRunner

    from tmm_cli.batch import folder_names
    from tmm_cli.cli import app
    files = [tmp_path / n for n in ("CON.yaml", "prn.yml", "v1..yaml", "v1.yaml", "V1.yaml", "com3.yaml")]
    assert folder_names(files) == ["_CON", "_prn", "v1", "v1-2", "V1-3", "_com3"]
    src = tmp_path / "src"
    src.mkdir()
    for n in ("CON.yaml", "v1.yaml", "V1.yaml"):
        (src / n).write_text(GEARS.format(v=1), encoding="utf-8")
    res = CliRunner().invoke(app, ["batch", str(src), "--out", str(tmp_path / "o"), "--format", "json"])
    assert res.exit_code == 0, res.output
    assert sorted(p.name for p in (tmp_path / "o").iterdir() if p.is_dir()) == ["V1", "_CON", "v1-2"]
    assert "results in _CON/" in (tmp_path / "o" / "summary.csv").read_text(encoding="utf-8")


def test_variants_files_are_names_windows_takes(tmp_path):
    from typer.testing import CliRunner

    from tmm_cli.cli import app
    (tmp_path / "tpl.yaml").write_text(GEARS.format(v='"{variant}"'), encoding="utf-8")
    (tmp_path / "tab.csv").write_text("variant\nCON\na\nA\n7.\n", encoding="utf-8")
    res = CliRunner().invoke(app, ["variants", str(tmp_path / "tpl.yaml"), str(tmp_path / "tab.csv"),
                                   "--out", str(tmp_path / "o")])
    assert res.exit_code == 0, res.output
    assert sorted(p.name for p in (tmp_path / "o").glob("*.yaml")) == ["7.yaml", "A_.yaml", "_CON.yaml", "a.yaml"]


def test_form_files_one_per_task_where_case_is_folded(tmp_path):
    from typer.testing import CliRunner

    from tmm_cli.cli import app
    src = tmp_path / "src"
    src.mkdir()
    (src / "V1.yaml").write_text(GEARS.format(v=1), encoding="utf-8")
    (src / "v1.yaml").write_text(GEARS.format(v=2), encoding="utf-8")
    res = CliRunner().invoke(app, ["form", str(src), "--quantities", "gears.aw", "--out", str(tmp_path / "f")])
    assert res.exit_code == 0, res.output
    assert sorted(p.name for p in (tmp_path / "f").glob("*.yaml")) == \
        ["V1.form.yaml", "V1.key.yaml", "v1-2.form.yaml", "v1-2.key.yaml"]
    assert f"{src / 'v1.yaml'}: its form and key are v1-2.form.yaml and v1-2.key.yaml" in res.output
    assert "variant: 2" in (tmp_path / "f" / "v1-2.form.yaml").read_text(encoding="utf-8")


def test_feedback_page_names():
    from tmm_cli.feedback import feedback_name
    assert feedback_name({"student": "CON", "index": 0}) == "feedback-CON-1"
    assert feedback_name({"student": "  ...  ", "index": -1}) == "feedback-answers-0"
    assert feedback_name({"student": "Petrenko O. ", "index": 2}) == "feedback-Petrenko_O-3"


# ------------------------------------------------------------------ the console
CYR_TITLE = "\u041a\u0440\u0438\u0432\u043e\u0448\u0438\u043f"       # a Russian word, as a title


def _tmm(*args, env=None, cwd=None):
    import os
    import subprocess
    import sys
    e = {k: v for k, v in os.environ.items() if k not in ("FORCE_COLOR", "TTY_COMPATIBLE", "PYTHONIOENCODING")}
    e.update(env or {})
    return subprocess.run([sys.executable, "-m", "tmm_cli", *args], capture_output=True, env=e, cwd=cwd,
                          timeout=300)


def test_cyrillic_on_a_console_in_a_legacy_code_page(tmp_path):
    """stdout and stderr in cp1252 (a Windows console or a redirected stream in a Western
    code page): the Cyrillic title, table and error lines are written in UTF-8, never an
    internal error (UnicodeEncodeError)."""
    task = tmp_path / "t.yaml"
    task.write_text(GEARS.format(v=1).replace("title: gears", f"title: {CYR_TITLE}"), encoding="utf-8")
    r = _tmm("run", str(task), "--out", str(tmp_path / "o"), "--format", "json", "--lang", "ru",
             env={"PYTHONIOENCODING": "cp1252"})
    assert r.returncode == 0, r.stderr.decode("utf-8", "replace")
    assert CYR_TITLE in r.stdout.decode("utf-8")
    bad = tmp_path / f"{CYR_TITLE}.yaml"                          # the error names the file
    bad.write_text(f"schema: tmm/1\ntitle: {CYR_TITLE}\ngears: {{m: 4 mm, z: [14, {CYR_TITLE}]}}\n",
                   encoding="utf-8")
    r = _tmm("run", str(bad), "--out", str(tmp_path / "o2"), "--lang", "ru", env={"PYTHONIOENCODING": "cp1252"})
    err = r.stderr.decode("utf-8")
    assert r.returncode == 2 and "internal error" not in err and f"{CYR_TITLE}.yaml:3" in err


def test_no_escape_codes_when_piped(tmp_path):
    """Output to a pipe or a file (not a terminal): tables and progress without ANSI codes."""
    src = tmp_path / "src"
    src.mkdir()
    (src / "v1.yaml").write_text(GEARS.format(v=1), encoding="utf-8")
    for args in (["run", str(src / "v1.yaml"), "--out", str(tmp_path / "o"), "--format", "json"],
                 ["batch", str(src), "--out", str(tmp_path / "b"), "--format", "json"]):
        r = _tmm(*args)
        assert r.returncode == 0, r.stderr
        assert r.stdout.strip() and b"\x1b[" not in r.stdout + r.stderr, args


# ------------------------------------------------------------------ without Linux's extras
# run first in every Python process (the spawned workers too, through PYTHONPATH): the
# modules Windows lacks made unimportable, os.fork and signal.SIGKILL taken away (psutil,
# whose Linux backend needs `resource`, loaded before: on Windows it has its own backend)
NO_UNIX = """import os, signal, sys
import psutil
for m in ("fcntl", "resource", "termios", "pwd", "grp"):
    sys.modules[m] = None
for a in ("fork", "forkpty"):
    if hasattr(os, a):
        delattr(os, a)
del signal.SIGKILL
"""
IMPORT_ALL = """import importlib, pkgutil, tmm_cli
bad = []
for m in pkgutil.walk_packages(tmm_cli.__path__, "tmm_cli."):
    if not m.name.endswith("__main__"):
        try:
            importlib.import_module(m.name)
        except BaseException as exc:
            bad.append(f"{m.name}: {type(exc).__name__}: {exc}")
print("\\n".join(bad) or "all imported")
"""


def _no_unix(tmp_path):
    import os
    site = tmp_path / "no_unix"
    site.mkdir()
    (site / "sitecustomize.py").write_text(NO_UNIX, encoding="utf-8")
    return {"PYTHONPATH": os.pathsep.join([str(site)] + [p for p in [os.environ.get("PYTHONPATH")] if p])}


def test_every_module_imports_without_unix_only_modules(tmp_path):
    import subprocess
    import sys
    env = {**__import__("os").environ, **_no_unix(tmp_path)}
    check = subprocess.run([sys.executable, "-c", "import os, signal; print(hasattr(os, 'fork'), "
                            "hasattr(signal, 'SIGKILL'))"], capture_output=True, text=True, env=env)
    assert check.stdout.split() == ["False", "False"]                # the stand-in works
    r = subprocess.run([sys.executable, "-c", IMPORT_ALL], capture_output=True, text=True, env=env, timeout=300)
    assert r.stdout.strip() == "all imported", r.stdout + r.stderr


def test_batch_with_limits_and_run_without_unix_only_modules(tmp_path):
    """As on Windows: `tmm batch` with --timeout and --memory (spawned workers, memory read
    with psutil) and `tmm run` with the JSON and HTML outputs work, no internal error."""
    env = _no_unix(tmp_path)
    src = tmp_path / "src"
    src.mkdir()
    for v in (1, 2):
        (src / f"v{v}.yaml").write_text(GEARS.format(v=v), encoding="utf-8")
    r = _tmm("batch", str(src), "--out", str(tmp_path / "b"), "--format", "json,html", "--jobs", "2",
             "--timeout", "60", "--memory", "1024", env=env)
    out = (r.stdout + r.stderr).decode("utf-8")
    assert r.returncode == 0 and "internal error" not in out and "not enforced" not in out, out
    assert (tmp_path / "b" / "summary.csv").read_text(encoding="utf-8").count(".yaml,ok,") == 2
    assert (tmp_path / "b" / "v2" / "report.html").exists() and (tmp_path / "b" / "v1" / "results.json").exists()
    r = _tmm("run", str(src / "v1.yaml"), "--out", str(tmp_path / "r"), "--format", "json,html", env=env)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "r" / "report.html").exists()


def test_batch_lists_its_files_with_slashes_on_windows_too():
    """The files a variant wrote, as the manifest lists them and summary.html links them:
    'v1/feedback-a-1.html', not Windows's 'v1\\feedback-a-1.html' (quoted into a link to
    nowhere, and never found among the written files: no feedback link at all)."""
    from pathlib import PurePosixPath, PureWindowsPath

    from tmm_cli.batch import _rel
    assert _rel(PureWindowsPath(r"C:\g\v1\feedback-a-1.html"), PureWindowsPath(r"C:\g")) == "v1/feedback-a-1.html"
    assert _rel("/g/v1/report.html", PurePosixPath("/g")) == "v1/report.html"
