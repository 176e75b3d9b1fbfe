"""Exact conversion of a DH table between the standard and modified conventions.

The lecture notes: "las matrices de transformación intermedias varían, pero el resultado
final es el mismo". Because ``Tras(x, a)`` and ``Rot(x, α)`` commute, a standard
table regroups into a modified one by moving each row's ``(a, α)`` to the next
row; the last row's pair goes into the tool, and the first modified row's pair
into the base. The end-effector pose is the same for every q.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from kinematica.dh.joints import Convention, Joint, check_convention

__all__ = ["convert_table", "rx_tx"]

FloatArray = NDArray[np.float64]


def rx_tx(alpha: float, a: float) -> FloatArray:
    """``Rot(x, α) · Tras(x, a)`` (equal to ``Tras(x, a) · Rot(x, α)``): ``(4, 4)``."""
    ca, sa = math.cos(alpha), math.sin(alpha)
    return np.array([[1.0, 0, 0, a], [0, ca, -sa, 0], [0, sa, ca, 0], [0, 0, 0, 1.0]])


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
        shifted = [*pairs[1:], (0.0, 0.0)]
        a_0, alpha_0 = pairs[0]
        base = base @ rx_tx(alpha_0, a_0)
    new = tuple(
        dataclasses.replace(j, a=a, alpha=alpha)
        for j, (a, alpha) in zip(rows, shifted, strict=True)
    )
    return new, base, tool
