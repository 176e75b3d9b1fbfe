"""The calibrated arm as kinematica describes robots: exact chain, URDF and DH table.

The fitted chain (:meth:`ErrorModel.transforms`) is written as a URDF chain: one joint
per motion, turning about (or sliding along) the z axis of its origin, each origin the
fixed transform before it. kinematica reads such a chain exactly
(:func:`kinematica.urdf_to_dh`): the calibrated :class:`~kinematica.Robot` computes with
the fitted transforms themselves (FK equal to the model's to round-off) and carries the
DH table the DH rules read off its axes as its description, with that table's
``fk_error``. The URDF text reproduces the robot exactly (its numbers are written with
the shortest decimal that reads back to the same float), and so does its robot file
(``robot.save``: the DH table, and the arm's own transforms in its ``chain`` block). The
DH table alone reproduces it to its ``fk_error``, which is round-off unless consecutive
axes are nearly parallel (there a DH table needs a far common normal and loses digits).
"""

from __future__ import annotations

import warnings
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from kinematica.errors import UnitWarning
from kinematica.io import UrdfChain, UrdfJoint, UrdfModel, urdf_text
from kinematica.io.spec import frame_of
from kinematica.robot.urdf import urdf_to_dh

if TYPE_CHECKING:
    from kinematica.calibration.model import ErrorModel
    from kinematica.robot import DHExtraction, Robot

__all__ = ["calibrated_chain", "calibrated_extraction", "calibrated_urdf"]

FloatArray = NDArray[np.float64]


def _names(robot: Robot) -> list[str]:
    names = list(robot.joint_names)
    return names if len(set(names)) == len(names) else [f"joint{i + 1}" for i in range(robot.dof)]


def calibrated_chain(robot: Robot, model: ErrorModel, delta: FloatArray) -> UrdfChain:
    """The fitted chain as a URDF chain ``world -> link1 -> ... -> tool0``.

    Args:
        robot: The nominal robot (joint names, kinds and limits).
        model: Its error model.
        delta: ``(6 n + 12,)`` the fitted parameters.
    """
    start, between, end = model.transforms(delta)
    origins = [start, *between]
    joints = []
    parent = "world"
    for i, (link, name) in enumerate(zip(robot.links, _names(robot), strict=True)):
        kind = "prismatic" if link.type == "P" else ("revolute" if link.qlim else "continuous")
        child = f"link{i + 1}"
        joints.append(
            UrdfJoint(name, kind, parent, child, frame_of(origins[i]), (0.0, 0.0, 1.0), link.qlim)
        )
        parent = child
    joints.append(UrdfJoint("tool0_joint", "fixed", parent, "tool0", frame_of(end)))
    return UrdfChain(name=robot.name, base="world", tip="tool0", joints=tuple(joints))


def _model(chain: UrdfChain) -> UrdfModel:
    links = (chain.base, *(j.child for j in chain.joints))
    return UrdfModel(name=chain.name, links=links, joints=chain.joints)


def calibrated_extraction(
    robot: Robot, model: ErrorModel, delta: FloatArray, convention: str | None = None
) -> DHExtraction:
    """The calibrated robot (exact) and its DH table (``.fk_error``), by the DH rules.

    Args:
        robot: The nominal robot.
        model: Its error model.
        delta: The fitted parameters.
        convention: Of the DH table; default the nominal robot's.

    Returns:
        The extraction: ``.robot`` computes with the fitted transforms (exact),
        its ``links`` the DH table; ``.fk_error`` how far that table alone is.
    """
    chain = calibrated_chain(robot, model, delta)
    with warnings.catch_warnings():
        # nearly parallel axes give a DH table lengths of metres (the common normal is
        # far away): the table's values are what they are, not a unit slip
        warnings.simplefilter("ignore", UnitWarning)
        return urdf_to_dh(_model(chain), convention=convention or robot.convention)


def calibrated_urdf(robot: Robot, model: ErrorModel, delta: FloatArray) -> str:
    """The URDF text of the fitted chain (reads back to the same FK, to round-off)."""
    return urdf_text(
        calibrated_chain(robot, model, delta),
        comment=f"{robot.name}, calibrated by kinematica: kinematics only "
        "(effort and velocity unknown: 0).",
    )
