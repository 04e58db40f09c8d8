"""The task model's validator, kept between runs like Python's bytecode.

Building the validator of :class:`tmm_cli.task.Task` (pydantic's schema generation for
every section, and the import of its plugin machinery) costs more than validating a task.
The validator is made of the core schema that generation produces and the model's core
config; :func:`save` writes both with pickle next to the model's bytecode
(``__pycache__``, or under ``PYTHONPYCACHEPREFIX``; nothing when bytecode is not written),
and :func:`load` rebuilds the identical validator from them (pydantic_core's
``SchemaValidator``, the class pydantic builds) when nothing it depends on changed: the
Python, pydantic and pydantic-core versions, and the size and modification time of each
module the model is defined in (as Python checks a .pyc against its source).

The schema's ``metadata`` (pydantic's JSON-schema hooks, which the validator never reads)
is left out; :func:`save` writes nothing unless the pickle gives back the very functions,
classes and values of the schema.
"""
from __future__ import annotations

import os
import pickle
import sys
from functools import partial
from pathlib import Path
from types import MethodType

from . import kept

# the modules the task model (its fields, types, validators) is defined in
# (every tmm_cli module `import tmm_cli.task` loads: tests/test_schema_cache.py)
MODULES = ("tmm_cli", "tmm_cli.errors", "tmm_cli.limits", "tmm_cli.messages", "tmm_cli.modelbase", "tmm_cli.units",
           "tmm_cli.linkage", "tmm_cli.linkage.spec", "tmm_cli.cam", "tmm_cli.cam.spec", "tmm_cli.gears",
           "tmm_cli.gears.spec", "tmm_cli.trainspec", "tmm_cli.dof2", "tmm_cli.dof2.spec", "tmm_cli.differential", "tmm_cli.differential.spec",
           "tmm_cli.balancing", "tmm_cli.balancing.spec", "tmm_cli.numfmt", "tmm_cli.kept", "tmm_cli.locales",
           "tmm_cli.task")
_FORMAT = 1


def _path(model: type) -> Path:
    from importlib.util import cache_from_source
    pyc = Path(cache_from_source(sys.modules[model.__module__].__file__))
    return pyc.with_name(f"{model.__name__.lower()}-validator.{sys.implementation.cache_tag}.pickle")


def _stamp(model: type) -> tuple:
    import pydantic
    import pydantic_core
    files = []
    for name in MODULES:
        st = os.stat(sys.modules[name].__file__)
        files.append((name, st.st_mtime_ns, st.st_size))
    return (_FORMAT, model.__module__, model.__qualname__, sys.version, pydantic.VERSION, pydantic_core.__version__,
            tuple(files))


def _strip(schema):
    """The core schema without its ``metadata`` entries (a schema's, never a field named so)."""
    if isinstance(schema, dict):
        return {k: _strip(v) for k, v in schema.items() if not (k == "metadata" and "type" in schema)}
    if isinstance(schema, list):
        return [_strip(v) for v in schema]
    if isinstance(schema, tuple):
        return tuple(_strip(v) for v in schema)
    return schema


def same(a, b) -> bool:
    """``a`` and ``b`` are the same schema: equal values, the same functions and classes."""
    if type(a) is not type(b):
        return False
    if isinstance(a, dict):
        return a.keys() == b.keys() and all(same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return len(a) == len(b) and all(same(x, y) for x, y in zip(a, b))
    if isinstance(a, partial):
        return same(a.func, b.func) and same(a.args, b.args) and same(a.keywords, b.keywords)
    if isinstance(a, MethodType):
        return a.__func__ is b.__func__ and a.__self__ is b.__self__
    if isinstance(a, (str, bytes, int, float, bool, type(None))):
        return a == b
    return a is b


_LOADED: dict[type, object] = {}


def validator(model: type):
    """The validator of a model of the task (what ``model.model_validate`` runs): the
    model's own once built, else the one cached by an earlier run, else the model's, built
    now and cached for the next run."""
    return _made(model, _LOADED, "__pydantic_validator__", load)


_SERIALIZERS: dict[type, object] = {}


def serializer(model: type):
    """The serializer of a model of the task (what ``model_dump`` runs): the model's own
    once built, else one made from the core schema cached by an earlier run (the same
    schema the validator is made of), else the model's, built now and cached."""
    return _made(model, _SERIALIZERS, "__pydantic_serializer__", _load_serializer)


def _made(model: type, made: dict, attr: str, load_cached):
    """The model's own ``attr`` once built, else ``load_cached(model)`` (kept in ``made``),
    else the model's, built now and cached for the next run."""
    if model.__pydantic_complete__:
        return getattr(model, attr)
    got = made.get(model)
    if got is None:
        got = load_cached(model)
        if got is None:
            model.model_rebuild()
            save(model)
            return getattr(model, attr)
        made[model] = got
    return got


def _load_serializer(model: type):
    """The model's serializer from the cache, or None (no cache, or a stale one)."""
    from pydantic_core import SchemaSerializer
    return _from_cache(model, SchemaSerializer)


def _from_cache(model: type, make):
    """``make(core schema, core config)`` of the cached schema, or None (no cache, a stale
    one, or one that cannot be read: then pydantic builds the object itself)."""
    sc = _schema(model)
    if sc is None:
        return None
    try:
        return make(*sc)
    except Exception:  # noqa: BLE001 - a cache that cannot be read is no cache
        return None


def _schema(model: type):
    """(core schema, core config) of the model from the cache, or None (no cache, or a stale one)."""
    try:
        path, stamp = _path(model), _stamp(model)
    except Exception:  # noqa: BLE001 - a module file that cannot be read: no cache, pydantic builds the model
        return None
    got = kept.read(path, stamp)
    return None if got is kept.MISSING else got


def load(model: type):
    """The model's validator from the cache, or None (no cache, or a stale one)."""
    from pydantic_core import SchemaValidator
    return _from_cache(model, SchemaValidator)


def save(model: type) -> None:
    """Write the (complete) model's validator to the cache; nothing if it cannot be
    written or would not give back the same schema."""
    if sys.dont_write_bytecode:
        return
    try:
        cls, (schema, config, *_) = model.__pydantic_validator__.__reduce__()
        data = (_strip(schema), config)
        blob = pickle.dumps(data, protocol=pickle.HIGHEST_PROTOCOL)
        if not same(pickle.loads(blob), data):
            return
        path, stamp = _path(model), _stamp(model)
    except Exception:  # noqa: BLE001 - a validator that cannot be pickled is not kept: the next run builds again
        return
    kept.write(path, stamp, pickled=blob)