"""Closed-form IK of planar arms and the SCARA, one target: every branch.

Every revolute axis of these arms is parallel to one direction ``k``; the slide
of the PR / PRR arms moves across ``k``, the SCARA's slide along it. In the
plane normal to ``k`` (coordinates on ``e1``, ``e2 = k × e1``; angles
counter-clockwise seen from the side ``k`` points to) a revolute joint turns
everything after it by ± its angle, so the problem is planar. It is written on
the joint axes at q = 0 (product of exponentials), so any base, tool, offset
and DH convention is the same problem: up to three revolute joints, an
optional slide across ``k`` before them, an optional slide along ``k`` (it
commutes with the rest and takes the height).

* Pose targets: the orientation gives the total turn ``φ`` (the sum of the
  revolute turns) and pins the last revolute axis at ``w = p + R w_tool``; the
  joints before it take that axis to ``w``: a 2R triangle (3R, SCARA: two
  branches), a slide and a link (PRR: two), one link (2R: one solution), the
  slide alone (PR: one). The last turn is ``φ`` minus the others.
* Position targets: the joints take the tool origin to the target (2R, PR:
  two branches). An arm with a third joint in the plane (3R, PRR, SCARA) has
  a continuum: its last revolute joint is free (``singular``), and the
  representative turn of it puts the remaining problem mid-way inside its reach.

Candidates are never withheld: out of reach each subproblem gives its
least-squares configuration (the triangle stretched or folded towards the
target, the link across the slide) for the check to judge by forward
kinematics, and ``gap`` is the exact distance from the target position to the
reachable set of the tool origin. Triangles are solved by half-angle formulas
that stay accurate at the folds, ``4 L1 L2 sin²(ψ/2) = (L1 + L2 − r)(L1 + L2 + r)``
and ``4 L1 L2 cos²(ψ/2) = (r − |L1 − L2|)(r + |L1 − L2|)``: a target 1e-9 m
from the first axis of a folded triangle with equal links keeps both
solutions. On that axis itself every first turn solves it (``singular``, that
joint free, and the last one for pose targets: it turns with it). No
quantity that grows with the target is squared: a target at 1e300 m gives
finite candidates and its gap.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from kinematica.kernels._numba import Array, batch_kernel, kernel
from kinematica.kernels.ik_check import (
    INFO_FREE,
    INFO_GAP,
    INFO_NEAR,
    INFO_SINGULAR,
    LIMIT_TOL,
)
from kinematica.kernels.so3 import wrap

__all__ = [
    "FREE_SAMPLES",
    "P_AXIS",
    "P_E1",
    "P_E2",
    "P_K",
    "P_LENGTH",
    "P_LIFT",
    "P_LIFT_SIGN",
    "P_LIFT_TILT",
    "P_NREV",
    "P_ORIGIN",
    "P_POSE",
    "P_QLIM",
    "P_RE1",
    "P_REACH",
    "P_REV",
    "P_RMAX",
    "P_RMIN",
    "P_SIGN",
    "P_SIZE",
    "P_SLACK",
    "P_SLIDE",
    "P_SLIDE_TILT",
    "P_SWAP",
    "P_TIP",
    "P_TOOL",
    "P_U",
    "P_WRIST",
    "SINGULAR_TOL",
    "solve",
    "solve_batch",
    "turn",
    "two_link",
]

#: Round-off of this kernel's geometry, relative to the arm's reach. A target
#: this close to the first axis of a folded triangle whose links differ by at
#: most as much is on the fold: every turn of the first joint reaches it. The
#: same measure tells a free last joint (a range of its turns reaches the
#: target) from an isolated solution, and a gap from round-off (a smaller
#: one is not reported).
SINGULAR_TOL = 1e-12
#: Representative turns of a free last joint tried, from the middle of its
#: range outwards (each with both signs), until a candidate is within the
#: joint limits (position targets of the 3R, PRR and SCARA arms).
FREE_SAMPLES = 33

# Parameters (a flat array packed by kinematica.ik.analytic.planar_arms).
P_POSE = 0  # 1.0: pose targets, 0.0: position targets (tool origin)
P_SWAP = 1  # 1.0: the triangle's branch ψ >= 0 takes slot 0 (SCARA), else ψ <= 0 does
P_SLIDE = 2  # joint index of the slide across k, or -1
P_LIFT = 3  # joint index of the slide along k (SCARA), or -1
P_LIFT_SIGN = 4  # k · (that slide's direction): +1 or -1
P_NREV = 5  # number of revolute joints, 1 to 3
P_REV = 6  # (3,) their joint indices, base to tip
P_SIGN = 9  # (3,) k · (their axis direction): +1 or -1
P_K = 12  # (3,) the common axis direction k (unit, base frame)
P_E1 = 15  # (3,) plane basis e1 (unit, normal to k)
P_E2 = 18  # (3,) plane basis e2 = k × e1
P_ORIGIN = 21  # (3,) origin of the plane coordinates: on the first revolute axis (base frame, m)
P_TOOL = 24  # (3,) tool origin at q = 0 (base frame, m)
P_RE1 = 27  # (3,) R_Mᵀ e1 (M = fk(0): the tool pose at q = 0)
P_WRIST = 30  # (3,) the last revolute axis point in the tool frame at q = 0 (m)
P_AXIS = 33  # (3, 2) the revolute axis points at q = 0, plane coordinates (m)
P_TIP = 39  # (2,) the tool origin at q = 0, plane coordinates (m)
P_U = 41  # (2,) the slide direction across k, plane coordinates (unit)
P_REACH = 43  # sum of the in-plane link lengths (m): the scale of SINGULAR_TOL
P_RMIN = 44  # least distance of the tool origin from the first revolute axis (m)
P_RMAX = 45  # largest distance from that axis (or across the slide's line) (m)
P_QLIM = 46  # (4, 2) joint limits (rad or m; ±inf where there are none)
P_SLACK = 54  # how far the arm's revolute axes may put the tool from the ideal arm's (m)
P_SLIDE_TILT = 55  # |k · slide direction|: the slide's tilt out of the plane (sine)
P_LIFT_TILT = 56  # |k × lift direction|: the SCARA slide's tilt off k (sine)
P_LENGTH = 57  # sum of the distances between consecutive axes and to the tool (m)
P_SIZE = 58

_TWO_PI = 2.0 * math.pi

_TURNS = 1  # column of the first revolute turn in a branch row (column 0: the slide)


@kernel
def turn(ax: float, ay: float, bx: float, by: float) -> float:
    """The rotation (rad) that turns the direction of ``(ax, ay)`` onto ``(bx, by)``.

    0 when either vector is zero (``atan2(0, 0)``).
    """
    return math.atan2(ax * by - ay * bx, ax * bx + ay * by)


@kernel
def two_link(ax: float, ay: float, bx: float, by: float, tx: float, ty: float, out: Array) -> bool:
    """The 2R triangle: turns ``d1, d2`` with ``Rot(d1) (a + Rot(d2) b) = t``.

    Args:
        ax: Link 1 (first axis to second) at q = 0, plane x (m).
        ay: Its plane y (m).
        bx: Link 2 (second axis to the point) at q = 0, plane x (m).
        by: Its plane y (m).
        tx: Target of the point relative to the first axis, plane x (m).
        ty: Its plane y (m).
        out: ``(2, 2)`` out: rows for ψ <= 0 and ψ >= 0 (ψ the angle of link
            2 relative to link 1), columns ``d1, d2`` (rad, from q = 0). Out of
            reach both rows hold the triangle stretched (or folded) towards
            ``t``, its least-squares configuration.

    Returns:
        True on the fold continuum: ``t`` on the first axis with equal links
        (within ``SINGULAR_TOL`` of the reach), where every ``d1`` solves.
    """
    L1 = math.hypot(ax, ay)
    L2 = math.hypot(bx, by)
    r = math.hypot(tx, ty)
    far = L1 + L2
    near = abs(L1 - L2)
    S = (far - r) * (far + r)  # 4 L1 L2 sin²(ψ/2)
    C = (r - near) * (r + near)  # 4 L1 L2 cos²(ψ/2)
    if S <= 0.0:  # stretched (a double root) or beyond
        psi = 0.0
        vx = far
        vy = 0.0
    elif C <= 0.0:  # folded or inside the hole
        psi = math.pi
        vx = L1 - L2
        vy = 0.0
    else:  # r < L1 + L2 here: r * r cannot overflow
        sS = math.sqrt(S)
        sC = math.sqrt(C)
        psi = 2.0 * math.atan2(sS, sC)
        vx = (r * r + (L1 - L2) * far) / (2.0 * L1)  # the point in link 1's frame
        vy = sS * sC / (2.0 * L1)  # the triangle's height over link 1
    a0 = math.atan2(ay, ax)
    psi0 = turn(ax, ay, bx, by)
    for row in range(2):
        sg = -1.0 if row == 0 else 1.0
        out[row, 0] = turn(vx, sg * vy, tx, ty) - a0
        out[row, 1] = sg * psi - psi0
    tol = SINGULAR_TOL * far
    return r <= tol and near <= tol


@kernel
def _slide_link(
    ux: float, uy: float, bx: float, by: float, tx: float, ty: float, out: Array
) -> None:
    """A slide then a link: ``s, d`` with ``s u + Rot(d) b = t`` (``t`` from the axis at s = 0).

    ``out (2, 2)``: rows "link forward" (``s`` the smaller root: the link
    points along ``+u``) and "link backward"; columns ``s`` (m), ``d`` (rad).
    Beyond reach, both rows hold the link across the slide towards ``t``.
    """
    L = math.hypot(bx, by)
    along = tx * ux + ty * uy
    across = abs(ty * ux - tx * uy)
    root = math.sqrt((L - across) * (L + across)) if across < L else 0.0
    for row in range(2):
        s = along - root if row == 0 else along + root
        out[row, 0] = s
        out[row, 1] = turn(bx, by, tx - s * ux, ty - s * uy)


@kernel
def _gap(params: Array, x: float, y: float, dz: float) -> float:
    """Distance (m) from the target position to the reachable set of the tool origin.

    ``x, y``: plane coordinates of the target; ``dz``: its height over the plane.
    """
    ax = x - params[P_AXIS]
    ay = y - params[P_AXIS + 1]
    if params[P_SLIDE] >= 0.0:
        across = abs(ay * params[P_U] - ax * params[P_U + 1])
        radial = max(across - params[P_RMAX], 0.0)
    else:
        r = math.hypot(ax, ay)
        radial = max(r - params[P_RMAX], params[P_RMIN] - r, 0.0)
    height = 0.0 if params[P_LIFT] >= 0.0 else dz
    return math.hypot(height, radial)


@kernel
def _dot(params: Array, at: int, x: float, y: float, z: float) -> float:
    """``params[at:at + 3] · (x, y, z)``."""
    return params[at] * x + params[at + 1] * y + params[at + 2] * z


@kernel
def _rotated_dot(params: Array, at: int, T: Array, v: int) -> float:
    """``params[at:at + 3] · (R params[v:v + 3])`` with ``R`` the rotation of ``T``."""
    s = 0.0
    for i in range(3):
        s += params[at + i] * (
            T[i, 0] * params[v] + T[i, 1] * params[v + 1] + T[i, 2] * params[v + 2]
        )
    return s


@kernel
def _slot(params: Array, row: Array) -> int:
    """The branch slot of a single solution (pose targets of a 2R or PR arm).

    2R: the sign of link 2's angle relative to link 1 (as :func:`two_link`'s
    rows); PR: whether the link points along the slide.
    """
    if params[P_SLIDE] >= 0.0:
        bx = params[P_TIP] - params[P_AXIS]
        by = params[P_TIP + 1] - params[P_AXIS + 1]
        d = row[_TURNS]
        along = (math.cos(d) * bx - math.sin(d) * by) * params[P_U]
        along += (math.sin(d) * bx + math.cos(d) * by) * params[P_U + 1]
        return 0 if along >= 0.0 else 1
    ax = params[P_AXIS + 2] - params[P_AXIS]
    ay = params[P_AXIS + 3] - params[P_AXIS + 1]
    psi = turn(ax, ay, params[P_TIP] - params[P_AXIS + 2], params[P_TIP + 1] - params[P_AXIS + 3])
    below = math.sin(psi + row[_TURNS + 1]) <= 0.0
    return 0 if below != (params[P_SWAP] != 0.0) else 1


@kernel
def _count(params: Array, used: int) -> int:
    """Branches of the subproblem solved by the slide and ``used`` revolute joints: 1 or 2."""
    if params[P_SLIDE] >= 0.0:
        return 2 if used == 1 else 1
    return 2 if used == 2 else 1


@kernel
def _reach(
    params: Array,
    used: int,
    tx: float,
    ty: float,
    y0x: float,
    y0y: float,
    br: Array,
    tri: Array,
) -> bool:
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
        True on the fold continuum of a triangle (see :func:`two_link`).
    """
    ax = params[P_AXIS]
    ay = params[P_AXIS + 1]
    if params[P_SLIDE] < 0.0 and used == 2:
        fold = two_link(
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
            br[row, _TURNS] = tri[src, 0]
            br[row, _TURNS + 1] = tri[src, 1]
        return fold
    if params[P_SLIDE] >= 0.0 and used == 1:
        _slide_link(params[P_U], params[P_U + 1], y0x - ax, y0y - ay, tx - ax, ty - ay, tri)
        for row in range(2):
            br[row, 0] = tri[row, 0]
            br[row, _TURNS] = tri[row, 1]
    elif used == 1:  # one link
        br[0, _TURNS] = turn(y0x - ax, y0y - ay, tx - ax, ty - ay)
    else:  # the slide alone
        br[0, 0] = (tx - y0x) * params[P_U] + (ty - y0y) * params[P_U + 1]
    return False


@kernel
def _emit(
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
    count = _count(params, used)
    for row in range(count):
        if used < nrev:
            total = 0.0
            for j in range(used):
                total += br[row, _TURNS + j]
            br[row, _TURNS + last] = value - total if pose else value
        slot = row if count == 2 else _slot(params, br[row])
        q = Q[slot]
        if slide >= 0:
            q[slide] = br[row, 0]
        for j in range(nrev):
            q[int(params[P_REV + j])] = params[P_SIGN + j] * br[row, _TURNS + j]
        if lift >= 0:
            q[lift] = params[P_LIFT_SIGN] * dz


@kernel
def _inside(params: Array, q: Array) -> bool:
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
def _free_turn(place: Array, ell: float, below: bool) -> float:
    """The last joint's turn (rad) that makes the last two links span ``ℓ``.

    ``below``: the angle from link ``b`` to link ``c`` is <= 0 (else >= 0).
    """
    Lb = place[3]
    Lc = place[4]
    shortest = abs(Lb - Lc)
    longest = Lb + Lc
    S = max((longest - ell) * (longest + ell), 0.0)
    C = max((ell - shortest) * (ell + shortest), 0.0)
    psi = 2.0 * math.atan2(math.sqrt(S), math.sqrt(C))
    return (-psi if below else psi) - place[5]


@kernel
def _free_try(params: Array, place: Array, d: float, br: Array, tri: Array, Q: Array) -> bool:
    """Candidates with the free last joint turned by ``d``; True on a fold continuum."""
    last = int(params[P_NREV]) - 1
    lx = params[P_AXIS + 2 * last]
    ly = params[P_AXIS + 2 * last + 1]
    cx = params[P_TIP] - lx
    cy = params[P_TIP + 1] - ly
    c = math.cos(d)
    s = math.sin(d)
    fold = _reach(
        params, last, place[0], place[1], lx + c * cx - s * cy, ly + s * cx + c * cy, br, tri
    )
    _emit(params, br, last, d, False, place[2], Q)
    return fold


@kernel
def _free_last(
    params: Array, x: float, y: float, dz: float, br: Array, tri: Array, Q: Array, info: Array
) -> bool:
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
        True on the fold continuum of the remaining triangle.
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
    place = np.empty(6)  # the target, its height, the last two links, and their angle
    place[0] = x
    place[1] = y
    place[2] = dz
    place[3] = Lb
    place[4] = Lc
    place[5] = turn(bx, by, cx, cy)
    if wholly:  # the other joints do not depend on it
        return _free_try(params, place, _window_rep(params, jl) * params[P_SIGN + last], br, tri, Q)
    if a > z:  # out of reach: the nearest length
        return _free_try(
            params, place, _free_turn(place, min(max(a, shortest), longest), False), br, tri, Q
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
            fold = _free_try(params, place, _free_turn(place, ell, side == 1), br, tri, Q)
            if _inside(params, Q[0]) or _inside(params, Q[1]):
                return fold
    return _free_try(params, place, _free_turn(place, 0.5 * (a + z), False), br, tri, Q)


@kernel
def solve(params: Array, T: Array, Q: Array, info: Array) -> None:
    """Candidates of one target of a planar arm or a SCARA (see the module docstring).

    Args:
        params: ``(P_SIZE,)`` the arm (``P_*``).
        T: ``(4, 4)`` target pose of the tool (base frame); for position
            targets only its translation is read.
        Q: ``(2, n)`` out: candidates, slot 0 and 1 the two branches (labels
            in the builder); NaN rows where a branch has no candidate.
        info: ``(INFO_FREE + n,)`` out (zero on entry): ``INFO_SINGULAR`` and
            the free joints on a continuum, ``INFO_GAP``.
    """
    Q[:, :] = np.nan
    br = np.zeros((2, 4))  # a subproblem's branches: slide (m), then revolute turns (rad)
    tri = np.empty((2, 2))
    pose = params[P_POSE] != 0.0
    nrev = int(params[P_NREV])
    last = nrev - 1
    ox = T[0, 3] - params[P_ORIGIN]
    oy = T[1, 3] - params[P_ORIGIN + 1]
    oz = T[2, 3] - params[P_ORIGIN + 2]
    x = _dot(params, P_E1, ox, oy, oz)
    y = _dot(params, P_E2, ox, oy, oz)
    dz = _dot(
        params,
        P_K,
        T[0, 3] - params[P_TOOL],
        T[1, 3] - params[P_TOOL + 1],
        T[2, 3] - params[P_TOOL + 2],
    )
    # The arm's axes are parallel (or normal) to k within the classification's
    # tolerance: the ideal arm solved here may put the tool up to `slack` away
    # from the real one. Beyond round-off, a gap shrinks by it and a miss is no proof.
    slack = params[P_SLACK] + params[P_SLIDE_TILT] * (
        math.hypot(math.hypot(ox, oy), oz) + params[P_LENGTH]
    )
    slack += params[P_LIFT_TILT] * (abs(dz) + params[P_LENGTH])
    gap = _gap(params, x, y, dz)
    if slack > SINGULAR_TOL * params[P_REACH]:
        info[INFO_NEAR] = 1.0
        gap -= slack
    info[INFO_GAP] = gap if gap > SINGULAR_TOL * params[P_REACH] else np.nan  # beyond round-off
    if pose:  # the orientation: the total turn, and where the last revolute axis goes
        phi = math.atan2(_rotated_dot(params, P_E2, T, P_RE1), _rotated_dot(params, P_E1, T, P_RE1))
        for i in range(3):
            w = T[i, 0] * params[P_WRIST] + T[i, 1] * params[P_WRIST + 1]
            w += T[i, 2] * params[P_WRIST + 2]
            if i == 0:
                ox += w
            elif i == 1:
                oy += w
            else:
                oz += w
        fold = _reach(
            params,
            last,
            _dot(params, P_E1, ox, oy, oz),
            _dot(params, P_E2, ox, oy, oz),
            params[P_AXIS + 2 * last],
            params[P_AXIS + 2 * last + 1],
            br,
            tri,
        )
        _emit(params, br, last, phi, True, dz, Q)
        if fold:  # the last joint turns with the first
            info[INFO_FREE + int(params[P_REV + last])] = 1.0
    elif nrev + (1 if params[P_SLIDE] >= 0.0 else 0) == 3:
        fold = _free_last(params, x, y, dz, br, tri, Q, info)
    else:
        fold = _reach(params, nrev, x, y, params[P_TIP], params[P_TIP + 1], br, tri)
        _emit(params, br, nrev, 0.0, False, dz, Q)
    if fold:
        info[INFO_SINGULAR] = 1.0
        info[INFO_FREE + int(params[P_REV])] = 1.0
    if info[INFO_NEAR] != 0.0:
        _snap_slides(params, Q, slack)


@kernel
def _snap_slides(params: Array, Q: Array, slack: float) -> None:
    """Slides that the ideal arm puts beyond a limit by less than ``slack`` (m) go onto it.

    The real arm's slide is uncertain by that much; the check judges the result.
    """
    for j in (int(params[P_SLIDE]), int(params[P_LIFT])):
        if j < 0:
            continue
        lo = params[P_QLIM + 2 * j]
        hi = params[P_QLIM + 2 * j + 1]
        for row in range(Q.shape[0]):
            v = Q[row, j]
            if lo - slack <= v < lo:
                Q[row, j] = lo
            elif hi < v <= hi + slack:
                Q[row, j] = hi


@batch_kernel
def solve_batch(params: Array, T: Array, Q: Array, info: Array) -> None:
    """:func:`solve` for targets ``T (N, 4, 4)`` in parallel; ``Q``, ``info`` gain an ``N`` axis."""
    for i in numba.prange(T.shape[0]):
        solve(params, T[i], Q[i], info[i])
