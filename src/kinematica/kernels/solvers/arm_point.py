"""Where joints 1-3 (R, R, R|P) put a point: every solution, honest at the edges.

Joints 1 and 2 are revolute (lines ``(h1, p1)``, ``(h2, p2)`` at q = 0); joint 3
is revolute or prismatic. A point ``c`` fixed after joint 3 must reach a target
``c_t``. Write ``u(q3)`` for the vector from ``p2`` to the point once joint 3
has moved, ``d = c_t - p1``, ``ζ = h1ᵀd`` its height along axis 1 and ``ρ`` its
distance from axis 1; joint 1 keeps both. In the plane normal to ``h2``
(orthonormal ``e1, e2``, ``e1 × e2 = h2``) joint 2 turns the part ``(u1, u2)``
of ``u`` to ``(v1, v2)``; with ``H = h2ᵀu``, ``L = |u|²``, ``cα = h1ᵀh2``,
``g = h1ᵀe2`` and ``a`` the distance of axes 1 and 2 (``δ = p2 - p1 = a e1``)::

    h1ᵀ(x - p1) = ζ      →   g v2 = ζ - cα H
    |x - p1|²   = |d|²   →   2 a v1 = |d|² - a² - L
    joint 2 keeps |v|    →   v1² + v2² = u1² + u2²

Three shoulders, decided once per arm (:mod:`kinematica.ik.analytic.arm_point`):

* meet (``a`` = 0, or within 1e-9 of it: PUMA, Stanford): ``|u(q3)| = |d|``
  gives q3 (two roots, in half-angle form), ``v2`` follows and
  ``a + v1 = ±sqrt(ρ² - m²)``, ``m = (H - cα ζ)/g`` (the shoulder sign);
* parallel: ``H(q3) = cα ζ`` gives q3 (SP4, or linear for a slide); the point
  is where the circles of radius ``ρ`` about axis 1 and ``|u⊥|`` about axis 2
  cross: ``v1 = (ρ² - |u⊥|²)/2a - a/2``, ``v2 = ±sqrt(...)/2a`` (Heron's form);
* skew (general): with axes 2 and 3 parallel ``H`` is constant, so ``v2``
  and ``a + v1 = ±sqrt(ρ² - m²)`` (shoulder front, back) come first, then q3
  from ``|u|² = v1² + v2² + H²``; otherwise Pieper's quartic
  (:mod:`kinematica.kernels.solvers.arm_quartic`).

Then ``q2 = atan2(u1 v2 - u2 v1, u1 v1 + u2 v2)`` and q1 turns the point onto
the target about axis 1. Every radicand is a product of a signed difference
of accurate lengths (``ρ`` from the target's coordinates, never
``|d|² - ζ²``; ``|u| - Dmin``, never ``|u|² - Dmin²`` near 0) and positive
factors, so that a point a few nanometres from an axis, or an arm folded
back onto its shoulder, is placed to round-off, not to the square root of it
(:func:`~kinematica.kernels.solvers.arm_base.clamped_root`).

At the edges: a point on axis 1 (``ρ`` below ``SINGULAR_TOL`` times the arm's
size) leaves q1 free, one on axis 2 leaves q2 free (the kernel gives 0 and
flags the joint); a fold's signed distance within round-off
(``DOUBLE_ROOT_TOL``) is a double root, one just past it (``NEAR_TOL``) gives
mirrored candidates for the check; both flag the target as near a fold, as
does a target within ``NEAR_SET_TOL`` (relative) of axis 1 or 2. Targets beyond
the reach get a proven gap before any square is taken.
"""

from __future__ import annotations

import math

import numpy as np

from kinematica.kernels._numba import Array, kernel
from kinematica.kernels.geometry import trig_linear
from kinematica.kernels.solvers.arm_base import (
    A_A,
    A_CA,
    A_COEF,
    A_ELBOW,
    A_FRAME1,
    A_G,
    A_KIND,
    A_P1,
    A_PAR23,
    A_PRISMATIC,
    A_Q3,
    A_REFINE,
    A_ROOTS,
    A_SCALE,
    A_SHELL,
    DOUBLE_ROOT_TOL,
    HUGE_REACH,
    KIND_MEET,
    KIND_PARALLEL,
    NEAR_SET_TOL,
    NEAR_TOL,
    ST_AZIMUTH,
    ST_GAP,
    ST_NEAR,
    ST_RHO,
    ST_SIZE,
    clamped_root,
    slot,
    values,
)
from kinematica.kernels.solvers.arm_quartic import general_position

__all__ = ["place", "shell_gap"]


@kernel
def _q3_pair(params: Array, a: float, b: float, rhs: float, st: Array, out: Array) -> None:
    """The two q3 with ``a cos q3 + b sin q3 = rhs`` into ``out (2,)``; NaN when none.

    A target just past the double root (by ``NEAR_TOL`` of ``a² + b²``) keeps
    the double root (see :func:`clamped_root`).
    """
    r2 = a * a + b * b
    disc = r2 - rhs * rhs
    if abs(disc) <= DOUBLE_ROOT_TOL * r2 or -NEAR_TOL * r2 <= disc < 0.0:
        st[ST_NEAR] = 1.0
    found = trig_linear(a, b, rhs, out)
    if found > 0 and abs(disc) <= DOUBLE_ROOT_TOL * r2:  # one double root
        out[0] = math.atan2(b * rhs, a * rhs)
        out[1] = out[0]
    # found < 0: a = b = 0, q3 moves nothing here (the builder excludes it)
    if found < 0 or (found == 0 and disc < -NEAR_TOL * r2):
        out[0] = math.nan
        out[1] = math.nan


@kernel
def _q3_distance(params: Array, D: float, st: Array, out: Array) -> None:
    """The two q3 with ``|u(q3)| = D`` into ``out (2,)`` (upper root first), NaN when none.

    Half-angle form (see ``A_Q3``): ``cos²ψ = (D² - Dmin²)/4mn`` and
    ``sin²ψ = (Dmax² - D²)/4mn``, each a product of differences of lengths, so
    that a point folded back onto axis 2 (``Dmin = 0``: equal link lengths) or
    stretched out is placed to round-off. A slide: ``q3 = -b ± sqrt(D² - m²)``.
    """
    o = A_Q3
    scale = params[A_SCALE]
    if params[A_PRISMATIC] != 0.0:
        m = params[o + 1]
        s = clamped_root(D - m, D + m, D + m, scale, st)
        out[0] = s - params[o]
        out[1] = -s - params[o]
        return
    lo = params[o + 3]
    hi = params[o + 4]
    c = clamped_root(D - lo, D + lo, D + lo, scale, st)  # 2 sqrt(mn) cos ψ
    s = clamped_root(hi - D, hi + D, hi + D, scale, st)  # 2 sqrt(mn) sin ψ
    psi = math.atan2(s, c)
    out[0] = params[o] + 2.0 * psi
    out[1] = params[o] - 2.0 * psi


@kernel
def _shoulder_v(
    params: Array, zeta: float, rho: float, H: float, sign: float, st: Array, v: Array
) -> None:
    """``v = [v1, v2]`` at the height ``H = h2ᵀu``: ``g v2 = ζ - cα H``, ``a + v1 = ±√(ρ² - m²)``.

    ``m = (H - cα ζ)/g`` is the part of the target's distance from axis 1 that
    the shoulder cannot turn away; ``sign`` picks the shoulder branch.
    """
    g = params[A_G]
    ca = params[A_CA]
    m = abs((H - ca * zeta) / g)
    scale = params[A_SCALE]
    v[0] = -params[A_A] + sign * clamped_root(rho - m, rho + m, rho + m, scale, st)
    v[1] = (zeta - ca * H) / g


@kernel
def _closed(params: Array, zeta: float, dd: float, st: Array, Q3: Array) -> None:
    """Axes 1 and 2 meet (``a`` ~ 0), or are skew with axes 2 ∥ 3 (``H`` ~ constant).

    Then ``|u(q3)|² = |d|² - a² - 2a v1`` (meet: ``|d|²``) gives q3, and
    ``(v1, v2)`` follow from ``H(q3)``; with ``H`` constant they come first and
    ``|u|² = v1² + v2² + H²``. One more pass with ``H`` and ``v1`` at the found
    q3 settles the small coupling of nearly meeting axes (an offset of 1e-10)
    or nearly parallel axes 2 and 3.
    """
    rho = st[ST_RHO]
    a = params[A_A]
    meet = params[A_KIND] == KIND_MEET
    passes = 2 if params[A_REFINE] != 0.0 else 1
    work = np.empty(10)  # scratch, one allocation
    vals = work[0:4]
    roots = work[4:6]
    at_d = work[6:8]  # meet: the roots of |u| = |d|, shared by every slot
    v = work[8:10]
    D = math.hypot(zeta, rho)
    if meet:
        _q3_distance(params, D, st, at_d)
    for A in range(2):
        sign = 1.0 if A == 0 else -1.0
        for B in range(2):
            if not meet:
                _shoulder_v(params, zeta, rho, params[A_COEF + 2], sign, st, v)
                D = math.sqrt(v[0] * v[0] + v[1] * v[1] + params[A_COEF + 2] ** 2)
            for it in range(passes):
                if meet and it == 0:
                    roots[0] = at_d[0]
                    roots[1] = at_d[1]
                else:
                    _q3_distance(params, D, st, roots)
                if meet:
                    q3 = roots[0] if params[A_ROOTS + 2 * A + B] > 0.0 else roots[1]
                else:  # elbow up first: the second root is "up" where elbow_sign · v1 > 0
                    first = 1 if params[A_ELBOW] * v[0] > 0.0 else 0
                    q3 = roots[first] if B == 0 else roots[1 - first]
                values(params, q3, vals)
                _shoulder_v(params, zeta, rho, vals[2], sign, st, v)
                if meet:
                    D = math.sqrt(max(dd - a * a - 2.0 * a * v[0], 0.0))
                else:
                    D = math.sqrt(v[0] * v[0] + v[1] * v[1] + vals[2] * vals[2])
            slot(params, 2 * A + B, q3, v[0], v[1], vals, st, Q3)


@kernel
def _circles(r1: float, r2: float, a: float, scale: float, st: Array) -> float:
    """``2a`` times the height where circles of radii r1, r2 with centres ``a`` apart cross.

    Heron's form ``sqrt((r1+r2+a)(r1+r2-a)(a+r2-r1)(a+r1-r2))``: the factor
    nearest 0 is the fold (the circles touch), the others are positive.
    """
    f2 = r1 + r2 - a
    f3 = a + r2 - r1
    f4 = a + r1 - r2
    other = r1 + r2 + a
    if abs(f2) <= abs(f3) and abs(f2) <= abs(f4):
        return clamped_root(f2, other, other * f3 * f4, scale, st)
    if abs(f3) <= abs(f4):
        return clamped_root(f3, other, other * f2 * f4, scale, st)
    return clamped_root(f4, other, other * f2 * f3, scale, st)


@kernel
def _parallel(params: Array, zeta: float, st: Array, Q3: Array) -> None:
    """Axes 1 and 2 parallel: ``H(q3) = cα ζ``, then two circles in the plane of axis 1."""
    o = A_COEF
    rho = st[ST_RHO]
    a = params[A_A]
    work = np.empty(6)  # scratch, one allocation
    vals = work[0:4]
    roots = work[4:6]
    scale = params[A_SCALE]
    rhs = params[A_CA] * zeta - params[o + 2]
    if params[A_PRISMATIC] != 0.0:
        roots[0] = rhs / params[o + 6]
        roots[1] = math.nan
    else:
        _q3_pair(params, params[o + 6], params[o + 10], rhs, st, roots)
    for A in range(2):
        sign = 1.0 if A == 0 else -1.0
        for B in range(2):
            q3 = roots[B]
            values(params, q3, vals)
            up = math.sqrt(vals[0] * vals[0] + vals[1] * vals[1])
            v1 = (rho - up) * (rho + up) / (2.0 * a) - 0.5 * a
            v2 = sign * _circles(rho, up, a, scale, st) / (2.0 * a)
            slot(params, 2 * A + B, q3, v1, v2, vals, st, Q3)


@kernel
def shell_gap(params: Array, r: float, zeta: float) -> float:
    """Distance of a target at ``|d| = r``, ``h1ᵀd = ζ`` outside the shell (and slab).

    Every reachable point lies in ``r_lo <= |x - p1| <= r_hi`` (triangle
    inequality on ``x - p1 = δ + R2 u`` with ``umin <= |u| <= umax``) and, with
    axes 1 and 2 parallel, ``z_lo <= h1ᵀ(x - p1) <= z_hi``: a proven lower
    bound of the distance to the reachable set (0 inside).
    """
    o = A_SHELL
    return max(0.0, r - params[o + 1], params[o] - r, zeta - params[o + 3], params[o + 2] - zeta)


@kernel
def place(params: Array, ct: Array, Q3: Array, st: Array) -> None:
    """Every (q1, q2, q3) putting the point at ``ct (3,)`` (base frame).

    Args:
        params: The solver's parameters; the arm part at ``[0:A_SIZE]``.
        ct: ``(3,)`` the target point.
        Q3: ``(4, 3)`` out: the four slots (labels of the builder), NaN rows
            where a branch has no real solution.
        st: ``(ST_SIZE,)`` out: free joints, near flag, the shell gap, ``ρ``.
    """
    for i in range(ST_SIZE):
        st[i] = 0.0
    Q3[:, :] = math.nan
    zeta = da = db = 0.0  # ct - p1 along h1, a1, b1
    for i in range(3):
        di = ct[i] - params[A_P1 + i]
        zeta += di * params[A_FRAME1 + 3 * i]
        da += di * params[A_FRAME1 + 3 * i + 1]
        db += di * params[A_FRAME1 + 3 * i + 2]
    big = max(abs(zeta), abs(da), abs(db))
    if not big < HUGE_REACH:  # NaN, or beyond any arm: no squares of it
        st[ST_GAP] = big - params[A_SHELL + 1] if big >= HUGE_REACH else math.nan
        st[ST_RHO] = math.nan
        st[ST_AZIMUTH] = math.nan
        if not st[ST_GAP] > 0.0:
            st[ST_NEAR] = 1.0  # unbounded reach (a slide): no proof either way
        return
    rho = math.hypot(da, db)
    st[ST_RHO] = rho
    st[ST_AZIMUTH] = math.atan2(db, da)
    dd = zeta * zeta + rho * rho
    st[ST_GAP] = shell_gap(params, math.sqrt(dd), zeta)
    scale = params[A_SCALE]
    if rho < NEAR_SET_TOL * scale:
        st[ST_NEAR] = 1.0
    kind = params[A_KIND]
    if kind == KIND_PARALLEL:
        _parallel(params, zeta, st, Q3)
    elif kind == KIND_MEET or params[A_PAR23] != 0.0:
        _closed(params, zeta, dd, st, Q3)
    else:
        general_position(params, zeta, dd, st, Q3)
