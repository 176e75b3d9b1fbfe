"""Position targets of arms with more than three joints: joints 1-3 place the tool origin.

The tool origin with joints 4..n at 0 is a point fixed after joint 3; the arm
part (:func:`~kinematica.kernels.solvers.arm_point.place`) puts it on the
target, up to four ways (the decoupling of the lecture notes: shoulder × elbow). Joints 4..n
stay free, so every target's solutions form a continuum: the candidates are
its representatives with those joints at 0, the target is ``singular`` and
joints 4..n are named free.

A target that no branch reaches with joints 4..n at 0 may still be reached
with other values of them (they move the tool origin by at most ``reach``,
a bound from the DH table): the gap is then the arm part's gap less that
bound, and the target is flagged near (no proof) unless the bound is 0 (the
tool origin on every later axis: a spherical wrist without tool offset).
"""

from __future__ import annotations

import math

from kinematica.kernels._numba import Array, kernel
from kinematica.kernels.ik_check import INFO_FREE, INFO_GAP, INFO_NEAR, INFO_SINGULAR
from kinematica.kernels.solvers.arm_base import A_SIZE, ST_FREE, ST_GAP, ST_NEAR

__all__ = ["P_REACH", "P_SIZE", "position"]

P_REACH = A_SIZE + 1  # bound (m) on how far joints 4..n move the tool origin from the point
P_SIZE = A_SIZE + 2


@kernel
def position(params: Array, Q3: Array, st: Array, Q: Array, info: Array) -> None:
    """Candidates for one position target, given where joints 1-3 put the tool origin.

    Args:
        params: ``(P_SIZE,)`` the arm part, the mode, then ``reach``.
        Q3: ``(4, 3)`` the placements (see
            :func:`~kinematica.kernels.solvers.arm_point.place`).
        st: What ``place`` reported.
        Q: ``(4, n)`` out: one slot per arm branch, joints 4..n at 0.
        info: ``(INFO_FREE + n,)`` out (zero on entry): see
            :mod:`kinematica.kernels.ik_check`.
    """
    n = Q.shape[1]
    real = False
    for k in range(4):
        ok = not math.isnan(Q3[k, 0])
        real |= ok
        for j in range(n):
            Q[k, j] = (Q3[k, j] if j < 3 else 0.0) if ok else math.nan
    reach = params[P_REACH]
    info[INFO_SINGULAR] = 1.0
    for j in range(n):
        info[INFO_FREE + j] = st[ST_FREE + j] if j < 3 else 1.0
    info[INFO_NEAR] = 1.0 if st[ST_NEAR] != 0.0 or (not real and reach > 0.0) else 0.0
    gap = max(0.0, st[ST_GAP] - reach)
    info[INFO_GAP] = gap if not real or gap > 0.0 else math.nan
