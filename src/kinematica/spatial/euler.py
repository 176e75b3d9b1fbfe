"""Euler angles in all 12 sequences, intrinsic and extrinsic, batched.

Sequence names follow ``scipy.spatial.transform.Rotation``: three axes from
``x, y, z`` with no axis repeated twice in a row; UPPER case (``"ZYZ"``) is
intrinsic, about the axes of the rotating frame, so ``R = R1(a) R2(b) R3(c)``;
lower case (``"zyz"``) is extrinsic, about the fixed axes, so
``R = R3(c) R2(b) R1(a)``. Mixed case is rejected. There are 6 proper Euler
sequences (first axis = third axis: XYX XZX YXY YZY ZXZ ZYZ) and 6 Tait-Bryan
sequences (three different axes: XYZ XZY YXZ YZX ZXY ZYX).

Angle ranges, as scipy's: the first and third angle lie in (−π, π]; the second
in [0, π] for proper Euler and [−π/2, π/2] for Tait-Bryan sequences. (Scipy
returns [−π, π); the two agree except that an angle of exactly ±π comes out
here as +π, the project's convention.)

Gimbal lock. When the second angle is within :data:`GIMBAL_LOCK_TOL` of its
singular value (0 or π for proper Euler, ±π/2 for Tait-Bryan) the first and
third axes line up and only their sum (or difference) is defined. Like scipy,
the THIRD angle of the returned triple is then set to 0 (for extrinsic
sequences too: it is the last-applied rotation about a fixed axis there, the
innermost about a moving axis for intrinsic ones) and the first angle carries
the whole rotation about the aligned axes. Exactly at the lock the angles
reproduce ``R`` to round-off; at a distance ``δ <= GIMBAL_LOCK_TOL`` from it
they reproduce ``R`` to about ``δ`` (the price of fixing the third angle).

Method: the direct general method of Bernardes & Viollet (2022), "Quaternion
to Euler angles conversion: A direct, general and computationally efficient
method", PLoS ONE 17(11): e0276302, applied to :func:`quat_from_matrix`; it is
the method scipy uses. It needs no ``arcsin``/``arccos``, hence no clipping of
round-off outside [−1, 1], and is accurate everywhere, near the lock included.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import KinematicaError
from kinematica.spatial.angles import wrap_angle
from kinematica.spatial.checks import as_batch_array
from kinematica.spatial.quaternion import quat_from_matrix
from kinematica.spatial.transform import rotx, roty, rotz

__all__ = [
    "GIMBAL_LOCK_TOL",
    "EulerSequenceError",
    "euler_from_matrix",
    "gimbal_locked",
    "matrix_from_euler",
]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

# Half-width (radians) of the band around the singular value of the second
# angle inside which a rotation is treated as gimbal locked. Equal to scipy's
# threshold, so this module locks exactly where scipy warns "Gimbal lock
# detected". The second angle itself is accurate to ~1e-16 near the lock (it is
# computed with atan2); the band only decides when the third angle is fixed to 0.
GIMBAL_LOCK_TOL = 1e-7

_AXIS_INDEX = {"x": 0, "y": 1, "z": 2}
_ELEMENTARY: tuple[Callable[[ArrayLike], FloatArray], ...] = (rotx, roty, rotz)


class EulerSequenceError(KinematicaError, ValueError):
    """An Euler sequence name is not one of the 24 accepted forms."""


def _parse(seq: str) -> tuple[tuple[int, int, int], bool]:
    """Axis indices (0=x, 1=y, 2=z) of ``seq`` and whether it is extrinsic."""
    valid = (
        isinstance(seq, str)
        and len(seq) == 3
        and (seq.isupper() or seq.islower())
        and all(c in "xyz" for c in seq.lower())
        and seq[0].lower() != seq[1].lower()
        and seq[1].lower() != seq[2].lower()
    )
    if not valid:
        raise EulerSequenceError(
            f"Euler sequence must be three axes from x, y, z with no axis twice in a "
            f"row, all upper case (intrinsic, e.g. 'ZYZ', 'XYZ') or all lower case "
            f"(extrinsic, e.g. 'zyz', 'xyz'); got {seq!r}"
        )
    i, j, k = (_AXIS_INDEX[c] for c in seq.lower())
    return (i, j, k), seq.islower()


def matrix_from_euler(angles: ArrayLike, seq: str = "ZYZ", degrees: bool = False) -> FloatArray:
    """Rotation matrix from three Euler angles.

    Args:
        angles: Angles ``(a, b, c)`` about the first, second and third axis of
            ``seq``, shape ``(..., 3)``; radians unless ``degrees``.
        seq: Sequence name, e.g. ``"ZYZ"`` (intrinsic: ``Rz(a) Ry(b) Rz(c)``)
            or ``"xyz"`` (extrinsic: ``Rz(c) Ry(b) Rx(a)``).
        degrees: ``angles`` are in degrees.

    Returns:
        Rotation matrices, shape ``(..., 3, 3)``.

    Raises:
        EulerSequenceError: ``seq`` is not a valid sequence name.
        DimensionError: ``angles`` is not ``(..., 3)`` or holds NaN/inf.
    """
    axes, extrinsic = _parse(seq)
    a = as_batch_array(angles, "angles", (3,))
    if degrees:
        a = np.deg2rad(a)
    R1, R2, R3 = (_ELEMENTARY[axis](a[..., n]) for n, axis in enumerate(axes))
    return R3 @ R2 @ R1 if extrinsic else R1 @ R2 @ R3


def _half_angles(
    R: ArrayLike, axes: tuple[int, int, int], extrinsic: bool
) -> tuple[FloatArray, FloatArray, FloatArray, bool, int]:
    """Steps 1-2 of Bernardes & Viollet: the raw second angle and half-angles.

    Works on the extrinsic form; an intrinsic sequence is the extrinsic one of
    its reversed axes with the first and third angle swapped.

    Returns:
        ``(middle, half_sum, half_diff, symmetric, sign)``: ``middle`` in
        [0, π] (before the −π/2 shift of Tait-Bryan sequences), the half sum
        and half difference of the first and third angle, whether the
        sequence is proper Euler, and the sign of the permutation of axes.
    """
    i, j, k = axes if extrinsic else axes[::-1]
    symmetric = i == k
    if symmetric:
        k = 3 - i - j  # the axis not in the sequence
    sign = (i - j) * (j - k) * (k - i) // 2  # Levi-Civita symbol ε_ijk = ±1
    q = quat_from_matrix(R)
    w, qi, qj, qk = q[..., 3], q[..., i], q[..., j], sign * q[..., k]
    if symmetric:
        a, b, c, d = w, qi, qj, qk
    else:  # rotate the quaternion so that the Tait-Bryan case becomes symmetric
        a, b, c, d = w - qj, qi + qk, qj + w, qk - qi
    middle = 2.0 * np.arctan2(np.hypot(c, d), np.hypot(a, b))
    return middle, np.arctan2(b, a), np.arctan2(d, c), symmetric, sign


def _locked(middle: FloatArray) -> tuple[BoolArray, BoolArray]:
    """Where the raw second angle is at its singular value 0, or π."""
    return middle <= GIMBAL_LOCK_TOL, middle >= np.pi - GIMBAL_LOCK_TOL


def euler_from_matrix(R: ArrayLike, seq: str = "ZYZ", degrees: bool = False) -> FloatArray:
    """Euler angles of a rotation matrix, the same as scipy's ``as_euler``.

    Args:
        R: Rotation matrices, shape ``(..., 3, 3)``; assumed orthonormal.
        seq: Sequence name (see the module docstring), default ``"ZYZ"``.
        degrees: Return degrees instead of radians.

    Returns:
        Angles of shape ``(..., 3)`` with ``matrix_from_euler(angles, seq) ≈ R``:
        first and third in (−π, π], second in [0, π] (proper Euler) or
        [−π/2, π/2] (Tait-Bryan). In gimbal lock (see :func:`gimbal_locked`) the
        third angle is 0, as in scipy; no NaN is ever produced.

    Raises:
        EulerSequenceError: ``seq`` is not a valid sequence name.
        DimensionError: ``R`` is not ``(..., 3, 3)`` or holds NaN/inf.
    """
    axes, extrinsic = _parse(seq)
    middle, half_sum, half_diff, symmetric, sign = _half_angles(R, axes, extrinsic)
    # Tait-Bryan sequences were made symmetric by a rotation that flips the
    # sign of their third (extrinsic-form) angle when ε_ijk = −1.
    third_sign = 1 if symmetric else sign
    near_zero, near_pi = _locked(middle)

    # Regular case: the first and third angle of the extrinsic form; they land
    # in the reversed places for an intrinsic sequence.
    ext_first = half_sum - half_diff
    ext_third = third_sign * (half_sum + half_diff)
    first, third = (ext_first, ext_third) if extrinsic else (ext_third, ext_first)

    # Gimbal lock: the third returned angle is 0 and the first carries the
    # whole rotation about the aligned axes, which is the sum of the two when
    # the middle angle is 0 and their difference when it is π.
    locked_first = np.where(near_zero, 2.0 * half_sum, (-2.0 if extrinsic else 2.0) * half_diff)
    if not extrinsic:
        locked_first = third_sign * locked_first
    locked = near_zero | near_pi
    first = np.where(locked, locked_first, first)
    third = np.where(locked, 0.0, third)

    second = middle if symmetric else middle - np.pi / 2.0
    angles = np.stack([wrap_angle(first), second, wrap_angle(third)], axis=-1)
    return np.rad2deg(angles) if degrees else angles


def gimbal_locked(R: ArrayLike, seq: str = "ZYZ") -> BoolArray:
    """Where the second Euler angle of ``R`` is at its singular value.

    Args:
        R: Rotation matrices, shape ``(..., 3, 3)``.
        seq: Sequence name, default ``"ZYZ"``.

    Returns:
        Booleans, shape ``(...)``: True where the second angle is within
        :data:`GIMBAL_LOCK_TOL` (radians) of 0 or π (proper Euler) or of ±π/2
        (Tait-Bryan), i.e. exactly where scipy warns about gimbal lock.

    Raises:
        EulerSequenceError: ``seq`` is not a valid sequence name.
        DimensionError: ``R`` is not ``(..., 3, 3)`` or holds NaN/inf.
    """
    axes, extrinsic = _parse(seq)
    near_zero, near_pi = _locked(_half_angles(R, axes, extrinsic)[0])
    return near_zero | near_pi
