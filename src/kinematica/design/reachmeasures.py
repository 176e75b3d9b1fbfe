"""Design measures from reachability: dexterous volume in a region, the task's index.

Two measures a designer states with :class:`ReachSettings` (``optimize(...,
reach=ReachSettings(...))``), both by the same exact batched IK as the
reachability maps (:mod:`kinematica.reach`):

- ``dexterous_volume`` (m³; m² for a planar arm): the volume of the voxels of
  ``region`` in which the arm reaches every one of ``orientations`` tool
  orientations spread over SO(3) (:func:`kinematica.reach.reachability` on that
  region, its :attr:`~kinematica.reach.ReachabilityMap.dexterous_volume`);
- ``task_reachability`` (0 to 1): the mean, over the task's targets, of the
  share of orientations within ``tolerance`` (rad) of the target's that the
  arm reaches at the target's position (``samples`` of them,
  :func:`kinematica.reach.ball_set`; all of SO(3) for ``tolerance=None`` or a
  position task, :func:`kinematica.reach.so3_set`). 1 when every nearby
  orientation is reached too: the task survives a tool held a little askew.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Final

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_count, check_number
from kinematica.design.task import Task
from kinematica.errors import ArgumentError
from kinematica.ik.result import IKBatchResult
from kinematica.reach import ball_set, reachability, so3_set
from kinematica.reach.orientations import MAX_ORIENTATIONS

if TYPE_CHECKING:
    from kinematica.robot import Robot

__all__ = [
    "REACH_MEASURES",
    "ReachSettings",
    "as_reach_settings",
    "reach_measures",
    "task_reachability",
]

FloatArray = NDArray[np.float64]

#: The measures :class:`ReachSettings` adds to a design's evaluation.
REACH_MEASURES: Final = ("dexterous_volume", "task_reachability")
#: Most orientations a target's tolerance set holds (its IK batch is targets × this).
MAX_SAMPLES: Final = 4096


@dataclass(frozen=True)
class ReachSettings:
    """How the reachability measures of a design are taken.

    Attributes:
        region: ``(2, 3)`` lower and upper corners of the box (m, base frame)
            whose dexterous volume is measured (kept as a read-only array);
            None: ``dexterous_volume`` is not measured (NaN).
        resolution: Voxel side (m) of that box's map.
        orientations: Orientations asked per voxel (spread over SO(3)).
        tolerance: The task's orientation tolerance (rad, 0 to π); None: all
            of SO(3) at each target position.
        samples: Orientations asked per target for ``task_reachability``.
    """

    region: ArrayLike | None = None
    resolution: float = 0.05
    orientations: int = 64
    tolerance: float | None = None
    samples: int = 64
    _key: str = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        region = None
        if self.region is not None:
            try:
                region = np.array(self.region, dtype=np.float64)
            except (TypeError, ValueError):
                raise ArgumentError(
                    f"region must be (2, 3) corners, got {self.region!r}", arg="region"
                ) from None
            if region.shape != (2, 3) or not np.all(np.isfinite(region)):
                raise ArgumentError(
                    f"region must be (2, 3) finite corners (m), got shape {region.shape}",
                    arg="region",
                )
            region.flags.writeable = False
        object.__setattr__(self, "region", region)
        res = check_number(self.resolution, "resolution", positive=True, unit="m", what="a length")
        object.__setattr__(self, "resolution", res)
        count = check_count(self.orientations, "orientations", lo=1, hi=MAX_ORIENTATIONS)
        object.__setattr__(self, "orientations", count)
        if self.tolerance is not None:
            tol = check_number(
                self.tolerance, "tolerance", lo=0.0, hi=math.pi, unit="rad", what="an angle"
            )
            object.__setattr__(self, "tolerance", tol)
        object.__setattr__(
            self, "samples", check_count(self.samples, "samples", lo=1, hi=MAX_SAMPLES)
        )
        corners = None if region is None else region.tolist()
        key = f"{corners}|{res!r}|{self.orientations}|{self.tolerance!r}|{self.samples}"
        object.__setattr__(self, "_key", key)

    @property
    def key(self) -> str:
        """The settings as text (checkpoints of a run with them record it)."""
        return self._key


def task_reachability(
    robot: Robot, task: Task, tolerance: float | None, samples: int, threads: int | None = None
) -> FloatArray:
    """Each target's share of the orientations near its own that the arm reaches.

    Args:
        robot: The robot.
        task: Positions or poses (base frame).
        tolerance: Orientation tolerance (rad); None (or a position task): all of SO(3).
        samples: Orientations asked per target.
        threads: Threads of the IK batch (None: the library default).

    Returns:
        ``(N,)`` the share, 0 to 1, of the ``samples`` orientations reached
        within the joint limits.
    """
    count = check_count(samples, "samples", lo=1, hi=MAX_SAMPLES)
    n = len(task)
    if tolerance is None or task.kind == "position":
        R = np.broadcast_to(so3_set(count), (n, count, 3, 3))
    else:
        R = task.targets[:, None, :3, :3] @ ball_set(count, tolerance)
    targets = np.zeros((n, count, 4, 4))
    targets[..., :3, :3] = R
    targets[..., :3, 3] = task.positions[:, None, :]
    targets[..., 3, 3] = 1.0
    res = robot.ik(targets.reshape(-1, 4, 4), workers=threads)
    assert isinstance(res, IKBatchResult)
    reached = np.count_nonzero(res.count.reshape(n, count) > 0, axis=1)
    out: FloatArray = reached / float(count)
    return out


def reach_measures(
    robot: Robot, task: Task, settings: ReachSettings, threads: int | None = None
) -> dict[str, float]:
    """``dexterous_volume`` and ``task_reachability`` of ``robot`` (module docs).

    Args:
        robot: The robot.
        task: The task.
        settings: How to measure.
        threads: Threads of the IK batches (None: the library default).

    Returns:
        ``{"dexterous_volume": m³ or NaN without a region, "task_reachability": 0..1}``.
    """
    volume = math.nan
    if settings.region is not None:
        reach_map = reachability(
            robot,
            region=settings.region,
            resolution=settings.resolution,
            orientations=settings.orientations,
            manipulability=False,
            threads=threads,
        )
        volume = reach_map.dexterous_volume
    index = task_reachability(robot, task, settings.tolerance, settings.samples, threads)
    return {"dexterous_volume": volume, "task_reachability": float(np.mean(index))}


def as_reach_settings(reach: ReachSettings | ArrayLike | None) -> ReachSettings | None:
    """``reach=`` of a design run: settings, or None."""
    if reach is None or isinstance(reach, ReachSettings):
        return reach
    raise ArgumentError(
        f"reach must be a kinematica.design.ReachSettings or None, got {reach!r}", arg="reach"
    )
