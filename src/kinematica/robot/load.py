"""Robots from descriptions and back: robot files, built-in models, :class:`RobotSpec`."""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from kinematica.dh import Joint, Prismatic, Revolute
from kinematica.dh.joints import values_checked
from kinematica.errors import ArgumentError, KinematicaError, UnknownRobotError
from kinematica.io.builtin import read_builtin
from kinematica.io.reading import ROBOT_FILE_SUFFIXES, URDF_SUFFIXES
from kinematica.io.spec import JointSpec, RobotSpec
from kinematica.robot.robot import Robot
from kinematica.robot.save import spec_from_robot, write_robot_file
from kinematica.robot.transforms import ChainTransforms

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
    transforms = None
    if spec.chain is not None:  # the arm's own transforms: its kinematics, exactly
        c = spec.chain
        transforms = ChainTransforms(
            start=c.start.as_matrix(),
            between=np.array([f.as_matrix() for f in c.between]).reshape(len(joints) - 1, 4, 4),
            end=c.end.as_matrix(),
            frame_offsets=np.array([f.as_matrix() for f in c.frames]),
        )
    return Robot(  # the dataclass validates links, convention, base and tool
        links=tuple(joints),
        convention=spec.convention,
        name=spec.name,
        base=np.eye(4) if spec.base is None else spec.base.as_matrix(),
        tool=np.eye(4) if spec.tool is None else spec.tool.as_matrix(),
        description=spec.description,
        source_spec=spec,
        transforms=transforms,
    )


def load(
    name_or_path: str | os.PathLike[str],
    *,
    base: str | None = None,
    tip: str | None = None,
    convention: str | None = None,
    xacro: bool = False,
    xacro_env: bool = False,
    trust_xacro: bool = False,
    packages: Mapping[str, str | os.PathLike[str]] | None = None,
    xacro_args: Mapping[str, str] | None = None,
) -> Robot:
    """Load a built-in model by name, a robot file or a URDF by path.

    Args:
        name_or_path: A built-in name (see ``kinematica robots``), a path to a
            ``.yaml``/``.yml``/``.json``/``.toml`` robot file, or a ``.urdf``
            file (``.xacro`` too, expanded by kinematica's own xacro expander,
            which runs no code from the file).
        base: URDF only: the base link of the chain (default the root link).
        tip: URDF only: the tip link (default the single leaf at the end of
            movable joints; the error lists the leaves when there are several).
        convention: URDF only: the DH convention of the extracted table,
            ``"standard"`` (default) or ``"modified"``; see
            :func:`kinematica.urdf_to_dh` for the rules and what they chose.
        xacro: URDF only: expand xacro in a ``.urdf`` file too (a ``.xacro``
            file always is); without it a ``.urdf`` holding xacro is refused.
        xacro_env: URDF only: let xacro read the environment variables
            (``$(env ...)``, ``$(optenv ...)``); refused by default.
        trust_xacro: URDF only: expand xacro with the ``xacro`` package, which
            runs the file's code (in a child process with limits): only for
            files you trust; by default kinematica's own expander.
        packages: URDF only: ROS package name -> folder, for ``$(find pkg)``
            in xacro files; ``ROS_PACKAGE_PATH``, ``AMENT_PREFIX_PATH`` and the
            file's own ``package.xml`` find the others.
        xacro_args: URDF only: values of the xacro file's ``<xacro:arg>`` (as
            xacro's ``name:=value``), over their defaults.

    Returns:
        The robot. A URDF's robot has the URDF's forward kinematics, its joint
        names and limits (continuous joints get none).

    Raises:
        UnknownRobotError: Neither a built-in name nor an existing file.
        RobotFileError: The file is malformed (the message says where).
        ArgumentError: ``name_or_path`` is not text or a path.
        KinematicaError: ``base``, ``tip``, ``convention``, ``xacro``,
            ``xacro_env``, ``trust_xacro``, ``packages`` or ``xacro_args`` for
            a robot that is not a URDF.
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
        if not exists:
            raise UnknownRobotError(f"{text}: no such URDF file")
        from kinematica.robot.urdf import robot_from_urdf  # the URDF readers: only for one

        return robot_from_urdf(
            path,
            base=base,
            tip=tip,
            convention=convention or "standard",
            xacro=xacro,
            xacro_env=xacro_env,
            trust_xacro=trust_xacro,
            packages=packages,
            xacro_args=xacro_args,
        )
    urdf_only = {
        "base": base,
        "tip": tip,
        "convention": convention,
        "xacro": xacro,
        "xacro_env": xacro_env,
        "trust_xacro": trust_xacro,
        "packages": packages,
        "xacro_args": xacro_args,
    }
    given = [k for k, v in urdf_only.items() if v]
    if given:
        raise KinematicaError(
            f"{', '.join(given)}: only for URDF files (.urdf, .xacro), and {text!r} is not one"
        )
    if path.suffix.lower() in ROBOT_FILE_SUFFIXES or exists or os.sep in text:
        if not exists:
            raise UnknownRobotError(f"{text}: no such robot file")
        from kinematica.io.robotfile import read_robot_file  # its writers too: only for a file

        return robot_from_spec(read_robot_file(path))
    return robot_from_spec(read_builtin(text))  # raises UnknownRobotError with suggestions
