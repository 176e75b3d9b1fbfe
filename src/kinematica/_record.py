"""Frozen dataclasses whose classes compile no code when they are made.

``@dataclass(frozen=True)`` writes the source of ``__init__``, ``__repr__``,
``__setattr__`` and ``__delattr__`` (``__eq__`` and ``__hash__`` too with
``eq=True``) and compiles it with ``exec`` when the class statement runs: 0.3 to
0.7 ms a class on a 2-core machine. The first ``robot.ik`` of a process made a
dozen such classes, half of its time. :func:`record` makes the same dataclass
(``dataclasses.fields``, ``replace`` and ``asdict`` work on it; ``is_dataclass``
is true) from the fields alone, 0.05 ms a class, with those methods written once
here: reading the fields at each call instead of compiled per class. A class
that is built in a hot path writes its own ``__init__`` (it then stores its
fields through :func:`store`).

The difference a user can see: ``inspect.signature`` of such a class reads
``(*args, **kwargs)`` unless it writes its ``__init__``; calls take the same
arguments, positional or by name, and fail with the same ``TypeError``.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any, TypeVar, cast, dataclass_transform, overload

__all__ = ["record", "store"]

T = TypeVar("T", bound=type)

#: Each record class's field names, the required ones, default values and default factories.
_PLAN = "__record_plan__"


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


def _values(obj: Any) -> tuple[Any, ...]:
    return tuple(getattr(obj, name) for name in getattr(type(obj), _PLAN)[0])


def _eq(self: Any, other: Any) -> Any:
    if other.__class__ is not self.__class__:
        return NotImplemented
    return _values(self) == _values(other)


def _hash(self: Any) -> int:
    return hash(_values(self))


def _make(cls: T, eq: bool) -> T:
    out = cast(T, dataclasses.dataclass(init=False, repr=False, eq=False)(cls))
    defaults: dict[str, Any] = {}
    factories: dict[str, Callable[[], Any]] = {}
    names = []
    for f in dataclasses.fields(out):
        names.append(f.name)
        if f.default is not dataclasses.MISSING:
            defaults[f.name] = f.default
        elif f.default_factory is not dataclasses.MISSING:
            factories[f.name] = f.default_factory
    required = frozenset(names) - defaults.keys() - factories.keys()
    setattr(out, _PLAN, (tuple(names), required, defaults, factories))
    methods: dict[str, Any] = {
        "__init__": _init,
        "__repr__": _repr,
        "__setattr__": _setattr,
        "__delattr__": _delattr,
    }
    if eq:
        methods |= {"__eq__": _eq, "__hash__": _hash}
    for key, method in methods.items():
        if key not in cls.__dict__:  # the class's own comes first
            setattr(out, key, method)
    return out


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
