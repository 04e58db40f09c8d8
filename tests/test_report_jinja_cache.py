"""The report's compiled templates are kept between runs next to the bytecode (Jinja's
bytecode cache): the same output from a cached template, nothing kept where bytecode is
not written, and a folder that cannot be written is no cache (no failure)."""
from __future__ import annotations

import sys

from tmm_cli import report


def _table(env) -> str:
    return str(env.get_template("macros.html.j2").module.table(["a", "b"], [[1, "x<y"]], caption="c"))


def test_templates_cached_and_read_back(tmp_path, monkeypatch):
    monkeypatch.setattr(sys, "dont_write_bytecode", False)
    monkeypatch.setattr(sys, "pycache_prefix", str(tmp_path / "prefix"))
    first = report.make_env()
    out = _table(first)
    files = list((tmp_path / "prefix").rglob("jinja-*.cache"))
    assert files, "no compiled template written"
    second = report.make_env()
    cache = second.bytecode_cache
    loaded = []
    orig = cache.load_bytecode

    def load(bucket):
        orig(bucket)
        loaded.append(bucket.code is not None)
    monkeypatch.setattr(cache, "load_bytecode", load)
    monkeypatch.setattr(second, "_compile", lambda *a: (_ for _ in ()).throw(AssertionError("compiled again")))
    assert _table(second) == out
    assert loaded == [True]
    # a damaged entry is compiled afresh
    for f in files:
        f.write_bytes(b"garbage")
    assert _table(report.make_env()) == out


def test_no_cache_without_bytecode_or_writable_folder(tmp_path, monkeypatch):
    monkeypatch.setattr(sys, "dont_write_bytecode", True)
    assert report.make_env().bytecode_cache is None
    monkeypatch.setattr(sys, "dont_write_bytecode", False)
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    monkeypatch.setattr(sys, "pycache_prefix", str(blocker))
    env = report.make_env()
    assert env.bytecode_cache is not None
    assert "x&lt;y" in _table(env)
