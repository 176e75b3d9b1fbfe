"""Robot files: a DH table as it is written on a slide, in YAML, JSON or TOML.

Example (YAML; JSON and TOML carry the same keys)::

    name: Seed 6-DOF arm
    convention: standard          # standard (Paul, distal) | modified (Craig, proximal)
    units: {angle: deg, length: m}
    parameters: {l1: 0.5, l2: 0.4, l3: 0.4, l4: 0.1}
    joints:                       # theta, d, a, alpha
      - {theta: q1,      d: l1, a: 0,  alpha: 90,  limits: [-160, 160]}
      - {theta: q2 + 90, d: 0,  a: l2, alpha: 0}
      ...
    tool: {xyz: [0, 0, 0.05]}

Keys:

- ``name`` (text; default: the file name without extension).
- ``convention``: ``standard`` (aliases ``dh``, ``paul``, ``distal``) or
  ``modified`` (aliases ``craig``, ``proximal``). In the modified convention
  each row holds a(i-1), alpha(i-1), theta(i), d(i), as Craig writes it. Left
  out, the table is read as standard and a
  :class:`~kinematica.errors.ConventionWarning` names the file and the key: the
  one rule of ``Robot.from_dh(rows)`` without ``convention=`` too.
- ``units``: ``{angle: deg | rad, length: m | mm}``; default **deg** and **m**.
  They apply to every number in the file: DH cells, parameters, limits, base
  and tool. Degrees become radians and millimetres metres on reading.
- ``parameters``: name -> number or expression of numbers, ``pi`` and the
  parameters above it, in file units; or ``{value: v, min: lo, max: hi}``, a
  design variable of a design template (bounds in ``RobotSpec.parameter_bounds``,
  the robot built at ``v``, midpoint if left out; see :mod:`kinematica.design`).
- ``joints`` (required, non-empty): one mapping per joint with ``theta``,
  ``d``, ``a``, ``alpha`` (numbers or expressions), and optionally
  ``limits: [lower, upper]`` (angle units for a revolute joint, length units
  for a prismatic one), ``name`` and ``type`` (``R``/``revolute`` or
  ``P``/``prismatic``; it must agree with where the variable appears).
  Joint *i*'s variable is ``q<i>``: it appears exactly once, with coefficient
  1, in ``theta`` (revolute) or ``d`` (prismatic), and nowhere else.
- ``base``, ``tool``: ``{xyz: [x, y, z], rpy: [roll, pitch, yaw]}`` (URDF's
  fixed-axis roll-pitch-yaw, R = Rz(yaw) Ry(pitch) Rx(roll); both optional) or
  ``{matrix: [[...], [...], [...], [0, 0, 0, 1]]}`` with the translation
  column in length units.
- ``description``, ``source`` (text; ``source`` says where the numbers come
  from and is kept as ``RobotSpec.reference``).

With ``units.angle: deg``, writing ``pi`` in an angle is an error: it almost
always means ``pi/2`` was meant as 90 degrees. Every mistake raises
:class:`~kinematica.errors.RobotFileError` naming the file, the joint, the key,
what was expected and what was found; user input never causes a traceback.
"""

from __future__ import annotations

import json
import os
import tomllib
from collections.abc import Callable
from pathlib import Path
from typing import Any

from kinematica.errors import ArgumentError, KinematicaError, RobotFileError
from kinematica.io._dump import dump_robot_dict, toml_dumps
from kinematica.io._parse import parse_robot_dict
from kinematica.io.atomic import unchanged, write_text_atomic
from kinematica.io.reading import ROBOT_FILE_SUFFIXES, file_kind, os_reason, read_limited
from kinematica.io.spec import RobotSpec

__all__ = [
    "MAX_FILE_SIZE",
    "dump_robot_dict",
    "dumps_robot_file",
    "load_robot_text",
    "parse_robot_dict",
    "read_robot_file",
    "write_robot_file",
]

#: Largest robot file read, in bytes (256 KiB). A DH table with limits and
#: comments is a few kilobytes; anything near this size is not a robot file,
#: and reading it would take long (YAML is read at about 1 MB per second).
MAX_FILE_SIZE = 262_144

_BOM = "\ufeff"

_YAML_MISSING = (
    "reading and writing YAML robot files needs PyYAML: pip install pyyaml "
    "(or pip install 'kinematica[yaml]'); JSON and TOML files need nothing extra"
)


class _DuplicateKeyError(Exception):
    def __init__(self, key: object, line: int | None = None) -> None:
        self.key = key
        self.line = line


def _import_yaml() -> Any:
    try:
        import yaml
    except ImportError as exc:
        raise KinematicaError(_YAML_MISSING) from exc
    return yaml


_YAML_MERGE = "tag:yaml.org,2002:merge"


def _load_yaml(text: str) -> object:
    yaml = _import_yaml()

    # libyaml's parser when PyYAML has it (about 5x faster), else the pure-Python one.
    safe_loader: Any = getattr(yaml, "CSafeLoader", yaml.SafeLoader)

    class UniqueKeyLoader(safe_loader):
        """SafeLoader refusing duplicate keys, with merge keys (``<<: *anchor``).

        Merging puts the merged pairs in front of a mapping's own pairs (which
        override them); only the own pairs are checked for duplicates.
        """

        def __init__(self, stream: str) -> None:
            super().__init__(stream)
            self.merged: dict[int, int] = {}  # id(node) -> number of merged pairs in front

        def flatten_mapping(self, node: Any) -> None:
            own = sum(1 for key_node, _ in node.value if key_node.tag != _YAML_MERGE)
            super().flatten_mapping(node)
            if len(node.value) > own:  # the first flattening of a node that merges
                self.merged[id(node)] = len(node.value) - own

        def construct_mapping(self, node: Any, deep: bool = False) -> Any:
            if isinstance(node, yaml.MappingNode):
                self.flatten_mapping(node)
            seen = set()
            for key_node, _ in node.value[self.merged.get(id(node), 0) :]:
                key = self.construct_object(key_node, deep=deep)
                try:
                    duplicate = key in seen
                except TypeError:  # an unhashable key; let PyYAML report it
                    break
                if duplicate:
                    raise _DuplicateKeyError(key, key_node.start_mark.line + 1)
                seen.add(key)
            return super().construct_mapping(node, deep=deep)

    try:
        return yaml.load(text, Loader=UniqueKeyLoader)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        problem = getattr(exc, "problem", None) or str(exc).splitlines()[0]
        where = f" (line {mark.line + 1}, column {mark.column + 1})" if mark is not None else ""
        lines = text.splitlines()
        if (
            mark is not None
            and mark.line < len(lines)
            and "\t" in lines[mark.line][: mark.column + 1]
        ):
            raise ValueError(
                f"not valid YAML: line {mark.line + 1} is indented with a tab; YAML indents "
                "with spaces only (replace the tab by spaces)"
            ) from exc
        raise ValueError(f"not valid YAML: {problem}{where}") from exc


def _yaml_dumps(data: dict[str, Any]) -> str:
    """YAML text for ``data``, with each joint on one line, as a DH table row."""
    yaml = _import_yaml()
    safe_dumper: Any = yaml.SafeDumper

    class RowDumper(safe_dumper):
        pass

    class Row(dict[str, Any]):
        pass

    def represent_row(dumper: Any, row: Row) -> Any:
        return dumper.represent_mapping("tag:yaml.org,2002:map", row, flow_style=True)

    def represent_str(dumper: Any, text: str) -> Any:
        # PyYAML writes some line breaks (U+0085, U+2028) raw even when quoting;
        # double quotes with escapes keep every string exact.
        odd = any(not ch.isprintable() or ch in "\x85\u2028\u2029" for ch in text)
        return dumper.represent_scalar("tag:yaml.org,2002:str", text, style='"' if odd else None)

    RowDumper.add_representer(Row, represent_row)
    RowDumper.add_representer(str, represent_str)
    data = dict(data, joints=[Row(j) for j in data["joints"]])
    text: str = yaml.dump(
        data, Dumper=RowDumper, sort_keys=False, allow_unicode=True, width=1000,
        default_flow_style=None,
    )  # fmt: skip
    return text


def _load_json(text: str) -> object:
    def unique(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
        out: dict[str, Any] = {}
        for key, value in pairs:
            if key in out:
                raise _DuplicateKeyError(key)
            out[key] = value
        return out

    try:
        return json.loads(text, object_pairs_hook=unique)
    except json.JSONDecodeError as exc:
        raise ValueError(
            f"not valid JSON: {exc.msg} (line {exc.lineno}, column {exc.colno})"
        ) from exc


def _load_toml(text: str) -> object:
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"not valid TOML: {exc}") from exc


_LOADERS: dict[str, Callable[[str], object]] = {
    ".yaml": _load_yaml,
    ".yml": _load_yaml,
    ".json": _load_json,
    ".toml": _load_toml,
}


def _suffix(path: Path) -> str:
    suffix = path.suffix.lower()
    if suffix not in _LOADERS:
        raise RobotFileError(
            f"unknown file type {suffix or '(no extension)'!r}: expected "
            f"{', '.join(ROBOT_FILE_SUFFIXES)}",
            path=str(path),
        )
    return suffix


def load_robot_text(text: str, suffix: str, *, source: str | None = None) -> RobotSpec:
    """Parse robot-file text in the format named by ``suffix``.

    Args:
        text: The file's content (a leading UTF-8 byte-order mark is ignored).
        suffix: ``".yaml"``, ``".yml"``, ``".json"`` or ``".toml"``.
        source: Where the text came from, for messages and ``RobotSpec.source``.

    Raises:
        RobotFileError: the text is longer than :data:`MAX_FILE_SIZE`, not
            valid in its format, or not a valid robot description.
    """
    if not isinstance(text, str) or not isinstance(suffix, str):
        raise ArgumentError(
            f"load_robot_text takes text and a suffix, got {type(text).__name__} "
            f"and {type(suffix).__name__}"
        )
    loader = _LOADERS.get(suffix.lower())
    if loader is None:
        raise RobotFileError(
            f"unknown file type {suffix!r}: expected {', '.join(ROBOT_FILE_SUFFIXES)}",
            path=source,
        )
    if len(text) > MAX_FILE_SIZE:
        raise RobotFileError(
            f"the file is {len(text):,} characters; robot files of at most "
            f"{MAX_FILE_SIZE:,} bytes are read",
            path=source,
        )
    text = text.removeprefix(_BOM)
    try:
        data = loader(text)
    except _DuplicateKeyError as exc:
        line = f" (line {exc.line})" if exc.line is not None else ""
        raise RobotFileError(
            f"the key {exc.key!r} appears twice in one mapping{line}", path=source
        ) from exc
    except RecursionError as exc:
        raise RobotFileError("the file is nested too deeply", path=source) from exc
    except ValueError as exc:  # syntax errors, and numbers too long to convert
        raise RobotFileError(str(exc), path=source) from exc
    if data is None:
        raise RobotFileError("the file is empty", path=source)
    return parse_robot_dict(data, source=source)


def read_robot_file(path: str | os.PathLike[str]) -> RobotSpec:
    """Read a robot file (``.yaml``/``.yml``, ``.json`` or ``.toml``).

    Args:
        path: The file. YAML needs PyYAML (``pip install pyyaml``).

    Returns:
        The robot description in radians and metres, with ``source`` the path.

    Raises:
        RobotFileError: the file is missing, unreadable, not a regular file
            (a directory, a FIFO, a device), larger than
            :data:`MAX_FILE_SIZE`, not valid in its format, or not a valid
            robot description.
        ArgumentError: ``path`` is not a path.
        KinematicaError: a YAML file and PyYAML is not installed.
    """
    p = _path(path)
    if p.is_dir():  # before its name's suffix: a folder is not a file of an unknown type
        raise RobotFileError("is a directory, not a robot file", path=str(p))
    suffix = _suffix(p)
    try:
        text = _read_bytes(p).decode("utf-8")
    except UnicodeDecodeError as exc:
        raise RobotFileError(
            f"not UTF-8 text (bad byte at position {exc.start})", path=str(p)
        ) from exc
    return load_robot_text(text, suffix, source=str(p))


def _path(path: object) -> Path:
    if not isinstance(path, str | os.PathLike):
        raise ArgumentError(f"expected a path (text or pathlib.Path), got {type(path).__name__}")
    return Path(path)


def _read_bytes(p: Path) -> bytes:
    """The bytes of a regular file of at most MAX_FILE_SIZE bytes, without a BOM."""
    data = read_limited(
        p, MAX_FILE_SIZE, "robot file", lambda reason: RobotFileError(reason, path=str(p))
    )
    return data.removeprefix(_BOM.encode("utf-8"))


def dumps_robot_file(spec: RobotSpec, suffix: str = ".yaml") -> str:
    """The text of ``spec`` as a robot file in the format named by ``suffix``.

    Args:
        spec: The robot description.
        suffix: ``".yaml"``/``".yml"`` (needs PyYAML), ``".json"`` or ``".toml"``.

    Raises:
        RobotFileError: unknown suffix.
        KinematicaError: YAML and PyYAML is not installed.
    """
    key = suffix.lower()
    if key not in _LOADERS:
        raise RobotFileError(
            f"unknown file type {suffix!r}: expected {', '.join(ROBOT_FILE_SUFFIXES)}"
        )
    data = dump_robot_dict(spec)
    if key == ".json":
        return json.dumps(data, indent=2, ensure_ascii=False) + "\n"
    if key == ".toml":
        return toml_dumps(data)
    return _yaml_dumps(data)


def write_robot_file(spec: RobotSpec, path: str | os.PathLike[str]) -> None:
    """Write ``spec`` as a robot file; the extension picks the format.

    ``read_robot_file(path)`` then gives back a spec equal to ``spec`` (see
    :func:`dump_robot_dict`).

    Args:
        spec: The robot description.
        path: Where to write: ``.json``, ``.toml``, or ``.yaml``/``.yml`` (needs
            PyYAML). An existing file is replaced.

    Raises:
        RobotFileError: unknown extension, ``path`` is not a regular file, or
            the file cannot be written.
        ArgumentError: ``spec`` is not a :class:`RobotSpec` (a ``Robot`` is
            saved by :meth:`kinematica.Robot.save`).
        KinematicaError: a YAML file and PyYAML is not installed.
    """
    if not isinstance(spec, RobotSpec):
        raise ArgumentError(
            f"expected a RobotSpec, got {type(spec).__name__}; to save a Robot, call "
            "robot.save(path) or kinematica.write_robot_file(robot, path)"
        )
    p = _path(path)
    suffix = _suffix(p)
    try:
        kind = file_kind(p.stat().st_mode)
    except OSError:  # missing (it will be created), or unreadable (open says why)
        kind = None
    if kind is not None:
        raise RobotFileError(f"is {kind}, not a robot file: not written", path=str(p))
    text = dumps_robot_file(spec, suffix)
    try:
        write_text_atomic(p, text)
    except (OSError, ValueError) as exc:
        raise RobotFileError(
            f"cannot write the file: {os_reason(exc)}; {unchanged(p)}", path=str(p)
        ) from exc
