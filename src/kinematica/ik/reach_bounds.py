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

A target is dropped only where a circle's range of distance or height misses its range
by more than the slack of the IK's acceptance tolerance (``P + R w``: an accepted
solution moves a point ``w`` from the tool frame's origin by at most that) and
:data:`ROUNDOFF_SLACK`. Joint limits are not used: the condition is necessary for a
solution anywhere, so within the limits too.

The ranges over three joints: exact over the joint nearest ``S`` (a circle's range of
distance from a point), sampled on a periodic ``GRID x GRID`` grid over the other two,
widened by a bound of the error: an extremum over the torus is a critical point, so a
grid point is within ``½ C |δ|²`` of it (``C`` bounds the Hessian, from the distances
of the point from the axes bounded by triangle inequalities, ``|δ|² ≤ 2 (h/2)²``).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.core import Chain
from kinematica.ik.structure import features
from kinematica.ik.tolerance import Tolerance

__all__ = ["GRID", "ROUNDOFF_SLACK", "ReachBounds", "may_reach", "reach_bounds", "violation"]

FloatArray = NDArray[np.float64]

#: Added to every slack (m): round-off of the moved targets, circles and ranges
#: (products of unit vectors and lengths under 10 m: about 1e-15 relative).
ROUNDOFF_SLACK = 1e-9
#: Samples per joint of the grid over two joints (the ranges' margin shrinks as 1/GRID²).
GRID = 256


@dataclass(frozen=True, slots=True, eq=False)
class ReachBounds:
    """What a 6R arm's middle joints keep, and the points that show it (made once per arm).

    Attributes:
        a6: ``(3,)`` axis 6's direction in the tool frame.
        p6: ``(3,)`` a point on axis 6 in the tool frame.
        x: ``(3,)`` the point on axis 5 at q6 = 0, in the tool frame.
        shoulder: ``(3,)`` the point S on axis 1 (base frame).
        a1: ``(3,)`` axis 1's direction (base frame).
        reach: ``(2,)`` the range of ``|x - S|`` (m), margin included.
        height: ``(2,)`` the range of ``(x - S)·a1`` (m).
        x_radius: The farthest a point of x's circle is from the tool frame's origin (m).
        circle: ``(3, 3)`` the circle of the point on axis 2 about axis 1: its centre and
            two orthogonal radius vectors (base frame).
        z: ``(3,)`` the point Z on axis 6 (tool frame).
        reach2: ``(2,)`` the range of ``|y - Z|`` (m), y on axis 2.
        height2: ``(2,)`` the range of ``(y - Z)·a6`` (m).
    """

    a6: FloatArray
    p6: FloatArray
    x: FloatArray
    shoulder: FloatArray
    a1: FloatArray
    reach: FloatArray
    height: FloatArray
    x_radius: float
    circle: FloatArray
    z: FloatArray
    reach2: FloatArray
    height2: FloatArray


def reach_bounds(arm: Chain) -> ReachBounds | None:
    """The arm's :class:`ReachBounds`, made once and kept; None unless it has 6 revolute joints."""
    found = arm.memo.get("reach bounds", False)
    if found is False:
        found = arm.memo["reach bounds"] = _made(arm)
    return found  # type: ignore[return-value]


def violation(bounds: ReachBounds, poses: FloatArray, tol: Tolerance) -> FloatArray:
    """``(M,)`` how far (m) each target misses the conditions beyond the tolerance's slack.

    Positive: no solution within ``tol`` reaches target i (by more than the round-off
    :func:`may_reach` allows); NaN where a target is not finite.

    Args:
        bounds: The arm's.
        poses: ``(M, 4, 4)`` targets of the arm (its tool frame, base frame).
        tol: The acceptance tolerance of its solutions.
    """
    R, t = poses[:, :3, :3], poses[:, :3, 3]
    P, turn = tol.position, tol.rotation
    a6 = R @ bounds.a6
    # forward: x's circle about axis 6 against S on axis 1
    p6 = R @ bounds.p6 + t
    x = R @ bounds.x + t
    c = p6 + ((x - p6) * a6).sum(-1)[:, None] * a6
    u = x - c
    v = np.cross(a6, u)
    slack = P + turn * bounds.x_radius
    out = _gaps(c - bounds.shoulder, u, v, bounds.reach, slack)
    out = np.maximum(out, _heights(c - bounds.shoulder, u, v, bounds.a1, bounds.height, slack))
    # reverse: y's circle about axis 1 against Z on axis 6
    z = R @ bounds.z + t
    centre, u2, v2 = bounds.circle
    slack = P + turn * float(np.linalg.norm(bounds.z))
    cz = centre - z
    n = cz.shape[0]
    U, V = np.broadcast_to(u2, (n, 3)), np.broadcast_to(v2, (n, 3))
    out = np.maximum(out, _gaps(cz, U, V, bounds.reach2, slack))
    lean = slack + turn * float(bounds.reach2[1])  # a6 turned by at most R
    return np.maximum(out, _heights(cz, U, V, a6, bounds.height2, lean))


def may_reach(bounds: ReachBounds, poses: FloatArray, tol: Tolerance) -> NDArray[np.bool_]:
    """``(M,)`` False only where target i is proved out of reach (:func:`violation`)."""
    return ~(violation(bounds, poses, tol) > ROUNDOFF_SLACK)


def _gaps(
    cs: FloatArray, u: FloatArray, v: FloatArray, span: FloatArray, slack: float
) -> FloatArray:
    """``(M,)`` how far the circles' distances from the origin miss ``span``, less ``slack``.

    Circle i: ``cs_i + u_i cos θ + v_i sin θ``.
    """
    mid = (cs * cs).sum(-1) + (u * u).sum(-1)
    swing = 2.0 * np.hypot((cs * u).sum(-1), (cs * v).sum(-1))
    near = np.sqrt(np.maximum(mid - swing, 0.0))
    far = np.sqrt(mid + swing)
    return np.maximum(near - span[1], span[0] - far) - slack


def _heights(
    cs: FloatArray, u: FloatArray, v: FloatArray, axis: FloatArray, span: FloatArray, slack: float
) -> FloatArray:
    """``(M,)`` how far the heights along ``axis`` of the circles miss ``span``, less ``slack``."""
    ax = np.broadcast_to(axis, cs.shape)
    mid = (cs * ax).sum(-1)
    swing = np.hypot((u * ax).sum(-1), (v * ax).sum(-1))
    return np.maximum(mid - swing - span[1], span[0] - mid - swing) - slack


# ---------------------------------------------------------------- made once per arm
def _made(arm: Chain) -> ReachBounds | None:
    if arm.dof != 6 or bool(np.asarray(arm.prismatic).any()):
        return None
    f = features(arm)
    P, A = np.asarray(f.points, dtype=float), np.asarray(f.directions, dtype=float)
    F = np.asarray(arm.fk(np.zeros(6))[0], dtype=float)
    Rt, t = F[:3, :3].T, F[:3, 3]

    def tool(point: FloatArray) -> FloatArray:  # a base-frame point at q = 0, in the tool frame
        return np.asarray(Rt @ (point - t))

    S, x0, reach, height = _ranges(P, A, 0, 4, (1, 2, 3))
    Z, y0, reach2, height2 = _ranges(P, A, 5, 1, (4, 3, 2))
    a6, p6, x = Rt @ A[5], tool(P[5]), tool(x0)
    c = p6 + ((x - p6) @ a6) * a6
    centre = P[0] + ((y0 - P[0]) @ A[0]) * A[0]
    u = y0 - centre
    circle = np.array([centre, u, np.cross(A[0], u)])
    x_radius = float(np.linalg.norm(c) + np.linalg.norm(x - c))
    return ReachBounds(a6, p6, x, S, A[0].copy(), reach, height, x_radius, circle, tool(Z),
                       reach2, height2)  # fmt: skip


def _foot(p1: FloatArray, a1: FloatArray, p2: FloatArray, a2: FloatArray) -> FloatArray:
    """The point of line 1 nearest line 2 (of a parallel pair: p2 projected on line 1)."""
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


def _ranges(
    P: FloatArray, A: FloatArray, s: int, m: int, mids: tuple[int, int, int]
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """S on axis s, x on axis m, and the ranges of ``|x - S|`` and ``(x - S)·a_s``.

    Over the joints ``mids`` (nearest S first): x's position is
    ``exp(j1) exp(j2) exp(j3) x₀``, the axes at q = 0 (``P``, ``A``: points, directions).
    """
    j1, j2, j3 = mids
    S = _foot(P[s], A[s], P[j1], A[j1])
    x0 = _foot(P[m], A[m], P[j3], A[j3])
    t = np.linspace(-math.pi, math.pi, GRID, endpoint=False)
    y = _turn(A[j3], t) @ (x0 - P[j3]) + P[j3]  # (G, 3)
    y = np.einsum("aij,bj->abi", _turn(A[j2], t), y - P[j2]) + P[j2]  # (G, G, 3)
    c = P[j1] + ((y - P[j1]) @ A[j1])[..., None] * A[j1]  # circles about axis j1
    u = y - c
    v = np.cross(A[j1], u)
    cs = c - S
    mid = (cs * cs).sum(-1) + (u * u).sum(-1)
    swing = 2.0 * np.hypot((cs * u).sum(-1), (cs * v).sum(-1))
    hmid, hswing = cs @ A[s], np.hypot(u @ A[s], v @ A[s])
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
    step = 2.0 * (math.pi / GRID) ** 2  # |δ|² at most, two coordinates half a step off
    wide = 0.5 * C * step
    lo, hi = float((mid - swing).min()) - wide, float((mid + swing).max()) + wide
    reach = np.array([math.sqrt(max(lo, 0.0)), math.sqrt(hi)])
    hw = 0.5 * Ch * step
    height = np.array([float((hmid - hswing).min()) - hw, float((hmid + hswing).max()) + hw])
    return S, x0, reach, height
