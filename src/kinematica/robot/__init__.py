"""The Robot: DH table, limits, base and tool; forward kinematics and Jacobians."""

from kinematica.robot.load import load, robot_from_spec, spec_from_robot, write_robot_file
from kinematica.robot.robot import Robot
from kinematica.robot.structure import Structure, classify

__all__ = [
    "Robot",
    "Structure",
    "classify",
    "load",
    "robot_from_spec",
    "spec_from_robot",
    "write_robot_file",
]
