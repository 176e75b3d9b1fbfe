"""The parser of xacro expressions: text into a syntax tree, refusing what is not offered.

A tokenizer and a recursive-descent parser of our own (no ``compile``, no ``ast``):
numbers, strings, names, ``+ - * / // % **``, comparisons, ``and``/``or``/``not``,
``in``, ``a if c else b``, calls, indexing, ``.name``, lists and tuples. Names with
a double underscore, ``lambda``, comprehensions, string prefixes and keyword
arguments are refused here, with the column, before anything is evaluated
(:mod:`kinematica.io.xacro_expr` evaluates the tree).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Final

__all__ = ["MAX_DEPTH", "Node", "XacroExpressionError", "parse"]

#: Deepest nesting of brackets, operators and calls in one expression.
MAX_DEPTH: Final = 64


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


_KEYWORDS: Final = frozenset({"and", "or", "not", "if", "else", "in", "True", "False", "None"})
_REFUSED_WORDS: Final = {
    "lambda": "lambda functions are not allowed",
    "for": "comprehensions are not allowed",
    "import": "import is not allowed",
    "yield": "yield is not allowed",
    "await": "await is not allowed",
    "is": "'is' is not supported (use ==)",
}

_TOKEN = re.compile(
    r"""
    (?P<space>\s+)
  | (?P<number>(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)
  | (?P<string>'[^'\\]*(?:\\.[^'\\]*)*'|"[^"\\]*(?:\\.[^"\\]*)*")
  | (?P<name>[A-Za-z_][A-Za-z_0-9]*)
  | (?P<op>\*\*|//|==|!=|<=|>=|[-+*/%<>()\[\],.=])
    """,
    re.VERBOSE | re.ASCII,
)
_ESCAPES: Final = {"n": "\n", "t": "\t", "\\": "\\", "'": "'", '"': '"'}


@dataclass(frozen=True)
class _Tok:
    kind: str
    text: str
    pos: int


def _unquote(text: str) -> str:
    body = text[1:-1]
    return re.sub(r"\\(.)", lambda m: _ESCAPES.get(m.group(1), "\\" + m.group(1)), body)


def _tokenize(text: str) -> list[_Tok]:
    tokens: list[_Tok] = []
    pos = 0
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if m is None:
            if text[pos] in "'\"":
                reason = "a string that is not closed (a '}' inside ${...} ends the expression)"
                raise XacroExpressionError(reason, text, pos)
            raise XacroExpressionError(f"unexpected character {text[pos]!r}", text, pos)
        kind = m.lastgroup or ""
        if kind == "name" and m.group().startswith("__"):
            raise XacroExpressionError("names with a double underscore are refused", text, pos)
        if kind == "name" and m.group() in _REFUSED_WORDS:
            raise XacroExpressionError(_REFUSED_WORDS[m.group()], text, pos)
        if (
            kind == "string"
            and tokens
            and tokens[-1].kind == "name"
            and tokens[-1].pos + len(tokens[-1].text) == pos
        ):
            raise XacroExpressionError(
                "string prefixes (f'', r'', b'') are not supported", text, pos
            )
        if kind != "space":
            tokens.append(_Tok(kind, m.group(), pos))
        pos = m.end()
    tokens.append(_Tok("end", "", len(text)))
    return tokens


#: The syntax tree: tuples (kind, position, ...), built here and walked by the evaluator.
Node = tuple[Any, ...]


class _Parser:
    def __init__(self, text: str) -> None:
        self.text = text
        self.toks = _tokenize(text)
        self.i = 0
        self.depth = 0

    @property
    def tok(self) -> _Tok:
        return self.toks[self.i]

    def take(self, text: str) -> bool:
        if self.tok.text == text and self.tok.kind in ("op", "name"):
            self.i += 1
            return True
        return False

    def expect(self, text: str) -> None:
        if not self.take(text):
            raise self.fail(f"expected {text!r}")

    def fail(self, what: str = "") -> XacroExpressionError:
        tok = self.tok
        got = "the end of the expression" if tok.kind == "end" else repr(tok.text)
        return XacroExpressionError(
            f"unexpected {got}" + (f" ({what})" if what else ""), self.text, tok.pos
        )

    def nest(self) -> None:
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise XacroExpressionError(
                f"nested deeper than {MAX_DEPTH} levels", self.text, self.tok.pos
            )

    def parse(self) -> Node:
        if self.tok.kind == "end":
            raise XacroExpressionError("empty expression", self.text, None)
        node = self.conditional()
        if self.tok.kind != "end":
            raise self.fail()
        return node

    def conditional(self) -> Node:
        self.nest()
        node = self.disjunction()
        if self.tok.text == "if" and self.tok.kind == "name":
            pos = self.tok.pos
            self.i += 1
            cond = self.disjunction()
            self.expect("else")
            node = ("if", pos, cond, node, self.conditional())
        self.depth -= 1
        return node

    def disjunction(self) -> Node:
        items = [self.conjunction()]
        while self.take("or"):
            items.append(self.conjunction())
        return items[0] if len(items) == 1 else ("or", None, items)

    def conjunction(self) -> Node:
        items = [self.negation()]
        while self.take("and"):
            items.append(self.negation())
        return items[0] if len(items) == 1 else ("and", None, items)

    def negation(self) -> Node:
        pos = self.tok.pos
        if self.take("not"):
            self.nest()
            node = ("not", pos, self.negation())
            self.depth -= 1
            return node
        return self.comparison()

    def comparison(self) -> Node:
        first = self.arith()
        rest = []
        while True:
            tok = self.tok
            if tok.kind == "op" and tok.text in ("<", "<=", ">", ">=", "==", "!="):
                op = tok.text
                self.i += 1
            elif self.take("in"):
                op = "in"
            elif tok.text == "not" and self.toks[self.i + 1].text == "in":
                self.i += 2
                op = "not in"
            else:
                break
            rest.append((op, tok.pos, self.arith()))
        return first if not rest else ("cmp", None, first, rest)

    def binary(self, ops: tuple[str, ...], operand: Callable[[], Node]) -> Node:
        # one node for ``a + b - c + ...``: a long sum makes a wide tree, not a deep one
        first = operand()
        rest = []
        while self.tok.kind == "op" and self.tok.text in ops:
            tok = self.tok
            self.i += 1
            rest.append((tok.text, tok.pos, operand()))
        return ("chain", None, first, rest) if rest else first

    def arith(self) -> Node:
        return self.binary(("+", "-"), self.term)

    def term(self) -> Node:
        return self.binary(("*", "/", "//", "%"), self.unary)

    def unary(self) -> Node:
        tok = self.tok
        if tok.kind == "op" and tok.text in ("+", "-"):
            self.i += 1
            self.nest()
            node = ("neg" if tok.text == "-" else "pos", tok.pos, self.unary())
            self.depth -= 1
            return node
        return self.power()

    def power(self) -> Node:
        node = self.postfix()
        if self.tok.kind == "op" and self.tok.text == "**":
            tok = self.tok
            self.i += 1
            self.nest()
            node = ("bin", tok.pos, "**", node, self.unary())
            self.depth -= 1
        return node

    def postfix(self) -> Node:
        node = self.atom()
        while self.tok.kind == "op" and self.tok.text in ("(", "[", "."):
            tok = self.tok
            self.i += 1
            self.nest()
            if tok.text == "(":
                args = self.items(")", keywords=True)
                node = ("call", tok.pos, node, args)
            elif tok.text == "[":
                index = self.conditional()
                self.expect("]")
                node = ("index", tok.pos, node, index)
            else:
                name = self.tok
                if name.kind != "name":
                    raise self.fail("expected a name after '.'")
                self.i += 1
                node = ("attr", name.pos, node, name.text)
        return node

    def items(self, close: str, *, keywords: bool = False) -> list[Node]:
        items: list[Node] = []
        while not self.take(close):
            if items:
                self.expect(",")
                if self.take(close):
                    break
            if self.tok.kind == "name" and self.toks[self.i + 1].text == "=":
                if not keywords:
                    raise self.fail("keyword arguments are only for calls")
                name = self.tok
                self.i += 2
                items.append(("keyword", name.pos, name.text, self.conditional()))
                continue
            items.append(self.conditional())
        self.depth -= 1
        return items

    def atom(self) -> Node:
        tok = self.tok
        if tok.kind == "number":
            self.i += 1
            is_int = re.fullmatch(r"[0-9]+", tok.text) is not None
            return ("const", tok.pos, int(tok.text) if is_int else float(tok.text))
        if tok.kind == "string":
            self.i += 1
            value = _unquote(tok.text)
            while self.tok.kind == "string":  # adjacent literals join, as in Python
                value += _unquote(self.tok.text)
                self.i += 1
            return ("const", tok.pos, value)
        if tok.kind == "name" and tok.text not in _KEYWORDS - {"True", "False", "None"}:
            self.i += 1
            return ("name", tok.pos, tok.text)
        if tok.kind == "op" and tok.text in ("(", "["):
            self.i += 1
            self.nest()
            if tok.text == "[":
                return ("list", tok.pos, self.items("]"))
            if self.take(")"):
                self.depth -= 1
                return ("tuple", tok.pos, [])
            first = self.conditional()
            if self.take(")"):
                self.depth -= 1
                return first
            self.expect(",")
            rest = self.items(")")
            return ("tuple", tok.pos, [first, *rest])
        raise self.fail("expected a number, a string, a name or '('")


def parse(text: str) -> Node:
    """The syntax tree of expression ``text``: nested tuples ``(kind, position, ...)``.

    Raises:
        XacroExpressionError: malformed, or using what is refused, with the column.
    """
    return _Parser(text).parse()
