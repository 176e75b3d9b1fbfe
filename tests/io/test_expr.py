"""The safe expression parser of robot files: values, affine forms, errors."""

from __future__ import annotations

import contextlib
import math
import sys
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinematica.errors import ArgumentError, KinematicaError, RobotFileError
from kinematica.io import parse_robot_dict
from kinematica.io.expr import (
    MAX_DEPTH,
    MAX_LENGTH,
    Affine,
    ExpressionError,
    evaluate,
    is_joint_variable,
    parse_expression,
)


@pytest.mark.parametrize(
    ("text", "value"),
    [
        ("90", 90.0),
        ("0.5", 0.5),
        (".5", 0.5),
        ("5.", 5.0),
        ("1e-3", 1e-3),
        ("2.5E+2", 250.0),
        ("  42  ", 42.0),
        ("1 + 2*3", 7.0),
        ("(1 + 2)*3", 9.0),
        ("2*3 - 4/2", 4.0),
        ("8/4/2", 1.0),
        ("1 - 2 - 3", -4.0),
        ("-2*3", -6.0),
        ("2*-3", -6.0),
        ("--2", 2.0),
        ("-(1 - 3)", 2.0),
        ("+7", 7.0),
        ("-2 + 5", 3.0),
        ("pi", math.pi),
        ("pi/2", math.pi / 2),
        ("-pi", -math.pi),
        ("2*pi", 2 * math.pi),
    ],
)
def test_constant_values_follow_usual_precedence(text: str, value: float) -> None:
    form = evaluate(text)
    assert form.is_constant
    assert form.const == value


def test_parameters_are_looked_up() -> None:
    assert evaluate("l1 + l2/2", {"l1": 0.5, "l2": 0.4}).const == 0.5 + 0.4 / 2
    assert evaluate("-l1", {"l1": 0.5}).const == -0.5


def test_a_parameter_may_shadow_pi() -> None:
    # The robot-file layer forbids a parameter named pi; the parser lets the
    # mapping win so that it stays a plain lookup.
    assert evaluate("pi", {"pi": 3.0}).const == 3.0


@pytest.mark.parametrize(
    ("text", "const", "coeffs"),
    [
        ("q2", 0.0, {"q2": 1.0}),
        ("q2 + 90", 90.0, {"q2": 1.0}),
        ("q3 - 90", -90.0, {"q3": 1.0}),
        ("90 + q2", 90.0, {"q2": 1.0}),
        ("-q1", 0.0, {"q1": -1.0}),
        ("2*(q1 + 1)/4", 0.5, {"q1": 0.5}),
        ("q1*3 - 2*q1", 0.0, {"q1": 1.0}),
        ("q1 - q1 + 5", 5.0, {}),
        ("0*q4", 0.0, {}),
        ("q1 + q2", 0.0, {"q1": 1.0, "q2": 1.0}),
        ("(q12 + l1)/2", 0.25, {"q12": 0.5}),
    ],
)
def test_affine_forms(text: str, const: float, coeffs: dict[str, float]) -> None:
    form = evaluate(text, {"l1": 0.5})
    assert form.const == const
    assert dict(form.coeffs) == coeffs
    assert form.is_constant is (not coeffs)


def test_affine_arithmetic_and_text() -> None:
    a = Affine(1.0, {"q1": 2.0})
    b = Affine(0.5, {"q1": -2.0, "q2": 1.0})
    assert a + b == Affine(1.5, {"q2": 1.0})
    assert a - a == Affine(0.0, {})
    assert a.scaled(0.5) == Affine(0.5, {"q1": 1.0})
    assert a.divided(4.0) == Affine(0.25, {"q1": 0.5})
    assert str(Affine(90.0, {"q2": 1.0})) == "q2 + 90"
    assert str(Affine(0.0, {})) == "0"


def test_parsed_expression_keeps_text_and_names() -> None:
    expr = parse_expression("q2 + l1*pi")
    assert expr.text == "q2 + l1*pi"
    assert expr.names == {"q2", "l1", "pi"}
    assert expr.variables == {"q2"}
    assert expr.evaluate({"l1": 2.0}) == Affine(2 * math.pi, {"q2": 1.0})


def test_joint_variable_names() -> None:
    assert is_joint_variable("q1")
    assert is_joint_variable("q12")
    assert not is_joint_variable("q")
    assert not is_joint_variable("qa")
    assert not is_joint_variable("Q1")
    assert not is_joint_variable("q1x")
    assert not is_joint_variable("q١")  # a non-ASCII digit is not a joint number


@pytest.mark.parametrize(
    ("text", "match", "column"),
    [
        ("q2 + 90)", r"unexpected '\)' at column 8 in 'q2 \+ 90\)'", 8),
        ("(1 + 2", r"expected '\)' to close the '\(' of column 1", 7),
        ("1 +", r"unexpected end of expression", 4),
        ("*2", r"unexpected '\*'", 1),
        ("2pi", r"write 2\*pi for a product", 2),
        ("l1 l2", r"write l1\*l2 for a product", 4),
        ("q1*q2", r"not linear in q1, q2 \(product of two variable terms\)", 3),
        ("(q1 + 1)*(q1 - 1)", r"not linear in q1", 9),
        ("1/q3", r"not linear in q3 \(division by a variable term\)", 2),
        ("1/(2 - 2)", r"division by zero", 2),
        ("90°", r"degree sign", 3),
        ("q1^2", r"powers are not supported", 3),
        ("1,5", r"decimal separator", 2),
        ("l5 + 1", r"unknown name 'l5' at column 1.*known names: l1, pi", 1),
        ("1e999", r"number too large", 1),
        ("()", r"unexpected '\)'", 2),
        ("q1 $ 2", r"unexpected character '\$'", 4),
    ],
)
def test_errors_say_what_and_where(text: str, match: str, column: int) -> None:
    with pytest.raises(ExpressionError, match=match) as info:
        evaluate(text, {"l1": 0.5})
    assert info.value.text == text
    assert info.value.column == column
    assert info.value.position == column - 1


@pytest.mark.parametrize("text", ["", "   "])
def test_empty_expression(text: str) -> None:
    with pytest.raises(ExpressionError, match="empty expression") as info:
        evaluate(text)
    assert info.value.position is None


def test_result_overflow_is_an_error() -> None:
    with pytest.raises(ExpressionError, match="not a finite number"):
        evaluate("1e300*1e300")


def test_expression_error_is_a_kinematica_error_and_a_value_error() -> None:
    with pytest.raises(KinematicaError):
        evaluate("(")
    with pytest.raises(ValueError, match="unexpected end"):
        evaluate("(")


@pytest.mark.parametrize("text", ["(" * 200 + "1" + ")" * 200, "-" * 500 + "1"])
def test_deep_nesting_is_refused_without_recursion_error(text: str) -> None:
    with pytest.raises(ExpressionError, match=f"nested deeper than {MAX_DEPTH}"):
        evaluate(text)


def test_nesting_up_to_the_limit_is_fine() -> None:
    depth = MAX_DEPTH
    assert evaluate("(" * depth + "q1" + ")" * depth).coeffs == {"q1": 1.0}


def test_non_string_input_is_an_argument_error() -> None:
    with pytest.raises(ArgumentError, match="must be text, got int"):
        parse_expression(90)  # type: ignore[arg-type]


@settings(max_examples=300, deadline=None)
@given(st.text())
def test_arbitrary_text_raises_only_expression_error(text: str) -> None:
    try:
        form = evaluate(text, {"l1": 0.5, "L2": 2.0})
    except ExpressionError as exc:
        assert exc.text == text
        assert exc.position is None or 0 <= exc.position <= len(text)
    else:
        assert math.isfinite(form.const)


_EXPRESSION_ALPHABET = "q0123456789+-*/(). eE_lpi1L2x"


@settings(max_examples=500, deadline=None)
@given(st.text(alphabet=_EXPRESSION_ALPHABET, max_size=40))
def test_expression_like_text_raises_only_expression_error(text: str) -> None:
    with contextlib.suppress(ExpressionError):
        evaluate(text, {"l1": 0.5, "L2": 2.0})


_finite = st.floats(min_value=-1e6, max_value=1e6, allow_nan=False)


@given(a=_finite, b=_finite, c=_finite)
def test_affine_form_matches_arithmetic(a: float, b: float, c: float) -> None:
    form = evaluate(f"{a!r}*q1 + {b!r} - ({c!r})")
    assert form.const == b - c
    assert dict(form.coeffs) == ({"q1": a} if a != 0.0 else {})


def _joints(n: int) -> dict[str, Any]:
    rows = [{"theta": f"q{i}", "d": 0, "a": 0.1, "alpha": 0} for i in range(1, n + 1)]
    return {"convention": "standard", "joints": rows}


def _sum(terms: int) -> str:
    return "q1" + " + 1" * (terms - 1)


def test_expression_of_max_length_evaluates_and_one_character_more_is_refused() -> None:
    terms = (MAX_LENGTH + 1) // 2
    text = ("1" + "+1" * (terms - 1)).ljust(MAX_LENGTH)
    assert len(text) == MAX_LENGTH
    assert evaluate(text).const == terms
    with pytest.raises(ExpressionError, match=rf"{MAX_LENGTH + 1} characters long; at most"):
        evaluate(text + "1")


def test_a_1000_term_expression_is_an_error_not_a_recursion_error() -> None:
    with pytest.raises(ExpressionError, match=f"at most {MAX_LENGTH} are accepted") as info:
        evaluate(_sum(1000))
    assert len(str(info.value)) < 300  # the text is shown cut short
    assert isinstance(info.value, KinematicaError)
    data = _joints(1)
    data["joints"][0]["theta"] = _sum(1000)
    with pytest.raises(RobotFileError, match="joint 1, key 'theta': the expression is 3998"):
        parse_robot_dict(data)


def test_long_expressions_need_no_deep_recursion() -> None:
    # A sum is one node with many terms, not a chain of nested nodes: an
    # expression of the longest accepted length evaluates with little stack.
    limit = sys.getrecursionlimit()
    depth = len(__import__("inspect").stack())
    sys.setrecursionlimit(depth + 60)
    try:
        form = evaluate(_sum(MAX_LENGTH // 4))
        product = evaluate("*".join(["1"] * (MAX_LENGTH // 2)))
    finally:
        sys.setrecursionlimit(limit)
    assert form.coeffs == {"q1": 1.0} and form.const == MAX_LENGTH // 4 - 1
    assert product.const == 1.0


def test_depth_limit_still_holds_within_the_length_limit() -> None:
    assert evaluate("(" * MAX_DEPTH + "1" + ")" * MAX_DEPTH).const == 1.0
    with pytest.raises(ExpressionError, match=f"nested deeper than {MAX_DEPTH}"):
        evaluate("(" * (MAX_DEPTH + 1) + "1" + ")" * (MAX_DEPTH + 1))
