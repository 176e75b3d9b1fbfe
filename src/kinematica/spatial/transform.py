"""Elementary rotations and homogeneous transforms, batched over leading axes.

A rotation is a ``(..., 3, 3)`` array; a homogeneous transform ``T_a_b`` (the
pose of frame b in frame a) is a ``(..., 4, 4)`` array whose last row is
``[0, 0, 0, 1]``. Angles are in radians, lengths in metres.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import DimensionError
from kinematica.spatial.checks import as_float_array

__all__ = [
    "compose",
    "inv_transform",
    "make_transform",
    "rotx",
    "roty",
    "rotz",
    "transl",
]

FloatArray = NDArray[np.float64]


def _elementary(angle: ArrayLike, axis: int) -> FloatArray:
    """Rotation by ``angle`` about coordinate axis ``axis`` (0=x, 1=y, 2=z)."""
    t = as_float_array(angle, "angle")
    c, s = np.cos(t), np.sin(t)
    R = np.zeros((*t.shape, 3, 3))
    i, j = (axis + 1) % 3, (axis + 2) % 3
    R[..., axis, axis] = 1.0
    R[..., i, i] = c
    R[..., j, j] = c
    R[..., i, j] = -s
    R[..., j, i] = s
    return R


def rotx(angle: ArrayLike) -> FloatArray:
    """Rotation about x by ``angle`` (radians): ``(...,)`` -> ``(..., 3, 3)``."""
    return _elementary(angle, 0)


def roty(angle: ArrayLike) -> FloatArray:
    """Rotation about y by ``angle`` (radians): ``(...,)`` -> ``(..., 3, 3)``."""
    return _elementary(angle, 1)


def rotz(angle: ArrayLike) -> FloatArray:
    """Rotation about z by ``angle`` (radians): ``(...,)`` -> ``(..., 3, 3)``."""
    return _elementary(angle, 2)


def make_transform(R: ArrayLike | None = None, p: ArrayLike | None = None) -> FloatArray:
    """Homogeneous transform from a rotation and a translation.

    Args:
        R: Rotation ``(..., 3, 3)``; identity when ``None``.
        p: Translation ``(..., 3)`` in metres; zero when ``None``.

    Returns:
        ``(..., 4, 4)`` transform, batch shape broadcast from ``R`` and ``p``.
    """
    Ra = np.eye(3) if R is None else as_float_array(R, "R", (3, 3))
    pa = np.zeros(3) if p is None else as_float_array(p, "p", (3,))
    try:
        batch = np.broadcast_shapes(Ra.shape[:-2], pa.shape[:-1])
    except ValueError as exc:
        raise DimensionError(
            f"the batch shapes of R {Ra.shape} and p {pa.shape} do not broadcast"
        ) from exc
    T = np.zeros((*batch, 4, 4))
    T[..., :3, :3] = Ra
    T[..., :3, 3] = pa
    T[..., 3, 3] = 1.0
    return T


def transl(x: ArrayLike, y: ArrayLike = 0.0, z: ArrayLike = 0.0) -> FloatArray:
    """Pure translation ``Tras(x, y, z)``: ``(...,)`` each -> ``(..., 4, 4)``."""
    xyz = (as_float_array(v, name) for v, name in ((x, "x"), (y, "y"), (z, "z")))
    try:
        p = np.stack(np.broadcast_arrays(*xyz), -1)
    except ValueError as exc:
        raise DimensionError(f"x, y and z do not broadcast: {exc}") from exc
    return make_transform(None, p)


def inv_transform(T: ArrayLike) -> FloatArray:
    """Inverse of a homogeneous transform, ``[Rᵀ, -Rᵀ p]``: ``(..., 4, 4)``.

    The rotation part is transposed rather than inverted numerically: exact for
    a rotation, and cheaper.
    """
    Ta = as_float_array(T, "T", (4, 4))
    Rt = np.swapaxes(Ta[..., :3, :3], -1, -2)
    return make_transform(Rt, -np.einsum("...ij,...j->...i", Rt, Ta[..., :3, 3]))


def compose(*transforms: ArrayLike) -> FloatArray:
    """Product ``T1 · T2 · ... · Tk`` of transforms, broadcasting batch shapes."""
    if not transforms:
        return np.eye(4)
    out = as_float_array(transforms[0], "transform 1", (4, 4))
    for i, T in enumerate(transforms[1:], start=2):
        Ta = as_float_array(T, f"transform {i}", (4, 4))
        try:
            out = out @ Ta
        except ValueError as exc:
            raise DimensionError(f"transform {i}: batch shapes do not broadcast: {exc}") from exc
    return out
