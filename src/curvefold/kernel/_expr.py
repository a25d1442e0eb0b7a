"""Safe arithmetic expressions in one variable, compiled to vectorised NumPy functions.

Design files and the command line give curvature, torsion and ruling angles as text such as
``"1 + 0.3*sin(s)"``. The text is parsed with :mod:`ast` and checked against a whitelist;
the tree is then turned, once, into a tree of closures over NumPy ufuncs. Nothing is ever
handed to ``eval``, ``exec`` or ``compile``.

Allowed: number literals (integers are read as float64), the variable (``s`` by default), the
constants ``pi`` and ``e``, the operators ``+ - * / **`` (binary) and ``+ -`` (unary),
parentheses, and calls of the functions in :data:`FUNCTIONS` by plain name with positional
arguments. Everything else (attributes, subscripts, comparisons, strings, keywords, lambdas,
comprehensions, ...) is refused with an :class:`~curvefold.kernel.InputError` that names the
parameter and shows the offending piece of text.

Resource limits keep hostile text harmless: at most :data:`MAX_LENGTH` characters,
:data:`MAX_NODES` terms and a nesting depth of :data:`MAX_DEPTH` (a chain of binary
operations such as a sum of many terms counts as one level); sub-expressions free of the
variable are folded at compile time in float64, and a constant exponent larger than
:data:`MAX_EXPONENT` in magnitude is refused (``9**9**9`` fails at once). Evaluation runs
under ``np.errstate(all="ignore")``: an overflow or a square root of a negative number gives
inf or nan, which the caller detects (the curve builder names the arc length).
"""

from __future__ import annotations

import ast
import keyword
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TypeAlias

import numpy as np

from ._errors import InputError

__all__ = [
    "Expression",
    "compile_expression",
    "CONSTANTS",
    "FUNCTIONS",
    "MAX_LENGTH",
    "MAX_NODES",
    "MAX_DEPTH",
    "MAX_EXPONENT",
]

#: Longest expression text accepted, in characters.
MAX_LENGTH = 1000
#: Most expression nodes (numbers, names, operators, calls) in one expression.
MAX_NODES = 500
#: Deepest nesting of expression nodes.
MAX_DEPTH = 50
#: Largest magnitude of a constant exponent of ``**``.
MAX_EXPONENT = 100.0

#: Named constants.
CONSTANTS: dict[str, float] = {"pi": float(np.pi), "e": float(np.e)}


def _clip(x: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
    """``min(max(x, lo), hi)`` elementwise (``hi`` wins when ``lo > hi``)."""
    return np.minimum(np.maximum(x, lo), hi)


#: Callable functions: name -> (NumPy function, number of arguments).
FUNCTIONS: dict[str, tuple[Callable[..., np.ndarray], int]] = {
    "sin": (np.sin, 1),
    "cos": (np.cos, 1),
    "tan": (np.tan, 1),
    "arcsin": (np.arcsin, 1),
    "arccos": (np.arccos, 1),
    "arctan": (np.arctan, 1),
    "arctan2": (np.arctan2, 2),
    "asin": (np.arcsin, 1),
    "acos": (np.arccos, 1),
    "atan": (np.arctan, 1),
    "atan2": (np.arctan2, 2),
    "sinh": (np.sinh, 1),
    "cosh": (np.cosh, 1),
    "tanh": (np.tanh, 1),
    "exp": (np.exp, 1),
    "log": (np.log, 1),
    "log10": (np.log10, 1),
    "sqrt": (np.sqrt, 1),
    "abs": (np.abs, 1),
    "min": (np.minimum, 2),
    "max": (np.maximum, 2),
    "clip": (_clip, 3),
}

_BINARY: dict[type, Callable[..., np.ndarray]] = {  # on arrays or float64 constants
    ast.Add: np.add,
    ast.Sub: np.subtract,
    ast.Mult: np.multiply,
    ast.Div: np.true_divide,
    ast.Pow: np.power,
}
_UNARY: dict[type, Callable[[np.ndarray], np.ndarray]] = {
    ast.UAdd: np.positive,
    ast.USub: np.negative,
}

#: A compiled piece of an expression: a function of the variable's values, which may return
#: a scalar, or a constant folded at compile time.
_Values: TypeAlias = Callable[[np.ndarray], "np.ndarray | np.float64"]
_Node: TypeAlias = "np.float64 | _Values"

# Spelling of refused operators, for messages.
_OPERATOR_TEXT: dict[type, str] = {
    ast.FloorDiv: "//",
    ast.Mod: "%",
    ast.MatMult: "@",
    ast.LShift: "<<",
    ast.RShift: ">>",
    ast.BitOr: "|",
    ast.BitXor: "^",
    ast.BitAnd: "&",
    ast.Invert: "~",
    ast.Not: "not",
}

# What a refused node is, phrased for "<phrase> not allowed in expressions".
_REFUSED: dict[type, str] = {
    ast.Attribute: "attribute access is",
    ast.Subscript: "subscripts are",
    ast.Slice: "slices are",
    ast.Lambda: "lambda functions are",
    ast.ListComp: "comprehensions are",
    ast.SetComp: "comprehensions are",
    ast.DictComp: "comprehensions are",
    ast.GeneratorExp: "comprehensions are",
    ast.Starred: "starred arguments are",
    ast.JoinedStr: "f-strings are",
    ast.FormattedValue: "f-strings are",
    ast.NamedExpr: "assignment expressions (:=) are",
    ast.Compare: "comparisons are",
    ast.BoolOp: "boolean operators (and, or) are",
    ast.IfExp: "conditional expressions (if/else) are",
    ast.List: "lists are",
    ast.Tuple: "tuples are",
    ast.Set: "sets are",
    ast.Dict: "dictionaries are",
    ast.Await: "'await' is",
    ast.Yield: "'yield' is",
    ast.YieldFrom: "'yield' is",
}

_EXCERPT = 60


def _excerpt(text: str, limit: int = _EXCERPT) -> str:
    return text if len(text) <= limit else text[: limit - 3] + "..."


@dataclass(frozen=True)
class Expression:
    """A compiled expression: call it with an array of the variable.

    Build it with :func:`compile_expression`; two expressions are equal when their text and
    variable are.

    Parameters
    ----------
    text : str
        The source text, as given.
    variable : str
        Name of the variable.
    constant : float or None
        The value when the expression does not depend on the variable.
    function : callable
        The compiled tree; it may return a scalar, which ``__call__`` broadcasts.

    Examples
    --------
    >>> f = compile_expression("1 + 0.5*s", name="kappa")
    >>> f(np.array([0.0, 2.0])).tolist(), f.constant
    ([1.0, 2.0], None)
    >>> compile_expression("2*pi", name="kappa")(np.zeros(2)).round(
    ...     6
    ... ).tolist()  # free of s: broadcast
    [6.283185, 6.283185]
    """

    text: str
    variable: str
    constant: float | None = field(compare=False)
    function: _Values = field(repr=False, compare=False)

    def __call__(self, s: np.ndarray) -> np.ndarray:
        """Evaluate at ``s`` (any shape); returns a new float64 array of the same shape."""
        x = np.asarray(s, dtype=float)
        with np.errstate(all="ignore"):
            out = self.function(x)
        return np.array(np.broadcast_to(out, x.shape), dtype=float)

    def __reduce__(self) -> tuple[Callable[[str, str], Expression], tuple[str, str]]:
        # Closures do not pickle; recompiling the text does.
        return (_recompile, (self.text, self.variable))

    def __str__(self) -> str:
        return self.text


def _recompile(text: str, variable: str) -> Expression:
    return compile_expression(text, variable=variable)


def compile_expression(text: str, *, variable: str = "s", name: str = "expression") -> Expression:
    """Compile a safe arithmetic expression in one variable to a vectorised function.

    Parameters
    ----------
    text : str
        The expression, e.g. ``"1 + 0.3*sin(2*pi*s/6)"``; at most :data:`MAX_LENGTH`
        characters.
    variable : str, optional
        Name of the variable (default ``"s"``, arc length).
    name : str, optional
        Parameter name used in error messages, e.g. ``"[curve] kappa"``.

    Returns
    -------
    Expression
        Callable: ``f(s)`` takes an array of any shape and returns a float64 array of the
        same shape (a constant expression broadcasts). Non-finite results are returned
        as they are, without a warning.

    Raises
    ------
    InputError
        The text is not a valid expression, uses anything outside the whitelist or exceeds
        a resource limit. The message names ``name`` and shows the offending piece.

    Examples
    --------
    >>> f = compile_expression("1 + 0.3*sin(s)", name="kappa")
    >>> f(np.array([0.0, np.pi / 2]))
    array([1. , 1.3])
    >>> compile_expression("2*pi")(np.zeros((2, 2))).shape
    (2, 2)
    >>> compile_expression("s.__class__", name="kappa")
    Traceback (most recent call last):
    ...
    curvefold.kernel._errors.InputError: kappa: attribute access is not allowed in expressions
    ('s.__class__')
    """
    if not isinstance(text, str):
        raise InputError(
            f"{name}: expected an expression string, got {type(text).__name__} "
            f"{_excerpt(repr(text))}"
        )
    _check_variable(variable, name)
    if len(text) > MAX_LENGTH:
        raise InputError(
            f"{name}: expression is {len(text)} characters long, the limit is {MAX_LENGTH}"
        )
    tree, body_text = _parse(text, name)
    _check_size(tree, body_text, name)
    compiler = _Compiler(body_text, variable, name)
    with np.errstate(all="ignore"):
        node = compiler.build(tree.body)
    if callable(node):
        return Expression(text, variable, None, node)
    value = np.float64(node)
    return Expression(text, variable, float(value), _constant(value))


def _check_variable(variable: str, name: str) -> None:
    if (
        not isinstance(variable, str)
        or not variable.isidentifier()
        or keyword.iskeyword(variable)
        or variable in CONSTANTS
        or variable in FUNCTIONS
    ):
        raise InputError(
            f"{name}: variable must be an identifier other than a keyword, constant or function "
            f"name, got {variable!r}"
        )


def _position(text: str, index: int) -> str:
    """'column c' or 'line l, column c' (1-based) of a character index into ``text``."""
    line = text.count("\n", 0, index) + 1
    column = index - (text.rfind("\n", 0, index) + 1) + 1
    return f"column {column}" if "\n" not in text else f"line {line}, column {column}"


def _parse(text: str, name: str) -> tuple[ast.Expression, str]:
    """Parse ``text`` in eval mode; return the tree and the text its positions refer to."""
    for i, ch in enumerate(text):
        if (ord(ch) < 32 and ch not in "\t\n\r") or ord(ch) == 127 or 0xD800 <= ord(ch) <= 0xDFFF:
            raise InputError(
                f"{name}: invalid character U+{ord(ch):04X} at {_position(text, i)} "
                f"in {_excerpt(text)!r}"
            )
    body = text.lstrip()
    lead = len(text) - len(body)
    if not body:
        raise InputError(f"{name}: empty expression")
    try:
        return ast.parse(body, mode="eval"), body
    except SyntaxError as exc:
        if exc.lineno is None or exc.offset is None or exc.offset < 1:
            where = "the end of the expression"  # the parser's way of saying it ran out of text
        else:
            lines = body.split("\n")
            line = min(max(exc.lineno, 1), len(lines))
            index = lead + sum(len(x) + 1 for x in lines[: line - 1]) + exc.offset - 1
            where = _position(text, min(index, len(text)))
        raise InputError(
            f"{name}: invalid expression: {exc.msg} at {where} in {_excerpt(text)!r}"
        ) from None
    except (RecursionError, MemoryError):
        raise InputError(
            f"{name}: expression is nested too deeply (limit {MAX_DEPTH}) in {_excerpt(text)!r}"
        ) from None
    except ValueError as exc:
        raise InputError(f"{name}: invalid expression: {exc} in {_excerpt(text)!r}") from None


def _check_size(tree: ast.Expression, text: str, name: str) -> None:
    """Count expression nodes and measure their nesting without recursion."""
    count = 0
    stack: list[tuple[ast.AST, int]] = [(tree.body, 1)]
    while stack:
        node, depth = stack.pop()
        if isinstance(node, ast.expr):
            count += 1
            if count > MAX_NODES:
                raise InputError(
                    f"{name}: expression has more than {MAX_NODES} terms in {_excerpt(text)!r}"
                )
            if depth > MAX_DEPTH:
                raise InputError(
                    f"{name}: expression is nested too deeply (more than {MAX_DEPTH} levels) in "
                    f"{_excerpt(text)!r}"
                )
        step = 1 if isinstance(node, ast.expr) else 0
        for child in ast.iter_child_nodes(node):
            chained = (
                isinstance(node, ast.BinOp) and child is node.left and isinstance(child, ast.BinOp)
            )
            # a chain a + b - c … is one level
            stack.append((child, depth if chained else depth + step))


@dataclass(frozen=True)
class _Compiler:
    """Turns a checked tree into constants and closures; refuses anything not whitelisted."""

    text: str
    variable: str
    name: str

    def piece(self, node: ast.AST) -> str:
        segment = ast.get_source_segment(self.text, node)
        return _excerpt(segment if segment is not None else self.text)

    def refuse(self, node: ast.AST, message: str) -> InputError:
        return InputError(f"{self.name}: {message} ({self.piece(node)!r})")

    def build(self, node: ast.AST) -> _Node:
        """A float64 constant (folded now) or a function of the variable."""
        if isinstance(node, ast.Constant):
            return self.literal(node)
        if isinstance(node, ast.Name):
            return self.name_value(node)
        if isinstance(node, ast.UnaryOp):
            op = _UNARY.get(type(node.op))
            if op is None:
                symbol = _OPERATOR_TEXT[type(node.op)]
                raise self.refuse(node, f"operator '{symbol}' is not allowed (allowed: + - * / **)")
            return _apply(op, [self.build(node.operand)])
        if isinstance(node, ast.BinOp):
            return self.binary(node)
        if isinstance(node, ast.Call):
            return self.call(node)
        phrase = _REFUSED.get(type(node), f"{type(node).__name__} expressions are")
        raise self.refuse(node, f"{phrase} not allowed in expressions")

    def literal(self, node: ast.Constant) -> np.float64:
        value = node.value
        if isinstance(value, bool) or value is None or value is Ellipsis:
            raise self.refuse(node, f"{value!r} is not allowed in expressions (only numbers)")
        if isinstance(value, (str, bytes)):
            raise self.refuse(node, "strings are not allowed in expressions")
        if isinstance(value, complex):
            raise self.refuse(node, "complex numbers are not allowed in expressions")
        try:
            number = float(value)
        except OverflowError:
            raise self.refuse(node, "number is too large for float64") from None
        if not np.isfinite(number):
            raise self.refuse(node, "number is too large for float64")
        return np.float64(number)

    def name_value(self, node: ast.Name) -> _Node:
        if node.id == self.variable:
            return _identity
        if node.id in CONSTANTS:
            return np.float64(CONSTANTS[node.id])
        if node.id in FUNCTIONS:
            raise self.refuse(
                node, f"function '{node.id}' must be called, e.g. {node.id}({self.variable})"
            )
        allowed = ", ".join([self.variable, *CONSTANTS])
        hint = (
            "; 'tau' is not a constant here (τ means torsion), write 2*pi"
            if node.id == "tau"
            else ""
        )
        raise InputError(f"{self.name}: unknown name {node.id!r} (allowed: {allowed}){hint}")

    def binary(self, node: ast.BinOp) -> _Node:
        """A chain of binary operations along their left operands (``a + b - c * d …``, a
        sum of many terms) is built in one loop and evaluated in one: it nests no deeper
        than a single operation, when compiled or evaluated."""
        spine = []
        left: ast.expr = node
        while isinstance(left, ast.BinOp):
            spine.append(left)
            left = left.left
        value = self.build(left)
        steps: list[tuple[Callable[..., np.ndarray], _Node]] = []
        for step in reversed(spine):
            op = _BINARY.get(type(step.op))
            if op is None:
                symbol = _OPERATOR_TEXT[type(step.op)]
                hint = "; use ** for powers" if symbol == "^" else ""
                raise self.refuse(
                    step, f"operator '{symbol}' is not allowed (allowed: + - * / **){hint}"
                )
            right = self.build(step.right)
            if (
                isinstance(step.op, ast.Pow)
                and not callable(right)
                and not abs(right) <= MAX_EXPONENT
            ):
                limit = f"|exponent| ≤ {MAX_EXPONENT:g}"
                raise self.refuse(
                    step, f"constant exponent {float(right):g} is out of range ({limit})"
                )
            if steps or callable(value) or callable(right):
                steps.append((op, right))
            else:
                value = np.float64(op(value, right))  # a constant start of the chain is folded now
        return _chain(value, steps) if steps else value

    def call(self, node: ast.Call) -> _Node:
        func = node.func
        if not isinstance(func, ast.Name):
            raise self.refuse(node, "only plain function names can be called")
        if func.id not in FUNCTIONS:
            if func.id == self.variable or func.id in CONSTANTS:
                raise self.refuse(node, f"'{func.id}' is not a function")
            raise self.refuse(
                node, f"function '{func.id}' is not allowed (allowed: {', '.join(FUNCTIONS)})"
            )
        if node.keywords:
            raise self.refuse(node, "keyword arguments are not allowed in expressions")
        for arg in node.args:
            if isinstance(arg, ast.Starred):
                raise self.refuse(arg, "starred arguments are not allowed in expressions")
        fn, arity = FUNCTIONS[func.id]
        if len(node.args) != arity:
            plural = "" if arity == 1 else "s"
            raise self.refuse(
                node, f"function '{func.id}' takes {arity} argument{plural}, got {len(node.args)}"
            )
        return _apply(fn, [self.build(arg) for arg in node.args])


def _identity(s: np.ndarray) -> np.ndarray:
    return s


def _constant(value: np.float64) -> _Values:
    """The function of a constant: ``value`` whatever the variable."""
    return lambda s: value


def _chain(first: _Node, steps: list[tuple[Callable[..., np.ndarray], _Node]]) -> _Values:
    """``(((first op₁ part₁) op₂ part₂) …)``, left to right in one loop; constants or functions."""

    def evaluate(s: np.ndarray) -> np.ndarray | np.float64:
        value = first(s) if callable(first) else first
        for op, part in steps:
            value = op(value, part(s) if callable(part) else part)
        return value

    return evaluate


def _apply(fn: Callable[..., np.ndarray], args: list[_Node]) -> _Node:
    """Fold constant arguments now; otherwise return a closure over the argument functions."""
    if not any(callable(a) for a in args):
        return np.float64(fn(*args))
    parts = [a if callable(a) else _constant(a) for a in args]
    if len(parts) == 1:
        (f,) = parts
        return lambda s: fn(f(s))
    if len(parts) == 2:
        f, g = parts
        return lambda s: fn(f(s), g(s))
    return lambda s: fn(*(p(s) for p in parts))
