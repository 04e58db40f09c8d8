"""Every field of the task file shown in the report's task data has a name in every language,
and every word value a field can take (a Literal of the model) is given in words: a ru/uk report
never shows a raw English field name such as `quadrature` or a value such as `ratio_error`."""
from __future__ import annotations

import types
import typing

import pytest
from pydantic import BaseModel

from tmm_cli.report.sections import task as task_section
from tmm_cli.task import Task

# shown in their own tables (mechanism), not in the task data, or meta/identifiers
SKIP_TOP = set(task_section._META) | {"mechanism", "answers", "tolerance"}
SKIP_LITERALS = {"schema"}


def _args(ann) -> list:
    origin = typing.get_origin(ann)
    if origin in (typing.Union, types.UnionType, list, tuple, dict, typing.Annotated):
        out = []
        for a in typing.get_args(ann)[:1] if origin is typing.Annotated else typing.get_args(ann):
            out += _args(a)
        return out
    return [ann]


def _fields():
    """(dotted key, annotation parts) of every field reachable from the task model; the keys of a
    dict of models (synthesis.links.<name>) are left out: they are named per link."""
    out = []

    def walk(model, prefix):
        for name, f in model.model_fields.items():
            key = f"{prefix}.{f.alias or name}" if prefix else (f.alias or name)
            parts = _args(f.annotation)
            is_map = typing.get_origin(f.annotation) is dict or any(
                typing.get_origin(a) is dict for a in typing.get_args(f.annotation))
            subs = [a for a in parts if isinstance(a, type) and issubclass(a, BaseModel)]
            if is_map:
                continue
            for s in subs:
                walk(s, key)
            leaf = [a for a in parts if a is not type(None) and not (isinstance(a, type) and issubclass(a, BaseModel))]
            if leaf:
                out.append((key, leaf))
    walk(Task, "")
    return [(k, p) for k, p in out if k.split(".")[0] not in SKIP_TOP]


@pytest.mark.parametrize("lang", ["en", "ru", "uk"])
def test_every_task_field_has_a_name(lang):
    missing = sorted(k for k, _ in _fields() if task_section.param_name(k, lang) is None)
    assert not missing, missing


@pytest.mark.parametrize("lang", ["ru", "uk"])
def test_every_word_value_is_translated(lang):
    missing = set()
    for key, parts in _fields():
        for a in parts:
            if typing.get_origin(a) is typing.Literal and key not in SKIP_LITERALS:
                missing |= {f"{key}={v}" for v in typing.get_args(a)
                            if isinstance(v, str) and task_section.word_of(key, v, lang) is None}
    assert not missing, sorted(missing)


def test_drive_train_task_data_in_russian():
    """The drive train's task data (a list of stages) reads in Russian: numbered stages, units."""
    rows = task_section._rows("drive_train", {"motor_speed": 150.0, "rank": "size", "stages": [
        {"type": "pair", "z": [17, 34]}, {"type": "planetary", "scheme": "B"}]}, "ru")
    assert ("угловая скорость двигателя ω_д", "150 рад/с") in rows
    assert ("порядок вариантов", "по габариту") in rows
    assert ("ступень 1: вид", "зубчатая пара") in rows
    assert ("ступень 2: вид", "планетарная") in rows
    assert ("ступень 1: числа зубьев", "17; 34") in rows


@pytest.mark.parametrize("lang, words", [("ru", "по отклонению передаточного отношения"),
                                         ("uk", "за відхиленням передатного відношення"),
                                         ("en", "by the error of the ratio")])
def test_drive_train_candidates_heading_in_words(lang, words):
    from tmm_cli.report.sections.drive_train import rank_words
    assert rank_words("ratio_error", lang) == words
    assert rank_words("size", lang) != "size"


def test_synthesis_lengths_named_in_every_language():
    """The synthesis section's link lengths (кривошип l_OA, …) exist in Ukrainian too, not English."""
    from tmm_cli.report.sections import synthesis
    for lang in ("ru", "uk"):
        assert set(synthesis._LEN[lang]) == set(synthesis._LEN["en"]), lang
    assert synthesis._LEN["uk"]["guide_height"] == "напрямна повзуна над O1"
