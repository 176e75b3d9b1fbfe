"""Random configurations within the joint limits."""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from kinematica.arguments import check_count, check_size
from kinematica.errors import KinematicaError
from kinematica.ik.numeric import check_seed

if TYPE_CHECKING:
    from kinematica.robot.description import RobotDescription

__all__ = ["MAX_CONFIGURATIONS", "Seed", "random_q", "sampling_box"]

FloatArray = NDArray[np.float64]
Seed = int | np.random.Generator | None

#: Most configurations :func:`random_q` draws in one call (80 MB per joint).
MAX_CONFIGURATIONS = 10_000_000


def _no_range(robot: RobotDescription, i: int) -> str:
    """Which joint of which robot (and file) needs limits, and how to give them."""
    spec = robot.source_spec
    source = None if spec is None else spec.source
    if source is not None and not source.startswith("builtin:"):
        suffix = Path(source).suffix.lower()
        how = (
            f"add <limit lower=... upper=.../> to its joint in {source}"
            if suffix in (".urdf", ".xacro")
            else f"add `limits: [lower, upper]` to joint {i + 1} (q{i + 1}) of {source}"
        )
    else:
        how = "give it limits, e.g. robot.with_limits(...)"
    return (
        f"joint {i + 1} (q{i + 1}) of {robot.name} is prismatic without limits: sampling "
        f"needs a finite range; {how}"
    )


def sampling_box(robot: RobotDescription, prismatic_range: float | None = None) -> FloatArray:
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
            raise KinematicaError(_no_range(robot, int(i)))
        box[i] = (-prismatic_range, prismatic_range)
    return box


def random_q(
    robot: RobotDescription, n: int | tuple[int, ...] = 1, seed: Seed = None
) -> FloatArray:
    """Configurations drawn uniformly within the joint limits.

    Args:
        robot: The robot.
        n: Number of configurations (or a batch shape).
        seed: Seed or ``numpy.random.Generator`` (reproducible draws).

    Returns:
        ``(n, dof)`` (or ``(*n, dof)``) joint values, rad and m, each within
        ``robot.qlim`` (free revolute joints within ``(-π, π)``).

    Raises:
        ArgumentError: ``n`` is not a whole number >= 0 (or a tuple of them),
            asks for more than MAX_CONFIGURATIONS, or ``seed`` is not a seed.
        KinematicaError: A prismatic joint has no limits.
    """
    if isinstance(n, tuple | list):
        shape = tuple(check_count(v, "n") for v in n)
    else:
        shape = (check_count(n, "n"),)
    check_size(math.prod(shape), MAX_CONFIGURATIONS, "n", "configurations")
    rng = np.random.default_rng(check_seed(seed))
    box = sampling_box(robot)
    u = rng.random((*shape, robot.dof))
    out: FloatArray = box[:, 0] + u * (box[:, 1] - box[:, 0])
    return np.clip(out, box[:, 0], box[:, 1])


def generic_rank_samples(robot: RobotDescription, count: int = 8) -> FloatArray:
    """A few fixed, reproducible configurations for measuring the generic rank."""
    box = sampling_box(robot, prismatic_range=1.0)
    rng = np.random.default_rng(20240)
    u = rng.random((count, robot.dof))
    out: FloatArray = box[:, 0] + u * (box[:, 1] - box[:, 0])
    return out
