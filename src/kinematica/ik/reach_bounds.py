"""Targets a 6R arm cannot reach, proved: bounds of distances its middle joints keep.

``auto`` on a 7R arm holds its first or last joint and screens the values of a sweep
with the 6R arm left (:mod:`kinematica.ik.redundancy`), one elimination a value. Most
values without a solution fail a necessary condition of two points, each fixed on an
axis, checked here in a few flops a value:

* **forward**: a point ``x`` on axis 5 (where the common normal of axes 4 and 5 meets
  it) and a point ``S`` on axis 1 (likewise with axis 2). The target fixes the last
  link, so axis 6; ``x`` is fixed to axis 6's link but for the turn q6 about it, so it
  lies on a known circle. Seen from axis 1, ``|x - S|`` and the height
  ``(x - S)·a₁`` depend on q2, q3, q4 alone, within ranges found once per arm.
* **reverse**: the same from the tool's side: a point on axis 2 (on a fixed circle
  about axis 1) and a point on axis 6 (fixed by the target), joints q3, q4, q5.

The forward circle's distance and height are also asked together: the angles q6 of x's
circle (within its arc) where the distance is in its range, and those where the height is
in its range, are arcs (``A + B cos q6 + C sin q6`` within bounds); where each range is
met alone but no q6 meets both, the target misses by the least widening of both ranges
that makes one q6 meet them (bisected, its lower end kept: ``km::reach::together_gap``).

A target is dropped only where a circle's range of distance or height misses its range
by more than the slack of the IK's acceptance tolerance (``P + R w``: an accepted
solution moves a point ``w`` from the tool frame's origin by at most that) and
:data:`ROUNDOFF_SLACK`. Where solutions are held to the joint limits, the circles are
arcs: x's over q6's limits, y's over q1's, and the ranges are over the limits of q2 to
q5 (each widened by the check's ``LIMIT_TOL``; the check takes an angle or its turn ±2π,
and so does a limit spanning less than a turn here).

The ranges over three joints: exact over the joint nearest ``S`` (a circle's or an arc's
range of distance from a point), sampled on a ``GRID x GRID`` grid over the other two
(a whole turn, or the limits with their ends), widened by a bound of the error: an
extremum is a critical point along every joint not at a limit, so a grid point is within
``½ C |δ|²`` of it (``C`` bounds the Hessian, from the distances of the point from the
axes bounded by triangle inequalities; ``|δ|² ≤ (h₂/2)² + (h₃/2)²``, ``h`` the steps).
Which way each joint turns its link is read from FK.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
from numpy.typing import NDArray

from kinematica import _core
from kinematica.core import Chain
from kinematica.ik.structure import features
from kinematica.ik.tolerance import Tolerance

__all__ = ["GRID", "ROUNDOFF_SLACK", "may_reach", "reach_bounds", "violation"]

FloatArray = NDArray[np.float64]

_ZERO = np.zeros(1)
_ZERO.flags.writeable = False
_STILL = (np.stack([np.eye(4), np.zeros((4, 4)), np.zeros((4, 4))]), False)  # M(v) = I
_STILL[0].flags.writeable = False

#: Added to every slack (m): round-off of the moved targets, circles and ranges
#: (products of unit vectors and lengths under 10 m: about 1e-15 relative).
ROUNDOFF_SLACK = 1e-9
#: Samples per joint of the grid over two joints (the ranges' margin shrinks as 1/GRID²).
GRID = 256


def reach_bounds(arm: Chain, limits: bool = True) -> FloatArray | None:
    """The arm's bounds, made once and kept; None unless it has 6 revolute joints.

    Args:
        arm: The 6R arm.
        limits: Bounds of solutions within the joint limits (else anywhere).

    Returns:
        ``(43,)`` read-only, laid out as ``km::reach::Slot`` says
        (``cpp/include/kinematica/reach_bounds.hpp``): axis 6's direction (tool frame);
        x's circle ``c + u cos q6 + v sin q6`` (tool frame); S and axis 1's direction
        (base frame); the ranges of ``|x - S|`` and ``(x - S)·a₁``; the farthest point of
        x's circle from the tool frame's origin; q6's limits; y's circle
        ``c + u cos q1 + v sin q1`` (base frame); q1's limits; Z (tool frame); the
        ranges of ``|y - Z|`` and ``(y - Z)·a₆``.
    """
    key = ("reach bounds", limits)
    found = arm.memo.get(key, False)
    if found is False:
        found = arm.memo[key] = _made(arm, limits)
    return found  # type: ignore[return-value]


def violation(
    bounds: FloatArray,
    poses: FloatArray,
    tol: Tolerance,
    values: FloatArray = _ZERO,
    move: tuple[FloatArray, bool] = _STILL,
    limits: bool = True,
) -> FloatArray:
    """``(t, G)`` how far (m) target i moved by ``values[j]`` misses the bounds beyond the slack.

    Positive: no solution within ``tol`` reaches it (by more than the round-off
    :func:`may_reach` allows); NaN where a target is not finite.

    Args:
        bounds: The arm's (:func:`reach_bounds`).
        poses: ``(t, 4, 4)`` targets.
        tol: The acceptance tolerance of the arm's solutions.
        values: ``(G,)`` the held joint's values (rad); by default one, 0.
        move: ``(A, after)``: the move of a held first or last (``after``) joint, its
            parts ``A`` ``(3, 4, 4)`` (:func:`kinematica.ik.moved.move_parts`): target i at
            value v is ``M(v) T``, or ``T M(v)`` after; by default none (``M = I``).
        limits: Whether solutions are held to the joint limits (q1's and q6's, here).
    """
    parts, after = move
    poses = np.ascontiguousarray(poses, dtype=float)
    values = np.ascontiguousarray(values, dtype=float)
    return _core.reach_violation(bounds, poses, values, parts, after, False, tol.position,
                                 tol.rotation, limits)  # fmt: skip


def may_reach(
    bounds: FloatArray,
    poses: FloatArray,
    tol: Tolerance,
    values: FloatArray = _ZERO,
    move: tuple[FloatArray, bool] = _STILL,
    limits: bool = True,
) -> NDArray[np.bool_]:
    """``(t, G)`` False only where target i at ``values[j]`` is proved out of reach.

    :func:`violation` above :data:`ROUNDOFF_SLACK`; its arguments.
    """
    return ~(violation(bounds, poses, tol, values, move, limits) > ROUNDOFF_SLACK)


# ---------------------------------------------------------------- made once per arm
def _made(arm: Chain, limits: bool) -> FloatArray | None:
    if arm.dof != 6 or bool(np.asarray(arm.prismatic).any()):
        return None
    f = features(arm)
    P, A = np.asarray(f.points, dtype=float), np.asarray(f.directions, dtype=float)
    F = np.asarray(arm.fk(np.zeros(6))[0], dtype=float)
    Rt, t = F[:3, :3].T, F[:3, 3]

    def tool(point: FloatArray) -> FloatArray:  # a base-frame point at q = 0, in the tool frame
        return np.asarray(Rt @ (point - t))

    # each joint's limits as angles t of the turns the ranges take (None: a whole turn)
    boxes: list[tuple[float, float] | None] = [None] * 6
    if limits:
        wider = np.asarray(arm.qlim, dtype=float) + np.array([-_core.LIMIT_TOL, _core.LIMIT_TOL])
        boxes = [None if hi - lo >= 2.0 * math.pi else (lo, hi) for lo, hi in wider.tolist()]
    sign = _signs(arm, P, A)
    if sign is None:
        return None
    # forward: x = exp(q2) exp(q3) exp(q4) x₀, turns by t = sign q; reverse: y seen from
    # link 5, exp(-q5) exp(-q4) exp(-q3) y₀, turns by t = -sign q
    S, x0, reach, height = _ranges(
        P, A, 0, 4, (1, 2, 3), [_box(boxes[j], sign[j]) for j in (1, 2, 3)]
    )
    Z, y0, reach2, height2 = _ranges(
        P, A, 5, 1, (4, 3, 2), [_box(boxes[j], -sign[j]) for j in (4, 3, 2)]
    )
    # x (fixed to link 5) in the tool frame at q6 = 0 and π/2, the other joints at 0; y
    # (fixed to link 1) at q1 = 0 and π/2: each circle as its joint turns it
    turned = np.zeros((3, 6))
    turned[1, 5] = turned[2, 0] = 0.5 * math.pi  # q6, then q1 turned
    frames = np.asarray(arm.fk(turned, all_frames=True)[0], dtype=float)  # (3, 7, 4, 4)
    tools = frames[:2, -1]
    xs = np.einsum("kji,kj->ki", tools[:, :3, :3], x0 - tools[:, :3, 3])
    a6, p6 = Rt @ A[5], tool(P[5])
    xc = p6 + ((xs[0] - p6) @ a6) * a6
    first = frames[0::2, 1]
    y_local = first[0, :3, :3].T @ (y0 - first[0, :3, 3])
    y_half = first[1, :3, :3] @ y_local + first[1, :3, 3]
    yc = P[0] + ((y0 - P[0]) @ A[0]) * A[0]
    lim = np.asarray(arm.qlim, dtype=float)
    widen = np.array([-_core.LIMIT_TOL, _core.LIMIT_TOL])
    x_radius = float(np.linalg.norm(xc) + np.linalg.norm(xs[0] - xc))
    flat = np.concatenate([a6, xc, xs[0] - xc, xs[1] - xc, S, A[0], reach, height, [x_radius],
                           lim[5] + widen, yc, y0 - yc, y_half - yc, lim[0] + widen, tool(Z),
                           reach2, height2])  # fmt: skip
    flat.flags.writeable = False
    return flat


def _foot(p1: FloatArray, a1: FloatArray, p2: FloatArray, a2: FloatArray) -> FloatArray:
    """The point of line 1 nearest line 2 (of a parallel pair: p2 projected on line 1).

    Any point of the line keeps the bounds true; this one keeps them tight.
    """
    w = p1 - p2
    b, d, e = a1 @ a2, a1 @ w, a2 @ w
    den = 1.0 - b * b
    s = (b * e - d) / den if den > 1e-12 else -d
    return np.asarray(p1 + s * a1)


def _turn(a: FloatArray, t: FloatArray) -> FloatArray:
    """``(n, 3, 3)`` rotations about the unit vector ``a`` by the angles ``t``."""
    K = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
    s, c = np.sin(t)[:, None, None], np.cos(t)[:, None, None]
    return np.asarray(np.eye(3) + s * K + (1.0 - c) * (K @ K))


def _signs(arm: Chain, P: FloatArray, A: FloatArray) -> FloatArray | None:
    """``(6,)`` ±1: joint j turns its link about ``A[j]`` by ±q (from FK); None if neither."""
    q = 0.3 * np.eye(6)
    frames = np.asarray(arm.fk(np.vstack([np.zeros(6), q]), all_frames=True)[0], dtype=float)
    out = np.ones(6)
    for j in range(6):
        e = np.cross(A[j], [1.0, 0.0, 0.0] if abs(A[j][0]) < 0.9 else [0.0, 1.0, 0.0])
        p = P[j] + e / np.linalg.norm(e)  # a point of link j off its axis, at q = 0
        F0, F = frames[0, j + 1], frames[j + 1, j + 1]
        moved = F[:3, :3] @ (F0[:3, :3].T @ (p - F0[:3, 3])) + F[:3, 3]
        turned = _turn(A[j], np.array([0.3, -0.3])) @ (p - P[j]) + P[j]
        off = np.linalg.norm(turned - moved, axis=1)
        if not off.min() < 1e-9:
            return None
        out[j] = 1.0 if off[0] < off[1] else -1.0
    return out


def _box(limits: tuple[float, float] | None, sign: float) -> tuple[float, float] | None:
    """The turns ``t`` with ``sign t`` within ``limits`` (None: a whole turn)."""
    if limits is None:
        return None
    lo, hi = sorted((sign * limits[0], sign * limits[1]))
    return lo, hi


def _arc(
    A: FloatArray, B: FloatArray, C: FloatArray, box: tuple[float, float] | None
) -> tuple[FloatArray, FloatArray]:
    """The least and greatest of ``A + B cos t + C sin t`` over ``t`` in ``box`` (None: all)."""
    rho = np.hypot(B, C)
    least, most = A - rho, A + rho
    if box is None:
        return least, most
    lo, hi = box
    ends = [A + B * math.cos(t) + C * math.sin(t) for t in (lo, hi)]
    top = np.arctan2(C, B)  # where the greatest is, the least half a turn on

    def inside(t: FloatArray) -> NDArray[np.bool_]:
        return np.mod(t - lo, 2.0 * math.pi) <= hi - lo

    most = np.where(inside(top), most, np.maximum(*ends))
    least = np.where(inside(top + math.pi), least, np.minimum(*ends))
    return least, most


def _grid(box: tuple[float, float] | None) -> tuple[FloatArray, float]:
    """The grid's angles over ``box`` (ends included) or a whole turn, and its step."""
    if box is None:
        return np.linspace(-math.pi, math.pi, GRID, endpoint=False), 2.0 * math.pi / GRID
    return np.linspace(box[0], box[1], GRID), (box[1] - box[0]) / (GRID - 1)


def _ranges(
    P: FloatArray,
    A: FloatArray,
    s: int,
    m: int,
    mids: tuple[int, int, int],
    boxes: list[tuple[float, float] | None],
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """S on axis s, x on axis m, and the ranges of ``|x - S|`` and ``(x - S)·a_s``.

    Over the joints ``mids`` (nearest S first): x's position is
    ``exp(t1) exp(t2) exp(t3) x₀``, turns about the axes at q = 0 (``P``, ``A``:
    points, directions), each ``t`` within its box (None: a whole turn). The grid holds
    the boxes' ends: an extremum at a box's face has a zero derivative along the
    others (a box is a product of intervals), so the ``½ C |δ|²`` bound holds there too.
    """
    j1, j2, j3 = mids
    S = _foot(P[s], A[s], P[j1], A[j1])
    x0 = _foot(P[m], A[m], P[j3], A[j3])
    t2, h2 = _grid(boxes[1])
    t3, h3 = _grid(boxes[2])
    y = _turn(A[j3], t3) @ (x0 - P[j3]) + P[j3]  # (G, 3)
    y = np.einsum("aij,bj->abi", _turn(A[j2], t2), y - P[j2]) + P[j2]  # (G, G, 3)
    c = P[j1] + ((y - P[j1]) @ A[j1])[..., None] * A[j1]  # circles about axis j1
    u = y - c
    v = np.cross(A[j1], u)
    cs = c - S
    g_lo, g_hi = _arc((cs * cs).sum(-1) + (u * u).sum(-1), 2.0 * (cs * u).sum(-1),
                      2.0 * (cs * v).sum(-1), boxes[0])  # fmt: skip
    h_lo, h_hi = _arc(cs @ A[s], u @ A[s], v @ A[s], boxes[0])
    # the distances of x from S and from the axes j1, j2, j3, bounded by triangle
    # inequalities along points each two of which are fixed in one link
    feet = [S, _foot(P[j1], A[j1], P[j2], A[j2]), _foot(P[j2], A[j2], P[j3], A[j3]),
            _foot(P[j3], A[j3], P[m], A[m]), x0]  # fmt: skip
    hops = [float(np.linalg.norm(b - a)) for a, b in itertools.pairwise(feet)]
    D = sum(hops)
    rho = [sum(hops[1:]), sum(hops[2:]), hops[3]]
    C = 2.0 * math.sqrt(sum((rho[i] * rho[k] + D * max(rho[i], rho[k])) ** 2
                            for i in range(3) for k in range(3)))  # fmt: skip
    Ch = math.sqrt(sum(max(rho[i], rho[k]) ** 2 for i in range(3) for k in range(3)))
    step = (0.5 * h2) ** 2 + (0.5 * h3) ** 2  # |δ|² at most: two coordinates half a step off
    wide = 0.5 * C * step
    lo, hi = float(g_lo.min()) - wide, float(g_hi.max()) + wide
    reach = np.array([math.sqrt(max(lo, 0.0)), math.sqrt(hi)])
    hw = 0.5 * Ch * step
    height = np.array([float(h_lo.min()) - hw, float(h_hi.max()) + hw])
    return S, x0, reach, height
