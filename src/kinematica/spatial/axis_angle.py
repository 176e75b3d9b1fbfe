"""Axis-angle and rotation vectors (exponential coordinates of SO(3)), batched.

A rotation by ``angle`` about the unit ``axis`` is
``R = cos θ I + sin θ [n]× + (1 − cos θ) n nᵀ`` (Rodrigues); its rotation
vector is ``θ n``. Going back, ``θ = atan2(|v|, (tr R − 1)/2)`` with ``v`` the
vector of the skew part of ``R`` (``v = sin θ · n``): unlike ``arccos`` alone
this is accurate to round-off for every angle, from 1e-12 rad to π.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

import kinematica._core as _core
from kinematica.errors import DimensionError
from kinematica.spatial.checks import as_batch_array, first_bad

__all__ = [
    "axis_angle_from_matrix",
    "matrix_from_axis_angle",
    "matrix_from_rotvec",
    "rotation_angle",
    "rotvec_from_matrix",
]

FloatArray = NDArray[np.float64]

# Below this angle (radians) the skew part of R, hence the rotation axis, is at
# the round-off level of R's entries (~2.2e-16 each), so the axis direction is
# noise; axis_angle_from_matrix then returns the z axis by convention.
IDENTITY_ANGLE_TOL = 10.0 * np.finfo(np.float64).eps


def _skew(v: FloatArray) -> FloatArray:
    """Cross-product matrix ``[v]×`` of ``(..., 3)`` vectors: ``(..., 3, 3)``."""
    x, y, z = v[..., 0], v[..., 1], v[..., 2]
    zero = np.zeros_like(x)
    return np.stack(
        [
            np.stack([zero, -z, y], axis=-1),
            np.stack([z, zero, -x], axis=-1),
            np.stack([-y, x, zero], axis=-1),
        ],
        axis=-2,
    )


def _log(R: ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
    """``(axis, angle, rotvec)`` of rotations ``R`` (the core's SO(3) log).

    ``θ = atan2(|v|, (tr R − 1)/2)`` with ``v`` the vector of the skew part: exact
    near 0; above π/2 the axis comes from the symmetric part,
    ``(R + Rᵀ)/2 − cos θ I = (1 − cos θ) n nᵀ``, whose error stays below eps up to and
    at π (the skew part's ~eps/sin θ grows without bound toward π). Below
    :data:`IDENTITY_ANGLE_TOL` the axis is the z axis by convention.
    """
    Ra = as_batch_array(R, "R", (3, 3))
    flat = np.ascontiguousarray(Ra.reshape(-1, 3, 3))
    rv, angle = _core.so3_log(flat)
    rotvec = rv.reshape(*Ra.shape[:-2], 3)
    angle = angle.reshape(Ra.shape[:-2])
    norm = np.linalg.norm(rotvec, axis=-1, keepdims=True)
    axis = np.divide(rotvec, norm, out=np.zeros_like(rotvec), where=norm > 0.0)
    tiny = angle < IDENTITY_ANGLE_TOL
    axis = np.where(tiny[..., None], np.array([0.0, 0.0, 1.0]), axis)
    return axis, angle, rotvec


def matrix_from_axis_angle(axis: ArrayLike, angle: ArrayLike, degrees: bool = False) -> FloatArray:
    """Rotation by ``angle`` about ``axis`` (Rodrigues' formula).

    Args:
        axis: Rotation axes, shape ``(..., 3)``, any nonzero length (normalised here).
        angle: Angles, shape ``(...)``; radians unless ``degrees``. Batch shapes
            of ``axis`` and ``angle`` broadcast.
        degrees: ``angle`` is in degrees.

    Returns:
        Rotation matrices, shape ``(..., 3, 3)``.

    Raises:
        DimensionError: Wrong shapes, NaN/inf, or a zero axis.
    """
    n = as_batch_array(axis, "axis", (3,))
    theta = as_batch_array(angle, "angle", ())
    if degrees:
        theta = np.deg2rad(theta)
    norm = np.linalg.norm(n, axis=-1)
    zero = norm == 0.0
    if zero.any():
        raise DimensionError(f"{first_bad('axis', zero)} is the zero vector; it has no direction")
    n = n / norm[..., None]
    c, s = np.cos(theta)[..., None, None], np.sin(theta)[..., None, None]
    return c * np.eye(3) + s * _skew(n) + (1.0 - c) * (n[..., :, None] * n[..., None, :])


def axis_angle_from_matrix(R: ArrayLike, degrees: bool = False) -> tuple[FloatArray, FloatArray]:
    """Axis and angle of rotation matrices.

    Args:
        R: Rotation matrices, shape ``(..., 3, 3)``; assumed orthonormal.
        degrees: Return the angle in degrees.

    Returns:
        ``(axis, angle)``: unit axes of shape ``(..., 3)`` and angles of shape
        ``(...)`` in [0, π]. Below :data:`IDENTITY_ANGLE_TOL` (R is the identity
        up to round-off) the axis is ``(0, 0, 1)`` by convention. At exactly π,
        ``n`` and ``−n`` are the same rotation; either may be returned.

    Raises:
        DimensionError: ``R`` is not ``(..., 3, 3)`` or holds NaN/inf.
    """
    axis, angle, _ = _log(R)
    return axis, np.rad2deg(angle) if degrees else angle


def matrix_from_rotvec(rotvec: ArrayLike, degrees: bool = False) -> FloatArray:
    """Rotation matrix of rotation vectors ``θ n`` (the SO(3) exponential).

    Uses ``R = I + (sin θ/θ) [v]× + ((1 − cos θ)/θ²) [v]×²`` with both
    coefficients written as sincs, which are exact for every θ including 0, so
    no small-angle branch is needed.

    Args:
        rotvec: Rotation vectors, shape ``(..., 3)``; their norm is the angle,
            in radians unless ``degrees``.
        degrees: The norm of ``rotvec`` is in degrees.

    Returns:
        Rotation matrices, shape ``(..., 3, 3)``.

    Raises:
        DimensionError: ``rotvec`` is not ``(..., 3)`` or holds NaN/inf.
    """
    v = as_batch_array(rotvec, "rotvec", (3,))
    if degrees:
        v = np.deg2rad(v)
    theta = np.linalg.norm(v, axis=-1)[..., None, None]
    K = _skew(v)
    # np.sinc(x) = sin(πx)/(πx): sin θ/θ = sinc(θ/π), (1 − cos θ)/θ² = sinc(θ/2π)²/2.
    return (
        np.eye(3) + np.sinc(theta / np.pi) * K + 0.5 * np.sinc(theta / (2 * np.pi)) ** 2 * (K @ K)
    )


def rotvec_from_matrix(R: ArrayLike, degrees: bool = False) -> FloatArray:
    """Rotation vectors ``θ n`` of rotation matrices (the SO(3) logarithm).

    Args:
        R: Rotation matrices, shape ``(..., 3, 3)``; assumed orthonormal.
        degrees: Return the vectors with their norm in degrees.

    Returns:
        Rotation vectors, shape ``(..., 3)``, norm in [0, π]; exact to round-off
        near 0 (no cut-off) and, via the symmetric part of ``R``, near π.

    Raises:
        DimensionError: ``R`` is not ``(..., 3, 3)`` or holds NaN/inf.
    """
    rotvec = _log(R)[2]
    return np.rad2deg(rotvec) if degrees else rotvec


def rotation_angle(R_a: ArrayLike, R_b: ArrayLike, degrees: bool = False) -> FloatArray:
    """Geodesic distance between rotations: the angle of ``R_aᵀ R_b``.

    Computed as ``atan2(|v|, (tr M − 1)/2)`` with ``M = R_aᵀ R_b`` and ``v``
    the vector of its skew part (by the core, as the IK check does), so it
    resolves angles down to round-off (~1e-16 rad), where
    ``arccos((tr M − 1)/2)`` alone bottoms out near 1e-8.

    Args:
        R_a: Rotation matrices, shape ``(..., 3, 3)``.
        R_b: Rotation matrices, shape ``(..., 3, 3)``; batch shapes broadcast.
        degrees: Return degrees instead of radians.

    Returns:
        Angles in [0, π], shape ``(...)``.

    Raises:
        DimensionError: An input is not ``(..., 3, 3)`` or holds NaN/inf.
    """
    A = as_batch_array(R_a, "R_a", (3, 3))
    B = as_batch_array(R_b, "R_b", (3, 3))
    A, B = np.broadcast_arrays(A, B)
    shape = A.shape[:-2]
    angle = _core.rotation_angles(
        np.ascontiguousarray(A.reshape(-1, 3, 3)), np.ascontiguousarray(B.reshape(-1, 3, 3))
    ).reshape(shape)
    return np.rad2deg(angle) if degrees else angle
