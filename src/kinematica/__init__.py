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

from typing import TYPE_CHECKING

from kinematica._lazy import exports
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

if TYPE_CHECKING:  # the names below load on first use: `import kinematica` stays light
    from kinematica.calibration import calibrate
    from kinematica.dh import (
        Prismatic,
        Revolute,
        link_matrix,
    )
    from kinematica.io import (
        ExpressionError,
        builtin_names,
        read_robot_file,
    )
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
    from kinematica.motion.workspace import (
        workspace,
    )
    from kinematica.reach import base_placement, reachability
    from kinematica.robot import (
        DHExtraction,
        Robot,
        Structure,
        classify,
        robot_from_spec,
        spec_from_robot,
        urdf_to_dh,
        write_robot_file,
    )
    from kinematica.robot.load import load
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

__version__ = "0.1.0"

#: Public names imported on first use, and the module each comes from.
_LAZY = {
    "Prismatic": "kinematica.dh",
    "calibrate": "kinematica.calibration",
    "Revolute": "kinematica.dh",
    "link_matrix": "kinematica.dh",
    "ExpressionError": "kinematica.io",
    "builtin_names": "kinematica.io",
    "read_robot_file": "kinematica.io",
    "DHExtraction": "kinematica.robot",
    "Robot": "kinematica.robot",
    "Structure": "kinematica.robot",
    "classify": "kinematica.robot",
    "load": "kinematica.robot.load",
    "robot_from_spec": "kinematica.robot",
    "spec_from_robot": "kinematica.robot",
    "urdf_to_dh": "kinematica.robot",
    "write_robot_file": "kinematica.robot",
    "EulerSequenceError": "kinematica.spatial",
    "axis_angle_from_matrix": "kinematica.spatial",
    "check_rotation": "kinematica.spatial",
    "check_transform": "kinematica.spatial",
    "compose": "kinematica.spatial",
    "euler_from_matrix": "kinematica.spatial",
    "from_pose": "kinematica.spatial",
    "gimbal_locked": "kinematica.spatial",
    "inv_transform": "kinematica.spatial",
    "make_transform": "kinematica.spatial",
    "matrix_from_axis_angle": "kinematica.spatial",
    "matrix_from_euler": "kinematica.spatial",
    "matrix_from_quat": "kinematica.spatial",
    "matrix_from_rotvec": "kinematica.spatial",
    "quat_conjugate": "kinematica.spatial",
    "quat_from_matrix": "kinematica.spatial",
    "quat_multiply": "kinematica.spatial",
    "quat_slerp": "kinematica.spatial",
    "rotation_angle": "kinematica.spatial",
    "rotvec_from_matrix": "kinematica.spatial",
    "rotx": "kinematica.spatial",
    "roty": "kinematica.spatial",
    "rotz": "kinematica.spatial",
    "se3_error": "kinematica.spatial",
    "to_pose": "kinematica.spatial",
    "transl": "kinematica.spatial",
    "wrap_angle": "kinematica.spatial",
    "workspace": "kinematica.motion.workspace",
    "reachability": "kinematica.reach",
    "base_placement": "kinematica.reach",
    "analytic_jacobian": "kinematica.motion",
    "cartesian_path": "kinematica.motion",
    "cartesian_via_path": "kinematica.motion",
    "condition_number": "kinematica.motion",
    "joint_trajectory": "kinematica.motion",
    "manipulability": "kinematica.motion",
    "via_trajectory": "kinematica.motion",
    "ellipsoid": "kinematica.motion",
    "hessian": "kinematica.motion",
    "jacobian_dot": "kinematica.motion",
    "resolved_rate": "kinematica.motion",
    "time_optimal": "kinematica.motion",
}
#: Subpackages reachable as attributes (``km.ik``, ``km.spatial``...) before anything imported them.
_SUBPACKAGES = frozenset(
    {
        "calibration",
        "core",
        "design",
        "dh",
        "errors",
        "ik",
        "io",
        "motion",
        "reach",
        "robot",
        "spatial",
        "symbolic",
        "viz",
        "cli",
    }
)


__getattr__, __dir__ = exports(
    __name__, {**_LAZY, **{name: f"kinematica.{name}" for name in _SUBPACKAGES}}
)

__all__ = [
    "ArgumentError",
    "ConventionWarning",
    "DHExtraction",
    "DimensionError",
    "EulerSequenceError",
    "ExpressionError",
    "KinematicaError",
    "KinematicaWarning",
    "LimitWarning",
    "Prismatic",
    "Revolute",
    "Robot",
    "RobotFileError",
    "Structure",
    "UnitWarning",
    "UnknownRobotError",
    "UnreachableError",
    "__version__",
    "analytic_jacobian",
    "axis_angle_from_matrix",
    "base_placement",
    "builtin_names",
    "calibrate",
    "cartesian_path",
    "cartesian_via_path",
    "check_rotation",
    "check_transform",
    "classify",
    "compose",
    "condition_number",
    "ellipsoid",
    "euler_from_matrix",
    "from_pose",
    "gimbal_locked",
    "hessian",
    "inv_transform",
    "jacobian_dot",
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
    "reachability",
    "read_robot_file",
    "resolved_rate",
    "robot_from_spec",
    "rotation_angle",
    "rotvec_from_matrix",
    "rotx",
    "roty",
    "rotz",
    "se3_error",
    "spec_from_robot",
    "time_optimal",
    "to_pose",
    "transl",
    "urdf_to_dh",
    "via_trajectory",
    "workspace",
    "wrap_angle",
    "write_robot_file",
]
