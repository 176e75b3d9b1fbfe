"""The Robot: DH table, limits, base and tool; forward kinematics and Jacobians."""

from kinematica.robot.robot import Robot

__all__ = ["Robot"]
