"""Closed-form position IK of 3R arms: anthropomorphic and elbow with shoulder offset.

Both arms have a first axis ``h1`` and two parallel axes 2 and 3 (direction
``k``) not parallel to it. Written as a product of exponentials,
``p(q) = E1(q1)·E2(q2)·E3(q3)·x`` with ``x`` the tool origin at q = 0, the
rotations about axes parallel to ``k`` keep the height ``k·x``, so

* ``k·E1⁻¹(p) = k·x`` fixes q1 (Paden-Kahan subproblem 4: two solutions,
  seed 002's ``q1 = atan2(py, px)`` and ``q1 + π``), then
* ``E2·E3·x = E1⁻¹(p)`` is the planar 2R triangle in the plane normal to
  ``k`` (two solutions, seed 002's ``cos q3 = (r² - a2² - a3²)/(2 a2 a3)``),

up to four solutions, for any offsets, base, tool and DH convention.

Branch labels (``σ = (p - p1)·(h1 × k1)`` with ``k1`` the current axis-2
direction, ψ the angle of link 3 relative to link 2 about ``k1``):

* ``"shoulder right"``: σ >= 0, the target lies on the ``h1 × k1`` side of
  axis 1. For an arm whose axes 1 and 2 meet this is Lee and Ziegler's right
  arm (a positive joint-2 rotation raises the wrist along h1); for seed 002's
  arm, ``q1 = atan2(py, px)``. ``"shoulder left"``: σ <= 0.
* ``"elbow up"``: in the arm's plane, the elbow (axis 3) lies on the side of
  the line from the shoulder (axis 2) to the target toward which ``h1``
  points (ψ has the sign of ``-(p - s)·(h1 × k1)``, ψ <= 0 when that is 0);
  ``"elbow down"``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.ik.analytic.planar import (
    REACH_TOL,
    SINGULAR_TOL,
    Plane,
    TwoLink,
    as_complex,
    skew,
    targets_array,
)
from kinematica.ik.candidates import Candidates
from kinematica.ik.structure import PARALLEL_TOL
from kinematica.robot.robot import Robot
from kinematica.robot.structure import classify

__all__ = [
    "AxisHeight",
    "common_normal",
    "height_angles",
    "height_angles_one",
    "make_arm3r_solver",
]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

LABELS = (
    "shoulder right, elbow up",
    "shoulder right, elbow down",
    "shoulder left, elbow up",
    "shoulder left, elbow down",
)


def common_normal(
    h1: FloatArray, p1: FloatArray, h2: FloatArray, p2: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """The feet ``(3,), (3,)`` on two non-parallel lines of their common normal."""
    n = np.cross(h1, h2)
    A = np.stack([h1, -h2, n], axis=1)
    t = np.linalg.solve(A, p2 - p1)
    return p1 + t[0] * h1, p2 + t[1] * h2


@dataclass(frozen=True)
class AxisHeight:
    """Paden-Kahan subproblem 4 about one axis: ``k·rot(h, θ)·v = d``.

    Attributes:
        h: ``(3,)`` unit rotation axis.
        k: ``(3,)`` unit direction along which the height is measured.
        W: ``(3, 3)`` columns ``k - (k·h) h``, ``k × h``, ``(k·h) h``: the
            coefficients ``A, B, C = v @ W`` of ``A cos θ + B sin θ + C``.
    """

    h: FloatArray
    k: FloatArray
    W: FloatArray

    @classmethod
    def about(cls, h: FloatArray, k: FloatArray) -> AxisHeight:
        """The subproblem for axis ``h`` and direction ``k`` (not parallel)."""
        kh = float(k @ h)
        return cls(h, k, np.stack([k - kh * h, np.cross(k, h), kh * h], axis=1))

    def solve(
        self, v: FloatArray, d: FloatArray | float
    ) -> tuple[FloatArray, FloatArray, FloatArray, BoolArray]:
        """Both angles θ for vectors ``v (..., 3)``, heights ``d (...)`` (:func:`height_angles`)."""
        A, B, C = np.moveaxis(v @ self.W, -1, 0)
        return height_angles(A, B, C, d)


def height_angles(
    A: FloatArray, B: FloatArray, C: FloatArray, d: FloatArray | float
) -> tuple[FloatArray, FloatArray, FloatArray, BoolArray]:
    """Subproblem 4 from its coefficients: ``A cos θ + B sin θ + C = d``, batched.

    Returns:
        ``cos θ, sin θ`` ``(..., 2)``: branch 0 is θ = φ + δ, where the left
        side decreases with θ, branch 1 θ = φ - δ; NaN without a real root.
        ``gap (...)``: how far ``d`` lies outside the range ``C ± |(A, B)|``
        (0 when solvable). ``singular (...)``: ``A = B = 0`` and ``C = d``, any
        θ solves (θ = 0 given for both branches).
    """
    rho, e = np.hypot(A, B), d - C
    singular = (rho < SINGULAR_TOL) & (np.abs(e) < SINGULAR_TOL)
    safe = np.where(rho > 0.0, rho, 1.0)
    cd = e / safe
    cd = np.where((np.abs(cd) <= 1.0 + REACH_TOL) & (rho > 0.0), cd, np.nan)
    cd = np.minimum(np.maximum(cd, -1.0), 1.0)
    sd = np.sqrt(1.0 - cd * cd)[..., None] * np.array([1.0, -1.0])
    cf, sf, cd = (A / safe)[..., None], (B / safe)[..., None], cd[..., None]
    c = np.where(singular[..., None], 1.0, cf * cd - sf * sd)
    s = np.where(singular[..., None], 0.0, sf * cd + cf * sd)
    return c, s, np.maximum(np.abs(e) - rho, 0.0), singular


def height_angles_one(A: float, B: float, e: float, rho: float) -> list[tuple[float, float]]:
    """:func:`height_angles` for one equation ``A cos θ + B sin θ = e``, ``rho = |(A, B)|``.

    Returns:
        ``(cos θ, sin θ)`` of branches 0 and 1 (NaN without a real root).
    """
    cd = e / rho if rho > 0.0 else math.inf
    if abs(cd) > 1.0 + REACH_TOL:
        return [(math.nan, math.nan)] * 2
    cd = min(max(cd, -1.0), 1.0)
    sd = math.sqrt(1.0 - cd * cd)
    cf, sf = A / rho, B / rho
    return [(cf * cd - sf * sd, sf * cd + cf * sd), (cf * cd + sf * sd, sf * cd - cf * sd)]


@dataclass
class Arm3RSolver:
    """Closed-form position IK of an anthropomorphic or elbow 3R arm (see module doc).

    Attributes:
        name: ``"anthropomorphic-3R"`` or ``"elbow-3R"``.
        position_only: Always True: targets are tool positions ``(N, 3)``.
        labels: The four branch names.
        shoulder: Subproblem 4 of axis 1 against the height along ``k``.
        height: ``k·(x - p1)``, the height the target must have.
        p1: ``(3,)`` a point on axis 1.
        plane: The plane normal to ``k``, complex coordinates.
        zx: ``(3, 4)`` real: ``v @ zx`` holds the plane coordinates of ``v``
            and of ``h1 × v`` (as two (x, y) pairs).
        zh: Coordinate of ``h1``; ``zup``: of ``h1 × k``.
        t0: Coordinate of ``p1 - p2`` (from the shoulder axis 2).
        arm: The 2R triangle axis 2 -> axis 3 -> tool.
        s3: +1/-1, axis 3 along/against ``k``.
        reach: ``(p1s, a, rmin, rmax)``: foot of the common normal on axis 1,
            shoulder offset, and the range of the tool's distance from the foot
            on axis 2 (for the gap of targets out of reach).
    """

    name: str
    position_only: bool
    labels: tuple[str, ...]
    shoulder: AxisHeight
    height: float
    p1: FloatArray
    plane: Plane
    zx: FloatArray
    zh: complex
    zup: complex
    t0: complex
    arm: TwoLink
    s3: float
    reach: tuple[FloatArray, float, float, float]

    def solve(self, targets: FloatArray) -> Candidates:
        """Every branch's solution for each tool position ``(N, 3)``."""
        y = targets_array(targets, True)
        N, h1 = y.shape[0], self.shoulder.h
        v = y - self.p1
        c, s, gap1, sing1 = self.shoulder.solve(v, self.height)  # θ = -q1, (N, 2)
        vc, vx = np.moveaxis(as_complex((v @ self.zx).reshape(N, 2, 2)), -1, 0)
        vh = (v @ h1)[:, None]
        t = self.t0 + c * vc[:, None] + s * vx[:, None] + (1.0 - c) * vh * self.zh
        d1, d2, _, sing2 = self.arm.solve(t)  # (N, 2 shoulder, 2 elbow)
        down = (t * np.conj(self.zup)).real < 0.0  # target behind: elbow up is ψ >= 0
        d1 = np.where(down[..., None], d1[..., ::-1], d1)
        d2 = np.where(down[..., None], d2[..., ::-1], d2)
        qb = np.empty((N, 2, 2, 3))
        qb[..., 0] = -np.arctan2(s, c)[..., None]
        qb[..., 1] = d1
        qb[..., 2] = self.s3 * d2
        q = qb.reshape(N, 4, 3)
        q[np.isnan(q).any(axis=2)] = np.nan  # a branch is real in full or not at all
        none: BoolArray = np.asarray(np.isnan(q[:, :, 0]).all(axis=1))
        p1s, a, rmin, rmax = self.reach
        r = np.sqrt(((y - p1s) ** 2).sum(axis=-1))
        gap = np.maximum.reduce([gap1, r - a - rmax, rmin - a - r, np.zeros(N)])
        free = np.zeros((N, 3), dtype=bool)
        free[:, 0] = sing1
        free[:, 1] = sing2.any(axis=1)
        free &= ~none[:, None]
        return Candidates(
            q=q,
            labels=self.labels,
            singular=np.asarray(free.any(axis=1)),
            free=free,
            gap=np.where(none, gap, np.nan),
        )


def make_arm3r_solver(robot: Robot) -> Arm3RSolver | None:
    """The closed-form position solver of a 3R anthropomorphic or elbow arm, or ``None``.

    Args:
        robot: Any robot.

    Returns:
        A solver when ``classify(robot).kind`` is ``"anthropomorphic-3R"`` or
        ``"elbow-3R"`` and the links are not degenerate; else ``None``.
    """
    kind = classify(robot).kind
    if kind not in ("anthropomorphic-3R", "elbow-3R"):
        return None
    h, p = robot.joint_axes()
    x = robot.fk(np.zeros(3))[:3, 3]
    k = h[1] / np.linalg.norm(h[1])
    if np.linalg.norm(np.cross(h[0], k)) < PARALLEL_TOL:
        return None
    plane = Plane.normal_to(k)
    arm = TwoLink(complex(plane.c(p[2] - p[1])), complex(plane.c(x - p[2])))
    if not arm.valid:
        return None
    p1s, p2s = common_normal(h[0], p[0], k, p[1])
    c3 = p[2] + ((x - p[2]) @ k) * k  # centre of the tool's circle about axis 3
    rho3 = float(np.linalg.norm(x - c3))
    dh = float(k @ (p2s - c3))
    dr = float(np.linalg.norm(p2s - c3 - dh * k))
    reach = (
        p1s,
        float(np.linalg.norm(p2s - p1s)),
        float(np.hypot(dh, abs(dr - rho3))),
        float(np.hypot(dh, dr + rho3)),
    )
    return Arm3RSolver(
        name=kind,
        position_only=True,
        labels=LABELS,
        shoulder=AxisHeight.about(h[0], k),
        height=float(k @ (x - p[0])),
        p1=p[0],
        plane=plane,
        zx=np.concatenate([plane.basis, skew(h[0]) @ plane.basis], axis=1),
        zh=complex(plane.c(h[0])),
        zup=complex(plane.c(np.cross(h[0], k))),
        t0=complex(plane.c(p[0] - p[1])),
        arm=arm,
        s3=1.0 if float(h[2] @ k) > 0 else -1.0,
        reach=reach,
    )
