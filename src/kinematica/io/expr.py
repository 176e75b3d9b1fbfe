"""A small, safe parser for the expressions written in DH tables.

Robot files write table cells as they appear on a slide: ``q2 + 90``, ``l1``,
``-pi/2``, ``0.5*l2``. This module turns such text into an :class:`Affine` form
``const + sum(coeff * q_i)`` in the joint variables, with a tokenizer and a
recursive-descent parser of our own: no ``eval``, no ``sympy``.

Grammar (usual precedence, left-associative)::

    expr   := term (("+" | "-") term)*
    term   := unary (("*" | "/") unary)*
    unary  := ("+" | "-") unary | atom
    atom   := NUMBER | NAME | "(" expr ")"

Numbers are decimal (``90``, ``0.5``, ``.5``, ``1e-3``). Names matching
``q<digits>`` are joint variables; ``pi`` is the constant; any other name is
looked up in a parameters mapping. The result must be affine in the joint
variables: ``q1*q2`` or ``1/q3`` are errors.

Errors raise :class:`ExpressionError`, which carries the text and the position
of the offending character; its message gives a 1-based column, as editors do.
"""

from __future__ import annotations

import functools
import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Final, TypeVar

from kinematica.errors import ArgumentError, KinematicaError

__all__ = [
    "MAX_DEPTH",
    "MAX_LENGTH",
    "Affine",
    "Expression",
    "ExpressionError",
    "evaluate",
    "is_joint_variable",
    "parse_expression",
]

_T = TypeVar("_T")

#: Deepest nesting of parentheses and unary signs accepted, so that hostile
#: input fails with an ExpressionError and never with a RecursionError.
MAX_DEPTH: Final = 64
#: Longest expression accepted, in characters. A DH cell is a few dozen
#: characters (``l1 + l2/2 - 0.0125``); this bounds the work one cell can ask for.
MAX_LENGTH: Final = 1000
#: Parsed expressions kept (by text): a template's cells, parsed once a search.
PARSE_CACHE: Final = 4096

#: Longest expression quoted whole in an error message; longer ones are cut.
_SHOWN: Final = 80
#: Most known names listed in an "unknown name" message.
_NAMES_SHOWN: Final = 20

_JOINT_VARIABLE = re.compile(r"q[0-9]+", re.ASCII)
_TOKEN = re.compile(
    r"""
    (?P<space>\s+)
  | (?P<number>(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?)
  | (?P<name>[A-Za-z_][A-Za-z_0-9]*)
  | (?P<op>[-+*/()])
    """,
    re.VERBOSE | re.ASCII,
)

# Characters people write on slides, with a hint of what to write instead.
_HINTS: Final = {
    "°": "write angles without the degree sign (units.angle sets the unit)",
    "^": "powers are not supported in DH expressions",
    "π": "write pi",
    ",": "use a dot as the decimal separator",
}


class ExpressionError(KinematicaError, ValueError):
    """An expression is malformed, uses an unknown name, or is not affine in q.

    Attributes:
        text: The full expression text.
        position: 0-based index of the offending character in ``text``, or
            ``None`` when the error is about the whole expression.
        reason: The message without the location.
        hint: What to write instead, when there is an obvious fix.
    """

    def __init__(
        self, reason: str, text: str, position: int | None = None, hint: str | None = None
    ) -> None:
        self.reason = reason
        self.hint = hint
        self.text = text
        self.position = position
        where = f" at column {position + 1}" if position is not None else ""
        advice = f"; {hint}" if hint else ""
        shown = repr(text) if len(text) <= _SHOWN else repr(text[: _SHOWN - 3]) + "..."
        super().__init__(f"{reason}{where} in {shown}{advice}")

    @property
    def column(self) -> int | None:
        """1-based column of the error, or ``None``."""
        return None if self.position is None else self.position + 1


def is_joint_variable(name: str) -> bool:
    """Whether ``name`` is a joint variable (``q`` followed by digits)."""
    return _JOINT_VARIABLE.fullmatch(name) is not None


@dataclass(frozen=True)
class Affine:
    """``const + sum(coeffs[v] * v)`` over joint variables ``v``.

    Attributes:
        const: The constant part, in the units the expression was written in.
        coeffs: Joint variable name (``"q2"``) -> its coefficient. Variables
            whose coefficient cancels to zero are dropped.
    """

    const: float
    coeffs: Mapping[str, float] = field(default_factory=dict, hash=False)

    @property
    def is_constant(self) -> bool:
        """True when no joint variable appears."""
        return not self.coeffs

    def __add__(self, other: Affine) -> Affine:
        coeffs = dict(self.coeffs)
        for name, c in other.coeffs.items():
            coeffs[name] = coeffs.get(name, 0.0) + c
        return Affine(self.const + other.const, {k: v for k, v in coeffs.items() if v != 0.0})

    def __neg__(self) -> Affine:
        return Affine(-self.const, {k: -v for k, v in self.coeffs.items()})

    def __sub__(self, other: Affine) -> Affine:
        return self + (-other)

    def scaled(self, factor: float) -> Affine:
        """This form multiplied by a number."""
        coeffs = {k: v * factor for k, v in self.coeffs.items()}
        return Affine(self.const * factor, {k: v for k, v in coeffs.items() if v != 0.0})

    def divided(self, divisor: float) -> Affine:
        """This form divided by a non-zero number."""
        coeffs = {k: v / divisor for k, v in self.coeffs.items()}
        return Affine(self.const / divisor, {k: v for k, v in coeffs.items() if v != 0.0})

    def __str__(self) -> str:
        parts = [f"{c:g}*{k}" if c != 1.0 else k for k, c in self.coeffs.items()]
        if self.const != 0.0 or not parts:
            parts.append(f"{self.const:g}")
        return " + ".join(parts)


# --- syntax tree -------------------------------------------------------------
# Sums and products are n-ary (one node for ``a + b - c + ...``), so a long
# expression makes a wide tree, not a deep one: recursion depth is bounded by
# the nesting of parentheses and signs (MAX_DEPTH), never by the length.


@dataclass(frozen=True)
class _Number:
    value: float
    pos: int


@dataclass(frozen=True)
class _Name:
    name: str
    pos: int


@dataclass(frozen=True)
class _Unary:
    op: str
    operand: _Node
    pos: int


@dataclass(frozen=True)
class _Chain:
    """``first op1 x1 op2 x2 ...`` with the operators of one precedence level."""

    first: _Node
    rest: tuple[tuple[str, _Node, int], ...]  # (operator, operand, position)


_Node = _Number | _Name | _Unary | _Chain


@dataclass(frozen=True)
class _Token:
    kind: str  # "number" | "name" | "op" | "end"
    text: str
    pos: int


def _tokenize(text: str) -> list[_Token]:
    tokens: list[_Token] = []
    pos = 0
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if m is None:
            ch = text[pos]
            raise ExpressionError(f"unexpected character {ch!r}", text, pos, _HINTS.get(ch))
        kind = m.lastgroup
        assert kind is not None
        if kind != "space":
            tokens.append(_Token(kind, m.group(), pos))
        pos = m.end()
    tokens.append(_Token("end", "", len(text)))
    return tokens


class _Parser:
    def __init__(self, text: str) -> None:
        self.text = text
        self.tokens = _tokenize(text)
        self.i = 0
        self.depth = 0

    @property
    def tok(self) -> _Token:
        return self.tokens[self.i]

    def fail(self, tok: _Token, expected: str = "") -> ExpressionError:
        what = "end of expression" if tok.kind == "end" else repr(tok.text)
        hint = f"expected {expected}" if expected else None
        if tok.kind in ("name", "number") and self.i > 0:
            prev = self.tokens[self.i - 1]
            if prev.kind in ("name", "number") or prev.text == ")":
                hint = f"write {prev.text}*{tok.text} for a product"
        return ExpressionError(f"unexpected {what}", self.text, tok.pos, hint)

    def parse(self) -> _Node:
        if self.tok.kind == "end":
            raise ExpressionError("empty expression", self.text, None)
        node = self.expr()
        if self.tok.kind != "end":
            raise self.fail(self.tok)
        return node

    def nest(self, tok: _Token) -> None:
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise ExpressionError(f"nested deeper than {MAX_DEPTH} levels", self.text, tok.pos)

    def chain(self, ops: tuple[str, str], operand: Callable[[], _Node]) -> _Node:
        first = operand()
        rest: list[tuple[str, _Node, int]] = []
        while self.tok.text in ops:
            op = self.tok
            self.i += 1
            rest.append((op.text, operand(), op.pos))
        return _Chain(first, tuple(rest)) if rest else first

    def expr(self) -> _Node:
        return self.chain(("+", "-"), self.term)

    def term(self) -> _Node:
        return self.chain(("*", "/"), self.unary)

    def unary(self) -> _Node:
        tok = self.tok
        if tok.text in ("+", "-"):
            self.i += 1
            self.nest(tok)
            node = _Unary(tok.text, self.unary(), tok.pos)
            self.depth -= 1
            return node
        return self.atom()

    def atom(self) -> _Node:
        tok = self.tok
        if tok.kind == "number":
            self.i += 1
            value = float(tok.text)
            if not math.isfinite(value):
                raise ExpressionError("number too large", self.text, tok.pos)
            return _Number(value, tok.pos)
        if tok.kind == "name":
            self.i += 1
            return _Name(tok.text, tok.pos)
        if tok.text == "(":
            self.i += 1
            self.nest(tok)
            node = self.expr()
            if self.tok.text != ")":
                raise self.fail(self.tok, f"')' to close the '(' of column {tok.pos + 1}")
            self.i += 1
            self.depth -= 1
            return node
        raise self.fail(tok, "a number, a name or '('")


def _names(node: _Node) -> set[str]:
    if isinstance(node, _Name):
        return {node.name}
    if isinstance(node, _Unary):
        return _names(node.operand)
    if isinstance(node, _Chain):
        found = _names(node.first)
        for _, operand, _ in node.rest:
            found |= _names(operand)
        return found
    return set()


def _not_linear(form: Affine, reason: str, text: str, pos: int) -> ExpressionError:
    variables = ", ".join(sorted(form.coeffs))
    return ExpressionError(f"expression is not linear in {variables} ({reason})", text, pos)


@dataclass(frozen=True)
class Expression:
    """A parsed expression: its text, and the names it uses.

    Attributes:
        text: The expression as written.
        names: Every name used: joint variables, ``pi`` and parameters.
    """

    text: str
    names: frozenset[str]
    _root: _Node = field(repr=False, compare=False)

    @property
    def variables(self) -> frozenset[str]:
        """The joint variables (``q<digits>``) the expression uses."""
        return frozenset(n for n in self.names if is_joint_variable(n))

    def evaluate(self, parameters: Mapping[str, float] | None = None) -> Affine:
        """The affine form of this expression.

        Args:
            parameters: Values of the non-variable names (``pi`` is built in).

        Raises:
            ExpressionError: unknown name, product of two variable terms,
                division by a variable term or by zero, or a non-finite result.
        """
        params = {} if parameters is None else parameters
        form = self._eval(self._root, params)
        if not math.isfinite(form.const) or not all(map(math.isfinite, form.coeffs.values())):
            raise ExpressionError("the value is not a finite number", self.text, None)
        return form

    def _eval(self, node: _Node, params: Mapping[str, float]) -> Affine:
        if isinstance(node, _Number):
            return Affine(node.value)
        if isinstance(node, _Name):
            return self._lookup(node, params)
        if isinstance(node, _Unary):
            operand = self._eval(node.operand, params)
            return -operand if node.op == "-" else operand
        form = self._eval(node.first, params)
        for op, child, pos in node.rest:
            form = self._apply(op, form, self._eval(child, params), pos)
        return form

    def _apply(self, op: str, left: Affine, right: Affine, pos: int) -> Affine:
        if op == "+":
            return left + right
        if op == "-":
            return left - right
        if op == "*":
            if not left.is_constant and not right.is_constant:
                both = left + right
                raise _not_linear(both, "product of two variable terms", self.text, pos)
            return right.scaled(left.const) if left.is_constant else left.scaled(right.const)
        if not right.is_constant:
            raise _not_linear(right, "division by a variable term", self.text, pos)
        if right.const == 0.0:
            raise ExpressionError("division by zero", self.text, pos)
        return left.divided(right.const)

    def _lookup(self, node: _Name, params: Mapping[str, float]) -> Affine:
        name = node.name
        if is_joint_variable(name):
            return Affine(0.0, {name: 1.0})
        if name in params:
            return Affine(float(params[name]))
        if name == "pi":
            return Affine(math.pi)
        names = sorted({*params, "pi"})
        known = ", ".join(names[:_NAMES_SHOWN]) + (", ..." if len(names) > _NAMES_SHOWN else "")
        raise ExpressionError(
            f"unknown name {name!r}",
            self.text,
            node.pos,
            f"known names: {known}; joint variables are q1, q2, ...",
        )

    def fold(
        self,
        number: Callable[[float], _T],
        name: Callable[[str], _T],
        unary: Callable[[str, _T], _T],
        binary: Callable[[str, _T, _T], _T],
    ) -> _T:
        """Rebuild the expression bottom-up with the given constructors.

        A later layer turns the parsed tree into its own objects this way (the
        symbolic layer builds sympy expressions from it, never from raw text).

        Args:
            number: Called with each number's value.
            name: Called with each name (joint variables, ``pi``, parameters).
            unary: Called with ``"+"`` or ``"-"`` and the folded operand.
            binary: Called with ``"+"``, ``"-"``, ``"*"`` or ``"/"`` and the
                folded left and right operands.

        Returns:
            What the constructors build for the whole expression.
        """

        def walk(node: _Node) -> _T:
            if isinstance(node, _Number):
                return number(node.value)
            if isinstance(node, _Name):
                return name(node.name)
            if isinstance(node, _Unary):
                return unary(node.op, walk(node.operand))
            # a chain a op1 b op2 c ... of one precedence level folds from the left
            acc = walk(node.first)
            for op, operand, _ in node.rest:
                acc = binary(op, acc, walk(operand))
            return acc

        return walk(self._root)


def parse_expression(text: str) -> Expression:
    """Parse ``text`` into an :class:`Expression` (no evaluation yet).

    Raises:
        ExpressionError: the text is not a well-formed expression, is nested
            deeper than :data:`MAX_DEPTH` or longer than :data:`MAX_LENGTH`.
        ArgumentError: ``text`` is not a string.
    """
    if not isinstance(text, str):
        raise ArgumentError(f"an expression must be text, got {type(text).__name__}")
    if len(text) > MAX_LENGTH:
        raise ExpressionError(
            f"the expression is {len(text)} characters long; at most {MAX_LENGTH} are accepted",
            text,
            None,
        )
    return _parse_text(text)


@functools.lru_cache(maxsize=PARSE_CACHE)
def _parse_text(text: str) -> Expression:
    """The parse of a checked text, kept (expressions are immutable).

    A design search parses the same template's cells again for every candidate.
    """
    root = _Parser(text).parse()
    return Expression(text, frozenset(_names(root)), root)


def evaluate(text: str, parameters: Mapping[str, float] | None = None) -> Affine:
    """Parse and evaluate ``text`` to its affine form in the joint variables.

    Example:
        >>> evaluate("q2 + 90")
        Affine(const=90.0, coeffs={'q2': 1.0})
        >>> evaluate("l1 / 2", {"l1": 0.5}).const
        0.25

    Args:
        text: The expression.
        parameters: Values of the non-variable names (``pi`` is built in).

    Raises:
        ExpressionError: with the position of the first problem.
    """
    return parse_expression(text).evaluate(parameters)
