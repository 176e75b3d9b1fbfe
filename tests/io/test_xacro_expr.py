"""The safe evaluator of xacro expressions: Python's meaning for what it accepts, and its
bounds (each with a case just inside and one just outside)."""

from __future__ import annotations

import math

import pytest

from kinematica.io.xacro_expr import (
    MAX_INT_BITS,
    MAX_LENGTH,
    MAX_TEXT,
    XacroExpressionError,
    YamlDict,
    evaluate,
)
from kinematica.io.xacro_parse import MAX_DEPTH

NAMES = {"a": 2, "b": 0.5, "s": "ab", "L": [1, 2.5, "x"], "T": (3, 4), "n": -7}

# Written as Python reads them: Python itself (on these constant, trusted strings, in the
# test only) is the reference for precedence, associativity and types.
SAME_AS_PYTHON = [
    "1 + 2 * 3 - 4 / 8",
    "2 ** 3 ** 2",
    "-2 ** 2",
    "(-2) ** 2",
    "a ** -1",
    "n // 2",
    "n % 3",
    "-n % 3",
    "7 / 2 * 2",
    "1 < a <= 2 < 3",
    "1 < a > 3",
    "not a == 2 or b",
    "a and b and 0",
    "0 or '' or 'z'",
    "not not s",
    "'x' if a > 1 else 'y'",
    "1 if 0 else 2 if 0 else 3",
    "s + 'c' * 3",
    "'b' in s",
    "'q' not in s",
    "3 in L",
    "L[1] * T[-1]",
    "s[-1]",
    "(1, 2)[0] + [4, 5][1]",
    "L",
    "T",
    "(a,)",
    "[]",
    "int(-3.7) + int('12')",
    "float('1e-3') * 2",
    "str(1.5) + str(a) + str(True)",
    "bool(0) or bool('x')",
    "round(2.567, 2)",
    "min(3, a, 1.5)",
    "max([1, 9, 3])",
    "len(L) + len(s)",
    "abs(n)",
    "sin(pi / 6) + cos(0) + tan(0)",
    "atan2(1, -1)",
    "sqrt(2) * hypot(3, 4)",
    "radians(90) - degrees(pi)",
    "floor(-2.5) + ceil(2.5)",
    "math.pi / 2 + math.sqrt(9)",
    "1e3 + .5 + 2.",
    "True + False",
    "'it''s'",
    "'a\\tb'",
    "s.split('b')[0]",
    "'1 2  3'.split()",
    "'a,b'.rsplit(',', 1)",
    "' x '.strip() + ' y'.lstrip() + 'z '.rstrip()",
    "s.upper() + s.lower()",
    "s.replace('a', 'zz')",
    "'-'.join(['a', 'b'])",
    "s.startswith('a') and not s.endswith('a')",
    "(s + 'c').upper()",
    "dict(j1=0.5, j2=a)['j2']",
    "dict(dict(x=1), y=2)",
    # read as Python (and xacro) reads them, the parser being Python's (issue 33)
    "0x10 + 0b11 + 0o7 + 1_000",
    "'\\x41\\u00e9'",
    "'''a'b'''",
    "1, a",
    "a  # a comment",
]


def python(text: str) -> object:
    namespace = {**NAMES, **{k: getattr(math, k) for k in dir(math) if not k.startswith("_")}}
    namespace.update(math=math, abs=abs, min=min, max=max, round=round, len=len, int=int)
    namespace.update(float=float, str=str, bool=bool, dict=dict)
    return eval(text, {"__builtins__": {}}, namespace)  # trusted test constants only


@pytest.mark.parametrize("text", SAME_AS_PYTHON)
def test_the_meaning_is_pythons(text: str) -> None:
    ours = evaluate(text, NAMES.__getitem__)
    expected = python(text)
    assert ours == expected and type(ours) is type(expected), (ours, expected)


def test_yaml_data_is_reached_by_key_and_attribute() -> None:
    data = YamlDict(arm=YamlDict(lengths=[0.1, 0.2]))
    names = {"cfg": data}
    assert evaluate("cfg.arm.lengths[1]", names.__getitem__) == 0.2
    assert evaluate("cfg['arm']['lengths'][0]", names.__getitem__) == 0.1
    with pytest.raises(XacroExpressionError, match="no key 'legs'"):
        evaluate("cfg.arm.legs", names.__getitem__)


def refused(text: str, *fragments: str) -> None:
    with pytest.raises(XacroExpressionError) as info:
        evaluate(text, NAMES.__getitem__)
    message = info.value.describe()
    for fragment in fragments:
        assert fragment in message, message


def test_integers_are_bounded() -> None:
    assert evaluate(f"2 ** {MAX_INT_BITS - 1}", NAMES.__getitem__) == 2 ** (MAX_INT_BITS - 1)
    refused(f"2 ** {MAX_INT_BITS}", f"more than {MAX_INT_BITS} bits")
    refused("9 ** 9 ** 9 ** 9", "larger than 2**1024")
    assert evaluate("2.0 ** 1000", NAMES.__getitem__) == 2.0**1000
    refused("2.0 ** 10000", "cannot evaluate")  # float overflow


def test_strings_and_lists_are_bounded() -> None:
    assert len(evaluate(f"'x' * {MAX_TEXT}", NAMES.__getitem__)) == MAX_TEXT
    refused(f"'x' * {MAX_TEXT + 1}", "longer than 1,000,000")
    refused(f"[0] * {MAX_TEXT + 1}", "longer than 1,000,000")
    # nested sharing: small in memory, 1e9 items as text
    refused("[[[0] * 1000] * 1000] * 1000", "longer than 1,000,000")
    refused("str([[0] * 1000] * 1001)", "longer than 1,000,000")


def test_string_methods_are_bounded() -> None:
    inside = "('x' * 1000).replace('x', 'y' * 999)"
    assert len(evaluate(inside, NAMES.__getitem__)) == 999_000
    refused("('x' * 1000).replace('x', 'y' * 1001)", "longer than 1,000,000")
    refused("'-'.join(['x' * 600000, 'y' * 600000])", "longer than 1,000,000")
    refused("'-'.join([1, 2])", "join() takes a list of strings")


def test_length_and_depth_are_bounded() -> None:
    assert evaluate("1" + " + 1" * ((MAX_LENGTH - 1) // 4), NAMES.__getitem__) > 0
    refused("1" + " " * MAX_LENGTH, f"at most {MAX_LENGTH}")
    inside = "(" * (MAX_DEPTH // 2 - 1) + "1" + ")" * (MAX_DEPTH // 2 - 1)
    assert evaluate(inside, NAMES.__getitem__) == 1
    outside = "(" * MAX_DEPTH + "1" + ")" * MAX_DEPTH
    refused(outside, f"deeper than {MAX_DEPTH}")
    refused("-" * (MAX_DEPTH + 1) + "1", f"deeper than {MAX_DEPTH}")


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("", "empty expression"),
        ("1 +", "unexpected the end"),
        ("a b", "unexpected 'b'"),
        ("foo", "unknown name 'foo'"),
        ("foo(1)", "unknown name 'foo'"),
        ("max", "is a function, not a value"),
        ("math", "is a namespace, not a value"),
        ("math.nothing", "math.nothing is not available"),
        ("s.encode()", "not a function that may be called"),
        ("s.format(a)", "not a function that may be called"),
        ("a.bit_length()", "not a function that may be called"),
        ("L.append", "attribute access (.append) is refused"),
        ("a.real", "attribute access (.real) is refused"),
        ("max(key=1)", "takes no keyword arguments"),
        ("[a=1]", "keyword arguments are only for calls"),
        ("1 is 1", "'is' is not supported"),
        ("'%d' % 3", "string formatting"),
        ("(-8) ** 0.5", "complex number"),
        ("1 / 0", "division by zero"),
        ("L[10]", "out of range"),
        ("L['x']", "cannot index a list with a str"),
        ("sum(['a'])", "sum() takes one list of numbers"),
        ("list(3)", "takes a string, list or tuple"),
        ("'abc", "string that is not closed"),
        ("a @ b", "unexpected character '@'"),
        ("__import__", "double underscore"),
        ("lambda: 0", "lambda"),
        ("[x for x in L]", "comprehensions"),
        ("b'x'", "string prefixes"),
    ],
)
def test_what_is_refused_is_named(text: str, fragment: str) -> None:
    refused(text, fragment)


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("-" * (MAX_LENGTH - 1) + "1", f"deeper than {MAX_DEPTH}"),  # the parser's recursion
        ("(" * (MAX_LENGTH // 2) + "1" + ")" * (MAX_LENGTH // 2 - 1), "deeper than"),
        ("not " * (MAX_LENGTH // 4 - 1) + "1", f"deeper than {MAX_DEPTH}"),
        ("L" + "[0]" * (MAX_LENGTH // 3 - 1), f"deeper than {MAX_DEPTH}"),
        ("abs(" * 799 + "1" + ")" * 799, "deeper than"),
        ("1\x00", "null bytes"),
        ("9**9**9**9", "larger than 2**1024"),
    ],
)
def test_hostile_input_to_the_parser_is_refused(text: str, fragment: str) -> None:
    assert len(text) <= MAX_LENGTH
    refused(text, fragment)


@pytest.mark.parametrize(
    ("text", "fragment"),
    [
        ("0 and (lambda: 0)", "lambda functions are not allowed at column 8"),
        ("1 if 1 else L.__len__()", "double underscore are refused at column 15"),
        ("a if 1 else [x for x in L]", "comprehensions"),
        ("'é' + 1", "at column 5"),  # columns count characters, not UTF-8 bytes
        ("(1 +\n 'x')", "at column 4"),
        ("r'x'", "string prefixes"),
        ("{1: 2}", "Dict is not supported"),
        ("L[0:1]", "slices are not supported"),
        ("max(*L)", "* in calls is not supported"),
        ("a << 1", "unexpected character '<<'"),
        ("1j", "the constant 1j is not supported"),
        ("01", "leading zeros"),  # as in Python and xacro
        ("1 +\n 2", "unexpected"),  # a line break outside brackets, as in Python and xacro
    ],
)
def test_refused_before_anything_is_evaluated(text: str, fragment: str) -> None:
    refused(text, fragment)
