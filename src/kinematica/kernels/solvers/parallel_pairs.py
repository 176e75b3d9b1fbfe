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
Newton steps on (1) and (2) (:mod:`.parallel_quartic`).

Near the aligned wrist (axis 6 parallel to ``k``) both sides of (1) sit at an
extremum and ``1 - k·u`` for unit ``u`` loses every digit to cancellation; it
is formed as ``|k × u|² / (1 + k·u)`` instead, which keeps q5 accurate to
round-off however close to alignment the target is.
"""

from __future__ import annotations

import math

import numpy as np

from kinematica.kernels._numba import Array, ComplexArray, IntArray, kernel
from kinematica.kernels.geometry import TRIG_TOL, Vec3, trig_linear
from kinematica.kernels.ik_check import INFO_NEAR
from kinematica.kernels.solvers.parallel_layout import (
    CONTINUUM_TOL,
    DOUBLE_ROOT_TOL,
    MODE_MEET,
    MODE_PARALLEL,
    NEAR_TOL,
    P_EQ1,
    P_EQ2,
    P_MODE,
    P_Q1REP,
    P_SCALE,
    P_WHI,
    P_WLO,
    PAIR_FREE_Q1,
    PAIR_NONE,
    PAIR_ROOT,
    V_HK,
    V_KPAR,
    V_KPERP,
    axis2_now,
    cross2,
    dot,
    row,
    store_pair,
)
from kinematica.kernels.solvers.parallel_quartic import pairs_general
from kinematica.kernels.trig import sincos

__all__ = ["pairs"]


@kernel
def _wrist(params: Array, d: float, m2: float, pq: Array, m: int) -> int:
    """q5 from (1) when axes 5 and 6 meet: ``k·R5 h6 = d``, ``m2 = |k1 × R_G h6|²``.

    ``q5 = φ ± δ`` with ``cos δ = (d - F1) / ρ``; ``1 ∓ cos δ`` is formed from
    ``1 ∓ d`` (``= m2 / (1 ± d)``) and the exact constants ``P_WLO``/``P_WHI``.

    Returns:
        1 (q5, cos q5, sin q5 of "no-flip" φ + δ into pair ``m`` of ``pq``,
        of "flip" φ - δ into pair ``m + 1``), 0 (near: the double root
        twice), -1 (no root; ``pq`` unchanged).
    """
    D1 = params[P_EQ1]
    E1 = params[P_EQ1 + 1]
    rho = math.sqrt(D1 * D1 + E1 * E1)  # lengths of the arm: no overflow (nor below)
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
    norm = math.sqrt(cd * cd + sd * sd)  # both within [0, 2]
    cf = D1 / (rho * norm)
    sf = E1 / (rho * norm)
    for i in range(2):
        sd_i = sd if i == 0 else -sd
        c5 = cf * cd - sf * sd_i
        s5 = sf * cd + cf * sd_i
        pq[m + i, 1] = math.atan2(s5, c5)
        pq[m + i, 4] = c5
        pq[m + i, 5] = s5
    return code


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
def _first(a: float, b: float, rhs: float, size: float, rep: float, out: Array, info: Array) -> int:
    """The q1 of ``a cos q1 + b sin q1 = rhs`` (``size``: the equation's scale).

    Returns:
        ``PAIR_ROOT`` (``out``: the root where the left side rises, then the
        one where it falls; see :func:`_roots`), ``PAIR_FREE_Q1`` (every q1:
        ``out`` holds ``rep``, then NaN), ``PAIR_NONE``.
    """
    if math.sqrt(a * a + b * b) <= CONTINUUM_TOL * size:  # bounded by the reach check
        if abs(rhs) <= CONTINUUM_TOL * size:
            out[0] = rep
            out[1] = np.nan
            return PAIR_FREE_Q1
        return PAIR_NONE
    return PAIR_ROOT if _roots(a, b, rhs, size, out, info) else PAIR_NONE


@kernel
def _pairs_meet(
    params: Array,
    V: Array,
    x6: Vec3,
    L2: Vec3,
    pq: Array,
    kinds: IntArray,
    info: Array,
    q1s: Array,
) -> None:
    """Axes 5 and 6 meet: q1 from (2) (shoulder right, left), q5 from (1) (no-flip, flip).

    ``q1s (2,)`` is scratch space.
    """
    size = params[P_SCALE]
    kind = _first(L2[0], L2[1], params[P_EQ2 + 2] - L2[2], size, params[P_Q1REP], q1s, info)
    if kind == PAIR_NONE:
        return
    for i in range(2):
        q1 = q1s[i]
        if np.isnan(q1):
            continue
        s1, c1 = sincos(q1)
        k1 = axis2_now(V, c1, s1)
        code = _wrist(params, dot(k1, x6), cross2(k1, x6), pq, 2 * i)
        if code < 0:
            continue
        if code == 0:
            info[INFO_NEAR] = 1.0
        for m in range(2 * i, 2 * i + 2):
            pq[m, 0] = q1
            pq[m, 2] = c1
            pq[m, 3] = s1
            kinds[m] = kind


@kernel
def _pairs_parallel(
    params: Array, L1: Vec3, L2: Vec3, pq: Array, kinds: IntArray, info: Array
) -> None:
    """Axes 5 and 6 parallel: q1 from (1), then q5 from (2)."""
    q1s = np.empty(2)
    q5s = np.empty(2)
    kind = _first(L1[0], L1[1], params[P_EQ1 + 2] - L1[2], 1.0, params[P_Q1REP], q1s, info)
    if kind == PAIR_NONE:
        return
    D2 = params[P_EQ2]
    E2 = params[P_EQ2 + 1]
    size = params[P_SCALE]
    for i in range(2):
        q1 = q1s[i]
        if np.isnan(q1):
            continue
        s1, c1 = sincos(q1)
        lhs = L2[0] * c1 + L2[1] * s1 + L2[2] - params[P_EQ2 + 2]
        if not _roots(D2, E2, lhs, size, q5s, info):
            continue
        for j in range(2):
            store_pair(pq, 2 * i + j, q1, q5s[j])
            kinds[2 * i + j] = kind


@kernel
def _sort(pq: Array, kinds: IntArray) -> None:
    """Order the pairs by q1 (found ones first): the "root j" labels."""
    for i in range(1, 4):
        j = i
        while (
            j > 0
            and kinds[j] != PAIR_NONE
            and (kinds[j - 1] == PAIR_NONE or pq[j, 0] < pq[j - 1, 0])
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
    params: Array,
    V: Array,
    x6: Vec3,
    w6: Vec3,
    pq: Array,
    kinds: IntArray,
    info: Array,
    aux: Array,
    roots: ComplexArray,
) -> None:
    """Every ``(q1, q5)`` of a target, by the arm's mode.

    Args:
        params: The arm (``P_SIZE``,).
        V: ``(NV, 3)`` its vectors (a view of ``params``).
        x6: ``R_G h6``: axis 6's direction in the target.
        w6: ``G(p6) - p1``.
        pq: ``(4, 8)`` out: ``q1, q5, cos q1, sin q1, cos q5, sin q5`` per pair (``MODE_MEET``:
            slot ``2 shoulder + wrist``; otherwise by increasing q1); columns 6, 7 scratch.
        kinds: ``(4,)`` out: ``PAIR_*`` of each slot.
        info: The target's ``info`` row (``INFO_NEAR`` is set here).
        aux: ``(5,)`` scratch space.
        roots: ``(4,)`` scratch space (a quartic's roots).
    """
    # a, b, c of (1) and (2): k1·y = a cos q1 + b sin q1 + c
    L1 = (dot(row(V, V_KPERP), x6), dot(row(V, V_HK), x6), dot(row(V, V_KPAR), x6))
    L2 = (dot(row(V, V_KPERP), w6), dot(row(V, V_HK), w6), dot(row(V, V_KPAR), w6))
    for i in range(4):
        kinds[i] = PAIR_NONE
    mode = params[P_MODE]
    if mode == MODE_MEET:
        _pairs_meet(params, V, x6, L2, pq, kinds, info, aux)
        return
    if mode == MODE_PARALLEL:
        _pairs_parallel(params, L1, L2, pq, kinds, info)
    else:
        pairs_general(params, V, x6, L1, L2, pq, kinds, info, aux, roots)
    _sort(pq, kinds)
