"""The geometry of an arm's joint axes: what the closed-form solvers look for.

Read from the joint axes as lines in space at q = 0 (direction and a point,
base frame), never from names: which consecutive axes are parallel, which
meet, which are perpendicular, where the last three meet. Joint motions keep
these relations (a joint moves every later axis rigidly), so they hold at
every q.
"""

from __future__ import annotations

import math
import weakref

import numpy as np
from numpy.typing import NDArray

from kinematica._record import record
from kinematica.core import Chain
from kinematica.dh.lines import (
    AXIS_ANGLE_TOL,
    AXIS_EXACT_TOL,
    common_point,
    cross3,
    length_tol,
    line_distance,
    lines_parallel,
    lines_perpendicular,
)

__all__ = ["Features", "arm_size", "features", "near_degenerate_slack"]

FloatArray = NDArray[np.float64]


def arm_size(chain: Chain) -> float:
    """The arm's size (m): the sum of its joints' fixed translations and the tool's offset.

    The scale the line geometry's length tolerance is relative to
    (:func:`kinematica.dh.lines.length_tol`); a slide's travel is not counted.
    """
    size = float(np.linalg.norm(chain.tool[:3, 3]))
    return size + float(np.abs(chain.translations).sum())


@record
class Features:
    """What the joint axes of an arm have in common, at q = 0.

    Attributes:
        joint_types: e.g. ``"RRRRRR"``.
        directions: ``(n, 3)`` unit axis directions (base frame).
        points: ``(n, 3)`` a point on each axis (base frame, m).
        parallel: Index pairs ``(i, i+1)`` (0-based) of consecutive parallel axes.
        intersecting: Index pairs ``(i, i+1)`` of consecutive axes that meet.
        wrist_center: ``(3,)`` point where the last three axes meet (base
            frame), when they are revolute, not all parallel, and meet.
        shoulder_center: ``(3,)`` point where the first three axes meet, likewise.
        size: The arm's size (m, :func:`arm_size`): lines meet within
            ``length_tol(size)``.
        slack: 0 when every relation of two axes (parallel, perpendicular,
            meeting) and the wrist centre holds exactly or not at all; else a
            bound (m) on how far an arm with those relations made exact moves the
            tool from this one's (see :func:`near_degenerate_slack`).

    Every relation is :mod:`kinematica.dh.lines`' (its tolerances, the same
    ones DH extraction uses).
    """

    joint_types: str
    directions: FloatArray
    points: FloatArray
    parallel: tuple[tuple[int, int], ...]
    intersecting: tuple[tuple[int, int], ...]
    wrist_center: FloatArray | None
    size: float
    slack: float = 0.0
    shoulder_center: FloatArray | None = None

    @property
    def near_degenerate(self) -> bool:
        """True when a relation of its axes holds only within the tolerances."""
        return self.slack > 0.0

    @property
    def dof(self) -> int:
        """Number of joints n."""
        return len(self.joint_types)

    def is_parallel(self, i: int, j: int) -> bool:
        """True when axes ``i`` and ``j`` (0-based) are parallel."""
        return lines_parallel(self.directions[i], self.directions[j])

    def is_perpendicular(self, i: int, j: int) -> bool:
        """True when axes ``i`` and ``j`` are perpendicular."""
        return lines_perpendicular(self.directions[i], self.directions[j])

    @property
    def length_tol(self) -> float:
        """The distance (m) below which two of its lines meet."""
        return length_tol(self.size)

    def all_parallel(self, indices: range | list[int]) -> bool:
        """True when every axis in ``indices`` is parallel to the first."""
        i0 = indices[0]
        return all(self.is_parallel(i0, i) for i in indices)

    def meet(self, i: int, j: int) -> bool:
        """True when axes ``i`` and ``j`` are not parallel and meet."""
        h, p = self.directions, self.points
        return (
            not self.is_parallel(i, j) and line_distance(h[i], p[i], h[j], p[j]) <= self.length_tol
        )


#: Each chain's features, made once (a chain is immutable; the cache forgets a chain
#: when it dies): the builders, the choice of a redundant arm's parameter and the
#: near-degenerate test all ask for them.
_FEATURES: weakref.WeakKeyDictionary[Chain, Features] = weakref.WeakKeyDictionary()


def features(chain: Chain) -> Features:
    """The features of a chain's joint axes at q = 0."""
    found = _FEATURES.get(chain)
    if found is None:
        found = _FEATURES[chain] = _features(chain)
    return found


def _features(chain: Chain) -> Features:
    axes = chain.joint_axes(np.zeros(chain.dof))
    h, p = axes[:, :3].copy(), axes[:, 3:].copy()
    n = chain.dof
    size = arm_size(chain)
    tol = length_tol(size)
    types = "".join("P" if v else "R" for v in chain.prismatic)
    parallel = tuple((i, i + 1) for i in range(n - 1) if lines_parallel(h[i], h[i + 1]))
    meet = tuple(
        (i, i + 1)
        for i in range(n - 1)
        if (i, i + 1) not in parallel and line_distance(h[i], p[i], h[i + 1], p[i + 1]) <= tol
    )
    wrist = _center(h, p, types, size, range(n - 3, n))
    shoulder = _center(h, p, types, size, range(3))
    for a in (h, p):
        a.flags.writeable = False
    slack = near_degenerate_slack(h, p, size, wrist, shoulder)
    return Features(types, h, p, parallel, meet, wrist, size, slack, shoulder)


def _center(
    h: FloatArray, p: FloatArray, types: str, size: float, axes: range
) -> FloatArray | None:
    """The point where three revolute axes, not all parallel, meet; else None."""
    if len(types) < 3 or any(types[i] != "R" for i in axes):
        return None
    if all(lines_parallel(h[axes[0]], h[i]) for i in axes):
        return None
    return common_point(h[axes], p[axes], size)


def near_degenerate_slack(
    h: FloatArray,
    p: FloatArray,
    size: float,
    wrist: FloatArray | None,
    shoulder: FloatArray | None = None,
) -> float:
    """A bound (m) on how far the relations that hold only within tolerance move the tool.

    Every pair of axes whose sine (parallel), cosine (perpendicular) or distance
    (meeting, coinciding) lies between ``AXIS_EXACT_TOL`` and the line
    geometry's tolerance, and each axis passing the wrist (or shoulder) centre
    within the tolerance but not exactly, is a relation a closed form takes as exact. An
    axis tilted by ε turns the points beyond it, at most ``size`` away, by at
    most ``2 ε size`` for any joint motion, a point off by δ moves them by δ: the
    slack is the sum over the relations, 0 when there are none.

    Args:
        h: ``(n, 3)`` unit axis directions at q = 0.
        p: ``(n, 3)`` a point on each axis.
        size: The arm's size (m).
        wrist: The wrist centre, if any.
        shoulder: The shoulder centre (axes 1-3), if any.
    """
    exact, tol = AXIS_EXACT_TOL, length_tol(size)
    exact_len = AXIS_EXACT_TOL * (1.0 + size)
    slack = 0.0
    n = len(h)
    for i in range(n):
        for j in range(i + 1, n):
            sine = math.hypot(*cross3(h[i], h[j]))
            cosine = abs(float(h[i] @ h[j]))
            for v in (sine, cosine):
                if exact < v <= AXIS_ANGLE_TOL:
                    slack += 2.0 * v * size
            d = line_distance(h[i], p[i], h[j], p[j])
            if exact_len < d <= tol:
                slack += d
    for center, axes in ((wrist, range(n - 3, n)), (shoulder, range(3))):
        if center is None:
            continue
        for i in axes:
            r = center - p[i]
            d = float(np.linalg.norm(r - float(r @ h[i]) * h[i]))
            if exact_len < d <= tol:
                slack += d
    return slack
