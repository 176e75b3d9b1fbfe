"""Where the first three joints put a point: the geometry, computed once per arm.

Joints 1 and 2 are revolute (lines ``(h1, p1)``, ``(h2, p2)`` at q = 0); joint 3
is revolute or prismatic. A point ``c`` fixed after joint 3 (a wrist centre, or
the tool origin with the later joints at 0) must reach a target. This module
reads the geometry from the joint axes and fills the named fields of the core's
``ArmPoint`` (``cpp/include/kinematica/solvers/arm_point.hpp``, see there for the
maths): which of three shoulders it is (axes 1 and 2 meet, are parallel, or are
skew), the motion ``u(q3)`` of the point as seen from axis 2, its expression on a
frame of axis 2, the bounds of the reachable shell, and the branch labels.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

import kinematica._core as _core
from kinematica.core import Chain
from kinematica.dh.lines import AXIS_ANGLE_TOL, cross3, length_tol, lines_parallel, normal_feet

__all__ = [
    "ELBOW_BENDS",
    "PROBES",
    "RANK_TOL",
    "ArmGeometry",
    "arm_geometry",
    "places_point",
    "unit_normal",
]

FloatArray = NDArray[np.float64]
_Shoulder = _core.decoupled.Shoulder

#: Joints 1-3 place the point when, at one of :data:`PROBES`, the smallest
#: singular value of the point's 3 x 3 Jacobian exceeds this times the largest.
RANK_TOL = 1e-6
#: Configurations of joints 1-3 at which that rank is tested (fixed, so that
#: the decision depends on the geometry alone).
PROBES = np.array([[0.3, -0.7, 1.1], [-1.3, 0.4, -0.6], [2.1, 1.7, 0.2]])


@dataclass(frozen=True, slots=True, eq=False)
class ArmGeometry:
    """The core's arm part, and the names of its four slots.

    Attributes:
        arm: The filled ``kinematica._core.decoupled.ArmPoint``.
        labels: ``(4,)`` names of the position branches (slots).
        kind: ``"meet"``, ``"parallel"`` or ``"general"`` (axes 1 and 2).
        parallel23: True when axes 2 and 3 are parallel (revolute joint 3).
    """

    arm: Any
    labels: tuple[str, ...]
    kind: str
    parallel23: bool


def places_point(chain: Chain, c_tool: FloatArray) -> bool:
    """True when joints 1-3 move a point in three independent directions.

    Args:
        chain: The arm.
        c_tool: ``(3,)`` the point in the tool frame when joints 4..n are at 0.
    """
    q = np.zeros((len(PROBES), chain.dof))
    q[:, :3] = PROBES
    return bool((chain.core.point_rank_ratios(q, c_tool) > RANK_TOL).any())


def unit_normal(h: FloatArray) -> FloatArray:
    """A unit vector normal to the unit vector ``h``."""
    n = cross3(h, [1.0, 0.0, 0.0])
    if np.linalg.norm(n) < 0.5:
        n = cross3(h, [0.0, 1.0, 0.0])
    return n / np.linalg.norm(n)


def arm_geometry(
    h: FloatArray, p: FloatArray, prismatic: bool, c: FloatArray, size: float
) -> ArmGeometry | None:
    """The geometry of joints 1-3 placing ``c``, or None when they cannot.

    Args:
        h: ``(3, 3)`` unit directions of joints 1..3 at q = 0 (base frame).
        p: ``(3, 3)`` a point on each axis.
        prismatic: Joint 3 slides (joints 1 and 2 are revolute).
        c: ``(3,)`` the point at q = 0.
        size: The arm's size (m, :attr:`Features.size`): axes are parallel and
            meet by :mod:`kinematica.dh.lines`' tolerances.

    Returns:
        None when axes 1 and 2 coincide, the point lies on axis 3, or three
        parallel axes keep the point in a plane.
    """
    h1, h2, h3 = (np.asarray(v, float) / np.linalg.norm(v) for v in h)
    p1, p2, p3 = (np.asarray(v, float) for v in p)
    c = np.asarray(c, float)
    tol = length_tol(size)
    # the lengths the solver's own tolerances scale with (its double roots, its polish)
    scale = 1.0 + float(np.linalg.norm(c - p1) + np.linalg.norm(p2 - p1))
    ca, sa = float(h1 @ h2), float(np.linalg.norm(cross3(h1, h2)))
    if sa <= AXIS_ANGLE_TOL:
        delta = (p2 - p1) - ((p2 - p1) @ h1) * h1
        a = float(np.linalg.norm(delta))
        if a <= tol:
            return None  # axes 1 and 2 coincide
        kind, p2 = _Shoulder.parallel, p1 + delta
        e1 = delta / a
        e2 = cross3(h2, e1)
    else:
        f1, f2 = normal_feet(h1, p1, h2, p2)
        a = float(np.linalg.norm(f2 - f1))
        if a <= tol:  # they meet, or all but (an offset of 1e-10)
            kind, p1, p2 = _Shoulder.meet, f1, f2
            e2 = (h1 - ca * h2) / sa
            e1 = cross3(e2, h2)
            a = float((f2 - f1) @ e1)  # signed: f2 - f1 is along h1 × h2, so along e1
        else:
            kind, p1, p2 = _Shoulder.general, f1, f2
            e1 = (f2 - f1) / a
            e2 = cross3(h2, e1)
    if prismatic:
        U = np.array([c - p2, h3, np.zeros(3)])
        parallel23 = False
    else:
        r = c - p3
        rpar = (r @ h3) * h3
        U = np.array([p3 - p2 + rpar, r - rpar, cross3(h3, r - rpar)])
        if float(np.linalg.norm(U[1])) <= tol:
            return None  # the point is on axis 3
        parallel23 = lines_parallel(h3, h2)
        if kind == _Shoulder.parallel and parallel23:
            return None  # three parallel axes: the point moves in a plane
    coef = U @ np.stack([e1, e2, h2, np.zeros(3)], axis=1)  # u1, u2, H, L
    if prismatic:
        L = [float(U[0] @ U[0]), 2 * float(U[0] @ U[1]), 1.0]
        umin = float(np.linalg.norm(U[0] - (U[0] @ h3) * h3))
        umax = math.inf
        Hq = float(h2 @ h3)
        Hrange = (-math.inf, math.inf) if abs(Hq) > 0 else (coef[0, 2], coef[0, 2])
    else:
        L = [float(U[0] @ U[0] + U[1] @ U[1]), 2 * float(U[0] @ U[1]), 2 * float(U[0] @ U[2])]
        rL = math.hypot(L[1], L[2])
        umin, umax = math.sqrt(max(L[0] - rL, 0.0)), math.sqrt(L[0] + rL)
        rH = math.hypot(coef[1, 2], coef[2, 2])
        Hrange = (coef[0, 2] - rH, coef[0, 2] + rH)
    coef[:, 3] = L
    b3 = float(U[0] @ h3)
    m3 = float(np.linalg.norm(U[0] - b3 * h3))  # distance of axis 3 from p2
    beta = dmin = dmax = 0.0  # |u(q3)| in half-angle form (revolute joint 3)
    if not prismatic:
        n3 = float(np.linalg.norm(U[1]))
        if m3 <= tol and (kind == _Shoulder.meet or parallel23):
            return None  # axis 3 through p2: |u| does not depend on q3
        beta = math.atan2(float(U[0] @ U[2]), float(U[0] @ U[1]))
        dmin, dmax = math.hypot(b3, m3 - n3), math.hypot(b3, m3 + n3)
    g = float(h1 @ e2)
    # |x - p1| = |δ + R2 u| lies in [max(0, umin - a, a - umax), a + umax]; with
    # axes 1 and 2 parallel h1ᵀ(x - p1) = cα H lies in cα [Hmin, Hmax]
    zlo, zhi = (
        sorted(ca * v for v in Hrange) if kind == _Shoulder.parallel else (-math.inf, math.inf)
    )
    shell = (max(0.0, umin - abs(a), abs(a) - umax), abs(a) + umax, zlo, zhi)
    a1 = unit_normal(h1)
    frame1 = np.stack([h1, a1, np.cross(h1, a1)], axis=1)
    xframe = np.stack([h2, e1, e2, p2 - p1]) @ frame1[:, 1:]
    # Elbow up: the elbow lies on the side of the shoulder-wrist line that
    # axis 1 points to: sign(h1ᵀ(h2 × R2 u)) s_e > 0 with s_e = uᵀ((e0 - p2) × h2)
    # (e0: the point of axis 3 nearest p2), Lee's ELBOW indicator read
    # geometrically. The first factor is sign(g v1); with axes 2 ∥ 3,
    # s_e = (h2ᵀh3 / 2) dL/dq3, which is -s (resp. +s) times that on the
    # first (second) root of a pair. So the second root is "up" exactly when
    # g v1 (h2ᵀh3) > 0.
    elbow_sign = g * float(np.sign(h2 @ h3))
    # axes 1 and 2 meet: sign(g v1) is the shoulder sign (g > 0), so the order is fixed
    root_signs = np.array([[1.0, -1.0], [1.0, -1.0]])
    if kind == _Shoulder.meet and parallel23:
        root_signs[0 if elbow_sign > 0 else 1] *= -1.0
    # a second pass where the closed form neglects a small coupling: axes 1, 2
    # meeting but for an offset, or axes 2, 3 parallel but for a twist
    refine = (kind == _Shoulder.meet and a != 0.0) or (
        parallel23 and abs(coef[1, 2]) + abs(coef[2, 2]) > _core.decoupled.DOUBLE_ROOT_TOL * scale
    )
    fourier = np.zeros((5, 5))
    if kind == _Shoulder.general and not prismatic:
        fourier = _fourier_matrix(a, sa, ca, np.array(L), coef[:, 2])
    arm = _core.decoupled.ArmPoint()
    arm.kind = kind
    arm.prismatic = bool(prismatic)
    arm.parallel23 = bool(parallel23)
    arm.p1 = p1
    arm.h1, arm.a1, arm.b1 = frame1.T
    arm.h2 = h2
    arm.h3 = h3
    arm.xframe = xframe
    arm.u1, arm.u2, arm.H, arm.L = coef.T
    arm.a = a
    arm.ca = ca
    arm.g = g
    arm.elbow = elbow_sign
    arm.upper_root = root_signs > 0.0
    arm.scale = scale
    arm.r_lo, arm.r_hi, arm.z_lo, arm.z_hi = shell
    arm.fourier = fourier
    arm.beta, arm.dmin, arm.dmax = beta, dmin, dmax
    arm.b3, arm.m3 = b3, m3
    arm.refine = bool(refine)
    names = {_Shoulder.meet: "meet", _Shoulder.parallel: "parallel", _Shoulder.general: "general"}
    return ArmGeometry(arm, _labels(kind, prismatic, parallel23), names[kind], parallel23)


def _trig_square(x0: float, xc: float, xs: float) -> FloatArray:
    """Fourier coefficients ``[g0, a1, b1, a2, b2]`` of ``(x0 + xc cos + xs sin)²``."""
    return np.array(
        [
            x0 * x0 + (xc * xc + xs * xs) / 2,
            2 * x0 * xc,
            2 * x0 * xs,
            (xc * xc - xs * xs) / 2,
            xc * xs,
        ]
    )


def _fourier_matrix(a: float, sa: float, ca: float, L: FloatArray, H: FloatArray) -> FloatArray:
    """``(5, 5)``: rows turn ``[X0², X0, Y0², Y0, 1]`` into the Fourier coefficients of F.

    ``F(q3) = sin²α X² + 4a² Y² - 4a² sin²α (L - H²)`` (Pieper's elimination,
    see ``cpp/include/kinematica/solvers/arm_quartic.hpp``) with
    ``X = X0 - L1 cos - L2 sin`` (``X0 = |d|² - a² - L0``) and
    ``Y = Y0 - cα (H1 cos + H2 sin)`` (``Y0 = ζ - cα H0``).
    """
    sa2, a2 = sa * sa, a * a
    F = np.zeros((5, 5))
    F[0, 0] = sa2
    F[1, 1:3] = -2 * sa2 * L[1:]
    F[2, 0] = 4 * a2
    F[3, 1:3] = -8 * a2 * ca * H[1:]
    F[4] = (
        sa2 * _trig_square(0.0, -L[1], -L[2])
        + 4 * a2 * _trig_square(0.0, -ca * H[1], -ca * H[2])
        - 4 * a2 * sa2 * (np.array([L[0], L[1], L[2], 0.0, 0.0]) - _trig_square(*H))
    )
    return F


#: The two elbows of a meeting shoulder whose axes 2 and 3 are not parallel (the arm
#: does not move in a plane, so "up" and "down" mean nothing): joint 3 turned from its
#: stretched angle q3* (where the point is farthest from the shoulder) by +bend or
#: -bend (right-hand rule about axis 3), bend in [0, π]; the two reach the same
#: distance. Slot order: q3* + bend first.
ELBOW_BENDS = ("elbow bent positive", "elbow bent negative")


def _labels(kind: _core.decoupled.Shoulder, prismatic: bool, parallel23: bool) -> tuple[str, ...]:
    if kind == _Shoulder.meet and parallel23:
        return (
            "shoulder right, elbow up",
            "shoulder right, elbow down",
            "shoulder left, elbow up",
            "shoulder left, elbow down",
        )
    if kind == _Shoulder.general and parallel23:
        return (
            "shoulder front, elbow up",
            "shoulder front, elbow down",
            "shoulder back, elbow up",
            "shoulder back, elbow down",
        )
    if kind == _Shoulder.meet:
        second = ("slide out", "slide in") if prismatic else ELBOW_BENDS
        return tuple(f"shoulder {s}, {e}" for s in ("right", "left") for e in second)
    return tuple(f"position {k}" for k in range(1, 5))
