"""Where the first three joints put a point: the geometry, computed once per arm.

Joints 1 and 2 are revolute (lines ``(h1, p1)``, ``(h2, p2)`` at q = 0); joint 3
is revolute or prismatic. A point ``c`` fixed after joint 3 (a wrist centre, or
the tool origin with the later joints at 0) must reach a target. The core's builders
read the geometry from the joint axes (``km::decoupled::arm_geometry``,
``cpp/include/kinematica/solvers/arm_point_build.hpp``; the maths in
``arm_point.hpp``): which of three shoulders it is (axes 1 and 2 meet, are
parallel, or are skew), the motion ``u(q3)`` of the point as seen from axis 2, its
expression on a frame of axis 2, the bounds of the reachable shell; whether joints
1-3 place the point at all (``places_point``, at ``PLACE_PROBES`` against
``PLACE_RANK_TOL``). This module names the branches of a built ``ArmPoint``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import kinematica._core as _core

__all__ = ["ELBOW_BENDS", "ArmGeometry", "geometry_of"]


@dataclass(frozen=True, slots=True, eq=False)
class ArmGeometry:
    """The core's arm part, and the names of its four slots.

    Attributes:
        arm: The filled ``kinematica._core.decoupled.ArmPoint``.
        labels: ``(4,)`` names of the position branches (slots).
        kind: ``"meet"``, ``"parallel"`` or ``"general"`` (axes 1 and 2).
        parallel23: True when axes 2 and 3 are parallel (revolute joint 3).
        prismatic: True when joint 3 slides.
    """

    arm: Any
    labels: tuple[str, ...]
    kind: str
    parallel23: bool
    prismatic: bool


def geometry_of(arm: Any) -> ArmGeometry:
    """The :class:`ArmGeometry` of a built ``ArmPoint`` (the core's ``arm_shape``)."""
    kind, prismatic, parallel23 = _core.decoupled.arm_shape(arm)
    return ArmGeometry(arm, _labels(kind, prismatic, parallel23), kind, parallel23, prismatic)


#: The two elbows of a meeting shoulder whose axes 2 and 3 are not parallel (the arm
#: does not move in a plane, so "up" and "down" mean nothing): joint 3 turned from its
#: stretched angle q3* (where the point is farthest from the shoulder) by +bend or
#: -bend (right-hand rule about axis 3), bend in [0, π]; the two reach the same
#: distance. Slot order: q3* + bend first.
ELBOW_BENDS = ("elbow bent positive", "elbow bent negative")


def _labels(kind: str, prismatic: bool, parallel23: bool) -> tuple[str, ...]:
    if kind == "meet" and parallel23:
        return (
            "shoulder right, elbow up",
            "shoulder right, elbow down",
            "shoulder left, elbow up",
            "shoulder left, elbow down",
        )
    if kind == "general" and parallel23:
        return (
            "shoulder front, elbow up",
            "shoulder front, elbow down",
            "shoulder back, elbow up",
            "shoulder back, elbow down",
        )
    if kind == "meet":
        second = ("slide out", "slide in") if prismatic else ELBOW_BENDS
        return tuple(f"shoulder {s}, {e}" for s in ("right", "left") for e in second)
    return tuple(f"position {k}" for k in range(1, 5))
