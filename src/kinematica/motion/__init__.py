"""Motion: velocity kinematics, named singularities, workspace, trajectories."""

from kinematica.motion.sampling import random_q
from kinematica.motion.singularities import (
    ELBOW_TOL,
    RANK_TOL,
    SHOULDER_TOL,
    WRIST_TOL,
    Singularity,
    singularities,
)
from kinematica.motion.velocity import analytic_jacobian, condition_number, manipulability

__all__ = [
    "ELBOW_TOL",
    "RANK_TOL",
    "SHOULDER_TOL",
    "WRIST_TOL",
    "Singularity",
    "analytic_jacobian",
    "condition_number",
    "manipulability",
    "random_q",
    "singularities",
]
