"""Exact conversion of a DH table between the standard and modified conventions.

The lecture notes: "las matrices de transformación intermedias varían, pero el resultado
final es el mismo". Because ``Tras(x, a)`` and ``Rot(x, α)`` commute, a standard
table regroups into a modified one by moving each row's ``(a, α)`` to the next
row; the last row's pair goes into the tool, and the first modified row's pair
into the base. The end-effector pose is the same for every q.

Back from modified to standard, a tool that is ``Tras(x, a) · Rot(x, α)`` (as the
regrouping of a standard table without a tool leaves it) is that pair, and it
returns to the last row: the textbook planar 3R has ``a3`` in its table, not in
its tool, whichever way it was converted, and the DH rules read the same last
row off the arm's axes (:func:`kinematica.dh.extract_dh`, whose test of the tip
is :func:`x_screw`, so that both agree on every arm).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from kinematica.dh.joints import Convention, Joint, check_convention
from kinematica.dh.lines import AXIS_ANGLE_TOL, length_tol

__all__ = ["ROUND_OFF_TOL", "convert_table", "rx_tx", "snap", "x_screw"]

FloatArray = NDArray[np.float64]

#: Round-off of the frame arithmetic: a DH length this close to a 12-decimal
#: number, an angle this close to a multiple of 45°, and a base or tool entry
#: this close to 0, 1 or -1 are set to that value (FK moves by about this much).
ROUND_OFF_TOL = 1e-15


def rx_tx(alpha: float, a: float) -> FloatArray:
    """``Rot(x, α) · Tras(x, a)`` (equal to ``Tras(x, a) · Rot(x, α)``): ``(4, 4)``."""
    ca, sa = math.cos(alpha), math.sin(alpha)
    return np.array([[1.0, 0, 0, a], [0, ca, -sa, 0], [0, sa, ca, 0], [0, 0, 0, 1.0]])


def snap(T: FloatArray) -> FloatArray:
    """``T`` with entries within :data:`ROUND_OFF_TOL` of 0, 1 or -1 set to them."""
    near = np.clip(np.round(T), -1.0, 1.0)
    return np.where(np.abs(T - near) <= ROUND_OFF_TOL, near, T)


def x_screw(T: FloatArray) -> tuple[float, float] | None:
    """``(a, α)`` when ``T`` is ``Tras(x, a) · Rot(x, α)``, else ``None``.

    Within the line geometry's tolerances: ``T``'s x lies along x (sine at most
    :data:`~kinematica.dh.lines.AXIS_ANGLE_TOL`) and its origin on the x axis
    (:func:`~kinematica.dh.lines.length_tol` of its distance along it), as the
    DH rules ask of a last standard frame on the x line of the modified one.

    Args:
        T: ``(4, 4)`` a rigid transform.
    """
    a = float(T[0, 3])
    if (
        T[0, 0] <= 0.0
        or math.hypot(T[1, 0], T[2, 0]) > AXIS_ANGLE_TOL
        or math.hypot(T[1, 3], T[2, 3]) > length_tol(abs(a))
    ):
        return None
    return a, math.atan2(-float(T[1, 2]), float(T[2, 2]))


def convert_table(
    joints: Sequence[Joint],
    source: Convention,
    target: Convention,
    base: FloatArray,
    tool: FloatArray,
) -> tuple[tuple[Joint, ...], FloatArray, FloatArray]:
    """Rewrite a DH table in another convention, keeping FK unchanged.

    Args:
        joints: Rows in the ``source`` convention.
        source: Convention of ``joints``.
        target: Convention wanted.
        base: ``(4, 4)`` base transform of the source model.
        tool: ``(4, 4)`` tool transform of the source model.

    Returns:
        ``(joints, base, tool)`` of the equivalent model in ``target``.
    """
    src, dst = check_convention(source), check_convention(target)
    rows = tuple(joints)
    base = np.array(base, dtype=float)
    tool = np.array(tool, dtype=float)
    if src == dst or not rows:
        return rows, base, tool
    pairs = [(j.a, j.alpha) for j in rows]
    if src == "standard":
        shifted = [(0.0, 0.0), *pairs[:-1]]
        a_n, alpha_n = pairs[-1]
        tool = rx_tx(alpha_n, a_n) @ tool
    else:
        last = x_screw(tool)
        shifted = [*pairs[1:], (0.0, 0.0) if last is None else last]
        if last is not None:  # what is left of the tool: I, but for round-off
            a_n, alpha_n = last
            tool = snap(rx_tx(-alpha_n, -a_n) @ tool)
        a_0, alpha_0 = pairs[0]
        base = base @ rx_tx(alpha_0, a_0)
    new = tuple(
        dataclasses.replace(j, a=a, alpha=alpha)
        for j, (a, alpha) in zip(rows, shifted, strict=True)
    )
    return new, base, tool
