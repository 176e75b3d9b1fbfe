"""Poses as 6-vectors, and the pose error used by numeric inverse kinematics.

A pose vector is ``(x, y, z, a, b, c)``: the position of the frame's origin in
metres, then three Euler angles of its orientation in a named sequence (see
:mod:`kinematica.spatial.euler`; default ``"ZYZ"``), in radians unless
``degrees=True``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

import kinematica._core as _core
from kinematica.spatial.checks import as_batch_array, check_transform
from kinematica.spatial.euler import euler_from_matrix, matrix_from_euler
from kinematica.spatial.transform import make_transform

__all__ = ["from_pose", "se3_error", "to_pose"]

FloatArray = NDArray[np.float64]


def to_pose(T: ArrayLike, euler: str = "ZYZ", degrees: bool = False) -> FloatArray:
    """Pose vector of homogeneous transforms.

    Args:
        T: Transforms ``T_a_b`` (frame b in frame a), shape ``(..., 4, 4)``,
            translations in metres; validated by :func:`check_transform`.
        euler: Euler sequence of the three angles, e.g. ``"ZYZ"`` or ``"xyz"``.
        degrees: Return the angles in degrees.

    Returns:
        ``(..., 6)``: the origin of b in a (x, y, z, metres), then the Euler
        angles of b's orientation in a (see :func:`euler_from_matrix` for their
        ranges and the gimbal-lock convention).

    Raises:
        DimensionError: ``T`` is not a valid rigid transform (shape, NaN/inf,
            last row, orthonormality).
        EulerSequenceError: ``euler`` is not a valid sequence name.
    """
    Ta = check_transform(T, "T")
    angles = euler_from_matrix(Ta[..., :3, :3], euler, degrees=degrees)
    return np.concatenate([Ta[..., :3, 3], angles], axis=-1)


def from_pose(p: ArrayLike, euler: str = "ZYZ", degrees: bool = False) -> FloatArray:
    """Homogeneous transforms of pose vectors; the inverse of :func:`to_pose`.

    Args:
        p: Pose vectors ``(x, y, z, a, b, c)``, shape ``(..., 6)``: metres,
            then Euler angles in the sequence ``euler``.
        euler: Euler sequence of the three angles, e.g. ``"ZYZ"`` or ``"xyz"``.
        degrees: The angles are in degrees.

    Returns:
        Transforms, shape ``(..., 4, 4)``.

    Raises:
        DimensionError: ``p`` is not ``(..., 6)`` or holds NaN/inf.
        EulerSequenceError: ``euler`` is not a valid sequence name.
    """
    pa = as_batch_array(p, "p", (6,))
    return make_transform(matrix_from_euler(pa[..., 3:], euler, degrees=degrees), pa[..., :3])


def se3_error(T_current: ArrayLike, T_target: ArrayLike) -> FloatArray:
    """Pose error from ``T_current`` to ``T_target``, both in the base frame.

    The error is ``(Δp, Δω)``:

    - ``Δp = p_target − p_current`` (metres, base frame);
    - ``Δω`` = rotation vector of ``R_target · R_currentᵀ`` (radians, base
      frame): the rotation that, applied in the base frame, carries the
      current orientation onto the target, ``R_target = exp([Δω]×) R_current``.

    Both parts are expressed in the base frame, as the geometric (base-frame)
    Jacobian ``J`` is, so a Newton/Levenberg-Marquardt step solves
    ``J Δq ≈ (Δp, Δω)``. For small errors ``Δω`` is the angular velocity that
    closes the gap in unit time. It is exactly zero when the poses agree and
    stays accurate to round-off for tiny errors and for errors near π. (The
    core's pose error: the one the IK check and the numeric search use.)

    Args:
        T_current: Current transforms, shape ``(..., 4, 4)``.
        T_target: Target transforms, shape ``(..., 4, 4)``; batch shapes broadcast.

    Returns:
        Errors of shape ``(..., 6)``: position then orientation.

    Raises:
        DimensionError: An input is not ``(..., 4, 4)`` or holds NaN/inf.
    """
    Tc = as_batch_array(T_current, "T_current", (4, 4))
    Tt = as_batch_array(T_target, "T_target", (4, 4))
    Tc, Tt = np.broadcast_arrays(Tc, Tt)
    shape = Tc.shape[:-2]
    e = _core.pose_errors(
        np.ascontiguousarray(Tc.reshape(-1, 4, 4)), np.ascontiguousarray(Tt.reshape(-1, 4, 4))
    )
    return e.reshape(*shape, 6)
