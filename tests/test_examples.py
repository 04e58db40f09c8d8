"""Every example in tasks/ validates and runs through the whole pipeline (CI runs them
all), and its results obey the cross-checks that must hold for any task.  The results are
those `tmm run` computes (shared with the tests that read an example's report); every example
through the Python API: tests/test_fuzz_inputs.py, test_examples_results_are_plain_json."""
from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from tmm_cli.messages import LANGS, PLAIN, catalogue, render
from tmm_cli.orchestrate import REPORT_ONLY

TASKS = sorted((Path(__file__).resolve().parents[1] / "tasks").glob("*.yaml"))


def _finite_numbers(obj, path="$"):
    if isinstance(obj, dict):
        for k, v in obj.items():
            yield from _finite_numbers(v, f"{path}.{k}")
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            yield from _finite_numbers(v, f"{path}[{i}]")
    elif isinstance(obj, float):
        yield path, obj


@pytest.mark.parametrize("path", TASKS, ids=[p.stem for p in TASKS])
def test_example_runs(path, shared_once):
    # the results `tmm run --format html,pdf` computes (a synthesis's mechanism generated), once per
    # session for the tests that read them (tests/pdf_extent.py), as results.json holds them
    from pdf_extent import results
    task, res = results(shared_once, path.stem)
    res = {k: v for k, v in res.items() if k not in REPORT_ONLY}
    assert res["schema"] == "tmm-results/1"
    json.dumps(res, allow_nan=False)          # plain JSON, no NaN anywhere
    # every warning as data: a catalogued code in every language, its English text the warning
    assert [m["text"] for m in res["messages"]] == res["warnings"]
    for m in res["messages"]:
        assert m["code"] != PLAIN and all(m["code"] in catalogue(lang)["messages"] for lang in LANGS)
        assert render(m["code"], m["params"], "en") == m["text"]
    for where, x in _finite_numbers(res):
        assert math.isfinite(x), where
    if task.mechanism is not None:
        st = res["structure"]
        assert st["W"] == 3 * st["n"] - 2 * st["p5"] - st["p4"] == 1
        kin = res["kinematics"]
        count = (task.positions.count if task.positions else 12)
        assert [e["index"] for e in kin[:count]] == list(range(count))
        # every point and every link at every position
        names = set(kin[0]["points"])
        for e in kin:
            assert set(e["points"]) == names
            assert 0 <= e["phi"] < 360
    if "kinetostatics" in res:
        for e in res["kinetostatics"]:
            if e.get("near_singular") or e.get("balancing_moment") is None:
                continue
            mk, mz, mv = e["balancing_moment"], e["zhukovsky_moment"], e["virtual_power_moment"]
            scale = max(abs(mk), 1e-6)
            assert abs(mz - mk) <= 1e-7 * scale + 1e-9, (path.name, e["index"])
            assert abs(mv - mk) <= 1e-7 * scale + 1e-9, (path.name, e["index"])
