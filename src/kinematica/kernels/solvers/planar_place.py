"""Placing a planar arm's joints: a subproblem's branches into full candidates.

The joints before a point (the slide and the first revolute joints) take it
to its target (:func:`place`: a triangle, a slide and a link, one link, or the
slide alone); :func:`emit` completes each branch (the last turn, the slide
along ``k``) into a candidate in the slot of its branch.
"""

from __future__ import annotations

import math

from kinematica.kernels._numba import Array, kernel
from kinematica.kernels.ik_check import LIMIT_TOL
from kinematica.kernels.so3 import wrap
from kinematica.kernels.solvers.planar_params import (
    P_AXIS,
    P_LIFT,
    P_LIFT_SIGN,
    P_NREV,
    P_QLIM,
    P_REV,
    P_SIGN,
    P_SLIDE,
    P_SWAP,
    P_TIP,
    P_U,
)
from kinematica.kernels.solvers.triangle import NEAR, REGULAR, slide_link, turn, two_link

__all__ = ["TURNS", "branch_count", "emit", "place", "slot_of", "within_limits"]

#: Column of the first revolute turn in a branch row (column 0: the slide).
TURNS = 1

_TWO_PI = 2.0 * math.pi


@kernel
def slot_of(params: Array, row: Array) -> int:
    """The branch slot of a single solution (pose targets of a 2R or PR arm).

    2R: the sign of link 2's angle relative to link 1 (as :func:`two_link`'s
    rows); PR: whether the link points along the slide.
    """
    if params[P_SLIDE] >= 0.0:
        bx = params[P_TIP] - params[P_AXIS]
        by = params[P_TIP + 1] - params[P_AXIS + 1]
        d = row[TURNS]
        along = (math.cos(d) * bx - math.sin(d) * by) * params[P_U]
        along += (math.sin(d) * bx + math.cos(d) * by) * params[P_U + 1]
        return 0 if along >= 0.0 else 1
    ax = params[P_AXIS + 2] - params[P_AXIS]
    ay = params[P_AXIS + 3] - params[P_AXIS + 1]
    psi = turn(ax, ay, params[P_TIP] - params[P_AXIS + 2], params[P_TIP + 1] - params[P_AXIS + 3])
    below = math.sin(psi + row[TURNS + 1]) <= 0.0
    return 0 if below != (params[P_SWAP] != 0.0) else 1


@kernel
def branch_count(params: Array, used: int) -> int:
    """Branches of the subproblem solved by the slide and ``used`` revolute joints: 1 or 2."""
    if params[P_SLIDE] >= 0.0:
        return 2 if used == 1 else 1
    return 2 if used == 2 else 1


@kernel
def place(
    params: Array,
    used: int,
    tx: float,
    ty: float,
    y0x: float,
    y0y: float,
    br: Array,
    tri: Array,
) -> int:
    """Place the point at ``y0`` (q = 0) on ``t`` with the slide and ``used`` revolute joints.

    Args:
        params: The arm.
        used: Revolute joints taking part, from the first.
        tx: Target plane x (m).
        ty: Target plane y (m).
        y0x: The point's plane x at q = 0 (m).
        y0y: Its plane y (m).
        br: ``(2, 4)`` out: one row per branch (:func:`_count`), the slide (m)
            then the turns of the revolute joints (rad).
        tri: ``(2, 2)`` scratch space.

    Returns:
        ``FOLD``, ``NEAR`` (branches merging) or ``REGULAR`` (see :func:`two_link`).
    """
    ax = params[P_AXIS]
    ay = params[P_AXIS + 1]
    if params[P_SLIDE] < 0.0 and used == 2:
        code = two_link(
            params[P_AXIS + 2] - ax,
            params[P_AXIS + 3] - ay,
            y0x - params[P_AXIS + 2],
            y0y - params[P_AXIS + 3],
            tx - ax,
            ty - ay,
            tri,
        )
        swap = params[P_SWAP] != 0.0
        for row in range(2):
            src = 1 - row if swap else row
            br[row, TURNS] = tri[src, 0]
            br[row, TURNS + 1] = tri[src, 1]
        return code
    if params[P_SLIDE] >= 0.0 and used == 1:
        near = slide_link(params[P_U], params[P_U + 1], y0x - ax, y0y - ay, tx - ax, ty - ay, tri)
        for row in range(2):
            br[row, 0] = tri[row, 0]
            br[row, TURNS] = tri[row, 1]
        return NEAR if near else REGULAR
    elif used == 1:  # one link
        br[0, TURNS] = turn(y0x - ax, y0y - ay, tx - ax, ty - ay)
    else:  # the slide alone
        br[0, 0] = (tx - y0x) * params[P_U] + (ty - y0y) * params[P_U + 1]
    return REGULAR


@kernel
def emit(
    params: Array, br: Array, used: int, value: float, pose: bool, dz: float, Q: Array
) -> None:
    """Candidates from a subproblem's branches ``br``: the last turn, the slot, every joint.

    ``value``: for pose targets the total turn φ (the last turn is what the
    others leave of it), for a free last joint its representative turn.
    """
    nrev = int(params[P_NREV])
    last = nrev - 1
    slide = int(params[P_SLIDE])
    lift = int(params[P_LIFT])
    count = branch_count(params, used)
    for row in range(count):
        if used < nrev:
            total = 0.0
            for j in range(used):
                total += br[row, TURNS + j]
            br[row, TURNS + last] = value - total if pose else value
        slot = row if count == 2 else slot_of(params, br[row])
        q = Q[slot]
        if slide >= 0:
            q[slide] = br[row, 0]
        for j in range(nrev):
            q[int(params[P_REV + j])] = params[P_SIGN + j] * br[row, TURNS + j]
        if lift >= 0:
            q[lift] = params[P_LIFT_SIGN] * dz


@kernel
def within_limits(params: Array, q: Array) -> bool:
    """True when ``q (n,)`` is within the joint limits (revolute angles modulo 2π), as the check."""
    for j in range(q.shape[0]):
        lo = params[P_QLIM + 2 * j] - LIMIT_TOL
        hi = params[P_QLIM + 2 * j + 1] + LIMIT_TOL
        v = q[j]
        if j != int(params[P_SLIDE]) and j != int(params[P_LIFT]):
            v = wrap(v)
            if v < lo and v + _TWO_PI <= hi:
                v += _TWO_PI
            elif v > hi and v - _TWO_PI >= lo:
                v -= _TWO_PI
        if not lo <= v <= hi:
            return False
    return True
