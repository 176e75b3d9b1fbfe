"""Closed-form IK of arms with a spherical wrist: 6R, and RRP (Stanford type).

The last three axes meet at the wrist centre ``c``, which only joints 1-3 move
(the lecture notes' "hipótesis de la muñeca esférica"). In product-of-exponentials
form (``T(q) = e1 e2 ... e6 M`` with the axes at q = 0) the target wrist
centre is the point fixed in the tool frame that sits at ``c`` at q = 0::

    c_t = T_target · M⁻¹ · c

and joints 1-3 put ``c`` there (:mod:`~kinematica.kernels.solvers.arm_point`: up
to four branches). The wrist then supplies the rotation left over,
``R4 R5 R6 = (R1 R2 R3)ᵀ · R_target · R_Mᵀ`` (the lecture notes' ``R36 = (R03)ᵀ R06``),
about wrist axes meeting at any angles:

* ``w = R4 R5 R6 h6`` (the target's axis 6, turned back by joints 1-3): the
  vector ``c' = R4ᵀ w = R5 h6`` has ``h4ᵀc' = h4ᵀw``, ``h5ᵀc' = h5ᵀh6`` and unit
  length, so ``c' = α h4 + β h5 ± γ (h4 × h5)`` (SP2): "no-flip" and "flip";
* q4 turns ``c'`` onto ``w`` about ``h4``, q5 turns ``h6`` onto ``c'`` about ``h5``
  (SP1 each), and q6 turns ``x6`` onto ``R5ᵀ R4ᵀ R x6`` about ``h6``: computed
  last, it absorbs the round-off of q4 and q5 (near the wrist singularity q4
  is ill-determined, their combination is not).

When ``h5 ⟂ h4`` and ``h6 ∥ h4`` at q = 0 (the usual wrist, within
``TWIN_TOL``), ``R(h4, π) R(h5, -q5) R(h4, π) = R(h5, q5)`` makes the flip
``(q4 + π, -q5, q6 + π)``: no second set of angles to solve for.

"No-flip" bends the wrist the way it is bent at q = 0 (or, when q = 0 is
itself singular, the way q5 > 0 bends it from there): on the PUMA, sin q5 > 0.
Slots: ``4 position × 2 wrist``, slot ``2 k + w``.

At the edges (each a continuum, flagged ``singular`` with its free joints):

* wrist singular (``w`` within ``WRIST_SINGULAR_TOL`` of ``±h4``: axes 4 and 6
  aligned): only ``q4 ± q6`` is determined; the no-flip slot holds the
  representative with ``q4 = 0``, the flip slot (the same family) is NaN;
* wrist centre on axis 1 (q1 free) or on axis 2 (q2 free): the first two
  position slots turn the free joint so that the arm faces the tool (axis 4
  turned towards the target's axis 6: the wrist is least bent), the last two
  hold it at 0 (where the shoulder branches merge, as they do at these
  points for shoulders in closed form, that is one representative of each).
"""

from __future__ import annotations

import math

import numpy as np

from kinematica.kernels._numba import Array, inline_kernel, kernel
from kinematica.kernels.geometry import rotate, subproblem1, turn
from kinematica.kernels.ik_check import INFO_FREE, INFO_GAP, INFO_NEAR, INFO_SINGULAR
from kinematica.kernels.so3 import wrap
from kinematica.kernels.solvers.arm_base import (
    A_H1,
    A_H2,
    A_H3,
    A_PRISMATIC,
    A_SIZE,
    NEAR_SET_TOL,
    ST_FREE,
    ST_GAP,
    ST_NEAR,
    clamped_root,
)
from kinematica.kernels.trig import sincos

__all__ = ["TWIN_TOL", "WRIST_SINGULAR_TOL", "W_SIZE", "W_TWIN", "pose", "wrist_centre"]

#: The wrist's flip is the no-flip's twin ``(q4 + π, -q5, q6 + π)`` when
#: ``h4ᵀh5``, ``h5ᵀh6`` and ``|h4 × h6|`` at q = 0 are all below this: the
#: identity then holds to about this (far below 1e-10), where the flip's own
#: solution would cost three more ``atan2``.
TWIN_TOL = 1e-13
#: The wrist is singular (axes 4 and 6 aligned) when the sine of the angle
#: between ``h4`` and ``w`` is below this: the representative ``q4 = 0`` then
#: reproduces the rotation to about twice this (far below 1e-10 rad).
WRIST_SINGULAR_TOL = 1e-12

_TWO_PI = 2.0 * math.pi

# Parameter offsets after the arm part and the mode (vectors at q = 0, base frame).
W_CTOOL = A_SIZE + 1  # (3,) wrist centre in the tool frame (M⁻¹ c)
W_LH = A_SIZE + 4  # (3,) R_Mᵀ h6: the target's axis 6 is R_target times this
W_LX = A_SIZE + 7  # (3,) R_Mᵀ x6
W_H4 = A_SIZE + 10  # (3,) wrist axes, and x6: a unit vector normal to h6
W_H5 = A_SIZE + 13
W_H6 = A_SIZE + 16
W_X6 = A_SIZE + 19
W_Y6 = A_SIZE + 22  # (3,) h6 × x6
W_EA = A_SIZE + 25  # (3,) unit part of h5 normal to h4; eb = h4 × ea
W_EB = A_SIZE + 28
W_K45 = A_SIZE + 31  # h4ᵀh5
W_S45 = A_SIZE + 32  # |h4 × h5|
W_K56 = A_SIZE + 33  # h5ᵀh6
W_N56 = A_SIZE + 34  # (3,) h5 × h6 in the frame (h4, ea, eb)
W_H6F = A_SIZE + 37  # (3,) h6 in that frame
W_FLIP = A_SIZE + 40  # sign of γ on the no-flip branch
W_LIMITS = A_SIZE + 41  # (4,) limits of q4, then of q6 (rad): where representatives go
W_TWIN = A_SIZE + 45  # 1.0: h5 ⟂ h4 and h6 ∥ h4 at q = 0, flip = (q4 + π, -q5, q6 + π)
W_SIZE = A_SIZE + 46


@inline_kernel
def _vec(params: Array, o: int) -> tuple[float, float, float]:
    """``params[o:o+3]`` as three scalars (no view: see :func:`~.geometry.turn`)."""
    return params[o], params[o + 1], params[o + 2]


@inline_kernel
def _dot(params: Array, o: int, v: tuple[float, float, float]) -> float:
    """``params[o:o+3] · v``."""
    return params[o] * v[0] + params[o + 1] * v[1] + params[o + 2] * v[2]


@kernel
def _undo(
    params: Array, Q3: Array, k: int, w: tuple[float, float, float], y: tuple[float, float, float]
) -> tuple[float, float, float, float, float, float]:
    """``R3ᵀ R2ᵀ R1ᵀ (w, y)``: joints 1-3 of slot ``k`` of ``Q3`` turned back (a slide: 1, 2)."""
    wx, wy, wz = w
    yx, yy, yz = y
    for j in range(2 if params[A_PRISMATIC] != 0.0 else 3):
        kx, ky, kz = _vec(params, A_H1 + 3 * j)  # h1, h2, h3 lie one after another
        s, c = sincos(Q3[k, j])
        wx, wy, wz = turn(kx, ky, kz, c, -s, wx, wy, wz)
        yx, yy, yz = turn(kx, ky, kz, c, -s, yx, yy, yz)
    return wx, wy, wz, yx, yy, yz


@kernel
def _q6(
    params: Array, y4: float, x4: float, y5: float, x5: float, y: tuple[float, float, float]
) -> float:
    """q6 turning ``x6`` onto ``z = R5ᵀ R4ᵀ y`` about ``h6`` (absorbs q4's, q5's round-off).

    ``q4 = atan2(y4, x4)``, ``q5 = atan2(y5, x5)``: their cosines and sines
    come from those arguments, not from the angles. (The arguments are of the
    order of 1 and, off the wrist singularity, above ``WRIST_SINGULAR_TOL``:
    ``sqrt`` of the sum of squares neither overflows nor underflows.)
    """
    r4 = math.sqrt(x4 * x4 + y4 * y4)
    r5 = math.sqrt(x5 * x5 + y5 * y5)
    c4 = x4 / r4 if r4 > 0.0 else 1.0
    s4 = y4 / r4 if r4 > 0.0 else 0.0
    c5 = x5 / r5 if r5 > 0.0 else 1.0
    s5 = y5 / r5 if r5 > 0.0 else 0.0
    h4x, h4y, h4z = _vec(params, W_H4)
    h5x, h5y, h5z = _vec(params, W_H5)
    z = turn(h4x, h4y, h4z, c4, -s4, y[0], y[1], y[2])
    z = turn(h5x, h5y, h5z, c5, -s5, z[0], z[1], z[2])
    return math.atan2(_dot(params, W_Y6, z), _dot(params, W_X6, z))


@kernel
def _within_limits(params: Array, w4: float, q6: float) -> tuple[float, float]:
    """The singular wrist's representative ``(0, q5, q6)`` moved along its family into the limits.

    With ``w = ±h4`` (``w4 = ±1``) turning q4 by t turns q6 by ``-t w4``: the
    family is ``(t, q5, q6 - t w4)``. When ``q4 = 0`` puts q6 outside its
    limits, t is chosen to put q6 mid-window, then kept within q4's limits, so
    that a family with members within the limits is not reported out of them.

    Returns:
        ``(q4, q6)``.
    """
    lo4 = params[W_LIMITS]
    hi4 = params[W_LIMITS + 1]
    lo6 = params[W_LIMITS + 2]
    hi6 = params[W_LIMITS + 3]
    inside = lo6 <= q6 <= hi6 or lo6 <= q6 + _TWO_PI <= hi6 or lo6 <= q6 - _TWO_PI <= hi6
    if inside or not (math.isfinite(lo6) and math.isfinite(hi6)):
        return 0.0, q6
    sign = 1.0 if w4 > 0.0 else -1.0
    t = sign * wrap(q6 - 0.5 * (lo6 + hi6))
    if math.isfinite(lo4) and math.isfinite(hi4):
        t = min(max(t, lo4), hi4)
    return t, q6 - sign * t


@kernel
def _wrist(
    params: Array, w: tuple[float, float, float], y: tuple[float, float, float], st: Array
) -> tuple[float, float, float, float, float, float, bool]:
    """(q4, q5, q6) of no-flip, then of flip, and whether the wrist is singular.

    Args:
        params: The solver's parameters.
        w: The target's axis 6 with joints 1-3 turned back.
        y: Its ``x6`` likewise.
        st: Arm state; ``ST_NEAR`` is raised near the wrist singularity or fold.

    Returns:
        Six angles (rad), NaN where the wrist cannot make the rotation (a
        singular wrist: the flip, the same family, is NaN), then the flag.
    """
    w4 = _dot(params, W_H4, w)
    wa = _dot(params, W_EA, w)
    wb = _dot(params, W_EB, w)
    off2 = wa * wa + wb * wb  # |w × h4|², exact (no 1 - cos² cancellation)
    k56 = params[W_K56]
    if off2 < NEAR_SET_TOL * NEAR_SET_TOL:
        st[ST_NEAR] = 1.0
    if off2 < WRIST_SINGULAR_TOL * WRIST_SINGULAR_TOL:
        # q4 free: c' = w; q5 turns h6 onto w about h5; q6 absorbs the rest
        cw = w4 * params[W_N56] + wa * params[W_N56 + 1] + wb * params[W_N56 + 2]
        ch = w4 * params[W_H6F] + wa * params[W_H6F + 1] + wb * params[W_H6F + 2] - k56 * k56
        q4, q6 = _within_limits(params, w4, _q6(params, 0.0, 1.0, cw, ch, y))
        return q4, math.atan2(cw, ch), q6, math.nan, math.nan, math.nan, True
    s45 = params[W_S45]
    beta = (k56 - params[W_K45] * w4) / (s45 * s45)
    off = math.sqrt(off2) / s45  # γ² = off² - β²
    gam0 = clamped_root(off - abs(beta), off + abs(beta), off + abs(beta), 1.0, st)
    ca = beta * s45
    cb = gam0 * s45 * params[W_FLIP]
    n4, n5, n6 = _branch(params, w4, wa, wb, ca, cb, y)
    if params[W_TWIN] != 0.0:  # R(h4, π) R(h5, -q5) R(h4, π) = R(h5, q5): the flip for free
        return n4, n5, n6, wrap(n4 + math.pi), -n5, wrap(n6 + math.pi), False
    f4, f5, f6 = _branch(params, w4, wa, wb, ca, -cb, y)
    return n4, n5, n6, f4, f5, f6, False


@inline_kernel
def _branch(
    params: Array,
    w4: float,
    wa: float,
    wb: float,
    ca: float,
    cb: float,
    y: tuple[float, float, float],
) -> tuple[float, float, float]:
    """(q4, q5, q6) putting ``c' = (w4, ca, cb)`` (frame ``h4, ea, eb``) where it must go.

    q4 turns ``c'`` onto ``w`` about h4 (their parts off h4, in the frame
    ``ea, eb``); q5 turns h6 onto ``c'`` about h5; q6 absorbs the rest.
    """
    y4 = ca * wb - cb * wa
    x4 = ca * wa + cb * wb
    k56 = params[W_K56]
    cw = w4 * params[W_N56] + ca * params[W_N56 + 1] + cb * params[W_N56 + 2]
    ch = w4 * params[W_H6F] + ca * params[W_H6F + 1] + cb * params[W_H6F + 2] - k56 * k56
    return math.atan2(y4, x4), math.atan2(cw, ch), _q6(params, y4, x4, cw, ch, y)


@kernel
def _face(params: Array, Q3: Array, k: int, W0: tuple[float, float, float], st: Array) -> None:
    """Set a free q2, then a free q1, of slot ``k``: axis 4 turned towards the target's axis 6.

    (Only at a wrist centre on axis 1 or 2: rare, so plain arrays here.)
    """
    kv = np.empty(3)  # axis 4 as joints 3, then 2 turn it
    tmp = np.empty(3)
    h1 = np.empty(3)
    h2 = np.empty(3)
    w0 = np.empty(3)
    for i in range(3):
        kv[i] = params[W_H4 + i]
        h1[i] = params[A_H1 + i]
        h2[i] = params[A_H2 + i]
        w0[i] = W0[i]
    if params[A_PRISMATIC] == 0.0:
        s3, c3 = sincos(Q3[k, 2])
        rotate(params[A_H3 : A_H3 + 3], c3, s3, kv, tmp)
        for i in range(3):
            kv[i] = tmp[i]
    if st[ST_FREE + 1] != 0.0:  # turned about axis 2 towards R1ᵀ h6_target
        s1, c1 = sincos(Q3[k, 0])
        rotate(h1, c1, -s1, w0, tmp)
        Q3[k, 1] = subproblem1(kv, tmp, h2)
    s2, c2 = sincos(Q3[k, 1])
    rotate(h2, c2, s2, kv, tmp)
    if st[ST_FREE] != 0.0:
        Q3[k, 0] = subproblem1(tmp, w0, h1)


@kernel
def wrist_centre(params: Array, T: Array, ct: Array) -> None:
    """``ct (3,)``: the target wrist centre ``T M⁻¹ c`` of a pose ``T (4, 4)``."""
    for i in range(3):
        ct[i] = T[i, 3]
        for j in range(3):
            ct[i] += T[i, j] * params[W_CTOOL + j]


@kernel
def pose(params: Array, T: Array, Q3: Array, st: Array, Q: Array, info: Array) -> None:
    """Candidates for one pose, given the wrist-centre placements.

    Args:
        params: ``(W_SIZE,)`` the arm part, the mode, then the wrist's.
        T: ``(4, 4)`` target tool pose (base frame).
        Q3: ``(4, 3)`` where joints 1-3 put the wrist centre (see
            :func:`~kinematica.kernels.solvers.arm_point.place`).
        st: What ``place`` reported.
        Q: ``(8, 6)`` out: slot ``2 k + w`` (position branch k, wrist no-flip
            or flip), NaN rows where the branch has no real solution.
        info: ``(INFO_FREE + 6,)`` out (zero on entry): see
            :mod:`kinematica.kernels.ik_check`.
    """
    W0 = (
        _dot(params, W_LH, (T[0, 0], T[0, 1], T[0, 2])),
        _dot(params, W_LH, (T[1, 0], T[1, 1], T[1, 2])),
        _dot(params, W_LH, (T[2, 0], T[2, 1], T[2, 2])),
    )  # the target's axis 6
    Y0 = (
        _dot(params, W_LX, (T[0, 0], T[0, 1], T[0, 2])),
        _dot(params, W_LX, (T[1, 0], T[1, 1], T[1, 2])),
        _dot(params, W_LX, (T[2, 0], T[2, 1], T[2, 2])),
    )  # and its x6
    real = False
    wrist_singular = False
    free = st[ST_FREE] != 0.0 or st[ST_FREE + 1] != 0.0
    for k in range(4):
        if math.isnan(Q3[k, 0]):  # no placement: both wrist rows NaN
            for r in range(2 * k, 2 * k + 2):
                for i in range(6):
                    Q[r, i] = math.nan
            continue
        if k < 2 and free:
            _face(params, Q3, k, W0, st)
        wx, wy, wz, yx, yy, yz = _undo(params, Q3, k, W0, Y0)
        a4, a5, a6, b4, b5, b6, singular = _wrist(params, (wx, wy, wz), (yx, yy, yz), st)
        wrist_singular |= singular
        for j in range(2):
            r = 2 * k + j
            q4 = a4 if j == 0 else b4
            q5 = a5 if j == 0 else b5
            q6 = a6 if j == 0 else b6
            ok = not math.isnan(q4 + q5 + q6)
            real |= ok
            for i in range(3):
                Q[r, i] = Q3[k, i] if ok else math.nan
            Q[r, 3] = q4 if ok else math.nan
            Q[r, 4] = q5 if ok else math.nan
            Q[r, 5] = q6 if ok else math.nan
    for i in range(3):
        info[INFO_FREE + i] = st[ST_FREE + i]
    if wrist_singular:
        info[INFO_FREE + 3] = 1.0
        info[INFO_FREE + 5] = 1.0
    singular = wrist_singular or st[ST_FREE] + st[ST_FREE + 1] + st[ST_FREE + 2] != 0.0
    info[INFO_SINGULAR] = 1.0 if singular else 0.0
    info[INFO_NEAR] = st[ST_NEAR]
    # a target outside the shell has no solution, whatever a clamped double root says
    info[INFO_GAP] = st[ST_GAP] if not real or st[ST_GAP] > 0.0 else math.nan
