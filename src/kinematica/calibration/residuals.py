"""Residuals of a calibration and their analytic Jacobian.

A pose measurement gives six residuals, a point three::

    r_position    = (p(q; δ) − p_measured) / σ_position           (m / m)
    r_orientation = log(R(q; δ) · R_measuredᵀ) / σ_orientation    (rad / rad, world frame)

each divided by the measurement's standard deviation (``noise``), so that the residuals
are numbers of standard deviations: one pooled variance describes both kinds, and a
robust loss's knee (``f_scale``) is a count of standard deviations.

The Jacobian is analytic. A parameter moves everything after it by a twist about or
along a world axis (:meth:`ErrorModel.twists`): a turn ``u`` about an axis through
``o`` moves the tool point by ``u × (p − o)`` and its rotation residual by
``J_l⁻¹(φ) u`` (:func:`~kinematica.calibration.model.inv_left_jacobian`); a slide along
``u`` moves the point by ``u`` and leaves the rotation.
"""

from __future__ import annotations

from typing import Literal

import numpy as np
from numpy.typing import NDArray

from kinematica.calibration.model import ErrorModel, inv_left_jacobian, log_rotation

__all__ = ["Kind", "Measurements", "jacobian", "pose_errors", "residuals"]

FloatArray = NDArray[np.float64]
Kind = Literal["pose", "position"]


class Measurements:
    """Joint readings and what was measured, with the noise that scales the residuals.

    Attributes:
        q: ``(m, n)`` joint readings (rad, m).
        measured: ``(m, 4, 4)`` tool poses or ``(m, 3)`` tool points (world frame, m).
        kind: ``"pose"`` or ``"position"``.
        noise: ``(σ_position (m), σ_orientation (rad))``.
    """

    def __init__(self, q: FloatArray, measured: FloatArray, kind: Kind, noise: tuple[float, float]):
        self.q = q
        self.measured = measured
        self.kind = kind
        self.noise = noise
        self.point = measured[:, :3, 3] if kind == "pose" else measured
        self.rotation_t = np.swapaxes(measured[:, :3, :3], -1, -2) if kind == "pose" else None

    @property
    def per_pose(self) -> int:
        """Residuals per measurement: 6 for a pose, 3 for a point."""
        return 6 if self.kind == "pose" else 3

    @property
    def count(self) -> int:
        """Measurements m."""
        return int(self.q.shape[0])


def pose_errors(T: FloatArray, data: Measurements) -> tuple[FloatArray, FloatArray | None]:
    """``(Δp (m, 3) in m, φ (m, 3) in rad or None)``: model minus measurement."""
    dp = T[:, :3, 3] - data.point
    if data.rotation_t is None:
        return dp, None
    return dp, log_rotation(T[:, :3, :3] @ data.rotation_t)


def residuals(model: ErrorModel, delta: FloatArray, data: Measurements) -> FloatArray:
    """``(m · k,)`` the scaled residuals at ``δ`` (k = 6 per pose, 3 per point)."""
    dp, phi = pose_errors(model.fk(delta, data.q), data)
    sp, sr = data.noise
    if phi is None:
        return (dp / sp).ravel()
    return np.concatenate([dp / sp, phi / sr], axis=1).ravel()


def jacobian(
    model: ErrorModel,
    delta: FloatArray,
    data: Measurements,
    columns: NDArray[np.intp] | None = None,
) -> tuple[FloatArray, FloatArray]:
    """The scaled residuals and their Jacobian at ``δ``, analytic.

    Args:
        model: The error model.
        delta: ``(p,)`` all the parameters.
        data: The measurements.
        columns: The parameters to differentiate by (indices), default all.

    Returns:
        ``(r (m · k,), J (m · k, len(columns)))``.
    """
    W, T = model.frames(delta, data.q)
    axis, point, rotation = model.twists(delta, W)
    if columns is not None:
        axis, point, rotation = axis[:, columns], point[:, columns], rotation[columns]
    tip = T[:, None, :3, 3]
    turn = rotation[None, :, None]
    dp = np.where(turn, np.cross(axis, tip - point), axis)  # (m, p, 3)
    dp_phi = pose_errors(T, data)
    sp, sr = data.noise
    m = data.count
    if dp_phi[1] is None:
        r = (dp_phi[0] / sp).ravel()
        J = np.swapaxes(dp / sp, 1, 2).reshape(m * 3, -1)
        return r, J
    dphi = (axis @ np.swapaxes(inv_left_jacobian(dp_phi[1]), 1, 2)) * turn
    r = np.concatenate([dp_phi[0] / sp, dp_phi[1] / sr], axis=1).ravel()
    J = np.concatenate([dp / sp, dphi / sr], axis=2)  # (m, p, 6)
    return r, np.swapaxes(J, 1, 2).reshape(m * 6, -1)
