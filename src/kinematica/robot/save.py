"""A robot back to a robot file: as it was written, wherever it still is the robot."""

from __future__ import annotations

import dataclasses
import os
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from kinematica.errors import ArgumentError
from kinematica.io.spec import ChainSpec, FrameSpec, JointSpec, RobotSpec, frame_of
from kinematica.robot.frames import rigid_frame

if TYPE_CHECKING:
    from kinematica.robot.description import RobotDescription

__all__ = ["spec_from_robot", "write_robot_file"]

FloatArray = NDArray[np.float64]


def _is_robot(value: object) -> bool:
    """True for a :class:`~kinematica.Robot` (told by what it holds: no import cycle)."""
    return all(hasattr(value, k) for k in ("links", "convention", "base", "tool", "source_spec"))


def _as_built(written: FrameSpec | None) -> FloatArray:
    """The transform a robot makes of a written base or tool.

    A rotation written with few digits is projected onto SO(3), as the robot does.
    """
    return np.eye(4) if written is None else rigid_frame(written.as_matrix(), "frame")


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
    return frame_of(T)


def _chain(robot: RobotDescription) -> ChainSpec | None:
    """The robot's own transforms (a URDF's, a calibration's), or ``None`` for a DH robot."""
    t = robot.transforms
    if t is None:
        return None
    return ChainSpec(
        start=frame_of(t.start),
        between=tuple(frame_of(T) for T in t.between),
        end=frame_of(t.end),
        frames=tuple(frame_of(T) for T in t.frame_offsets),
    )


def spec_from_robot(robot: RobotDescription) -> RobotSpec:
    """The description of a robot, for writing it to a file.

    For a robot read from a file (``robot.source_spec``), every part that
    still describes the robot keeps the file's writing: units, parameters and
    the expression of each unchanged joint (``q2 + 90`` in degrees stays
    ``q2 + 90``), base and tool as written. Parts changed since (by
    :meth:`Robot.with_tool`, :meth:`Robot.with_limits`,
    :meth:`Robot.to_convention`...) are described by their numbers.

    A robot that computes with its own transforms (read from a URDF, or calibrated)
    keeps them, in the ``chain`` block: the file reproduces it exactly, its DH table
    describing it.

    Args:
        robot: The robot.

    Returns:
        The description, in radians and metres, with the texts it keeps.
    """
    if not _is_robot(robot):
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
            chain=_chain(robot),
        )
    return RobotSpec(
        name=robot.name,
        convention=robot.convention,
        joints=tuple(joints),
        base=_frame(robot.base, written.base, _as_built(written.base)),
        tool=_frame(robot.tool, written.tool, _as_built(written.tool)),
        parameters=written.parameters,
        source=written.source,
        description=robot.description,
        units=written.units,
        reference=written.reference,
        parameter_texts=written.parameter_texts,
        chain=_chain(robot),
    )


def write_robot_file(robot: RobotDescription | RobotSpec, path: str | os.PathLike[str]) -> None:
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
    if isinstance(robot, RobotSpec):
        spec = robot
    elif _is_robot(robot):
        spec = spec_from_robot(robot)
    else:
        raise ArgumentError(f"expected a Robot or a RobotSpec, got {type(robot).__name__}")
    from kinematica.io.robotfile import write_robot_file as write_spec_file  # the writers

    write_spec_file(spec, path)
