"""The checks of a calibration's input: shapes, numbers, joint limits, rigid poses."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import ArgumentError, DimensionError

if TYPE_CHECKING:
    from kinematica.robot import Robot

__all__ = ["ROTATION_TOL", "check_kind", "check_measured", "check_noise", "check_readings"]

FloatArray = NDArray[np.float64]

#: A measured rotation whose ``RᵀR`` differs from the identity by more than this (any
#: entry), or whose determinant is not +1 within it, is not a rotation.
ROTATION_TOL = 1e-6
KINDS = ("pose", "position")


def check_kind(kind: object) -> str:
    """``"pose"`` or ``"position"``, else :class:`ArgumentError`."""
    if kind not in KINDS:
        raise ArgumentError(f"kind must be 'pose' or 'position', got {kind!r}")
    return str(kind)


def check_readings(robot: Robot, q: ArrayLike) -> FloatArray:
    """``(m, n)`` joint readings: finite, within the robot's own limits.

    Raises:
        DimensionError: not ``(m, n)``, or NaN/inf.
        ArgumentError: a reading beyond its joint's limits (row and joint named).
    """
    try:
        qa = np.array(q, dtype=float)
    except (TypeError, ValueError) as exc:
        raise DimensionError(f"q must be numbers of shape (m, {robot.dof}): {exc}") from None
    if qa.ndim != 2 or qa.shape[1] != robot.dof:
        raise DimensionError(
            f"q must have shape (m, {robot.dof}), one row of {robot.dof} joint readings per "
            f"measurement of {robot.name}, got shape {qa.shape}"
        )
    bad = np.argwhere(~np.isfinite(qa))
    if bad.size:
        raise DimensionError(f"q holds NaN or inf at row {bad[0][0]}, joint {bad[0][1] + 1}")
    lim = robot.chain.own_limits
    outside = np.argwhere((qa < lim[:, 0]) | (qa > lim[:, 1]))
    if outside.size:
        row, j = (int(v) for v in outside[0])
        unit = "m" if robot.links[j].type == "P" else "rad"
        raise ArgumentError(
            f"q: row {row}, joint {j + 1} = {qa[row, j]:.6g} {unit} is outside its limits "
            f"[{lim[j, 0]:.6g}, {lim[j, 1]:.6g}] {unit} ({len(outside)} readings outside): "
            "a reading the arm cannot give, most likely a unit or column slip"
        )
    return qa


def check_measured(measured: ArrayLike, kind: str, m: int) -> FloatArray:
    """``(m, 4, 4)`` rigid poses or ``(m, 3)`` points, finite.

    Raises:
        DimensionError: wrong shape, NaN/inf, or a pose that is not rigid.
    """
    shape = (m, 4, 4) if kind == "pose" else (m, 3)
    try:
        M = np.array(measured, dtype=float)
    except (TypeError, ValueError) as exc:
        raise DimensionError(f"measured must be numbers of shape {shape}: {exc}") from None
    if M.shape != shape:
        what = "one 4x4 pose" if kind == "pose" else "one point (x, y, z)"
        raise DimensionError(
            f"measured must have shape {shape}, {what} per row of q (kind={kind!r}), "
            f"got shape {M.shape}"
        )
    bad = np.argwhere(~np.isfinite(M))
    if bad.size:
        raise DimensionError(f"measured holds NaN or inf in measurement {bad[0][0]}")
    if kind == "pose":
        R = M[:, :3, :3]
        gram = np.abs(np.swapaxes(R, 1, 2) @ R - np.eye(3)).max(axis=(1, 2))
        det = np.linalg.det(R)
        wrong = np.flatnonzero((gram > ROTATION_TOL) | (np.abs(det - 1.0) > ROTATION_TOL))
        last = np.abs(M[:, 3] - (0.0, 0.0, 0.0, 1.0)).max(axis=1) > 0.0
        wrong = np.union1d(wrong, np.flatnonzero(last))
        if wrong.size:
            raise DimensionError(
                f"measured pose {wrong[0]} is not a rigid transform (its rotation part is "
                f"not orthonormal within {ROTATION_TOL:g} or its last row is not 0 0 0 1)"
            )
    return M


def check_noise(noise: object) -> tuple[float, float]:
    """``(σ_position (m), σ_orientation (rad))``, both positive and finite."""
    try:
        values = tuple(float(v) for v in noise)  # type: ignore[attr-defined]
    except (TypeError, ValueError):
        raise ArgumentError(
            f"noise must be (position in m, orientation in rad), got {noise!r}"
        ) from None
    if len(values) != 2 or not all(np.isfinite(v) and v > 0 for v in values):
        raise ArgumentError(
            f"noise must be two positive numbers (position in m, orientation in rad), got {noise!r}"
        )
    return values[0], values[1]
