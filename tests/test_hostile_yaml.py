"""Hostile task files (issue 10, items 1, 6 and 14): each is refused as an invalid task,
exit 2, with the file, the line and (where there is one) the field - never an
"internal error", a hang or gigabytes of memory. Large files are generated here."""
from __future__ import annotations

import codecs
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from tmm_cli.cli import app
from tmm_cli.yamlload import MAX_BYTES, MAX_DEPTH, MAX_NODES

runner = CliRunner()

GEARS = "schema: tmm/1\ntitle: pair\ngears:\n  m: 9 mm\n  z: [20, 15]\n  x: [0, 0]\n"


def _validate(path: Path):
    res = runner.invoke(app, ["validate", str(path)])
    return res.exit_code, res.output


def _write(tmp_path: Path, text: str, name: str = "task.yaml") -> Path:
    f = tmp_path / name
    f.write_text(text, encoding="utf-8")
    return f


def _billion_laughs(levels: int = 9, width: int = 10) -> str:
    lines = ["schema: tmm/1", "lol0: &a0 [" + ", ".join(["lol"] * width) + "]"]
    for i in range(1, levels + 1):
        lines.append(f"lol{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * width) + "]")
    return "\n".join(lines) + "\n"


def test_alias_bomb_refused_fast_with_the_alias_line(tmp_path):
    # 10 ** 10 strings once expanded; under 1 KB on disk. Nodes as the reader counts them
    # (each alias with the nodes it stands for): root 1, `schema: tmm/1` 2, lol0 1 + 11,
    # lol1 2 + 10 * 11, lol2 2 + 10 * 111, lol3 2 + 10 * 1111 -> 12351 after line 5; on
    # line 6 the first alias *a3 brings 11111 more: 23464 > 20000, refused there.
    text = _billion_laughs()
    assert len(text) < 1024
    f = _write(tmp_path, text)
    proc = subprocess.run([sys.executable, "-m", "tmm_cli", "validate", str(f)], capture_output=True,
                          text=True, timeout=60)
    assert proc.returncode == 2, proc.stderr
    assert f"{f}:6:" in proc.stderr and "field 'lol4[0]'" in proc.stderr
    assert f"more than {MAX_NODES} values" in proc.stderr and "'*a3' alone stands for 11111" in proc.stderr
    assert "internal error" not in proc.stderr and "Traceback" not in proc.stderr
    # refused fast: bounded work, not a wall time (a busy machine's). The refusal reads
    # no more than the bound's worth of nodes: its memory is a small task's, nothing of
    # the 10 ** 10 strings; its CPU time a few readings of an example task (not a clock).
    import tracemalloc

    from tmm_cli.errors import TaskError
    from tmm_cli.yamlload import load_yaml
    example = (Path(__file__).resolve().parents[1] / "tasks" / "forging_sixbar.yaml").read_text(encoding="utf-8")
    load_yaml("warm.yaml", text=example)
    tracemalloc.start()
    try:
        c0 = time.process_time()
        with pytest.raises(TaskError):
            load_yaml("bomb.yaml", text=text)
        bomb_cpu = time.process_time() - c0
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 1 << 20                        # tens of kB: the aliases counted, never expanded
    c0 = time.process_time()
    for _ in range(5):
        load_yaml("t.yaml", text=example)
    example_cpu = (time.process_time() - c0) / 5
    assert bomb_cpu < 50 * example_cpu + 0.05, (bomb_cpu, example_cpu)


def _alias_text(n: int, k: int, pad: int) -> str:
    return ("base: &b [" + ", ".join(["1"] * n) + "]\n" + "pad: [" + ", ".join(["2"] * pad) + "]\n"
            + "use: [" + ", ".join(["*b"] * k) + "]\n")


def test_node_bound_counts_alias_contents():
    from tmm_cli.errors import TaskError
    from tmm_cli.yamlload import load_yaml
    # nodes: root 1; base key 1, list 1 + n; pad key 1, list 1 + pad; use key 1, list 1,
    # k aliases of n + 1 nodes each: 7 + n + pad + k (n + 1)
    n, k = 999, 18
    pad = MAX_NODES - 7 - n - k * (n + 1)
    data, _ = load_yaml("t.yaml", text=_alias_text(n, k, pad))      # exactly at the bound
    assert len(data["use"]) == k and len(data["use"][0]) == n and len(data["pad"]) == pad
    with pytest.raises(TaskError) as ei:
        load_yaml("t.yaml", text=_alias_text(n, k, pad + 1))
    field, line, _, msg = ei.value.issues[0]
    assert (field, line) == (f"use[{k - 1}]", 3) and "alias '*b'" in msg


def test_many_plain_values_refused_quickly(tmp_path):
    f = _write(tmp_path, "schema: tmm/1\ntitle: [" + ", ".join(["1"] * 60000) + "]\n")
    t0 = time.process_time()      # CPU time of this process: the work done, not the machine's load
    code, out = _validate(f)
    assert code == 2 and f"more than {MAX_NODES} values" in out and "field 'title[" in out
    assert time.process_time() - t0 < 10


@pytest.mark.parametrize("text, line, field", [
    ("schema: tmm/1\ntitle: &a [*a]\n", 2, "title[0]"),
    ("schema: tmm/1\nmechanism:\n  links: &l {a: {extra: *l}}\n", 3, "mechanism.links.a.extra"),
])
def test_recursive_alias(tmp_path, text, line, field):
    code, out = _validate(_write(tmp_path, text))
    assert code == 2, out
    assert f"task.yaml:{line}:" in out and f"field '{field}'" in out and "recursive alias" in out


def test_deep_nesting(tmp_path):
    depth = 5000
    code, out = _validate(_write(tmp_path, "schema: tmm/1\ntitle: " + "[" * depth + "]" * depth + "\n"))
    assert code == 2, out
    # the root mapping is level 1, `title`'s list level 2: the refused node opens at
    # column 8 + (MAX_DEPTH - 1) of line 2
    assert f"task.yaml:2:{8 + MAX_DEPTH - 1}:" in out and f"more than {MAX_DEPTH} deep" in out
    assert "internal error" not in out


def test_nesting_at_the_limit_is_read():
    from tmm_cli.yamlload import load_yaml
    d = MAX_DEPTH - 1  # the root mapping is one level
    data, _ = load_yaml("t.yaml", text="a: " + "[" * (d - 1) + "]" * (d - 1) + "\n")
    x, levels = data["a"], 1
    while x:
        x, levels = x[0], levels + 1
    assert levels == d - 1


@pytest.mark.parametrize("number, digits", [(str(10 ** 309), 310), ("7" * 5000, 5000), ("-" + "9" * 4400, 4400)])
def test_integer_out_of_float_range(tmp_path, number, digits):
    code, out = _validate(_write(tmp_path, GEARS.replace("x: [0, 0]", f"x: [{number}, 0]")))
    assert code == 2, out
    assert "task.yaml:6:7: field 'gears.x[0]'" in out and f"integer of {digits} digits" in out
    assert len(out) < 1000  # the number is not echoed


def test_integer_just_inside_float_range_reaches_the_field_check(tmp_path):
    # 10**308 fits a float: the YAML reader passes it, the 1e12 limit of the field refuses it
    code, out = _validate(_write(tmp_path, GEARS.replace("x: [0, 0]", f"x: [{10 ** 308}, 0]")))
    assert code == 2 and "gears.x[0]" in out and "internal error" not in out


def test_integer_above_1e308_in_a_quantity_field(tmp_path):
    root = Path(__file__).resolve().parents[1]
    text = (root / "tasks" / "crank_rocker_fourbar.yaml").read_text()
    f = _write(tmp_path, text.replace("mass: 1.0,", f"mass: {10 ** 320},"))
    code, out = _validate(f)
    assert code == 2 and "field 'mechanism.links.crank.mass'" in out, out


def test_gear_teeth_above_the_value_limit(tmp_path):
    code, out = _validate(_write(tmp_path, GEARS.replace("z: [20, 15]", f"z: [{10 ** 30}, 15]")))
    assert code == 2, out
    assert "task.yaml:5:7: field 'gears.z[0]'" in out and "1000000000000" in out


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="needs /dev/zero")
def test_device_is_refused_before_reading():
    code, out = _validate(Path("/dev/zero"))
    assert code == 2 and "/dev/zero: not a regular file (a device)" in out


def test_fifo_is_refused_without_hanging(tmp_path):
    fifo = tmp_path / "pipe.yaml"
    os.mkfifo(fifo)
    proc = subprocess.run([sys.executable, "-m", "tmm_cli", "validate", str(fifo)], capture_output=True,
                          text=True, timeout=30)
    assert proc.returncode == 2 and "not a regular file (a FIFO" in proc.stderr


def test_folder_is_refused(tmp_path):
    """A folder is no task file for `tmm run`; `tmm validate` takes a folder for its task
    files (as `tmm batch` does), and one with none is exit 2 saying so."""
    d = tmp_path / "dir.yaml"
    d.mkdir()
    res = runner.invoke(app, ["run", str(d), "--format", "json", "-o", str(tmp_path / "o")])
    assert res.exit_code == 2 and "not a regular file (a folder)" in res.output, res.output
    code, out = _validate(d)
    assert code == 2 and "no task files (*.yaml, *.yml) in this folder" in out


def test_oversized_file_is_refused(tmp_path):
    f = _write(tmp_path, GEARS + "# " + "x" * MAX_BYTES + "\n")
    code, out = _validate(f)
    assert code == 2 and f"larger than {MAX_BYTES // 1024} KiB" in out
    _write(tmp_path, GEARS + "# " + "x" * (MAX_BYTES - len(GEARS) - 3) + "\n")  # exactly MAX_BYTES: read
    assert (tmp_path / "task.yaml").stat().st_size == MAX_BYTES
    code, out = _validate(tmp_path / "task.yaml")
    assert code == 0, out


@pytest.mark.parametrize("encoding, bom", [("utf-8", codecs.BOM_UTF8), ("utf-16-le", codecs.BOM_UTF16_LE),
                                           ("utf-16-be", codecs.BOM_UTF16_BE), ("utf-32-le", codecs.BOM_UTF32_LE),
                                           ("utf-32-be", codecs.BOM_UTF32_BE)])
def test_unicode_with_bom_is_read(tmp_path, encoding, bom):
    from tmm_cli.task import load_task
    f = tmp_path / "task.yaml"
    f.write_bytes(bom + GEARS.replace("title: pair", "title: пара колёс").encode(encoding))
    task = load_task(f)
    assert task.title == "пара колёс" and tuple(task.gears.z) == (20, 15)


def test_latin1_file_names_the_line_and_the_encoding(tmp_path):
    f = tmp_path / "task.yaml"
    f.write_bytes(GEARS.replace("title: pair", "title: café").encode("latin-1"))
    code, out = _validate(f)
    assert code == 2 and "task.yaml:2: not a UTF-8 text file" in out and "save it as UTF-8" in out


@pytest.mark.parametrize("key", ["~", "null", "true", "3"])
def test_non_string_key_reported_at_its_line(tmp_path, key):
    code, out = _validate(_write(tmp_path, GEARS + f"{key}: 1\n"))
    assert code == 2, out
    assert "task.yaml:7:1:" in out and "unknown key" in out


# ------------------------------------------------------------ libyaml's fast reading
def _python_reading(text: str):
    """(data, marks) as PyYAML's Python reader (_Loader12) gives them, or the error's type."""
    from tmm_cli import yamlload
    try:
        loader = yamlload._Loader12(text)
        try:
            node = loader.get_single_node()
            marks: dict = {}
            if node is not None:
                yamlload._walk(node, (), marks, "f", loader)
            data = loader.construct_document(node) if node is not None else None
        finally:
            loader.dispose()
    except Exception as exc:  # noqa: BLE001 - any refusal is compared by its type
        return type(exc).__name__
    return data, marks


def _same(a, b) -> bool:
    import math
    if type(a) is not type(b):
        return False
    if isinstance(a, dict):
        return list(a) == list(b) and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, list):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, float) and math.isnan(a):
        return math.isnan(b)
    return a == b


def _random_edits() -> list[str]:
    """The 3,000 random edits of the example tasks (characters of YAML's syntax inserted,
    deleted, replaced), the same every time (one seeded generator, in order)."""
    import random
    root = Path(__file__).resolve().parents[1]
    texts = [p.read_text(encoding="utf-8") for p in sorted((root / "tasks").glob("*.yaml"))]
    rng = random.Random(12)
    alphabet = list(":-[]{},#&*!|>'\"?%@` \n\t.0123456789aeé\\\r~\ufeff")
    out = []
    for i in range(3000):
        t = texts[i % len(texts)]
        for _ in range(rng.randint(1, 4)):
            pos, op = rng.randrange(len(t)), rng.random()
            t = (t[:pos] + rng.choice(alphabet) + t[pos:] if op < 0.4 else t[:pos] + t[pos + 1:] if op < 0.7
                 else t[:pos] + rng.choice(alphabet) + t[pos + 1:])
        out.append(t)
    return out


_SHARDS = 6


@pytest.mark.parametrize("shard", range(_SHARDS))
def test_fast_reading_is_the_python_readers(shard):
    """What libyaml reads (tmm_cli.yamlload._load_fast) is, value for value and mark for
    mark, what PyYAML's Python reader reads: on every example task and on 3,000 random
    edits of them (characters of YAML's syntax inserted, deleted, replaced); whatever the
    Python reader refuses, the fast reading leaves to it (returns None). Six tests, each
    reading every sixth edit (the suite's workers share them out)."""
    from tmm_cli import yamlload
    root = Path(__file__).resolve().parents[1]
    texts = [p.read_text(encoding="utf-8") for p in sorted((root / "tasks").glob("*.yaml"))]
    assert sum(yamlload._load_fast(t, "f") is not None for t in texts) >= len(texts) - 4
    fast = 0
    for t in _random_edits()[shard::_SHARDS]:
        got = yamlload._load_fast(t, "f")
        if got is None:
            continue
        fast += 1
        want = _python_reading(t)
        assert not isinstance(want, str), (want, t)
        assert _same(got[0], want[0]) and got[1] == want[1], t
    assert fast > 600 / _SHARDS          # each share's; together more than 600 of the 3,000


@pytest.mark.parametrize("text", [
    "a: &x [1, 2]\nb: *x\n",                       # an alias: the Python reader counts it
    "a:\t1\n",                                      # a tab
    "a: {b: c?d}\n",                                # '?' in a flow plain scalar
    "a: !\n",                                       # a bare tag
    "a: >#x\n",                                     # a block scalar's header
    "a: 1\n\ufeffb: 2\n",                           # a byte-order mark inside
    "a: " + "[" * (MAX_DEPTH + 1) + "]" * (MAX_DEPTH + 1) + "\n",   # too deep
    "a: [" + ", ".join(["1"] * 9000) + "]\n",       # too long for libyaml's recursion bound
    "a: 1\na: 2\n",                                 # a duplicate key
    "a: 1\n---\nb: 2\n",                            # two documents
])
def test_fast_reading_leaves_the_rest_to_the_python_reader(text):
    from tmm_cli import yamlload
    assert yamlload._load_fast(text, "f") is None
