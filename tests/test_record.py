"""kinematica._record: frozen dataclasses made without generated code behave as dataclasses.

Each record class is checked against the same class made by ``@dataclass(frozen=True)``:
the same fields, ``replace``, ``asdict``, ``repr``, equality and hash, frozenness, the
same ``TypeError`` for a bad call, pickling.
"""

from __future__ import annotations

import copy
import dataclasses
import pickle
from dataclasses import dataclass, field
from typing import Any

import pytest

from kinematica._record import record, replace, store


@record
class Plain:
    """A record compared by identity."""

    a: int
    b: str
    c: float = 1.5
    d: dict[str, int] = field(default_factory=dict, repr=False)


@dataclass(frozen=True, eq=False)
class PlainDC:
    """The same as a frozen dataclass."""

    a: int
    b: str
    c: float = 1.5
    d: dict[str, int] = field(default_factory=dict, repr=False)


@record(eq=True)
class Valued:
    """A record compared by value."""

    a: int
    b: str
    c: float = 1.5
    d: tuple[int, ...] = field(default_factory=tuple, repr=False)


@dataclass(frozen=True)
class ValuedDC:
    """The same as a frozen dataclass."""

    a: int
    b: str
    c: float = 1.5
    d: tuple[int, ...] = field(default_factory=tuple, repr=False)


def _pair(eq: bool) -> tuple[Any, Any]:
    """The same class as a record and as a frozen dataclass."""
    return (Valued, ValuedDC) if eq else (Plain, PlainDC)


@pytest.mark.parametrize("eq", [False, True])
def test_a_record_behaves_as_the_frozen_dataclass(eq: bool) -> None:
    mine, theirs = _pair(eq)
    assert dataclasses.is_dataclass(mine)
    d = (1, 2) if eq else {"k": 1}
    x, y = mine(1, "s", d=d), theirs(1, "s", d=d)
    assert [f.name for f in dataclasses.fields(x)] == [f.name for f in dataclasses.fields(y)]
    assert dataclasses.asdict(x) == dataclasses.asdict(y)
    assert repr(x) == repr(y).replace("DC(", "(") == f"{mine.__name__}(a=1, b='s', c=1.5)"
    assert dataclasses.replace(x, b="t").b == "t" and x.b == "s"
    assert mine(2, "u").d == theirs(2, "u").d  # the factory's value
    assert mine.__match_args__ == theirs.__match_args__
    with pytest.raises(dataclasses.FrozenInstanceError):
        x.a = 3  # type: ignore[misc]
    with pytest.raises(dataclasses.FrozenInstanceError):
        del x.a
    assert (x == mine(1, "s", d=d)) is (y == theirs(1, "s", d=d)) is eq
    if eq:
        assert hash(x) == hash(mine(1, "s", d=d))
    else:
        assert hash(x) != hash(mine(1, "s", d=d)) or x is not mine(1, "s", d=d)
    back = pickle.loads(pickle.dumps(x))
    assert dataclasses.asdict(back) == dataclasses.asdict(x)
    assert copy.copy(x).a == 1


def test_a_hashable_record_hashes_by_value() -> None:
    @record(eq=True)
    class P:
        x: float = 1.0
        y: float = 2.0

    assert P() == P(1.0, 2.0) and P() != P(1.0, 3.0)
    assert {P(): "found"}[P(1.0, y=2.0)] == "found"


@pytest.mark.parametrize(
    ("args", "kwargs"),
    [((), {}), ((1, "s", 1.5, {}, 9), {}), ((1,), {"a": 2}), ((1, "s"), {"zz": 3})],
)
def test_bad_calls_fail_as_the_dataclass_s(args: tuple[Any, ...], kwargs: dict[str, Any]) -> None:
    mine, theirs = _pair(False)
    with pytest.raises(TypeError) as theirs_error:
        theirs(*args, **kwargs)  # a, b required; c, d not
    with pytest.raises(TypeError) as mine_error:
        mine(*args, **kwargs)
    # the same complaint: "missing 2", "takes ...", "got multiple", "got an unexpected"
    theirs_words = str(theirs_error.value).split("()")[1].split()
    mine_words = str(mine_error.value).split("()")[1].split()
    same = 1 if theirs_words[0] == "takes" else 2
    assert theirs_words[:same] == mine_words[:same]


def test_fields_are_made_when_first_asked_for_and_a_hand_written_init_is_kept() -> None:
    @record
    class Q:
        a: int
        b: int = 2

        def __init__(self, a: int, b: int = 2) -> None:
            store(self, a=a, b=b)

    assert "__dataclass_fields__" not in Q.__dict__ or not isinstance(
        Q.__dict__["__dataclass_fields__"], dict
    )
    q = Q(1)
    assert (q.a, q.b) == (1, 2)
    assert dataclasses.replace(q, b=5).b == 5
    assert isinstance(Q.__dict__["__dataclass_fields__"], dict)  # made by replace


@pytest.mark.parametrize("eq", [False, True])
def test_replace_is_dataclasses_replace_without_making_the_dataclass(eq: bool) -> None:
    @record(eq=eq)
    class R:
        a: int
        b: str = "s"
        c: list[int] = field(default_factory=list)

    r = R(1, c=[3])
    new = replace(r, b="t")
    assert not isinstance(R.__dict__["__dataclass_fields__"], dict)  # still not made
    assert (new.a, new.b, new.c) == (1, "t", [3]) and r.b == "s"
    assert vars(new) == vars(dataclasses.replace(r, b="t"))
    assert vars(r.__replace__(a=2)) == vars(dataclasses.replace(r, a=2))
    with pytest.raises(TypeError, match="unexpected keyword argument 'z'"):
        replace(r, z=1)


def test_what_a_record_does_not_take() -> None:
    @dataclass(frozen=True)
    class Base:
        a: int = 0

    with pytest.raises(TypeError, match="inherits no fields"):
        record(type("Sub", (Base,), {"__annotations__": {"b": "int"}}))
    with pytest.raises(TypeError, match="ClassVar"):
        record(type("C", (), {"__annotations__": {"k": "ClassVar[int]"}}))
