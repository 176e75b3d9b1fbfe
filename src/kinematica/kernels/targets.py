"""How far a 4x4 matrix is from a rigid transform: the defects of IK targets.

One small kernel, so that checking one target costs a call, not a dozen numpy
operations; a batch runs it in a parallel loop.
"""

from __future__ import annotations

import math

import numba

from kinematica.kernels._numba import Array, batch_kernel, kernel

__all__ = [
    "DEFECT_DET",
    "DEFECT_FINITE",
    "DEFECT_LAST_ROW",
    "DEFECT_ORTHO",
    "DEFECT_SIZE",
    "pose_defects",
    "pose_defects_batch",
]

# What :func:`pose_defects` writes.
DEFECT_FINITE, DEFECT_LAST_ROW, DEFECT_ORTHO, DEFECT_DET = range(4)
DEFECT_SIZE = 4


@kernel
def pose_defects(T: Array, out: Array) -> None:
    """The defects of ``T (4, 4)`` as a rigid transform, in ``out (DEFECT_SIZE,)``.

    ``DEFECT_FINITE``: 1.0 when every entry is finite (else the others are NaN);
    ``DEFECT_LAST_ROW``: max |last row − [0, 0, 0, 1]|; ``DEFECT_ORTHO``: max
    |RᵀR − I| of the rotation block; ``DEFECT_DET``: det R.
    """
    finite = True
    for i in range(4):
        for j in range(4):
            finite &= math.isfinite(T[i, j])
    out[DEFECT_FINITE] = 1.0 if finite else 0.0
    if not finite:
        out[DEFECT_LAST_ROW] = math.nan
        out[DEFECT_ORTHO] = math.nan
        out[DEFECT_DET] = math.nan
        return
    last = abs(T[3, 0])
    last = max(last, abs(T[3, 1]))
    last = max(last, abs(T[3, 2]))
    last = max(last, abs(T[3, 3] - 1.0))
    out[DEFECT_LAST_ROW] = last
    ortho = 0.0
    for i in range(3):
        for j in range(i, 3):
            g = T[0, i] * T[0, j] + T[1, i] * T[1, j] + T[2, i] * T[2, j]
            if i == j:
                g -= 1.0
            ortho = max(ortho, abs(g))
    out[DEFECT_ORTHO] = ortho
    out[DEFECT_DET] = (
        T[0, 0] * (T[1, 1] * T[2, 2] - T[1, 2] * T[2, 1])
        - T[0, 1] * (T[1, 0] * T[2, 2] - T[1, 2] * T[2, 0])
        + T[0, 2] * (T[1, 0] * T[2, 1] - T[1, 1] * T[2, 0])
    )


@batch_kernel
def pose_defects_batch(T: Array, out: Array) -> None:
    """:func:`pose_defects` of every ``T (N, 4, 4)`` into ``out (N, DEFECT_SIZE)``."""
    for i in numba.prange(T.shape[0]):
        pose_defects(T[i], out[i])
