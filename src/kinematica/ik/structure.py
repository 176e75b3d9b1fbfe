"""The geometry of an arm's joint axes: what the closed-form solvers look for.

Read from the joint axes as lines in space at q = 0 (direction and a point,
base frame), never from names: which consecutive axes are parallel, which
meet, which are perpendicular, where the last three meet. Joint motions keep
these relations (a joint moves every later axis rigidly), so they hold at
every q.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica._core import lines as _lines
from kinematica.core import Chain
from kinematica.dh.lines import length_tol, line_distance, lines_parallel, lines_perpendicular

__all__ = ["Features", "arm_size", "features"]

FloatArray = NDArray[np.float64]


def arm_size(chain: Chain) -> float:
    """The arm's size (m): the sum of its joints' fixed translations and the tool's offset.

    The scale the line geometry's length tolerance is relative to
    (:func:`kinematica.dh.lines.length_tol`); a slide's travel is not counted. Where a
    revolute chain's size measured along its axes (each axis's point the one nearest the
    previous axis's) is below a tenth of that, that one: a DH table of nearly parallel
    axes puts its frames km away, at the foot of their common normal.
    """
    return _lines.arm_size(chain.core)


@dataclass(frozen=True, slots=True, eq=False)
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
            tool from this one's: each relation whose sine, cosine or distance
            lies in ``(AXIS_EXACT_TOL, tolerance]`` adds ``2 ε size`` (an axis
            tilted by ε) or its distance δ (an axis, or one through a centre, off by δ).

    Every relation is :mod:`kinematica.dh.lines`' (its tolerances, the same
    ones DH extraction uses); :func:`features` reads them all in one call of the
    core (``km::lines::axis_features``, ``cpp/include/kinematica/lines.hpp``).
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


def features(chain: Chain) -> Features:
    """The features of a chain's joint axes at q = 0 (made once, kept by the chain).

    The builders, the choice of a redundant arm's parameter and the near-degenerate
    test all ask for them.
    """
    memo = chain.memo
    found = memo.get("features")
    if found is None:
        found = memo["features"] = Features(*_lines.features(chain.core))  # in Features' order
    return found  # type: ignore[return-value]
