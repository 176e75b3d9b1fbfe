"""The expressions of xacro files (``${...}``, ``$(eval ...)``), evaluated safely.

xacro evaluates ``${...}`` with Python's ``eval`` behind a thin guard, which a
file can get around (``python.vars(python.type(f))['__globals__']`` reaches
``os.system``). This module evaluates the part of Python that robot
descriptions write: parsed by Python's :func:`ast.parse` (which runs nothing),
checked against a whitelist (:mod:`kinematica.io.xacro_parse`) and evaluated by a
walker of its own (no ``eval``, no ``compile``, no attribute of any Python object
is ever looked up):

- numbers, strings in quotes, ``True``/``False``/``None``, lists ``[a, b]`` and
  tuples ``(a, b)``, indexing ``x[i]``;
- ``+ - * / // % **``, comparisons (chained), ``and``/``or``/``not``, ``in``,
  and the conditional ``a if c else b``;
- names: the file's properties (looked up by the caller), ``pi``, ``e``,
  ``tau``, ``inf``, ``nan``;
- calls of the functions of :data:`FUNCTIONS` (``sin``, ``radians``, ``min``,
  ``int``, ``str``, ...; ``math.sin`` too) and those the caller adds
  (``load_yaml``);
- ``.key`` only on what ``load_yaml`` returned (a mapping read from YAML), and
  the string methods ``split``, ``strip``, ``lower``, ``upper``, ``replace``,
  ``startswith``, ``endswith``, ``join`` (and ``rsplit``, ``lstrip``, ``rstrip``).

Anything else (other attributes, ``__`` names, lambdas, comprehensions,
unknown names or functions, string formatting with ``%``) raises
:class:`XacroExpressionError` naming the expression and the column. Numbers,
strings and lists are bounded (:data:`MAX_INT_BITS`, :data:`MAX_TEXT`), so an
expression cannot ask for unbounded memory or time.
"""

from __future__ import annotations

import ast
import functools
import math
import operator
from collections.abc import Callable, Mapping
from typing import Any, Final

from kinematica.errors import KinematicaError
from kinematica.io.xacro_parse import MAX_DEPTH, Expression, XacroExpressionError, parse

__all__ = [
    "FUNCTIONS",
    "MAX_DEPTH",
    "MAX_INT_BITS",
    "MAX_LENGTH",
    "MAX_TEXT",
    "Namespace",
    "XacroExpressionError",
    "YamlDict",
    "YamlList",
    "evaluate",
    "flat_size",
    "text_of",
]

#: Longest expression, in characters (real ones are a few dozen).
MAX_LENGTH: Final = 4000
#: Largest integer, in bits, an expression may make (``2**1024`` and beyond are refused:
#: ``9**9**9**9`` would otherwise compute for ever).
MAX_INT_BITS: Final = 1024
#: Longest string or list an expression may make, in characters or items.
MAX_TEXT: Final = 1_000_000


class YamlDict(dict[Any, Any]):
    """A mapping read by ``load_yaml``: its keys are reachable as ``.key`` too."""


class YamlList(list[Any]):
    """A list read by ``load_yaml``."""


def flat_size(value: Any, limit: int = MAX_TEXT) -> int:
    """Items and characters of ``value`` with nested lists counted as often as they appear.

    Stops counting past ``limit`` (a list of a list of a list ... shared a thousand times at
    each level is small in memory and huge as text).
    """
    total = 0
    todo = [value]
    while todo and total <= limit:
        item = todo.pop()
        if isinstance(item, str):
            total += len(item)
        elif isinstance(item, dict):
            total += len(item)
            todo.extend(item.keys())
            todo.extend(item.values())
        elif isinstance(item, list | tuple):
            total += len(item)
            todo.extend(item)
        else:
            total += 1
    return total


def text_of(value: Any) -> str:
    """``str(value)``, refused when the text would be longer than :data:`MAX_TEXT`."""
    if isinstance(value, list | tuple | dict) and flat_size(value) > MAX_TEXT:
        raise ValueError(f"a value longer than {MAX_TEXT:,} as text: refused")
    return str(value)


def _check_size(value: Any) -> Any:
    if isinstance(value, bool):
        return value
    if isinstance(value, complex):
        raise ValueError("a complex number (a root of a negative number?)")
    if isinstance(value, int) and value.bit_length() > MAX_INT_BITS:
        raise ValueError(f"an integer of more than {MAX_INT_BITS} bits: refused")
    if isinstance(value, str | list | tuple) and flat_size(value) > MAX_TEXT:
        raise ValueError(f"a string or list longer than {MAX_TEXT:,}: refused")
    return value


def _sum(*args: Any) -> Any:
    if len(args) != 1 or not all(isinstance(v, int | float) for v in args[0]):
        raise ValueError("sum() takes one list of numbers here")
    return sum(args[0])


def _power(a: Any, b: Any) -> Any:
    whole = isinstance(a, int) and isinstance(b, int) and not isinstance(b, bool)
    if whole and b > 0 and abs(a) > 1 and b * max(a.bit_length() - 1, 1) > MAX_INT_BITS:
        raise ValueError(f"{a}**{b} is larger than 2**{MAX_INT_BITS}: refused")
    return a**b


def _times(a: Any, b: Any) -> Any:
    for seq, n in ((a, b), (b, a)):
        sequence = isinstance(seq, str | list | tuple) and isinstance(n, int)
        if sequence and len(seq) * max(n, 0) > MAX_TEXT:
            raise ValueError(f"a string or list longer than {MAX_TEXT:,}: refused")
    return a * b


def _modulo(a: Any, b: Any) -> Any:
    if isinstance(a, str):
        raise ValueError("string formatting with % is not supported")
    return a % b


_BINARY: Final[dict[type[ast.AST], Callable[[Any, Any], Any]]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: _times,
    ast.Div: operator.truediv,
    ast.FloorDiv: operator.floordiv,
    ast.Mod: _modulo,
    ast.Pow: _power,
}

_COMPARE: Final[dict[type[ast.AST], Callable[[Any, Any], bool]]] = {
    ast.Lt: operator.lt,
    ast.LtE: operator.le,
    ast.Gt: operator.gt,
    ast.GtE: operator.ge,
    ast.Eq: operator.eq,
    ast.NotEq: operator.ne,
    ast.In: lambda a, b: a in b,
    ast.NotIn: lambda a, b: a not in b,
}


def _replace(text: str, old: Any, new: Any, *count: Any) -> str:
    if not isinstance(old, str) or not isinstance(new, str):
        raise ValueError("replace() takes strings here")
    growth = max(len(new) - len(old), 0) * (text.count(old) if old else len(text) + 1)
    if len(text) + growth > MAX_TEXT:
        raise ValueError(f"a string longer than {MAX_TEXT:,}: refused")
    return text.replace(old, new, *count)


def _join(separator: str, items: Any) -> str:
    if not isinstance(items, list | tuple) or not all(isinstance(i, str) for i in items):
        raise ValueError("join() takes a list of strings here")
    if sum(map(len, items)) + len(separator) * len(items) > MAX_TEXT:
        raise ValueError(f"a string longer than {MAX_TEXT:,}: refused")
    return separator.join(items)


#: The methods of strings an expression may call (``xyz.split(' ')[0]``): these and no
#: other attribute of any object, each a function of ours or of ``str`` itself.
_STRING_METHODS: Final[Mapping[str, Callable[..., Any]]] = {
    **{m: getattr(str, m) for m in ["split", "rsplit", "strip", "lstrip", "rstrip", "lower"]},
    **{m: getattr(str, m) for m in ["upper", "startswith", "endswith"]},
    "replace": _replace,
    "join": _join,
}


def _dict(*args: Any, **keywords: Any) -> dict[Any, Any]:
    if len(args) > 1 or (args and not isinstance(args[0], dict)):
        raise ValueError("dict() takes a mapping or keyword arguments here")
    return {**(args[0] if args else {}), **keywords}


def _number(kind: Callable[[Any], Any]) -> Callable[..., Any]:
    def convert(*args: Any) -> Any:
        if len(args) > 1:
            raise ValueError(f"{kind.__name__}() takes one argument here")
        return kind(*args)

    return convert


def _sequence(kind: type) -> Callable[..., Any]:
    def convert(*args: Any) -> Any:
        if len(args) > 1 or (args and not isinstance(args[0], str | list | tuple | dict)):
            raise ValueError(f"{kind.__name__}() takes a string, list or tuple here")
        return kind(*args)

    return convert


_MATH: Final = frozenset(
    {"sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sinh", "cosh", "tanh", "asinh"}
    | {"acosh", "atanh", "sqrt", "exp", "log", "log10", "log2", "pow", "fabs", "floor", "ceil"}
    | {"trunc", "radians", "degrees", "hypot", "copysign", "fmod", "isclose", "isfinite"}
    | {"isinf", "isnan"}
)

#: Functions an expression may call, by name (``math.NAME`` reaches the math ones too).
FUNCTIONS: Final[Mapping[str, Callable[..., Any]]] = {
    **{name: getattr(math, name) for name in _MATH},
    "abs": abs,
    "min": min,
    "max": max,
    "round": round,
    "sum": _sum,
    "len": len,
    "int": _number(int),
    "float": _number(float),
    "bool": _number(bool),
    "str": _number(text_of),
    "list": _sequence(list),
    "dict": _dict,
    "tuple": _sequence(tuple),
}

#: Names an expression may use as values, besides the file's properties.
CONSTANTS: Final[Mapping[str, Any]] = {
    "pi": math.pi,
    "e": math.e,
    "tau": math.tau,
    "inf": math.inf,
    "nan": math.nan,
}


class Namespace:
    """``math`` and ``xacro`` in ``math.sin(x)``, ``xacro.load_yaml(f)``."""

    def __init__(self, name: str, members: Mapping[str, Any]) -> None:
        self.name = name
        self.members = members


class _Evaluator:
    def __init__(
        self,
        tree: Expression,
        lookup: Callable[[str], Any],
        functions: Mapping[str, Callable[..., Any]],
    ) -> None:
        self.fail = tree.fail
        self.lookup = lookup
        self.functions = functions

    def name(self, node: ast.Name) -> Any:
        name = node.id
        try:
            return self.lookup(name)
        except KeyError:
            pass
        if name in CONSTANTS:
            return CONSTANTS[name]
        if name in self.functions:
            return self.functions[name]
        if name == "math":
            return Namespace("math", {**{n: FUNCTIONS[n] for n in _MATH}, **CONSTANTS})
        if name == "xacro":
            members = {k[6:]: v for k, v in self.functions.items() if k.startswith("xacro.")}
            return Namespace("xacro", members)
        if name == "python":
            raise self.fail("the 'python' namespace is refused", node)
        raise self.fail(f"unknown name {name!r}", node)

    def owner(self, node: ast.expr) -> Any:
        """What ``.name`` is taken of: a name may be a namespace, anything else a value."""
        return self.name(node) if isinstance(node, ast.Name) else self.value(node)

    def value(self, node: ast.expr) -> Any:
        if isinstance(node, ast.Constant):
            return node.value
        if isinstance(node, ast.Name):
            found = self.name(node)
            if isinstance(found, Namespace):
                raise self.fail(f"{node.id!r} is a namespace, not a value", node)
            if callable(found):
                raise self.fail(f"{node.id!r} is a function, not a value", node)
            return found
        if isinstance(node, ast.Attribute):
            return self.attribute(node)
        if isinstance(node, ast.BinOp):
            return self.binary(node)
        return self.guarded(node, lambda: self.compute(node))

    def guarded(self, node: ast.expr, compute: Callable[[], Any]) -> Any:
        """``compute()`` within the bounds; Python's errors named at ``node``."""
        try:
            return _check_size(compute())
        except (XacroExpressionError, KinematicaError):
            raise
        except (ArithmeticError, ValueError, TypeError, IndexError, KeyError) as exc:
            reason = str(exc).strip("'\"") or type(exc).__name__
            raise self.fail(f"cannot evaluate: {reason}", node) from exc

    def binary(self, node: ast.BinOp) -> Any:
        # ``a + b - c + ...`` in a loop along the left operands: a long sum is not deep
        chain = [node]
        while isinstance(chain[-1].left, ast.BinOp):
            chain.append(chain[-1].left)
        result = self.value(chain[-1].left)
        for step in reversed(chain):
            right = self.value(step.right)
            function = _BINARY[type(step.op)]
            result = self.guarded(step, functools.partial(function, result, right))
        return result

    def compute(self, node: ast.expr) -> Any:
        if isinstance(node, ast.UnaryOp):
            operand = self.value(node.operand)
            if isinstance(node.op, ast.Not):
                return not operand
            return -operand if isinstance(node.op, ast.USub) else +operand
        if isinstance(node, ast.BoolOp):
            result = None
            for item in node.values:
                result = self.value(item)
                if bool(result) == isinstance(node.op, ast.Or):
                    break
            return result
        if isinstance(node, ast.IfExp):
            return self.value(node.body if self.value(node.test) else node.orelse)
        if isinstance(node, ast.Compare):
            left = self.value(node.left)
            for op, operand in zip(node.ops, node.comparators, strict=True):
                right = self.value(operand)
                if not _COMPARE[type(op)](left, right):
                    return False
                left = right
            return True
        if isinstance(node, ast.List):
            return [self.value(item) for item in node.elts]
        if isinstance(node, ast.Tuple):
            return tuple(self.value(item) for item in node.elts)
        if isinstance(node, ast.Subscript):
            return self.index(self.value(node.value), self.value(node.slice), node)
        if isinstance(node, ast.Call):
            return self.call(node)
        raise self.fail("unsupported expression", node)  # pragma: no cover - parse() refuses it

    def index(self, seq: Any, key: Any, node: ast.expr) -> Any:
        if isinstance(seq, dict):
            return seq[key]
        if isinstance(seq, str | list | tuple) and isinstance(key, int):
            return seq[key]
        raise self.fail(f"cannot index a {type(seq).__name__} with a {type(key).__name__}", node)

    def attribute(self, node: ast.Attribute) -> Any:
        owner, name = self.owner(node.value), node.attr
        if isinstance(owner, Namespace):
            if name in owner.members:
                member = owner.members[name]
                if callable(member):
                    raise self.fail(f"{owner.name}.{name} is a function, not a value", node)
                return member
            raise self.fail(f"{owner.name}.{name} is not available", node)
        if isinstance(owner, YamlDict):
            if name not in owner:
                raise self.fail(f"the YAML mapping has no key {name!r}", node)
            return owner[name]
        refused = f"attribute access (.{name}) is refused except on what load_yaml read"
        raise self.fail(refused, node)

    def call(self, node: ast.Call) -> Any:
        callee = node.func
        function: Any = None
        if isinstance(callee, ast.Name):
            function = self.name(callee)
            shown = callee.id
        elif isinstance(callee, ast.Attribute):
            owner, method = self.owner(callee.value), callee.attr
            shown = f"(...).{method}"
            if isinstance(callee.value, ast.Name):
                shown = f"{callee.value.id}.{method}"
            if isinstance(owner, Namespace) and method in owner.members:
                function = owner.members[method]
            elif isinstance(owner, str) and method in _STRING_METHODS:
                function = functools.partial(_STRING_METHODS[method], owner)
            elif isinstance(owner, YamlDict) and method == "get" and method not in owner:
                function = owner.get
        else:
            self.value(callee)  # refuses what it is made of first (python., unknown names, ...)
            shown = "the result of an expression"
        if not callable(function) or isinstance(function, type):
            raise self.fail(f"{shown} is not a function that may be called", node)
        args = [self.value(arg) for arg in node.args]
        keywords = {str(k.arg): self.value(k.value) for k in node.keywords}
        if keywords and function is not _dict:
            raise self.fail(f"{shown} takes no keyword arguments (only dict() does)", node)
        return function(*args, **keywords)


def evaluate(
    text: str,
    lookup: Callable[[str], Any],
    functions: Mapping[str, Callable[..., Any]] = FUNCTIONS,
) -> Any:
    """The value of expression ``text``.

    Args:
        text: The expression (what is between ``${`` and ``}``).
        lookup: The value of a property by name; raises ``KeyError`` for an
            unknown one (then constants and functions are tried).
        functions: The functions that may be called (``"xacro.NAME"`` entries
            are reached as ``xacro.NAME(...)``).

    Raises:
        XacroExpressionError: malformed, refused, or failing to evaluate.
    """
    if len(text) > MAX_LENGTH:
        raise XacroExpressionError(
            f"the expression is {len(text)} characters long; at most {MAX_LENGTH} are accepted",
            text[:100],
        )
    tree = parse(text.strip())
    return _Evaluator(tree, lookup, functions).value(tree.body)
