"""One kernel for the arms decoupled at joint 3: spherical-wrist poses, arm positions.

Both solvers place a point fixed after joint 3 by joints 1-3
(:func:`~kinematica.kernels.solvers.arm_point.place`): the wrist centre of a
pose, whose wrist then supplies the rotation
(:func:`~kinematica.kernels.solvers.spherical_wrist.pose`), or the tool origin
of a position target with the later joints at 0
(:func:`~kinematica.kernels.solvers.arm_position.position`). They share the
arm part's parameters and this entry point, chosen by ``params[P_MODE]``: one
compiled ``place`` and one batch loop serve both (each caller of ``place`` and
each ``prange`` loop costs a second or two of compilation).
"""

from __future__ import annotations

import numba
import numpy as np

from kinematica.kernels._numba import Array, batch_kernel, kernel
from kinematica.kernels.ik_check import TARGET_BLOCK
from kinematica.kernels.solvers.arm_base import A_SIZE, ST_SIZE
from kinematica.kernels.solvers.arm_point import place
from kinematica.kernels.solvers.arm_position import position
from kinematica.kernels.solvers.spherical_wrist import pose, wrist_centre

__all__ = ["MODE_POSE", "MODE_POSITION", "P_MODE", "solve", "solve_batch"]

P_MODE = A_SIZE  # which solver: MODE_POSE or MODE_POSITION
MODE_POSE, MODE_POSITION = 0.0, 1.0


@kernel
def _solve(params: Array, T: Array, Q: Array, info: Array, ct: Array, Q3: Array, st: Array) -> None:
    """:func:`solve` with its work arrays given: ``ct (3,)``, ``Q3 (4, 3)``, ``st (ST_SIZE,)``."""
    if params[P_MODE] == MODE_POSE:
        wrist_centre(params, T, ct)
    else:
        for i in range(3):
            ct[i] = T[i, 3]
    place(params, ct, Q3, st)
    if params[P_MODE] == MODE_POSE:
        pose(params, T, Q3, st, Q, info)
    else:
        position(params, Q3, st, Q, info)


@kernel
def solve(params: Array, T: Array, Q: Array, info: Array) -> None:
    """Candidates of one target ``T (4, 4)`` (base frame) into ``Q (m, n)`` and ``info``.

    See :func:`~kinematica.kernels.solvers.spherical_wrist.pose` (``m = 8``,
    ``n = 6``) and :func:`~kinematica.kernels.solvers.arm_position.position`
    (``m = 4``; only the translation of ``T`` is read).
    """
    _solve(params, T, Q, info, np.empty(3), np.empty((4, 3)), np.empty(ST_SIZE))


@batch_kernel
def solve_batch(params: Array, T: Array, Q: Array, info: Array) -> None:
    """:func:`solve` for targets ``T (N, 4, 4)`` in parallel (``Q``, ``info``: an ``N`` axis)."""
    N = T.shape[0]
    for blk in numba.prange((N + TARGET_BLOCK - 1) // TARGET_BLOCK):
        ct, Q3, st = np.empty(3), np.empty((4, 3)), np.empty(ST_SIZE)  # once per block
        for i in range(blk * TARGET_BLOCK, min(N, (blk + 1) * TARGET_BLOCK)):
            _solve(params, T[i], Q[i], info[i], ct, Q3, st)
