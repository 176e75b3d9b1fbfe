"""Rotation errors inside kernels: the SO(3) log, the angle between two rotations.

These are the only copies in kinematica of the rotation-vector formulas used
by the IK checks and the numeric solver (:mod:`kinematica.spatial` has the
numpy versions for users, tested against scipy).
"""

from __future__ import annotations

import math

from kinematica.kernels._numba import Array, inline_kernel, kernel

__all__ = [
    "ATAN_LINEAR",
    "SERIES_ANGLE",
    "angle_between",
    "inverse_right_jacobian",
    "pose_error",
    "rotvec",
    "wrap",
]

#: Below this rotation angle (rad) ``θ/2 · cot(θ/2)`` is evaluated by its
#: series: the closed form loses digits to cancellation there.
SERIES_ANGLE = 1e-2
#: ``atan x`` rounds to ``x`` for ``|x|`` below this (``x - atan x ≈ x³/3`` is
#: under half an ulp of ``x`` up to about 1.8e-8): the angle between two
#: nearly equal rotations is then one division, not an ``atan2``.
ATAN_LINEAR = 1e-8

_TWO_PI = 2.0 * math.pi


@kernel
def wrap(v: float) -> float:
    """An angle (rad) in (-π, π], unchanged when it already is."""
    if -math.pi < v <= math.pi:
        return v
    if math.pi < v <= 3.0 * math.pi:  # one turn off (the usual case): no fmod call
        w = v - _TWO_PI
    elif -3.0 * math.pi < v <= -math.pi:
        w = v + _TWO_PI
    elif math.isfinite(v):
        w = (v + math.pi) % _TWO_PI - math.pi  # in [-π, π)
    else:  # NaN (a branch without a solution) or inf: no fmod call
        return math.nan
    return math.pi if w <= -math.pi else w


@kernel
def rotvec(
    m00: float,
    m01: float,
    m02: float,
    m10: float,
    m11: float,
    m12: float,
    m20: float,
    m21: float,
    m22: float,
) -> tuple[float, float, float]:
    """Rotation vector ``(x, y, z)`` (rad) of a rotation matrix given by its entries.

    ``atan2`` of the sine and cosine of the angle: exact near 0; near π the
    axis comes from the column of the symmetric part with the largest
    diagonal, ``(M + Mᵀ)/2 − cos θ I = (1 − cos θ) n nᵀ``, its sign from the
    skew part.
    """
    v0 = 0.5 * (m21 - m12)
    v1 = 0.5 * (m02 - m20)
    v2 = 0.5 * (m10 - m01)
    sin = math.sqrt(v0 * v0 + v1 * v1 + v2 * v2)
    cos = 0.5 * (m00 + m11 + m22 - 1.0)
    angle = math.atan2(sin, cos)
    if cos >= 0.0:
        ratio = angle / sin if sin > 0.0 else 1.0
        return v0 * ratio, v1 * ratio, v2 * ratio
    s00, s11, s22 = m00 - cos, m11 - cos, m22 - cos
    if s00 >= s11 and s00 >= s22:
        n0, n1, n2 = s00, 0.5 * (m10 + m01), 0.5 * (m20 + m02)
    elif s11 >= s22:
        n0, n1, n2 = 0.5 * (m01 + m10), s11, 0.5 * (m21 + m12)
    else:
        n0, n1, n2 = 0.5 * (m02 + m20), 0.5 * (m12 + m21), s22
    norm = math.sqrt(n0 * n0 + n1 * n1 + n2 * n2)
    if n0 * v0 + n1 * v1 + n2 * v2 < 0.0:
        norm = -norm
    k = angle / norm
    return n0 * k, n1 * k, n2 * k


@inline_kernel
def angle_between(T: Array, Tt: Array) -> float:
    """Angle (rad) of ``Rtᵀ R`` for the rotation parts of ``T`` and ``Tt`` (exact near 0).

    ``atan2`` of its sine and cosine, or their ratio where that is the same
    to the last bit (``ATAN_LINEAR``).
    """
    tr = vx = vy = vz = 0.0
    for i in range(3):
        r0, r1, r2 = T[i, 0], T[i, 1], T[i, 2]
        t0, t1, t2 = Tt[i, 0], Tt[i, 1], Tt[i, 2]
        tr += t0 * r0 + t1 * r1 + t2 * r2
        vx += t2 * r1 - t1 * r2
        vy += t0 * r2 - t2 * r0
        vz += t1 * r0 - t0 * r1
    sin = 0.5 * math.sqrt(vx * vx + vy * vy + vz * vz)
    cos = 0.5 * (tr - 1.0)
    if cos > 0.0 and sin <= ATAN_LINEAR * cos:  # the checks' usual case: a tiny error
        return sin / cos
    return math.atan2(sin, cos)


@kernel
def _rows(A: Array, i: int, B: Array, j: int) -> float:
    """Row i of A's rotation part dotted with row j of B's: ``(A Bᵀ)[i, j]``."""
    return A[i, 0] * B[j, 0] + A[i, 1] * B[j, 1] + A[i, 2] * B[j, 2]


@kernel
def pose_error(T: Array, Tt: Array, e: Array) -> None:
    """``e (6,)``: ``p_t − p`` (m), then the rotation vector of ``R_t Rᵀ`` (rad), base frame."""
    e[0] = Tt[0, 3] - T[0, 3]
    e[1] = Tt[1, 3] - T[1, 3]
    e[2] = Tt[2, 3] - T[2, 3]
    e[3], e[4], e[5] = rotvec(
        _rows(Tt, 0, T, 0),
        _rows(Tt, 0, T, 1),
        _rows(Tt, 0, T, 2),
        _rows(Tt, 1, T, 0),
        _rows(Tt, 1, T, 1),
        _rows(Tt, 1, T, 2),
        _rows(Tt, 2, T, 0),
        _rows(Tt, 2, T, 1),
        _rows(Tt, 2, T, 2),
    )


@kernel
def inverse_right_jacobian(x: float, y: float, z: float, A: Array) -> None:
    """``A (3, 3) = J_r⁻¹(φ)`` of SO(3) at the rotation vector ``φ = (x, y, z)``."""
    th2 = x * x + y * y + z * z
    half = 0.5 * math.sqrt(th2)
    if half < 0.5 * SERIES_ANGLE:
        alpha = 1.0 - th2 / 12.0 - th2 * th2 / 720.0
        c = 1.0 / 12.0 + th2 / 720.0 + th2 * th2 / 30240.0
    else:
        alpha = half / math.tan(half)
        c = (1.0 - alpha) / th2
    hx, hy, hz = 0.5 * x, 0.5 * y, 0.5 * z
    A[0, 0], A[0, 1], A[0, 2] = alpha + c * x * x, c * x * y - hz, c * x * z + hy
    A[1, 0], A[1, 1], A[1, 2] = c * y * x + hz, alpha + c * y * y, c * y * z - hx
    A[2, 0], A[2, 1], A[2, 2] = c * z * x - hy, c * z * y + hx, alpha + c * z * z
