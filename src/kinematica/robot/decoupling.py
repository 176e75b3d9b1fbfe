"""The spherical wrist's kinematic decoupling, step by step (seed 002).

An arm whose last three axes meet in one point, the wrist centre, is solved in two
halves. Seed 002 ("Fundamentos de Robótica: Cinemática Inversa") writes the steps:

1. the wrist centre p_m = p - d6·R·z (in general: the point fixed in the tool where
   axes 4-6 meet, :func:`wrist_center`);
2. joints 1-3 place it: the arm solutions (a 3-joint position problem);
3. for each, R03, the rotation of frame 3, and R36 = R03ᵀ·R06, the rotation the wrist
   has to make (R06: the target's rotation of DH frame 6, the tool removed);
4. joints 4-6 make R36: the wrist solutions (two of a generic spherical wrist).

:func:`decouple` returns every step. The arm solutions come from the 3-joint arm of
joints 1-3 carrying the wrist centre; the wrist solutions are the robot's closed-form
IK solutions that share each arm solution (the closed form solves the wrist from the
same R36), each checked here: the wrist's rotation at them is R36.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import KinematicaError
from kinematica.ik import IKResult
from kinematica.spatial import check_transform, wrap_angle

if TYPE_CHECKING:
    from kinematica.robot.inverse import RobotIK

__all__ = ["ARM_MATCH_TOL", "ArmStep", "Decoupling", "decouple", "wrist_center", "wrist_offset"]

FloatArray = NDArray[np.float64]

#: A solution of the whole arm belongs to an arm solution of joints 1-3 when its
#: q1..q3 differ from it by at most this (rad, or m for a slide): the two closed forms
#: reach the same values by different roundings (1e-12 apart on a generic target);
#: a solution farther from every arm solution gets an arm step of its own.
ARM_MATCH_TOL = 1e-6
#: The joints of the arm and of the wrist.
_ARM, _WRIST = slice(0, 3), slice(3, 6)
_DOF = 6


def _wrist_point(robot: RobotIK) -> FloatArray:
    """The wrist centre at q = 0 (world frame, m), or a KinematicaError naming why none."""
    from kinematica.ik.structure import features

    f = features(robot.chain)
    if f.wrist_center is None:
        raise KinematicaError(
            f"{robot.name} ({robot.joint_types}) has no spherical wrist: its last three "
            "axes are not revolute axes meeting in one point, so it has no wrist centre"
        )
    return np.asarray(f.wrist_center, dtype=float)


def wrist_offset(robot: RobotIK) -> FloatArray:
    """Where the wrist centre sits in the tool frame (m): ``(3,)``.

    For a DH arm without a tool whose last row is ``d6`` along z6 (the seeds' arm),
    ``(0, 0, -d6)``.

    Raises:
        KinematicaError: The robot has no spherical wrist.
    """
    M = robot.fk(np.zeros(robot.dof))
    c = _wrist_point(robot)
    return M[:3, :3].T @ (c - M[:3, 3])


def wrist_center(robot: RobotIK, T: ArrayLike) -> FloatArray:
    """The wrist centre p_m of a tool pose: ``p + R·c`` with ``c`` the :func:`wrist_offset`.

    Seed 002's ``p_m = p - d6·R·z`` for an arm whose tool is frame 6.

    Args:
        robot: An arm whose last three axes meet.
        T: ``(..., 4, 4)`` tool poses in the base (world) frame.

    Returns:
        ``(..., 3)`` wrist centres, world frame (m).

    Raises:
        KinematicaError: The robot has no spherical wrist.
        DimensionError: ``T`` is not of shape ``(..., 4, 4)``.
    """
    Ta = check_transform(T, "T")
    c = wrist_offset(robot)
    return np.asarray(Ta[..., :3, :3] @ c + Ta[..., :3, 3], dtype=float)


@dataclass(frozen=True, slots=True, eq=False)
class ArmStep:
    """One arm solution and the wrist solutions that complete it.

    Attributes:
        q: ``(3,)`` q1, q2, q3 placing the wrist centre (rad, m).
        branch: The arm solution's branch (e.g. ``"shoulder right, elbow up"``).
        R03: ``(3, 3)`` rotation of DH frame 3 at ``q`` (world frame).
        R36: ``(3, 3)`` ``R03ᵀ·R06``: the rotation joints 4-6 make.
        wrist: ``(k, 3)`` q4, q5, q6 of each wrist solution (rad): those within the
            limits first, as ``robot.ik`` gives them (a turn added where the limits hold
            the angle there), then those beyond.
        wrist_branches: ``(k,)`` their branches (e.g. ``"wrist no-flip"``).
        within_limits: ``(k,)`` whether the whole configuration is within the limits.
    """

    q: FloatArray
    branch: str
    R03: FloatArray
    R36: FloatArray
    wrist: FloatArray
    wrist_branches: tuple[str, ...]
    within_limits: NDArray[np.bool_]


@dataclass(frozen=True, slots=True, eq=False)
class Decoupling:
    """The steps of the spherical wrist's decoupling for one target pose.

    Attributes:
        target: ``(4, 4)`` the tool pose.
        offset: ``(3,)`` the wrist centre in the tool frame (``(0, 0, -d6)`` on the seeds' arm).
        wrist_center: ``(3,)`` p_m, world frame (m).
        R06: ``(3, 3)`` the rotation of DH frame 6 the target asks for (tool removed).
        arm_status: The status of the arm's position problem (``"ok"``,
            ``"singular"`` for a family of arm solutions, ``"unreachable"``).
        arms: One :class:`ArmStep` per arm solution.
        status: The status of the whole IK (``robot.ik(T)``: ``"out_of_limits"`` when
            every solution is beyond the joint limits).
        message: Its message.
    """

    target: FloatArray
    offset: FloatArray
    wrist_center: FloatArray
    R06: FloatArray
    arm_status: str
    arms: tuple[ArmStep, ...]
    status: str
    message: str

    @property
    def solutions(self) -> FloatArray:
        """``(k, 6)`` every configuration, arm by arm (rad, m)."""
        rows = [np.concatenate([a.q, w]) for a in self.arms for w in a.wrist]
        return np.array(rows, dtype=float).reshape(-1, _DOF)


def _arm_robot(robot: RobotIK, c3: FloatArray) -> RobotIK:
    """Joints 1-3 with the wrist centre as their tool (its place in frame 3)."""
    tool = np.eye(4)
    tool[:3, 3] = c3
    return type(robot).from_dh(
        robot.links[_ARM],
        convention=robot.convention,
        base=robot.base,
        tool=tool,
        name=f"{robot.name}, joints 1-3",
    )


def _distance(robot: RobotIK, a: FloatArray, b: FloatArray) -> float:
    """Largest difference of two arm configurations (revolute joints modulo 2π)."""
    d = np.asarray(a - b, dtype=float)
    revolute = ~robot.is_prismatic[_ARM]
    d = np.where(revolute, wrap_angle(d), d)
    return float(np.max(np.abs(d)))


def group_by_arm(
    robot: RobotIK, arms: list[FloatArray], rows: FloatArray, tol: float = ARM_MATCH_TOL
) -> tuple[list[list[int]], list[int]]:
    """Which solution rows share each arm solution's q1..q3.

    Returns:
        ``(members, strays)``: for each arm solution the indices of the rows within
        ``tol`` of it (the nearest arm), and the rows near none.
    """
    members: list[list[int]] = [[] for _ in arms]
    strays: list[int] = []
    for i, row in enumerate(rows):
        gaps = [_distance(robot, row[_ARM], a) for a in arms]
        k = int(np.argmin(gaps)) if gaps else -1
        if k >= 0 and gaps[k] <= tol:
            members[k].append(i)
        else:
            strays.append(i)
    return members, strays


def _arm_label(branch: str) -> str:
    """The arm's part of a whole-arm branch label (without the wrist's)."""
    return ", ".join(p for p in branch.split(", ") if not p.startswith("wrist")) or branch


def _wrist_label(branch: str) -> str:
    """The wrist's part of a whole-arm branch label."""
    parts = [p.strip() for p in branch.split(",")]
    wrist = [p for p in parts if p.startswith("wrist")]
    return ", ".join(wrist) if wrist else branch


def decouple(robot: RobotIK, T: ArrayLike) -> Decoupling:
    """Seed 002's decoupling of a 6-joint arm with a spherical wrist, every step.

    Args:
        robot: A 6-joint DH arm whose last three axes meet (not a URDF robot: the
            steps are written in its DH frames).
        T: ``(4, 4)`` tool pose in the base (world) frame.

    Returns:
        The :class:`Decoupling`: p_m, the arm solutions, R03 and R36 of each, and
        the wrist solutions of each (all of them, also outside the limits: see
        ``within_limits``).

    Raises:
        KinematicaError: The robot has not 6 joints, no spherical wrist, or comes
            from a URDF.
    """
    if robot.dof != _DOF:
        raise KinematicaError(
            f"the decoupling needs 6 joints (3 for the arm, 3 for the wrist); "
            f"{robot.name} has {robot.dof}"
        )
    if robot.transforms is not None:
        raise KinematicaError(
            f"{robot.name} is read from a URDF: the decoupling's steps are written in DH "
            "frames; convert it first (robot.to_dh(), `kinematica convert --to dh`)"
        )
    Ta = check_transform(T, "T")
    if Ta.shape != (4, 4):
        raise KinematicaError(f"T must be one (4, 4) pose, got shape {Ta.shape}", arg="T")
    offset = wrist_offset(robot)
    p_m = Ta[:3, :3] @ offset + Ta[:3, 3]
    frames0 = robot.fk(np.zeros(_DOF), all_frames=True)
    c = _wrist_point(robot)
    c3 = frames0[3, :3, :3].T @ (c - frames0[3, :3, 3])
    R06 = Ta[:3, :3] @ robot.tool[:3, :3].T
    arm_res = _arm_robot(robot, c3).ik(p_m, respect_limits=False)
    whole = robot.ik(Ta)
    assert isinstance(arm_res, IKResult) and isinstance(whole, IKResult)  # one target each
    arms = [np.asarray(s, dtype=float) for s in arm_res.solutions]
    arm_branches = list(arm_res.branches)
    # within the limits first (a revolute joint's value as the limits hold it), then beyond
    rows = np.concatenate([whole.solutions, whole.out_of_limits]).reshape(-1, _DOF)
    branches = (*whole.branches, *whole.out_of_limits_branches)
    inside = np.arange(rows.shape[0]) < whole.solutions.shape[0]
    members, strays = group_by_arm(robot, arms, rows)
    solved = len(arms)
    for i in strays:  # a whole solution no arm solution gave (the arm's search found one)
        near, _ = group_by_arm(robot, arms[solved:], rows[i : i + 1])
        k = next((solved + j for j, m in enumerate(near) if m), None)
        if k is None:  # its own arm step
            arms.append(rows[i, _ARM])
            arm_branches.append(_arm_label(branches[i]))
            members.append([i])
        else:  # beside a stray with the same q1..q3
            members[k].append(i)
    # the whole robot's names of the arm solutions, as robot.ik prints them
    arm_branches = [
        _arm_label(branches[m[0]]) if m else b for b, m in zip(arm_branches, members, strict=True)
    ]
    free = robot.with_limits([None] * _DOF)  # R03 of arm solutions beyond the limits, unwarned
    steps = []
    for qa, branch, idx in zip(arms, arm_branches, members, strict=True):
        R03 = free.fk(np.concatenate([qa, np.zeros(3)]), all_frames=True)[3, :3, :3]
        wrist = rows[idx, _WRIST] if idx else np.zeros((0, 3))
        steps.append(
            ArmStep(
                q=qa,
                branch=branch,
                R03=R03,
                R36=R03.T @ R06,
                wrist=wrist,
                wrist_branches=tuple(_wrist_label(branches[i]) for i in idx),
                within_limits=inside[idx],
            )
        )
    return Decoupling(
        target=Ta,
        offset=offset,
        wrist_center=p_m,
        R06=R06,
        arm_status=arm_res.status,
        arms=tuple(steps),
        status=whole.status,
        message=whole.message,
    )
