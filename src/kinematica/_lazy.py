"""A package's public names, each written once: imported, or imported on first use (PEP 562).

A package's ``__init__`` imports its public names; those it imports under
``if TYPE_CHECKING:`` (what type checkers read) load when first asked for
instead, from the module that block names: ``from kinematica.io import read_urdf``
imports ``kinematica.io.urdf`` then, and the name stays bound after. Its last
line, ``__getattr__, __dir__, __all__ = exports(__name__)``, makes the rest from
those imports: ``__all__`` is every public name imported either way.
"""

from __future__ import annotations

import ast
import importlib
import importlib.util
import sys
from collections.abc import Callable
from types import ModuleType
from typing import Any

__all__ = ["exports"]


def _first_use(package: ModuleType) -> dict[str, str]:
    """Each name the package's ``if TYPE_CHECKING:`` block imports, and its module."""
    source = package.__spec__.loader.get_source(package.__name__)  # type: ignore[union-attr]
    where: dict[str, str] = {}
    for node in ast.parse(source or "").body:
        if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING":
            for imported in node.body:
                if isinstance(imported, ast.ImportFrom) and imported.module is not None:
                    for alias in imported.names:
                        where[alias.asname or alias.name] = imported.module
    return where


def exports(
    package: str,
) -> tuple[Callable[[str], Any], Callable[[], list[str]], list[str]]:
    """The ``(__getattr__, __dir__, __all__)`` of a package, from its imports.

    Args:
        package: The package's ``__name__``, called at the end of its ``__init__``.

    Returns:
        ``__getattr__`` (a name of the ``if TYPE_CHECKING:`` block, imported from its
        module; any other submodule of the package, imported by its name), ``__dir__``,
        and ``__all__``: the public names imported (modules aside) and those of the block.
    """
    module = sys.modules[package]
    where = _first_use(module)
    public = [
        name
        for name, value in vars(module).items()
        if not name.startswith("_")
        and not isinstance(value, ModuleType)
        and value is not exports
        and name not in ("annotations", "TYPE_CHECKING")
    ]

    def get(name: str) -> Any:
        source = where.get(name)
        if source is None:
            # a submodule of the package not named above (``kinematica.dh.lines``): an
            # eager package that imported it had it as an attribute too
            if name.startswith("__") or importlib.util.find_spec(f"{package}.{name}") is None:
                raise AttributeError(f"module {package!r} has no attribute {name!r}")
            source = f"{package}.{name}"
        found = importlib.import_module(source)
        # a subpackage is its own value
        value = found if source == f"{package}.{name}" else getattr(found, name)
        setattr(module, name, value)  # later lookups skip this function
        return value

    def names() -> list[str]:
        return sorted(set(vars(module)) | set(where))

    return get, names, sorted({*public, *where})
