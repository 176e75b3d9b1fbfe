"""Three-parallel 6R arms (UR type): the kernels' parameters, tolerances and vector helpers.

``params`` holds the arm as ``NV`` vectors (rows ``V_*`` of
``params[:3 NV].reshape(NV, 3)``, base frame, at q = 0), then scalars
(``P_*``); :mod:`kinematica.ik.analytic.parallel` packs it. The method is
described in :mod:`.parallel_pairs` (the pairs ``(q1, q5)``),
:mod:`.parallel_quartic` (axes 5 and 6 apart) and :mod:`.parallel` (the rest).
"""

from __future__ import annotations

from kinematica.kernels._numba import Array, inline_kernel, kernel
from kinematica.kernels.geometry import Vec3
from kinematica.kernels.trig import sincos

__all__ = [
    "CONTINUUM_TOL",
    "DOUBLE_ROOT_TOL",
    "MODE_GENERAL",
    "MODE_MEET",
    "MODE_PARALLEL",
    "NEAR_TOL",
    "NV",
    "PAIR_FREE_Q1",
    "PAIR_NONE",
    "PAIR_ROOT",
    "P_SIZE",
    "axis2_now",
    "cross2",
    "dot",
    "row",
    "store_pair",
]

# --- params: vectors (rows of params[:3 NV].reshape(NV, 3)), base frame, q = 0
V_K = 0  # k: direction of axes 2, 3, 4 (along axis 2)
V_H1 = 1  # axis 1 direction
V_P1 = 2  # a point on axis 1
V_KPAR = 3  # (h1·k) h1: k1 = kpar + cos q1 kperp + sin q1 hk
V_KPERP = 4  # k - kpar
V_HK = 5  # h1 × k
V_H5 = 6  # axis 5 direction
V_P5 = 7  # on axis 5: foot of the common normal with axis 6 (their meeting point)
V_H6 = 8  # axis 6 direction
V_P6 = 9  # on axis 6: foot of the common normal with axis 5
V_H6PAR = 10  # (h5·h6) h5: R5 h6 = h6par + cos q5 h6perp + sin q5 h5xh6
V_H6PERP = 11  # h6 - h6par
V_H5XH6 = 12  # h5 × h6
V_P2 = 13  # a point on axis 2
V_P4 = 14  # a point on axis 4
V_E1 = 15  # unit vector across k: plane coordinates are (·e1, ·e2)
V_E2 = 16  # k × e1
V_RM = 17  # 3 rows: R_M, the tool rotation at q = 0
V_TM = 20  # t_M, the tool position at q = 0
V_P1S = 21  # on axis 1: foot of the common normal with axis 2
V_A6 = 22  # on axis 6: |G(a6) - p1s| <= P_BOUND for every reachable target
NV = 23
# --- params: scalars
P_MODE = 3 * NV  # MODE_*
P_EQ1 = P_MODE + 1  # D1, E1, F1: k·R5 h6 = D1 cos q5 + E1 sin q5 + F1
P_EQ2 = P_EQ1 + 3  # D2, E2, F2: right side of (2), F2 including k·(p5 - p1)
P_MINV = P_EQ2 + 3  # 2x2 row-major inverse of [[D1, E1], [D2, E2]] (MODE_GENERAL)
P_WLO = P_MINV + 4  # 1 - |D1, E1| - F1, exactly (1 - the largest k·R5 h6)
P_WHI = P_WLO + 1  # 1 - |D1, E1| + F1, exactly (1 + the smallest k·R5 h6)
P_ARM = P_WHI + 1  # |A|, |B|, arg A, arg B: A, B plane coordinates of p3 - p2, p4 - p3
P_ZUP = P_ARM + 4  # plane coordinates of h1 × k ("elbow up" side)
P_SIGN3 = P_ZUP + 2  # h3·k = ±1
P_SIGN4 = P_SIGN3 + 1  # h4·k = ±1
P_BOUND = P_SIGN4 + 1  # reach bound about p1s (m)
P_LIP = P_BOUND + 1  # |h1·k| + |kperp|: (2)'s sides move at most this per metre of target
P_SCALE = P_LIP + 1  # size of the arm (m), for relative tolerances
P_Q1REP = P_SCALE + 1  # q1 given when q1 is free (middle of its limits)
P_Q2REP = P_Q1REP + 1  # q2 given when q2 is free
P_SIZE = P_Q2REP + 1

MODE_MEET, MODE_PARALLEL, MODE_GENERAL = 0, 1, 2
# What a pair is (``kinds``): none, a root, or a representative of a
# continuum in which q1 turns freely (the other joints following it).
PAIR_NONE, PAIR_ROOT, PAIR_FREE_Q1 = 0, 1, 2

#: A point within this fraction of the arm's size from an axis, or two unit
#: vectors within this sine of parallel, is on it: the solutions form a
#: continuum (q1 free with the wrist point on axis 1; q6 free with axis 6
#: along k; q2 free with axis 4 on axis 2). Moving along such a continuum
#: moves the tool by at most about this fraction of the arm's size.
CONTINUUM_TOL = 1e-12
#: An equation missing a root by at most this (relative to the arm's size,
#: or absolute for unit vectors) may be a double root moved by round-off or a
#: target within tolerance of the workspace boundary: its least-squares angle
#: is proposed (the check decides by FK) and the target is marked near. Two
#: merging quartic roots split into a complex pair ``a ± bi`` with ``b`` about
#: the square root of such a miss: roots with ``|b| <= sqrt(NEAR_TOL) (1 + |t|)``
#: are polished as real, and kept when they then meet (1) and (2) to
#: ``TRIG_TOL`` (a root) or ``NEAR_TOL`` (near).
NEAR_TOL = 1e-6
#: The two roots of ``a cos θ + b sin θ = c`` (q1, or q5 when axes 5 and 6
#: are parallel) whose discriminant ``r² - c²`` is within this fraction of
#: ``r²`` are one double root: round-off of the target (~1e-16) splits a
#: double root into two roots about 1e-8 apart, which the other joints
#: amplify past the check's deduplication.
DOUBLE_ROOT_TOL = 1e-14


@inline_kernel
def row(V: Array, i: int) -> Vec3:
    """Row ``i`` of ``V (NV, 3)`` as three scalars (no view: no reference counting)."""
    return V[i, 0], V[i, 1], V[i, 2]


@inline_kernel
def dot(u: Vec3, v: Vec3) -> float:
    """``u · v``."""
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]


@inline_kernel
def cross2(u: Vec3, v: Vec3) -> float:
    """``|u × v|²`` (exact near parallel, unlike ``1 - (u·v)²``)."""
    x = u[1] * v[2] - u[2] * v[1]
    y = u[2] * v[0] - u[0] * v[2]
    z = u[0] * v[1] - u[1] * v[0]
    return x * x + y * y + z * z


@inline_kernel
def axis2_now(V: Array, c1: float, s1: float) -> Vec3:
    """``k1 = R1 k``, the direction of axis 2 after joint 1 turns by q1."""
    return (
        V[V_KPAR, 0] + c1 * V[V_KPERP, 0] + s1 * V[V_HK, 0],
        V[V_KPAR, 1] + c1 * V[V_KPERP, 1] + s1 * V[V_HK, 1],
        V[V_KPAR, 2] + c1 * V[V_KPERP, 2] + s1 * V[V_HK, 2],
    )


@kernel
def store_pair(pq: Array, m: int, q1: float, q5: float) -> None:
    """Pair ``m``: ``pq[m] = (q1, q5, cos q1, sin q1, cos q5, sin q5)``."""
    pq[m, 0] = q1
    pq[m, 1] = q5
    pq[m, 3], pq[m, 2] = sincos(q1)
    pq[m, 5], pq[m, 4] = sincos(q5)
