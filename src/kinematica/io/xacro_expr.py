"""The expressions of xacro files (``${...}``, ``$(eval ...)``), evaluated safely.

xacro evaluates ``${...}`` with Python's ``eval`` behind a thin guard, which a
file can get around (``python.vars(python.type(f))['__globals__']`` reaches
``os.system``). This module evaluates the part of Python that robot
descriptions write, with a tokenizer, parser and evaluator of its own (no
``eval``, no ``compile``, no attribute of any Python object is ever looked up):

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

import functools
import math
from collections.abc import Callable, Mapping
from typing import Any, Final

from kinematica.errors import KinematicaError
from kinematica.io.xacro_parse import MAX_DEPTH, Node, XacroExpressionError, parse

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


_BINARY: Final[dict[str, Callable[[Any, Any], Any]]] = {
    "+": lambda a, b: a + b,
    "-": lambda a, b: a - b,
    "*": _times,
    "/": lambda a, b: a / b,
    "//": lambda a, b: a // b,
    "%": _modulo,
    "**": _power,
}

_COMPARE: Final[dict[str, Callable[[Any, Any], bool]]] = {
    "<": lambda a, b: a < b,
    "<=": lambda a, b: a <= b,
    ">": lambda a, b: a > b,
    ">=": lambda a, b: a >= b,
    "==": lambda a, b: a == b,
    "!=": lambda a, b: a != b,
    "in": lambda a, b: a in b,
    "not in": lambda a, b: a not in b,
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
    "split": str.split,
    "rsplit": str.rsplit,
    "strip": str.strip,
    "lstrip": str.lstrip,
    "rstrip": str.rstrip,
    "lower": str.lower,
    "upper": str.upper,
    "startswith": str.startswith,
    "endswith": str.endswith,
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


_MATH: Final = [
    "sin",
    "cos",
    "tan",
    "asin",
    "acos",
    "atan",
    "atan2",
    "sinh",
    "cosh",
    "tanh",
    "asinh",
    "acosh",
    "atanh",
    "sqrt",
    "exp",
    "log",
    "log10",
    "log2",
    "pow",
    "fabs",
    "floor",
    "ceil",
    "trunc",
    "radians",
    "degrees",
    "hypot",
    "copysign",
    "fmod",
    "isclose",
    "isfinite",
    "isinf",
    "isnan",
]

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
    "True": True,
    "False": False,
    "None": None,
}


class Namespace:
    """``math`` and ``xacro`` in ``math.sin(x)``, ``xacro.load_yaml(f)``."""

    def __init__(self, name: str, members: Mapping[str, Any]) -> None:
        self.name = name
        self.members = members


class _Evaluator:
    def __init__(
        self, text: str, lookup: Callable[[str], Any], functions: Mapping[str, Callable[..., Any]]
    ) -> None:
        self.text = text
        self.lookup = lookup
        self.functions = functions

    def fail(self, reason: str, pos: int | None) -> XacroExpressionError:
        return XacroExpressionError(reason, self.text, pos)

    def name(self, name: str, pos: int) -> Any:
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
            raise self.fail("the 'python' namespace is refused", pos)
        raise self.fail(f"unknown name {name!r}", pos)

    def value(self, node: Node) -> Any:
        kind, pos = node[0], node[1]
        if kind == "const":
            return node[2]
        if kind == "name":
            found = self.name(node[2], pos)
            if isinstance(found, Namespace):
                raise self.fail(f"{node[2]!r} is a namespace, not a value", pos)
            if callable(found):
                raise self.fail(f"{node[2]!r} is a function, not a value", pos)
            return found
        if kind == "attr":
            return self.attribute(node)
        try:
            return _check_size(self.compute(node))
        except (XacroExpressionError, KinematicaError):
            raise
        except (ArithmeticError, ValueError, TypeError, IndexError, KeyError) as exc:
            reason = str(exc).strip("'\"") or type(exc).__name__
            raise self.fail(f"cannot evaluate: {reason}", pos) from exc

    def compute(self, node: Node) -> Any:
        kind, pos = node[0], node[1]
        if kind == "bin":
            return _BINARY[node[2]](self.value(node[3]), self.value(node[4]))
        if kind == "chain":
            result = self.value(node[2])
            for op, where, operand in node[3]:
                right = self.value(operand)
                try:
                    result = _check_size(_BINARY[op](result, right))
                except (ArithmeticError, ValueError, TypeError) as exc:
                    raise self.fail(f"cannot evaluate: {exc}", where) from exc
            return result
        if kind == "neg":
            return -self.value(node[2])
        if kind == "pos":
            return +self.value(node[2])
        if kind == "not":
            return not self.value(node[2])
        if kind == "and" or kind == "or":
            result = None
            for item in node[2]:
                result = self.value(item)
                if bool(result) == (kind == "or"):
                    break
            return result
        if kind == "if":
            return self.value(node[3] if self.value(node[2]) else node[4])
        if kind == "cmp":
            left = self.value(node[2])
            for op, _, operand in node[3]:
                right = self.value(operand)
                if not _COMPARE[op](left, right):
                    return False
                left = right
            return True
        if kind == "list":
            return [self.value(item) for item in node[2]]
        if kind == "tuple":
            return tuple(self.value(item) for item in node[2])
        if kind == "index":
            return self.index(self.value(node[2]), self.value(node[3]), pos)
        if kind == "call":
            return self.call(node)
        raise self.fail("unsupported expression", pos)  # pragma: no cover - the parser makes none

    def index(self, seq: Any, key: Any, pos: int) -> Any:
        if isinstance(seq, dict):
            return seq[key]
        if isinstance(seq, str | list | tuple) and isinstance(key, int):
            return seq[key]
        raise self.fail(f"cannot index a {type(seq).__name__} with a {type(key).__name__}", pos)

    def attribute(self, node: Node) -> Any:
        owner_node, name = node[2], node[3]
        if owner_node[0] == "name":
            owner = self.name(owner_node[2], owner_node[1])
        else:
            owner = self.value(owner_node)
        if isinstance(owner, Namespace):
            if name in owner.members:
                member = owner.members[name]
                if callable(member):
                    raise self.fail(f"{owner.name}.{name} is a function, not a value", node[1])
                return member
            raise self.fail(f"{owner.name}.{name} is not available", node[1])
        if isinstance(owner, YamlDict):
            if name not in owner:
                raise self.fail(f"the YAML mapping has no key {name!r}", node[1])
            return owner[name]
        raise self.fail(
            f"attribute access (.{name}) is refused except on what load_yaml read", node[1]
        )

    def call(self, node: Node) -> Any:
        callee, pos = node[2], node[1]
        function: Any = None
        if callee[0] == "name":
            function = self.name(callee[2], callee[1])
            shown = callee[2]
        elif callee[0] == "attr":
            owner_node, method = callee[2], callee[3]
            if owner_node[0] == "name":
                owner = self.name(owner_node[2], owner_node[1])
                shown = f"{owner_node[2]}.{method}"
            else:
                owner = self.value(owner_node)
                shown = f"(...).{method}"
            if isinstance(owner, Namespace) and method in owner.members:
                function = owner.members[method]
            elif isinstance(owner, str) and method in _STRING_METHODS:
                function = functools.partial(_STRING_METHODS[method], owner)
            elif isinstance(owner, YamlDict) and method == "get" and method not in owner:
                function = owner.get
        else:
            self.value(callee)  # refuses what it is made of first (python., __, ...)
            shown = "the result of an expression"
        if not callable(function) or isinstance(function, type):
            raise self.fail(f"{shown} is not a function that may be called", pos)
        args = [self.value(arg) for arg in node[3] if arg[0] != "keyword"]
        keywords = {arg[2]: self.value(arg[3]) for arg in node[3] if arg[0] == "keyword"}
        if keywords and function is not _dict:
            raise self.fail(f"{shown} takes no keyword arguments (only dict() does)", pos)
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
    return _Evaluator(text.strip(), lookup, functions).value(tree)
