"""The geometric Jacobian of a serial chain, batched."""

from __future__ import annotations

from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import KinematicaError

if TYPE_CHECKING:
    from kinematica.robot.robot import Robot

__all__ = ["jacobian"]

FloatArray = NDArray[np.float64]


def jacobian(robot: Robot, q: ArrayLike, frame: Literal["base", "tool"] = "base") -> FloatArray:
    """Geometric Jacobian of the tool point.

    Rows 0-2 map joint rates to the linear velocity of the tool origin, rows 3-5
    to the angular velocity, both expressed in the base frame (``frame="base"``)
    or in the tool frame (``frame="tool"``). Column i is ``[z × (p - o); z]``
    for a revolute joint with axis ``z`` through ``o``, ``[z; 0]`` for a
    prismatic one.

    Args:
        robot: The robot.
        q: ``(..., n)`` joint values.
        frame: ``"base"`` or ``"tool"``.

    Returns:
        ``(..., 6, n)`` Jacobian (m/rad or m/m in the top rows, rad/rad below).
    """
    if frame not in ("base", "tool"):
        raise KinematicaError(f"frame must be 'base' or 'tool', got {frame!r}")
    qa, bad = robot._batch(q)
    n = robot.dof
    flat = qa.reshape(-1, n)
    F = robot._chain.joint_frames(flat)  # (B, n+1, 4, 4)
    z = F[:, :n, :3, 2]  # (B, n, 3) joint axes
    o = F[:, :n, :3, 3]  # (B, n, 3) a point on each axis
    p = F[:, n, :3, 3]  # (B, 3) tool origin
    prismatic = robot.is_prismatic
    J = np.empty((flat.shape[0], 6, n))
    lin = np.cross(z, p[:, None, :] - o)
    J[:, :3, :] = np.swapaxes(np.where(prismatic[None, :, None], z, lin), 1, 2)
    J[:, 3:, :] = np.swapaxes(np.where(prismatic[None, :, None], 0.0, z), 1, 2)
    if frame == "tool":
        Rt = np.swapaxes(F[:, n, :3, :3], 1, 2)
        J[:, :3, :] = Rt @ J[:, :3, :]
        J[:, 3:, :] = Rt @ J[:, 3:, :]
    out = J.reshape(*qa.shape[:-1], 6, n)
    if bad is not None:
        out[bad] = np.nan  # rows of q holding NaN/inf (a warning named them)
    return out
