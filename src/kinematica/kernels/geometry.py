"""Small geometry inside kernels: rotations about axes, and the subproblems they pose.

The building blocks of the closed-form solvers (Paden-Kahan subproblems in
product-of-exponentials form): rotate a vector about a unit axis, the angle
that turns one vector onto another about an axis (SP1), and the two angles of
``a cos θ + b sin θ = c``.
"""

from __future__ import annotations

import math

from kinematica.kernels._numba import Array, kernel

__all__ = ["TRIG_TOL", "rotate", "subproblem1", "trig_linear"]

#: ``a cos θ + b sin θ = c`` with ``|c|`` above ``hypot(a, b)`` by at most this
#: fraction is taken as touching (one double root) rather than unreachable: a
#: target on the boundary of the reachable set, computed by forward kinematics,
#: lands a few ulps on either side of it.
TRIG_TOL = 1e-10


@kernel
def rotate(k: Array, c: float, s: float, v: Array, out: Array) -> None:
    """``out = R(k, θ) v`` (Rodrigues) for a unit axis ``k (3,)``, ``c = cos θ``, ``s = sin θ``."""
    kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2]
    x = k[1] * v[2] - k[2] * v[1]
    y = k[2] * v[0] - k[0] * v[2]
    z = k[0] * v[1] - k[1] * v[0]
    t = (1.0 - c) * kv
    out[0] = c * v[0] + s * x + t * k[0]
    out[1] = c * v[1] + s * y + t * k[1]
    out[2] = c * v[2] + s * z + t * k[2]


@kernel
def subproblem1(p1: Array, p2: Array, k: Array) -> float:
    """SP1: the angle ``θ`` with ``R(k, θ) p1 = p2`` (closest when not exact).

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
