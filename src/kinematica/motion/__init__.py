"""Motion: velocity kinematics, named singularities, workspace, trajectories, control.

Layer 6: built on the robot and ik layers (public API only); numpy only. The
velocity kinematics (measures, ellipsoids, Hessian and J̇), the named
singularities and the sampling of joint space live in the robot layer
(``Robot.jacobian(euler=)``, ``Robot.singularities``, ``Robot.random_q``, ``Robot.self_motion`` are
thin methods over them) and are re-exported here.
"""

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
