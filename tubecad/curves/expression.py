"""Safe arithmetic expressions in s, for curvature functions typed into spec files.

The text is parsed with :mod:`ast` (parsing only, nothing is executed) and every node
is checked against a whitelist: numbers, the variable ``s``, the constants ``pi`` and
``e``, + - * / ** and unary minus, and a fixed set of numpy functions. The checked tree
is turned into a closure over numpy ufuncs. Names, attributes, subscripts, strings,
comprehensions, lambdas and keyword arguments are refused with a message that says so.
"""

from __future__ import annotations

import ast
import math
import operator
import sys
from collections.abc import Callable
from typing import Any

import numpy as np

from tubecad.core.errors import ExpressionError

MAX_LENGTH = 1000
MAX_NODES = 400
MAX_LITERAL_EXPONENT = 64.0

FUNCTIONS: dict[str, Callable[[np.ndarray], np.ndarray]] = {
    "sin": np.sin,
    "cos": np.cos,
    "tan": np.tan,
    "asin": np.arcsin,
    "acos": np.arccos,
    "atan": np.arctan,
    "sinh": np.sinh,
    "cosh": np.cosh,
    "tanh": np.tanh,
    "exp": np.exp,
    "log": np.log,
    "ln": np.log,
    "log10": np.log10,
    "sqrt": np.sqrt,
    "abs": np.abs,
}
CONSTANTS = {"pi": math.pi, "e": math.e}
BINARY: dict[type[ast.operator], Callable[[Any, Any], Any]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.Pow: operator.pow,
}
UNARY: dict[type[ast.unaryop], Callable[[Any], Any]] = {ast.USub: operator.neg, ast.UAdd: operator.pos}

Compiled = Callable[[np.ndarray], np.ndarray]


def compile_expression(
    text: str, name: str = "k", variable: str = "s", derived: dict[str, Compiled] | None = None
) -> Compiled:
    """Turn ``text`` (e.g. ``"10 / s"``, ``"0.02 + 1e-5 * s"``) into a vectorised f(s).

    ``derived``: further names, each a function of the variable (e.g. the axis point's x,
    y, z at s for a radius law). Raises :class:`ExpressionError` naming ``name`` and the
    offending part.
    """
    derived = derived or {}
    if not isinstance(text, str):
        raise ExpressionError(f"{name} must be a string expression in {variable}, got {text!r}")
    if len(text) > MAX_LENGTH:
        raise ExpressionError(f"{name} is {len(text)} characters long; at most {MAX_LENGTH} are allowed")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        raise ExpressionError(f"{name} = {text!r} is not a valid expression: {exc.msg}") from None
    except (RecursionError, MemoryError, ValueError):
        raise ExpressionError(f"{name} = {text!r} is nested too deeply") from None
    nodes = sum(1 for _ in ast.walk(tree))
    if nodes > MAX_NODES:
        raise ExpressionError(f"{name} has {nodes} syntax nodes; at most {MAX_NODES} are allowed")
    _check_numbers(tree, text.strip(), name)
    try:
        return _compile(tree.body, name, variable, derived)
    except RecursionError:
        raise ExpressionError(f"{name} = {text!r} is nested too deeply") from None


def _compile(node: ast.AST, name: str, variable: str, derived: dict[str, Compiled]) -> Compiled:
    where = f"{name}: "
    if isinstance(node, ast.Constant):
        value = node.value
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ExpressionError(f"{where}only numbers are allowed as constants, got {value!r}")
        const = float(value)  # finite: checked by _check_numbers
        return lambda s: np.full(np.shape(s), const)
    if isinstance(node, ast.Name):
        if node.id == variable:
            return lambda s: np.asarray(s, dtype=float)
        if node.id in derived:
            return derived[node.id]
        if node.id in CONSTANTS:
            const = CONSTANTS[node.id]
            return lambda s: np.full(np.shape(s), const)
        allowed = ", ".join([variable, *derived, *CONSTANTS])
        raise ExpressionError(f"{where}unknown name {node.id!r}; the names allowed are {allowed}")
    if isinstance(node, ast.BinOp):
        if isinstance(node.op, ast.BitXor):
            raise ExpressionError(f"{where}'^' is not a power here; write a ** b")
        op = BINARY.get(type(node.op))
        if op is None:
            raise ExpressionError(f"{where}operator {type(node.op).__name__} is not allowed; use + - * / **")
        if op is operator.pow:
            _check_exponent(node.right, where)
        left, right = _compile(node.left, name, variable, derived), _compile(node.right, name, variable, derived)
        return lambda s: op(left(s), right(s))
    if isinstance(node, ast.UnaryOp):
        unary = UNARY.get(type(node.op))
        if unary is None:
            raise ExpressionError(f"{where}operator {type(node.op).__name__} is not allowed")
        operand = _compile(node.operand, name, variable, derived)
        return lambda s: unary(operand(s))
    if isinstance(node, ast.Call):
        if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
            shown = ast.unparse(node.func)
            raise ExpressionError(f"{where}function {shown!r} is not allowed; use one of {', '.join(FUNCTIONS)}")
        if node.keywords or len(node.args) != 1:
            raise ExpressionError(f"{where}{node.func.id}() takes exactly one argument")
        func, arg = FUNCTIONS[node.func.id], _compile(node.args[0], name, variable, derived)
        return lambda s: func(arg(s))
    if isinstance(node, ast.Attribute):
        raise ExpressionError(f"{where}attribute access ({ast.unparse(node)}) is not allowed")
    raise ExpressionError(f"{where}{type(node).__name__} ({ast.unparse(node)}) is not allowed in an expression")


def _check_numbers(tree: ast.AST, text: str, name: str) -> None:
    """Refuse numbers a double cannot hold (``1e999``, integers with hundreds of digits)."""
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(node.value, bool):
            try:
                finite = math.isfinite(float(node.value))
            except OverflowError:
                finite = False
            if not finite:
                shown = ast.get_source_segment(text, node) or "?"
                shown = shown if len(shown) <= 30 else f"{shown[:15]}... ({len(shown)} digits)"
                raise ExpressionError(
                    f"{name}: number {shown} is out of range; numbers must be finite and at most "
                    f"{sys.float_info.max:.4g} in magnitude"
                )


def _check_exponent(node: ast.AST, where: str) -> None:
    """Refuse literal exponents beyond +-64 (e.g. 9 ** 9 ** 9): they only overflow."""
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        node = node.operand
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
        if abs(float(node.value)) > MAX_LITERAL_EXPONENT:
            raise ExpressionError(f"{where}exponent {node.value!r} is out of range [-64, 64]")
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow):
        raise ExpressionError(f"{where}nested powers (a ** b ** c) are not allowed")
