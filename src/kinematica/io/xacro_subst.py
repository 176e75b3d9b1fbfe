"""Substitutions and files of kinematica's xacro expander: ``${...}``, ``$(...)``, reading.

``${expr}`` is evaluated by :mod:`kinematica.io.xacro_expr`; ``$(find pkg)`` asks the
package map; ``$(arg x)``, ``$(dirname)`` and ``$(eval expr)`` are answered here, and
``$(env X)``/``$(optenv X D)`` only when the caller allows the environment. Files (the
included ones, the YAML ones) are read only inside the allowed folders, within the
size and count limits. :mod:`kinematica.io.xacro_expand` walks the elements.
"""

from __future__ import annotations

import os
import re
import time
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any, Final

from kinematica.io.packages import PackageMap
from kinematica.io.reading import read_limited
from kinematica.io.xacro_expr import (
    FUNCTIONS,
    Namespace,
    XacroExpressionError,
    evaluate,
    text_of,
)
from kinematica.io.xacro_scope import Scope, ScopeView, XacroError, auto_value
from kinematica.io.xacro_yaml import load_yaml
from kinematica.io.xml_parse import parse_xml

__all__ = ["ENV_REFUSED", "MAX_FILES", "MissingPackageError", "Substitutions"]

#: Most files (the file, its includes, YAML files) one expansion reads.
MAX_FILES: Final = 500

#: The message for ``$(env ...)`` without the caller's consent ({name}: the variable).
ENV_REFUSED: Final = (
    "reads the environment variable {name!r}: refused, kinematica expands xacro without the "
    "environment unless asked (xacro_env=True, --xacro-env on the command line)"
)

_LEXER: Final = re.compile(
    r"(?P<dollars>\$\$+[{(])|(?P<expr>\$\{[^}]*\})|(?P<ext>\$\([^)]*\))|(?P<text>[^$]+|\$[^{($]+|\$\Z)"
)


class Substitutions:
    """The files and substitutions of one expansion.

    It holds what the expansion may read (``roots`` and the package map), its
    arguments, and the characters and time it may use.
    """

    def __init__(
        self,
        packages: PackageMap,
        *,
        env: bool,
        max_chars: int,
        deadline: float,
        roots: list[Path],
    ) -> None:
        self.packages = packages
        self.env = env
        self.max_chars = max_chars
        self.deadline = deadline
        self.roots = roots
        self.files: list[Path] = []
        self.stack: list[int] = []  # indices into files: the file being read, innermost last
        self.args: dict[str, str] = {}
        self.chars = 0
        self.functions: dict[str, Callable[..., Any]] = {
            **FUNCTIONS,
            "load_yaml": self.load_yaml,
            "xacro.load_yaml": self.load_yaml,
            "xacro.arg": self.arg,
            "xacro.fatal": self.fatal,
            **{f"xacro.{name}": (lambda *_: "") for name in ("message", "warning", "error")},
        }

    # --- files ----------------------------------------------------------------------

    def current_dir(self) -> Path:
        """The folder of the file being read (relative paths start there)."""
        return self.files[self.stack[-1]].parent

    def readable(self, path: Path, what: str) -> Path:
        """``path`` resolved, if it is inside the folders a xacro file may read."""
        real = path.resolve()
        allowed = [*self.roots, *self.packages.folders()]
        if not any(real == root or root in real.parents for root in allowed):
            raise XacroError(
                f"{what} {str(path)!r} is outside the folders a xacro file may read (its own "
                "folder, its package's and those of the packages it names): refused; to allow "
                "a folder, name it as a package (--package NAME=DIR, packages= in Python)"
            )
        if len(self.files) >= MAX_FILES:
            raise XacroError(f"more than {MAX_FILES} files included or loaded: refused")
        return real

    def parse_file(self, path: Path) -> Any:
        """The root element of xacro file ``path``, each element marked with its line."""
        index = len(self.files)
        self.files.append(path)
        data = read_limited(path, self.max_chars, "xacro file", _file_error(path))
        return parse_xml(data, str(path), lines=str(index))

    def load_yaml(self, filename: Any) -> Any:
        """``load_yaml(filename)``: the data of a YAML file inside the allowed folders."""
        if not isinstance(filename, str):
            raise XacroError("load_yaml takes a file name")
        path = self.readable(self.current_dir() / filename, "the YAML file")
        self.files.append(path)
        data = read_limited(path, self.max_chars, "YAML file", _file_error(path))
        return load_yaml(data, str(path))

    # --- substitutions --------------------------------------------------------------

    def arg(self, name: Any) -> str:
        """``$(arg name)``: the argument's text."""
        if not isinstance(name, str) or name not in self.args:
            raise XacroError(f"undefined argument {name!r} (declare it with <xacro:arg>)")
        return self.args[name]

    @staticmethod
    def fatal(*words: Any) -> str:
        """``xacro.fatal(...)``: the file stops the expansion."""
        raise XacroError("the file stops the expansion: " + " ".join(map(str, words)))

    def check_time(self) -> None:
        """Refuse to go on past the expansion's deadline."""
        if time.monotonic() > self.deadline:
            raise XacroError("the expansion did not finish within its time limit: refused")

    def count(self, text: str) -> str:
        """``text``, counted against the characters the expansion may make."""
        self.chars += len(text)
        if self.chars > self.max_chars:
            raise XacroError(
                f"the expansion made more than {self.max_chars:,} characters of text: refused"
            )
        return text

    def text(self, text: str, scope: Scope) -> Any:
        """``text`` with its ``${...}`` and ``$(...)`` substituted; typed when it is one of them."""
        results: list[Any] = []
        pos = 0
        while pos < len(text):
            m = _LEXER.match(text, pos)
            if m is None:
                raise XacroError(f"invalid substitution: {text[pos : pos + 60]!r}")
            pos = m.end()
            piece = m.group()
            if m.lastgroup == "dollars":
                results.append(piece[1:])
            elif m.lastgroup == "expr":
                inner = _text(self.text(piece[2:-1], scope))
                results.append(self.expression(inner, _lookup(scope), self.functions))
            elif m.lastgroup == "ext":
                results.append(self.extension(_text(self.text(piece[2:-1], scope))))
            else:
                results.append(piece)
        if len(results) == 1:
            return results[0]
        return self.count("".join(map(_text, results)))

    def string(self, text: str, scope: Scope) -> str:
        """``text`` substituted, as text (an attribute's value)."""
        return self.count(_text(self.text(text, scope)))

    def expression(
        self, text: str, lookup: Callable[[str], Any], functions: Mapping[str, Any]
    ) -> Any:
        """The value of expression ``text``; one :class:`XacroError` if refused or wrong."""
        self.check_time()
        try:
            return evaluate(text, lookup, functions)
        except XacroExpressionError as exc:
            raise XacroError(exc.describe()) from exc

    def extension(self, content: str) -> str:
        """``$(content)``: ``find``, ``arg``, ``dirname``, ``eval``, ``env``, ``optenv``."""
        if content.startswith("eval "):
            return _text(self.expression(content[5:], self.eval_lookup, self.eval_functions()))
        words = content.split()
        command, args = (words[0], words[1:]) if words else ("", [])
        if command == "find" and len(args) == 1:
            folder = self.packages.find(args[0])
            if folder is None:
                raise MissingPackageError(args[0])
            return str(folder)
        if command == "arg" and len(args) == 1:
            return self.arg(args[0])
        if command == "dirname" and not args:
            return str(self.current_dir().resolve())
        if command in ("env", "optenv") and args:
            if not self.env:
                raise XacroError(ENV_REFUSED.format(name=args[0]))
            if command == "env":
                if args[0] not in os.environ:
                    raise XacroError(f"the environment variable {args[0]!r} is not set")
                return os.environ[args[0]]
            return os.environ.get(args[0], " ".join(args[1:]))
        raise XacroError(
            f"unknown or malformed substitution $({content}): kinematica expands $(find PKG), "
            "$(arg NAME), $(dirname), $(eval EXPR), and $(env NAME)/$(optenv NAME DEFAULT) "
            "when allowed"
        )

    def eval_lookup(self, name: str) -> Any:
        """Names in ``$(eval ...)``: ``true``, ``false`` and the arguments (typed)."""
        if name in ("true", "false"):
            return name == "true"
        if name in self.args:
            return auto_value(self.args[name])
        raise KeyError(name)

    def eval_functions(self) -> dict[str, Callable[..., Any]]:
        """Functions in ``$(eval ...)``: :data:`FUNCTIONS`, ``arg()`` and ``dirname()``."""

        def arg(name: Any) -> Any:
            return auto_value(self.arg(name))

        def dirname() -> str:
            return str(self.current_dir().resolve())

        return {**FUNCTIONS, "arg": arg, "dirname": dirname}


def _lookup(scope: Scope) -> Callable[[str], Any]:
    """Property lookup for expressions: a namespace scope is seen as ``ns.name``."""

    def lookup(name: str) -> Any:
        value = scope.lookup(name)
        return Namespace(name, ScopeView(value)) if isinstance(value, Scope) else value

    return lookup


def _text(value: Any) -> str:
    try:
        return text_of(value)
    except ValueError as exc:
        raise XacroError(str(exc)) from exc


class MissingPackageError(XacroError):
    """A ``$(find pkg)`` no rule of the package map answers."""

    def __init__(self, name: str) -> None:
        super().__init__(name)
        self.name = name


def _file_error(path: Path) -> Callable[[str], Exception]:
    return lambda reason: XacroError(f"{path}: {reason}")
