"""Tasks: the targets a design must reach, from files, arrays or sampled regions.

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
import hashlib
import json
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError, KinematicaError
from kinematica.spatial import check_rotation, check_transform, from_pose

__all__ = ["Task", "TaskError", "load_task"]

FloatArray = NDArray[np.float64]
TaskKind = Literal["position", "pose"]

#: File extensions :func:`load_task` reads.
TASK_SUFFIXES = (".csv", ".json", ".npy", ".npz")
_REGION_KEYS = {
    "ring": ("region", "radius", "count", "center", "normal", "orientation"),
    "box": ("region", "lower", "upper", "count", "seed", "orientation"),
    "sphere": ("region", "radius", "count", "center", "surface", "seed", "orientation"),
}


class TaskError(KinematicaError, ValueError):
    """A task (file, array or region) is malformed; the message says where."""


def _freeze(a: FloatArray) -> FloatArray:
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class Task:
    """The targets a design must reach, in the base frame (metres).

    Attributes:
        targets: ``(N, 3)`` positions (tool orientation free) or ``(N, 4, 4)``
            poses of the tool in the robot's base (world) frame. Read-only.
        name: A label for reports.
    """

    targets: FloatArray
    name: str = "task"
    _digest: str = field(init=False, repr=False)

    def __post_init__(self) -> None:
        raw = np.asarray(self.targets)
        if raw.dtype.kind not in "iuf":
            raise TaskError(f"task {self.name!r}: targets must be numbers, got {raw.dtype}")
        t = np.array(raw, dtype=float)
        if t.ndim == 2 and t.shape[1] == 3:
            bad = np.flatnonzero(~np.all(np.isfinite(t), axis=1))
            if bad.size:
                raise TaskError(f"task {self.name!r}: target {bad[0]} holds NaN or inf")
        elif t.ndim == 3 and t.shape[1:] == (4, 4):
            try:
                check_transform(t, name="target")  # names the first malformed target
            except DimensionError as exc:
                raise TaskError(f"task {self.name!r}: {exc}") from exc
        else:
            raise TaskError(
                f"task {self.name!r}: targets must be positions (N, 3) or poses (N, 4, 4), "
                f"got shape {t.shape}"
            )
        if t.shape[0] == 0:
            raise TaskError(f"task {self.name!r}: no targets")
        object.__setattr__(self, "targets", _freeze(t))
        digest = hashlib.sha256(t.tobytes() + str(t.shape).encode()).hexdigest()
        object.__setattr__(self, "_digest", digest)

    @property
    def kind(self) -> TaskKind:
        """``"position"`` or ``"pose"``."""
        return "position" if self.targets.ndim == 2 else "pose"

    @property
    def positions(self) -> FloatArray:
        """``(N, 3)`` target positions, m."""
        return self.targets if self.kind == "position" else self.targets[:, :3, 3]

    @property
    def fingerprint(self) -> str:
        """A hash of the targets (checkpoints check they are unchanged)."""
        return self._digest

    def __len__(self) -> int:
        return int(self.targets.shape[0])

    # ------------------------------------------------------------ from arrays
    @classmethod
    def from_positions(cls, points: ArrayLike, *, name: str = "positions") -> Task:
        """Positions ``(..., 3)`` (m, base frame); leading axes are flattened."""
        p = np.asarray(points, dtype=float)
        if p.ndim == 0 or p.shape[-1] != 3:
            raise TaskError(f"positions must have shape (..., 3), got {p.shape}")
        return cls(p.reshape(-1, 3), name=name)

    @classmethod
    def from_poses(
        cls,
        poses: ArrayLike,
        *,
        euler: str = "ZYZ",
        degrees: bool = False,
        name: str = "poses",
    ) -> Task:
        """Poses ``(..., 4, 4)``, or ``(..., 6)`` rows ``x, y, z`` + three Euler angles.

        Args:
            poses: Homogeneous transforms of the tool in the base frame (m), or
                pose rows read with :func:`kinematica.from_pose`.
            euler: The Euler sequence of ``(..., 6)`` rows (scipy's naming).
            degrees: Angles of ``(..., 6)`` rows in degrees.
            name: A label.
        """
        p = np.asarray(poses, dtype=float)
        if p.ndim >= 2 and p.shape[-2:] == (4, 4):
            return cls(p.reshape(-1, 4, 4), name=name)
        if p.ndim >= 1 and p.shape[-1] == 6:
            if not np.all(np.isfinite(p)):
                raise TaskError(f"task {name!r}: pose rows hold NaN or inf")
            return cls(from_pose(p.reshape(-1, 6), euler=euler, degrees=degrees), name=name)
        raise TaskError(f"poses must have shape (..., 4, 4) or (..., 6), got {p.shape}")

    # ------------------------------------------------------------ regions
    @classmethod
    def ring(
        cls,
        radius: float,
        count: int,
        *,
        center: ArrayLike = (0.0, 0.0, 0.0),
        normal: ArrayLike = (0.0, 0.0, 1.0),
        orientation: ArrayLike | None = None,
    ) -> Task:
        """``count`` points evenly spaced on a circle.

        Args:
            radius: Circle radius, m.
            count: Number of points; the first lies along the in-plane axis
                closest to the base x axis.
            center: ``(3,)`` circle centre, m.
            normal: ``(3,)`` the circle's axis.
            orientation: ``(3, 3)`` tool rotation for every point (pose
                targets); ``None`` for positions.
        """
        r = _positive(radius, "radius")
        n_points = _count(count)
        c = _vector(center, "center")
        axis = _vector(normal, "normal")
        norm = float(np.linalg.norm(axis))
        if norm == 0.0:
            raise TaskError("ring normal must not be zero")
        axis = axis / norm
        # In-plane basis: base x projected on the plane (base y if x is the normal).
        ref = np.array([1.0, 0.0, 0.0]) if abs(axis[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
        u = ref - axis * float(ref @ axis)
        u /= np.linalg.norm(u)
        v = np.cross(axis, u)
        angle = 2.0 * np.pi * np.arange(n_points) / n_points
        points = c + r * (np.cos(angle)[:, None] * u + np.sin(angle)[:, None] * v)
        return _with_orientation(points, orientation, f"ring r={r:g}")

    @classmethod
    def box(
        cls,
        lower: ArrayLike,
        upper: ArrayLike,
        count: int,
        *,
        seed: int = 0,
        orientation: ArrayLike | None = None,
    ) -> Task:
        """``count`` points drawn uniformly in an axis-aligned box (seeded).

        Args:
            lower: ``(3,)`` lower corner, m.
            upper: ``(3,)`` upper corner, m (``>= lower``; equal gives a flat box).
            count: Number of points.
            seed: Seed of the draw (same seed, same points).
            orientation: ``(3, 3)`` tool rotation for pose targets, or ``None``.
        """
        lo, hi = _vector(lower, "lower"), _vector(upper, "upper")
        if np.any(hi < lo):
            raise TaskError(f"box upper {hi.tolist()} is below lower {lo.tolist()}")
        points = np.random.default_rng(seed).uniform(lo, hi, (_count(count), 3))
        return _with_orientation(points, orientation, "box")

    @classmethod
    def sphere(
        cls,
        radius: float,
        count: int,
        *,
        center: ArrayLike = (0.0, 0.0, 0.0),
        surface: bool = False,
        seed: int = 0,
        orientation: ArrayLike | None = None,
    ) -> Task:
        """``count`` points drawn uniformly in a ball, or on its surface (seeded).

        Args:
            radius: Ball radius, m.
            count: Number of points.
            center: ``(3,)`` centre, m.
            surface: Draw on the sphere rather than in the ball.
            seed: Seed of the draw.
            orientation: ``(3, 3)`` tool rotation for pose targets, or ``None``.
        """
        r = _positive(radius, "radius")
        n_points = _count(count)
        rng = np.random.default_rng(seed)
        d = rng.normal(size=(n_points, 3))
        d /= np.linalg.norm(d, axis=1, keepdims=True)
        # Uniform in volume: the radius of a uniform point has CDF (s / r)^3.
        s = np.ones(n_points) if surface else rng.uniform(size=n_points) ** (1.0 / 3.0)
        points = _vector(center, "center") + r * s[:, None] * d
        return _with_orientation(points, orientation, f"sphere r={r:g}")


def _positive(value: float, what: str) -> float:
    v = float(value)
    if not math.isfinite(v) or v <= 0.0:
        raise TaskError(f"{what} must be a positive number, got {value!r}")
    return v


def _count(value: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 1:
        raise TaskError(f"count must be a positive whole number, got {value!r}")
    return int(value)


def _vector(value: ArrayLike, what: str) -> FloatArray:
    try:
        v = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise TaskError(f"{what} must be 3 numbers, got {value!r}") from exc
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise TaskError(f"{what} must be 3 finite numbers, got {value!r}")
    return v


def _with_orientation(points: FloatArray, orientation: ArrayLike | None, name: str) -> Task:
    if orientation is None:
        return Task(points, name=name)
    try:
        R = check_rotation(np.asarray(orientation, dtype=float), name="orientation")
    except (DimensionError, TypeError, ValueError) as exc:
        raise TaskError(f"orientation must be a 3x3 rotation matrix: {exc}") from exc
    T = np.broadcast_to(np.eye(4), (points.shape[0], 4, 4)).copy()
    T[:, :3, :3] = R
    T[:, :3, 3] = points
    return Task(T, name=name)


# ---------------------------------------------------------------- files
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
