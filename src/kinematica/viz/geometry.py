"""What a drawing of the arm shows, as numbers: frames, joint shapes, arrows, size.

Pure numpy over the public ``Robot`` API, no matplotlib: the drawing modules
turn these arrays into artists, and the tests check them directly.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.robot import Robot
from kinematica.spatial import inv_transform

__all__ = [
    "PLANAR_TOL",
    "ArmPose",
    "arm_pose",
    "arrow_segments",
    "box",
    "cylinder",
    "drawing_plane",
    "plane_normal_sign",
    "robot_scale",
]

FloatArray = NDArray[np.float64]

#: A joint axis counts as parallel (revolute) or perpendicular (prismatic) to a
#: world axis for the 2-D view when the sine (cross product) or cosine (dot
#: product) of the angle between them is below this.
PLANAR_TOL = 1e-9

#: Arrow length of a drawn frame, as a fraction of :func:`robot_scale`.
ARROW = 0.12
#: Radius of a drawn joint, as a fraction of :func:`robot_scale`.
JOINT_RADIUS = 0.025
#: Arrow head length and half-width, as fractions of the arrow length.
HEAD_LENGTH, HEAD_WIDTH = 0.25, 0.1


@dataclass(frozen=True)
class ArmPose:
    """Everything drawn of an arm at joint values ``q`` of shape ``(..., n)``.

    Attributes:
        origins: ``(..., n+1, 3)`` the points the links line passes through,
            the origins of ``robot.fk(q, all_frames=True)``: S0 (the base),
            S1, ..., S(n-1), then the tool (Sn with the tool transform).
        frames: ``(..., n+1, 4, 4)`` the DH frames S0..Sn (Sn without the tool).
        tool: ``(..., 4, 4)`` the tool frame, ``robot.fk(q)``.
        joints: ``(..., n, 4, 4)`` for each joint, a frame whose z axis is the
            joint axis and whose origin lies on it: S(i-1) for joint i in the
            standard convention, Si in the modified one.
    """

    origins: FloatArray
    frames: FloatArray
    tool: FloatArray
    joints: FloatArray


def arm_pose(robot: Robot, q: ArrayLike) -> ArmPose:
    """The frames of ``robot`` at ``q`` (rad, m), any leading batch shape.

    Args:
        robot: The robot.
        q: ``(..., n)`` joint values.

    Returns:
        The :class:`ArmPose` (world frame, metres).
    """
    Fs = robot.fk(q, all_frames=True)
    n = robot.dof
    tool = Fs[..., n, :, :]
    frames = Fs.copy()
    frames[..., n, :, :] = tool @ inv_transform(robot.tool)
    joints = frames[..., :n, :, :] if robot.convention == "standard" else frames[..., 1:, :, :]
    return ArmPose(origins=Fs[..., :3, 3], frames=frames, tool=tool.copy(), joints=joints)


def robot_scale(robot: Robot) -> float:
    """A length (m) that sizes arrows and joints: the sum of the link lengths.

    Adds ``|a|`` and ``|d|`` of every row, the stroke of prismatic joints with
    finite limits, and the tool offset; 1 m for an arm with none of these.
    """
    table = robot.dh_table()
    total = float(np.abs(table[:, 1]).sum() + np.abs(table[:, 2]).sum())
    for lim, prismatic in zip(robot.qlim, robot.is_prismatic, strict=True):
        if prismatic and np.all(np.isfinite(lim)):
            total += float(np.max(np.abs(lim)))
    total += float(np.linalg.norm(robot.tool[:3, 3]))
    return total if total > 1e-9 else 1.0


def drawing_plane(robot: Robot) -> tuple[int, int] | None:
    """The two world coordinates of a planar arm's plane, or ``None``.

    An arm is drawn in 2-D when every revolute axis is parallel to one world
    axis and every prismatic axis perpendicular to it (within
    :data:`PLANAR_TOL`): it then moves in planes normal to that axis, for every
    ``q``. World z is tried first (plane ``(0, 1)``: x right, y up), then y
    (``(0, 2)``: x, z) and x (``(1, 2)``: y, z).
    """
    h, _ = robot.joint_axes()
    prismatic = robot.is_prismatic
    for k, plane in ((2, (0, 1)), (1, (0, 2)), (0, (1, 2))):
        e = np.zeros(3)
        e[k] = 1.0
        sines = np.linalg.norm(np.cross(h, e), axis=-1)
        cosines = np.abs(h @ e)
        off = np.where(prismatic, cosines, sines)
        if np.all(off < PLANAR_TOL):
            return plane
    return None


def plane_normal_sign(plane: tuple[int, int]) -> float:
    """+1 when the world axis normal to ``plane`` points out of the screen, else -1.

    The screen shows the first coordinate to the right and the second up; the
    out-of-screen direction is their cross product.
    """
    return {(0, 1): 1.0, (0, 2): -1.0, (1, 2): 1.0}[plane]


def cylinder(frame: FloatArray, radius: float, height: float, segments: int = 12) -> FloatArray:
    """Faces of a closed cylinder along the z axis of ``frame``, centred on its origin.

    Args:
        frame: ``(4, 4)`` pose (world frame).
        radius: Radius, m.
        height: Length along z, m.
        segments: Number of side faces.

    Returns:
        ``(segments + 2, segments, 3)`` polygons: the side quads (padded by
        repeating their last corner) and the two caps.
    """
    ang = np.linspace(0.0, 2.0 * np.pi, segments, endpoint=False)
    ring = np.stack([radius * np.cos(ang), radius * np.sin(ang), np.zeros(segments)], axis=1)
    half = np.array([0.0, 0.0, height / 2.0])
    bottom, top = ring - half, ring + half
    faces = np.empty((segments + 2, segments, 3))
    nxt = np.roll(np.arange(segments), -1)
    quads = np.stack([bottom, bottom[nxt], top[nxt], top], axis=1)  # (segments, 4, 3)
    faces[:segments, :4] = quads
    faces[:segments, 4:] = quads[:, 3:4]
    faces[segments] = bottom
    faces[segments + 1] = top
    R, p = frame[:3, :3], frame[:3, 3]
    return np.asarray(faces @ R.T + p, dtype=np.float64)


def box(frame: FloatArray, half: tuple[float, float, float]) -> FloatArray:
    """Faces ``(6, 4, 3)`` of a box with half-sizes ``half`` along the axes of ``frame``."""
    sx, sy, sz = half
    c = np.array([[x, y, z] for x in (-sx, sx) for y in (-sy, sy) for z in (-sz, sz)])
    idx = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)]
    faces = c[np.array(idx)]
    R, p = frame[:3, :3], frame[:3, 3]
    return np.asarray(faces @ R.T + p, dtype=np.float64)


def arrow_segments(frame: FloatArray, length: float) -> FloatArray:
    """Line segments ``(3, 3, 2, 3)`` of the x, y, z arrows of ``frame``.

    Index ``[axis, part]``: part 0 is the shaft from the origin, parts 1 and 2
    the two strokes of the head (in the plane of the axis and the next one).
    """
    o, R = frame[:3, 3], frame[:3, :3]
    out = np.empty((3, 3, 2, 3))
    for j in range(3):
        e, side = R[:, j], R[:, (j + 1) % 3]
        tip = o + length * e
        back = tip - HEAD_LENGTH * length * e
        out[j, 0] = (o, tip)
        out[j, 1] = (tip, back + HEAD_WIDTH * length * side)
        out[j, 2] = (tip, back - HEAD_WIDTH * length * side)
    return out
