"""The Robot: DH table, limits, base and tool; forward kinematics and Jacobians; URDF."""

# ruff: noqa: F401 (the imports are the public names; kinematica._lazy makes __all__)

from typing import TYPE_CHECKING

from kinematica._lazy import exports
from kinematica.robot.load import load, robot_from_spec, spec_from_robot, write_robot_file
from kinematica.robot.robot import Robot

if TYPE_CHECKING:  # the names below load on first use (kinematica._lazy): the IK layer, URDF
    from kinematica.robot.dh_rules import DHExtraction
    from kinematica.robot.structure import Structure, classify
    from kinematica.robot.urdf import urdf_to_dh

__getattr__, __dir__, __all__ = exports(__name__)
