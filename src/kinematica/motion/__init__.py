"""Motion: velocity kinematics, named singularities, workspace, trajectories, control.

Layer 6: built on the robot and ik layers (public API only); numpy only. The
velocity kinematics (measures, ellipsoids, Hessian and J̇), the named
singularities and the sampling of joint space live in the robot layer
(``Robot.jacobian(euler=)``, ``Robot.singularities``, ``Robot.random_q``, ``Robot.self_motion`` are
thin methods over them) and are re-exported here. The names load on first use
(:mod:`kinematica._lazy`): timing a path does not import the Cartesian paths, the
singularities or the IK layer.
"""

# ruff: noqa: F401 (the imports are the public names; kinematica._lazy makes __all__)

import sys
import types
from typing import TYPE_CHECKING

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

    def __setattr__(self, name: str, value: object) -> None:
        if name == "workspace" and isinstance(value, types.ModuleType):
            value = value.workspace
        super().__setattr__(name, value)


sys.modules[__name__].__class__ = _Motion

__getattr__, __dir__, __all__ = exports(__name__)
