"""The cached validator of the task model (tmm_cli.schemacache) is pydantic's: the same
tasks, the same values, the same errors (type, place, message) on every mutation of
every example task; a stale or broken cache is not used; a second command line in a fresh
process reads the cache instead of building the schema."""
from __future__ import annotations

import copy
import os
import subprocess
import sys
from functools import partial
from pathlib import Path
from types import FunctionType, MethodType

import pytest
from pydantic import ValidationError

from tmm_cli import schemacache
from tmm_cli.task import Task
from tmm_cli.yamlload import load_yaml

ROOT = Path(__file__).resolve().parents[1]
_STAMP = schemacache._stamp
EXAMPLES = sorted((ROOT / "tasks").glob("*.yaml")) + sorted((ROOT / "tmm_cli" / "starters").glob("*.yaml"))
BAD = [None, True, "x", "-1 m", "3 kg", -1, 0, 1e400, "1e400", [], {}, [1, 2, 3], {"a": 1}, "1/0", "nan", 10**30]


def _cached(model, tmp_path, monkeypatch):
    """(the validator read back from a cache written now, pydantic's validator)."""
    monkeypatch.setattr(schemacache, "_path", lambda m: tmp_path / f"{m.__name__}-validator.pickle")
    monkeypatch.setattr(sys, "dont_write_bytecode", False)
    model.model_rebuild()
    schemacache.save(model)
    assert (tmp_path / f"{model.__name__}-validator.pickle").exists()
    v = schemacache.load(model)
    assert v is not None and v is not model.__pydantic_validator__
    return v, model.__pydantic_validator__


@pytest.fixture()
def cached(tmp_path, monkeypatch):
    return _cached(Task, tmp_path, monkeypatch)


def _outcome(validator, data):
    try:
        t = validator.validate_python(copy.deepcopy(data))
    except ValidationError as exc:
        return "error", [(e["type"], e["loc"], e["msg"], repr(e.get("input")), repr((e.get("ctx") or {}).get("error")))
                         for e in exc.errors(include_url=False)]
    return "ok", t


def _mutations(data, path=()):
    """Every leaf replaced by each bad value, every key deleted and misspelt."""
    if isinstance(data, dict):
        for k, v in data.items():
            without = {kk: vv for kk, vv in data.items() if kk != k}
            yield path, without
            yield path, {**without, f"{k}x": v}
            yield from _mutations(v, path + (k,))
    elif isinstance(data, list):
        for i in range(len(data)):
            yield path, data[:i] + data[i + 1:]
    if not isinstance(data, (dict, list)) or not data:
        for b in BAD:
            yield path, b


def _put(data, path, value):
    if not path:
        return value
    out = copy.copy(data)
    out[path[0]] = _put(data[path[0]], path[1:], value)
    return out


def test_the_mutations_are_many():
    """More than 2,000 mutations of the examples in all (test_cached_validator_is_pydantics
    validates them in five shares)."""
    assert sum(1 for f in EXAMPLES for _ in _mutations(load_yaml(f)[0])) > 2000


_SHARES = 5


@pytest.mark.parametrize("share", range(_SHARES))
def test_cached_validator_is_pydantics(cached, share):
    """Every fifth example (and every mutation of it) in each of five tests: the suite's
    workers share them out."""
    mine, theirs = cached
    n = 0
    for f in EXAMPLES[share::_SHARES]:
        data, _ = load_yaml(f)
        a, b = _outcome(mine, data), _outcome(theirs, data)
        assert a[0] == b[0] == "ok", f
        assert a[1] == b[1] and a[1].model_fields_set == b[1].model_fields_set, f     # fields and private ones
        for path, sub in _mutations(data):
            bad = _put(data, path, sub)
            a, b = _outcome(mine, bad), _outcome(theirs, bad)
            assert a == b, (f.name, path)
            n += 1
    assert n > 2000 / _SHARES


def _strict(a, b) -> bool:
    """Equal values of the same types, dict keys in the same order."""
    if type(a) is not type(b):
        return False
    if isinstance(a, dict):
        return list(a) == list(b) and all(_strict(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return len(a) == len(b) and all(_strict(x, y) for x, y in zip(a, b))
    return a == b or (a != a and b != b)


def test_cached_serializer_is_pydantics(cached, monkeypatch):
    """The report's dump of the task (the serializer made from the cached schema): the
    very dict model_dump gives, on every example, with and without the report's options."""
    mine, _ = cached
    monkeypatch.setattr(Task, "__pydantic_complete__", False)      # as in a fresh process
    monkeypatch.setattr(schemacache, "_SERIALIZERS", {})
    ser = schemacache.serializer(Task)
    assert ser is not Task.__pydantic_serializer__
    for f in EXAMPLES:
        data, _ = load_yaml(f)
        t = mine.validate_python(data)
        for kw in ({"exclude_none": True, "by_alias": True}, {}):
            assert _strict(ser.to_python(t, **kw), t.model_dump(**kw)), (f.name, kw)


@pytest.mark.parametrize("name", ["MechanismSection", "PositionsSection"])
def test_cached_section_validators_are_pydantics(name, tmp_path, monkeypatch):
    """The sections validated on their own (a synthesis's generated mechanism, its
    positions): the same values and errors, on every mutation of the examples' sections."""
    import tmm_cli.task as T
    model = getattr(T, name)
    mine, theirs = _cached(model, tmp_path, monkeypatch)
    key = {"MechanismSection": "mechanism", "PositionsSection": "positions"}[name]
    n = 0
    for f in EXAMPLES:
        data, _ = load_yaml(f)
        if key not in data:
            continue
        assert _outcome(mine, data[key]) == _outcome(theirs, data[key]), f
        for path, sub in _mutations(data[key]):
            bad = _put(data[key], path, sub)
            assert _outcome(mine, bad) == _outcome(theirs, bad), (f.name, path)
            n += 1
    assert n > 300


def test_stale_or_broken_cache_is_not_used(cached, tmp_path, monkeypatch):
    path = tmp_path / "Task-validator.pickle"
    stamp = schemacache._stamp(Task)
    monkeypatch.setattr(schemacache, "_stamp", lambda model: stamp[:-1] + ((("tmm_cli.task", 0, 0),),))
    assert schemacache.load(Task) is None                          # a module of the model changed
    monkeypatch.setattr(schemacache, "_stamp", lambda model: stamp)
    assert schemacache.load(Task) is not None
    (tmp_path / "MechanismSection-validator.pickle").write_bytes(path.read_bytes())
    monkeypatch.setattr(schemacache, "_stamp", _STAMP)
    from tmm_cli.linkage.spec import MechanismSection
    assert schemacache.load(MechanismSection) is None              # another model's validator
    monkeypatch.setattr(schemacache, "_stamp", lambda model: stamp)
    path.write_bytes(path.read_bytes()[:-100])                     # cut short
    assert schemacache.load(Task) is None
    path.unlink()
    assert schemacache.load(Task) is None
    monkeypatch.setattr(sys, "dont_write_bytecode", True)          # PYTHONDONTWRITEBYTECODE: nothing written
    schemacache.save(Task)
    assert not path.exists()


def test_the_stamp_covers_the_model():
    """Every function and class of the schema is defined in a module of the stamp, and the
    stamp lists every tmm_cli module the task model loads."""
    Task.model_rebuild()

    def walk(o):
        if isinstance(o, dict):
            for k, v in o.items():
                if not (k == "metadata" and "type" in o):
                    yield from walk(v)
        elif isinstance(o, (list, tuple)):
            for v in o:
                yield from walk(v)
        elif isinstance(o, partial):
            yield o.func
            yield from walk(list(o.args) + list(o.keywords.values()))
        elif isinstance(o, (FunctionType, MethodType, type)):
            yield o

    mods = {getattr(x, "__module__", None) for x in walk(Task.__pydantic_core_schema__)}
    mods = {m for m in mods if m and m.startswith("tmm_cli")}
    assert mods and mods <= set(schemacache.MODULES), mods - set(schemacache.MODULES)
    code = "import sys, tmm_cli.task; print(' '.join(m for m in sys.modules if m.startswith('tmm_cli')))"
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, cwd=ROOT)
    assert set(p.stdout.split()) == set(schemacache.MODULES)


def test_second_run_reads_the_cache(tmp_path):
    """With the bytecode cache on (an installed tmm), the first `tmm validate` writes the
    cache, the second reads it: the same output, and pydantic builds no validator (its
    plugin loader, which imports importlib.metadata, is never reached) -- also for a
    synthesis (the generated mechanism is validated as a MechanismSection), a cam and a
    flywheel without `shape` (default sections)."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env["PYTHONPYCACHEPREFIX"] = str(tmp_path / "pycache")
    code = ("import sys\nfrom tmm_cli.cli import main\ntry:\n    main()\nfinally:\n"
            "    print('BUILT', 'pydantic.plugin._loader' in sys.modules, file=sys.stderr)\n")
    tasks = [str(ROOT / "tasks" / f"{n}.yaml") for n in ("forging_sixbar", "synthesis_shaper", "cam_translating",
                                                          "press_drive_train")]
    runs = [subprocess.run([sys.executable, "-c", code, "validate", *tasks], capture_output=True, text=True,
                           env=env, cwd=tmp_path, timeout=300) for _ in range(2)]
    assert [r.returncode for r in runs] == [0, 0]
    assert runs[0].stdout == runs[1].stdout == "".join(f"{t}: ok\n" for t in tasks)
    assert "BUILT True" in runs[0].stderr and "BUILT False" in runs[1].stderr, runs[1].stderr
    assert {p.name.split("-")[0] for p in (tmp_path / "pycache").rglob("*-validator.*.pickle")} == \
        {"task", "mechanismsection"}
