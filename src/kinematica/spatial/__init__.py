"""SE(3)/SO(3) maths: rotations, homogeneous transforms, Euler angles, quaternions."""

from kinematica.spatial.angles import wrap_angle
from kinematica.spatial.axis_angle import (
    axis_angle_from_matrix,
    matrix_from_axis_angle,
    matrix_from_rotvec,
    rotation_angle,
    rotvec_from_matrix,
)
from kinematica.spatial.checks import (
    ORTHONORMAL_TOL,
    ROUNDOFF_TOL,
    check_rotation,
    check_transform,
    nearest_rotation,
    orthonormality_error,
    orthonormalize,
)
from kinematica.spatial.euler import (
    GIMBAL_LOCK_TOL,
    EulerSequenceError,
    euler_from_matrix,
    gimbal_locked,
    matrix_from_euler,
)
from kinematica.spatial.euler_rates import euler_rate_matrix, euler_rate_singular
from kinematica.spatial.pose import from_pose, se3_error, to_pose
from kinematica.spatial.quaternion import (
    matrix_from_quat,
    quat_conjugate,
    quat_from_matrix,
    quat_multiply,
    quat_slerp,
)
from kinematica.spatial.transform import (
    compose,
    inv_transform,
    make_transform,
    rotx,
    roty,
    rotz,
    transl,
)

__all__ = [
    "GIMBAL_LOCK_TOL",
    "ORTHONORMAL_TOL",
    "ROUNDOFF_TOL",
    "EulerSequenceError",
    "axis_angle_from_matrix",
    "check_rotation",
    "check_transform",
    "compose",
    "euler_from_matrix",
    "euler_rate_matrix",
    "euler_rate_singular",
    "from_pose",
    "gimbal_locked",
    "inv_transform",
    "make_transform",
    "matrix_from_axis_angle",
    "matrix_from_euler",
    "matrix_from_quat",
    "matrix_from_rotvec",
    "nearest_rotation",
    "orthonormality_error",
    "orthonormalize",
    "quat_conjugate",
    "quat_from_matrix",
    "quat_multiply",
    "quat_slerp",
    "rotation_angle",
    "rotvec_from_matrix",
    "rotx",
    "roty",
    "rotz",
    "se3_error",
    "to_pose",
    "transl",
    "wrap_angle",
]
