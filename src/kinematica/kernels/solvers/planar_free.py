"""Position targets of a planar arm with a third joint in the plane: a free last joint.

The 3R, PRR and SCARA arms reach a position with a continuum of
configurations: the last revolute joint is free. :func:`free_last` picks its
representative turn: within the joint limits when it can.
"""

from __future__ import annotations

import math

import numpy as np

from kinematica.kernels._numba import Array, kernel
from kinematica.kernels.ik_check import INFO_FREE, INFO_SINGULAR
from kinematica.kernels.solvers.planar_params import (
    P_AXIS,
    P_NREV,
    P_QLIM,
    P_REACH,
    P_REV,
    P_SIGN,
    P_SLIDE,
    P_TIP,
    P_U,
)
from kinematica.kernels.solvers.planar_place import emit, place, within_limits
from kinematica.kernels.solvers.triangle import SINGULAR_TOL, turn

__all__ = ["FREE_SAMPLES", "free_last"]

#: Representative turns of a free last joint tried, from the middle of its
#: range outwards (each with both signs), until a candidate is within the
#: joint limits (position targets of the 3R, PRR and SCARA arms).
FREE_SAMPLES = 33


@kernel
def _fraction(i: int) -> float:
    """The i-th of ``FREE_SAMPLES`` samples of [0, 1], from the middle outwards to both ends."""
    j = (i + 1) // 2
    side = 1.0 if i % 2 == 1 else -1.0
    return 0.5 + side * j / (FREE_SAMPLES - 1)


@kernel
def _window_rep(params: Array, j: int) -> float:
    """A value for a wholly free joint ``j``: 0 if within its limits, else their middle."""
    lo = params[P_QLIM + 2 * j]
    hi = params[P_QLIM + 2 * j + 1]
    if lo <= 0.0 <= hi or not math.isfinite(lo + hi):
        return 0.0
    return 0.5 * (lo + hi)


@kernel
def _slide_length(
    params: Array, along: float, across: float, a: float, z: float, fwd: bool
) -> float:
    """The length ``ℓ`` that puts the slide mid-way in its limits on one branch, or -1.

    On the forward (backward) branch the slide is ``along ∓ √(ℓ² − across²)``
    for ``ℓ`` in ``[a, z]``; -1 when no such slide is within the limits.
    """
    j = int(params[P_SLIDE])
    r_lo = math.sqrt(max((a - across) * (a + across), 0.0))
    r_hi = math.sqrt(max((z - across) * (z + across), 0.0))
    lo = params[P_QLIM + 2 * j]
    hi = params[P_QLIM + 2 * j + 1]
    if fwd:  # s = along - r: r = along - s in [along - hi, along - lo]
        r0 = max(r_lo, along - hi)
        r1 = min(r_hi, along - lo)
    else:  # s = along + r
        r0 = max(r_lo, lo - along)
        r1 = min(r_hi, hi - along)
    if r0 > r1:
        return -1.0
    r = 0.5 * (r0 + r1) if math.isfinite(r0 + r1) else min(max(0.5 * (r_lo + r_hi), r0), r1)
    return math.hypot(r, across)


@kernel
def _free_turn(ctx: Array, ell: float, below: bool) -> float:
    """The last joint's turn (rad) that makes the last two links span ``ℓ``.

    ``below``: the angle from link ``b`` to link ``c`` is <= 0 (else >= 0).
    """
    Lb = ctx[3]
    Lc = ctx[4]
    shortest = abs(Lb - Lc)
    longest = Lb + Lc
    S = max((longest - ell) * (longest + ell), 0.0)
    C = max((ell - shortest) * (ell + shortest), 0.0)
    psi = 2.0 * math.atan2(math.sqrt(S), math.sqrt(C))
    return (-psi if below else psi) - ctx[5]


@kernel
def _free_try(params: Array, ctx: Array, d: float, br: Array, tri: Array, Q: Array) -> int:
    """Candidates with the free last joint turned by ``d``; what :func:`place` says."""
    last = int(params[P_NREV]) - 1
    lx = params[P_AXIS + 2 * last]
    ly = params[P_AXIS + 2 * last + 1]
    cx = params[P_TIP] - lx
    cy = params[P_TIP + 1] - ly
    c = math.cos(d)
    s = math.sin(d)
    code = place(params, last, ctx[0], ctx[1], lx + c * cx - s * cy, ly + s * cx + c * cy, br, tri)
    emit(params, br, last, d, False, ctx[2], Q)
    return code


@kernel
def free_last(
    params: Array, x: float, y: float, dz: float, br: Array, tri: Array, Q: Array, info: Array
) -> int:
    """Position targets of an arm with a third joint in the plane: its last revolute joint is free.

    The last two links, ``b`` (to the last axis) and ``c`` (from it to the
    tool origin), span any length ``ℓ`` in ``[|Lb − Lc|, Lb + Lc]``; the joints
    before reach the target (``x, y``) with ``ℓ`` in some range. The
    representative is the first of these lengths (each with both signs of the
    angle between ``b`` and ``c``) that puts a candidate within the joint
    limits, else the first: after a slide, the lengths that put it mid-way in
    its limits on either branch; then ``FREE_SAMPLES`` lengths from the middle
    of the range outwards. A tool origin on the last axis (``Lc = 0``) leaves
    that joint wholly free: 0, or the middle of its limits.

    Returns:
        What :func:`place` says of the remaining triangle (``FOLD``, ``NEAR``
        or ``REGULAR``).
    """
    last = int(params[P_NREV]) - 1
    jl = int(params[P_REV + last])
    slide = params[P_SLIDE] >= 0.0
    lx = params[P_AXIS + 2 * last]
    ly = params[P_AXIS + 2 * last + 1]
    bx = lx - params[P_AXIS + 2 * last - 2]
    by = ly - params[P_AXIS + 2 * last - 1]
    cx = params[P_TIP] - lx
    cy = params[P_TIP + 1] - ly
    rx = x - params[P_AXIS]
    ry = y - params[P_AXIS + 1]
    along = rx * params[P_U] + ry * params[P_U + 1]
    if slide:  # ℓ at least the distance across the slide
        lo = abs(ry * params[P_U] - rx * params[P_U + 1])
        hi = math.inf
    else:  # the 2R triangle before it: |r - L1| <= ℓ <= r + L1
        r = math.hypot(rx, ry)
        L1 = math.hypot(
            params[P_AXIS + 2] - params[P_AXIS], params[P_AXIS + 3] - params[P_AXIS + 1]
        )
        lo = abs(r - L1)
        hi = r + L1
    Lb = math.hypot(bx, by)
    Lc = math.hypot(cx, cy)
    shortest = abs(Lb - Lc)
    longest = Lb + Lc
    a = max(shortest, lo)
    z = min(longest, hi)
    tol = SINGULAR_TOL * params[P_REACH]
    wholly = Lc <= tol
    if wholly or z - a > tol:
        info[INFO_SINGULAR] = 1.0
        info[INFO_FREE + jl] = 1.0
    ctx = np.empty(6)  # the target, its height, the last two links and their angle
    ctx[0] = x
    ctx[1] = y
    ctx[2] = dz
    ctx[3] = Lb
    ctx[4] = Lc
    ctx[5] = turn(bx, by, cx, cy)
    if wholly:  # the other joints do not depend on it
        return _free_try(params, ctx, _window_rep(params, jl) * params[P_SIGN + last], br, tri, Q)
    if a > z:  # out of reach: the nearest length
        return _free_try(
            params, ctx, _free_turn(ctx, min(max(a, shortest), longest), False), br, tri, Q
        )
    first = 2 if slide else 0  # lengths from the slide's limits first
    for t in range(first + FREE_SAMPLES):
        if t < first:
            ell = _slide_length(params, along, lo, a, z, t == 0)
            if ell < 0.0:
                continue
        else:
            ell = a + _fraction(t - first) * (z - a)
        for side in range(2):
            code = _free_try(params, ctx, _free_turn(ctx, ell, side == 1), br, tri, Q)
            if within_limits(params, Q[0]) or within_limits(params, Q[1]):
                return code
    return _free_try(params, ctx, _free_turn(ctx, 0.5 * (a + z), False), br, tri, Q)
