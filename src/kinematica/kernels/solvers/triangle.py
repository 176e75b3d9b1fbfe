"""Planar subproblems inside kernels: the 2R triangle, and a slide then a link.

Points are written in plane coordinates (x, y) on a basis ``e1``, ``e2 = k × e1``
of the plane normal to the joints' common axis direction ``k``; a turn by
``d`` is counter-clockwise seen from the side ``k`` points to. The triangle is
solved by half-angle formulas that keep their accuracy at the folds:
``4 L1 L2 sin²(ψ/2) = (L1 + L2 − r)(L1 + L2 + r)`` and
``4 L1 L2 cos²(ψ/2) = (r − |L1 − L2|)(r + |L1 − L2|)``, so that a target 1e-9 m
from the first axis of a folded triangle with equal links keeps both
solutions, and no quantity that grows with the target is squared. Out of
reach both give their least-squares configuration (stretched or folded
towards the target; the link across the slide).
"""

from __future__ import annotations

import math

from kinematica.kernels._numba import Array, kernel

__all__ = ["FOLD", "MERGE_TOL", "NEAR", "REGULAR", "SINGULAR_TOL", "slide_link", "turn", "two_link"]

#: Round-off of the small arms' geometry, relative to the arm's reach. A target
#: this close to the first axis of a folded triangle whose links differ by at
#: most as much is on the fold: every turn of the first joint reaches it. The
#: same measure tells a free last joint (a range of its turns reaches the
#: target) from an isolated solution, and a gap from round-off (a smaller
#: one is not reported).
SINGULAR_TOL = 1e-12
#: Two branches whose angles are within twice this (rad) of each other are
#: merging: as close as the check's ``DEDUP_TOL``, where round-off of the
#: target moves them by as much, and both may be given as one. The same
#: relative distance from the first axis makes the first turn that uncertain.
MERGE_TOL = 1e-7

# What :func:`two_link` says of a target.
REGULAR, NEAR, FOLD = 0, 1, 2


@kernel
def turn(ax: float, ay: float, bx: float, by: float) -> float:
    """The rotation (rad) that turns the direction of ``(ax, ay)`` onto ``(bx, by)``.

    0 when either vector is zero (``atan2(0, 0)``).
    """
    return math.atan2(ax * by - ay * bx, ax * bx + ay * by)


@kernel
def two_link(ax: float, ay: float, bx: float, by: float, tx: float, ty: float, out: Array) -> int:
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
        ``FOLD`` on the fold continuum: ``t`` on the first axis with equal
        links (within ``SINGULAR_TOL`` of the reach), where every ``d1``
        solves; ``NEAR`` when the branches merge (ψ within ``MERGE_TOL`` of 0
        or π, at or beyond the reach's edges) or ``t`` is within
        ``MERGE_TOL`` of the reach from the first axis; else ``REGULAR``.
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
    if r <= tol and near <= tol:
        return FOLD
    merge = MERGE_TOL * MERGE_TOL * L1 * L2  # 4 L1 L2 sin²(MERGE_TOL / 2)
    return NEAR if min(S, C) < merge or r < MERGE_TOL * far else REGULAR


@kernel
def slide_link(
    ux: float, uy: float, bx: float, by: float, tx: float, ty: float, out: Array
) -> bool:
    """A slide then a link: ``s, d`` with ``s u + Rot(d) b = t`` (``t`` from the axis at s = 0).

    ``out (2, 2)``: rows "link forward" (``s`` the smaller root: the link
    points along ``+u``) and "link backward"; columns ``s`` (m), ``d`` (rad).
    Beyond reach, both rows hold the link across the slide towards ``t``.

    Returns:
        True when the branches merge: the link within ``MERGE_TOL`` of across
        the slide (or beyond reach).
    """
    L = math.hypot(bx, by)
    along = tx * ux + ty * uy
    across = abs(ty * ux - tx * uy)
    root = math.sqrt((L - across) * (L + across)) if across < L else 0.0
    for row in range(2):
        s = along - root if row == 0 else along + root
        out[row, 0] = s
        out[row, 1] = turn(bx, by, tx - s * ux, ty - s * uy)
    return root < MERGE_TOL * L
