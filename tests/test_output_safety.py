"""Issue 10, items 13 and 14: tmm never writes through a symbolic link to a folder inside
its output folder, and a write error names the file asked for (not a temporary file,
not nothing)."""
from __future__ import annotations

import errno
import os
from pathlib import Path

import pytest
from typer.testing import CliRunner

from tmm_cli.cli import app

ROOT = Path(__file__).resolve().parents[1]
GEARS = str(ROOT / "tasks" / "gears_zero.yaml")
runner = CliRunner()


def _run(out: Path, fmt: str = "json,html"):
    return runner.invoke(app, ["run", GEARS, "--out", str(out), "--format", fmt, "--quiet"])


def test_symlinked_subfolder_is_refused(tmp_path):
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    precious = elsewhere / "fig-01.svg"
    precious.write_text("the user's own drawing")
    out = tmp_path / "out"
    out.mkdir()
    (out / "figures").symlink_to(elsewhere, target_is_directory=True)
    res = _run(out)
    assert res.exit_code == 3, res.output
    assert "stage 'output' failed" in res.output and "is a symbolic link" in res.output
    assert str(out / "figures") in res.output
    assert precious.read_text() == "the user's own drawing"
    assert sorted(p.name for p in elsewhere.iterdir()) == ["fig-01.svg"]


def test_output_folder_itself_may_be_a_link(tmp_path):
    real = tmp_path / "real"
    real.mkdir()
    link = tmp_path / "link"
    link.symlink_to(real, target_is_directory=True)
    res = _run(link)
    assert res.exit_code == 0, res.output
    assert (real / "report.html").is_file() and (real / "figures" / "gear-mesh.svg").is_file()


def test_inside_refuses_leaving_the_folder(tmp_path):
    from tmm_cli.safepath import SymlinkedFolder, inside
    with pytest.raises(SymlinkedFolder):
        inside(tmp_path, "../x.csv")
    assert inside(tmp_path, "a/b/c.csv") == tmp_path / "a" / "b" / "c.csv"
    assert (tmp_path / "a" / "b").is_dir()


def test_disk_full_names_the_file(tmp_path, monkeypatch):
    import tmm_cli.io as tio

    def full(fd):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))  # as write/fsync raise it: no file name
    monkeypatch.setattr(tio.os, "fsync", full)
    out = tmp_path / "out"
    res = _run(out, "json")
    assert res.exit_code == 3, res.output
    assert f"cannot write {out / 'results.json'}: No space left on device" in res.output
    assert not [p for p in out.iterdir() if p.name.endswith(".tmp")]  # the temporary file is removed


def test_write_error_names_the_target_not_the_temporary_file(tmp_path, monkeypatch):
    import tmm_cli.io as tio

    def denied(path):
        raise PermissionError(errno.EACCES, os.strerror(errno.EACCES),
                              os.path.join(path.parent, f".{path.name}.k3j9x0qz.tmp"))
    monkeypatch.setattr(tio, "_mkstemp", denied)
    out = tmp_path / "out"
    res = _run(out, "json")
    assert res.exit_code == 3, res.output
    assert f"cannot write {out / 'results.json'}: Permission denied" in res.output
    assert ".tmp" not in res.output


def test_temporary_file_as_mkstemp_makes_it(tmp_path):
    """atomic_write's temporary file: mkstemp's name pattern (which the manifest's clean-up
    of a killed run's leftovers matches), mode 0600 until written, never an existing file."""
    import stat

    import tmm_cli.io as tio

    target = tmp_path / "results.json"
    names = set()
    for _ in range(50):
        fd, name = tio._mkstemp(target)
        os.close(fd)
        assert os.path.isabs(name) and os.path.dirname(name) == str(tmp_path)
        assert tio._TMP.match(os.path.basename(name)).group("name") == "results.json"
        assert stat.S_IMODE(os.stat(name).st_mode) == 0o600
        names.add(name)
    assert len(names) == 50
    tio.atomic_write(target, "x")
    assert target.read_text() == "x" and stat.S_IMODE(target.stat().st_mode) == tio.file_mode()
