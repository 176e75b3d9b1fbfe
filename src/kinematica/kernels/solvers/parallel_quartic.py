"""Three-parallel 6R arms whose axes 5 and 6 are apart: the pairs ``(q1, q5)`` of a quartic.

With ``(cos q5, sin q5) = P (cos q1, sin q1, 1)`` (equations (1) and (2) of
:mod:`.parallel_pairs`, solved for the wrist's side), ``|P x|² = 1`` is a
quartic in ``t = tan((q1 - φ0) / 2)`` (IK-Geo's subproblem 6), with ``φ0``
putting ``t = ∞`` where ``|P x|² - 1`` is largest (a leading coefficient far
from 0). Each root is polished by Newton steps on (1) and (2) themselves.

Near the aligned wrist (axis 6 along ``k``) both sides of (1) sit at an
extremum and two roots merge: ``1 - k·u`` for unit ``u`` loses every digit to
cancellation, so (1) is evaluated as ``|k × u|² / (1 + k·u)`` instead, which
resolves the two roots however close they are; two seeds that polish to one
root send the second across their midpoint (the sum of a near-double root is
well conditioned).
"""

from __future__ import annotations

import math

import numpy as np

from kinematica.kernels._numba import Array, ComplexArray, IntArray, kernel
from kinematica.kernels.geometry import TRIG_TOL, Vec3
from kinematica.kernels.ik_check import DEDUP_TOL, INFO_NEAR
from kinematica.kernels.polynomial import quartic_roots
from kinematica.kernels.so3 import wrap
from kinematica.kernels.solvers.parallel_layout import (
    CONTINUUM_TOL,
    NEAR_TOL,
    P_EQ1,
    P_EQ2,
    P_MINV,
    P_Q1REP,
    P_SCALE,
    PAIR_FREE_Q1,
    PAIR_NONE,
    PAIR_ROOT,
    V_H5XH6,
    V_H6PAR,
    V_H6PERP,
    V_K,
    axis2_now,
    cross2,
    dot,
    row,
    store_pair,
)
from kinematica.kernels.trig import sincos

__all__ = ["NEWTON_QUIET", "NEWTON_STEPS", "pairs_general"]

#: Newton steps at most polishing a quartic root on equations (1) and (2):
#: quadratic convergence takes 2-3, but at a double root (the wrist aligned)
#: it is linear, halving the error per step from the quartic's ~1e-8.
NEWTON_STEPS = 50
#: A Newton step of at most this (``|Δq1| + |Δq5|``, rad) is the last: the
#: error it leaves is about its square while convergence is quadratic, about
#: its size while it is linear (merging roots), both far below the 1e-10 the
#: check asks. Without it each root took one more step, to find that steps
#: had stopped shrinking (two sine-cosine pairs per root).
NEWTON_QUIET = 1e-14

# cos and sin of m π/4, m = 0..7: where |P x|² - 1 is sampled
_SAMPLES = np.array([[math.cos(m * math.pi / 4), math.sin(m * math.pi / 4)] for m in range(8)])
_ROOT_IMAG = math.sqrt(NEAR_TOL)


@kernel
def _unit_gap(d: float, m2: float, e: float, n2: float) -> float:
    """``d - e`` for ``d = k·u``, ``e = k·v`` (unit u, v), ``m2 = |k × u|²``, ``n2 = |k × v|²``.

    ``1 ∓ d = m2 / (1 ± d)``: exact however close u and v are to ``±k``.
    """
    if d + e >= 0.0:
        return n2 / (1.0 + e) - m2 / (1.0 + d)
    return m2 / (1.0 - d) - n2 / (1.0 - e)


@kernel
def _newton(
    params: Array, V: Array, x6: Vec3, L1: Vec3, L2: Vec3, q1: float, q5: float
) -> tuple[float, float, float, int, float, float, float, float]:
    """Newton steps on (1) and (2) from ``(q1, q5)``.

    Steps stop after one of at most ``NEWTON_QUIET``, or when they no longer
    shrink (round-off reached, or no root nearby). (1) is evaluated as
    :func:`_unit_gap`: its error stays at round-off of its (small) terms near
    the aligned wrist, where two roots merge, so the roots are resolved
    however close they are.

    Returns:
        The last ``q1``, ``q5``; ``|f1| + |f2| / size`` where the last step
        was computed; how many times (1) and (2) were evaluated; cos q1,
        sin q1, cos q5, sin q5 (after a step of at most ``NEWTON_QUIET``,
        the last ones turned by it to first order: exact, and no sine-cosine
        pairs to evaluate again).
    """
    D1 = params[P_EQ1]
    E1 = params[P_EQ1 + 1]
    D2 = params[P_EQ2]
    E2 = params[P_EQ2 + 1]
    size = params[P_SCALE]
    h6par = row(V, V_H6PAR)
    h6perp = row(V, V_H6PERP)
    h5xh6 = row(V, V_H5XH6)
    k = row(V, V_K)
    res = math.inf
    last = math.inf
    evaluations = 0
    moved = False
    c1 = s1 = c5 = s5 = math.nan
    for _ in range(NEWTON_STEPS):
        evaluations += 1
        s1, c1 = sincos(q1)
        s5, c5 = sincos(q5)
        moved = False
        k1 = axis2_now(V, c1, s1)
        r = (  # R5 h6
            h6par[0] + c5 * h6perp[0] + s5 * h5xh6[0],
            h6par[1] + c5 * h6perp[1] + s5 * h5xh6[1],
            h6par[2] + c5 * h6perp[2] + s5 * h5xh6[2],
        )
        f1 = _unit_gap(dot(k1, x6), cross2(k1, x6), dot(k, r), cross2(k, r))
        f2 = L2[0] * c1 + L2[1] * s1 + L2[2] - (D2 * c5 + E2 * s5 + params[P_EQ2 + 2])
        res = abs(f1) + abs(f2) / size
        j11 = L1[1] * c1 - L1[0] * s1
        j12 = D1 * s5 - E1 * c5
        j21 = L2[1] * c1 - L2[0] * s1
        j22 = D2 * s5 - E2 * c5
        det = j11 * j22 - j12 * j21
        if det == 0.0 or not np.isfinite(det):
            break
        d1 = (f1 * j22 - f2 * j12) / det
        d5 = (j11 * f2 - j21 * f1) / det
        step = abs(d1) + abs(d5)
        if not step < last:  # no longer contracting: round-off (or no root here)
            break
        last = step
        q1 -= d1
        q5 -= d5
        moved = True
        if step <= NEWTON_QUIET:  # to first order, exactly (d² < 1e-28)
            c1, s1 = c1 + s1 * d1, s1 - c1 * d1
            c5, s5 = c5 + s5 * d5, s5 - c5 * d5
            moved = False
            break
    if moved:  # NEWTON_STEPS used up
        s1, c1 = sincos(q1)
        s5, c5 = sincos(q5)
    return q1, q5, res, evaluations, c1, s1, c5, s5


@kernel
def pairs_general(
    params: Array,
    V: Array,
    x6: Vec3,
    L1: Vec3,
    L2: Vec3,
    pq: Array,
    kinds: IntArray,
    info: Array,
    coef: Array,
    roots: ComplexArray,
) -> None:
    """Axes 5 and 6 apart: the quartic of subproblem 6, its roots polished by Newton.

    ``(1)`` and ``(2)`` read ``k1·y = a cos q1 + b sin q1 + c`` with ``L1``,
    ``L2 = (a, b, c)``; ``coef (5,)`` and ``roots (4,)`` are scratch space, and
    so are columns 6, 7 of ``pq`` (the seeds of the roots).
    """
    m0 = params[P_MINV]
    m1 = params[P_MINV + 1]
    m2 = params[P_MINV + 2]
    m3 = params[P_MINV + 3]
    P00 = m0 * L1[0] + m1 * L2[0]
    P01 = m0 * L1[1] + m1 * L2[1]
    P02 = m0 * L1[2] + m1 * L2[2] - (m0 * params[P_EQ1 + 2] + m1 * params[P_EQ2 + 2])
    P10 = m2 * L1[0] + m3 * L2[0]
    P11 = m2 * L1[1] + m3 * L2[1]
    P12 = m2 * L1[2] + m3 * L2[2] - (m2 * params[P_EQ1 + 2] + m3 * params[P_EQ2 + 2])
    # φ0 puts t = ∞ where |P x|² - 1 is largest: the leading coefficient is then large.
    worst = -1.0
    far = 0.0
    size = 1.0 + P00 * P00 + P01 * P01 + P02 * P02 + P10 * P10 + P11 * P11 + P12 * P12
    for m in range(8):
        u = P00 * _SAMPLES[m, 0] + P01 * _SAMPLES[m, 1] + P02
        v = P10 * _SAMPLES[m, 0] + P11 * _SAMPLES[m, 1] + P12
        f = abs(u * u + v * v - 1.0)
        if f > worst:
            worst = f
            far = 0.25 * math.pi * m
    if worst <= CONTINUUM_TOL * size:  # every q1 solves, each with one q5
        q1 = params[P_Q1REP]
        u = P00 * math.cos(q1) + P01 * math.sin(q1) + P02
        v = P10 * math.cos(q1) + P11 * math.sin(q1) + P12
        store_pair(pq, 0, q1, math.atan2(v, u))
        kinds[0] = PAIR_FREE_Q1
        return
    phi0 = far - math.pi
    sp, cp = sincos(phi0)
    # rows i = 0, 1 of P x at q1 = φ0 + 2 atan t, times (1 + t²): u0 + u1 t + u2 t²
    a0 = P00 * cp + P01 * sp
    b0 = P10 * cp + P11 * sp
    u00, u01 = a0 + P02, b0 + P12
    u10, u11 = 2.0 * (P01 * cp - P00 * sp), 2.0 * (P11 * cp - P10 * sp)
    u20, u21 = P02 - a0, P12 - b0
    coef[0] = u20 * u20 + u21 * u21 - 1.0
    coef[1] = 2.0 * (u10 * u20 + u11 * u21)
    coef[2] = u10 * u10 + u11 * u11 + 2.0 * (u00 * u20 + u01 * u21) - 2.0
    coef[3] = 2.0 * (u00 * u10 + u01 * u11)
    coef[4] = u00 * u00 + u01 * u01 - 1.0
    quartic_roots(coef, roots)
    for m in range(4):
        t = roots[m]
        size_t = math.sqrt(t.real * t.real + t.imag * t.imag)  # roots are O(1): no overflow
        if not abs(t.imag) <= _ROOT_IMAG * (1.0 + size_t):
            continue
        # a merging pair a ± bi: start from a + b and a - b, on either side
        q1 = phi0 + 2.0 * math.atan(t.real + t.imag)
        s1, c1 = sincos(q1)
        pq[m, 6] = q1
        pq[m, 7] = math.atan2(P10 * c1 + P11 * s1 + P12, P00 * c1 + P01 * s1 + P02)
        _polish(params, V, x6, L1, L2, pq, kinds, m, info)
    # Two seeds of a merging pair may polish to one root; the other then lies
    # across their midpoint (the sum of a near-double root is well conditioned).
    for j in range(4):
        for i in range(j):
            if kinds[i] == PAIR_NONE or kinds[j] == PAIR_NONE:
                continue
            if max(abs(wrap(pq[i, 0] - pq[j, 0])), abs(wrap(pq[i, 1] - pq[j, 1]))) >= DEDUP_TOL:
                continue
            for c in range(2):
                pq[j, 6 + c] = (
                    pq[i, c] + wrap(pq[i, 6 + c] - pq[i, c]) + wrap(pq[j, 6 + c] - pq[i, c])
                )
            _polish(params, V, x6, L1, L2, pq, kinds, j, info)


@kernel
def _polish(
    params: Array,
    V: Array,
    x6: Vec3,
    L1: Vec3,
    L2: Vec3,
    pq: Array,
    kinds: IntArray,
    m: int,
    info: Array,
) -> None:
    """Newton from the seed ``pq[m, 6:8]`` into pair ``m`` of ``pq``/``kinds``.

    A root meets (1) and (2) to ``TRIG_TOL``; one that meets them to
    ``NEAR_TOL`` only is proposed too, and the target marked near.
    """
    q1, q5, res, _, c1, s1, c5, s5 = _newton(params, V, x6, L1, L2, pq[m, 6], pq[m, 7])
    kinds[m] = PAIR_NONE
    if res <= NEAR_TOL:
        kinds[m] = PAIR_ROOT
        if res > TRIG_TOL:
            info[INFO_NEAR] = 1.0
    pq[m, 0] = wrap(q1)
    pq[m, 1] = wrap(q5)
    pq[m, 2] = c1
    pq[m, 3] = s1
    pq[m, 4] = c5
    pq[m, 5] = s5
