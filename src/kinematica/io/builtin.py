"""Built-in robot models, shipped as TOML files inside the package.

Each model is a robot file in ``kinematica/io/models/NAME.toml`` whose comments
give its source (book, paper or datasheet) and the origin of its joint limits.
They are read from the folder beside this module: the package holds a compiled
extension, so it is always installed as files, never imported from a zip
(:mod:`importlib.resources` and the zip reader it brings would slow every start).
"""

from __future__ import annotations

import tomllib
from pathlib import Path

from kinematica.errors import RobotFileError, UnknownRobotError
from kinematica.io._parse import parse_robot_dict
from kinematica.io.spec import RobotSpec

__all__ = ["builtin_names", "builtin_path", "read_builtin"]

_SUFFIX = ".toml"


_MODELS = Path(__file__).resolve().parent / "models"


def builtin_names() -> list[str]:
    """The names of the built-in robot models, sorted."""
    return sorted(
        entry.name.removesuffix(_SUFFIX)
        for entry in _MODELS.iterdir()
        if entry.is_file() and entry.name.endswith(_SUFFIX)
    )


def builtin_path(name: str) -> Path:
    """The data file of built-in model ``name`` (case and ``_``/``-`` ignored).

    Raises:
        UnknownRobotError: no built-in model has that name; the message lists
            the available ones and suggests the closest.
    """
    names = builtin_names()
    key = name.strip().lower().replace("_", "-") if isinstance(name, str) else ""
    if key not in names:
        import difflib  # only for the message: a known name never needs it

        close = difflib.get_close_matches(key, names, n=1, cutoff=0.5)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        raise UnknownRobotError(
            f"no built-in robot named {name!r}{hint}; built-in robots: {', '.join(names)}"
        )
    return _MODELS / (key + _SUFFIX)


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
