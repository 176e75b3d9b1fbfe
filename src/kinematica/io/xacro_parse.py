"""The parser of xacro expressions: Python's own, and a whitelist check of its tree.

xacro evaluates ``${...}`` with Python's ``eval``, so Python's grammar is the faithful
one: the text is parsed by :func:`ast.parse` (which runs nothing), and its tree is
checked, before anything is evaluated, to hold only what
:mod:`kinematica.io.xacro_expr` evaluates (:data:`OFFERED`). Names with a double
underscore, ``lambda``, comprehensions, string prefixes, slices, ``*`` arguments,
other operators and nesting deeper than :data:`MAX_DEPTH` are refused with the column.
"""

from __future__ import annotations

import ast
import io
import re
import tokenize
import warnings
from typing import Final

__all__ = ["MAX_DEPTH", "OFFERED", "Expression", "XacroExpressionError", "parse"]

#: Deepest nesting of brackets, operators and calls in one expression.
MAX_DEPTH: Final = 64

#: The kinds of node (:mod:`ast` class names) an expression may hold: constants,
#: names, ``+ - * / // % **``, unary ``- + not``, ``and``/``or``, comparisons,
#: ``a if c else b``, lists, tuples, indexing, calls (with keywords) and ``.name``.
OFFERED: Final = frozenset(
    {"Constant", "Name", "Load", "List", "Tuple", "Subscript", "Call", "keyword", "Attribute"}
    | {"BinOp", "Add", "Sub", "Mult", "Div", "FloorDiv", "Mod", "Pow"}
    | {"UnaryOp", "USub", "UAdd", "Not", "BoolOp", "And", "Or", "IfExp"}
    | {"Compare", "Eq", "NotEq", "Lt", "LtE", "Gt", "GtE", "In", "NotIn"}
)
_COMPREHENSION: Final = "comprehensions are not allowed"
_REFUSED: Final = {
    "Lambda": "lambda functions are not allowed",
    "ListComp": _COMPREHENSION,
    "SetComp": _COMPREHENSION,
    "DictComp": _COMPREHENSION,
    "GeneratorExp": _COMPREHENSION,
    "JoinedStr": "string prefixes (f'', r'', b'') are not supported",
    "Is": "'is' is not supported (use ==)",
    "IsNot": "'is' is not supported (use ==)",
    "Slice": "slices are not supported",
    "Starred": "* in calls is not supported",
}
_CONSTANTS: Final = (int, float, str, type(None))
_NODES: Final = (ast.expr, ast.keyword)
_TOKEN: Final = re.compile(r"\w+|\*\*|//|<<|>>|[=!<>]=|\S")


class XacroExpressionError(Exception):
    """An expression that is malformed or asks for something refused.

    Attributes:
        reason: What is wrong.
        text: The expression.
        position: 0-based index in ``text`` of the offending part, or None.
    """

    def __init__(self, reason: str, text: str = "", position: int | None = None) -> None:
        self.reason = reason
        self.text = text
        self.position = position
        super().__init__(reason)

    def describe(self) -> str:
        """The reason with the expression and the column."""
        where = f" at column {self.position + 1}" if self.position is not None else ""
        shown = self.text if len(self.text) <= 100 else self.text[:97] + "..."
        return f"{self.reason}{where} in the expression {shown!r}"


class Expression:
    """The tree of one expression, with the columns of its nodes.

    Attributes:
        text: The expression.
        body: The root of its tree (checked by :func:`parse`).
    """

    def __init__(self, text: str, body: ast.expr) -> None:
        self.text = text
        self.body = body
        self._lines = [0] + [m.end() for m in re.finditer(r"\r\n?|\n", text)]
        self._brackets: dict[int, int] = {}  # a token's start -> the brackets open around it

    def index(self, line: int | None, column: int | None, *, chars: bool = False) -> int:
        """The index in :attr:`text` of a line (from 1) and a column (in UTF-8 bytes)."""
        start = self._lines[(line or 1) - 1]
        if chars or self.text.isascii():
            return start + (column or 0)
        return start + len(self.text[start:].encode()[: column or 0].decode(errors="ignore"))

    def position(self, node: ast.expr | ast.keyword) -> int:
        """The column of ``node``: its operator for ``a + b``, its name for ``a.name``."""
        if isinstance(node, ast.BinOp):  # after the left operand, its brackets and spaces
            after = self.text[self.end(node.left) :]
            return len(self.text) - len(after.lstrip(" \t\r\n)"))
        if isinstance(node, ast.Attribute):
            return self.end(node) - len(node.attr)
        return self.index(node.lineno, node.col_offset)

    def end(self, node: ast.expr) -> int:
        """The index just after ``node`` in :attr:`text`."""
        return self.index(node.end_lineno, node.end_col_offset)

    def fail(self, reason: str, node: ast.expr | ast.keyword | int | None) -> XacroExpressionError:
        """The error ``reason`` at ``node`` (or at an index in the text)."""
        where = node if isinstance(node, int | None) else self.position(node)
        return XacroExpressionError(reason, self.text, where)

    def scan(self) -> None:
        """Refuse string prefixes, and count the brackets open around each token."""
        depth = 0
        for tok in tokenize.generate_tokens(io.StringIO(self.text, newline=None).readline):
            if tok.start[0] > len(self._lines):  # the end marker
                break
            at = self.index(*tok.start, chars=True)
            if tok.type == tokenize.STRING and tok.string[0] not in "'\"":
                raise self.fail(_REFUSED["JoinedStr"], at)
            self._brackets[at] = depth
            if tok.type == tokenize.OP and tok.string in "([{":
                depth += 1
            elif tok.type == tokenize.OP and tok.string in ")]}":
                depth -= 1

    def check(self) -> None:
        """Refuse what is not :data:`OFFERED`, and nesting deeper than :data:`MAX_DEPTH`.

        A node's depth is the nodes above it plus the brackets around it; the left
        operand of ``a + b`` stays at its parent's depth, so that a long sum
        ``a + b - c + ...`` is wide, not deep (it is evaluated in a loop).
        """
        todo: list[tuple[ast.expr | ast.keyword, int]] = [(self.body, 1)]
        while todo:
            node, level = todo.pop()
            where = self.index(node.lineno, node.col_offset)
            if level + self._brackets.get(where, 0) > MAX_DEPTH:
                raise self.fail(f"nested deeper than {MAX_DEPTH} levels", where)
            kind = type(node).__name__
            if kind not in OFFERED:
                raise self.fail(_REFUSED.get(kind, f"{kind} is not supported"), node)
            name = getattr(node, "id", None) or getattr(node, "attr", None) or ""
            if str(name).startswith("__") or str(getattr(node, "arg", "")).startswith("__"):
                raise self.fail("names with a double underscore are refused", node)
            constant = getattr(node, "value", None) if isinstance(node, ast.Constant) else None
            if not isinstance(constant, _CONSTANTS):
                raise self.fail(f"the constant {constant!r} is not supported", node)
            if isinstance(node, ast.keyword) and node.arg is None:
                raise self.fail("** in calls is not supported", node)
            children = list(ast.iter_child_nodes(node))
            for kind in {type(c).__name__ for c in children if not isinstance(c, _NODES)}:
                if kind not in OFFERED:
                    symbol = _TOKEN.match(self.text, self.position(node))
                    shown = f"unexpected character {symbol and symbol.group()!r} (not offered)"
                    raise self.fail(_REFUSED.get(kind, shown), node)
            for child in reversed(children):  # popped first to last, as written
                if isinstance(child, _NODES):
                    same = isinstance(node, ast.BinOp) and child is node.left
                    todo.append((child, level if same else level + 1))


def _syntax_error(text: str, exc: SyntaxError) -> XacroExpressionError:
    """Python's syntax error as ours: what is unexpected, and where."""
    if exc.lineno is None:  # null bytes
        return XacroExpressionError(exc.msg, text, None)
    offset = exc.offset or 0
    at = Expression(text, ast.Constant(None)).index(exc.lineno, offset - 1, chars=True)
    at = min(at, len(text)) if offset > 0 else len(text)
    found = _TOKEN.match(text, at)
    got = repr(found.group()) if found else "the end of the expression"
    hint = exc.msg.removeprefix("invalid syntax").strip(". ")
    if exc.msg.startswith("unterminated"):
        hint = "a string that is not closed (a '}' inside ${...} ends the expression)"
        return XacroExpressionError(hint, text, at)
    if "too many nested" in exc.msg:
        hint = f"nested deeper than {MAX_DEPTH} levels"
    elif "'='" in exc.msg:
        at, got, hint = max(text.find("=", at), 0), "'='", "keyword arguments are only for calls"
    return XacroExpressionError(f"unexpected {got}" + (f" ({hint})" if hint else ""), text, at)


def parse(text: str) -> Expression:
    """The checked tree of expression ``text``, parsed by Python's :func:`ast.parse`.

    Raises:
        XacroExpressionError: malformed, or using what is refused, with the column.
    """
    if not text.strip():
        raise XacroExpressionError("empty expression", text, None)
    try:
        with warnings.catch_warnings():  # '\d' stays as written, as in Python
            warnings.simplefilter("ignore")
            expression = Expression(text, ast.parse(text, mode="eval").body)
        expression.scan()
    except SyntaxError as exc:
        raise _syntax_error(text, exc) from None
    except (RecursionError, MemoryError) as exc:
        reason = f"nested deeper than {MAX_DEPTH} levels ({type(exc).__name__} in the parser)"
        raise XacroExpressionError(reason, text, None) from None
    except (ValueError, tokenize.TokenError) as exc:
        raise XacroExpressionError(f"malformed: {exc}", text, None) from None
    expression.check()
    return expression
