"""Arithmetic expressions in ``u`` and ``v`` for design files: ``x = "cos(2 * pi * u)"``.

A design file's ``[surface]`` with ``shape = "parametric"`` gives ``x``, ``y`` and ``z`` as
strings. They are parsed (Python syntax) and walked node by node over numpy arrays: numbers,
the names ``u``, ``v``, ``pi``, ``tau``, ``e``, the operators ``+ - * / ** %`` and the
functions in :data:`FUNCTIONS`. Nothing else is accepted (no attributes, no other names, no
calls of anything else), so a design file cannot run code.

Examples
--------
>>> import numpy as np
>>> f = compile_expression("1 + u * sin(pi * v)")
>>> float(f(np.array(0.5), np.array(0.5)))
1.5
"""

from __future__ import annotations

import ast
import math
import operator
from collections.abc import Callable

import numpy as np

__all__ = ["FUNCTIONS", "compile_expression", "parametric_map"]

#: The functions an expression may call.
FUNCTIONS: dict[str, Callable] = {
    "sin": np.sin,
    "cos": np.cos,
    "tan": np.tan,
    "asin": np.arcsin,
    "acos": np.arccos,
    "atan": np.arctan,
    "atan2": np.arctan2,
    "sinh": np.sinh,
    "cosh": np.cosh,
    "tanh": np.tanh,
    "exp": np.exp,
    "log": np.log,
    "sqrt": np.sqrt,
    "abs": np.abs,
    "floor": np.floor,
    "ceil": np.ceil,
    "min": np.minimum,
    "max": np.maximum,
    "clip": np.clip,
}
_CONSTANTS = {"pi": math.pi, "tau": math.tau, "e": math.e}
_BINARY = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.Pow: operator.pow,
    ast.Mod: operator.mod,
}
_UNARY = {ast.USub: operator.neg, ast.UAdd: operator.pos}
_MAX_LENGTH = 2000


def _check(node: ast.AST, text: str) -> None:
    """Raise ``ValueError`` for any node outside the accepted language."""
    if isinstance(node, ast.Expression):
        return _check(node.body, text)
    if isinstance(node, ast.Constant):
        if isinstance(node.value, bool) or not isinstance(node.value, int | float):
            raise ValueError(f"{text!r}: only numbers are allowed as constants")
        try:
            big = not math.isfinite(float(node.value))
        except OverflowError:  # an integer past the largest double
            big = True
        if big:
            raise ValueError(f"{text!r}: the number {_short(node.value)} is not a finite double")
        return None
    if isinstance(node, ast.Name):
        if node.id not in ("u", "v") and node.id not in _CONSTANTS:
            raise ValueError(
                f"{text!r}: unknown name {node.id!r} (use u, v, pi, tau, e and "
                f"the functions {', '.join(sorted(FUNCTIONS))})"
            )
        return None
    if isinstance(node, ast.BinOp) and type(node.op) in _BINARY:
        _check(node.left, text)
        return _check(node.right, text)
    if isinstance(node, ast.UnaryOp) and type(node.op) in _UNARY:
        return _check(node.operand, text)
    if isinstance(node, ast.Call):
        if not isinstance(node.func, ast.Name) or node.func.id not in FUNCTIONS:
            name = node.func.id if isinstance(node.func, ast.Name) else ast.unparse(node.func)
            raise ValueError(f"{text!r}: unknown function {name!r}")
        if node.keywords or not node.args:
            raise ValueError(f"{text!r}: {node.func.id}(...) takes positional arguments")
        for a in node.args:
            _check(a, text)
        return None
    raise ValueError(f"{text!r}: {type(node).__name__} is not allowed in an expression")


def _short(value) -> str:
    text = repr(value)
    return text if len(text) <= 24 else f"{text[:10]}...({len(text)} digits)"


def _walk(node: ast.AST, env: dict):
    # numbers are numpy doubles: ``10 ** 400`` of two constants is inf (then refused as a
    # non-finite surface), not Python's OverflowError
    if isinstance(node, ast.Expression):
        return _walk(node.body, env)
    if isinstance(node, ast.Constant):
        return np.float64(node.value)
    if isinstance(node, ast.Name):
        return env[node.id] if node.id in env else np.float64(_CONSTANTS[node.id])
    if isinstance(node, ast.BinOp):
        return _BINARY[type(node.op)](_walk(node.left, env), _walk(node.right, env))
    if isinstance(node, ast.UnaryOp):
        return _UNARY[type(node.op)](_walk(node.operand, env))
    return FUNCTIONS[node.func.id](*(_walk(a, env) for a in node.args))


def compile_expression(text: str) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    """``text`` as a vectorised function of ``(u, v)``.

    Raises
    ------
    ValueError
        For a syntax error, an unknown name or function, or anything but arithmetic.
    """
    if not isinstance(text, str) or not text.strip():
        raise ValueError(f"an expression must be a non-empty string; got {text!r}")
    if len(text) > _MAX_LENGTH:
        raise ValueError(f"an expression may have at most {_MAX_LENGTH} characters")
    try:
        tree = ast.parse(text.strip(), mode="eval")
    except SyntaxError as exc:
        raise ValueError(f"{text!r} is not an expression: {exc.msg}") from None
    _check(tree, text)

    def f(u, v):
        u = np.asarray(u, dtype=np.float64)
        v = np.asarray(v, dtype=np.float64)
        with np.errstate(all="ignore"):
            out = _walk(tree, {"u": u, "v": v})
        return np.broadcast_to(np.asarray(out, dtype=np.float64), np.broadcast(u, v).shape)

    return f


def parametric_map(x: str, y: str, z: str) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    """``f(u, v) -> (..., 3)`` from three coordinate expressions (see the module)."""
    fx, fy, fz = (compile_expression(t) for t in (x, y, z))

    def f(u, v):
        return np.stack([fx(u, v), fy(u, v), fz(u, v)], axis=-1)

    return f
