"""Motion: velocity kinematics, named singularities, workspace, trajectories, control.

Layer 6: built on the robot and ik layers (public API only); numpy only. The
velocity kinematics (measures, ellipsoids, Hessian and J̇), the named
singularities and the sampling of joint space live in the robot layer
(``Robot.jacobian(euler=)``, ``Robot.singularities``, ``Robot.random_q``, ``Robot.self_motion`` are
thin methods over them) and are re-exported here. The names load on first use
(:mod:`kinematica._lazy`): timing a path does not import the Cartesian paths, the
singularities or the IK layer.
"""

import sys
import types
from typing import TYPE_CHECKING, Any

from kinematica._lazy import exports

if TYPE_CHECKING:  # the names below load on first use (kinematica._lazy)
    from kinematica.motion.cartesian import (
        MAX_JOINT_STEP,
        CartesianPath,
        PathEvent,
        cartesian_path,
    )
    from kinematica.motion.cartesian_via import ROTATION_LENGTH, cartesian_via_path
    from kinematica.motion.control import RateControl, resolved_rate
    from kinematica.motion.export import read_csv, write_csv, write_json
    from kinematica.motion.optimal import Slowdown, TimeOptimal, time_optimal
    from kinematica.motion.piecewise import PiecewisePolynomial
    from kinematica.motion.scurve import JerkTrajectory
    from kinematica.motion.trajectory import (
        JointTrajectory,
        joint_trajectory,
        minimum_time,
        time_scaling,
    )
    from kinematica.motion.via import via_polynomials, via_trajectory
    from kinematica.motion.workspace import Workspace, WorkspaceSlice, workspace
    from kinematica.robot.differential import exp_jacobian, hessian, jacobian_dot
    from kinematica.robot.ellipsoid import Ellipsoid, ellipsoid
    from kinematica.robot.sampling import random_q
    from kinematica.robot.self_motion import MAX_JUMP, Family, SelfMotion, self_motion
    from kinematica.robot.singularities import (
        ELBOW_TOL,
        RANK_TOL,
        SHOULDER_TOL,
        WRIST_TOL,
        Singularity,
        jacobian_rank,
        singularities,
    )
    from kinematica.robot.velocity import (
        analytic_jacobian,
        condition_number,
        manipulability,
        manipulability_gradient,
    )


class _Motion(types.ModuleType):
    """This package, whose function ``workspace`` has its module's name.

    The import system binds a submodule to its package's attribute of that name once
    it has loaded it; here the attribute stays the function (as when the package
    imported it eagerly): ``from kinematica.motion import workspace`` is the function,
    whoever imported :mod:`kinematica.motion.workspace` first.
    """

    def __setattr__(self, name: str, value: Any) -> None:
        if name == "workspace" and isinstance(value, types.ModuleType):
            value = value.workspace
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Motion

__getattr__, __dir__ = exports(
    __name__,
    {
        "MAX_JOINT_STEP": "kinematica.motion.cartesian",
        "CartesianPath": "kinematica.motion.cartesian",
        "PathEvent": "kinematica.motion.cartesian",
        "cartesian_path": "kinematica.motion.cartesian",
        "ROTATION_LENGTH": "kinematica.motion.cartesian_via",
        "cartesian_via_path": "kinematica.motion.cartesian_via",
        "RateControl": "kinematica.motion.control",
        "resolved_rate": "kinematica.motion.control",
        "read_csv": "kinematica.motion.export",
        "write_csv": "kinematica.motion.export",
        "write_json": "kinematica.motion.export",
        "Slowdown": "kinematica.motion.optimal",
        "TimeOptimal": "kinematica.motion.optimal",
        "time_optimal": "kinematica.motion.optimal",
        "PiecewisePolynomial": "kinematica.motion.piecewise",
        "JerkTrajectory": "kinematica.motion.scurve",
        "JointTrajectory": "kinematica.motion.trajectory",
        "joint_trajectory": "kinematica.motion.trajectory",
        "minimum_time": "kinematica.motion.trajectory",
        "time_scaling": "kinematica.motion.trajectory",
        "via_polynomials": "kinematica.motion.via",
        "via_trajectory": "kinematica.motion.via",
        "Workspace": "kinematica.motion.workspace",
        "WorkspaceSlice": "kinematica.motion.workspace",
        "workspace": "kinematica.motion.workspace",
        "exp_jacobian": "kinematica.robot.differential",
        "hessian": "kinematica.robot.differential",
        "jacobian_dot": "kinematica.robot.differential",
        "Ellipsoid": "kinematica.robot.ellipsoid",
        "ellipsoid": "kinematica.robot.ellipsoid",
        "random_q": "kinematica.robot.sampling",
        "MAX_JUMP": "kinematica.robot.self_motion",
        "Family": "kinematica.robot.self_motion",
        "SelfMotion": "kinematica.robot.self_motion",
        "self_motion": "kinematica.robot.self_motion",
        "ELBOW_TOL": "kinematica.robot.singularities",
        "RANK_TOL": "kinematica.robot.singularities",
        "SHOULDER_TOL": "kinematica.robot.singularities",
        "WRIST_TOL": "kinematica.robot.singularities",
        "Singularity": "kinematica.robot.singularities",
        "jacobian_rank": "kinematica.robot.singularities",
        "singularities": "kinematica.robot.singularities",
        "analytic_jacobian": "kinematica.robot.velocity",
        "condition_number": "kinematica.robot.velocity",
        "manipulability": "kinematica.robot.velocity",
        "manipulability_gradient": "kinematica.robot.velocity",
    },
)

__all__ = [
    "ELBOW_TOL",
    "MAX_JOINT_STEP",
    "MAX_JUMP",
    "RANK_TOL",
    "ROTATION_LENGTH",
    "SHOULDER_TOL",
    "WRIST_TOL",
    "CartesianPath",
    "Ellipsoid",
    "Family",
    "JerkTrajectory",
    "JointTrajectory",
    "PathEvent",
    "PiecewisePolynomial",
    "RateControl",
    "SelfMotion",
    "Singularity",
    "Slowdown",
    "TimeOptimal",
    "Workspace",
    "WorkspaceSlice",
    "analytic_jacobian",
    "cartesian_path",
    "cartesian_via_path",
    "condition_number",
    "ellipsoid",
    "exp_jacobian",
    "hessian",
    "jacobian_dot",
    "jacobian_rank",
    "joint_trajectory",
    "manipulability",
    "manipulability_gradient",
    "minimum_time",
    "random_q",
    "read_csv",
    "resolved_rate",
    "self_motion",
    "singularities",
    "time_optimal",
    "time_scaling",
    "via_polynomials",
    "via_trajectory",
    "workspace",
    "write_csv",
    "write_json",
]
