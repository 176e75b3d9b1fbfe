"""The Robot: DH table, limits, base and tool; forward kinematics and Jacobians; URDF."""

from kinematica.robot.dh_rules import DHExtraction
from kinematica.robot.load import load, robot_from_spec, spec_from_robot, write_robot_file
from kinematica.robot.robot import Robot
from kinematica.robot.structure import Structure, classify
from kinematica.robot.urdf import urdf_to_dh

__all__ = [
    "DHExtraction",
    "Robot",
    "Structure",
    "classify",
    "load",
    "robot_from_spec",
    "spec_from_robot",
    "urdf_to_dh",
    "write_robot_file",
]
