"""No import cycles between the modules of tmm_cli at module level (the imports a module
runs when it is imported: top-level statements and the bodies of top-level if / try,
except `if TYPE_CHECKING:`); imports inside functions are deferred and not counted.
Found from the source with ast, so the test cannot be fooled by what happens to be
imported already."""
from __future__ import annotations

import ast
from pathlib import Path

PKG = Path(__file__).resolve().parent.parent / "tmm_cli"


def _modules() -> dict[str, tuple[Path, bool]]:
    out = {}
    for p in PKG.rglob("*.py"):
        parts = list(p.relative_to(PKG.parent).with_suffix("").parts)
        is_pkg = parts[-1] == "__init__"
        out[".".join(parts[:-1] if is_pkg else parts)] = (p, is_pkg)
    return out


def _top_level_imports(tree: ast.Module) -> list[ast.stmt]:
    found: list[ast.stmt] = []

    def walk(body):
        for n in body:
            if isinstance(n, (ast.Import, ast.ImportFrom)):
                found.append(n)
            elif isinstance(n, ast.If):
                if not (isinstance(n.test, ast.Name) and n.test.id == "TYPE_CHECKING"):
                    walk(n.body)
                walk(n.orelse)
            elif isinstance(n, ast.Try):
                walk(n.body)
                walk(n.orelse)
                walk(n.finalbody)
                for h in n.handlers:
                    walk(h.body)
    walk(tree.body)
    return found


def import_graph() -> dict[str, set[str]]:
    """module -> the tmm_cli modules it imports at module level (a `from X import name`
    depends on the submodule X.name when that is a module, else on X)."""
    mods = _modules()
    graph: dict[str, set[str]] = {}
    for name, (path, is_pkg) in mods.items():
        base = name.split(".") if is_pkg else name.split(".")[:-1]
        deps: set[str] = set()
        for node in _top_level_imports(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                cands = [a.name for a in node.names]
            else:
                target = ".".join(base[:len(base) - node.level + 1] + ([node.module] if node.module else [])) \
                    if node.level else (node.module or "")
                subs = [f"{target}.{a.name}" for a in node.names if f"{target}.{a.name}" in mods]
                cands = subs + ([target] if len(subs) < len(node.names) else [])
            deps |= {c for c in cands if c in mods and c != name}
        graph[name] = deps
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
    assert "tmm_cli.linkage.context" in g["tmm_cli.linkage.drive_speed"]   # from .context import Drive
    assert "tmm_cli.linkage.dynamics.flywheel" in g["tmm_cli.linkage.dynamics.cycle"]  # from . import flywheel


def test_no_import_cycles_in_tmm_cli():
    assert cycles(import_graph()) == []
