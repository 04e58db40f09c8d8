"""The floats of the CSV files (tmm_cli.tables.csv_text): the shortest repr (the
instructor's files) or the shortest digits as results.json spells them (the report's
tables, AS_JSON, a whole table by one orjson call). Either way
every finite float reads back as the very same float (its bits: -0.0, subnormals, the
largest and smallest exponents), NaN and inf give an empty cell, and every other cell
(text, int, bool, None, a numpy scalar) is written as the csv writer with safe_cell
writes it."""
from __future__ import annotations

import csv
import math
import struct

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from tmm_cli.tables import AS_JSON, SHORTEST, csv_text, safe_cell


def _bits(x: float) -> bytes:
    return struct.pack("<d", x)


def _cells(text: str) -> list[list[str]]:
    return list(csv.reader(text.splitlines()))


finite = st.floats(allow_nan=False, allow_infinity=False, allow_subnormal=True)
cell = st.one_of(finite, finite, finite, st.integers(min_value=-2 ** 80, max_value=2 ** 80), st.none(),
                 st.sampled_from([math.nan, math.inf, -math.inf, -0.0, 5e-324, -5e-324, 2.2250738585072014e-308,
                                  1.7976931348623157e308, True, False, "x", "-1", "=1+2", "a,b", ""]))


def _writer_reference(header, rows, fmt) -> str:
    """What csv_text gives, cell by cell: a finite float as ``repr(v)`` (SHORTEST) or
    as json's encoder spells it, turned into orjson's spelling by hand (AS_JSON),
    anything else through safe_cell, every row through the csv writer."""
    import io
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow([safe_cell(h) for h in header])
    for r in rows:
        w.writerow([(repr(v) if fmt == SHORTEST else _json_spelling(v)) if type(v) is float and math.isfinite(v)
                    else safe_cell(v) for v in r])
    return buf.getvalue()


def _json_spelling(v: float) -> str:
    """orjson's text of a finite float, from Python's repr by its documented rules
    (ryu's shortest digits, which repr also gives): a decimal point and no exponent for
    1e-5 <= |v| < 1e16 (``0.00001`` where repr gives ``1e-05``), else the exponent
    with its sign before a positive one and no leading zero (``2.5e-7``, ``1e+16``)."""
    r = repr(v)
    if "e" not in r:
        return r
    mant, exp = r.split("e")
    e = int(exp)
    if -5 <= e < 16:                   # repr writes 1e-05 .. 9.99e-05 with an exponent
        from decimal import Decimal
        return format(Decimal(r), "f")
    return f"{mant}e{'+' if e > 0 else '-'}{abs(e)}"


@settings(max_examples=300, deadline=None)
@given(st.lists(st.lists(cell, min_size=0, max_size=6), min_size=1, max_size=6))
def test_rows_as_the_writer_gives_them_and_floats_read_back_bit_for_bit(rows):
    width = max(len(r) for r in rows)
    header = [f"c{i}" for i in range(width)]
    for fmt in (SHORTEST, AS_JSON):
        text = csv_text(header, rows, fmt)
        assert text == _writer_reference(header, rows, fmt)
        back = _cells(text)[1:]
        assert len(back) == len(rows)
        for r, b in zip(rows, back):
            assert len(b) == max(1, len(r)) if r else b == []
            for v, c in zip(r, b):
                if type(v) is float and math.isfinite(v):
                    assert _bits(float(c)) == _bits(v), (v, c)
                elif type(v) is float or v is None:
                    assert c == ""
                elif type(v) is int:
                    assert int(c) == v and c == str(v)


@settings(max_examples=500, deadline=None)
@given(st.lists(finite, min_size=1, max_size=40))
def test_number_rows_read_back_bit_for_bit(vals):
    """The fast path (a row of numbers only) of both formats."""
    rows = [vals, [7] + vals, [None] + vals + [None]]
    header = [str(i) for i in range(len(vals) + 2)]
    for fmt in (SHORTEST, AS_JSON):
        back = _cells(csv_text(header, rows, fmt))[1:]
        assert [_bits(float(c)) for c in back[0]] == [_bits(v) for v in vals]
        assert back[1][0] == "7" and [_bits(float(c)) for c in back[1][1:]] == [_bits(v) for v in vals]
        assert back[2][0] == back[2][-1] == ""
        assert [_bits(float(c)) for c in back[2][1:-1]] == [_bits(v) for v in vals]


def test_as_json_text():
    vals = [30.0, 0.1, -0.0, 0.0, 5e-324, 1.7976931348623157e308, 1e16, 1e-07, 0.00001, 2.5e-05, -1.5, 3,
            -2 ** 70, None]
    text = csv_text(["h"] * len(vals), [vals], AS_JSON)
    assert text.splitlines()[1] == ("30.0,0.1,-0.0,0.0,5e-324,1.7976931348623157e+308,1e+16,1e-7,0.00001,0.000025,"
                                    "-1.5,3,-1180591620717411303424,")
    # the same cells as results.json writes them (one_line: orjson)
    from tmm_cli.results import one_line
    assert text.splitlines()[1].split(",")[:11] == one_line(vals[:11]).strip("[]").split(",")
    # the shortest repr, as before
    assert csv_text(["h"] * len(vals), [vals]).splitlines()[1] == \
        "30.0,0.1,-0.0,0.0,5e-324,1.7976931348623157e+308,1e+16,1e-07,1e-05,2.5e-05,-1.5,3,-1180591620717411303424,"


def test_as_json_whole_table_and_row_by_row_agree():
    """A table of plain numbers goes through orjson at once; one text cell anywhere sends
    every row through the row-by-row path: the number rows' text is the same."""
    rows = [[1, 0.1, None, 2.5e-7], [True, -0.0, 1e300, None], [None, None], [3]]
    whole = csv_text(["a", "b", "c", "d"], rows, AS_JSON).splitlines()[1:]
    mixed = csv_text(["a", "b", "c", "d"], rows + [["x"]], AS_JSON).splitlines()[1:]
    assert whole == ["1,0.1,,2.5e-7", "true,-0.0,1e+300,", ",", "3"]
    assert mixed == whole + ["x"]


@pytest.mark.parametrize("fmt", [SHORTEST, AS_JSON])
def test_non_finite_and_other_cells_as_before(fmt):
    """NaN and inf: empty; bool, text, numpy scalars: safe_cell's text; a row of one empty
    cell quoted; the same whether the row also holds floats or not."""
    rows = [[1, math.nan, 0.5], [math.inf, -math.inf], [True, 0.5], ["-x", 0.5], [None], [None, None], [],
            [np.float64(0.5), np.int64(3), 0.5], {"a": 0.5, "b": None}]
    text = csv_text(["a", "b", "c"], rows, fmt)
    half = "0.5"
    assert text.splitlines() == ["a,b,c", f"1,,{half}", ",", f"true,{half}", f"'-x,{half}", '""', ",", "",
                                 f"{half},3,{half}", f"{half},,"]
    # a numpy float64 is a float: its cell is the number, never numpy 2's "np.float64(0.5)"
    assert safe_cell(np.float64(0.1)) == "0.1" and safe_cell(np.float64(math.nan)) == ""


def test_unknown_float_format_refused():
    with pytest.raises(ValueError):
        csv_text(["a"], [[1.0]], "%.6g")


def test_report_tables_read_back_as_results(tmp_path):
    """kinematics.csv beside a report: every number the very float of the results."""
    import tmm_cli
    from tmm_cli.report import render
    from tmm_cli.orchestrate import REPORT_ONLY
    from pathlib import Path
    task = tmm_cli.load_task(Path(__file__).resolve().parents[1] / "tasks" / "forging_sixbar.yaml")
    res = tmm_cli.run(task)
    render({k: v for k, v in res.items() if k not in REPORT_ONLY}, task, tmp_path, {"html"}, "en")
    rows = list(csv.DictReader((tmp_path / "kinematics.csv").open(encoding="utf-8")))
    assert len(rows) == len(res["kinematics"])
    from tmm_cli.results import one_line
    n = 0
    for row, e in zip(rows, res["kinematics"]):
        assert int(row["index"]) == e["index"] and _bits(float(row["phi"])) == _bits(float(e["phi"]))
        for p, d in e["points"].items():
            for k, v in d.items():
                if f"{p}.{k}" in row:
                    assert (row[f"{p}.{k}"] == "") if v is None else _bits(float(row[f"{p}.{k}"])) == _bits(v)
                    assert row[f"{p}.{k}"] == ("" if v is None else one_line(v))      # results.json's text
                    n += 1
    assert n > 100
