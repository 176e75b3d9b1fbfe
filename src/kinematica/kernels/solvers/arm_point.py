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

* meet (``a = 0``: PUMA, Stanford): ``L(q3) = |d|²`` gives q3 (two roots:
  SP3, or a quadratic for a slide), ``v2`` follows and
  ``v1 = ±sqrt(ρ² - k²)``, ``k = (cα ζ - H)/sin α`` (the shoulder sign);
* parallel: ``H(q3) = cα ζ`` gives q3 (SP4, or linear for a slide); the point
  is where the circles of radius ``ρ`` about axis 1 and ``|u⊥|`` about axis 2
  cross: ``v1 = (ρ² - |u⊥|²)/2a - a/2``, ``v2 = ±sqrt(...)/2a`` (Heron's form);
* skew (general): with axes 2 and 3 parallel ``H`` is constant, ``v2``
  follows and ``a + v1 = ±sqrt(ρ² - m²)``, ``m = (H - cα ζ)/g`` (shoulder
  front, back), then q3 from ``L``; otherwise Pieper's quartic
  (:mod:`kinematica.kernels.solvers.arm_quartic`).

Then ``q2 = atan2(u1 v2 - u2 v1, u1 v1 + u2 v2)`` and q1 turns the point onto
the target about axis 1. Every radicand is written as a product of
differences of accurate lengths (``ρ`` from the target's coordinates, never
``|d|² - ζ²``), so that a point a few nanometres from an axis is placed to
round-off, not to the square root of it.

At the edges: a point on axis 1 (``ρ`` below ``SINGULAR_TOL`` times the arm's
size) leaves q1 free, one on axis 2 leaves q2 free (the kernel gives 0 and
flags the joint); a radicand negative by at most ``NEAR_TOL`` of its scale is a
double root (its candidate is handed to the check) and flags the target as
near a fold; so does a target within ``NEAR_TOL`` (relative) of axis 1 or 2.
Targets beyond the reach get a proven gap before any square is taken.
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
    A_ROOTS,
    A_SA,
    A_SCALE,
    A_SHELL,
    HUGE_REACH,
    KIND_MEET,
    KIND_PARALLEL,
    NEAR_TOL,
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
    if abs(disc) <= NEAR_TOL * r2:
        st[ST_NEAR] = 1.0
    found = trig_linear(a, b, rhs, out)
    # found < 0: a = b = 0, q3 moves nothing here (the builder excludes it)
    if found < 0 or (found == 0 and disc < -NEAR_TOL * r2):
        out[0] = math.nan
        out[1] = math.nan


@kernel
def _meet(params: Array, dz: Array, dd: float, st: Array, Q3: Array) -> None:
    """Axes 1 and 2 meet: ``L(q3) = |d|²``, then the shoulder sign of ``v1``."""
    o = A_COEF
    zeta = dz[0]
    rho = st[ST_RHO]
    ca = params[A_CA]
    sa = params[A_SA]
    g = params[A_G]
    vals = np.empty(4)
    roots = np.empty(2)
    prismatic = params[A_PRISMATIC] != 0.0
    if prismatic:  # L0 + L1 q + q² = |d|²
        half = 0.5 * params[o + 7]
        rad = half * half - params[o + 3] + dd
        s = clamped_root(rad, max(dd, half * half), st)
        roots[0] = s - half
        roots[1] = -s - half
    else:
        _q3_pair(params, params[o + 7], params[o + 11], dd - params[o + 3], st, roots)
    for A in range(2):
        sign = 1.0 if A == 0 else -1.0
        for B in range(2):
            q3 = roots[0] if params[A_ROOTS + 2 * A + B] > 0.0 else roots[1]
            values(params, q3, math.cos(q3), math.sin(q3), vals)
            H = vals[2]
            k = abs(ca * zeta - H) / sa
            v1 = sign * clamped_root((rho - k) * (rho + k), (rho + k) * (rho + k), st)
            v2 = (zeta - ca * H) / g
            slot(params, 2 * A + B, q3, v1, v2, vals, dz, st, Q3)


@kernel
def _parallel(params: Array, dz: Array, st: Array, Q3: Array) -> None:
    """Axes 1 and 2 parallel: ``H(q3) = cα ζ``, then two circles in the plane of axis 1."""
    o = A_COEF
    rho = st[ST_RHO]
    a = params[A_A]
    vals = np.empty(4)
    roots = np.empty(2)
    rhs = params[A_CA] * dz[0] - params[o + 2]
    if params[A_PRISMATIC] != 0.0:
        roots[0] = rhs / params[o + 6]
        roots[1] = math.nan
    else:
        _q3_pair(params, params[o + 6], params[o + 10], rhs, st, roots)
    for A in range(2):
        sign = 1.0 if A == 0 else -1.0
        for B in range(2):
            q3 = roots[B]
            values(params, q3, math.cos(q3), math.sin(q3), vals)
            up = math.sqrt(vals[0] * vals[0] + vals[1] * vals[1])
            v1 = (rho - up) * (rho + up) / (2.0 * a) - 0.5 * a
            rad = (rho + up + a) * (rho + up - a) * (a + up - rho) * (a + rho - up)
            size = (rho + up + a) ** 4
            v2 = sign * clamped_root(rad, size, st) / (2.0 * a)
            slot(params, 2 * A + B, q3, v1, v2, vals, dz, st, Q3)


@kernel
def _general23(params: Array, dz: Array, dd: float, st: Array, Q3: Array) -> None:
    """Skew axes 1, 2 and axes 2 ∥ 3: ``H`` is constant, so ``v2`` and ``a + v1`` are known."""
    o = A_COEF
    zeta = dz[0]
    rho = st[ST_RHO]
    a = params[A_A]
    ca = params[A_CA]
    g = params[A_G]
    H0 = params[o + 2]
    v2 = (zeta - ca * H0) / g
    m = abs(H0 - ca * zeta) / g
    s = clamped_root((rho - m) * (rho + m), (rho + m) * (rho + m), st)
    vals = np.empty(4)
    roots = np.empty(2)
    for A in range(2):
        sign = 1.0 if A == 0 else -1.0
        v1 = -a + sign * s  # shoulder front (A = 0) or back
        L = dd + a * a - 2.0 * a * (a + v1)
        _q3_pair(params, params[o + 7], params[o + 11], L - params[o + 3], st, roots)
        # elbow up first: the second root is "up" where elbow_sign · v1 > 0
        first = 1 if params[A_ELBOW] * v1 > 0.0 else 0
        for B in range(2):
            q3 = roots[first] if B == 0 else roots[1 - first]
            values(params, q3, math.cos(q3), math.sin(q3), vals)
            slot(params, 2 * A + B, q3, v1, v2, vals, dz, st, Q3)


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
    dz = np.empty(3)
    big = 0.0
    for j in range(3):
        dj = 0.0
        for i in range(3):
            dj += (ct[i] - params[A_P1 + i]) * params[A_FRAME1 + 3 * i + j]
        dz[j] = dj
        big = max(big, abs(dj))
    if not big < HUGE_REACH:  # NaN, or beyond any arm: no squares of it
        st[ST_GAP] = big - params[A_SHELL + 1] if big >= HUGE_REACH else math.nan
        st[ST_RHO] = math.nan
        if not st[ST_GAP] > 0.0:
            st[ST_NEAR] = 1.0  # unbounded reach (a slide): no proof either way
        return
    rho = math.hypot(dz[1], dz[2])
    st[ST_RHO] = rho
    dd = dz[0] * dz[0] + rho * rho
    st[ST_GAP] = shell_gap(params, math.sqrt(dd), dz[0])
    scale = params[A_SCALE]
    if rho < NEAR_TOL * scale:
        st[ST_NEAR] = 1.0
    kind = params[A_KIND]
    if kind == KIND_MEET:
        _meet(params, dz, dd, st, Q3)
    elif kind == KIND_PARALLEL:
        _parallel(params, dz, st, Q3)
    elif params[A_PAR23] != 0.0:
        _general23(params, dz, dd, st, Q3)
    else:
        general_position(params, dz, dd, st, Q3)
