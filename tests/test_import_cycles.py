"""No import cycles between the modules of tmm_cli, counting every import a module makes:
at module level and inside functions (deferred, but a cycle all the same: the two modules
need each other), except under `if TYPE_CHECKING:` (types only, never run). Found from
the source with ast, so the test cannot be fooled by what happens to be imported already."""
from __future__ import annotations

import ast
import functools
from pathlib import Path

PKG = Path(__file__).resolve().parent.parent / "tmm_cli"


def _modules() -> dict[str, tuple[Path, bool]]:
    out = {}
    for p in PKG.rglob("*.py"):
        parts = list(p.relative_to(PKG.parent).with_suffix("").parts)
        is_pkg = parts[-1] == "__init__"
        out[".".join(parts[:-1] if is_pkg else parts)] = (p, is_pkg)
    return out


def _type_checking(node: ast.AST) -> bool:
    """`if TYPE_CHECKING:` (or `if typing.TYPE_CHECKING:`)."""
    t = getattr(node, "test", None)
    return isinstance(node, ast.If) and (isinstance(t, ast.Name) and t.id == "TYPE_CHECKING"
                                         or isinstance(t, ast.Attribute) and t.attr == "TYPE_CHECKING")


def _imports(tree: ast.Module) -> list[ast.stmt]:
    """Every import statement of a module: at module level, in if / try, in function and
    class bodies; not the body of an `if TYPE_CHECKING:` (its `else` counts)."""
    found: list[ast.stmt] = []

    def walk(node: ast.AST) -> None:
        for n in ast.iter_child_nodes(node):
            if isinstance(n, (ast.Import, ast.ImportFrom)):
                found.append(n)
            elif _type_checking(n):
                for m in n.orelse:
                    walk(ast.Module(body=[m], type_ignores=[]))
            else:
                walk(n)
    walk(tree)
    return found


def import_graph() -> dict[str, set[str]]:
    """module -> the tmm_cli modules it imports anywhere (a `from X import name` depends on
    the submodule X.name when that is a module, else on X): a fresh copy of the graph, read
    from the sources once per process (2 s of parsing; four tests read it)."""
    return {k: set(v) for k, v in _graph().items()}


@functools.cache
def _graph() -> dict[str, frozenset[str]]:
    mods = _modules()
    graph: dict[str, frozenset[str]] = {}
    for name, (path, is_pkg) in mods.items():
        base = name.split(".") if is_pkg else name.split(".")[:-1]
        deps: set[str] = set()
        for node in _imports(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                cands = [a.name for a in node.names]
            else:
                target = ".".join(base[:len(base) - node.level + 1] + ([node.module] if node.module else [])) \
                    if node.level else (node.module or "")
                subs = [f"{target}.{a.name}" for a in node.names if f"{target}.{a.name}" in mods]
                cands = subs + ([target] if len(subs) < len(node.names) else [])
            deps |= {c for c in cands if c in mods and c != name}
        graph[name] = frozenset(deps)
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_the_finder_sees_a_cycle():
    g = {"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}
    assert cycles(g) == [["a", "b", "c"]]
    assert cycles({"a": {"b"}, "b": set()}) == []


def test_the_graph_reads_relative_imports():
    g = import_graph()
    assert "tmm_cli.errors" in g["tmm_cli.pipeline"]                  # from .errors import ...
    assert "tmm_cli.linkage.drive_speed" in g["tmm_cli.linkage.context"]   # from .drive_speed import Drive
    assert "tmm_cli.linkage.dynamics.flywheel" in g["tmm_cli.linkage.dynamics.cycle"]  # from . import flywheel


def test_no_import_cycles_in_tmm_cli():
    assert cycles(import_graph()) == []


def test_the_graph_counts_imports_inside_functions_not_type_checking():
    g = import_graph()
    assert "tmm_cli.linkage.synthesis" in g["tmm_cli.pipeline"]        # inside run(): generate
    assert "tmm_cli.linkage.kinematics" in g["tmm_cli.linkage.context"]    # inside reported_positions
    # the context's Linkage is a type of the kinematics stage's functions only
    assert "tmm_cli.linkage.context" not in g["tmm_cli.linkage.kinematics.stage"]
    tree = ast.parse("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import a\nelse:\n    import b\n"
                     "def f():\n    import c\n    class K:\n        import d\n")
    assert [getattr(n, "module", None) or n.names[0].name for n in _imports(tree)] == ["typing", "b", "c", "d"]


def test_the_task_model_imports_no_stage():
    """The task model composes the sections and loads: it reaches no stage (the stages read
    their sections, tmm_cli/<topic>/spec.py), even inside a validator."""
    g = import_graph()
    seen, todo = set(), ["tmm_cli.task"]
    while todo:
        m = todo.pop()
        if m not in seen:
            seen.add(m)
            todo.extend(g[m])
    stages = {m for m in seen if m.startswith(("tmm_cli.linkage.", "tmm_cli.cam.", "tmm_cli.gears."))
              and not m.endswith(".spec")}
    assert not stages, sorted(stages)
