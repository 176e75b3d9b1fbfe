"""Joint axes as lines in space, and the DH frames that can sit on them.

The geometry under the Denavit-Hartenberg rules: the common normal of two axes
(rules 6 and 7), and the "closest valid DH frame" to a frame a description
already has (a URDF link or joint frame), so that a table extracted from a
description keeps its frames wherever they already obey the rules.

A line is a unit direction ``h`` and a point ``p`` on it, both ``(3,)`` in one
frame; a frame is a ``(4, 4)`` homogeneous transform whose columns are x, y, z
and the origin.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "EXTRACT_ANGLE_TOL",
    "EXTRACT_LENGTH_TOL",
    "LinePair",
    "cross3",
    "frame_from",
    "frame_normal_to_axis",
    "frame_on_axis",
    "line_pair",
    "perpendicular_hint",
]

FloatArray = NDArray[np.float64]

#: Two axis directions are parallel when the sine of their angle is at most this;
#: a direction is normal to another when the cosine is at most this. Parallel
#: axes get the DH rule for parallel axes; when they are not exactly parallel
#: their true common normal is far away (at about offset / angle), and the
#: frames placed by the rule are off it by at most this angle. Near 1e-8 the
#: two errors cross: the far normal costs round-off of about 1e-16 · offset /
#: angle, the parallel rule about angle · arm length.
EXTRACT_ANGLE_TOL = 1e-8
#: Two lines meet, and a point is on a line, when their distance is at most this
#: (m). Meeting axes are placed exactly either way (only the sense of x may
#: change); coinciding axes within this distance lose that offset.
EXTRACT_LENGTH_TOL = 1e-12

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


def cross3(a: FloatArray, b: FloatArray) -> FloatArray:
    """``a × b`` of two ``(3,)`` vectors (``np.cross`` costs 30x more on one pair)."""
    a0, a1, a2 = float(a[0]), float(a[1]), float(a[2])
    b0, b1, b2 = float(b[0]), float(b[1]), float(b[2])
    return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])


def _unit(v: FloatArray) -> FloatArray:
    out: FloatArray = v / np.linalg.norm(v)
    return out


def line_pair(hA: FloatArray, pA: FloatArray, hB: FloatArray, pB: FloatArray) -> LinePair:
    """Classify two lines and find their common normal.

    Args:
        hA: ``(3,)`` unit direction of line A.
        pA: ``(3,)`` a point on A.
        hB: ``(3,)`` unit direction of line B.
        pB: ``(3,)`` a point on B.

    Returns:
        The :class:`LinePair`. Lines are parallel when ``|hA × hB| <=``
        :data:`EXTRACT_ANGLE_TOL`, and meet (or coincide) when their distance
        is at most :data:`EXTRACT_LENGTH_TOL`.
    """
    cross = cross3(hA, hB)
    s = float(np.linalg.norm(cross))
    w = pB - pA
    if s <= EXTRACT_ANGLE_TOL:
        perp = w - float(w @ hA) * hA
        dist = float(np.linalg.norm(perp))
        if dist <= EXTRACT_LENGTH_TOL:
            return LinePair("collinear", None, pA, pB, dist)
        return LinePair("parallel", perp / dist, pA, pB, dist)
    n = cross / s
    signed = float(w @ n)
    # Feet: pA + tA hA + signed n = pB + tB hB; 1 - (hA·hB)² is written s² (no cancellation).
    r = w - signed * n
    c = float(hA @ hB)
    ra, rb = float(r @ hA), float(r @ hB)
    tA = (ra - c * rb) / (s * s)
    tB = (c * ra - rb) / (s * s)
    foot_a, foot_b = pA + tA * hA, pB + tB * hB
    if abs(signed) <= EXTRACT_LENGTH_TOL:
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
    along ``h`` (within :data:`EXTRACT_ANGLE_TOL`), its y axis projected.
    """
    for column in (0, 1):
        v = F[:3, column] - float(F[:3, column] @ h) * h
        if np.linalg.norm(v) > EXTRACT_ANGLE_TOL:
            return _unit(v)
    raise AssertionError("a frame's x and y cannot both lie along one direction")


def frame_on_axis(F: FloatArray, h: FloatArray, p: FloatArray) -> FloatArray | None:
    """The frame with z along the axis ``(h, p)`` closest to ``F``, if ``F`` nearly is one.

    Args:
        F: ``(4, 4)`` a frame.
        h: ``(3,)`` unit axis direction.
        p: ``(3,)`` a point on the axis.

    Returns:
        ``None`` unless ``F``'s z points along ``+h`` and its origin lies on the
        axis (within the tolerances); otherwise ``F`` with its z set to ``h``,
        its x projected normal to ``h`` and its origin projected on the axis.
    """
    z = F[:3, 2]
    if np.linalg.norm(cross3(z, h)) > EXTRACT_ANGLE_TOL or float(z @ h) <= 0.0:
        return None
    d = F[:3, 3] - p
    along = float(d @ h)
    if np.linalg.norm(d - along * h) > EXTRACT_LENGTH_TOL:
        return None
    return frame_from(perpendicular_hint(F, h), h, p + along * h)


def frame_normal_to_axis(F: FloatArray, h: FloatArray, p: FloatArray) -> FloatArray | None:
    """The frame whose x line meets the axis ``(h, p)`` at a right angle, closest to ``F``.

    Such a frame is a valid DH frame after the axis in the standard
    convention (x_n normal to z_(n-1) and meeting it) and before it in the
    modified one (x_0 normal to z_1 and meeting it).

    Args:
        F: ``(4, 4)`` a frame.
        h: ``(3,)`` unit axis direction.
        p: ``(3,)`` a point on the axis.

    Returns:
        ``None`` unless ``F``'s x is normal to ``h`` and its x line meets the
        axis (within the tolerances); otherwise ``F`` adjusted to obey both
        exactly.
    """
    x = F[:3, 0]
    if abs(float(x @ h)) > EXTRACT_ANGLE_TOL:
        return None
    x = _unit(x - float(x @ h) * h)
    m = cross3(h, x)  # unit: normal to the plane of the axis and the x line
    off = float((F[:3, 3] - p) @ m)
    if abs(off) > EXTRACT_LENGTH_TOL:
        return None
    z = _unit(F[:3, 2] - float(F[:3, 2] @ x) * x)
    return frame_from(x, z, F[:3, 3] - off * m)
