"""Unit quaternions, batched over leading axes.

Quaternions are stored scalar-LAST, ``(x, y, z, w)``, as
``scipy.spatial.transform.Rotation`` does; every function takes
``scalar_first=True`` to read and write ``(w, x, y, z)`` instead. The product
is Hamilton's, so ``matrix_from_quat(quat_multiply(q1, q2)) ==
matrix_from_quat(q1) @ matrix_from_quat(q2)``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError
from kinematica.spatial.checks import as_batch_array, first_bad

__all__ = [
    "matrix_from_quat",
    "quat_conjugate",
    "quat_from_matrix",
    "quat_multiply",
    "quat_slerp",
]

FloatArray = NDArray[np.float64]

_FIRST_TO_LAST = [1, 2, 3, 0]  # (w, x, y, z) -> (x, y, z, w)
_LAST_TO_FIRST = [3, 0, 1, 2]  # (x, y, z, w) -> (w, x, y, z)


def _read(q: ArrayLike, name: str, scalar_first: bool) -> FloatArray:
    """Validated ``(..., 4)`` float array in scalar-last order."""
    qa = as_batch_array(q, name, (4,))
    return qa[..., _FIRST_TO_LAST] if scalar_first else qa


def _write(q: FloatArray, scalar_first: bool) -> FloatArray:
    """Scalar-last ``q`` in the caller's order."""
    return q[..., _LAST_TO_FIRST] if scalar_first else q


def _normalized(q: FloatArray, name: str) -> FloatArray:
    """``q / |q|``; a zero quaternion has no rotation, so it is an error."""
    norm = np.linalg.norm(q, axis=-1, keepdims=True)
    zero = norm[..., 0] == 0.0
    if zero.any():
        raise DimensionError(
            f"{first_bad(name, zero)} has zero norm; a rotation quaternion must be nonzero"
        )
    return q / norm


def _canonical(q: FloatArray) -> FloatArray:
    """Choose the sign of each quaternion so that ``w > 0``.

    When ``w == 0`` (half turns) the first nonzero of ``x, y, z`` is made
    positive, as scipy's ``as_quat(canonical=True)`` does, so that the result
    is unique.
    """
    order = q[..., _LAST_TO_FIRST]
    first_nonzero = np.argmax(order != 0.0, axis=-1)[..., None]
    lead = np.take_along_axis(order, first_nonzero, axis=-1)
    return np.where(lead < 0.0, -q, q)


def quat_from_matrix(R: ArrayLike, scalar_first: bool = False) -> FloatArray:
    """Unit quaternion of a rotation matrix (Shepperd's method).

    Of the four algebraically equal formulas, each row uses the one built on
    the largest of ``trace R, R_xx, R_yy, R_zz``, which keeps the divisor away
    from zero and the result accurate to round-off for every rotation. The sign
    is canonical: ``w >= 0`` (see :func:`_canonical` for the tie at ``w == 0``).

    Args:
        R: Rotation matrices, shape ``(..., 3, 3)``; assumed orthonormal (use
            :func:`~kinematica.spatial.checks.check_rotation` to make sure).
        scalar_first: Return ``(w, x, y, z)`` instead of ``(x, y, z, w)``.

    Returns:
        Unit quaternions, shape ``(..., 4)``.
    """
    Ra = as_batch_array(R, "R", (3, 3))
    diag = np.diagonal(Ra, axis1=-2, axis2=-1)
    trace = diag.sum(axis=-1)
    # candidates[..., c, :] is the (unnormalised) quaternion from formula c:
    # c = 0, 1, 2 build on R_xx, R_yy, R_zz; c = 3 builds on the trace.
    candidates = np.empty((*Ra.shape[:-2], 4, 4))
    for i in range(3):
        j, k = (i + 1) % 3, (i + 2) % 3
        candidates[..., i, i] = 1.0 - trace + 2.0 * Ra[..., i, i]
        candidates[..., i, j] = Ra[..., j, i] + Ra[..., i, j]
        candidates[..., i, k] = Ra[..., k, i] + Ra[..., i, k]
        candidates[..., i, 3] = Ra[..., k, j] - Ra[..., j, k]
    candidates[..., 3, 0] = Ra[..., 2, 1] - Ra[..., 1, 2]
    candidates[..., 3, 1] = Ra[..., 0, 2] - Ra[..., 2, 0]
    candidates[..., 3, 2] = Ra[..., 1, 0] - Ra[..., 0, 1]
    candidates[..., 3, 3] = 1.0 + trace
    choice = np.argmax(np.concatenate([diag, trace[..., None]], axis=-1), axis=-1)
    q = np.take_along_axis(candidates, choice[..., None, None], axis=-2)[..., 0, :]
    q = _canonical(q / np.linalg.norm(q, axis=-1, keepdims=True))
    return _write(q, scalar_first)


def matrix_from_quat(q: ArrayLike, scalar_first: bool = False) -> FloatArray:
    """Rotation matrix of a quaternion, normalising it first.

    Args:
        q: Quaternions, shape ``(..., 4)``, any nonzero norm.
        scalar_first: ``q`` is ``(w, x, y, z)`` instead of ``(x, y, z, w)``.

    Returns:
        Rotation matrices, shape ``(..., 3, 3)``.

    Raises:
        DimensionError: Wrong shape, NaN/inf, or a zero quaternion.
    """
    x, y, z, w = np.moveaxis(_normalized(_read(q, "q", scalar_first), "q"), -1, 0)
    R = np.empty((*x.shape, 3, 3))
    R[..., 0, 0] = 1.0 - 2.0 * (y * y + z * z)
    R[..., 0, 1] = 2.0 * (x * y - z * w)
    R[..., 0, 2] = 2.0 * (x * z + y * w)
    R[..., 1, 0] = 2.0 * (x * y + z * w)
    R[..., 1, 1] = 1.0 - 2.0 * (x * x + z * z)
    R[..., 1, 2] = 2.0 * (y * z - x * w)
    R[..., 2, 0] = 2.0 * (x * z - y * w)
    R[..., 2, 1] = 2.0 * (y * z + x * w)
    R[..., 2, 2] = 1.0 - 2.0 * (x * x + y * y)
    return R


def quat_multiply(q1: ArrayLike, q2: ArrayLike, scalar_first: bool = False) -> FloatArray:
    """Hamilton product ``q1 ⊗ q2``: the rotation ``q2`` followed by ``q1``.

    The inputs are not normalised, so the product of unit quaternions is unit
    up to round-off and ``matrix_from_quat(q1 ⊗ q2) = R(q1) · R(q2)``.

    Args:
        q1: Quaternions, shape ``(..., 4)``.
        q2: Quaternions, shape ``(..., 4)``; batch shapes broadcast.
        scalar_first: Inputs and output are ``(w, x, y, z)``.

    Returns:
        The products, shape ``(..., 4)``.
    """
    a = _read(q1, "q1", scalar_first)
    b = _read(q2, "q2", scalar_first)
    va, wa = a[..., :3], a[..., 3:]
    vb, wb = b[..., :3], b[..., 3:]
    v = wa * vb + wb * va + np.cross(va, vb)
    w = wa * wb - np.sum(va * vb, axis=-1, keepdims=True)
    return _write(np.concatenate([v, w], axis=-1), scalar_first)


def quat_conjugate(q: ArrayLike, scalar_first: bool = False) -> FloatArray:
    """Conjugate ``(−x, −y, −z, w)``: the inverse rotation of a unit quaternion.

    Args:
        q: Quaternions, shape ``(..., 4)``.
        scalar_first: Input and output are ``(w, x, y, z)``.

    Returns:
        The conjugates, shape ``(..., 4)``.
    """
    qa = _read(q, "q", scalar_first) * np.array([-1.0, -1.0, -1.0, 1.0])
    return _write(qa, scalar_first)


def quat_slerp(
    q1: ArrayLike, q2: ArrayLike, t: ArrayLike, scalar_first: bool = False
) -> FloatArray:
    """Spherical linear interpolation along the shortest arc from ``q1`` to ``q2``.

    ``q2`` is negated where ``q1 · q2 < 0`` so that the path is the shorter of
    the two arcs (rotation angle at most π). With ``Ω`` the angle between the
    unit 4-vectors, the weights ``sin((1 − t)Ω)/sin Ω`` and ``sin(tΩ)/sin Ω``
    are evaluated as ``(1 − t)·sinc((1 − t)Ω)/sinc Ω`` and
    ``t·sinc(tΩ)/sinc Ω``. That is the deliberate near-parallel branch: instead
    of switching to linear interpolation below some threshold, the ratio of
    sincs (``sinc Ω >= 2/π`` for ``Ω <= π/2``) tends smoothly to the linear
    weights ``1 − t`` and ``t`` and stays exact for any ``Ω``, including 0.

    Args:
        q1: Start quaternions, shape ``(..., 4)``, nonzero (normalised here).
        q2: End quaternions, shape ``(..., 4)``, nonzero (normalised here).
        t: Interpolation parameters, shape ``(...)``; 0 gives ``q1``, 1 gives
            ``q2`` (up to sign); values outside ``[0, 1]`` extrapolate.
        scalar_first: Inputs and output are ``(w, x, y, z)``.

    Returns:
        Unit quaternions of shape ``(..., 4)``, the batch shapes of ``q1``,
        ``q2`` and ``t`` broadcast together. The sign is continuous in ``t``
        (not canonicalised), so a sampled path does not jump.

    Raises:
        DimensionError: Wrong shapes, NaN/inf, or a zero quaternion.
    """
    a = _normalized(_read(q1, "q1", scalar_first), "q1")
    b = _normalized(_read(q2, "q2", scalar_first), "q2")
    ta = as_batch_array(t, "t", ())[..., None]
    b = np.where(np.sum(a * b, axis=-1, keepdims=True) < 0.0, -b, b)
    # Angle between unit vectors from atan2, accurate for tiny and large angles.
    omega = 2.0 * np.arctan2(
        np.linalg.norm(a - b, axis=-1, keepdims=True),
        np.linalg.norm(a + b, axis=-1, keepdims=True),
    )
    sinc_omega = np.sinc(omega / np.pi)  # np.sinc(x) = sin(πx)/(πx)
    s = 1.0 - ta
    wa = s * np.sinc(s * omega / np.pi) / sinc_omega
    wb = ta * np.sinc(ta * omega / np.pi) / sinc_omega
    return _write(wa * a + wb * b, scalar_first)
