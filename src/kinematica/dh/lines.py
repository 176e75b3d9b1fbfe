"""Joint axes as lines in space, and the DH frames that can sit on them.

The one line geometry of the package, with its one pair of tolerances: DH
extraction, the structure classification of the IK solvers, their builders
and the singularity analysis all ask here whether two axes are parallel,
perpendicular, meet or coincide, so an arm is one shape to all of them.

The geometry under the Denavit-Hartenberg rules: the common normal of two axes
(rules 6 and 7), and the "closest valid DH frame" to a frame a description
already has (a URDF link or joint frame), so that a table extracted from a
description keeps its frames wherever they already obey the rules.

A line is a unit direction ``h`` and a point ``p`` on it, both ``(3,)`` in one
frame; a frame is a ``(4, 4)`` homogeneous transform whose columns are x, y, z
and the origin. Lengths are compared relative to the arm's size (see
:func:`length_tol`). The tolerances, the predicates (parallel, perpendicular),
:func:`line_distance` and :func:`common_point` are the compiled core's
(``cpp/include/kinematica/lines.hpp``), where an arm's features are read too.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from kinematica._core import lines as _lines

__all__ = [
    "AXIS_ANGLE_TOL",
    "AXIS_EXACT_TOL",
    "AXIS_LENGTH_TOL",
    "LinePair",
    "common_point",
    "cross3",
    "frame_from",
    "frame_normal_to_axis",
    "frame_on_axis",
    "length_tol",
    "line_distance",
    "line_pair",
    "lines_parallel",
    "lines_perpendicular",
    "normal_feet",
    "perpendicular_hint",
]

FloatArray = NDArray[np.float64]

# The tolerances and the predicates below are the core's (cpp/include/kinematica/lines.hpp,
# where each value's reasons are written): the classification of an arm's features
# (kinematica.ik.structure) runs there, and the callers here ask the same code.

#: Two axis directions are parallel when the sine of their angle is at most this;
#: perpendicular when the cosine is (the core's ``km::lines::AXIS_ANGLE_TOL``).
AXIS_ANGLE_TOL: float = _lines.AXIS_ANGLE_TOL
#: Two lines meet, a point is on a line, and parallel lines coincide when their
#: distance is at most this times ``1 + size`` (size: the arm's, m; see
#: :func:`length_tol`; the core's ``km::lines::AXIS_LENGTH_TOL``).
AXIS_LENGTH_TOL: float = _lines.AXIS_LENGTH_TOL
#: A relation holds exactly, not only within the tolerances above, when its sine,
#: cosine or distance / (1 + size) is at most this: an arm whose axes meet one of
#: its relations only within the tolerances is *near-degenerate* (the core's
#: ``km::lines::AXIS_EXACT_TOL``).
AXIS_EXACT_TOL: float = _lines.AXIS_EXACT_TOL


def length_tol(size: float) -> float:
    """The distance (m) below which lines meet, for an arm of this size (m).

    ``AXIS_LENGTH_TOL · (1 + size)``: relative to the arm for arms of a metre
    and more, ``AXIS_LENGTH_TOL`` metres for small ones (whose round-off is
    smaller still).
    """
    return _lines.length_tol(size)


def lines_parallel(hA: FloatArray, hB: FloatArray) -> bool:
    """True when unit directions ``hA``, ``hB`` (3,) are parallel or anti-parallel."""
    return _lines.lines_parallel(hA, hB)


def lines_perpendicular(hA: FloatArray, hB: FloatArray) -> bool:
    """True when unit directions ``hA``, ``hB`` (3,) are perpendicular."""
    return _lines.lines_perpendicular(hA, hB)


def line_distance(hA: FloatArray, pA: FloatArray, hB: FloatArray, pB: FloatArray) -> float:
    """Distance (m) between the lines ``pA + t hA`` and ``pB + s hB`` (unit directions)."""
    return _lines.line_distance(hA, pA, hB, pB)


def normal_feet(
    hA: FloatArray, pA: FloatArray, hB: FloatArray, pB: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Where the common normal of two non-parallel lines meets each: ``(3,), (3,)``.

    ``pA + tA hA`` and ``pB + tB hB`` with ``1 - (hA·hB)²`` written as
    ``|hA × hB|²`` (no cancellation for nearly parallel lines).
    """
    cross = cross3(hA, hB)
    s2 = float(cross @ cross)
    n = cross / math.sqrt(s2)
    w = pB - pA
    r = w - float(w @ n) * n
    c = float(hA @ hB)
    ra, rb = float(r @ hA), float(r @ hB)
    tA = (ra - c * rb) / s2
    tB = (c * ra - rb) / s2
    return pA + tA * hA, pB + tB * hB


def common_point(h: FloatArray, p: FloatArray, size: float) -> FloatArray | None:
    """The point where all lines ``p[i] + t h[i]`` meet, or ``None``.

    Args:
        h: ``(k, 3)`` unit directions, not all parallel.
        p: ``(k, 3)`` a point on each line.
        size: The arm's size (m), for :func:`length_tol`.

    Returns:
        ``(3,)`` the least-squares point, if the normal matrix ``Σ (I - h hᵀ)``
        has rank 3 at tolerance :data:`AXIS_ANGLE_TOL` and every line passes
        within ``length_tol(size)`` of it; otherwise ``None``.
    """
    return _lines.common_point(
        np.ascontiguousarray(h, dtype=np.float64), np.ascontiguousarray(p, dtype=np.float64), size
    )


PairKind = Literal["skew", "intersecting", "parallel", "collinear"]


@dataclass(frozen=True)
class LinePair:
    """How two axes A and B lie, and their common normal.

    Attributes:
        kind: ``"skew"``, ``"intersecting"``, ``"parallel"`` or ``"collinear"``.
        normal: ``(3,)`` unit direction of the common normal: from A to B for
            skew and parallel axes, ``hA × hB`` for intersecting ones; ``None``
            for collinear axes (any direction normal to them will do).
        foot_a: ``(3,)`` where the normal meets A (for parallel and collinear
            axes, A's own point: the joint on A).
        foot_b: ``(3,)`` where the normal meets B (likewise B's own point).
        distance: Length of the common normal (m), 0 for intersecting axes.
    """

    kind: PairKind
    normal: FloatArray | None
    foot_a: FloatArray
    foot_b: FloatArray
    distance: float


def cross3(a: FloatArray | Sequence[float], b: FloatArray | Sequence[float]) -> FloatArray:
    """``a × b`` of two ``(3,)`` vectors (``np.cross`` costs 15-30x more on one pair).

    The same operations as ``np.cross`` (two products, one difference per
    component), so the same floats.
    """
    a0, a1, a2 = float(a[0]), float(a[1]), float(a[2])
    b0, b1, b2 = float(b[0]), float(b[1]), float(b[2])
    return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])


def _unit(v: FloatArray) -> FloatArray:
    out: FloatArray = v / np.linalg.norm(v)
    return out


def line_pair(
    hA: FloatArray, pA: FloatArray, hB: FloatArray, pB: FloatArray, size: float
) -> LinePair:
    """Classify two lines and find their common normal.

    Args:
        hA: ``(3,)`` unit direction of line A.
        pA: ``(3,)`` a point on A.
        hB: ``(3,)`` unit direction of line B.
        pB: ``(3,)`` a point on B.
        size: The arm's size (m), for :func:`length_tol`.

    Returns:
        The :class:`LinePair`. Lines are parallel when ``|hA × hB| <=``
        :data:`AXIS_ANGLE_TOL`, and meet (or coincide) when their distance
        is at most ``length_tol(size)``.
    """
    w = pB - pA
    tol = length_tol(size)
    if lines_parallel(hA, hB):
        perp = w - float(w @ hA) * hA
        dist = float(np.linalg.norm(perp))
        if dist <= tol:
            return LinePair("collinear", None, pA, pB, dist)
        return LinePair("parallel", perp / dist, pA, pB, dist)
    cross = cross3(hA, hB)
    n = cross / float(np.linalg.norm(cross))
    signed = float(w @ n)
    foot_a, foot_b = normal_feet(hA, pA, hB, pB)
    if abs(signed) <= tol:
        return LinePair("intersecting", n, foot_a, foot_b, abs(signed))
    return LinePair("skew", n if signed > 0 else -n, foot_a, foot_b, abs(signed))


def frame_from(x: FloatArray, z: FloatArray, origin: FloatArray) -> FloatArray:
    """The ``(4, 4)`` frame with unit z ``z``, x along ``x`` made normal to it, ``y = z × x``.

    ``x`` is projected on the plane normal to ``z`` once more and normalised, so
    the frame is orthonormal to round-off even when ``x`` came from a projection
    that lost digits (a direction nearly along ``z``).
    """
    x = _unit(x - float(x @ z) * z)
    F = np.eye(4)
    F[:3, 0], F[:3, 1], F[:3, 2], F[:3, 3] = x, cross3(z, x), z, origin
    return F


def perpendicular_hint(F: FloatArray, h: FloatArray) -> FloatArray:
    """A unit direction normal to ``h`` taken from frame ``F``: its x, else its y.

    ``F``'s x axis projected on the plane normal to ``h``; when that x lies
    along ``h`` (within :data:`AXIS_ANGLE_TOL`), its y axis projected.
    """
    for column in (0, 1):
        v = F[:3, column] - float(F[:3, column] @ h) * h
        if np.linalg.norm(v) > AXIS_ANGLE_TOL:
            return _unit(v)
    raise AssertionError("a frame's x and y cannot both lie along one direction")


def frame_on_axis(F: FloatArray, h: FloatArray, p: FloatArray, size: float) -> FloatArray | None:
    """The frame with z along the axis ``(h, p)`` closest to ``F``, if ``F`` nearly is one.

    Args:
        F: ``(4, 4)`` a frame.
        h: ``(3,)`` unit axis direction.
        p: ``(3,)`` a point on the axis.
        size: The arm's size (m), for :func:`length_tol`.

    Returns:
        ``None`` unless ``F``'s z points along ``+h`` and its origin lies on the
        axis (within the tolerances); otherwise ``F`` with its z set to ``h``,
        its x projected normal to ``h`` and its origin projected on the axis.
    """
    z = F[:3, 2]
    if not lines_parallel(z, h) or float(z @ h) <= 0.0:
        return None
    d = F[:3, 3] - p
    along = float(d @ h)
    if np.linalg.norm(d - along * h) > length_tol(size):
        return None
    return frame_from(perpendicular_hint(F, h), h, p + along * h)


def frame_normal_to_axis(
    F: FloatArray, h: FloatArray, p: FloatArray, size: float
) -> FloatArray | None:
    """The frame whose x line meets the axis ``(h, p)`` at a right angle, closest to ``F``.

    Such a frame is a valid DH frame after the axis in the standard
    convention (x_n normal to z_(n-1) and meeting it) and before it in the
    modified one (x_0 normal to z_1 and meeting it).

    Args:
        F: ``(4, 4)`` a frame.
        h: ``(3,)`` unit axis direction.
        p: ``(3,)`` a point on the axis.
        size: The arm's size (m), for :func:`length_tol`.

    Returns:
        ``None`` unless ``F``'s x is normal to ``h`` and its x line meets the
        axis (within the tolerances); otherwise ``F`` adjusted to obey both
        exactly.
    """
    x = F[:3, 0]
    if abs(float(x @ h)) > AXIS_ANGLE_TOL:
        return None
    x = _unit(x - float(x @ h) * h)
    m = cross3(h, x)  # unit: normal to the plane of the axis and the x line
    off = float((F[:3, 3] - p) @ m)
    if abs(off) > length_tol(size):
        return None
    z = _unit(F[:3, 2] - float(F[:3, 2] @ x) * x)
    return frame_from(x, z, F[:3, 3] - off * m)
