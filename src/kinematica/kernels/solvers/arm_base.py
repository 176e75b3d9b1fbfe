"""The arm part's parameters and the steps every shoulder geometry shares.

:mod:`kinematica.kernels.solvers.arm_point` places a point fixed after joint 3
by joints 1-3; this module holds its parameter layout (offsets ``A_*`` into the
flat ``params`` array, written by :mod:`kinematica.ik.analytic.arm_point`), what
it reports per target (``ST_*``), its tolerances, and the two steps every
geometry ends with: ``u(q3)`` on the frame of axis 2, and q1, q2 of a slot.
"""

from __future__ import annotations

import math

from kinematica.kernels._numba import Array, kernel
from kinematica.kernels.trig import sincos

__all__ = [
    "A_A",
    "A_CA",
    "A_COEF",
    "A_ELBOW",
    "A_FOURIER",
    "A_FRAME1",
    "A_G",
    "A_H1",
    "A_H2",
    "A_H3",
    "A_KIND",
    "A_P1",
    "A_P21",
    "A_PAR23",
    "A_PRISMATIC",
    "A_Q3",
    "A_REFINE",
    "A_ROOTS",
    "A_SA",
    "A_SCALE",
    "A_SHELL",
    "A_SIZE",
    "A_U",
    "A_XFRAME",
    "DOUBLE_ROOT_TOL",
    "HUGE_REACH",
    "KIND_GENERAL",
    "KIND_MEET",
    "KIND_PARALLEL",
    "NEAR_SET_TOL",
    "NEAR_TOL",
    "SINGULAR_TOL",
    "ST_AZIMUTH",
    "ST_FREE",
    "ST_GAP",
    "ST_NEAR",
    "ST_RHO",
    "ST_SIZE",
    "clamped_root",
    "slot",
    "values",
]

#: A point within this distance (times the arm's size) of axis 1 leaves q1
#: free; within it of axis 2, q2. Far below the default position tolerance
#: (1e-10 m): any representative of the free joint then reaches the target.
SINGULAR_TOL = 1e-12
#: A fold's signed distance (see :func:`clamped_root`) past 0 by at most this
#: fraction of its scale still gives candidates (mirrored) for the check, and
#: flags the target as near a fold (no real candidate is then no proof).
NEAR_TOL = 1e-6
#: A target within this distance (times the arm's size) of axis 1 or of axis
#: 2, or a wrist within this sine of aligning axes 4 and 6, is near a singular
#: set: the joint that turns about it is then determined only to round-off
#: over this (1e-7, the check's duplicate threshold), and the target is flagged.
NEAR_SET_TOL = 1e-9
#: A fold's signed distance within this fraction of its scale (and of the
#: arm's size) of 0 is round-off: a double root, one solution (as the check's
#: dedupe would have it), not two split by round-off and pulled further apart
#: by ill-conditioned joints.
DOUBLE_ROOT_TOL = 1e-14
#: Targets farther than this (metres) from axis 1's foot point are beyond any
#: arm: no squares are taken of their coordinates (1e154² overflows).
HUGE_REACH = 1e100

# Shoulder geometries (axes 1 and 2).
KIND_MEET, KIND_PARALLEL, KIND_GENERAL = 0.0, 1.0, 2.0

# Parameter offsets of the arm part (``params[0:A_SIZE]``).
A_KIND = 0  # KIND_*
A_PRISMATIC = 1  # 1.0: joint 3 slides
A_PAR23 = 2  # 1.0: axes 2 and 3 parallel
A_P1 = 3  # (3,) foot point of axis 1 (base frame)
A_FRAME1 = 6  # (3, 3) columns h1, a1, b1 (a frame of axis 1)
A_XFRAME = 15  # (4, 2) components along a1, b1 of h2, e1, e2, p2 - p1
A_COEF = 23  # (3, 4) u1, u2, H, L on the basis (1, cos q3, sin q3) or (1, q3, q3²)
A_A = 35  # distance of axes 1 and 2, along e1 (signed, ~0 when they meet)
A_CA = 36  # cos α = h1ᵀh2
A_SA = 37  # sin α = |h1 × h2|
A_G = 38  # g = h1ᵀe2
A_ELBOW = 39  # sign deciding "elbow up" (axes 2 ∥ 3)
A_ROOTS = 40  # (2, 2) sign of the q3 root of each slot (meet)
A_SCALE = 44  # a length of the arm's size (m), for tolerances
A_SHELL = 45  # (4,) r_lo, r_hi (bounds of |x - p1|), z_lo, z_hi (of h1ᵀ(x - p1))
A_FOURIER = 49  # (5, 5) [X0², X0, Y0², Y0, 1] -> Fourier coefficients of Pieper's F
A_H1 = 74  # (3,) axis directions h1, h2, h3, one after another
A_H2 = 77
A_H3 = 80
A_P21 = 83  # (3,) p2 - p1
A_U = 86  # (3, 3) u(q3) = U0 + U1 cos q3 + U2 sin q3 (or U0 + q3 U1)
# |u(q3)| in half-angle form (revolute): with m = |U0⊥| (U0 off axis 3), n = |U1|,
# |u|² = Dmin² + 4mn cos²ψ = Dmax² - 4mn sin²ψ, ψ = (q3 - β)/2; a slide: b = U0ᵀh3, m.
A_Q3 = 95  # (5,) β, m, n, Dmin, Dmax (revolute); b, m (slide)
A_REFINE = 100  # 1.0: a second pass settles nearly meeting axes 1, 2 or nearly parallel 2, 3
A_SIZE = 101

# What ``arm_point.place`` reports besides the candidates (``st``).
ST_FREE = 0  # (3,) 1.0 for q1, q2, q3 left free (a continuum)
ST_NEAR = 3  # 1.0: near a singular set or a fold
ST_GAP = 4  # lower bound of the distance of the target to the reachable points (m)
ST_RHO = 5  # distance of the target from axis 1 (m)
ST_AZIMUTH = 6  # the target's angle about axis 1 (rad), from the first axis of its frame
ST_SIZE = 7


@kernel
def clamped_root(diff: float, size: float, other: float, scale: float, st: Array) -> float:
    """``sqrt(diff · other)``, clamped where ``diff`` (a fold's signed distance) is ~0.

    A radicand is written as a signed difference ``diff`` (it vanishes at a
    fold, where two roots merge) times positive factors ``other``. ``diff``
    within ``DOUBLE_ROOT_TOL · (size + scale)`` of 0 is round-off: a double
    root (0 comes back). A negative ``diff`` down to ``-(NEAR_TOL · size +
    DOUBLE_ROOT_TOL · scale)`` gives ``sqrt(|diff| · other)``: the target is
    just past the fold as computed, but the arm's true roots (round-off, an
    axis offset of 1e-10 the closed form neglects) may lie on either side, so
    both mirrored candidates go to the check, which polishes them onto the
    true roots or rejects them. Below, NaN. A double root and a target past
    the fold raise ``st[ST_NEAR]``.

    Args:
        diff: The difference (e.g. of two lengths).
        size: Its scale (e.g. their sum).
        other: The other factors (>= 0; negative: NaN, another factor failed).
        scale: The arm's size (lengths) or 1: the round-off where ``size`` is ~0.
        st: Arm state.
    """
    roundoff = DOUBLE_ROOT_TOL * scale
    if abs(diff) <= DOUBLE_ROOT_TOL * size + roundoff:
        st[ST_NEAR] = 1.0
        return 0.0
    if diff < 0.0:
        if diff < -(NEAR_TOL * size + roundoff):
            return math.nan
        st[ST_NEAR] = 1.0
    if other < 0.0:
        return math.nan
    return math.sqrt(abs(diff) * other)


@kernel
def values(params: Array, q3: float, vals: Array) -> None:
    """``vals = [u1, u2, H, L]`` at q3 (rad; a slide's q3 in m)."""
    o = A_COEF
    if params[A_PRISMATIC] != 0.0:
        for j in range(4):
            vals[j] = params[o + j] + q3 * (params[o + 4 + j] + q3 * params[o + 8 + j])
    else:
        s3, c3 = sincos(q3)
        for j in range(4):
            vals[j] = params[o + j] + c3 * params[o + 4 + j] + s3 * params[o + 8 + j]


@kernel
def slot(
    params: Array,
    k: int,
    q3: float,
    v1: float,
    v2: float,
    vals: Array,
    st: Array,
    Q3: Array,
) -> None:
    """Slot ``k``: q2 turns ``(u1, u2)`` onto ``(v1, v2)``, q1 turns the point onto the target.

    A free q1 (target on axis 1) or q2 (point on axis 2) is set to 0 and
    flagged; a NaN anywhere makes the whole row NaN.
    """
    u1 = vals[0]
    u2 = vals[1]
    H = vals[2]
    scale = params[A_SCALE]
    tiny = SINGULAR_TOL * scale
    up2 = u1 * u1 + u2 * u2
    if up2 < (NEAR_SET_TOL * scale) ** 2:
        st[ST_NEAR] = 1.0
    if up2 < tiny * tiny:
        q2 = 0.0
        st[ST_FREE + 1] = 1.0
    else:
        q2 = math.atan2(u1 * v2 - u2 * v1, u1 * v1 + u2 * v2)
    if st[ST_RHO] < tiny:
        q1 = 0.0
        st[ST_FREE] = 1.0
    else:
        o = A_XFRAME
        xa = H * params[o] + v1 * params[o + 2] + v2 * params[o + 4] + params[o + 6]
        xb = H * params[o + 1] + v1 * params[o + 3] + v2 * params[o + 5] + params[o + 7]
        q1 = st[ST_AZIMUTH] - math.atan2(xb, xa)
        if q1 <= -math.pi:
            q1 += 2.0 * math.pi
        elif q1 > math.pi:
            q1 -= 2.0 * math.pi
    if math.isnan(q1 + q2 + q3 + v1 + v2):
        Q3[k, 0] = math.nan
        Q3[k, 1] = math.nan
        Q3[k, 2] = math.nan
    else:
        Q3[k, 0] = q1
        Q3[k, 1] = q2
        Q3[k, 2] = q3
