"""Euler-angle rates and angular velocity, for all 24 sequences.

For Euler angles ``(a, b, c)`` of a sequence with axes ``(i, j, k)`` (see
:mod:`kinematica.spatial.euler` for the naming), the angular velocity ``ω``
of the rotating frame, expressed in the FIXED frame, is linear in the angle
rates: ``ω = E(a, b, c) · (ȧ, ḃ, ċ)``. Differentiating ``R`` term by term:

- intrinsic, ``R = R_i(a) R_j(b) R_k(c)``:
  ``ω = e_i ȧ + R_i(a) e_j ḃ + R_i(a) R_j(b) e_k ċ``;
- extrinsic, ``R = R_k(c) R_j(b) R_i(a)``:
  ``ω = R_k(c) R_j(b) e_i ȧ + R_k(c) e_j ḃ + e_k ċ``.

``det E = ± sin b`` for proper Euler sequences (first axis = third axis) and
``± cos b`` for Tait-Bryan ones: ``E`` is singular exactly at gimbal lock,
where the first and third axes line up and angle rates stop being defined by
``ω``. That is a singularity of the representation, not of the arm.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.spatial.checks import as_batch_array
from kinematica.spatial.euler import GIMBAL_LOCK_TOL
from kinematica.spatial.euler import _parse as parse_sequence
from kinematica.spatial.transform import rotx, roty, rotz

__all__ = ["euler_rate_matrix", "euler_rate_singular"]

FloatArray = NDArray[np.float64]

_ELEMENTARY = (rotx, roty, rotz)


def euler_rate_matrix(angles: ArrayLike, seq: str = "ZYZ", degrees: bool = False) -> FloatArray:
    """The matrix ``E`` with ``ω = E · (ȧ, ḃ, ċ)`` (``ω`` in the fixed frame).

    Args:
        angles: Euler angles ``(a, b, c)``, shape ``(..., 3)``; radians unless
            ``degrees`` (the rates are then per degree too: ``ω`` in rad/s for
            rates in deg/s means multiplying by π/180 yourself).
        seq: Sequence name, scipy naming: upper case intrinsic (``"ZYZ"``),
            lower case extrinsic (``"zyz"``); all 24 are accepted.
        degrees: ``angles`` are in degrees.

    Returns:
        ``(..., 3, 3)``; column ``m`` is the (unit) axis of the ``m``-th
        elementary rotation, expressed in the fixed frame. Singular where
        :func:`euler_rate_singular` is True.

    Raises:
        EulerSequenceError: ``seq`` is not a valid sequence name.
        DimensionError: ``angles`` is not ``(..., 3)`` or holds NaN/inf.
    """
    (i, j, k), extrinsic = parse_sequence(seq)
    a = as_batch_array(angles, "angles", (3,))
    if degrees:
        a = np.deg2rad(a)
    eye = np.eye(3)
    E = np.empty((*a.shape[:-1], 3, 3))
    if extrinsic:
        Rk = _ELEMENTARY[k](a[..., 2])
        Rkj = Rk @ _ELEMENTARY[j](a[..., 1])
        E[..., :, 0] = Rkj[..., :, i]
        E[..., :, 1] = Rk[..., :, j]
        E[..., :, 2] = eye[k]
    else:
        Ri = _ELEMENTARY[i](a[..., 0])
        Rij = Ri @ _ELEMENTARY[j](a[..., 1])
        E[..., :, 0] = eye[i]
        E[..., :, 1] = Ri[..., :, j]
        E[..., :, 2] = Rij[..., :, k]
    return E


def euler_rate_singular(
    angles: ArrayLike, seq: str = "ZYZ", degrees: bool = False
) -> NDArray[np.bool_]:
    """Where ``E`` is singular: the second angle within ``GIMBAL_LOCK_TOL`` of lock.

    The band is the one :func:`kinematica.spatial.gimbal_locked` uses, so
    angles read from a locked rotation are flagged here too.

    Args:
        angles: ``(..., 3)`` Euler angles (radians unless ``degrees``).
        seq: Sequence name.
        degrees: ``angles`` are in degrees.

    Returns:
        ``(...)`` booleans.
    """
    (i, _, k), _ext = parse_sequence(seq)
    a = as_batch_array(angles, "angles", (3,))
    b = np.deg2rad(a[..., 1]) if degrees else a[..., 1]
    # Distance of b from the nearest singular value: multiples of π for proper
    # Euler sequences (sin b = 0), odd multiples of π/2 for Tait-Bryan ones.
    shift = 0.0 if i == k else np.pi / 2
    dist = np.abs(np.remainder(b - shift + np.pi / 2, np.pi) - np.pi / 2)
    return np.asarray(dist <= GIMBAL_LOCK_TOL)
