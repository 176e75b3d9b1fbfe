"""Task files: CSV, JSON and numpy files of targets, or a region to sample.

A :class:`Task` is a batch of targets in the robot's base frame, in metres:
positions ``(N, 3)`` (the tool's orientation is free) or poses ``(N, 4, 4)``.
Files (:func:`load_task`):

- CSV, one target a row, an optional header row: 3 columns ``x, y, z``; 6
  columns ``x, y, z`` and three Euler angles (``euler``, ``degrees``); or 16
  columns, a 4x4 matrix row by row.
- JSON: ``{"positions": [[x, y, z], ...]}``, ``{"poses": [[x, y, z, a, b, g],
  ...], "euler": "ZYZ", "angle": "deg"}``, ``{"matrices": [4x4, ...]}``, a bare
  list of such rows, or a region ``{"region": "ring", "radius": 0.6,
  "count": 32, "center": [0, 0, 0], "normal": [0, 0, 1]}`` (also ``box`` with
  ``lower``/``upper`` and ``sphere`` with ``radius``/``surface``; ``seed`` for
  the sampled ones).
- numpy ``.npy`` (one array ``(N, 3)``, ``(N, 6)``, ``(N, 16)`` or
  ``(N, 4, 4)``) and ``.npz`` (the array ``targets``, or the only one).
"""

from __future__ import annotations

import csv
import json
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.design.task import Task, TaskError
from kinematica.errors import KinematicaError

__all__ = ["TASK_SUFFIXES", "as_task", "load_task"]

FloatArray = NDArray[np.float64]

#: File extensions :func:`load_task` reads.
TASK_SUFFIXES = (".csv", ".json", ".npy", ".npz")
_REGION_KEYS = {
    "ring": ("region", "radius", "count", "center", "normal", "orientation"),
    "box": ("region", "lower", "upper", "count", "seed", "orientation"),
    "sphere": ("region", "radius", "count", "center", "surface", "seed", "orientation"),
}


def _rows(table: FloatArray, where: str, *, euler: str, degrees: bool) -> Task:
    """A task from a ``(N, 3 | 6 | 16)`` table or ``(N, 4, 4)`` stack."""
    if table.ndim == 3 and table.shape[1:] == (4, 4):
        return Task(table, name=where)
    if table.ndim != 2 or table.shape[1] not in (3, 6, 16):
        raise TaskError(
            f"{where}: expected rows of 3 (x, y, z), 6 (x, y, z + Euler angles) or 16 "
            f"(a 4x4 matrix) numbers, found shape {table.shape}"
        )
    bad = np.argwhere(~np.isfinite(table))
    if bad.size:
        raise TaskError(f"{where}: row {bad[0][0] + 1}, column {bad[0][1] + 1} is not finite")
    try:
        if table.shape[1] == 3:
            return Task(table, name=where)
        if table.shape[1] == 6:
            return Task.from_poses(table, euler=euler, degrees=degrees, name=where)
        return Task(table.reshape(-1, 4, 4), name=where)
    except KinematicaError as exc:
        raise TaskError(f"{where}: {exc}") from exc


def _read_csv(path: Path, *, euler: str, degrees: bool) -> Task:
    with path.open(newline="", encoding="utf-8") as f:
        rows = [r for r in csv.reader(f) if r and any(c.strip() for c in r)]
    if rows and not _numeric(rows[0][0]):
        rows = rows[1:]  # a header row
    if not rows:
        raise TaskError(f"{path}: no target rows")
    width = len(rows[0])
    table = np.empty((len(rows), width))
    for i, row in enumerate(rows, start=1):
        if len(row) != width:
            raise TaskError(f"{path}: row {i} has {len(row)} columns, the first has {width}")
        for j, cell in enumerate(row):
            if not _numeric(cell):
                raise TaskError(
                    f"{path}: row {i}, column {j + 1}: expected a number, found {cell!r}"
                )
            table[i - 1, j] = float(cell)
    return _rows(table, str(path), euler=euler, degrees=degrees)


def _numeric(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _array(raw: object, where: str) -> FloatArray:
    try:
        return np.array(raw, dtype=float)
    except (TypeError, ValueError) as exc:
        raise TaskError(f"{where}: expected numbers in equal-length rows") from exc


def _read_json(path: Path, *, euler: str, degrees: bool) -> Task:
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as exc:
        raise TaskError(f"{path}: not valid JSON: {exc.msg} (line {exc.lineno})") from exc
    where = str(path)
    if isinstance(data, list):
        return _rows(_array(data, where), where, euler=euler, degrees=degrees)
    if not isinstance(data, Mapping):
        raise TaskError(f"{where}: expected a list of targets or a mapping")
    if "region" in data:
        return _region(data, where)
    keys = [k for k in ("positions", "poses", "matrices") if k in data]
    if len(keys) != 1:
        raise TaskError(f"{where}: expected exactly one of positions, poses, matrices or region")
    allowed = {"positions": {"positions"}, "poses": {"poses", "euler", "angle"}}
    extra = set(data) - allowed.get(keys[0], {keys[0]}) - {"name"}
    if extra:
        raise TaskError(f"{where}: unknown key {sorted(extra)[0]!r}")
    table = _array(data[keys[0]], f"{where}, key '{keys[0]}'")
    expected = {"positions": 3, "poses": 6}.get(keys[0])
    if expected is not None and (table.ndim != 2 or table.shape[1] != expected):
        raise TaskError(
            f"{where}, key '{keys[0]}': expected rows of {expected} numbers, "
            f"found shape {table.shape}"
        )
    if keys[0] == "matrices" and (table.ndim != 3 or table.shape[1:] != (4, 4)):
        raise TaskError(f"{where}, key 'matrices': expected 4x4 matrices, found {table.shape}")
    seq = data.get("euler", euler)
    angle = data.get("angle", "deg" if degrees else "rad")
    if angle not in ("deg", "rad"):
        raise TaskError(f"{where}, key 'angle': expected deg or rad, found {angle!r}")
    task = _rows(table, where, euler=str(seq), degrees=angle == "deg")
    name = data.get("name")
    return Task(task.targets, name=str(name)) if name is not None else task


def _region(data: Mapping[str, Any], where: str) -> Task:
    kind = data["region"]
    if kind not in _REGION_KEYS:
        raise TaskError(f"{where}, key 'region': expected ring, box or sphere, found {kind!r}")
    extra = set(data) - set(_REGION_KEYS[kind]) - {"name"}
    if extra:
        raise TaskError(f"{where}: unknown key {sorted(extra)[0]!r} for a {kind} region")
    args = {k: v for k, v in data.items() if k not in ("region", "name")}
    try:
        if kind == "ring":
            task = Task.ring(**args)
        elif kind == "box":
            task = Task.box(**args)
        else:
            task = Task.sphere(**args)
    except TypeError as exc:  # a missing key
        raise TaskError(f"{where}: {kind} region: {exc}") from exc
    except KinematicaError as exc:
        raise TaskError(f"{where}: {exc}") from exc
    return Task(task.targets, name=str(data.get("name", task.name)))


def _read_numpy(path: Path, *, euler: str, degrees: bool) -> Task:
    try:
        loaded = np.load(path, allow_pickle=False)
    except (ValueError, OSError, EOFError) as exc:
        raise TaskError(f"{path}: not a numpy file ({exc})") from exc
    if isinstance(loaded, np.lib.npyio.NpzFile):
        with loaded:
            names = list(loaded.files)
            if "targets" in names:
                table = loaded["targets"]
            elif len(names) == 1:
                table = loaded[names[0]]
            else:
                raise TaskError(f"{path}: holds {names}; name the array 'targets'")
    else:
        table = loaded
    if table.dtype.kind not in "iuf":
        raise TaskError(f"{path}: expected numbers, found dtype {table.dtype}")
    return _rows(np.asarray(table, dtype=float), str(path), euler=euler, degrees=degrees)


def load_task(path: str | os.PathLike[str], *, euler: str = "ZYZ", degrees: bool = True) -> Task:
    """Read a task file: CSV, JSON, ``.npy`` or ``.npz`` (see the module docs).

    Args:
        path: The file.
        euler: Euler sequence of 6-number pose rows (a JSON file may say its own).
        degrees: Angles of 6-number pose rows in degrees (as robot files,
            the default), or radians. A JSON file may say ``"angle": "rad"``.

    Returns:
        The task; its name is the path.

    Raises:
        TaskError: The file is missing, unreadable or malformed (the message
            names the file, row and column).
    """
    p = Path(path)
    suffix = p.suffix.lower()
    readers = {".csv": _read_csv, ".json": _read_json, ".npy": _read_numpy, ".npz": _read_numpy}
    if suffix not in readers:
        raise TaskError(
            f"{p}: unknown task file type {suffix or '(no extension)'!r}; expected "
            f"{', '.join(TASK_SUFFIXES)}"
        )
    if not p.is_file():
        raise TaskError(f"{p}: no such task file")
    try:
        return readers[suffix](p, euler=euler, degrees=degrees)
    except UnicodeDecodeError as exc:
        raise TaskError(f"{p}: not UTF-8 text") from exc
    except OSError as exc:
        raise TaskError(f"{p}: cannot read the file: {exc.strerror or exc}") from exc


def as_task(task: Task | ArrayLike | str | os.PathLike[str]) -> Task:
    """A :class:`Task` from a task, a file path, or an array of targets.

    Arrays ``(N, 3)`` are positions, ``(N, 4, 4)`` poses (m, base frame).
    """
    if isinstance(task, Task):
        return task
    if isinstance(task, str | os.PathLike):
        return load_task(task)
    arr = np.asarray(task, dtype=float)
    if arr.ndim >= 2 and arr.shape[-2:] == (4, 4):
        return Task.from_poses(arr, name="targets")
    if arr.ndim >= 1 and arr.shape[-1] == 3:
        return Task.from_positions(arr, name="targets")
    raise TaskError(f"targets must be positions (N, 3) or poses (N, 4, 4), got {arr.shape}")
