"""Kinematic structure of an arm, read from the geometry of its joint axes.

The classification never looks at names: it takes each joint's axis as a line
in space at q = 0 (direction and a point, base frame) and tests which axes are
parallel, which meet, which are perpendicular. Joint motions keep these
relations (a joint moves every later axis rigidly), so they hold at every q.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from kinematica.robot.robot import Robot

__all__ = ["Structure", "axes_intersect", "classify", "common_point", "lines_parallel"]

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


def axes_intersect(h1: FloatArray, p1: FloatArray, h2: FloatArray, p2: FloatArray) -> bool:
    """True when two non-parallel lines meet (within ``MEET_TOL``)."""
    return not lines_parallel(h1, h2) and line_distance(h1, p1, h2, p2) < MEET_TOL


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


@dataclass(frozen=True)
class Structure:
    """What the joint axes of an arm have in common.

    Attributes:
        kind: Machine-readable class, one of ``"planar-2R"``, ``"planar-3R"``,
            ``"planar-PR"``, ``"planar-PRR"``, ``"scara"``, ``"anthropomorphic-3R"``,
            ``"elbow-3R"``, ``"spherical-wrist-6R"``, ``"three-parallel-6R"``,
            ``"rrp-spherical-wrist"``, ``"general"``.
        summary: One line for people, e.g. ``"6R, spherical wrist"``.
        joint_types: e.g. ``"RRRRRR"``.
        parallel: Index pairs ``(i, i+1)`` (0-based) of consecutive parallel axes.
        intersecting: Index pairs ``(i, i+1)`` of consecutive axes that meet.
        wrist_center: ``(3,)`` point where the last three axes meet at q = 0
            (base frame), or ``None``.
    """

    kind: str
    summary: str
    joint_types: str
    parallel: tuple[tuple[int, int], ...]
    intersecting: tuple[tuple[int, int], ...]
    wrist_center: FloatArray | None


def _all_parallel(h: FloatArray, idx: range | list[int]) -> bool:
    i0 = idx[0]
    return all(lines_parallel(h[i0], h[i]) for i in idx)


def classify(robot: Robot) -> Structure:
    """Classify an arm from its joint axes at q = 0.

    Args:
        robot: The robot.

    Returns:
        Its :class:`Structure`.
    """
    h, p = robot.joint_axes()
    n, types = robot.dof, robot.joint_types
    parallel = tuple((i, i + 1) for i in range(n - 1) if lines_parallel(h[i], h[i + 1]))
    meet = tuple((i, i + 1) for i in range(n - 1) if axes_intersect(h[i], p[i], h[i + 1], p[i + 1]))
    wrist = None
    if n >= 3 and types[-3:] == "RRR" and not _all_parallel(h, [n - 3, n - 2, n - 1]):
        wrist = common_point(h[-3:], p[-3:])

    def perp(i: int, j: int) -> bool:
        return abs(float(np.dot(h[i], h[j]))) < PERP_TOL

    kind, summary = "general", f"{n} joints ({types})"
    if n == 2 and types == "RR" and (0, 1) in parallel:
        kind, summary = "planar-2R", "2R planar"
    elif n == 2 and types == "PR" and perp(0, 1):
        kind, summary = "planar-PR", "PR planar (prismatic then revolute)"
    elif n == 3 and types == "RRR" and _all_parallel(h, range(3)):
        kind, summary = "planar-3R", "3R planar"
    elif n == 3 and types == "PRR" and (1, 2) in parallel and perp(0, 1):
        kind, summary = "planar-PRR", "PRR planar (prismatic then two parallel revolute)"
    elif n == 3 and types == "RRR" and (1, 2) in parallel and perp(0, 1):
        if (0, 1) in meet:
            kind, summary = "anthropomorphic-3R", "3R anthropomorphic (shoulder axes meet)"
        else:
            kind, summary = "elbow-3R", "3R elbow arm with shoulder offset"
    elif n == 4 and types == "RRPR" and _all_parallel(h, range(4)):
        kind, summary = "scara", "SCARA (RRPR, all axes parallel)"
    elif n == 6 and types == "RRRRRR" and wrist is not None:
        kind, summary = "spherical-wrist-6R", "6R, spherical wrist"
    elif n == 6 and types == "RRPRRR" and wrist is not None:
        kind, summary = "rrp-spherical-wrist", "RRP + spherical wrist (Stanford type)"
    elif n == 6 and types == "RRRRRR" and {(1, 2), (2, 3)} <= set(parallel):
        kind, summary = "three-parallel-6R", "6R, three parallel axes (2-3-4), UR type"
    elif n == 6 and types == "RRRRRR" and {(0, 1), (1, 2)} <= set(parallel):
        kind, summary = "general", "6R, three parallel axes (1-2-3)"
    elif n > 6:
        summary = f"{n} joints ({types}), redundant"
        if wrist is not None:
            summary += ", spherical wrist"
    elif wrist is not None:
        summary += ", last three axes meet (wrist)"
    return Structure(
        kind=kind,
        summary=summary,
        joint_types=types,
        parallel=parallel,
        intersecting=meet,
        wrist_center=wrist,
    )
