"""Motion: velocity kinematics, named singularities, workspace, trajectories.

Layer 6: built on the robot and ik layers (public API only); numpy only.
"""

from kinematica.motion.cartesian import (
    MAX_JOINT_STEP,
    CartesianPath,
    PathEvent,
    cartesian_path,
)
from kinematica.motion.export import read_csv, write_csv, write_json
from kinematica.motion.sampling import random_q
from kinematica.motion.singularities import (
    ELBOW_TOL,
    RANK_TOL,
    SHOULDER_TOL,
    WRIST_TOL,
    Singularity,
    jacobian_rank,
    singularities,
)
from kinematica.motion.trajectory import JointTrajectory, joint_trajectory, time_scaling
from kinematica.motion.velocity import analytic_jacobian, condition_number, manipulability
from kinematica.motion.workspace import Workspace, WorkspaceSlice, workspace

__all__ = [
    "ELBOW_TOL",
    "MAX_JOINT_STEP",
    "RANK_TOL",
    "SHOULDER_TOL",
    "WRIST_TOL",
    "CartesianPath",
    "JointTrajectory",
    "PathEvent",
    "Singularity",
    "Workspace",
    "WorkspaceSlice",
    "analytic_jacobian",
    "cartesian_path",
    "condition_number",
    "jacobian_rank",
    "joint_trajectory",
    "manipulability",
    "random_q",
    "read_csv",
    "singularities",
    "time_scaling",
    "workspace",
    "write_csv",
    "write_json",
]
