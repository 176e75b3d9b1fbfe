"""The arm as a product of exponentials: joint screws read from its DH table.

Each joint is a line in space at q = 0 (``robot.joint_axes()``): a unit
direction ``h_i`` and a point ``p_i`` (base frame). A revolute joint turning by
``q_i`` rotates everything after it about that line; a prismatic joint slides
it by ``q_i h_i``. With ``M = robot.fk(0)`` the home pose, forward kinematics
is exactly::

    T(q) = exp(ξ1 q1) · exp(ξ2 q2) ··· exp(ξn qn) · M

whatever the DH convention, offsets, base and tool (Brockett's formula; the
tests check it against ``robot.fk``). Closed-form solvers work on this form:
it turns "where does joint i move this point" into rotations about known lines.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.ik.analytic.subproblems import rotation_matrix

if TYPE_CHECKING:
    from kinematica.robot import Robot

__all__ = ["Screws", "screw_motion"]

FloatArray = NDArray[np.float64]


def screw_motion(h: ArrayLike, p: ArrayLike, prismatic: bool, q: ArrayLike) -> FloatArray:
    """The rigid motion ``exp(ξ q)`` of one joint.

    Args:
        h: ``(3,)`` unit axis direction (base frame).
        p: ``(3,)`` a point on the axis (base frame, metres).
        prismatic: True for a slide along ``h``, False for a rotation about the line.
        q: ``(...)`` joint values (rad or m).

    Returns:
        ``(..., 4, 4)``: ``[R(h, q), (I - R) p]`` or ``[I, q h]``.
    """
    hh, pp, qq = np.asarray(h, float), np.asarray(p, float), np.asarray(q, float)
    T = np.zeros((*qq.shape, 4, 4))
    T[..., 3, 3] = 1.0
    if prismatic:
        T[..., :3, :3] = np.eye(3)
        T[..., :3, 3] = qq[..., None] * hh
    else:
        R = rotation_matrix(hh, qq)
        T[..., :3, :3] = R
        T[..., :3, 3] = pp - R @ pp
    return T


@dataclass(frozen=True, eq=False)
class Screws:
    """An arm's joint screws at q = 0 and its home pose.

    Attributes:
        directions: ``(n, 3)`` unit axis directions, base frame.
        points: ``(n, 3)`` one point on each axis, base frame (metres).
        prismatic: ``(n,)`` True for prismatic joints.
        home: ``(4, 4)`` tool pose at q = 0, ``M = robot.fk(0)``.
    """

    directions: FloatArray
    points: FloatArray
    prismatic: NDArray[np.bool_]
    home: FloatArray

    @classmethod
    def from_robot(cls, robot: Robot) -> Screws:
        """The screws of ``robot`` (from ``joint_axes()`` and ``fk`` at q = 0)."""
        h, p = robot.joint_axes()
        return cls(
            directions=np.array(h, dtype=float),
            points=np.array(p, dtype=float),
            prismatic=robot.is_prismatic,
            home=np.array(robot.fk(np.zeros(robot.dof)), dtype=float),
        )

    @property
    def dof(self) -> int:
        """Number of joints n."""
        return len(self.prismatic)

    def fk(self, q: ArrayLike) -> FloatArray:
        """Forward kinematics by the product of exponentials.

        Args:
            q: ``(..., n)`` joint values.

        Returns:
            ``(..., 4, 4)`` tool pose in the base frame.
        """
        qq = np.asarray(q, dtype=float)
        T = np.broadcast_to(np.eye(4), (*qq.shape[:-1], 4, 4))
        for i in range(self.dof):
            E = screw_motion(
                self.directions[i], self.points[i], bool(self.prismatic[i]), qq[..., i]
            )
            T = T @ E
        return T @ self.home
