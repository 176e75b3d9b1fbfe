"""Three-parallel 6R arms (UR type), first half: the pairs ``(q1, q5)`` of one target.

Written as a product of exponentials ``G = T·M⁻¹ = E1(q1)···E6(q6)`` (``M`` the
tool pose at q = 0, ``Ei`` the rotation by ``qi`` about joint i's axis, unit
``hi`` through ``pi`` at q = 0), with ``k`` the direction of axes 2, 3, 4:
``E2 E3 E4`` is a planar motion about ``k`` (it keeps heights along ``k``),
``E6`` fixes ``p6`` and ``E5`` fixes ``p5``. So, with ``k1 = R1 k`` (axis 2 now)::

    (1)  k1 · R_G h6        = k · R5 h6                            (orientation)
    (2)  k1 · (G(p6) - p1)  = k · (p5 - p1) + k · R5 (p6 - p5)     (height)

both ``a cos q1 + b sin q1 + c = D cos q5 + E sin q5 + F``. With ``p5``, ``p6``
the feet of the common normal of axes 5 and 6, ``[[D1, E1], [D2, E2]]`` is
singular exactly when the axes meet (row 2 is zero: UR type, ``MODE_MEET``) or
are parallel (row 1 is zero, ``MODE_PARALLEL``): then one equation holds q1
alone and the other gives q5 (two and two). Otherwise (``MODE_GENERAL``)
``(cos q5, sin q5) = P (cos q1, sin q1, 1)`` and ``|P x|² = 1`` is a quartic
in ``tan((q1 - φ0) / 2)`` (IK-Geo's subproblem 6), whose roots are polished by
Newton steps on (1) and (2).

Near the aligned wrist (axis 6 parallel to ``k``) both sides of (1) sit at an
extremum and ``1 - k·u`` for unit ``u`` loses every digit to cancellation; it
is computed as ``|k × u|² / (1 + k·u)`` instead, which keeps q5 accurate to
round-off however close to alignment the target is.

``params`` holds the arm as ``NV`` vectors (rows ``V_*`` of
``params[:3 NV].reshape(NV, 3)``), then scalars (``P_*``); it is packed by
:mod:`kinematica.ik.analytic.parallel`.
"""

from __future__ import annotations

import math

import numpy as np

from kinematica.kernels._numba import Array, IntArray, kernel
from kinematica.kernels.geometry import TRIG_TOL, trig_linear
from kinematica.kernels.ik_check import DEDUP_TOL, INFO_NEAR
from kinematica.kernels.polynomial import quartic_roots
from kinematica.kernels.so3 import wrap

__all__ = [
    "CONTINUUM_TOL",
    "DOUBLE_ROOT_TOL",
    "MODE_GENERAL",
    "MODE_MEET",
    "MODE_PARALLEL",
    "NEAR_TOL",
    "NEWTON_STEPS",
    "NV",
    "PAIR_FREE_Q1",
    "PAIR_FREE_Q15",
    "PAIR_NONE",
    "PAIR_ROOT",
    "P_SIZE",
    "pairs",
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
# What a pair is (``kinds``): none, a root, a root whose q1 is free (a
# continuum), q1 and q5 free (the quartic vanishes).
PAIR_NONE, PAIR_ROOT, PAIR_FREE_Q1, PAIR_FREE_Q15 = 0, 1, 2, 3

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
#: Newton steps at most polishing a quartic root on equations (1) and (2):
#: quadratic convergence takes 2-3, but at a double root (the wrist aligned)
#: it is linear, halving the error per step from the quartic's ~1e-8.
NEWTON_STEPS = 50

_H = math.sqrt(0.5)
_COS8 = (1.0, _H, 0.0, -_H, -1.0, -_H, 0.0, _H)  # cos(m π/4); sin is cos((m + 6) π/4)
_ROOT_IMAG = math.sqrt(NEAR_TOL)


@kernel
def dot(u: Array, v: Array) -> float:
    """``u · v`` for ``(3,)`` vectors."""
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]


@kernel
def cross2(u: Array, v: Array) -> float:
    """``|u × v|²`` for ``(3,)`` vectors (exact near parallel, unlike ``1 - (u·v)²``)."""
    x = u[1] * v[2] - u[2] * v[1]
    y = u[2] * v[0] - u[0] * v[2]
    z = u[0] * v[1] - u[1] * v[0]
    return x * x + y * y + z * z


@kernel
def axis2_now(V: Array, c1: float, s1: float, out: Array) -> None:
    """``out = k1 = R1 k``, the direction of axis 2 after joint 1 turns by q1."""
    for r in range(3):
        out[r] = V[V_KPAR, r] + c1 * V[V_KPERP, r] + s1 * V[V_HK, r]


@kernel
def _unit_gap(d: float, m2: float, e: float, n2: float) -> float:
    """``d - e`` for ``d = k·u``, ``e = k·v`` (unit u, v), ``m2 = |k × u|²``, ``n2 = |k × v|²``.

    ``1 ∓ d = m2 / (1 ± d)``: exact however close u and v are to ``±k``.
    """
    if d + e >= 0.0:
        return n2 / (1.0 + e) - m2 / (1.0 + d)
    return m2 / (1.0 - d) - n2 / (1.0 - e)


@kernel
def _wrist(params: Array, d: float, m2: float, out: Array) -> int:
    """q5 from (1) when axes 5 and 6 meet: ``k·R5 h6 = d``, ``m2 = |k1 × R_G h6|²``.

    ``q5 = φ ± δ`` with ``cos δ = (d - F1) / ρ``; ``1 ∓ cos δ`` is formed from
    ``1 ∓ d`` (``= m2 / (1 ± d)``) and the exact constants ``P_WLO``/``P_WHI``.

    Returns:
        1 (``out (2, 3)``: q5, cos q5, sin q5 of "no-flip" φ + δ, then "flip"
        φ - δ), 0 (near: the double root twice), -1 (no root).
    """
    D1 = params[P_EQ1]
    E1 = params[P_EQ1 + 1]
    rho = math.hypot(D1, E1)
    omd = m2 / (1.0 + d) if d > 0.0 else 1.0 - d
    opd = m2 / (1.0 - d) if d < 0.0 else 1.0 + d
    lo = (omd - params[P_WLO]) / rho  # 1 - cos δ
    hi = (opd - params[P_WHI]) / rho  # 1 + cos δ
    code = 1
    worst = min(lo, hi) * rho
    if worst < -TRIG_TOL:
        if worst < -NEAR_TOL:
            return -1
        code = 0
    lo = max(lo, 0.0)
    hi = max(hi, 0.0)
    cd = 0.5 * (hi - lo)
    sd = math.sqrt(lo * hi)
    norm = math.hypot(cd, sd)
    cf = D1 / (rho * norm)
    sf = E1 / (rho * norm)
    for i in range(2):
        sd_i = sd if i == 0 else -sd
        c5 = cf * cd - sf * sd_i
        s5 = sf * cd + cf * sd_i
        out[i, 0] = math.atan2(s5, c5)
        out[i, 1] = c5
        out[i, 2] = s5
    return code


@kernel
def _store(pq: Array, kinds: IntArray, m: int, q1: float, q5: float, kind: int) -> None:
    """Pair ``m``: ``pq[m] = (q1, q5, cos q1, sin q1, cos q5, sin q5)`` and its kind."""
    pq[m, 0] = q1
    pq[m, 1] = q5
    pq[m, 2] = math.cos(q1)
    pq[m, 3] = math.sin(q1)
    pq[m, 4] = math.cos(q5)
    pq[m, 5] = math.sin(q5)
    kinds[m] = kind


@kernel
def _roots(a: float, b: float, c: float, size: float, out: Array, info: Array) -> bool:
    """The two θ of ``a cos θ + b sin θ = c`` into ``out``: the rising root, then the falling.

    A double root within ``DOUBLE_ROOT_TOL`` is one angle, twice; a root
    missed by less than ``NEAR_TOL`` (of ``size``) gives the least-squares
    angle twice and marks the target near (``info``).

    Returns:
        False when there is no root (``out`` unchanged).
    """
    r2 = a * a + b * b
    if trig_linear(a, b, c, out) <= 0:
        if abs(c) - math.sqrt(r2) > NEAR_TOL * size:
            return False
        info[INFO_NEAR] = 1.0
    elif r2 - c * c <= DOUBLE_ROOT_TOL * r2:
        out[0] = math.atan2(b * c, a * c)
        out[1] = out[0]
    else:
        rise = out[1]  # a cos + b sin = r cos(θ - φ): rising at φ - δ
        out[1] = out[0]
        out[0] = rise
    return True


@kernel
def _first(
    a: float, b: float, rhs: float, size: float, rep: float, out: Array, info: Array
) -> int:
    """The q1 of ``a cos q1 + b sin q1 = rhs`` (``size``: the equation's scale).

    Returns:
        ``PAIR_ROOT`` (``out``: the root where the left side rises, then the
        one where it falls; see :func:`_roots`), ``PAIR_FREE_Q1`` (every q1:
        ``out`` holds ``rep``, then NaN), ``PAIR_NONE``.
    """
    if math.hypot(a, b) <= CONTINUUM_TOL * size:
        if abs(rhs) <= CONTINUUM_TOL * size:
            out[0] = rep
            out[1] = np.nan
            return PAIR_FREE_Q1
        return PAIR_NONE
    return PAIR_ROOT if _roots(a, b, rhs, size, out, info) else PAIR_NONE


@kernel
def _pairs_meet(
    params: Array, V: Array, x6: Array, L: Array, pq: Array, kinds: IntArray, info: Array
) -> None:
    """Axes 5 and 6 meet: q1 from (2) ("shoulder right", "left"), q5 from (1) ("no-flip", "flip")."""
    size = params[P_SCALE]
    q1s = np.empty(2)
    w = np.empty((2, 3))
    k1 = np.empty(3)
    kind = _first(L[1, 0], L[1, 1], params[P_EQ2 + 2] - L[1, 2], size, params[P_Q1REP], q1s, info)
    if kind == PAIR_NONE:
        return
    for i in range(2):
        q1 = q1s[i]
        if np.isnan(q1):
            continue
        c1 = math.cos(q1)
        s1 = math.sin(q1)
        axis2_now(V, c1, s1, k1)
        code = _wrist(params, dot(k1, x6), cross2(k1, x6), w)
        if code < 0:
            continue
        if code == 0:
            info[INFO_NEAR] = 1.0
        for j in range(2):
            m = 2 * i + j
            pq[m, 0] = q1
            pq[m, 1] = w[j, 0]
            pq[m, 2] = c1
            pq[m, 3] = s1
            pq[m, 4] = w[j, 1]
            pq[m, 5] = w[j, 2]
            kinds[m] = kind


@kernel
def _pairs_parallel(
    params: Array, L: Array, pq: Array, kinds: IntArray, info: Array
) -> None:
    """Axes 5 and 6 parallel: q1 from (1), then q5 from (2)."""
    q1s = np.empty(2)
    q5s = np.empty(2)
    kind = _first(L[0, 0], L[0, 1], params[P_EQ1 + 2] - L[0, 2], 1.0, params[P_Q1REP], q1s, info)
    if kind == PAIR_NONE:
        return
    D2 = params[P_EQ2]
    E2 = params[P_EQ2 + 1]
    size = params[P_SCALE]
    for i in range(2):
        q1 = q1s[i]
        if np.isnan(q1):
            continue
        lhs = L[1, 0] * math.cos(q1) + L[1, 1] * math.sin(q1) + L[1, 2] - params[P_EQ2 + 2]
        if not _roots(D2, E2, lhs, size, q5s, info):
            continue
        for j in range(2):
            _store(pq, kinds, 2 * i + j, q1, q5s[j], kind)


@kernel
def _newton(params: Array, V: Array, x6: Array, L: Array, q: Array, k1: Array) -> float:
    """Newton steps on (1) and (2) from ``q = (q1, q5)`` (in place); the residual.

    Steps stop when they no longer shrink (round-off reached, or no root
    nearby). (1) is evaluated as :func:`_unit_gap`: its error stays at
    round-off of its (small) terms near the aligned wrist, where two roots
    merge, so the roots are resolved however close they are.

    Returns:
        ``|f1| + |f2| / size`` at ``q`` (before the last, rejected step).
    """
    D1 = params[P_EQ1]
    E1 = params[P_EQ1 + 1]
    D2 = params[P_EQ2]
    E2 = params[P_EQ2 + 1]
    size = params[P_SCALE]
    rv = np.empty(3)
    res = math.inf
    last = math.inf
    for _ in range(NEWTON_STEPS):
        c1 = math.cos(q[0])
        s1 = math.sin(q[0])
        c5 = math.cos(q[1])
        s5 = math.sin(q[1])
        axis2_now(V, c1, s1, k1)
        for r in range(3):
            rv[r] = V[V_H6PAR, r] + c5 * V[V_H6PERP, r] + s5 * V[V_H5XH6, r]  # R5 h6
        d = dot(k1, x6)
        e = dot(V[V_K], rv)
        f1 = _unit_gap(d, cross2(k1, x6), e, cross2(V[V_K], rv))
        f2 = L[1, 0] * c1 + L[1, 1] * s1 + L[1, 2] - (D2 * c5 + E2 * s5 + params[P_EQ2 + 2])
        res = abs(f1) + abs(f2) / size
        j11 = L[0, 1] * c1 - L[0, 0] * s1
        j12 = D1 * s5 - E1 * c5
        j21 = L[1, 1] * c1 - L[1, 0] * s1
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
        q[0] -= d1
        q[1] -= d5
    return res


@kernel
def _pairs_general(
    params: Array, V: Array, x6: Array, L: Array, pq: Array, kinds: IntArray, info: Array
) -> None:
    """Axes 5 and 6 apart: the quartic of subproblem 6, its roots polished by Newton."""
    P = np.empty((2, 3))
    for i in range(2):
        for j in range(3):
            P[i, j] = params[P_MINV + 2 * i] * L[0, j] + params[P_MINV + 2 * i + 1] * L[1, j]
    P[0, 2] -= params[P_MINV] * params[P_EQ1 + 2] + params[P_MINV + 1] * params[P_EQ2 + 2]
    P[1, 2] -= params[P_MINV + 2] * params[P_EQ1 + 2] + params[P_MINV + 3] * params[P_EQ2 + 2]
    # φ0 puts t = ∞ where |P x|² - 1 is largest: the leading coefficient is then large.
    worst = -1.0
    far = 0.0
    size = 1.0
    for i in range(2):
        for j in range(3):
            size += P[i, j] * P[i, j]
    for m in range(8):
        c = _COS8[m]
        sn = _COS8[(m + 6) % 8]
        u = P[0, 0] * c + P[0, 1] * sn + P[0, 2]
        v = P[1, 0] * c + P[1, 1] * sn + P[1, 2]
        f = abs(u * u + v * v - 1.0)
        if f > worst:
            worst = f
            far = 0.25 * math.pi * m
    if worst <= CONTINUUM_TOL * size:  # every q1 solves: four representatives
        for m in range(4):
            q1 = params[P_Q1REP] + 0.5 * math.pi * m
            u = P[0, 0] * math.cos(q1) + P[0, 1] * math.sin(q1) + P[0, 2]
            v = P[1, 0] * math.cos(q1) + P[1, 1] * math.sin(q1) + P[1, 2]
            _store(pq, kinds, m, wrap(q1), math.atan2(v, u), PAIR_FREE_Q15)
        return
    phi0 = far - math.pi
    cp = math.cos(phi0)
    sp = math.sin(phi0)
    u0 = np.empty(2)
    u1 = np.empty(2)
    u2 = np.empty(2)
    for i in range(2):
        r0 = P[i, 0] * cp + P[i, 1] * sp
        r1 = P[i, 1] * cp - P[i, 0] * sp
        u0[i] = r0 + P[i, 2]
        u1[i] = 2.0 * r1
        u2[i] = P[i, 2] - r0
    coef = np.empty(5)
    coef[0] = u2[0] * u2[0] + u2[1] * u2[1] - 1.0
    coef[1] = 2.0 * (u1[0] * u2[0] + u1[1] * u2[1])
    coef[2] = u1[0] * u1[0] + u1[1] * u1[1] + 2.0 * (u0[0] * u2[0] + u0[1] * u2[1]) - 2.0
    coef[3] = 2.0 * (u0[0] * u1[0] + u0[1] * u1[1])
    coef[4] = u0[0] * u0[0] + u0[1] * u0[1] - 1.0
    roots = np.empty(4, dtype=np.complex128)
    quartic_roots(coef, roots)
    seeds = np.empty((4, 2))
    k1 = np.empty(3)
    for m in range(4):
        t = roots[m]
        if not abs(t.imag) <= _ROOT_IMAG * (1.0 + abs(t)):
            continue
        # a merging pair a ± bi: start from a + b and a - b, on either side
        q1 = phi0 + 2.0 * math.atan(t.real + t.imag)
        c1 = math.cos(q1)
        s1 = math.sin(q1)
        seeds[m, 0] = q1
        seeds[m, 1] = math.atan2(
            P[1, 0] * c1 + P[1, 1] * s1 + P[1, 2], P[0, 0] * c1 + P[0, 1] * s1 + P[0, 2]
        )
        _polish(params, V, x6, L, seeds[m], pq, kinds, m, info, k1)
    # Two seeds of a merging pair may polish to one root; the other then lies
    # across their midpoint (the sum of a near-double root is well conditioned).
    for j in range(4):
        for i in range(j):
            if kinds[i] == PAIR_NONE or kinds[j] == PAIR_NONE:
                continue
            if max(abs(wrap(pq[i, 0] - pq[j, 0])), abs(wrap(pq[i, 1] - pq[j, 1]))) >= DEDUP_TOL:
                continue
            for c in range(2):
                seeds[j, c] = pq[i, c] + wrap(seeds[i, c] - pq[i, c]) + wrap(seeds[j, c] - pq[i, c])
            _polish(params, V, x6, L, seeds[j], pq, kinds, j, info, k1)


@kernel
def _polish(
    params: Array,
    V: Array,
    x6: Array,
    L: Array,
    seed: Array,
    pq: Array,
    kinds: IntArray,
    m: int,
    info: Array,
    k1: Array,
) -> None:
    """Newton from ``seed (2,)`` into pair ``m`` of ``pq``/``kinds``.

    A root meets (1) and (2) to ``TRIG_TOL``; one that meets them to
    ``NEAR_TOL`` only is proposed too, and the target marked near.
    """
    q = pq[m, :2]
    q[0] = seed[0]
    q[1] = seed[1]
    res = _newton(params, V, x6, L, q, k1)
    kind = PAIR_NONE
    if res <= NEAR_TOL:
        kind = PAIR_ROOT
        if res > TRIG_TOL:
            info[INFO_NEAR] = 1.0
    _store(pq, kinds, m, wrap(q[0]), wrap(q[1]), kind)


@kernel
def _sort(pq: Array, kinds: IntArray) -> None:
    """Order the pairs by q1 (found ones first): the "root j" labels."""
    for i in range(1, 4):
        j = i
        while j > 0 and (
            kinds[j - 1] == PAIR_NONE and kinds[j] != PAIR_NONE
            or kinds[j] != PAIR_NONE and pq[j, 0] < pq[j - 1, 0]
        ):
            for c in range(6):
                tmp = pq[j, c]
                pq[j, c] = pq[j - 1, c]
                pq[j - 1, c] = tmp
            kk = kinds[j]
            kinds[j] = kinds[j - 1]
            kinds[j - 1] = kk
            j -= 1


@kernel
def pairs(
    params: Array, V: Array, x6: Array, w6: Array, pq: Array, kinds: IntArray, info: Array
) -> None:
    """Every ``(q1, q5)`` of a target, by the arm's mode.

    Args:
        params: The arm (``P_SIZE``,).
        V: ``(NV, 3)`` its vectors (a view of ``params``).
        x6: ``(3,)`` ``R_G h6``: axis 6's direction in the target.
        w6: ``(3,)`` ``G(p6) - p1``.
        pq: ``(4, 6)`` out: ``q1, q5, cos q1, sin q1, cos q5, sin q5`` per pair (``MODE_MEET``: slot
            ``2 shoulder + wrist``; otherwise by increasing q1).
        kinds: ``(4,)`` out: ``PAIR_*`` of each slot.
        info: The target's ``info`` row (``INFO_NEAR`` is set here).
    """
    L = np.empty((2, 3))  # a, b, c of (1) and (2): k1·y = a cos q1 + b sin q1 + c
    L[0, 0] = dot(V[V_KPERP], x6)
    L[0, 1] = dot(V[V_HK], x6)
    L[0, 2] = dot(V[V_KPAR], x6)
    L[1, 0] = dot(V[V_KPERP], w6)
    L[1, 1] = dot(V[V_HK], w6)
    L[1, 2] = dot(V[V_KPAR], w6)
    for i in range(4):
        kinds[i] = PAIR_NONE
    mode = params[P_MODE]
    if mode == MODE_MEET:
        _pairs_meet(params, V, x6, L, pq, kinds, info)
        return
    if mode == MODE_PARALLEL:
        _pairs_parallel(params, L, pq, kinds, info)
    else:
        _pairs_general(params, V, x6, L, pq, kinds, info)
    _sort(pq, kinds)
