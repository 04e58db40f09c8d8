"""A restricted expression of one variable, ``y(x)``, as a task writes a function to generate:
``x``, numbers, ``+ - * / **``, parentheses and the functions sin cos tan exp log log10 sqrt
(and abs). Parsed by Python's ``ast`` into a tree that only these nodes may form, then
evaluated on numpy arrays -- never ``eval``: no names but ``x``, no attributes, no calls but
the listed functions, at most 200 nodes and 10 levels of powers, so a text cannot run code,
hang or build a huge integer (numbers are floats: ``9**9**9`` is inf, refused as not finite).
"""
from __future__ import annotations

import ast
from typing import Callable

FUNCTIONS = ("sin", "cos", "tan", "exp", "log", "log10", "sqrt", "abs")
MAX_NODES = 200


class ExprError(ValueError):
    """The text is not an expression of the grammar: the reason in words."""


_OPS = {ast.Add: "add", ast.Sub: "subtract", ast.Mult: "multiply", ast.Div: "divide", ast.Pow: "power"}


def compile_expr(text: str) -> Callable:
    """A function of a numpy array ``x`` computing the expression; ExprError if the text is not one."""
    if not isinstance(text, str) or not text.strip():
        raise ExprError("an empty expression")
    if len(text) > 1000:
        raise ExprError("an expression longer than 1000 characters")
    # the minus sign of a word processor (U+2212) is a minus, as in every number tmm reads
    text = text.replace("\u2212", "-")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        raise ExprError(f"not an expression: {exc.msg}") from None
    nodes = list(ast.walk(tree))
    if len(nodes) > MAX_NODES:
        raise ExprError(f"more than {MAX_NODES} terms")
    _check(tree.body, 0)

    def f(x):
        import numpy as np
        with np.errstate(all="ignore"):
            return _eval(tree.body, np.asarray(x, float))
    return f


def _check(node, powers: int) -> None:
    if isinstance(node, ast.BinOp) and type(node.op) in _OPS:
        depth = powers + (1 if isinstance(node.op, ast.Pow) else 0)
        if depth > 10:
            raise ExprError("powers nested more than 10 deep")
        _check(node.left, depth)
        _check(node.right, depth)
    elif isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        _check(node.operand, powers)
    elif isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(node.value, bool):
        pass
    elif isinstance(node, ast.Name):
        if node.id != "x":
            raise ExprError(f"unknown name '{node.id}' (the variable is x; functions: {', '.join(FUNCTIONS)})")
    elif isinstance(node, ast.Call):
        if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
            name = node.func.id if isinstance(node.func, ast.Name) else ast.unparse(node.func)
            raise ExprError(f"unknown function '{name}' (known: {', '.join(FUNCTIONS)})")
        if len(node.args) != 1 or node.keywords:
            raise ExprError(f"{node.func.id} takes one argument")
        _check(node.args[0], powers)
    elif isinstance(node, ast.BinOp) and isinstance(node.op, ast.BitXor):
        raise ExprError(f"'{ast.unparse(node)}': a power is written ** (x**1.5), not ^")
    elif isinstance(node, ast.Tuple):
        raise ExprError(f"'{ast.unparse(node)}' is not one expression: a decimal number is written with a point "
                        "(1.5), not a comma")
    else:
        raise ExprError(f"'{ast.unparse(node) if hasattr(ast, 'unparse') else type(node).__name__}' is not allowed "
                        f"(x, numbers, + - * / **, parentheses and {', '.join(FUNCTIONS)})")


def _eval(node, x):
    import numpy as np
    if isinstance(node, ast.BinOp):
        a, b = _eval(node.left, x), _eval(node.right, x)
        op = type(node.op)
        if op is ast.Add:
            return a + b
        if op is ast.Sub:
            return a - b
        if op is ast.Mult:
            return a * b
        if op is ast.Div:
            return a / b
        return np.power(np.asarray(a, float), np.asarray(b, float))
    if isinstance(node, ast.UnaryOp):
        v = _eval(node.operand, x)
        return -v if isinstance(node.op, ast.USub) else v
    if isinstance(node, ast.Constant):
        return np.float64(node.value)          # numpy arithmetic: 1/0 is inf, not an exception
    if isinstance(node, ast.Name):
        return x
    fn = {"sin": np.sin, "cos": np.cos, "tan": np.tan, "exp": np.exp, "log": np.log, "log10": np.log10,
          "sqrt": np.sqrt, "abs": np.abs}[node.func.id]
    return fn(_eval(node.args[0], x))
