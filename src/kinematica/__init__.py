"""kinematica: kinematics of serial robot manipulators.

Describe an arm by its Denavit-Hartenberg table (standard or modified), compute
every frame of its forward kinematics, and every inverse-kinematics solution
with an honest status::

    import kinematica as km

    robot = km.load("puma560")
    T = robot.fk([0, 0.5, -0.3, 0, 0.4, 0])
    pose = km.to_pose(T, euler="ZYZ")
    res = robot.ik(T)
"""

import importlib
from typing import TYPE_CHECKING, Any

from kinematica.dh import Prismatic, Revolute, link_matrix
from kinematica.errors import (
    ArgumentError,
    DimensionError,
    KinematicaError,
    KinematicaWarning,
    RobotFileError,
    UnknownRobotError,
    UnreachableError,
)
from kinematica.io import ExpressionError, builtin_names, read_robot_file
from kinematica.robot import (
    DHExtraction,
    Robot,
    Structure,
    classify,
    load,
    robot_from_spec,
    spec_from_robot,
    urdf_to_dh,
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

if TYPE_CHECKING:  # imported on first use (below): `import kinematica` stays light
    from kinematica.motion import (
        analytic_jacobian,
        cartesian_path,
        condition_number,
        joint_trajectory,
        manipulability,
    )
    from kinematica.motion.workspace import workspace

__version__ = "0.1.0"

#: Public names imported on first use, and the module each comes from.
_LAZY = {
    name: "kinematica.motion"
    for name in (
        "analytic_jacobian",
        "cartesian_path",
        "condition_number",
        "joint_trajectory",
        "manipulability",
        "workspace",
    )
}


def __getattr__(name: str) -> Any:
    """The motion names, imported when first asked for (PEP 562)."""
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'kinematica' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))


__all__ = [
    "ArgumentError",
    "DHExtraction",
    "DimensionError",
    "EulerSequenceError",
    "ExpressionError",
    "KinematicaError",
    "KinematicaWarning",
    "Prismatic",
    "Revolute",
    "Robot",
    "RobotFileError",
    "Structure",
    "UnknownRobotError",
    "UnreachableError",
    "__version__",
    "analytic_jacobian",
    "axis_angle_from_matrix",
    "builtin_names",
    "cartesian_path",
    "check_rotation",
    "check_transform",
    "classify",
    "compose",
    "condition_number",
    "euler_from_matrix",
    "from_pose",
    "gimbal_locked",
    "inv_transform",
    "joint_trajectory",
    "link_matrix",
    "load",
    "make_transform",
    "manipulability",
    "matrix_from_axis_angle",
    "matrix_from_euler",
    "matrix_from_quat",
    "matrix_from_rotvec",
    "quat_conjugate",
    "quat_from_matrix",
    "quat_multiply",
    "quat_slerp",
    "read_robot_file",
    "robot_from_spec",
    "rotation_angle",
    "rotvec_from_matrix",
    "rotx",
    "roty",
    "rotz",
    "se3_error",
    "spec_from_robot",
    "to_pose",
    "transl",
    "urdf_to_dh",
    "workspace",
    "wrap_angle",
    "write_robot_file",
]
