"""The small arms the closed forms solve (planar, SCARA, 3R elbow) and a round trip."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

import kinematica as km
from kinematica.dh import Prismatic, Revolute
from kinematica.robot import Robot

FloatArray = NDArray[np.float64]


PI = math.pi


KINDS = (
    "planar-2R",
    "planar-3R",
    "planar-PR",
    "planar-PRR",
    "scara",
    "anthropomorphic-3R",
    "elbow-3R",
)


def as_poses(targets: FloatArray) -> FloatArray:
    """Position targets ``(N, 3)`` as poses with identity rotation; poses unchanged."""
    if targets.shape[-1] == 3:
        T = np.broadcast_to(np.eye(4), (*targets.shape[:-1], 4, 4)).copy()
        T[..., :3, 3] = targets
        return T
    return targets


def reached(robot: Robot, q: FloatArray, target: FloatArray) -> FloatArray:
    """Position (m) and rotation (rad) errors ``(..., 2)`` of ``q (..., n)`` for ``target``."""
    T = robot.fk(q)
    want = as_poses(target)
    pos = np.linalg.norm(T[..., :3, 3] - want[..., :3, 3], axis=-1)
    if target.shape[-1] == 3:
        return np.stack([pos, 0 * pos], axis=-1)
    rot = km.rotation_angle(
        T[..., :3, :3], np.broadcast_to(want[..., :3, :3], T[..., :3, :3].shape)
    )
    return np.stack([pos, rot], axis=-1)


# ------------------------------------------------------- seeds' hand formulas
L1, L2 = 0.3, 0.5  # seed 000's l1, l2


def seed_pr_arm() -> Robot:
    """Seed 000's PR mechanism: x = q1 + l1 + l2 cos q2, y = l2 sin q2 (world x, y).

    DH: the slide along z0 = world x (base), then the revolute axis z1 = world z.
    """
    base = np.array([[0, 0, 1, 0], [-1, 0, 0, 0], [0, -1, 0, 0], [0, 0, 0, 1]], dtype=float)
    return Robot.from_dh(
        [Prismatic(alpha=PI / 2, offset=L1), Revolute(a=L2, offset=PI / 2)],
        base=base,
        convention="standard",
    )


D1, A2, A3 = 0.4, 0.35, 0.3  # seed 002's L1, L2, L3


def seed_anthropomorphic() -> Robot:
    """Seed 002's table: q1, L1, 0, 90° / q2, 0, L2, 0 / q3, 0, L3, 0."""
    return Robot.from_dh(
        [Revolute(d=D1, alpha=PI / 2), Revolute(a=A2), Revolute(a=A3)], convention="standard"
    )
