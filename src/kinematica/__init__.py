"""kinematica: kinematics of serial robot manipulators.

Describe an arm by its Denavit-Hartenberg table (standard or modified), compute
every frame of its forward kinematics, and every inverse-kinematics solution
with an honest status::

    import kinematica as km

    robot = km.load("puma560")
    T = robot.fk([0, 0.5, -0.3, 0, 0.4, 0])
    pose = km.to_pose(T, euler="ZYZ")
    res = robot.ik(T)

The public names are the ones imported below, each written once
(:mod:`kinematica._lazy` makes ``__all__`` from them). ``import kinematica``
imports what ``load`` and ``fk`` need; the names of the layers above (IK, URDF and
DH rules, motion, reachability, calibration) are imported under ``TYPE_CHECKING``,
and load on first use, as the subpackages (``km.ik``, ``km.viz``...) do. No
optional extra (scipy, matplotlib, sympy, Dask, ruckig) is imported before a
function that needs it runs.
"""

# ruff: noqa: F401 (the imports are the public names; kinematica._lazy makes __all__)

from typing import TYPE_CHECKING

from kinematica._lazy import exports
from kinematica.dh import Prismatic, Revolute, link_matrix
from kinematica.errors import (
    ArgumentError,
    ConventionWarning,
    DimensionError,
    KinematicaError,
    KinematicaWarning,
    LimitWarning,
    RobotFileError,
    UnitWarning,
    UnknownRobotError,
    UnreachableError,
)
from kinematica.io import ExpressionError, builtin_names, read_robot_file
from kinematica.robot import (
    Robot,
    load,
    robot_from_spec,
    spec_from_robot,
    write_robot_file,
)
from kinematica.spatial import (
    EulerSequenceError,
    axis_angle_from_matrix,
    check_rotation,
    check_transform,
    compose,
    euler_from_matrix,
    from_pose,
    gimbal_locked,
    inv_transform,
    make_transform,
    matrix_from_axis_angle,
    matrix_from_euler,
    matrix_from_quat,
    matrix_from_rotvec,
    quat_conjugate,
    quat_from_matrix,
    quat_multiply,
    quat_slerp,
    rotation_angle,
    rotvec_from_matrix,
    rotx,
    roty,
    rotz,
    se3_error,
    to_pose,
    transl,
    wrap_angle,
)

if TYPE_CHECKING:  # the names below load on first use
    from kinematica.calibration import calibrate
    from kinematica.motion import (
        analytic_jacobian,
        cartesian_path,
        cartesian_via_path,
        condition_number,
        ellipsoid,
        hessian,
        jacobian_dot,
        joint_trajectory,
        manipulability,
        resolved_rate,
        time_optimal,
        via_trajectory,
    )
    from kinematica.motion.workspace import workspace
    from kinematica.reach import base_placement, reachability
    from kinematica.robot import DHExtraction, Structure, classify, urdf_to_dh

__version__ = "0.1.0"

__getattr__, __dir__, _public = exports(__name__)
__all__ = ["__version__", *_public]
