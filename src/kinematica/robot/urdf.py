"""URDF in: a Robot from any serial chain of a URDF file.

The chain's joint axes get DH frames by the rules (:mod:`kinematica.robot.dh_rules`);
the robot's forward kinematics equals the URDF's.
"""

from __future__ import annotations

import os

from kinematica.dh import check_convention
from kinematica.io import UrdfModel, read_urdf
from kinematica.robot.dh_rules import DHExtraction, dh_from_chain
from kinematica.robot.robot import Robot

__all__ = ["robot_from_urdf", "urdf_to_dh"]


def urdf_to_dh(
    urdf: str | os.PathLike[str] | UrdfModel,
    *,
    base: str | None = None,
    tip: str | None = None,
    convention: str = "standard",
) -> DHExtraction:
    """Read a URDF and extract the DH table of its chain from ``base`` to ``tip``.

    Args:
        urdf: A ``.urdf`` file (``.xacro`` too, with the ``xacro`` package), or
            a parsed :class:`~kinematica.io.UrdfModel`.
        base: Base link; default the root link.
        tip: Tip link; default the single leaf at the end of movable joints
            (the error lists the leaves when there are several).
        convention: ``"standard"`` or ``"modified"``.

    Returns:
        The :class:`DHExtraction`: ``.robot`` (FK equal to the URDF's),
        ``.rules`` (which rule placed each frame), ``.fk_error``.

    Raises:
        RobotFileError: the file cannot be read, is hostile or malformed, or
            the chain holds a joint kinematica cannot model (the message names
            the file, the joint or link, and the problem).
    """
    check_convention(convention)
    model = urdf if isinstance(urdf, UrdfModel) else read_urdf(urdf)
    chain = model.chain(base, tip)
    source = f"URDF {chain.source}" if chain.source else "URDF"
    return dh_from_chain(
        chain,
        convention,
        make=Robot.from_dh,
        description=f"{source}, chain {chain.base} -> {chain.tip}",
    )


def robot_from_urdf(
    urdf: str | os.PathLike[str] | UrdfModel,
    *,
    base: str | None = None,
    tip: str | None = None,
    convention: str = "standard",
) -> Robot:
    """The robot of a URDF chain (see :func:`urdf_to_dh`)."""
    return urdf_to_dh(urdf, base=base, tip=tip, convention=convention).robot
