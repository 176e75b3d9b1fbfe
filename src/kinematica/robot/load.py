"""Robots from descriptions and back: robot files, built-in models, :class:`RobotSpec`."""

from __future__ import annotations

import dataclasses
import os
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from kinematica.dh import Joint, Prismatic, Revolute
from kinematica.dh.joints import values_checked
from kinematica.errors import ArgumentError, KinematicaError, UnknownRobotError
from kinematica.io import (
    ROBOT_FILE_SUFFIXES,
    URDF_SUFFIXES,
    FrameSpec,
    JointSpec,
    RobotSpec,
    read_builtin,
    read_robot_file,
)
from kinematica.io import write_robot_file as write_spec_file
from kinematica.robot.robot import Robot

__all__ = ["load", "robot_from_spec", "spec_from_robot", "write_robot_file"]

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
        The robot, with ``source_spec`` set to ``spec`` (so that
        :meth:`Robot.save` writes the file back as it was written).
    """
    if not isinstance(spec, RobotSpec):
        raise ArgumentError(f"expected a RobotSpec, got {type(spec).__name__}")
    with values_checked():  # the file reader has warned, naming file, joint and key
        joints = [_joint(j) for j in spec.joints]
    return Robot(  # the dataclass validates links, convention, base and tool
        links=tuple(joints),
        convention=spec.convention,
        name=spec.name,
        base=np.eye(4) if spec.base is None else spec.base.as_matrix(),
        tool=np.eye(4) if spec.tool is None else spec.tool.as_matrix(),
        description=spec.description,
        source_spec=spec,
    )


def _frame(T: FloatArray, written: FrameSpec | None, T_written: FloatArray) -> FrameSpec | None:
    """The spec of a base/tool transform ``T``: as written when it still is ``T``.

    ``T_written`` is the transform the robot made of ``written`` when it was
    built (which may differ from ``written.as_matrix()`` by the projection of
    a rotation written with few digits onto the nearest rotation).
    """
    if np.array_equal(T, T_written):
        return written
    if np.array_equal(T, np.eye(4)):
        return None
    if np.array_equal(T[:3, :3], np.eye(3)):
        return FrameSpec(xyz=(float(T[0, 3]), float(T[1, 3]), float(T[2, 3])))
    return FrameSpec(matrix=tuple(tuple(float(v) for v in row) for row in T))


def spec_from_robot(robot: Robot) -> RobotSpec:
    """The description of a robot, for writing it to a file.

    For a robot read from a file (``robot.source_spec``), every part that
    still describes the robot keeps the file's writing: units, parameters and
    the expression of each unchanged joint (``q2 + 90`` in degrees stays
    ``q2 + 90``), base and tool as written. Parts changed since (by
    :meth:`Robot.with_tool`, :meth:`Robot.with_limits`,
    :meth:`Robot.to_convention`...) are described by their numbers.

    Args:
        robot: The robot.

    Returns:
        The description, in radians and metres, with the texts it keeps.
    """
    if not isinstance(robot, Robot):
        raise ArgumentError(f"expected a Robot, got {type(robot).__name__}")
    written = robot.source_spec
    same_table = written is not None and written.convention == robot.convention
    identity = np.eye(4)
    joints = []
    for i, link in enumerate(robot.links):
        joint = JointSpec(
            kind=link.type,
            theta=link.theta,  # the offset of a revolute joint
            d=link.d,  # the offset of a prismatic joint
            a=link.a,
            alpha=link.alpha,
            qlim=link.qlim,
            name=link.name,
        )
        if written is not None and same_table and i < written.dof:
            before = written.joints[i]
            if dataclasses.replace(joint, qlim=before.qlim) == before:  # same DH row
                joint = dataclasses.replace(joint, expr=before.expr)
        joints.append(joint)
    if written is None:
        return RobotSpec(
            name=robot.name,
            convention=robot.convention,
            joints=tuple(joints),
            base=_frame(robot.base, None, identity),
            tool=_frame(robot.tool, None, identity),
            description=robot.description,
            units={"angle": "rad", "length": "m"},
        )
    as_written = robot_from_spec(written)  # base and tool as the robot made them
    return RobotSpec(
        name=robot.name,
        convention=robot.convention,
        joints=tuple(joints),
        base=_frame(robot.base, written.base, as_written.base),
        tool=_frame(robot.tool, written.tool, as_written.tool),
        parameters=written.parameters,
        source=written.source,
        description=robot.description,
        units=written.units,
        reference=written.reference,
        parameter_texts=written.parameter_texts,
    )


def write_robot_file(robot: Robot | RobotSpec, path: str | os.PathLike[str]) -> None:
    """Write a robot as a robot file; the extension picks the format.

    A robot read from a file is written as the file was (see
    :func:`spec_from_robot`): units, parameters and expressions, degrees as
    degrees. ``kinematica.load(path)`` then gives back the same robot.

    Args:
        robot: The robot, or its :class:`RobotSpec`.
        path: Where to write: ``.yaml``/``.yml`` (needs PyYAML), ``.json`` or
            ``.toml``. An existing file is replaced.

    Raises:
        RobotFileError: unknown extension, or the file cannot be written.
        ArgumentError: ``robot`` is neither a Robot nor a RobotSpec.
    """
    if isinstance(robot, Robot):
        spec = spec_from_robot(robot)
    elif isinstance(robot, RobotSpec):
        spec = robot
    else:
        raise ArgumentError(f"expected a Robot or a RobotSpec, got {type(robot).__name__}")
    write_spec_file(spec, path)


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
        ArgumentError: ``name_or_path`` is not text or a path.
        KinematicaError: ``base``, ``tip`` or ``convention`` for a robot that is
            not a URDF.
    """
    if not isinstance(name_or_path, str | os.PathLike):
        raise ArgumentError(
            "load takes a built-in robot name or the path of a robot file, "
            f"got {type(name_or_path).__name__}"
        )
    text = os.fspath(name_or_path)
    if not isinstance(text, str) or not text.strip():
        raise ArgumentError(f"load takes a built-in robot name or a path, got {text!r}")
    path = Path(text)
    try:
        exists = path.exists()
    except OSError:  # e.g. a name too long for the file system: not a file
        exists = False
    if path.name.lower().endswith(URDF_SUFFIXES):
        from kinematica.robot.urdf import robot_from_urdf

        if not exists:
            raise UnknownRobotError(f"{text}: no such URDF file")
        return robot_from_urdf(path, base=base, tip=tip, convention=convention or "standard")
    given = [k for k, v in (("base", base), ("tip", tip), ("convention", convention)) if v]
    if given:
        raise KinematicaError(
            f"{', '.join(given)}: only for URDF files (.urdf, .xacro), and {text!r} is not one"
        )
    if path.suffix.lower() in ROBOT_FILE_SUFFIXES or exists or os.sep in text:
        if not exists:
            raise UnknownRobotError(f"{text}: no such robot file")
        return robot_from_spec(read_robot_file(path))
    return robot_from_spec(read_builtin(text))  # raises UnknownRobotError with suggestions
