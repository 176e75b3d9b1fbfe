"""Packages whose public names load on first use (PEP 562).

A package's ``__init__`` that imported every module of the package made any
import of one of them import them all: ``kinematica.dh.joints`` needs two small
modules of :mod:`kinematica.io`, and pulled in the URDF and xacro readers with
them (``subprocess``, ``xml``). A package built with :func:`exports` imports
nothing when it is imported; ``from kinematica.io import read_urdf`` imports
``kinematica.io.urdf`` then, and the name stays bound after. Type checkers read
the names from the package's ``if TYPE_CHECKING:`` imports.
"""

from __future__ import annotations

import importlib
import importlib.util
import sys
from collections.abc import Callable, Mapping
from typing import Any

__all__ = ["exports"]


def exports(
    package: str, where: Mapping[str, str]
) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """The ``(__getattr__, __dir__)`` of a package whose names load when first asked for.

    Args:
        package: The package's ``__name__``.
        where: Each public name and the module (absolute name) that defines it;
            a subpackage or submodule named for itself is the module. Any other
            submodule loads when asked for by its name, as an attribute.

    Returns:
        The two module-level functions to assign in the package's ``__init__``.
    """

    def get(name: str) -> Any:
        source = where.get(name)
        if source is None:
            # a submodule of the package not named above (``kinematica.dh.lines``): an
            # eager package that imported it had it as an attribute too
            if name.startswith("__") or importlib.util.find_spec(f"{package}.{name}") is None:
                raise AttributeError(f"module {package!r} has no attribute {name!r}")
            source = f"{package}.{name}"
        module = importlib.import_module(source)
        # a subpackage is its own value (``where["ik"] = "kinematica.ik"`` at the root)
        value = module if source == f"{package}.{name}" else getattr(module, name)
        setattr(sys.modules[package], name, value)  # later lookups skip this function
        return value

    def names() -> list[str]:
        return sorted(set(vars(sys.modules[package])) | set(where))

    return get, names
