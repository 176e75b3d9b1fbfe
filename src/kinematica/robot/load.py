"""Robots from descriptions: robot files, built-in models, :class:`RobotSpec`."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from kinematica.dh import Joint, Prismatic, Revolute
from kinematica.errors import KinematicaError, UnknownRobotError
from kinematica.io import (
    ROBOT_FILE_SUFFIXES,
    URDF_SUFFIXES,
    FrameSpec,
    JointSpec,
    RobotSpec,
    builtin_names,
    read_builtin,
    read_robot_file,
)
from kinematica.robot.robot import Robot

__all__ = ["load", "robot_from_spec", "spec_from_robot"]

FloatArray = NDArray[np.float64]


def _joint(spec: JointSpec) -> Joint:
    if spec.kind == "R":
        return Revolute(
            d=spec.d, a=spec.a, alpha=spec.alpha, offset=spec.theta, qlim=spec.qlim, name=spec.name
        )
    return Prismatic(
        theta=spec.theta, a=spec.a, alpha=spec.alpha, offset=spec.d, qlim=spec.qlim, name=spec.name
    )


def robot_from_spec(spec: RobotSpec) -> Robot:
    """Build a :class:`Robot` from a parsed description.

    Args:
        spec: What a robot file (or built-in model) says, in radians and metres.

    Returns:
        The robot.
    """
    return Robot.from_dh(
        [_joint(j) for j in spec.joints],
        convention=spec.convention,
        name=spec.name,
        base=None if spec.base is None else spec.base.as_matrix(),
        tool=None if spec.tool is None else spec.tool.as_matrix(),
        description=spec.description,
    )


def spec_from_robot(robot: Robot) -> RobotSpec:
    """The description of a robot, for writing it to a file."""
    joints = [
        JointSpec(
            kind=link.type,
            theta=link.theta,  # the offset of a revolute joint
            d=link.d,  # the offset of a prismatic joint
            a=link.a,
            alpha=link.alpha,
            qlim=link.qlim,
            name=link.name,
        )
        for link in robot.links
    ]

    def frame(T: FloatArray) -> FrameSpec | None:
        if np.array_equal(T, np.eye(4)):
            return None
        return FrameSpec(matrix=tuple(tuple(float(v) for v in row) for row in T))

    return RobotSpec(
        name=robot.name,
        convention=robot.convention,
        joints=tuple(joints),
        base=frame(robot.base),
        tool=frame(robot.tool),
        description=robot.description,
        units={"angle": "rad", "length": "m"},
    )


def load(
    name_or_path: str | os.PathLike[str],
    *,
    base: str | None = None,
    tip: str | None = None,
    convention: str | None = None,
) -> Robot:
    """Load a built-in model by name, a robot file or a URDF by path.

    Args:
        name_or_path: A built-in name (see ``kinematica robots``), a path to a
            ``.yaml``/``.yml``/``.json``/``.toml`` robot file, or a ``.urdf``
            file (``.xacro`` too, expanded with the ``xacro`` package).
        base: URDF only: the base link of the chain (default the root link).
        tip: URDF only: the tip link (default the single leaf at the end of
            movable joints; the error lists the leaves when there are several).
        convention: URDF only: the DH convention of the extracted table,
            ``"standard"`` (default) or ``"modified"``; see
            :func:`kinematica.urdf_to_dh` for the rules and what they chose.

    Returns:
        The robot. A URDF's robot has the URDF's forward kinematics, its joint
        names and limits (continuous joints get none).

    Raises:
        UnknownRobotError: Neither a built-in name nor an existing file.
        RobotFileError: The file is malformed (the message says where).
        KinematicaError: ``base``, ``tip`` or ``convention`` for a robot that is
            not a URDF.
    """
    text = os.fspath(name_or_path)
    path = Path(text)
    if path.name.lower().endswith(URDF_SUFFIXES):
        from kinematica.robot.urdf import robot_from_urdf

        if not path.exists():
            raise UnknownRobotError(f"{text}: no such URDF file")
        return robot_from_urdf(path, base=base, tip=tip, convention=convention or "standard")
    given = [k for k, v in (("base", base), ("tip", tip), ("convention", convention)) if v]
    if given:
        raise KinematicaError(
            f"{', '.join(given)}: only for URDF files (.urdf, .xacro), and {text!r} is not one"
        )
    if path.suffix.lower() in ROBOT_FILE_SUFFIXES or path.exists() or os.sep in text:
        if not path.exists():
            raise UnknownRobotError(f"{text}: no such robot file")
        return robot_from_spec(read_robot_file(path))
    if text in builtin_names() or text.lower() in builtin_names():
        return robot_from_spec(read_builtin(text))
    return robot_from_spec(read_builtin(text))  # raises UnknownRobotError with suggestions
