"""The results file's writer: the per-position entries the stages build already clean
(tmm_cli.results.Entries, and LazyEntries made block by block when read) are written
without being cleaned again, so their builders must give exactly what clean() would:
checked here by writing the same results with every Entries and LazyEntries turned into
a plain list (cleaned value by value)."""
from __future__ import annotations

import json
import math
import struct
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import tmm_cli
from tmm_cli.pipeline import run       # the results as the command line writes them (lazy entries)
from tmm_cli.results import Entries, LazyEntries, one_line, clean, dumps

ROOT = Path(__file__).resolve().parents[1]


def _plain(obj):
    """The same results with every Entries and LazyEntries a plain list (deep copies)."""
    if isinstance(obj, dict):
        return {k: _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple, LazyEntries)):
        return [_plain(v) for v in obj]
    return obj


def _entries_clean(obj, path="") -> None:
    """Every value under an Entries is a plain clean JSON value."""
    if isinstance(obj, dict):
        for k, v in obj.items():
            assert type(k) is str, path
            _entries_clean(v, f"{path}.{k}")
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            _entries_clean(v, f"{path}[{i}]")
    elif type(obj) is float:
        assert math.isfinite(obj), path
        assert not (obj == 0.0 and math.copysign(1.0, obj) < 0), f"{path}: -0.0"
    else:
        assert obj is None or type(obj) in (int, bool, str), (path, type(obj))


def _check(results: dict) -> None:
    n = 0
    for key, sec in results.items():
        if type(sec) in (Entries, LazyEntries):
            n += 1
            _entries_clean(list(sec), key)
    assert dumps(results) == dumps(_plain(results))
    assert n, "no section built as Entries"


@pytest.mark.parametrize("name", ["forging_sixbar", "shaper_slotted_ram", "engine_slider_crank",
                                  "triad_class3", "static_gravity"])
def test_entries_written_as_cleaned(name):
    res = run(tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml"))
    _check(res)
    g = res.get("graphical_error")
    if g and "plans" in g:
        assert type(g["plans"]["positions"]) is Entries
        _entries_clean(g["plans"]["positions"])


def test_entries_with_nulls_near_a_change_point(tmp_path):
    """Values with no finite limit (None) and the near_singular flags."""
    from test_change_points import LIMIT
    f = tmp_path / "task.yaml"
    f.write_text(LIMIT, encoding="utf-8")
    try:
        res = run(tmm_cli.load_task(f))
    except tmm_cli.StageError as exc:            # pragma: no cover - partial results still written
        res = exc.partial
    assert any(e.get("near_singular") for e in res["kinematics"])
    assert any(e["points"]["B"]["a"] is None for e in res["kinematics"])
    _check(res)


def test_fine_grid_with_friction():
    """A fine grid (no per-position loads) with friction in the pairs."""
    text = (ROOT / "tasks" / "forging_sixbar.yaml").read_text(encoding="utf-8").replace("count: 12", "count: 500")
    task = tmm_cli.load_task(ROOT / "tasks" / "forging_sixbar.yaml", text=text)
    res = run(task)
    assert len(res["kinetostatics"]) >= 500
    _check(res)


def _same_in_any_blocks(entries: LazyEntries) -> None:
    """Entries made block by block (iteration), all in one block (a slice) and one at a
    time (indexing) are the same: no value depends on the other rows of its block."""
    assert type(entries) is LazyEntries and len(entries) > LazyEntries.BLOCK
    n = len(entries)
    whole = entries[0:n]
    assert type(whole) is Entries and len(whole) == n
    assert list(entries) == whole
    for i in (0, 1, LazyEntries.BLOCK - 1, LazyEntries.BLOCK, n - 1):
        assert entries[i] == whole[i] and entries[i - n] == whole[i]
    assert entries[7:n:97] == whole[7::97]


def _same_bits(a, b) -> bool:
    """Two JSON values equal with every float the same double (its sign included)."""
    if type(a) is float or type(b) is float:
        return type(a) is type(b) and struct.pack("<d", a) == struct.pack("<d", b)
    if type(a) is dict:
        return type(b) is dict and list(a) == list(b) and all(_same_bits(a[k], b[k]) for k in a)
    if type(a) is list:
        return type(b) is list and len(a) == len(b) and all(_same_bits(x, y) for x, y in zip(a, b))
    return type(a) is type(b) and a == b


_leaf = (st.floats(allow_nan=False, allow_infinity=False) | st.integers(-2**70, 2**70) | st.booleans()
         | st.none() | st.text())
_value = st.recursive(_leaf, lambda kids: st.lists(kids, max_size=4)
                      | st.dictionaries(st.text(max_size=5), kids, max_size=4), max_leaves=12)


@pytest.mark.parametrize("value", [0.0, 1.5, -2.25, 1e-05, 2.5e-07, 1e16, 1e22, 1.0000000000000002, 5e-324,
                                   1.7976931348623157e308, 123456789.123, 3, -7, 2**64, -2**63 - 1, True, False,
                                   None, "S2", "μ ü \"q\"\n\t\x00\u2028", [1.0, None], {"x": 1e-300, "y": [True]}])
def testone_line_reads_back_bit_for_bit(value):
    text = one_line(clean(value))
    assert "\n" not in text
    assert _same_bits(json.loads(text), clean(value))


@given(_value)
@settings(max_examples=300, deadline=None)
def testone_line_reads_back_bit_for_bit_any(value):
    v = clean(value)
    text = one_line(v)
    assert "\n" not in text
    assert _same_bits(json.loads(text), v)


def testone_line_floats_shortest():
    """Every float written in the fewest significant digits that read back to it: the
    same digits as Python's repr (both shortest, ties to the nearest), on random doubles
    of every magnitude."""
    import random
    rnd = random.Random(12)
    for _ in range(20000):
        x = struct.unpack("<d", struct.pack("<Q", rnd.getrandbits(64)))[0]
        if not math.isfinite(x):
            continue
        text = one_line(x)
        assert float(text) == x
        mant = lambda t: t.lower().split("e")[0].replace("-", "").replace(".", "").strip("0")   # noqa: E731
        assert mant(text) == mant(repr(x)), (text, repr(x))


def _csv_reference(header, rows) -> str:
    """csv_text as the csv writer alone gives it (every cell through safe_cell)."""
    import csv
    import io
    from tmm_cli.tables import safe_cell
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow([safe_cell(h) for h in header])
    for r in rows:
        vals = [r.get(h) for h in header] if isinstance(r, dict) else list(r)
        w.writerow([safe_cell(v) for v in vals])
    return buf.getvalue()


def test_csv_number_rows_as_the_writer_gives_them():
    import numpy as np
    from tmm_cli.tables import csv_text
    header = ["index", "phi", "a", "b"]
    rows = [[0, 12.5, -0.0, 1e-05], (1, 1e16, -3, 2.5e-300), [2, None, 1.0, float("nan")],
            [3, float("inf"), True, "text"], [4, "=1+2", "-1,5", ""], [5, np.float64(0.1), np.int64(3), 7],
            {"index": 6, "phi": 0.25, "a": None, "b": 1.5}, iter([7, 0.5, 0.5, 0.5]), [], [8, "1e5", -1, 0],
            [9, None, None, 2.0], [None, None, None, None], [None], [None, None], [10, "None", None, 1e-7],
            [11, None, float("nan"), 1.0], [None, 12], (13, None, -2.5e-12, None)]
    ref_rows = rows[:7] + [[7, 0.5, 0.5, 0.5]] + rows[8:]       # the iterator row, as a list
    assert csv_text(header, rows) == _csv_reference(header, ref_rows)


def test_written_piece_by_piece_as_a_whole(tmp_path):
    """results.json written in pieces (a fine grid: several pieces per section) is the
    text of dumps() to the byte, through the atomic writer."""
    from tmm_cli.io import atomic_write
    from tmm_cli.results import ENTRIES_PER_SPILL, dump
    text = (ROOT / "tasks" / "forging_sixbar.yaml").read_text(encoding="utf-8").replace("count: 12", "count: 600")
    res = run(tmm_cli.load_task(ROOT / "tasks" / "forging_sixbar.yaml", text=text))
    res["task"]["title"] = "Кривошипно-ползунный μ \"q\""       # non-ASCII across the pieces
    pieces: list[bytes] = []
    dump(res, pieces.append)
    assert len(pieces) >= 2 * (600 // ENTRIES_PER_SPILL)
    whole = dumps(res).encode("utf-8")
    assert b"".join(pieces) == whole
    p = atomic_write(tmp_path / "results.json", lambda write: dump(res, write))
    assert p.read_bytes() == whole
    assert json.loads(whole)["kinetostatics"][599]["index"] == res["kinetostatics"][599]["index"]
    _same_in_any_blocks(res["kinetostatics"])
    from tmm_cli.linkage import kinematics
    from tmm_cli.linkage.context import build
    lk = build(tmm_cli.load_task(ROOT / "tasks" / "forging_sixbar.yaml", text=text))
    _same_in_any_blocks(kinematics.analyze(lk).to_entries(list(lk.positions.index)))


def test_lazy_entries_as_a_read_only_sequence():
    """LazyEntries: len, indexing (new dicts each time), slices, iteration in blocks,
    equality with lists, copies and pickles as a plain list, written as a list."""
    import copy
    import pickle
    calls = []

    def build(i0, i1):
        calls.append((i0, i1))
        return [{"index": i, "x": i / 4} for i in range(i0, i1)]
    e = LazyEntries(5, build, block=2)
    ref = [{"index": i, "x": i / 4} for i in range(5)]
    assert len(e) == 5 and bool(e) and not LazyEntries(0, build)
    assert list(e) == ref and calls == [(0, 2), (2, 4), (4, 5)]
    assert e == ref and ref == e and e != ref[:4] and e == LazyEntries(5, build) and e != "x"
    assert e[-1] == ref[4] and e[1:3] == ref[1:3] and e[::2] == ref[::2] and e[4:1] == []
    with pytest.raises(IndexError):
        e[5]
    with pytest.raises(IndexError):
        e[-6]
    e[0]["x"] = 99.0
    assert e[0]["x"] == 0.0                       # read-only: each access builds anew
    assert {"index": 3, "x": 0.75} in e and e.index({"index": 2, "x": 0.5}) == 2
    for other in (copy.copy(e), copy.deepcopy(e), pickle.loads(pickle.dumps(e))):
        assert type(other) is Entries and other == ref
    assert dumps({"s": e}) == dumps({"s": ref})
    assert json.loads(dumps({"s": e}))["s"] == ref
    with pytest.raises(TypeError):
        hash(e)


def test_listed_makes_the_lazy_entries_lists():
    """listed: every LazyEntries in dicts at any depth made an Entries list (the dicts on
    the way copied, the caller's untouched); results without one come back as they are."""
    from tmm_cli.results import listed
    e = LazyEntries(3, lambda i0, i1: [{"index": i} for i in range(i0, i1)])
    res = {"a": e, "b": {"entries": e, "n": 1}, "c": [1.0], "d": {"x": 2}}
    out = listed(res)
    assert type(out["a"]) is Entries and type(out["b"]["entries"]) is Entries
    assert out["a"] == [{"index": 0}, {"index": 1}, {"index": 2}] == out["b"]["entries"]
    assert out["c"] is res["c"] and out["d"] is res["d"] and res["a"] is e and res["b"]["entries"] is e
    plain = {"c": [1.0], "d": {"x": 2}}
    assert listed(plain) is plain
    assert json.loads(json.dumps(out)) == json.loads(dumps(res))
