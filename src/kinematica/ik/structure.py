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

from kinematica.core import Chain

__all__ = [
    "MEET_TOL",
    "PARALLEL_TOL",
    "PERP_TOL",
    "Features",
    "common_point",
    "features",
    "line_distance",
    "lines_parallel",
]

FloatArray = NDArray[np.float64]

#: Two unit directions are parallel when |h1 × h2| is below this (sine of the angle).
PARALLEL_TOL = 1e-9
#: Lines meet when their distance is below this (metres).
MEET_TOL = 1e-9
#: Two unit directions are perpendicular when |h1 · h2| is below this.
PERP_TOL = 1e-9


def lines_parallel(h1: FloatArray, h2: FloatArray) -> bool:
    """True when unit directions ``h1``, ``h2`` (3,) are parallel or anti-parallel."""
    return bool(np.linalg.norm(np.cross(h1, h2)) < PARALLEL_TOL)


def line_distance(h1: FloatArray, p1: FloatArray, h2: FloatArray, p2: FloatArray) -> float:
    """Distance between the lines ``p1 + t h1`` and ``p2 + s h2`` (metres)."""
    n = np.cross(h1, h2)
    nn = float(np.linalg.norm(n))
    if nn < PARALLEL_TOL:
        d = p2 - p1
        return float(np.linalg.norm(d - np.dot(d, h1) * h1))
    return abs(float(np.dot(p2 - p1, n))) / nn


def common_point(h: FloatArray, p: FloatArray) -> FloatArray | None:
    """The point where all lines ``p[i] + t h[i]`` meet, or ``None``.

    Args:
        h: ``(k, 3)`` unit directions, not all parallel.
        p: ``(k, 3)`` a point on each line.

    Returns:
        ``(3,)`` the least-squares point, if every line passes within
        ``MEET_TOL`` of it; otherwise ``None``.
    """
    A = np.zeros((3, 3))
    b = np.zeros(3)
    for hi, pi in zip(h, p, strict=True):
        P = np.eye(3) - np.outer(hi, hi)  # projector orthogonal to the line
        A += P
        b += P @ pi
    if np.linalg.matrix_rank(A, tol=1e-9) < 3:
        return None
    c: FloatArray = np.linalg.solve(A, b).astype(np.float64)
    for hi, pi in zip(h, p, strict=True):
        d = c - pi
        if np.linalg.norm(d - np.dot(d, hi) * hi) > MEET_TOL:
            return None
    return c


@dataclass(frozen=True, eq=False)
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
    """

    joint_types: str
    directions: FloatArray
    points: FloatArray
    parallel: tuple[tuple[int, int], ...]
    intersecting: tuple[tuple[int, int], ...]
    wrist_center: FloatArray | None

    @property
    def dof(self) -> int:
        """Number of joints n."""
        return len(self.joint_types)

    def is_parallel(self, i: int, j: int) -> bool:
        """True when axes ``i`` and ``j`` (0-based) are parallel."""
        return lines_parallel(self.directions[i], self.directions[j])

    def is_perpendicular(self, i: int, j: int) -> bool:
        """True when axes ``i`` and ``j`` are perpendicular."""
        return abs(float(self.directions[i] @ self.directions[j])) < PERP_TOL

    def all_parallel(self, indices: range | list[int]) -> bool:
        """True when every axis in ``indices`` is parallel to the first."""
        i0 = indices[0]
        return all(self.is_parallel(i0, i) for i in indices)

    def meet(self, i: int, j: int) -> bool:
        """True when axes ``i`` and ``j`` are not parallel and meet."""
        h, p = self.directions, self.points
        return not self.is_parallel(i, j) and line_distance(h[i], p[i], h[j], p[j]) < MEET_TOL


def features(chain: Chain) -> Features:
    """The features of a chain's joint axes at q = 0."""
    axes = chain.joint_axes(np.zeros(chain.dof))
    h, p = axes[:, :3].copy(), axes[:, 3:].copy()
    n = chain.dof
    types = "".join("P" if v else "R" for v in chain.prismatic)
    parallel = tuple((i, i + 1) for i in range(n - 1) if lines_parallel(h[i], h[i + 1]))
    meet = tuple(
        (i, i + 1)
        for i in range(n - 1)
        if (i, i + 1) not in parallel and line_distance(h[i], p[i], h[i + 1], p[i + 1]) < MEET_TOL
    )
    wrist = None
    if n >= 3 and types[-3:] == "RRR":
        last = [n - 3, n - 2, n - 1]
        if not all(lines_parallel(h[last[0]], h[i]) for i in last):
            wrist = common_point(h[-3:], p[-3:])
    for a in (h, p):
        a.flags.writeable = False
    return Features(types, h, p, parallel, meet, wrist)
