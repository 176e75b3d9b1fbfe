"""Joint limits in the numeric search: projection, bound scaling, an active set.

``bounds (n, 3)`` holds per joint the start of a revolute joint's 2π wrap
window and the lower and upper clamps (±inf where none; a full-turn revolute
joint is wrapped, never clamped).
"""

from __future__ import annotations

import math

from kinematica.kernels._numba import Array, kernel
from kinematica.kernels.arrays import copy2
from kinematica.kernels.fk import LINK_PRISMATIC
from kinematica.kernels.linalg import damped_least_squares

__all__ = [
    "BOUND_HI",
    "BOUND_LO",
    "BOUND_SCALE",
    "BOUND_WRAP",
    "active_step",
    "bound_scaling",
    "project",
]

#: Distance to a bound (rad or m) below which a joint heading for it slows
#: down: its column and step are scaled by ``√min(distance / BOUND_SCALE, 1)``.
#: Measured on the Panda within its limits: 10-15 % fewer evaluations than
#: blocking joints only once they sit on a bound, the same on the iiwa14.
BOUND_SCALE = 1.0

# Columns of ``bounds`` (n, 3): start of each revolute joint's 2π window, clamps.
BOUND_WRAP, BOUND_LO, BOUND_HI = range(3)

_TWO_PI = 2.0 * math.pi


@kernel
def project(links: Array, bounds: Array, q: Array) -> None:
    """Wrap revolute angles into their window, then clamp into the bounds (in place)."""
    for i in range(links.shape[0]):
        lo = bounds[i, BOUND_LO]
        hi = bounds[i, BOUND_HI]
        v = q[i]
        revolute = links[i, LINK_PRISMATIC] == 0.0
        if revolute:
            base = bounds[i, BOUND_WRAP]
            v = base + (v - base) % _TWO_PI
        if v > hi:
            v = lo if revolute and v - hi > lo + _TWO_PI - v else hi
        q[i] = lo if v < lo else v


@kernel
def bound_scaling(bounds: Array, q: Array, J: Array, ew: Array, Jb: Array, d: Array) -> None:
    """Coleman-Li scaling: ``d (n,)`` per joint, and the scaled Jacobian ``Jb = J · diag(d)``.

    ``d_j = √min(v_j / BOUND_SCALE, 1)``, ``v_j`` the distance to the bound
    that the steepest-descent direction ``Jᵀ W e`` pushes joint ``j``
    towards (no such bound: 1).
    """
    count = J.shape[0]
    for j in range(J.shape[1]):
        g = 0.0
        for r in range(count):
            g += J[r, j] * ew[r]
        v = BOUND_SCALE
        if g > 0.0:
            v = min(v, bounds[j, BOUND_HI] - q[j])
        elif g < 0.0:
            v = min(v, q[j] - bounds[j, BOUND_LO])
        d[j] = math.sqrt(max(v, 0.0) / BOUND_SCALE)
        for r in range(count):
            Jb[r, j] = J[r, j] * d[j]


@kernel
def active_step(
    bounds: Array,
    q: Array,
    J: Array,
    ew: Array,
    damping: float,
    Jb: Array,
    dq: Array,
    G: Array,
    b: Array,
    x: Array,
    L: Array,
) -> None:
    """A Gauss-Newton step ``dq`` holding the joints on a bound that it would carry out.

    Solved again without each such joint until no held joint would leave
    (an active set); ``damping`` is relative, as in :func:`damped_least_squares`.
    """
    n = q.shape[0]
    copy2(Jb, J)
    for _ in range(n + 1):
        damped_least_squares(Jb, ew, damping, dq, G, b, x, L)
        held = False
        for i in range(n):
            if (q[i] <= bounds[i, BOUND_LO] and dq[i] < 0.0) or (
                q[i] >= bounds[i, BOUND_HI] and dq[i] > 0.0
            ):
                for r in range(J.shape[0]):
                    Jb[r, i] = 0.0
                held = True
        if not held:
            return
