"""The documentation site builds offline with `mkdocs build --strict` (every page, link and
picture found; the reference pages generated from the task model, the commands and the
catalogue), and its generated reference names every task-file field and message code."""
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
mkdocs = pytest.importorskip("mkdocs", reason="the docs extra (mkdocs, mkdocs-material) is not installed")


def test_site_builds_strict(tmp_path):
    site = tmp_path / "site"
    p = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir", str(site)],
                       cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-3000:]
    fields = (site / "reference" / "task-file" / "index.html").read_text(encoding="utf-8")
    from tmm_cli.task import field_docs
    from html import escape
    for path, _, _ in field_docs():
        assert f"<code>{escape(path, quote=False)}</code>" in fields, path
    msgs = (site / "reference" / "messages" / "index.html").read_text(encoding="utf-8")
    from tmm_cli.messages import catalogue
    for code in catalogue("en")["messages"]:
        if code != "text":
            assert f"<code>{code}</code>" in msgs, code
    cmds = (site / "reference" / "commands" / "index.html").read_text(encoding="utf-8")
    for name in ("run", "validate", "check", "batch", "variants", "paths", "form", "study", "sheets", "new"):
        assert f"tmm {name}" in cmds, name
    assert (site / "gallery" / "engine-1.png").is_file()


def test_every_gallery_picture_the_pages_use_is_made_by_the_script():
    """The pictures are the gallery script's (tools/gallery.py), not pasted ones: every picture a
    page shows is one the script makes, and the script makes no picture no page shows."""
    import re
    sys.path.insert(0, str(ROOT / "tools"))
    try:
        import gallery
    finally:
        sys.path.pop(0)
    made = {f"{name}-{k}.png" for _, _, _, pages, name in gallery.PICTURES for k in range(1, len(pages) + 1)}
    used = set()
    for md in (ROOT / "docs").rglob("*.md"):
        used |= set(re.findall(r"gallery/([\w-]+\.png)", md.read_text(encoding="utf-8")))
    assert used == made
