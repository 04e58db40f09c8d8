"""`tmm check`: compare a student's answers with the computed results."""
from __future__ import annotations

import csv
import io
import math
from pathlib import Path

from .errors import TaskError
from .results import lookup, parse_path

DEFAULT_TOLERANCE = 0.05


def load_answers(task, answers_file: Path | None) -> tuple[dict[str, float], dict[str, float]]:
    """The answers and tolerances: from --answers FILE (a YAML mapping with `answers`
    and optional `tolerance`, or a bare mapping path -> value) or from the task."""
    ans = dict(task.answers)
    tol = dict(task.tolerance)
    if answers_file is not None:
        from .yamlload import load_yaml
        data, marks = load_yaml(answers_file)
        if not isinstance(data, dict):
            raise TaskError("expected a mapping of answers", file=str(answers_file))
        if "answers" in data:
            unknown = set(data) - {"answers", "tolerance"}
            if unknown:
                k = sorted(map(str, unknown))[0]
                line, col = marks.get((k,), (None, None))
                raise TaskError("unknown key", file=str(answers_file),
                                issues=[(k, line, col, f"unknown key '{k}'; an answers file holds "
                                                       f"`answers` and `tolerance`")])
            raw_a, raw_t = data.get("answers") or {}, data.get("tolerance") or {}
            base = ("answers",)
        else:
            raw_a, raw_t, base = data, {}, ()
        for what, raw, b in (("answers", raw_a, base), ("tolerance", raw_t, ("tolerance",))):
            if not isinstance(raw, dict):
                line, col = marks.get(b, (None, None))
                raise TaskError("invalid answers file", file=str(answers_file),
                                issues=[(what, line, col, f"expected a mapping of paths to numbers, "
                                                          f"got {type(raw).__name__}")])
        ans = {str(k): _number(v, answers_file, marks, base + (k,), f"answers.{k}", positive=False)
               for k, v in raw_a.items()}
        tol = {str(k): _number(v, answers_file, marks, ("tolerance", k), f"tolerance.{k}", positive=True)
               for k, v in raw_t.items()}
    for k in ans:
        try:
            parse_path(k)
        except KeyError as exc:
            if answers_file is None:
                raise task.error(("answers", k), str(exc).strip("'\""))
            line, col = marks.get(base + (k,), (None, None))
            raise TaskError("invalid answers file", file=str(answers_file),
                            issues=[(f"answers.{k}", line, col, str(exc).strip("'\""))])
    if not ans:
        src = answers_file or task.file
        raise TaskError("no answers to check: add an `answers:` section (paths into results.json) "
                        "or give --answers FILE", file=str(src) if src else None)
    return ans, tol


def _number(v, file, marks, path, field: str, *, positive: bool) -> float:
    """A finite number (a tolerance: also >= 0) from an answers file, or a TaskError."""
    import math
    line, col = marks.get(path, (None, None))
    ok = isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(float(v))
    if ok and positive and float(v) < 0:
        ok = False
    if not ok:
        want = "a non-negative number (relative tolerance)" if positive else "a finite number"
        raise TaskError("invalid answers file", file=str(file), issues=[(field, line, col,
                                                                          f"expected {want}, got {v!r}")])
    return float(v)


def tolerance_for(key: str, tol: dict[str, float]) -> float:
    if key in tol:
        return tol[key]
    # a tolerance may be given for a section or a prefix ("flywheel", "kinematics")
    best, best_len = tol.get("default", DEFAULT_TOLERANCE), -1
    for k, v in tol.items():
        if k != "default" and key.startswith(k) and len(k) > best_len:
            best, best_len = v, len(k)
    return best


def check_task(results: dict, answers: dict[str, float], tol: dict[str, float]) -> list[dict]:
    """One row per answer: quantity, student, reference, rel_error, tolerance, verdict.
    The relative error is |student - reference| / |reference|; for a zero reference
    the absolute error is compared with the tolerance."""
    rows = []
    for key, student in answers.items():
        t = tolerance_for(key, tol)
        try:
            ref = lookup(results, key)
        except KeyError as exc:
            rows.append({"quantity": key, "student": student, "reference": None, "rel_error": None,
                         "tolerance": t, "verdict": "missing", "note": str(exc).strip("'\"")})
            continue
        if isinstance(ref, bool):
            ref = float(ref)
        if not isinstance(ref, (int, float)) or ref is None or not math.isfinite(ref):
            rows.append({"quantity": key, "student": student, "reference": ref, "rel_error": None,
                         "tolerance": t, "verdict": "missing", "note": "not a number in the results"})
            continue
        err = abs(student - ref) / abs(ref) if ref != 0 else abs(student - ref)
        rows.append({"quantity": key, "student": student, "reference": float(ref), "rel_error": err,
                     "tolerance": t, "verdict": "ok" if err <= t else "wrong", "note": ""})
    return rows


def rows_csv(rows: list[dict]) -> str:
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=["quantity", "student", "reference", "rel_error", "tolerance",
                                        "verdict", "note"], lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow(r)
    return buf.getvalue()
