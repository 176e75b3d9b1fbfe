"""The tables of kinematica's xacro expander: properties, macros, conversions of text.

Properties follow xacro's scoping and lazy evaluation; the conversions are the small
ones xacro applies to text (literals, booleans, arguments in ``$(eval)``).

Property values are kept as written and evaluated at their first use
("lazy", as xacro does), then kept evaluated; a property that needs itself
while being evaluated is a circular definition. Each macro call and each
``<xacro:include ns=...>`` opens a scope whose parent is where it was called.
"""

from __future__ import annotations

import keyword
import re
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any, Final

__all__ = [
    "MAX_PARAMS_LENGTH",
    "Macro",
    "Macros",
    "Scope",
    "ScopeView",
    "XacroError",
    "auto_value",
    "boolean",
    "literal",
    "parse_params",
]

_IDENTIFIER: Final = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


class XacroError(Exception):
    """A problem in a xacro file; the expander adds the file and the line."""


def literal(value: Any) -> Any:
    """A property's text as xacro types it: ``'quoted'`` text, int, float, boolean, or text.

    Text holding ``_`` stays text (``1_000`` is not a number to xacro).
    """
    if not isinstance(value, str):
        return value
    if len(value) >= 2 and value[0] == "'" and value[-1] == "'":
        return value[1:-1]
    if "_" in value:
        return value
    for convert in (int, float):
        try:
            return convert(value)
        except ValueError:
            pass
    if value in ("true", "True"):
        return True
    if value in ("false", "False"):
        return False
    return value


def auto_value(value: str) -> Any:
    """An argument's text as ``$(eval ...)`` sees it: float (with a dot), int, bool, or text."""
    try:
        return float(value) if "." in value else int(value)
    except ValueError:
        pass
    if value.lower() in ("true", "false"):
        return value.lower() == "true"
    return value


def boolean(value: Any, condition: str) -> bool:
    """The truth of a condition's value as xacro reads it (``true``, ``1``, ``False``, ``0``...)."""
    if isinstance(value, str):
        if value in ("true", "True"):
            return True
        if value in ("false", "False"):
            return False
        try:
            return bool(int(value))
        except ValueError:
            pass
        raise XacroError(
            f"the condition {condition!r} evaluated to {value!r}, which is not a boolean"
        )
    return bool(value)


def valid_name(name: Any) -> bool:
    """Whether ``name`` may name a property (an identifier, not a keyword, no ``__``)."""
    return (
        isinstance(name, str)
        and _IDENTIFIER.fullmatch(name) is not None
        and not keyword.iskeyword(name)
        and not name.startswith("__")
    )


class Scope:
    """Properties of one scope, with a parent scope to look further in.

    Args:
        parent: The enclosing scope, or None for the file's global scope.
        evaluate: Evaluates a property's text (``eval_text``) in a scope.
        namespace: A scope opened by ``<xacro:include ns=...>`` (reached as ``ns.name``).
    """

    def __init__(
        self,
        parent: Scope | None,
        evaluate: Callable[[str, Scope], Any] | None = None,
        *,
        namespace: bool = False,
    ) -> None:
        self.parent = parent
        self.values: dict[str, Any] = {}
        self.lazy: set[str] = set()
        self.namespace = namespace
        inherited = parent._evaluate if parent is not None else None
        self._evaluate: Callable[[str, Scope], Any] | None = (
            evaluate if evaluate is not None else inherited
        )
        self._resolving: list[str] = [] if parent is None else parent._resolving

    def lookup(self, name: str) -> Any:
        """The value of ``name`` here or in a parent scope; ``KeyError`` when none has it."""
        scope: Scope | None = self
        while scope is not None:
            if name in scope.values:
                return scope._resolve(name)
            scope = scope.parent
        raise KeyError(name)

    def __contains__(self, name: str) -> bool:
        scope: Scope | None = self
        while scope is not None:
            if name in scope.values:
                return True
            scope = scope.parent
        return False

    def _resolve(self, name: str) -> Any:
        if name in self.lazy:
            if name in self._resolving:
                chain = " -> ".join([*self._resolving, name])
                raise XacroError(f"circular property definition: {chain}")
            self._resolving.append(name)
            try:
                assert self._evaluate is not None
                self.values[name] = literal(self._evaluate(self.values[name], self))
            finally:
                self._resolving.remove(name)
            self.lazy.discard(name)
        return self.values[name]

    def set(self, name: str, value: Any, *, lazy: bool) -> None:
        """Define ``name`` here; text that is not a literal is evaluated later when ``lazy``."""
        value = literal(value)
        self.values[name] = value
        if lazy and isinstance(value, str):
            self.lazy.add(name)
        else:
            self.lazy.discard(name)

    def remove(self, name: str) -> None:
        """Remove ``name`` from this scope and every enclosing one."""
        scope: Scope | None = self
        while scope is not None:
            scope.values.pop(name, None)
            scope.lazy.discard(name)
            scope = scope.parent

    def top(self) -> Scope:
        """The file's global scope."""
        scope = self
        while scope.parent is not None:
            scope = scope.parent
        return scope


class ScopeView(Mapping[str, Any]):
    """A namespace scope as the members of ``ns.name`` in an expression."""

    def __init__(self, scope: Scope) -> None:
        self.scope = scope

    def __getitem__(self, name: str) -> Any:
        if name in self.scope.values:
            return self.scope._resolve(name)
        raise KeyError(name)

    def __iter__(self) -> Iterator[str]:
        return iter(self.scope.values)

    def __len__(self) -> int:
        return len(self.scope.values)


@dataclass
class Macro:
    """A macro: its parameters (``*block`` and ``**blocks`` ones too), defaults and body.

    Attributes:
        name: As defined.
        params: Parameter names in order, with their ``*``/``**`` marks.
        defaults: Parameter -> (forwarded from the caller's scope, default text or None).
        body: The ``<xacro:macro>`` element (copied at each call).
        where: The file and line of the definition, for messages.
    """

    name: str
    params: list[str]
    defaults: dict[str, tuple[bool, str | None]]
    body: Any
    where: str = ""


@dataclass
class Macros:
    """Macros of one scope, with the enclosing scope's behind them and namespaces by name."""

    parent: Macros | None = None
    table: dict[str, Macro] = field(default_factory=dict)
    namespaces: dict[str, Macros] = field(default_factory=dict)

    def find(self, name: str) -> Macro | None:
        """The macro ``name`` here or in an enclosing scope."""
        macros: Macros | None = self
        while macros is not None:
            if name in macros.table:
                return macros.table[name]
            macros = macros.parent
        return None

    def namespace(self, name: str) -> Macros | None:
        """The macros of namespace ``name`` here or in an enclosing scope."""
        macros: Macros | None = self
        while macros is not None:
            if name in macros.namespaces:
                return macros.namespaces[name]
            macros = macros.parent
        return None


#: Longest ``params`` of a macro read (real ones are a few hundred characters).
MAX_PARAMS_LENGTH: Final = 10_000

# One way only to match each piece of a default (``${...}`` is never also read character
# by character), so that a default that does not end cannot make the match backtrack
# exponentially.
_PARAM_DEFAULT: Final = re.compile(
    r"""\s*(?P<name>[^\s:=]+?)\s*:?=\s*(?P<forward>\^\|?)?
    (?P<default>(?:\$\{[^}]*\}|\$\([^)]*\)|'[^']*'|"[^"]*"|[^\s'"$]|\$(?![{(]))*)(?:\s+|$)""",
    re.VERBOSE,
)


def parse_params(text: str) -> tuple[list[str], dict[str, tuple[bool, str | None]]]:
    """A macro's ``params``: ``a b:=1 c:=^ d:=^|2 *block **blocks`` as names and defaults.

    A default may be quoted (``'0 0 0'``) and is kept as written, quotes
    included (a property's ``'...'`` is text, as in xacro).

    Raises:
        XacroError: a parameter name that is not an identifier.
    """
    if len(text) > MAX_PARAMS_LENGTH:
        raise XacroError(
            f"the macro's params are {len(text):,} characters long; at most "
            f"{MAX_PARAMS_LENGTH:,} are read"
        )
    names: list[str] = []
    defaults: dict[str, tuple[bool, str | None]] = {}
    rest = text
    while rest.strip():
        m = _PARAM_DEFAULT.match(rest)
        if m is not None:
            name = m.group("name")
            default = m.group("default") or None
            defaults[name] = (m.group("forward") is not None, default)
            rest = rest[m.end() :]
        else:
            name, _, rest = rest.strip().partition(" ")
        bare = name.lstrip("*")
        if not valid_name(bare) or len(name) - len(bare) > 2:
            shown = name if len(name) <= 60 else name[:57] + "..."
            raise XacroError(f"the macro parameter {shown!r} is not a name")
        names.append(name)
    return names, defaults
