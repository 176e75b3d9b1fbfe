"""Pieper's elimination: a point placed by skew axes 1, 2 and a general joint 3.

When axes 1 and 2 are skew (distance ``a`` along their common normal, angle
``α``), joint 1 keeps ``|d|`` and ``ζ = h1ᵀd`` of the target, and the two
resulting equations are linear in ``(cos q2, sin q2)``: the part of ``R2 u``
normal to axis 2 must be ``v = (X / 2a, Y / g)`` in the basis ``(e1, e2)``
with ``X = |d|² - a² - L(q3)`` and ``Y = ζ - cos α · H(q3)``. Joint 2 keeps the
length of that part, so q3 must satisfy (Pieper 1968; Craig, "Introduction to
Robotics", §4.7)::

    F(q3) = sin²α · X² + 4a² · Y² - 4a² sin²α · (L - H²) = 0

``L`` and ``H`` are of degree 1 in ``(cos q3, sin q3)`` for a revolute joint 3,
so ``F`` is a trigonometric polynomial of degree 2: a quartic in
``tan((q3 - θ)/2)`` (up to four real roots), with the shift ``θ`` (a multiple of
π/4) that makes its leading coefficient ``F(θ + π)`` largest, so that every
root is finite and well scaled. For a slide ``L`` is quadratic and ``H`` linear
in q3: a quartic in q3. The roots (:func:`~kinematica.kernels.polynomial.quartic_roots`)
are polished by Newton steps on ``F``, handed on when the point they place
misses the target by at most ``NEAR_TOL`` (times the arm's size); the
error the elimination amplifies near double roots is removed by the check's
Gauss-Newton polishing (:mod:`kinematica.kernels.ik_check`), which works on
the whole arm.
``F ≡ 0`` is a self-motion of joints 1-3: every q3 reaches the target, q3 is
free and four representatives are given.
"""

from __future__ import annotations

import math

import numpy as np

from kinematica.kernels._numba import Array, kernel
from kinematica.kernels.polynomial import quartic_roots
from kinematica.kernels.solvers.arm_base import (
    A_A,
    A_CA,
    A_COEF,
    A_FOURIER,
    A_G,
    A_PRISMATIC,
    A_SCALE,
    NEAR_TOL,
    ST_FREE,
    ST_NEAR,
    slot,
    values,
)

__all__ = [
    "IMAG_TOL",
    "MAX_NEWTON_STEP",
    "NEWTON_STEPS",
    "SELF_MOTION_TOL",
    "general_position",
]

#: A quartic root with ``|Im t| <= IMAG_TOL (1 + |t|)`` is taken as real and
#: polished: a double root (target on the workspace boundary) splits into a
#: complex pair of size ~sqrt(ulp).
IMAG_TOL = 1e-6
#: Newton steps on ``F`` for each quartic root.
NEWTON_STEPS = 2
#: Newton steps on ``F`` longer than this (rad or m) are round-off at a double
#: root (``F' ≈ 0``) and are skipped: the closed form is far closer than that.
MAX_NEWTON_STEP = 1e-4
#: ``F`` is identically 0 (a self-motion of joints 1-3) when its largest
#: leading coefficient is below this fraction of its Fourier coefficients.
SELF_MOTION_TOL = 1e-14

_QUARTER = 0.25 * math.pi


@kernel
def _bounded(f: float, df: float) -> float:
    """The Newton step ``f / df``, or 0 when it is longer than ``MAX_NEWTON_STEP``."""
    step = f / df if df != 0.0 else math.nan
    return step if abs(step) <= MAX_NEWTON_STEP else 0.0


@kernel
def _sort4(q: Array) -> None:
    """Sort ``q (4,)`` ascending, NaN last (insertion sort)."""
    for i in range(1, 4):
        v = q[i]
        j = i
        while j > 0 and (math.isnan(q[j - 1]) or q[j - 1] > v) and not math.isnan(v):
            q[j] = q[j - 1]
            j -= 1
        q[j] = v


@kernel
def _real(t: complex, st: Array) -> float:
    """``t.real`` where ``t`` counts as real (``IMAG_TOL``), else NaN.

    A root dropped with ``|Im t| <= sqrt(NEAR_TOL) (1 + |t|)`` is a double root
    split by a target just past a fold (by about ``Im²``): ``st[ST_NEAR]`` is raised.
    """
    size = 1.0 + abs(t)
    if abs(t.imag) <= IMAG_TOL * size:
        return t.real
    if abs(t.imag) <= math.sqrt(NEAR_TOL) * size:
        st[ST_NEAR] = 1.0
    return math.nan


@kernel
def trig_roots(F: Array, size: float, q: Array, st: Array) -> bool:
    """The real roots of ``F0 + F1 cos q + F2 sin q + F3 cos 2q + F4 sin 2q`` in ``q (4,)``.

    Args:
        F: ``(5,)`` the coefficients.
        size: The magnitude of the terms they were computed from: ``F`` within
            ``SELF_MOTION_TOL`` of it at every sample is 0 to round-off.
        q: ``(4,)`` out.
        st: Arm state (``ST_NEAR`` raised for a root just off the real axis).

    Returns:
        True for ``F ≡ 0`` (every q is a root: ``q`` holds -π/2, 0, π/2, π).
        Otherwise the roots in (-π, π], sorted, NaN-padded.
    """
    best = -1.0
    kbest = 0
    for k in range(8):
        th = k * _QUARTER + math.pi
        val = F[0] + F[1] * math.cos(th) + F[2] * math.sin(th)
        val += F[3] * math.cos(2.0 * th) + F[4] * math.sin(2.0 * th)
        if abs(val) > best:
            best = abs(val)
            kbest = k
    if not best > SELF_MOTION_TOL * size:
        for i in range(4):
            q[i] = (i - 1) * 0.5 * math.pi if i < 3 else math.pi
        return True
    th = kbest * _QUARTER
    c = math.cos(th)
    s = math.sin(th)
    c2 = math.cos(2.0 * th)
    s2 = math.sin(2.0 * th)
    g0 = F[0]
    a1 = c * F[1] + s * F[2]
    b1 = c * F[2] - s * F[1]
    a2 = c2 * F[3] + s2 * F[4]
    b2 = c2 * F[4] - s2 * F[3]
    coef = np.empty(5)  # (1 + t²)² F(θ + 2 atan t), highest power first
    coef[0] = g0 - a1 + a2
    coef[1] = 2.0 * b1 - 4.0 * b2
    coef[2] = 2.0 * g0 - 6.0 * a2
    coef[3] = 2.0 * b1 + 4.0 * b2
    coef[4] = g0 + a1 + a2
    roots = np.empty(4, dtype=np.complex128)
    quartic_roots(coef, roots)
    for i in range(4):
        x = th + 2.0 * math.atan(_real(roots[i], st))
        for _ in range(NEWTON_STEPS):
            cx = math.cos(x)
            sx = math.sin(x)
            c2x = cx * cx - sx * sx
            s2x = 2.0 * sx * cx
            f = F[0] + F[1] * cx + F[2] * sx + F[3] * c2x + F[4] * s2x
            df = F[2] * cx - F[1] * sx + 2.0 * (F[4] * c2x - F[3] * s2x)
            x -= _bounded(f, df)
        q[i] = math.atan2(math.sin(x), math.cos(x))
    _sort4(q)
    return False


@kernel
def slide_roots(k: Array, q: Array, st: Array) -> None:
    """The real roots of the quartic ``k (5,)`` (highest power first) in ``q (4,)``, sorted.

    ``st[ST_NEAR]`` is raised for a root just off the real axis (see :func:`trig_roots`).
    """
    roots = np.empty(4, dtype=np.complex128)
    quartic_roots(k, roots)
    for i in range(4):
        x = _real(roots[i], st)
        for _ in range(NEWTON_STEPS):
            f = 0.0
            df = 0.0
            for j in range(5):
                df = df * x + f
                f = f * x + k[j]
            x -= _bounded(f, df)
        q[i] = x
    _sort4(q)


@kernel
def _q3_roots(params: Array, zeta: float, dd: float, q: Array, st: Array) -> bool:
    """Pieper's roots q3 ``(4,)`` for a target; True for a self-motion."""
    a = params[A_A]
    ca = params[A_CA]
    o = A_COEF
    L0 = params[o + 3]
    H0 = params[o + 2]
    if params[A_PRISMATIC] != 0.0:
        sa2 = params[A_G] * params[A_G]
        a2 = a * a
        L1 = params[o + 7]
        H1 = params[o + 6]
        x1 = -L1
        x0 = dd - a2 - L0
        y1 = -ca * H1
        y0 = zeta - ca * H0
        k = np.empty(5)  # X = -q² + x1 q + x0, Y = y1 q + y0, L - H² = P0 q² + P1 q + P2
        k[0] = sa2
        k[1] = -2.0 * sa2 * x1
        k[2] = sa2 * (x1 * x1 - 2.0 * x0) + 4.0 * a2 * y1 * y1 - 4.0 * a2 * sa2 * (1.0 - H1 * H1)
        k[3] = 2.0 * sa2 * x1 * x0 + 8.0 * a2 * y1 * y0 - 4.0 * a2 * sa2 * (L1 - 2.0 * H1 * H0)
        k[4] = sa2 * x0 * x0 + 4.0 * a2 * y0 * y0 - 4.0 * a2 * sa2 * (L0 - H0 * H0)
        slide_roots(k, q, st)
        return False
    X0 = dd - a * a - L0
    Y0 = zeta - ca * H0
    Xs = dd + a * a + abs(L0)  # the sizes X0 and Y0 were computed at
    Ys = abs(zeta) + abs(ca * H0)
    inv = 1.0 / params[A_SCALE] ** 4
    F = np.empty(5)
    size = 0.0
    for j in range(5):
        o = A_FOURIER + j
        F[j] = (
            X0 * X0 * params[o]
            + X0 * params[o + 5]
            + Y0 * Y0 * params[o + 10]
            + Y0 * params[o + 15]
            + params[o + 20]
        ) * inv
        size += (
            Xs * Xs * abs(params[o])
            + Xs * abs(params[o + 5])
            + Ys * Ys * abs(params[o + 10])
            + Ys * abs(params[o + 15])
            + abs(params[o + 20])
        ) * inv
    return trig_roots(F, size, q, st)


@kernel
def general_position(params: Array, zeta: float, dd: float, st: Array, Q3: Array) -> None:
    """Skew axes 1, 2, axis 3 not parallel to axis 2: Pieper's roots, one slot each.

    Args:
        params: The arm part (see :mod:`kinematica.kernels.solvers.arm_base`).
        zeta: ``h1ᵀ(ct - p1)``: the target point's height along axis 1 (m).
        dd: ``|ct - p1|²``.
        st: What :func:`~kinematica.kernels.solvers.arm_point.place` reports.
        Q3: ``(4, 3)`` out: a slot per root, ascending q3, NaN-padded.
    """
    a = params[A_A]
    ca = params[A_CA]
    g = params[A_G]
    scale = params[A_SCALE]
    roots = np.empty(4)
    if _q3_roots(params, zeta, dd, roots, st):
        st[ST_FREE + 2] = 1.0
    vals = np.empty(4)
    for k in range(4):
        q3 = roots[k]
        values(params, q3, vals)
        v1 = (dd - a * a - vals[3]) * (0.5 / a)
        v2 = (zeta - ca * vals[2]) / g
        miss = abs(math.hypot(v1, v2) - math.hypot(vals[0], vals[1]))
        if miss > NEAR_TOL * scale:  # a complex root taken for real: drop it
            q3 = math.nan
        slot(params, k, q3, v1, v2, vals, st, Q3)
