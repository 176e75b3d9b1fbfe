"""Second-order and other-frame velocity kinematics: Hessian, J̇, spatial and exponential Jacobians.

Everything here is a function of the geometric Jacobian ``J = robot.jacobian(q)``
(``(..., 6, n)``, base frame: rows ``vx, vy, vz`` of the tool origin, then
``ωx, ωy, ωz``) and of the tool pose.

The Hessian follows Haviland & Corke, "Manipulator Differential Kinematics,
Part I" (2023), written for both joint kinds. Moving joint ``j`` turns (or,
prismatic, shifts) everything beyond it: a point beyond it at ``ω_j × (x − o_j)``
(or ``v_j``), a direction beyond it at ``ω_j × d`` (or not at all). Joint ``i``'s
axis lies beyond joint ``j`` exactly when ``j < i``; the tool origin lies beyond
every joint and moves at ``v_j``. With ``v_i, ω_i`` the columns of ``J`` (``ω = 0``
for a prismatic joint) that gives, for ``∂J_i/∂q_j``::

    j <  i:  [ω_j × v_i ;  ω_j × ω_i]
    j >= i:  [ω_i × v_j ;  0        ]

Why numpy and not the C++ core: each derivative is ``n²`` cross products of the
columns the core's one chain walk already returned, nothing walks the chain
again, and numpy does them over a whole batch at once. Measured on a PUMA 560:
44 µs for one configuration (the SVD a resolved-rate step takes anyway costs
12 µs), 86 ms for 10⁴ (9 µs each, ~150 times the Jacobian's own cost). Should
batches of Hessians become hot, these formulas are a second pass over the
columns in ``jacobian.hpp``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from kinematica.errors import KinematicaError
from kinematica.spatial import rotvec_from_matrix

if TYPE_CHECKING:
    from kinematica.robot.kinematics import RobotKinematics

__all__ = [
    "EXP_SERIES_ANGLE",
    "Frame",
    "exp_jacobian",
    "hessian",
    "jacobian_dot",
    "left_jacobian_inverse_coefficient",
    "spatial_from_base",
]

FloatArray = NDArray[np.float64]

#: Frames of a Jacobian: ``"base"`` (tool-origin velocity and ω in base axes),
#: ``"tool"`` (the same in tool axes: the body Jacobian) or ``"spatial"`` (the
#: spatial twist: ω and the velocity of the body point at the base origin).
Frame = Literal["base", "tool", "spatial"]

#: Below this rotation angle (rad) the coefficient of ``[φ]×²`` in the inverse
#: left Jacobian of SO(3) (:func:`left_jacobian_inverse_coefficient`) comes from
#: its Taylor series: the closed form ``(1 − (θ/2)·cot(θ/2))/θ²`` loses digits to
#: cancellation for small θ (relative error ~eps·12/θ², 3e-13 at 0.1), while the
#: four-term series' first omitted term is ~2.5e-7·θ⁸ relative (3e-15 at 0.1).
EXP_SERIES_ANGLE = 0.1

_FRAMES = ("base", "tool", "spatial")


def _columns(J: FloatArray) -> tuple[FloatArray, FloatArray]:
    """``(v, ω)``, each ``(..., n, 3)``: the columns of ``J`` split in halves."""
    cols = np.swapaxes(J, -1, -2)
    return cols[..., :3], cols[..., 3:]


def _stack(top: FloatArray, bottom: FloatArray) -> FloatArray:
    """``(..., 6, n, n)`` from the halves ``(..., n, n, 3)`` indexed ``[i, j]``."""
    return np.moveaxis(np.concatenate([top, bottom], axis=-1), -1, -3)


def spatial_from_base(J: FloatArray, p: FloatArray) -> FloatArray:
    """The spatial Jacobian from the base-frame one and the tool origin ``p``.

    The spatial twist is ``(v_s, ω)`` with ``v_s = ṗ + p × ω``, the velocity of
    the body point that passes through the base origin. It equals ``Ad_T`` times
    the tool (body) twist, ``Ad_T = [[R, [p]× R], [0, R]]`` in this row order.

    Args:
        J: ``(..., 6, n)`` geometric Jacobian, base frame.
        p: ``(..., 3)`` tool origin (m, base frame).

    Returns:
        ``(..., 6, n)`` spatial Jacobian (base axes).
    """
    v, w = _columns(J)
    vs = v + np.cross(p[..., None, :], w)
    return np.concatenate([np.swapaxes(vs, -1, -2), np.swapaxes(w, -1, -2)], axis=-2)


def _cross(a: FloatArray, b: FloatArray) -> FloatArray:
    """``a × b`` over the last axis, broadcasting (component-wise: faster than np.cross)."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=-1)


def _hessian_base(J: FloatArray) -> FloatArray:
    """``(..., 6, n, n)``: ``H[..., :, i, j] = ∂J_i/∂q_j`` in the base frame."""
    v, w = _columns(J)
    n = J.shape[-1]
    wj, wi = w[..., None, :, :], w[..., :, None, :]  # broadcast to [i, j]
    vj, vi = v[..., None, :, :], v[..., :, None, :]
    before = np.tri(n, k=-1, dtype=bool)[..., None]  # [i, j] with j < i
    top = np.where(before, _cross(wj, vi), _cross(wi, vj))
    bottom = np.where(before, _cross(wj, wi), 0.0)
    return _stack(top, bottom)


def hessian(robot: RobotKinematics, q: ArrayLike, frame: Frame = "base") -> FloatArray:
    """The Jacobian's derivatives with respect to the joints (the manipulator Hessian).

    ``H[..., :, i, j] = ∂J[..., :, i]/∂q_j`` for the geometric Jacobian ``J`` of
    ``robot.jacobian(q, frame)`` (``frame="spatial"`` included). The position
    rows are symmetric in ``i, j`` (second derivatives of the tool origin); the
    rotation rows are not. ``J̇ = H · q̇`` over the last axis (:func:`jacobian_dot`).

    Args:
        robot: The robot.
        q: ``(..., n)`` joint values (rad, m).
        frame: ``"base"`` (default), ``"tool"`` or ``"spatial"``.

    Returns:
        ``(..., 6, n, n)``, per rad or m of each of the two joints.
    """
    if frame not in _FRAMES:
        raise KinematicaError(
            f"frame must be 'base', 'tool' or 'spatial', got {frame!r}", arg="frame"
        )
    J = robot.jacobian(q)
    H = _hessian_base(J)
    if frame == "base":
        return H
    v, w = _columns(J)
    if frame == "spatial":
        # v_s,i = v_i + p × ω_i: ∂/∂q_j adds v_j × ω_i + p × ∂ω_i/∂q_j (∂p/∂q_j = v_j).
        p = robot.fk(q)[..., :3, 3]
        dv = np.moveaxis(H[..., :3, :, :], -3, -1)
        dw = np.moveaxis(H[..., 3:, :, :], -3, -1)
        top = (
            dv + _cross(v[..., None, :, :], w[..., :, None, :]) + _cross(p[..., None, None, :], dw)
        )
        return _stack(top, dw)
    # tool: J_t = Rᵀ J blockwise and ∂Rᵀ/∂q_j x = −Rᵀ (ω_j × x).
    R = robot.fk(q)[..., :3, :3]
    wj = w[..., None, :, :]
    dv = np.moveaxis(H[..., :3, :, :], -3, -1) - _cross(wj, v[..., :, None, :])
    dw = np.moveaxis(H[..., 3:, :, :], -3, -1) - _cross(wj, w[..., :, None, :])
    Rt = np.swapaxes(R, -1, -2)[..., None, None, :, :]
    return _stack((Rt @ dv[..., None])[..., 0], (Rt @ dw[..., None])[..., 0])


def jacobian_dot(
    robot: RobotKinematics, q: ArrayLike, qd: ArrayLike, frame: Frame = "base"
) -> FloatArray:
    """The Jacobian's time derivative ``J̇ = Σ_j (∂J/∂q_j) q̇_j`` along a motion.

    So the tool acceleration is ``J q̈ + J̇ q̇`` (in the chosen frame).

    Args:
        robot: The robot.
        q: ``(..., n)`` joint values (rad, m).
        qd: ``(..., n)`` joint velocities (rad/s, m/s); broadcasts against ``q``.
        frame: ``"base"`` (default), ``"tool"`` or ``"spatial"``.

    Returns:
        ``(..., 6, n)`` (per s).
    """
    H = hessian(robot, q, frame)
    qda = robot.check_q(qd, "qd")
    out: FloatArray = np.einsum("...kij,...j->...ki", H, qda)
    return out


def left_jacobian_inverse_coefficient(theta: ArrayLike) -> FloatArray:
    """``(1 − (θ/2) cot(θ/2)) / θ²``, the ``[φ]×²`` term of ``J_l(φ)⁻¹``.

    Finite for ``0 <= θ < 2π``; its series is ``Σ_k |B_2k| θ^(2k−2) / (2k)!``
    (Bernoulli numbers), used below :data:`EXP_SERIES_ANGLE`.

    Args:
        theta: ``(...)`` rotation angles (rad), ``>= 0``.

    Returns:
        ``(...)`` the coefficient (1/rad²).
    """
    theta = np.asarray(theta, dtype=float)
    t2 = theta * theta
    series = 1.0 / 12.0 + t2 * (1.0 / 720.0 + t2 * (1.0 / 30240.0 + t2 / 1209600.0))
    safe = np.where(theta < EXP_SERIES_ANGLE, 1.0, theta)
    half = safe / 2.0
    closed = (1.0 - half * np.cos(half) / np.sin(half)) / (safe * safe)
    out: FloatArray = np.where(theta < EXP_SERIES_ANGLE, series, closed)
    return out


def exp_jacobian(robot: RobotKinematics, q: ArrayLike) -> FloatArray:
    """Analytic Jacobian in exponential coordinates: rates of ``(p, φ)``.

    ``φ = km.rotvec_from_matrix(R)`` is the rotation vector of the tool
    orientation ``R = exp([φ]×)`` in the base frame, ``|φ| <= π``. Its rate
    follows from the base-frame angular velocity by the inverse *left* Jacobian
    of SO(3) (equivalently the inverse right Jacobian of the tool-frame ω):

        φ̇ = J_l(φ)⁻¹ ω,  J_l(φ)⁻¹ = I − ½[φ]× + (1 − (θ/2) cot(θ/2))/θ² · [φ]×²

    so ``J_a = blockdiag(I, J_l(φ)⁻¹) · J`` with ``J`` the base-frame geometric
    Jacobian. The map is regular for every ``θ = |φ| < 2π``, so unlike the Euler
    rates it has no singularity in the principal range; at ``θ = π`` the
    rotation vector itself jumps (``φ`` and ``−φ`` name the same rotation) and
    the rates are those of the returned ``φ``.

    Args:
        robot: The robot.
        q: ``(..., n)`` joint values (rad, m).

    Returns:
        ``(..., 6, n)``: rows 0-2 ``ṗ`` (m per rad or m), rows 3-5 ``φ̇`` (rad per rad or m).
    """
    J = robot.jacobian(q)
    phi = rotvec_from_matrix(robot.fk(q)[..., :3, :3])
    theta = np.linalg.norm(phi, axis=-1)
    c = left_jacobian_inverse_coefficient(theta)[..., None, None]
    _, w = _columns(J)
    ph = np.broadcast_to(phi[..., None, :], w.shape)
    p_x_w = _cross(ph, w)
    rates = w - 0.5 * p_x_w + c * _cross(ph, p_x_w)
    Ja = J.copy()
    Ja[..., 3:, :] = np.swapaxes(rates, -1, -2)
    return Ja
