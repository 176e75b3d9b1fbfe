"""Python entry points of the FK and Jacobian kernels, over a :class:`DHChain`.

They take joint values already validated as floats of shape ``(..., n)``
(the robot layer checks and explains bad input), flatten any batch shape, call
the single-configuration kernel for one configuration and the parallel batch
kernel otherwise, and restore the batch shape.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from kinematica.dh.chain import DHChain
from kinematica.kernels._numba import set_workers
from kinematica.kernels.fk import FK_NOT_FINITE, FK_OUTSIDE_LIMITS, fk_batch, fk_one, fk_pose
from kinematica.kernels.jacobian import jacobian_batch, jacobian_one

__all__ = ["fk", "jacobian", "joint_axes"]

FloatArray = NDArray[np.float64]

_NO_FRAMES = np.empty((0, 4, 4))
_NO_AXES = np.empty((0, 6))
_NO_FRAMES_B = np.empty((0, 0, 4, 4))
_NO_AXES_B = np.empty((0, 0, 6))


def _contiguous(q: FloatArray) -> FloatArray:
    """``q (n,)`` as the one array type the single-call kernels are compiled for.

    A strided or read-only array is another type to numba: passed as it is, it
    would cost a compilation of its own (seconds) for the same result.
    """
    flags = q.flags
    return q if flags.c_contiguous and flags.writeable else q.copy()


def _flat(chain: DHChain, q: FloatArray) -> FloatArray:
    return np.ascontiguousarray(q.reshape(-1, chain.dof), dtype=np.float64)


def fk(
    chain: DHChain, q: FloatArray, all_frames: bool = False, workers: int | None = None
) -> tuple[FloatArray, int, int]:
    """Tool poses (or every frame) of configurations ``q``.

    Args:
        chain: The chain.
        q: ``(..., n)`` float joint values (rad, m).
        all_frames: Every frame ``0T0 (base), 0T1, ..., 0Tn (with tool)``.
        workers: Threads for a batch (None: the library default).

    Returns:
        ``(T, bad, outside)``: ``(..., 4, 4)`` poses or ``(..., n+1, 4, 4)``
        frames; the number of configurations holding NaN/inf (their results
        are NaN; for one configuration ``T`` is then undefined); the number
        beyond some joint's own limits (computed all the same).
    """
    if q.ndim == 1:  # the single-call path: every attribute look-up here counts
        q = _contiguous(q)
        pose = np.empty((4, 4))
        if all_frames:
            frames = np.empty((q.shape[0] + 1, 4, 4))
            code = fk_one(chain.links, chain.ends, chain.frames_mid, q, pose, frames, _NO_AXES)
            pose = frames
        else:
            code = fk_pose(chain.links, chain.ends, q, pose)
        return pose, code == FK_NOT_FINITE, code == FK_OUTSIDE_LIMITS
    flat = _flat(chain, q)
    poses = np.empty((flat.shape[0], 4, 4))
    frames = np.empty((flat.shape[0], chain.dof + 1, 4, 4)) if all_frames else _NO_FRAMES_B
    set_workers(workers)
    bad, outside = fk_batch(
        chain.links, chain.ends, chain.frames_mid, flat, poses, frames, _NO_AXES_B
    )
    out = frames if all_frames else poses
    return out.reshape(*q.shape[:-1], *out.shape[1:]), int(bad), int(outside)


def joint_axes(chain: DHChain, q: FloatArray) -> FloatArray:
    """Each joint's axis as a line: ``(..., n, 6)`` unit direction, then a point (base frame)."""
    flat = _flat(chain, q)
    poses = np.empty((flat.shape[0], 4, 4))
    axes = np.empty((flat.shape[0], chain.dof, 6))
    fk_batch(chain.links, chain.ends, chain.frames_mid, flat, poses, _NO_FRAMES_B, axes)
    return axes.reshape(*q.shape[:-1], chain.dof, 6)


def jacobian(
    chain: DHChain, q: FloatArray, tool_frame: bool = False, workers: int | None = None
) -> tuple[FloatArray, int]:
    """Geometric Jacobians ``(..., 6, n)`` of configurations ``q (..., n)``.

    Returns:
        ``(J, bad)`` as for :func:`fk`.
    """
    if q.ndim == 1:
        q = _contiguous(q)
        J = np.empty((6, q.shape[0]))
        ok = jacobian_one(chain.links, chain.ends, q, tool_frame, J)
        return J, int(not ok)
    n = chain.dof
    flat = _flat(chain, q)
    Jb = np.empty((flat.shape[0], 6, n))
    set_workers(workers)
    bad = jacobian_batch(chain.links, chain.ends, flat, tool_frame, Jb)
    return Jb.reshape(*q.shape[:-1], 6, n), int(bad)
