"""Run tmm twice on the same inputs and list every output file that differs.

    python tools/repro_diff.py [TASK.yaml ...] [--batch] [--keep DIR]

Default: every tasks/*.yaml with ``--format json,html,pdf,sheets`` and one ``tmm batch`` over a few
variants (json,html,pdf), each into two folders (a/ and b/), then a byte comparison of the two trees
(all files but tmm's bookkeeping .tmm-manifest.json, which records modification times).
SOURCE_DATE_EPOCH is set (as a reproducible build would); pass --no-epoch to see what changes without it.
Exit code 1 when some file differs or exists in one tree only.
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
MANIFEST = ".tmm-manifest.json"
BATCH_TASKS = ["cam_knife.yaml", "gears_auto.yaml", "engine_slider_crank.yaml"]


def _run(args: list[str], env: dict[str, str]) -> None:
    subprocess.run([sys.executable, "-m", "tmm_cli", *args], cwd=ROOT, env=env, check=False,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def produce(dest: Path, tasks: list[Path], batch: bool, env: dict[str, str]) -> None:
    for t in tasks:
        _run(["run", str(t), "--out", str(dest / t.stem), "--format", "json,html,pdf,sheets", "-q"], env)
    if batch:
        src = dest.parent / "batch_in"
        src.mkdir(exist_ok=True)
        for name in BATCH_TASKS:
            (src / name).write_bytes((ROOT / "tasks" / name).read_bytes())
        _run(["batch", str(src), "--out", str(dest / "_batch"), "--format", "json,html,pdf"], env)


def _files(root: Path) -> set[Path]:
    # .tmm-manifest.json is tmm's bookkeeping: the size and modification time of each file it
    # wrote (a file edited since is never removed), so it differs by design
    return {p.relative_to(root) for p in root.rglob("*") if p.is_file() and p.name != MANIFEST}


def differing(a: Path, b: Path) -> list[str]:
    fa, fb = _files(a), _files(b)
    out = [f"only in one run: {p}" for p in sorted(fa ^ fb)]
    out += [f"differs: {p}" for p in sorted(fa & fb) if (a / p).read_bytes() != (b / p).read_bytes()]
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("tasks", nargs="*", type=Path)
    ap.add_argument("--no-batch", action="store_true")
    ap.add_argument("--no-epoch", action="store_true", help="leave SOURCE_DATE_EPOCH unset")
    ap.add_argument("--keep", type=Path, help="write the two trees here (else a temporary folder)")
    ns = ap.parse_args()
    tasks = ns.tasks or sorted((ROOT / "tasks").glob("*.yaml"))
    env = dict(os.environ)
    env.pop("SOURCE_DATE_EPOCH", None)
    if not ns.no_epoch:
        env["SOURCE_DATE_EPOCH"] = "1700000000"
    with tempfile.TemporaryDirectory(prefix="tmm-repro-") as tmp:
        base = ns.keep or Path(tmp)
        for side in ("a", "b"):
            produce(base / side, [t.resolve() for t in tasks], not ns.no_batch, env)
        diffs = differing(base / "a", base / "b")
    print("\n".join(diffs) if diffs else "all outputs identical")
    return 1 if diffs else 0


if __name__ == "__main__":
    sys.exit(main())
