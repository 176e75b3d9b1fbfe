"""Frozen dataclasses whose classes cost next to nothing to make.

``@dataclass(frozen=True)`` reads every field's annotation and default, then
writes the source of ``__init__``, ``__repr__``, ``__setattr__`` and
``__delattr__`` (``__eq__`` and ``__hash__`` too with ``eq=True``) and compiles
it with ``exec``, when the class statement runs: 0.3 to 0.7 ms a class on a
2-core machine, in a fresh process. The first ``robot.ik`` of a process made a
dozen such classes: half of its time.

:func:`record` makes the same frozen dataclass with methods written once here,
which read a plan of the fields (their names, defaults and default factories,
taken from the class body: 0.01 ms) at each call, and leaves the dataclass's own
bookkeeping (``__dataclass_fields__``) to the first thing that asks for it:
``dataclasses.fields``, ``replace``, ``asdict`` and ``is_dataclass`` then run
:func:`dataclasses.dataclass` on the class (without generating methods) and work
as on any dataclass. A class that is built in a hot path may write its own
``__init__`` (storing its fields with :func:`store`: records are frozen).

What differs from ``@dataclass(frozen=True)``: ``inspect.signature`` of a record
class reads ``(*args, **kwargs)`` unless it writes its ``__init__`` (calls take the
same arguments, positional or by name, and fail with the same ``TypeError``); a
record class declares its own fields, none inherited, and no ``ClassVar``.
"""

from __future__ import annotations

import _thread
import dataclasses
import inspect
from collections.abc import Callable
from typing import Any, TypeVar, dataclass_transform, overload

__all__ = ["record", "replace", "store"]

T = TypeVar("T", bound=type)
R = TypeVar("R")

#: Each record class's field names, the required ones, default values and default factories.
_PLAN = "__record_plan__"
#: Where :func:`dataclasses.fields` and the rest look for a dataclass's fields.
_FIELDS = "__dataclass_fields__"


def store(obj: object, **fields: Any) -> None:
    """Set fields of a new record (in a hand-written ``__init__``; records are frozen)."""
    obj.__dict__.update(fields)


def _init(self: Any, /, *args: Any, **kwargs: Any) -> None:
    """Bind the arguments to the fields as a dataclass's generated ``__init__`` does."""
    names, required, defaults, factories = getattr(type(self), _PLAN)
    if len(args) > len(names):
        raise TypeError(
            f"{type(self).__qualname__}.__init__() takes {len(names) + 1} positional "
            f"arguments but {len(args) + 1} were given"
        )
    values = dict(zip(names, args, strict=False))
    if kwargs:
        if not values.keys().isdisjoint(kwargs):
            twice = next(k for k in kwargs if k in values)
            raise TypeError(
                f"{type(self).__qualname__}.__init__() got multiple values for argument {twice!r}"
            )
        if not kwargs.keys() <= set(names):
            unknown = next(k for k in kwargs if k not in names)
            raise TypeError(
                f"{type(self).__qualname__}.__init__() got an unexpected keyword argument "
                f"{unknown!r}"
            )
        values.update(kwargs)
    d = self.__dict__
    if len(values) < len(names):
        if not required <= values.keys():
            missing = [k for k in names if k in required and k not in values]
            raise TypeError(
                f"{type(self).__qualname__}.__init__() missing {len(missing)} required "
                "argument(s): " + ", ".join(map(repr, missing))
            )
        d.update(defaults)
        for key, factory in factories.items():
            if key not in values:
                d[key] = factory()
    d.update(values)


def _setattr(self: Any, name: str, value: Any) -> None:
    raise dataclasses.FrozenInstanceError(f"cannot assign to field {name!r}")


def _delattr(self: Any, name: str) -> None:
    raise dataclasses.FrozenInstanceError(f"cannot delete field {name!r}")


def _repr(self: Any) -> str:
    shown = (f"{f.name}={getattr(self, f.name)!r}" for f in dataclasses.fields(self) if f.repr)
    return f"{type(self).__qualname__}({', '.join(shown)})"


def replace(obj: R, /, **changes: Any) -> R:
    """``dataclasses.replace`` of a record, without making its class a dataclass first.

    The same new record (its ``__init__`` takes every field, the changed ones from
    ``changes``), and the same ``TypeError`` for a name that is no field; what it
    saves is the class's first ``dataclasses`` look-up (0.1-0.2 ms, in a builder on
    the first ``robot.ik`` of a process). Records are also ``__replace__``-able
    (``copy.replace`` of Python 3.13).
    """
    values = {name: obj.__dict__[name] for name in getattr(type(obj), _PLAN)[0]}
    values.update(changes)
    return type(obj)(**values)


def _values(obj: Any) -> tuple[Any, ...]:
    return tuple(getattr(obj, name) for name in getattr(type(obj), _PLAN)[0])


def _eq(self: Any, other: Any) -> Any:
    if other.__class__ is not self.__class__:
        return NotImplemented
    return _values(self) == _values(other)


def _hash(self: Any) -> int:
    return hash(_values(self))


class _Fields:
    """A record class's ``__dataclass_fields__`` before anything asked for it.

    The first look-up makes the class a dataclass (fields only: every method is
    already there), which puts the real mapping in this descriptor's place.
    """

    def __get__(self, obj: object, cls: type) -> dict[str, dataclasses.Field[Any]]:
        with _MAKING:  # once: a second pass would read the defaults the first took away
            if cls.__dict__[_FIELDS] is self:
                dataclasses.dataclass(init=False, repr=False, eq=False)(cls)
        fields: dict[str, dataclasses.Field[Any]] = cls.__dict__[_FIELDS]
        return fields


#: Held while a record class is made a dataclass (two threads may ask at once).
_MAKING = _thread.allocate_lock()  # (the threading module: 0.7 ms to import)


_LAZY_FIELDS = _Fields()


def _make(cls: T, eq: bool) -> T:
    if any(hasattr(base, _FIELDS) for base in cls.__mro__[1:]):
        raise TypeError(f"record {cls.__qualname__}: a record inherits no fields")
    names: list[str] = []
    defaults: dict[str, Any] = {}
    factories: dict[str, Callable[[], Any]] = {}
    for name, annotation in inspect.get_annotations(cls).items():
        if "ClassVar" in str(annotation) or "InitVar" in str(annotation):
            raise TypeError(f"record {cls.__qualname__}: {name} is a ClassVar or InitVar")
        names.append(name)
        value = cls.__dict__.get(name, dataclasses.MISSING)
        if isinstance(value, dataclasses.Field):
            if value.default is not dataclasses.MISSING:
                defaults[name] = value.default
            elif value.default_factory is not dataclasses.MISSING:
                factories[name] = value.default_factory
        elif value is not dataclasses.MISSING:
            defaults[name] = value
    required = frozenset(names) - defaults.keys() - factories.keys()
    setattr(cls, _PLAN, (tuple(names), required, defaults, factories))
    methods: dict[str, Any] = {
        "__init__": _init,
        "__repr__": _repr,
        "__setattr__": _setattr,
        "__delattr__": _delattr,
        "__replace__": replace,
        "__match_args__": tuple(names),
        _FIELDS: _LAZY_FIELDS,
    }
    if eq:
        methods |= {"__eq__": _eq, "__hash__": _hash}
    for key, method in methods.items():
        if key not in cls.__dict__:  # the class's own comes first
            setattr(cls, key, method)
    return cls


@overload
def record(cls: T, /) -> T: ...
@overload
def record(*, eq: bool = False) -> Callable[[T], T]: ...
@dataclass_transform(
    frozen_default=True, eq_default=False, field_specifiers=(dataclasses.field, dataclasses.Field)
)
def record(cls: T | None = None, /, *, eq: bool = False) -> T | Callable[[T], T]:
    """A frozen dataclass of ``cls``, its methods shared (see the module's docstring).

    Args:
        cls: The class, as ``@record``; or none, as ``@record(eq=True)``.
        eq: Compare and hash by the fields' values (as ``@dataclass(frozen=True)``);
            False: by identity (as ``eq=False``).

    Returns:
        The class (or the decorator). Methods the class defines itself are kept.
    """
    if cls is None:
        return lambda c: _make(c, eq)
    return _make(cls, eq)
