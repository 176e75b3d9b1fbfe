"""Robots from descriptions: robot files, built-in models, :class:`RobotSpec`."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from kinematica.dh import Joint, Prismatic, Revolute
from kinematica.errors import UnknownRobotError
from kinematica.io import (
    ROBOT_FILE_SUFFIXES,
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


def load(name_or_path: str | os.PathLike[str]) -> Robot:
    """Load a built-in model by name, or a robot file by path.

    Args:
        name_or_path: A built-in name (see ``kinematica robots``) or a path to a
            ``.yaml``/``.yml``/``.json``/``.toml`` robot file.

    Returns:
        The robot.

    Raises:
        UnknownRobotError: Neither a built-in name nor an existing file.
        RobotFileError: The file is malformed (the message says where).
    """
    text = os.fspath(name_or_path)
    path = Path(text)
    if path.suffix.lower() in ROBOT_FILE_SUFFIXES or path.exists() or os.sep in text:
        if not path.exists():
            raise UnknownRobotError(f"{text}: no such robot file")
        return robot_from_spec(read_robot_file(path))
    if text in builtin_names() or text.lower() in builtin_names():
        return robot_from_spec(read_builtin(text))
    return robot_from_spec(read_builtin(text))  # raises UnknownRobotError with suggestions
