"""Tasks: the targets a design must reach, from arrays or sampled regions.

A :class:`Task` is a batch of targets in the robot's base frame, in metres:
positions ``(N, 3)`` (the tool's orientation is free) or poses ``(N, 4, 4)``.
Build one from arrays (:meth:`Task.from_positions`, :meth:`Task.from_poses`),
as a sampled region (:meth:`Task.ring`, :meth:`Task.box`, :meth:`Task.sphere`),
or read a task file with :func:`kinematica.design.load_task`.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_count, check_flag, check_number
from kinematica.errors import ArgumentError, DimensionError, KinematicaError
from kinematica.spatial import check_rotation, check_transform, from_pose

__all__ = ["MAX_REGION_POINTS", "Task", "TaskError"]

FloatArray = NDArray[np.float64]
TaskKind = Literal["position", "pose"]


#: Most points a sampled region makes: a design solves IK at every target for every
#: candidate arm, so a million targets is already hours of search.
MAX_REGION_POINTS = 1_000_000


class TaskError(KinematicaError, ValueError):
    """A task (file, array or region) is malformed; the message says where."""


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
        t.flags.writeable = False
        object.__setattr__(self, "targets", t)
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
        points = np.random.default_rng(_seed(seed)).uniform(lo, hi, (_count(count), 3))
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
        try:
            on_surface = check_flag(surface, "surface")
        except ArgumentError as exc:
            raise _as_task_error(exc) from None
        rng = np.random.default_rng(_seed(seed))
        d = rng.normal(size=(n_points, 3))
        d /= np.linalg.norm(d, axis=1, keepdims=True)
        # Uniform in volume: the radius of a uniform point has CDF (s / r)^3.
        s = np.ones(n_points) if on_surface else rng.uniform(size=n_points) ** (1.0 / 3.0)
        points = _vector(center, "center") + r * s[:, None] * d
        return _with_orientation(points, orientation, f"sphere r={r:g}")


def _as_task_error(exc: ArgumentError) -> TaskError:
    return TaskError(exc.message, arg=exc.arg)


def _positive(value: object, what: str) -> float:
    """``value`` as a length in metres greater than 0 (the library's argument check)."""
    try:
        return check_number(value, what, positive=True, unit="m", what="a length")
    except ArgumentError as exc:
        raise _as_task_error(exc) from None


def _count(value: object) -> int:
    """``value`` as a number of points from 1 to :data:`MAX_REGION_POINTS`."""
    try:
        return check_count(value, "count", lo=1, hi=MAX_REGION_POINTS)
    except ArgumentError as exc:
        raise _as_task_error(exc) from None


def _seed(value: object) -> int:
    """``value`` as the seed of a region's draw: a whole number of at least 0."""
    try:
        return check_count(value, "seed", lo=0)
    except ArgumentError as exc:
        raise _as_task_error(exc) from None


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
