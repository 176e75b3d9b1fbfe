"""A robot description with its numbers written as a user reads them.

A DH table extracted from a URDF carries the round-off of the extraction:
``q1 + 1.1850091143197455e-11`` for an offset of 0, ``360.0000000000237`` for a
limit of 2π written as ``6.28318530718``. The line geometry already reads such
values as the round ones (:mod:`kinematica.dh.lines`: axes are parallel,
perpendicular or meet to within ``AXIS_ANGLE_TOL`` rad and ``AXIS_LENGTH_TOL``
m); :func:`rounded_spec` writes each number as the shortest decimal, in the
file's units, that stays within those tolerances of it.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

from kinematica.dh.lines import AXIS_ANGLE_TOL, AXIS_LENGTH_TOL
from kinematica.io import FrameSpec, JointSpec, RobotSpec

__all__ = ["rounded_spec", "shortest_within"]

#: Decimals tried, fewest first (17 digits reproduce any double).
_MAX_DIGITS = 17
#: Conversions of the file's units to radians and metres, as the reader makes them.
_TO_SI: dict[str, Callable[[float], float]] = {
    "deg": lambda v: v * (math.pi / 180.0),
    "rad": lambda v: v,
    "m": lambda v: v,
    "mm": lambda v: v / 1000.0,
}


def shortest_within(value: float, tol: float, to_si: Callable[[float], float]) -> float:
    """The value (SI) of the shortest decimal in file units within ``tol`` of ``value``.

    Args:
        value: The value in SI units (rad, m).
        tol: The largest change allowed, SI units.
        to_si: The conversion of a number written in the file's unit to SI.

    Returns:
        ``to_si(c)`` for the decimal ``c`` of fewest digits with
        ``|to_si(c) - value| <= tol``; ``value`` itself when none is.
    """
    if not math.isfinite(value) or value == 0.0:
        return value
    naive = value / to_si(1.0)
    for digits in range(_MAX_DIGITS):
        c = round(naive, digits)
        if abs(to_si(c) - value) <= tol:
            return to_si(c) if c != 0.0 else 0.0
    return value


def rounded_spec(spec: RobotSpec) -> RobotSpec:
    """``spec`` with every DH number, limit, base and tool entry rounded within the tolerances.

    Angles move by at most ``AXIS_ANGLE_TOL`` rad, lengths by at most
    ``AXIS_LENGTH_TOL`` m, rotation-matrix entries by at most ``AXIS_ANGLE_TOL``:
    the line geometry tells the result from ``spec`` by no relation of its axes.
    Expression texts are dropped (the numbers are written).

    Args:
        spec: The description, its ``units`` those the file is written in.

    Returns:
        The rounded description.
    """
    angle = _TO_SI[spec.units.get("angle", "deg")]
    length = _TO_SI[spec.units.get("length", "m")]
    unitless: Callable[[float], float] = _TO_SI["rad"]

    def a(v: float) -> float:
        return shortest_within(v, AXIS_ANGLE_TOL, angle)

    def m(v: float) -> float:
        return shortest_within(v, AXIS_LENGTH_TOL, length)

    def joint(j: JointSpec) -> JointSpec:
        limit = a if j.kind == "R" else m
        qlim = None if j.qlim is None else (limit(j.qlim[0]), limit(j.qlim[1]))
        return dataclasses.replace(
            j, theta=a(j.theta), d=m(j.d), a=m(j.a), alpha=a(j.alpha), qlim=qlim, expr={}
        )

    def frame(f: FrameSpec | None) -> FrameSpec | None:
        if f is None:
            return None
        if f.matrix is not None:
            rows = tuple(
                (
                    *(shortest_within(v, AXIS_ANGLE_TOL, unitless) for v in row[:3]),
                    m(row[3]) if i < 3 else row[3],
                )
                for i, row in enumerate(f.matrix)
            )
            return dataclasses.replace(f, matrix=rows)
        xyz = (m(f.xyz[0]), m(f.xyz[1]), m(f.xyz[2]))
        rpy = None if f.rpy is None else (a(f.rpy[0]), a(f.rpy[1]), a(f.rpy[2]))
        return dataclasses.replace(f, xyz=xyz, rpy=rpy)

    return dataclasses.replace(
        spec,
        joints=tuple(joint(j) for j in spec.joints),
        base=frame(spec.base),
        tool=frame(spec.tool),
    )
