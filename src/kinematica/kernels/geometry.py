"""Small geometry inside kernels: rotations about axes, and the subproblems they pose.

The building blocks of the closed-form solvers (Paden-Kahan subproblems in
product-of-exponentials form): rotate a vector about a unit axis, the angle
that turns one vector onto another about an axis (SP1), and the two angles of
``a cos θ + b sin θ = c``.
"""

from __future__ import annotations

import math

from kinematica.kernels._numba import Array, inline_kernel, kernel

__all__ = [
    "TRIG_TOL",
    "Vec3",
    "add3",
    "rot",
    "rotate",
    "sub3",
    "subproblem1",
    "trig_linear",
    "turn",
]

#: A 3-vector held as three scalars (a kernel keeps them in registers).
Vec3 = tuple[float, float, float]

#: ``a cos θ + b sin θ = c`` with ``|c|`` above ``hypot(a, b)`` by at most this
#: fraction is taken as touching (one double root) rather than unreachable: a
#: target on the boundary of the reachable set, computed by forward kinematics,
#: lands a few ulps on either side of it.
TRIG_TOL = 1e-10


@inline_kernel
def turn(
    kx: float, ky: float, kz: float, c: float, s: float, vx: float, vy: float, vz: float
) -> tuple[float, float, float]:
    """``R(k, θ) v`` (Rodrigues) for a unit axis ``k``, ``c = cos θ``, ``s = sin θ``.

    Scalars in and out: a hot loop keeps them in registers (an array view per
    call costs two atomic reference-count updates).
    """
    t = (1.0 - c) * (kx * vx + ky * vy + kz * vz)
    return (
        c * vx + s * (ky * vz - kz * vy) + t * kx,
        c * vy + s * (kz * vx - kx * vz) + t * ky,
        c * vz + s * (kx * vy - ky * vx) + t * kz,
    )


@inline_kernel
def rot(k: Vec3, c: float, s: float, v: Vec3) -> Vec3:
    """``R(k, θ) v`` (:func:`turn`) for a unit axis ``k``, ``c = cos θ``, ``s = sin θ``."""
    return turn(k[0], k[1], k[2], c, s, v[0], v[1], v[2])


@inline_kernel
def add3(u: Vec3, v: Vec3) -> Vec3:
    """``u + v``."""
    return u[0] + v[0], u[1] + v[1], u[2] + v[2]


@inline_kernel
def sub3(u: Vec3, v: Vec3) -> Vec3:
    """``u - v``."""
    return u[0] - v[0], u[1] - v[1], u[2] - v[2]


@kernel
def rotate(k: Array, c: float, s: float, v: Array, out: Array) -> None:
    """``out = R(k, θ) v`` (:func:`turn`) for ``k (3,)``, ``v (3,)``, ``out (3,)``."""
    out[0], out[1], out[2] = turn(k[0], k[1], k[2], c, s, v[0], v[1], v[2])


@kernel
def subproblem1(p1: Array | Vec3, p2: Array | Vec3, k: Array | Vec3) -> float:
    """SP1: the angle ``θ`` with ``R(k, θ) p1 = p2`` (closest when not exact).

    The vectors are ``(3,)`` arrays or :data:`Vec3` tuples.

    If ``p1`` or ``p2`` lies on the axis every angle is as good and 0 comes
    back (``atan2(0, 0)``). Both vectors are projected across ``k`` first:
    near the axis their parts along it would swamp the small cross parts.
    """
    kp = k[0] * p1[0] + k[1] * p1[1] + k[2] * p1[2]
    a0 = p1[0] - kp * k[0]
    a1 = p1[1] - kp * k[1]
    a2 = p1[2] - kp * k[2]
    kq = k[0] * p2[0] + k[1] * p2[1] + k[2] * p2[2]
    b0 = p2[0] - kq * k[0]
    b1 = p2[1] - kq * k[1]
    b2 = p2[2] - kq * k[2]
    x = a1 * b2 - a2 * b1
    y = a2 * b0 - a0 * b2
    z = a0 * b1 - a1 * b0
    return math.atan2(k[0] * x + k[1] * y + k[2] * z, a0 * b0 + a1 * b1 + a2 * b2)


@kernel
def trig_linear(a: float, b: float, c: float, out: Array) -> int:
    """The angles ``θ`` with ``a cos θ + b sin θ = c``, in ``out (2,)``.

    With ``r = hypot(a, b)`` and ``s = sqrt(r² - c²)``: ``θ = atan2(b c ± a s,
    a c ∓ b s)`` (no ``acos``: no loss of accuracy away from the double root).
    ``|c| > r`` by at most ``TRIG_TOL`` relative is a double root.

    Returns:
        1 (two solutions, possibly a double root), 0 when ``|c| > r``
        beyond the tolerance (``out`` holds the least-squares angle twice), or
        -1 when ``a = b = 0`` (every angle solves ``c = 0``, none ``c != 0``;
        ``out`` holds 0).
    """
    r2 = a * a + b * b
    if r2 == 0.0:
        out[0] = 0.0
        out[1] = 0.0
        return -1
    disc = r2 - c * c
    exact = disc >= -2.0 * TRIG_TOL * r2
    s = math.sqrt(disc) if disc > 0.0 else 0.0
    out[0] = math.atan2(b * c + a * s, a * c - b * s)
    out[1] = math.atan2(b * c - a * s, a * c + b * s)
    return 1 if exact else 0
