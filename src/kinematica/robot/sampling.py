"""Random configurations within the joint limits."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from kinematica.errors import KinematicaError

if TYPE_CHECKING:
    from kinematica.robot import Robot

__all__ = ["Seed", "random_q", "sampling_box"]

FloatArray = NDArray[np.float64]
Seed = int | np.random.Generator | None


def sampling_box(robot: Robot, prismatic_range: float | None = None) -> FloatArray:
    """``(n, 2)`` the box joint values are drawn from: the joint limits.

    Free revolute joints span ``(-π, π]``. A prismatic joint without limits
    has no finite range: ``prismatic_range`` (m) gives it ``[-r, r]``, else
    it is an error.

    Raises:
        KinematicaError: A prismatic joint has no limits and no range was given.
    """
    box = robot.qlim.copy()
    for i in np.flatnonzero(~np.all(np.isfinite(box), axis=1)):
        if prismatic_range is None:
            raise KinematicaError(
                f"joint {i + 1} of {robot.name} is prismatic without limits: sampling "
                "needs a finite range (give the joint limits, e.g. robot.with_limits(...))"
            )
        box[i] = (-prismatic_range, prismatic_range)
    return box


def random_q(robot: Robot, n: int | tuple[int, ...] = 1, seed: Seed = None) -> FloatArray:
    """Configurations drawn uniformly within the joint limits.

    Args:
        robot: The robot.
        n: Number of configurations (or a batch shape).
        seed: Seed or ``numpy.random.Generator`` (reproducible draws).

    Returns:
        ``(n, dof)`` (or ``(*n, dof)``) joint values, rad and m, each within
        ``robot.qlim`` (free revolute joints within ``(-π, π)``).

    Raises:
        KinematicaError: A prismatic joint has no limits, or ``n`` is negative.
    """
    shape = (n,) if isinstance(n, int | np.integer) else tuple(int(v) for v in n)
    if any(v < 0 for v in shape):
        raise KinematicaError(f"n must be a non-negative count, got {n!r}")
    box = sampling_box(robot)
    rng = np.random.default_rng(seed)
    u = rng.random((*shape, robot.dof))
    out: FloatArray = box[:, 0] + u * (box[:, 1] - box[:, 0])
    return np.clip(out, box[:, 0], box[:, 1])


def generic_rank_samples(robot: Robot, count: int = 8) -> FloatArray:
    """A few fixed, reproducible configurations for measuring the generic rank."""
    box = sampling_box(robot, prismatic_range=1.0)
    rng = np.random.default_rng(20240)
    u = rng.random((count, robot.dof))
    out: FloatArray = box[:, 0] + u * (box[:, 1] - box[:, 0])
    return out
