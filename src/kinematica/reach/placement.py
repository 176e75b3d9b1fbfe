"""Where to put the robot: base positions and yaws from which it reaches a whole task.

A direct batched search. The candidate bases are the nodes of a grid over a
box of the world (``resolution`` apart, both ends included; an axis whose
bounds are equal holds one value: a floor), each at every yaw of a set (turns
of the base about the world z axis). A candidate base ``W_B = [Rz(yaw), p]``
sees task pose ``W_T`` as ``B_T = W_B⁻¹ · W_T``; the candidate is *feasible*
when the arm's IK (closed form, within the joint limits) reaches every task
pose so seen. Candidates for which some task position lies outside the arm's
reach ball are rejected without asking the IK. Feasible candidates are ranked
by the worst, over the task's poses, of the best manipulability among each
pose's solutions (the arm chooses its branch per pose), largest first;
candidates within :data:`TIE_TOL` of each other in that measure keep their
grid order.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.arguments import check_count, check_number
from kinematica.errors import ArgumentError
from kinematica.ik.numeric import reach_bound
from kinematica.ik.result import IKBatchResult
from kinematica.robot.sampling import sampling_box
from kinematica.robot.velocity import manipulability as _manipulability
from kinematica.spatial import check_transform

if TYPE_CHECKING:
    from kinematica.robot import Robot

__all__ = ["MAX_CANDIDATES", "TIE_TOL", "BasePlacement", "base_placement", "rank", "yaw_pose"]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

#: Most candidate bases (positions × yaws) one search considers.
MAX_CANDIDATES = 1_000_000
#: Poses solved in one IK call (bounds the memory of a search).
CHUNK_POSES = 1 << 16
#: Feasible candidates whose worst manipulability differs by less than this share of
#: the best one's rank as equals, in grid order (position, then yaw): yaws about the
#: vertical of an arm whose first joint turns about it leave the manipulability
#: unchanged but for round-off, which must not decide the order.
TIE_TOL = 1e-9


def yaw_pose(position: ArrayLike, yaw: ArrayLike) -> FloatArray:
    """``(..., 4, 4)`` base poses: a turn ``yaw`` (rad) about world z, then ``position`` (m)."""
    p = np.asarray(position, dtype=np.float64)
    y = np.asarray(yaw, dtype=np.float64)
    shape = np.broadcast_shapes(p.shape[:-1], y.shape)
    T = np.zeros((*shape, 4, 4))
    c, s = np.cos(y), np.sin(y)
    T[..., 0, 0], T[..., 0, 1], T[..., 1, 0], T[..., 1, 1] = c, -s, s, c
    T[..., 2, 2] = 1.0
    T[..., :3, 3] = p
    T[..., 3, 3] = 1.0
    return T


@dataclass(frozen=True)
class BasePlacement:
    """The candidate bases of a search and how each does on the task.

    Attributes:
        positions: ``(C, 3)`` candidate base positions (m, world frame).
        yaws: ``(C,)`` their yaws (rad, about world z).
        feasible: ``(C,)`` True where every task pose is reached within the limits.
        reached: ``(C,)`` share of the task poses reached.
        worst_manipulability: ``(C,)`` worst over the task of each pose's best
            manipulability (task rows, as :func:`kinematica.motion.manipulability`
            with ``axes="task"``); NaN where not feasible.
        order: ``(F,)`` indices of the feasible candidates, best first.
        resolution: Spacing (m) of the position grid.
    """

    positions: FloatArray
    yaws: FloatArray
    feasible: BoolArray
    reached: FloatArray
    worst_manipulability: FloatArray
    order: NDArray[np.intp]
    resolution: float

    @property
    def count(self) -> int:
        """Number of feasible candidates."""
        return int(self.order.size)

    @property
    def best(self) -> FloatArray | None:
        """``(4, 4)`` the best base pose in the world frame, or None if none is feasible."""
        if not self.order.size:
            return None
        i = int(self.order[0])
        return yaw_pose(self.positions[i], self.yaws[i])

    def poses(self) -> FloatArray:
        """``(F, 4, 4)`` the feasible base poses, best first."""
        return yaw_pose(self.positions[self.order], self.yaws[self.order])


def rank(worst: FloatArray, feasible: BoolArray) -> NDArray[np.intp]:
    """Indices of the feasible candidates, largest ``worst`` first; equals (TIE_TOL) in order."""
    idx = np.flatnonzero(feasible)
    if not idx.size:
        return idx
    top = float(np.max(np.abs(worst[idx])))
    step = TIE_TOL * top if top > 0.0 else 1.0
    # whole steps of TIE_TOL·top below the best: those in one step keep the grid order
    below = np.floor((float(np.max(worst[idx])) - worst[idx]) / step)
    out: NDArray[np.intp] = idx[np.argsort(below, kind="stable")]
    return out


def _task(task_poses: ArrayLike) -> FloatArray:
    T = check_transform(task_poses, "task_poses")
    if T.ndim == 2:
        T = T[None]
    T = T.reshape(-1, 4, 4)
    if T.shape[0] == 0:
        raise ArgumentError("task_poses holds no pose", arg="task_poses")
    return T


def _box(region: ArrayLike) -> FloatArray:
    try:
        box = np.asarray(region, dtype=np.float64)
    except (TypeError, ValueError):
        box = np.empty(0)
    if box.shape != (2, 3) or not np.all(np.isfinite(box)) or np.any(box[1] < box[0]):
        raise ArgumentError(
            "region must be [[xmin, ymin, zmin], [xmax, ymax, zmax]] (m) of base positions, "
            f"each maximum at least its minimum; got {region!r}",
            arg="region",
        )
    return box


def _yaws(yaw: int | ArrayLike) -> FloatArray:
    if isinstance(yaw, int | np.integer) and not isinstance(yaw, bool):
        n = check_count(yaw, "yaw", lo=1, hi=3600)
        out: FloatArray = 2.0 * math.pi * np.arange(n) / n
        return out
    try:
        y = np.atleast_1d(np.asarray(yaw, dtype=np.float64))
    except (TypeError, ValueError):
        y = np.empty(0)
    if y.ndim != 1 or y.size == 0 or not np.all(np.isfinite(y)):
        raise ArgumentError(
            f"yaw must be a number of yaws or yaw angles in rad, got {yaw!r}", arg="yaw"
        )
    return y


def base_placement(
    robot: Robot,
    task_poses: ArrayLike,
    region: ArrayLike | None = None,
    *,
    resolution: float = 0.05,
    yaw: int | ArrayLike = 8,
    threads: int | None = None,
) -> BasePlacement:
    """Base positions and yaws from which every task pose is reachable.

    Args:
        robot: The robot; its own ``base`` transform stays between the placed
            base and its first joint.
        task_poses: ``(m, 4, 4)`` (or ``(4, 4)``) tool poses in the world frame.
        region: ``(2, 3)`` lower and upper corners (m, world frame) of the box
            of base positions; equal bounds on an axis fix it (e.g. z = 0).
            None: the floor z = 0 under the task, its x and y bounds widened
            by the arm's reach bound R (no base farther can reach a task pose),
            from a multiple of ``resolution``.
        resolution: Spacing (m) of the candidate positions.
        yaw: Number of yaws spread evenly over a turn (8: every 45°), or the
            yaw angles (rad) to try.
        threads: Core threads of each IK batch (None: the library default).

    Returns:
        The :class:`BasePlacement` (``.best``, ``.poses()``).

    Raises:
        ArgumentError: Bad poses, region, resolution or yaw, or more than
            MAX_CANDIDATES candidates.
    """
    W_T = _task(task_poses)
    h = check_number(resolution, "resolution", positive=True, unit="m", what="a length")
    lim = sampling_box(robot)
    radius = reach_bound(robot.chain, lim[:, 0], lim[:, 1])
    if region is None:
        p = W_T[:, :3, 3]
        lo = np.floor((p.min(axis=0) - radius) / h) * h  # round numbers, h apart
        hi = p.max(axis=0) + radius
        region = [[lo[0], lo[1], 0.0], [hi[0], hi[1], 0.0]]
    box = _box(region)
    yaws = _yaws(yaw)
    with np.errstate(over="ignore"):
        counts = np.floor((box[1] - box[0]) / h + 1e-9) + 1.0
    total = float(np.prod(counts)) * yaws.size
    if not math.isfinite(total) or total > MAX_CANDIDATES:
        raise ArgumentError(
            f"{total:.3g} candidate bases (positions × yaws); at most {MAX_CANDIDATES}: "
            "a coarser resolution, fewer yaws or a smaller region",
            arg="resolution",
        )
    axes = [box[0, k] + h * np.arange(int(counts[k])) for k in range(3)]
    grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    positions = np.repeat(grid, yaws.size, axis=0)
    cand_yaw = np.tile(yaws, grid.shape[0])
    C, m = positions.shape[0], W_T.shape[0]

    # Reject without IK the candidates that leave a task position outside the reach ball.
    centre = robot.chain.start[:3, 3]
    B_inv = np.linalg.inv(yaw_pose(positions, cand_yaw))  # (C, 4, 4)
    local_p = np.einsum("cij,mj->cmi", B_inv[:, :3, :3], W_T[:, :3, 3]) + B_inv[:, None, :3, 3]
    maybe = np.all(np.sum((local_p - centre) ** 2, axis=-1) <= radius**2, axis=1)

    reached = np.zeros(C)
    worst = np.full(C, np.nan)
    todo = np.flatnonzero(maybe)
    per_call = max(1, CHUNK_POSES // m)
    for start in range(0, todo.size, per_call):
        idx = todo[start : start + per_call]
        targets = (B_inv[idx][:, None] @ W_T[None]).reshape(-1, 4, 4)
        res = robot.ik(targets, workers=threads)
        assert isinstance(res, IKBatchResult)
        ok = (res.count > 0).reshape(idx.size, m)
        reached[idx] = ok.mean(axis=1)
        full = ok.all(axis=1)
        if not full.any():
            continue
        sol = res.solutions.reshape(idx.size, m, *res.solutions.shape[1:])[full]
        valid = np.isfinite(sol[..., 0])
        w = np.full(valid.shape, -np.inf)
        w[valid] = _manipulability(robot, sol[valid], axes="task")
        worst[idx[full]] = w.max(axis=2).min(axis=1)
    feasible = reached == 1.0
    order = rank(worst, feasible)
    return BasePlacement(
        positions=positions,
        yaws=cand_yaw,
        feasible=feasible,
        reached=reached,
        worst_manipulability=worst,
        order=order,
        resolution=h,
    )
