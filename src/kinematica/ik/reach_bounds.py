"""Targets a 6R arm cannot reach, proved: bounds of distances its middle joints keep.

``auto`` on a 7R arm holds its first or last joint and screens the values of a sweep
with the 6R arm left (:mod:`kinematica.ik.redundancy`), one elimination a value. Most
values without a solution fail a necessary condition of two points, each fixed on an
axis, checked in the core in a few flops a value:

* **forward**: a point ``x`` on axis 5 (where the common normal of axes 4 and 5 meets
  it) and a point ``S`` on axis 1 (likewise with axis 2). The target fixes the last
  link, so axis 6; ``x`` is fixed to axis 6's link but for the turn q6 about it, so it
  lies on a known circle. Seen from axis 1, ``|x - S|`` and the height
  ``(x - S)·a₁`` depend on q2, q3, q4 alone, within ranges found once per arm.
* **reverse**: the same from the tool's side: a point on axis 2 (on a fixed circle about
  axis 1) and a point on axis 6 (fixed by the target), joints q3, q4, q5.

A target is dropped only where a circle's range of distance or height misses its range
by more than the slack of the IK's acceptance tolerance (``P + R w``: an accepted
solution moves a point ``w`` from the tool frame's origin by at most that) and
:data:`ROUNDOFF_SLACK`. The core builds the bounds (``reach_bounds_build.hpp``: the
ranges over three joints, exact over one and on a 256² grid over two widened by a bound
of the Hessian, within the joint limits or not) and checks targets against them
(``reach_bounds.hpp``).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from kinematica import _core
from kinematica.core import Chain
from kinematica.ik.tolerance import Tolerance

__all__ = ["ROUNDOFF_SLACK", "may_reach", "reach_bounds", "violation"]

FloatArray = NDArray[np.float64]

_ZERO = np.zeros(1)
_ZERO.flags.writeable = False
_STILL = (np.stack([np.eye(4), np.zeros((4, 4)), np.zeros((4, 4))]), False)  # M(v) = I
_STILL[0].flags.writeable = False

#: Added to every slack (m): round-off of the moved targets, circles and ranges
#: (products of unit vectors and lengths under 10 m: about 1e-15 relative).
ROUNDOFF_SLACK = 1e-9


def reach_bounds(arm: Chain, limits: bool = True) -> _core.ReachBounds | None:
    """The arm's bounds, made once and kept; None unless it has 6 revolute joints.

    Args:
        arm: The 6R arm.
        limits: Bounds of solutions within the joint limits (else anywhere).

    Returns:
        The core's ``ReachBounds`` (``km::reach::Bounds``,
        ``cpp/include/kinematica/reach_bounds.hpp``): axis 6's direction (tool frame); x's
        circle ``c + u cos q6 + v sin q6`` (tool frame); S and axis 1's direction (base
        frame); the ranges of ``|x - S|`` and ``(x - S)·a₁``; the farthest point of x's
        circle from the tool frame's origin; q6's limits; y's circle ``c + u cos q1 + v sin
        q1`` (base frame); q1's limits; Z (tool frame); the ranges of ``|y - Z|`` and
        ``(y - Z)·a₆``.
    """
    key = ("reach bounds", limits)
    found = arm.memo.get(key, False)
    if found is False:
        found = arm.memo[key] = _core.reach_bounds(arm.core, limits)
    return found  # type: ignore[return-value]


def violation(
    bounds: _core.ReachBounds,
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
    bounds: _core.ReachBounds,
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
