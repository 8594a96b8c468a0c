"""Arithmetic expressions of a layout file's parameters, evaluated safely (no ``eval``).

A numeric value in a layout file is a number, a parameter's name (``"l1"``) or an
expression of parameters (``"l + l1"``, ``"-b4"``, ``"W * g / 2"``). An expression is parsed
once with :mod:`ast` and only numbers, names, ``+ - * / **``, unary ``+``/``-``,
parentheses and the functions ``sqrt``, ``abs``, ``min``, ``max`` and the constant ``pi``
are accepted; anything else (attributes, calls of other functions, subscripts, strings) is
refused when the file is read. :class:`Expression` keeps the parsed tree and evaluates it
against a mapping of parameter values.

:func:`difference` subtracts two expressions term by term (``"r0 + h4"`` minus ``"r0"`` is
``h4``, exactly, not the rounded ``(r0 + h4) - r0``): attachment arms and distances between
bodies are computed that way, so that the numbers of a layout equal the numbers written in
terms of the paper's own distances.
"""

from __future__ import annotations

import ast
import math
import operator
from collections.abc import Callable, Mapping
from functools import lru_cache

__all__ = ["Expression", "ExpressionError", "difference", "evaluate_parameters"]

_BINARY: dict[type, Callable[[float, float], float]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.Pow: operator.pow,
}
_FUNCTIONS: dict[str, Callable[..., float]] = {
    "sqrt": math.sqrt, "abs": abs, "min": min, "max": max,
}  # fmt: skip
_CONSTANTS = {"pi": math.pi}


class ExpressionError(ValueError):
    """An expression that cannot be parsed or evaluated (names the expression and why)."""


class Expression:
    """A number, a parameter name or an arithmetic expression of parameters.

    Parameters
    ----------
    source : str or float
        The value as written in the file.

    Raises
    ------
    ExpressionError
        The text is not an expression of the accepted form.
    """

    __slots__ = ("_fn", "names", "source", "terms")

    def __init__(self, source: str | float) -> None:
        if isinstance(source, bool) or not isinstance(source, (str, int, float)):
            raise ExpressionError(f"{source!r} is not a number or an expression")
        self.source: str | float = source if isinstance(source, str) else float(source)
        tree = _parse(source) if isinstance(source, str) else ast.Constant(float(source))
        functions = {id(n.func) for n in ast.walk(tree) if isinstance(n, ast.Call)}
        self.names: frozenset[str] = frozenset(
            n.id for n in ast.walk(tree) if isinstance(n, ast.Name)
            and n.id not in _CONSTANTS and id(n) not in functions
        )  # the parameters it names: not the functions it calls (sqrt, abs, min, max)
        self._fn = _compile(tree)
        self.terms = _terms(tree)

    def __call__(self, values: Mapping[str, float]) -> float:
        """The value for the given parameter values (SI)."""
        try:
            return float(self._fn(values))
        except KeyError as exc:
            raise ExpressionError(
                f"{self.source!r}: unknown parameter {exc.args[0]!r}"
            ) from None
        except (ZeroDivisionError, OverflowError, ValueError, TypeError) as exc:
            raise ExpressionError(f"{self.source!r} cannot be evaluated: {exc}") from None

    @property
    def is_constant(self) -> bool:
        """True when the expression names no parameter."""
        return not self.names

    def __repr__(self) -> str:
        return f"Expression({self.source!r})"

    def __reduce__(self) -> tuple:
        return (Expression, (self.source,))

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Expression) and self.source == other.source

    def __hash__(self) -> int:
        return hash(self.source)


@lru_cache(maxsize=4096)
def _parse(text: str) -> ast.expr:
    try:
        tree = ast.parse(text.strip(), mode="eval").body
    except SyntaxError as exc:
        raise ExpressionError(f"{text!r} is not an arithmetic expression: {exc.msg}") from None
    _check(tree, text)
    return tree


def _check(node: ast.AST, text: str) -> None:
    if isinstance(node, ast.Constant):
        if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
            raise ExpressionError(f"{text!r}: {node.value!r} is not a number")
    elif isinstance(node, ast.Name):
        if not node.id.isidentifier():
            raise ExpressionError(f"{text!r}: {node.id!r} is not a parameter name")
    elif isinstance(node, ast.BinOp):
        if type(node.op) not in _BINARY:
            raise ExpressionError(f"{text!r}: only + - * / ** are allowed")
        _check(node.left, text)
        _check(node.right, text)
    elif isinstance(node, ast.UnaryOp):
        if not isinstance(node.op, (ast.UAdd, ast.USub)):
            raise ExpressionError(f"{text!r}: only unary + and - are allowed")
        _check(node.operand, text)
    elif isinstance(node, ast.Call):
        if (not isinstance(node.func, ast.Name) or node.func.id not in _FUNCTIONS
                or node.keywords or not node.args):  # fmt: skip
            raise ExpressionError(
                f"{text!r}: the only functions are {', '.join(sorted(_FUNCTIONS))}"
            )
        for arg in node.args:
            _check(arg, text)
    else:
        raise ExpressionError(
            f"{text!r}: only numbers, parameter names, + - * / **, parentheses and "
            f"{', '.join(sorted(_FUNCTIONS))}, pi are allowed"
        )


def _compile(node: ast.AST) -> Callable[[Mapping[str, float]], float]:
    """A closure computing the node (parsed once; a model build evaluates many)."""
    if isinstance(node, ast.Constant):
        value = float(node.value)
        return lambda p: value
    if isinstance(node, ast.Name):
        name = node.id
        if name in _CONSTANTS:
            const = _CONSTANTS[name]
            return lambda p: const
        return lambda p: p[name]
    if isinstance(node, ast.UnaryOp):
        inner = _compile(node.operand)
        if isinstance(node.op, ast.USub):
            return lambda p: -inner(p)
        return inner
    if isinstance(node, ast.BinOp):
        op = _BINARY[type(node.op)]
        left, right = _compile(node.left), _compile(node.right)
        return lambda p: op(left(p), right(p))
    assert isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
    fn = _FUNCTIONS[node.func.id]
    args = [_compile(a) for a in node.args]
    return lambda p: fn(*(a(p) for a in args))


def _terms(node: ast.AST) -> tuple[tuple[float, str, ast.AST], ...]:
    """The expression as a signed sum of terms ``(sign, key, node)`` (top-level + and -)."""
    if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub)):
        right = _terms(node.right)
        if isinstance(node.op, ast.Sub):
            right = tuple((-s, k, n) for s, k, n in right)
        return _terms(node.left) + right
    if isinstance(node, ast.UnaryOp):
        inner = _terms(node.operand)
        if isinstance(node.op, ast.USub):
            return tuple((-s, k, n) for s, k, n in inner)
        return inner
    if isinstance(node, ast.Constant) and float(node.value) == 0.0:
        return ()
    return ((1.0, ast.dump(node), node),)


def difference(a: Expression, b: Expression, values: Mapping[str, float]) -> float:
    """``a - b`` with the terms the two sums share cancelled before any rounding.

    ``"l + l1"`` minus ``"l"`` is ``l1`` exactly; ``"r0 + h4 + h3"`` minus
    ``"r0 + h4 + h3 + h1"`` is ``-h1``. The remaining terms are added left to right
    (those of ``a``, then minus those of ``b``); with nothing left the result is 0.
    """
    plan = _difference_plan(a, b)
    if not plan:
        return 0.0
    try:
        sign, fn = plan[0]
        total = fn(values) if sign > 0 else -fn(values)
        for sign, fn in plan[1:]:
            total = total + fn(values) if sign > 0 else total - fn(values)
    except KeyError as exc:
        raise ExpressionError(f"unknown parameter {exc.args[0]!r}") from None
    return float(total)


@lru_cache(maxsize=8192)
def _difference_plan(a: Expression, b: Expression) -> tuple[tuple[float, Callable], ...]:
    """The terms left of ``a - b`` after cancelling, each with its compiled closure."""
    left = list(a.terms)
    right = list(b.terms)
    for term in list(right):
        for k, other in enumerate(left):
            if other[0] == term[0] and other[1] == term[1]:
                del left[k]
                right.remove(term)
                break
    rest = left + [(-s, key, node) for s, key, node in right]
    return tuple((sign, _compile(node)) for sign, _, node in rest)


def evaluate_parameters(entries: Mapping[str, Expression]) -> dict[str, float]:
    """Values of parameters that may be given as expressions of one another.

    Parameters
    ----------
    entries : Mapping[str, Expression]
        Each parameter's value as written.

    Returns
    -------
    dict[str, float]
        The values, in the order of ``entries``.

    Raises
    ------
    ExpressionError
        An expression names an unknown parameter, or the expressions form a cycle (the
        message lists the cycle, e.g. ``a -> b -> a``).
    """
    done: dict[str, float] = {}
    visiting: list[str] = []

    def visit(name: str) -> float:
        if name in done:
            return done[name]
        if name in visiting:
            cycle = " -> ".join([*visiting[visiting.index(name):], name])
            raise ExpressionError(f"parameters refer to each other in a cycle: {cycle}")
        expr = entries[name]
        visiting.append(name)
        for dep in sorted(expr.names):
            if dep not in entries:
                raise ExpressionError(
                    f"parameter {name!r} = {expr.source!r}: unknown parameter {dep!r}"
                )
            visit(dep)
        visiting.pop()
        done[name] = expr(done)
        return done[name]

    for name in entries:
        visit(name)
    return {name: done[name] for name in entries}
