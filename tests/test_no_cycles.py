"""tmm's own functions leave no reference cycles behind: what they made is freed by its
reference counts when the caller drops it, not later by Python's cycle collector.  A
recursive inner function is such a cycle (the function, the cell that holds it for its own
calls, the cells of everything else it reads): the results' leaf paths (~10^4 tuples a
variant in a batch's grading), the PDF writer's tables (with the writer and its tree), the
force polygon's search and the structure's cycle search each stayed alive until a collection
found them.  tmm has no such inner function: each recursion is a function of its module."""
from __future__ import annotations

import ast
import gc
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _recursive_inner_functions(tree: ast.AST):
    """(enclosing function, inner function) pairs where the inner one calls itself by name."""
    for outer in ast.walk(tree):
        if not isinstance(outer, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        for inner in ast.walk(outer):
            if inner is outer or not isinstance(inner, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            if any(isinstance(n, ast.Name) and n.id == inner.name for n in ast.walk(inner)):
                yield outer, inner


def test_no_recursive_inner_function():
    found = [f"{path.relative_to(ROOT)}:{inner.lineno} {outer.name}.{inner.name}"
             for path in sorted((ROOT / "tmm_cli").rglob("*.py"))
             for outer, inner in _recursive_inner_functions(ast.parse(path.read_text(encoding="utf-8")))]
    assert not found, f"recursive inner functions (reference cycles: make them functions of the module): {found}"


def test_the_check_sees_a_recursive_inner_function():
    tree = ast.parse("def f(x):\n    def g(n):\n        return 0 if n == 0 else g(n - 1)\n    return g(x)\n")
    assert [(o.name, i.name) for o, i in _recursive_inner_functions(tree)] == [("f", "g")]
    tree = ast.parse("def g(n):\n    return 0 if n == 0 else g(n - 1)\n\ndef f(x):\n    return g(x)\n")
    assert list(_recursive_inner_functions(tree)) == []


def _garbage(call) -> int:
    """How many objects ``call()`` leaves in reference cycles once its result is dropped."""
    gc.collect()
    was = gc.isenabled()
    gc.disable()
    try:
        out = call()
        del out
        return gc.collect()
    finally:
        if was:
            gc.enable()


@pytest.mark.parametrize("what", ["leaf_paths", "longest_cycle", "pdf_table", "apart_order"])
def test_no_cycle_left_behind(what):
    if what == "leaf_paths":
        from tmm_cli.results import leaf_paths
        data = {"kinematics": [{"index": k, "phi": 30.0 * k, "v": {"B": [1.0, 2.0]}} for k in range(12)]}
        call = lambda: leaf_paths(data)                                         # noqa: E731
    elif what == "longest_cycle":
        from types import SimpleNamespace

        from tmm_cli.linkage.structure import _longest_cycle
        edges = [SimpleNamespace(a=a, b=b) for a, b in ((0, 1), (1, 2), (2, 3), (3, 0), (0, 2))]
        call = lambda: _longest_cycle([0, 1, 2, 3], edges)                      # noqa: E731
    elif what == "pdf_table":
        from tmm_cli.report.typst_pdf import to_typst
        html = ("<html><head><title>t</title></head><body><table><caption>c</caption><thead><tr><th>a</th>"
                "<th>b</th></tr></thead><tbody><tr><td>1</td><td>2</td></tr></tbody></table></body></html>")
        call = lambda: to_typst(html)                                           # noqa: E731
    else:
        from tmm_cli.drawings.forces import apart_order
        vecs = [("G", (0.0, -1.0), "load"), ("F", (0.0, 1.0), "load"), ("R1", (1.0, 0.5), "reaction"),
                ("R2", (-1.0, -0.5), "reaction")]
        call = lambda: apart_order(vecs)                                        # noqa: E731
    call()                          # its first call may import modules (their own cycles)
    assert _garbage(call) == 0
