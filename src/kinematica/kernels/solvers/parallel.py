"""Three-parallel 6R arms (UR type), second half: every solution of one target.

For each pair ``(q1, q5)`` of :mod:`kinematica.kernels.solvers.parallel_pairs`:

* q6 by subproblem 1: ``R(h6, -q6) R5ᵀ k = R_Gᵀ k1`` (``R1ᵀ R_G = R234 R5 R6``
  and ``R234`` keeps ``k``);
* θ234, the angle of ``R234 = R1ᵀ R_G R6ᵀ R5ᵀ`` about ``k``;
* ``H = E1⁻¹ G E6⁻¹ E5⁻¹ = E2 E3 E4`` takes axis 4 (``p4``) where the planar
  triangle axis 2 -> axis 3 -> axis 4 must put it: q2 and q3 (two elbows),
  then ``q4 = σ4 (θ234 - q2 - σ3 q3)``.

Up to 8 solutions. Singular sets, all continua of solutions (``info`` marks
them and names the free joints; the candidates are representatives):

* the wrist aligned, axis 6 along ``k`` (sine below ``CONTINUUM_TOL``): q6
  turns with q2, q3, q4 (axes 2, 3, 4, 6 all parallel). The representative q6
  puts axis 4 at mid-reach of the triangle;
* axis 4 on axis 2 with equal links (the folded elbow): q2 turns with q4;
* equations (1) and (2) independent of q1 (with axes 5 and 6 meeting: the
  wrist point on axis 1 and no shoulder offset; apart: axis 6 along axis 1
  through it, and the offsets such that q5 can meet both): q1 turns, the
  other joints following it.

Elbow labels: "up" when the elbow (axis 3) lies on the side of the line
axis 2 -> axis 4 toward which ``h1`` points.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from kinematica.kernels._numba import (
    Array,
    ComplexArray,
    IntArray,
    batch_kernel,
    inline_kernel,
    kernel,
)
from kinematica.kernels.geometry import (
    TRIG_TOL,
    Vec3,
    add3,
    rot,
    sub3,
    subproblem1,
    trig_linear,
)
from kinematica.kernels.ik_check import (
    INFO_FREE,
    INFO_GAP,
    INFO_NEAR,
    INFO_SINGULAR,
    TARGET_BLOCK,
)
from kinematica.kernels.so3 import wrap
from kinematica.kernels.solvers.parallel_layout import (
    CONTINUUM_TOL,
    NEAR_TOL,
    NV,
    P_ARM,
    P_BOUND,
    P_EQ2,
    P_LIP,
    P_Q2REP,
    P_SCALE,
    P_SIGN3,
    P_SIGN4,
    P_ZUP,
    PAIR_FREE_Q1,
    PAIR_NONE,
    V_A6,
    V_E1,
    V_E2,
    V_H1,
    V_H5,
    V_H6,
    V_HK,
    V_K,
    V_KPAR,
    V_KPERP,
    V_P1,
    V_P1S,
    V_P2,
    V_P4,
    V_P5,
    V_P6,
    V_RM,
    V_TM,
    cross2,
    dot,
    row,
)
from kinematica.kernels.solvers.parallel_pairs import pairs
from kinematica.kernels.trig import sincos

__all__ = ["SLOTS", "solve", "solve_batch"]

#: Candidate slots: four pairs (q1, q5) times two elbows.
SLOTS = 8

# What the triangle reports.
_FOLD, _NEAR = 1, 2


#: ``G = T M⁻¹`` as 12 scalars: the rows of ``R_G``, then ``t_G`` (a tuple,
#: not arrays: numba increfs and decrefs each array handed to a kernel, and
#: those atomic updates were 8 % of the solver's profile while ``_finish``
#: took ten arrays).
Pose12 = tuple[float, ...]


@kernel
def _goal(V: Array, T: Array) -> Pose12:
    """``G = T M⁻¹``: ``R_G = R_T R_Mᵀ``, ``t_G = t_T - R_G t_M``."""
    r00, r01, r02 = _row_times_rm(V, T, 0)
    r10, r11, r12 = _row_times_rm(V, T, 1)
    r20, r21, r22 = _row_times_rm(V, T, 2)
    tm = row(V, V_TM)
    return (
        r00, r01, r02, r10, r11, r12, r20, r21, r22,
        T[0, 3] - (r00 * tm[0] + r01 * tm[1] + r02 * tm[2]),
        T[1, 3] - (r10 * tm[0] + r11 * tm[1] + r12 * tm[2]),
        T[2, 3] - (r20 * tm[0] + r21 * tm[1] + r22 * tm[2]),
    )  # fmt: skip


@inline_kernel
def _row_times_rm(V: Array, T: Array, i: int) -> Vec3:
    """Row ``i`` of ``R_T R_Mᵀ`` (the rows of ``R_M`` are ``V[V_RM + j]``)."""
    return (
        T[i, 0] * V[V_RM, 0] + T[i, 1] * V[V_RM, 1] + T[i, 2] * V[V_RM, 2],
        T[i, 0] * V[V_RM + 1, 0] + T[i, 1] * V[V_RM + 1, 1] + T[i, 2] * V[V_RM + 1, 2],
        T[i, 0] * V[V_RM + 2, 0] + T[i, 1] * V[V_RM + 2, 1] + T[i, 2] * V[V_RM + 2, 2],
    )


@inline_kernel
def _apply(G: Pose12, v: Vec3) -> Vec3:
    """``R_G v``."""
    return (
        G[0] * v[0] + G[1] * v[1] + G[2] * v[2],
        G[3] * v[0] + G[4] * v[1] + G[5] * v[2],
        G[6] * v[0] + G[7] * v[1] + G[8] * v[2],
    )


@inline_kernel
def _apply_t(G: Pose12, v: Vec3) -> Vec3:
    """``R_Gᵀ v``."""
    return (
        G[0] * v[0] + G[3] * v[1] + G[6] * v[2],
        G[1] * v[0] + G[4] * v[1] + G[7] * v[2],
        G[2] * v[0] + G[5] * v[1] + G[8] * v[2],
    )


@inline_kernel
def _from(G: Pose12, p: Vec3) -> Vec3:
    """``t_G - p``."""
    return G[9] - p[0], G[10] - p[1], G[11] - p[2]


@inline_kernel
def _plane(V: Array, x: Vec3) -> tuple[float, float]:
    """The coordinates of ``x`` across ``k`` (along e1, e2)."""
    return dot(row(V, V_E1), x), dot(row(V, V_E2), x)


@kernel
def _back(V: Array, G: Pose12, c1: float, s1: float, x: Vec3) -> Vec3:
    """``R1ᵀ R_G x``: a direction of the target seen from link 1."""
    return rot(row(V, V_H1), c1, -s1, _apply(G, x))


@kernel
def _moved(V: Array, G: Pose12, c1: float, s1: float, x: Vec3) -> tuple[float, float]:
    """``E1⁻¹(G(x)) - p2`` in plane coordinates."""
    p1 = row(V, V_P1)
    g = add3(_apply(G, x), _from(G, p1))
    return _plane(V, add3(rot(row(V, V_H1), c1, -s1, g), sub3(p1, row(V, V_P2))))


@kernel
def _free_q6(params: Array, V: Array, G: Pose12, c1: float, s1: float, v: Vec3) -> float:
    """The representative q6 of an aligned wrist: axis 4 at mid-reach of the triangle.

    With axis 6 along ``k``, axis 4 (``E1⁻¹ G (p6 + R(h6, -q6) v) - p2``, ``v =
    E5⁻¹(p4) - p6``) runs on the circle ``Z0 + cos q6 Z1 - sin q6 Z2`` of radius
    ``|v across h6|``: take the point at distance ``max(|A|, |B|)`` from axis 2
    (clamped to the circle's range).
    """
    h6 = row(V, V_H6)
    along = dot(h6, v)
    on = (along * h6[0], along * h6[1], along * h6[2])
    z0 = _moved(V, G, c1, s1, add3(row(V, V_P6), on))
    z1 = _plane(V, _back(V, G, c1, s1, sub3(v, on)))
    across = (h6[1] * v[2] - h6[2] * v[1], h6[2] * v[0] - h6[0] * v[2], h6[0] * v[1] - h6[1] * v[0])
    z2 = _plane(V, _back(V, G, c1, s1, across))
    r0 = math.hypot(z0[0], z0[1])
    rad = 0.5 * (math.hypot(z1[0], z1[1]) + math.hypot(z2[0], z2[1]))
    want = min(max(max(params[P_ARM], params[P_ARM + 1]), abs(r0 - rad)), r0 + rad)
    # |Z0|² + rad² + 2 cos q6 Z0·Z1 - 2 sin q6 Z0·Z2 = want²
    out = np.empty(2)  # (an aligned wrist is rare: no scratch passed down for it)
    trig_linear(
        2.0 * (z0[0] * z1[0] + z0[1] * z1[1]),
        -2.0 * (z0[0] * z2[0] + z0[1] * z2[1]),
        want * want - r0 * r0 - rad * rad,
        out,
    )
    return out[0]


@kernel
def _triangle(params: Array, tx: tuple[float, float]) -> tuple[int, float, float, float, float]:
    """q2 and ψ = σ3 q3 putting axis 4 at ``tx`` (plane, from axis 2): two elbows.

    ``tx = e^{i q2} (A + e^{iψ} B)``; with ``γ = ψ + arg B - arg A``,
    ``1 ∓ cos γ`` are formed as products of sums and differences of lengths
    (exact at the folded and stretched elbow).

    Returns:
        Flags, then (q2, ψ) of elbow up and of elbow down. Flags: -1 (no
        solution; angles NaN), else ``_FOLD`` (axis 4 on axis 2 with equal
        links: q2 free, the first elbow a representative and the second NaN)
        and ``_NEAR`` (missed by less than ``NEAR_TOL``: the least-squares
        elbow).
    """
    a = params[P_ARM]
    b = params[P_ARM + 1]
    arg_a = params[P_ARM + 2]
    arg_b = params[P_ARM + 3]
    span = a + b
    d = abs(a - b)
    n = math.sqrt(tx[0] * tx[0] + tx[1] * tx[1])  # within reach (the gap check): no overflow
    if n <= CONTINUUM_TOL * span and d <= CONTINUUM_TOL * span:
        return _FOLD, params[P_Q2REP], wrap(math.pi + arg_a - arg_b), math.nan, math.nan
    miss = max(n - span, d - n)
    flags = 0
    if miss > TRIG_TOL * span:
        if miss > NEAR_TOL * span:
            return -1, math.nan, math.nan, math.nan, math.nan
        flags = _NEAR
    omc = max((span - n) * (span + n) / (2.0 * a * b), 0.0)  # 1 - cos γ
    opc = max((n - d) * (n + d) / (2.0 * a * b), 0.0)  # 1 + cos γ
    sg = math.sqrt(omc * opc)  # sin γ >= 0
    gamma = math.atan2(sg, 0.5 * (opc - omc))
    arg_t = math.atan2(tx[1], tx[0])
    turn = math.atan2(b * sg, (a - b) + b * opc)  # arg(A + e^{iψ} B) - arg A; a + b cos γ
    # With γ >= 0 the elbow e^{i q2} A is clockwise of t about k: "up" (on
    # the side of h1 × k from the line axis 2 -> axis 4) when t·zup < 0.
    cw = (arg_t - arg_a - turn, gamma + arg_a - arg_b)
    ccw = (arg_t - arg_a + turn, -gamma + arg_a - arg_b)
    if tx[0] * params[P_ZUP] + tx[1] * params[P_ZUP + 1] < 0.0:
        return flags, cw[0], cw[1], ccw[0], ccw[1]
    return flags, ccw[0], ccw[1], cw[0], cw[1]


@kernel
def _finish(
    params: Array,
    V: Array,
    G: Pose12,
    pair: tuple[float, float, float, float, float, float],
    kind: int,
    j: int,
    Q: Array,
    info: Array,
) -> int:
    """The solutions of pair ``j`` into ``Q[2 j]`` (elbow up) and ``Q[2 j + 1]``.

    ``pair``: q1, q5, cos q1, sin q1, cos q5, sin q5; ``kind``: its ``PAIR_*``.

    Returns:
        How many candidates were written (0, 1 or 2).
    """
    q1, q5, c1, s1, c5, s5 = pair
    h5 = row(V, V_H5)
    h6 = row(V, V_H6)
    k = row(V, V_K)
    b = _apply_t(G, rot(row(V, V_H1), c1, s1, k))  # R_Gᵀ k1
    a = rot(h5, c5, -s5, k)  # R5ᵀ k
    # v = E5⁻¹(p4) - p6 = p5 - p6 + R5ᵀ (p4 - p5)
    p5 = row(V, V_P5)
    v = add3(rot(h5, c5, -s5, sub3(row(V, V_P4), p5)), sub3(p5, row(V, V_P6)))
    aligned = cross2(a, h6) <= CONTINUUM_TOL * CONTINUUM_TOL  # axis 6 along k
    q6 = _free_q6(params, V, G, c1, s1, v) if aligned else -subproblem1(a, b, h6)
    s6, c6 = sincos(q6)
    # θ234: R234 e1 = R1ᵀ R_G R6ᵀ R5ᵀ e1
    y = _back(V, G, c1, s1, rot(h6, c6, -s6, rot(h5, c5, -s5, row(V, V_E1))))
    th234 = math.atan2(dot(row(V, V_E2), y), dot(row(V, V_E1), y))
    # axis 4: E1⁻¹ G E6⁻¹ (p6 + v) - p2 = E1⁻¹ G (p6 + R6ᵀ v) - p2
    t = _moved(V, G, c1, s1, add3(row(V, V_P6), rot(h6, c6, -s6, v)))
    flags, q2_up, psi_up, q2_down, psi_down = _triangle(params, t)
    if flags < 0:
        return 0
    sign3 = params[P_SIGN3]
    sign4 = params[P_SIGN4]
    count = 0
    for e in range(2):
        q2 = q2_up if e == 0 else q2_down
        psi = psi_up if e == 0 else psi_down
        if np.isnan(q2):
            continue
        r = 2 * j + e
        Q[r, 0] = q1
        Q[r, 1] = q2
        Q[r, 2] = sign3 * psi
        Q[r, 3] = sign4 * (th234 - q2 - psi)
        Q[r, 4] = q5
        Q[r, 5] = q6
        count += 1
    if flags & _NEAR:
        info[INFO_NEAR] = 1.0
    if aligned:
        for joint in (1, 2, 3, 5):
            info[INFO_FREE + joint] = 1.0
    if flags & _FOLD:
        info[INFO_FREE + 1] = 1.0
        info[INFO_FREE + 3] = 1.0
    free_q1 = kind == PAIR_FREE_Q1
    if free_q1:
        info[INFO_FREE] = 1.0
    if aligned or flags & _FOLD or free_q1:
        info[INFO_SINGULAR] = 1.0
    return count


@kernel
def _scratch() -> tuple[Array, IntArray, Array, ComplexArray]:
    """The work arrays of :func:`_solve`.

    The pairs ``pq (4, 8)`` (q1, q5, their cosines and sines, then a quartic
    root's seed) and their ``kinds (4,)``; ``aux (5,)``: a quartic's
    coefficients or the angles of ``a cos θ + b sin θ = c``; the quartic's
    roots ``(4,)``.
    """
    return (
        np.empty((4, 8)),
        np.empty(4, dtype=np.int64),
        np.empty(5),
        np.empty(4, dtype=np.complex128),
    )


@kernel
def solve(params: Array, T: Array, Q: Array, info: Array) -> None:
    """Every solution of one target: candidates ``Q (8, 6)`` and ``info``.

    Args:
        params: ``(P_SIZE,)`` the arm (see :mod:`.parallel_layout`).
        T: ``(4, 4)`` target tool pose (base frame, m).
        Q: ``(8, 6)`` out: candidates (rad), NaN rows where a branch has none.
        info: ``(INFO_FREE + 6,)`` out, zero on entry (see
            :mod:`kinematica.kernels.ik_check`).
    """
    pq, kinds, aux, roots = _scratch()
    _solve(params, params[: 3 * NV].reshape((NV, 3)), T, Q, info, pq, kinds, aux, roots)


@kernel
def _solve(
    params: Array,
    V: Array,
    T: Array,
    Q: Array,
    info: Array,
    pq: Array,
    kinds: IntArray,
    aux: Array,
    roots: ComplexArray,
) -> None:
    """:func:`solve` with the vectors ``V (NV, 3)`` of ``params`` and its work arrays given.

    (:func:`_scratch`: a batch makes them once per block.)
    """
    Q[:, :] = np.nan
    info[INFO_GAP] = np.nan
    ok = True
    for i in range(3):
        for j in range(4):
            ok &= np.isfinite(T[i, j])
    if not ok:
        return
    G = _goal(V, T)
    size = params[P_SCALE]
    # |G(a6) - p1s| beyond the reach bound proves the target out of reach
    # (and keeps huge targets out of the maths: no overflow).
    x = add3(_apply(G, row(V, V_A6)), _from(G, row(V, V_P1S)))
    gap = math.hypot(math.hypot(x[0], x[1]), x[2]) - params[P_BOUND]  # no overflow
    if gap > NEAR_TOL * size:
        info[INFO_GAP] = gap
        return
    x6 = _apply(G, row(V, V_H6))
    w6 = add3(_apply(G, row(V, V_P6)), _from(G, row(V, V_P1)))
    # (2) cannot hold when its sides' ranges do not meet: a proven gap too.
    miss = (
        abs(params[P_EQ2 + 2] - dot(row(V, V_KPAR), w6))
        - math.sqrt(dot(row(V, V_KPERP), w6) ** 2 + dot(row(V, V_HK), w6) ** 2)
        - math.sqrt(params[P_EQ2] ** 2 + params[P_EQ2 + 1] ** 2)
    )
    gap = max(gap, miss / params[P_LIP], 0.0)
    count = 0
    if miss <= NEAR_TOL * size:
        pairs(params, V, x6, w6, pq, kinds, info, aux, roots)
        for j in range(4):
            if kinds[j] != PAIR_NONE:
                pair = (pq[j, 0], pq[j, 1], pq[j, 2], pq[j, 3], pq[j, 4], pq[j, 5])
                count += _finish(params, V, G, pair, kinds[j], j, Q, info)
    if count == 0:
        info[INFO_GAP] = gap
        for j in range(INFO_FREE, info.shape[0]):
            info[j] = 0.0
        info[INFO_SINGULAR] = 0.0


@batch_kernel
def solve_batch(params: Array, T: Array, Q: Array, info: Array) -> None:
    """:func:`solve` for targets ``T (N, 4, 4)`` in parallel: ``Q (N, 8, 6)``, ``info (N, k)``."""
    N = T.shape[0]
    V = params[: 3 * NV].reshape((NV, 3))
    for blk in numba.prange((N + TARGET_BLOCK - 1) // TARGET_BLOCK):
        pq, kinds, aux, roots = _scratch()  # once per block
        for i in range(blk * TARGET_BLOCK, min(N, (blk + 1) * TARGET_BLOCK)):
            _solve(params, V, T[i], Q[i], info[i], pq, kinds, aux, roots)
