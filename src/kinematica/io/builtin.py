"""Built-in robot models, shipped as TOML files inside the package.

Each model is a robot file in ``kinematica/io/models/NAME.toml`` whose comments
give its source (book, paper or datasheet) and the origin of its joint limits.
Files are read with :mod:`importlib.resources`, so they work from a wheel or a
zip as well as from a source checkout.
"""

from __future__ import annotations

import difflib
import tomllib
from importlib.resources import files
from importlib.resources.abc import Traversable

from kinematica.errors import RobotFileError, UnknownRobotError
from kinematica.io._parse import parse_robot_dict
from kinematica.io.spec import RobotSpec

__all__ = ["builtin_names", "builtin_path", "read_builtin"]

_SUFFIX = ".toml"


def _models() -> Traversable:
    return files("kinematica.io").joinpath("models")


def _normalize(name: str) -> str:
    return name.strip().lower().replace("_", "-")


def builtin_names() -> list[str]:
    """The names of the built-in robot models, sorted."""
    return sorted(
        entry.name.removesuffix(_SUFFIX)
        for entry in _models().iterdir()
        if entry.is_file() and entry.name.endswith(_SUFFIX)
    )


def builtin_path(name: str) -> Traversable:
    """The data file of built-in model ``name`` (case and ``_``/``-`` ignored).

    Raises:
        UnknownRobotError: no built-in model has that name; the message lists
            the available ones and suggests the closest.
    """
    names = builtin_names()
    key = _normalize(name) if isinstance(name, str) else ""
    if key not in names:
        close = difflib.get_close_matches(key, names, n=1, cutoff=0.5)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        raise UnknownRobotError(
            f"no built-in robot named {name!r}{hint}; built-in robots: {', '.join(names)}"
        )
    return _models().joinpath(key + _SUFFIX)


def read_builtin(name: str) -> RobotSpec:
    """The :class:`RobotSpec` of built-in model ``name``.

    Its ``source`` is ``"builtin:NAME"``.

    Raises:
        UnknownRobotError: no built-in model has that name.
    """
    path = builtin_path(name)
    key = path.name.removesuffix(_SUFFIX)
    source = f"builtin:{key}"
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except tomllib.TOMLDecodeError as exc:  # a packaging defect, reported like a file error
        raise RobotFileError(f"not valid TOML: {exc}", path=source) from exc
    return parse_robot_dict(data, source=source)
