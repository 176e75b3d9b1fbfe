"""The geometric Jacobian of the tool, from the joint axes of one chain walk.

Rows 0-2 map joint rates to the linear velocity of the tool origin, rows 3-5
to the angular velocity. Column i is ``[z × (p - o); z]`` for a revolute joint
with axis ``z`` through ``o``, ``[z; 0]`` for a prismatic one, ``p`` the tool
origin; all in the base frame, or rotated into the tool frame on request.
"""

from __future__ import annotations

import numba
import numpy as np

from kinematica.kernels._numba import Array, batch_kernel, inline_kernel, kernel
from kinematica.kernels.fk import (
    BLOCK,
    FK_NOT_FINITE,
    LINK_PRISMATIC,
    block_trig,
    check_row,
    walk_row,
)

__all__ = ["columns", "columns_row", "jacobian_batch", "jacobian_one", "jacobian_rows"]


@inline_kernel
def columns_row(links: Array, axes: Array, pose: Array, tool_frame: bool, J: Array, b: int) -> None:
    """Fill ``J[b] (6, n)`` from the joint ``axes (n, 6)`` and the tool ``pose (4, 4)``."""
    # J[b] indexed, not taken as a view: see kinematica.kernels.fk.block_trig.
    n = links.shape[0]
    px, py, pz = pose[0, 3], pose[1, 3], pose[2, 3]
    for i in range(n):
        zx, zy, zz = axes[i, 0], axes[i, 1], axes[i, 2]
        if links[i, LINK_PRISMATIC] != 0.0:
            vx, vy, vz, wx, wy, wz = zx, zy, zz, 0.0, 0.0, 0.0
        else:
            dx, dy, dz = px - axes[i, 3], py - axes[i, 4], pz - axes[i, 5]
            vx, vy, vz = zy * dz - zz * dy, zz * dx - zx * dz, zx * dy - zy * dx
            wx, wy, wz = zx, zy, zz
        if tool_frame:  # Rᵀ v, Rᵀ ω: the columns of R are the tool's axes
            vx, vy, vz = (
                pose[0, 0] * vx + pose[1, 0] * vy + pose[2, 0] * vz,
                pose[0, 1] * vx + pose[1, 1] * vy + pose[2, 1] * vz,
                pose[0, 2] * vx + pose[1, 2] * vy + pose[2, 2] * vz,
            )
            wx, wy, wz = (
                pose[0, 0] * wx + pose[1, 0] * wy + pose[2, 0] * wz,
                pose[0, 1] * wx + pose[1, 1] * wy + pose[2, 1] * wz,
                pose[0, 2] * wx + pose[1, 2] * wy + pose[2, 2] * wz,
            )
        J[b, 0, i] = vx
        J[b, 1, i] = vy
        J[b, 2, i] = vz
        J[b, 3, i] = wx
        J[b, 4, i] = wy
        J[b, 5, i] = wz


@inline_kernel
def columns(links: Array, axes: Array, pose: Array, tool_frame: bool, J: Array) -> None:
    """Fill ``J (6, n)`` from the joint ``axes (n, 6)`` and the tool ``pose (4, 4)``."""
    columns_row(links, axes, pose, tool_frame, J[None], 0)


@kernel
def jacobian_rows(
    links: Array,
    ends: Array,
    Q: Array,
    b0: int,
    b1: int,
    tool_frame: bool,
    J: Array,
) -> int:
    """Rows ``b0:b1`` of a batch, in one thread: a block of :func:`jacobian_batch`.

    Returns:
        The number of these rows holding NaN or inf (their ``J`` is NaN).
    """
    n = links.shape[0]
    C = np.empty((n, b1 - b0))
    S = np.empty((n, b1 - b0))
    poses = np.empty((1, 4, 4))
    axes = np.empty((n, 6))
    pose = poses[0]
    no_frames = np.empty((0, 4, 4))
    bad = 0
    block_trig(links, Q, b0, b1, C, S)
    for b in range(b0, b1):
        walk_row(links, ends, False, C, S, b - b0, Q, b, poses, 0, no_frames, axes)
        columns_row(links, axes, pose, tool_frame, J, b)
        if check_row(links, Q, b) == FK_NOT_FINITE:
            bad += 1
            J[b, :, :] = np.nan
    return bad


@kernel
def jacobian_one(links: Array, ends: Array, q: Array, tool_frame: bool, J: Array) -> bool:
    """``J (6, n)`` at one configuration ``q (n,)``; False (and NaN) when ``q`` is not finite."""
    # A batch of one; see kinematica.kernels.fk.fk_one for np.int64 and x[None].
    first: int = np.int64(0)  # type: ignore[assignment]
    last: int = np.int64(1)  # type: ignore[assignment]
    return jacobian_rows(links, ends, q[None], first, last, tool_frame, J[None]) == 0


@batch_kernel
def jacobian_batch(links: Array, ends: Array, Q: Array, tool_frame: bool, J: Array) -> int:
    """``J (B, 6, n)`` of a batch ``Q (B, n)``; rows holding NaN/inf come out NaN.

    Returns:
        The number of rows of ``Q`` holding NaN or inf.
    """
    B = Q.shape[0]
    nblocks = (B + BLOCK - 1) // BLOCK
    bad = 0
    for blk in numba.prange(nblocks):
        b0 = blk * BLOCK
        bad += jacobian_rows(links, ends, Q, b0, min(B, b0 + BLOCK), tool_frame, J)
    return bad
