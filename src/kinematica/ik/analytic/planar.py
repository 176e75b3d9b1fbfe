"""Closed-form IK of planar arms and the SCARA: every solution, batched.

All joint axes of these arms are parallel to one direction ``k`` (prismatic
joints of the planar PR / PRR arms slide in the plane normal to ``k``). Written
as a product of exponentials, ``T(q) = E1(q1)···En(qn)·M`` with ``M = fk(0)``
and ``Ei`` the rotation about joint i's axis at ``q = 0`` (or the slide along
it), the problem is planar: points are written as complex numbers in the plane
normal to ``k`` (``x·e1 + i x·e2`` with ``e1 × e2 = k``), a rotation by ``θ``
about ``k`` is a product by ``exp(iθ)``. So any base, tool, offset and DH
convention is handled by the same code.

Solvers and their branch labels (angles measured about ``k``, seen from the
side ``k`` points to, so that positive rotations are counter-clockwise):

* planar 2R (position ``(N, 3)``), planar 3R (pose ``x, y, φ``, ``(N, 4, 4)``):
  ``"elbow up"``, ``"elbow down"``. Elbow up: the elbow lies to the left of the
  line from the shoulder (axis 1) to the wrist, i.e. link 2 is turned clockwise
  from link 1 (relative angle ψ in [-π, 0]); drawn with the target to the
  right of the shoulder, the elbow is above the line.
* SCARA RRPR (pose ``x, y, z, yaw``, ``(N, 4, 4)``): ``"right-handed"`` (ψ in
  [0, π]: elbow to the right of the shoulder-wrist line, as a right arm seen
  from above) and ``"left-handed"``.
* planar PR (position ``(N, 3)``), planar PRR (pose, ``(N, 4, 4)``): ``"link
  forward"`` (the revolute link points along the slide direction, seed 000's
  ``q2A = asin(y/l2)``) and ``"link backward"`` (``q2B = π - asin(y/l2)``).

A target the arm cannot take (off the plane, a tilted orientation, out of
reach) gets NaN candidates and a ``gap``: the distance in metres from the
target position to the reachable set (exact for these arms), or, when the
position is reachable but the orientation is tilted out of the plane, the tilt
angle in radians.
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.errors import DimensionError
from kinematica.ik.candidates import Candidates
from kinematica.robot.robot import Robot
from kinematica.robot.structure import classify

__all__ = [
    "Plane",
    "TwoLink",
    "as_complex",
    "make_planar_solver",
    "skew",
    "targets_array",
    "two_link_one",
]

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]
BoolArray = NDArray[np.bool_]

#: A cosine (or sine) argument up to this far beyond ±1 is taken as ±1: the
#: target is on the workspace boundary up to rounding (a relative measure).
REACH_TOL = 1e-12
#: Distance (m) or angle (rad) below which a target is taken as exactly on a
#: singular set (e.g. the wrist on axis 1 with equal links: q1 is free).
SINGULAR_TOL = 1e-12
#: Out-of-plane distance (m) and orientation tilt (rad) accepted as in-plane:
#: the caller's forward-kinematics check (1e-10) is the judge beyond this.
PLANE_TOL = 1e-10
#: Links shorter than this (m) make the arm degenerate: no solver is built.
LENGTH_TOL = 1e-9


def targets_array(targets: FloatArray, position_only: bool) -> FloatArray:
    """Targets as a float array ``(N, 3)`` or ``(N, 4, 4)``, checked."""
    t = np.asarray(targets, dtype=float)
    want = (3,) if position_only else (4, 4)
    if t.shape[1:] != want or t.ndim != len(want) + 1:
        raise DimensionError(f"targets must have shape (N, {', '.join(map(str, want))})")
    return t


def skew(h: FloatArray) -> FloatArray:
    """``(3, 3)`` matrix ``K`` with ``v @ K == h × v`` for row vectors ``v``."""
    return np.array([[0.0, h[2], -h[1]], [-h[2], 0.0, h[0]], [h[1], -h[0], 0.0]])


@dataclass(frozen=True)
class Plane:
    """Complex coordinates in the plane normal to a unit direction ``k``.

    Attributes:
        k: ``(3,)`` unit normal.
        basis: ``(3, 2)`` columns ``e1, e2 = k × e1``; the coordinate of ``x``
            is ``x·e1 + i x·e2``.
    """

    k: FloatArray
    basis: FloatArray

    @classmethod
    def normal_to(cls, k: FloatArray) -> Plane:
        """The plane normal to ``k`` with some fixed basis ``e1, e2 = k × e1``."""
        k = np.asarray(k, dtype=float) / np.linalg.norm(k)
        e1 = np.cross(k, np.eye(3)[int(np.argmin(np.abs(k)))])
        e1 /= np.linalg.norm(e1)
        return cls(k, np.stack([e1, np.cross(k, e1)], axis=1))

    def c(self, x: FloatArray) -> ComplexArray:
        """The complex coordinate ``(...)`` of vectors ``x (..., 3)``."""
        return as_complex(x @ self.basis)


def as_complex(xy: FloatArray) -> ComplexArray:
    """Pairs ``(..., 2)`` (last axis contiguous) as complex numbers ``(...)``, no copy.

    A real matrix product followed by this view costs a tenth of a product
    of real vectors with a complex matrix.
    """
    if xy.strides[-1] != xy.itemsize:
        xy = np.ascontiguousarray(xy)
    return xy.view(np.complex128)[..., 0]


@dataclass(frozen=True)
class TwoLink:
    """The planar 2R triangle: a shoulder, an elbow and a wrist point.

    Attributes:
        a0: Shoulder to elbow at q = 0 (complex, in the plane).
        b0: Elbow to wrist at q = 0.
    """

    a0: complex
    b0: complex

    @property
    def valid(self) -> bool:
        """Both links longer than ``LENGTH_TOL``."""
        return min(abs(self.a0), abs(self.b0)) > LENGTH_TOL

    def solve(self, t: ComplexArray) -> tuple[FloatArray, FloatArray, FloatArray, BoolArray]:
        """Rotations that take the wrist to ``t``.

        Args:
            t: ``(...)`` wrist targets relative to the shoulder (complex).

        Returns:
            ``d1, d2`` ``(..., 2)``: rotation of the shoulder and of the elbow
            (about ``k``, from q = 0), branches ``[ψ <= 0, ψ >= 0]`` where ψ is
            the angle of link 2 relative to link 1; NaN without a real solution.
            ``gap (...)``: distance of ``t`` outside the annulus (0 inside).
            ``singular (...)``: ``t`` at the shoulder with equal links (d1 free, 0 given).
        """
        L1, L2 = abs(self.a0), abs(self.b0)
        r2 = t.real**2 + t.imag**2
        c = (r2 - L1 * L1 - L2 * L2) / (2.0 * L1 * L2)
        ok = np.abs(c) <= 1.0 + REACH_TOL
        c = np.where(ok, np.minimum(np.maximum(c, -1.0), 1.0), np.nan)
        s = np.sqrt(1.0 - c * c)[..., None] * np.array([-1.0, 1.0])
        cb = c[..., None]
        v = self.a0 * (1.0 + (L2 / L1) * (cb + 1j * s))  # shoulder -> wrist after the elbow
        d1 = np.angle(t[..., None] * np.conj(v))
        psi0 = np.angle(self.b0 / self.a0)
        d2 = np.arctan2(s, cb) - psi0
        r = np.sqrt(r2)
        gap = np.maximum(np.maximum(r - (L1 + L2), abs(L1 - L2) - r), 0.0)
        singular = (r < SINGULAR_TOL) & (abs(L1 - L2) < SINGULAR_TOL)
        return d1, d2, gap, singular


def two_link_one(arm: TwoLink, t: complex) -> tuple[list[float], list[float], bool]:
    """:meth:`TwoLink.solve` for one target, on Python floats (no numpy overhead).

    Returns:
        ``d1, d2`` (two branches each, NaN without a real solution) and ``singular``.
    """
    L1, L2 = abs(arm.a0), abs(arm.b0)
    r2 = t.real * t.real + t.imag * t.imag
    c = (r2 - L1 * L1 - L2 * L2) / (2.0 * L1 * L2)
    if abs(c) > 1.0 + REACH_TOL:
        return [math.nan, math.nan], [math.nan, math.nan], False
    c = min(max(c, -1.0), 1.0)
    s0 = math.sqrt(1.0 - c * c)
    psi0 = cmath.phase(arm.b0 / arm.a0)
    d1, d2 = [], []
    for s in (-s0, s0):
        v = arm.a0 * (1.0 + (L2 / L1) * complex(c, s))
        d1.append(cmath.phase(t * v.conjugate()))
        d2.append(math.atan2(s, c) - psi0)
    return d1, d2, math.sqrt(r2) < SINGULAR_TOL and abs(L1 - L2) < SINGULAR_TOL


def _axis_sign(h: FloatArray, k: FloatArray) -> float:
    return 1.0 if float(h @ k) > 0 else -1.0


@dataclass
class PlanarSolver:
    """Closed-form IK of a planar 2R / 3R / PR / PRR arm or a SCARA (see module doc).

    Attributes:
        name: ``"planar-2R"``, ``"planar-3R"``, ``"planar-PR"``, ``"planar-PRR"`` or ``"scara"``.
        position_only: True for 2R and PR (targets ``(N, 3)``), else poses ``(N, 4, 4)``.
        labels: Branch names (see module doc).
        n: Number of joints.
        plane: The plane of motion (normal ``k``).
        sign: ``(n,)`` +1/-1: joint axis along/against ``k`` (slide: unused).
        origin: ``(3,)`` shoulder point (axis 1; axis 2 for PR/PRR).
        tool0: ``(3,)`` tool origin at q = 0.
        arm: The 2R triangle (2R, 3R, SCARA), or ``None``.
        slide: Complex unit slide direction (PR, PRR), else 0.
        link: Complex link from axis 2 to the wrist at q = 0 (PR, PRR), else 0.
        wrist: ``(3,)`` the wrist point expressed in the tool frame at q = 0,
            i.e. ``R_Mᵀ (w - t_M)`` (pose solvers; zeros otherwise).
        rot0: ``(3, 2)`` ``R_Mᵀ k`` and ``R_Mᵀ e1`` (pose solvers).
        lift: SCARA: ``k·h3`` (±1) and the wrist height ``k·p4``; else zeros.
    """

    name: str
    position_only: bool
    labels: tuple[str, ...]
    n: int
    plane: Plane
    sign: FloatArray
    origin: FloatArray
    tool0: FloatArray
    arm: TwoLink | None
    slide: complex
    link: complex
    wrist: FloatArray
    rot0: FloatArray
    lift: tuple[float, float]

    def solve(self, targets: FloatArray) -> Candidates:
        """Every branch's solution for each target (see :class:`AnalyticSolver`)."""
        T = targets_array(targets, self.position_only)
        N, k = T.shape[0], self.plane.k
        if self.position_only:
            p, tilt, phi = T, np.zeros(N), np.zeros(N)
            w = p
        else:
            p = T[:, :3, 3]
            R0 = T[:, :3, :3] @ self.rot0  # (N, 3, 2): R_G k and R_G e1
            dk = R0[..., 0] - k  # |R_G k - k| = 2 sin(tilt / 2), exact near 0
            tilt = 2.0 * np.arcsin(np.minimum(np.sqrt((dk * dk).sum(axis=-1)) / 2.0, 1.0))
            phi = np.angle(self.plane.c(R0[..., 1]))
            w = p + T[:, :3, :3] @ self.wrist
        dz = (p - self.tool0) @ k  # out of the plane (m)
        t = self.plane.c(w - self.origin)
        q = np.empty((N, 2, self.n))
        singular = np.zeros(N, dtype=bool)
        free = np.zeros((N, self.n), dtype=bool)
        if self.arm is not None:  # 2R, 3R, SCARA: shoulder on axis 1
            d1, d2, rgap, singular = self.arm.solve(t)
            if self.name == "scara":
                d2 = d2[:, ::-1]  # right-handed first: ψ >= 0
                d1 = d1[:, ::-1]
            q[..., 0] = d1
            q[..., 1] = self.sign[1] * d2
            free[:, 0] = singular
            if self.name == "planar-3R":
                q[..., 2] = self.sign[2] * (phi[:, None] - d1 - d2)
                free[:, 2] = singular
            elif self.name == "scara":
                q[..., 2] = self.lift[0] * (w @ k - self.lift[1])[:, None]
                q[..., 3] = self.sign[3] * (phi[:, None] - d1 - d2)
                free[:, 3] = singular
                dz = np.zeros(N)  # the slide takes any height
        else:  # PR, PRR: slide, then a revolute link
            u = t * np.conj(self.slide)  # real part along the slide
            L = abs(self.link)
            ok = np.abs(u.imag) <= L * (1.0 + REACH_TOL)
            root = np.sqrt(np.maximum(L * L - u.imag**2, 0.0))
            root = np.where(ok, root, np.nan)[:, None] * np.array([1.0, -1.0])
            q1 = u.real[:, None] - root
            d2 = np.angle((u[:, None] - q1) * self.slide * np.conj(self.link))
            q[..., 0], q[..., 1] = q1, self.sign[1] * d2
            if self.name == "planar-PRR":
                q[..., 2] = self.sign[2] * (phi[:, None] - d2)
            rgap = np.maximum(np.abs(u.imag) - L, 0.0)
        bad = (np.abs(dz) > PLANE_TOL) | (tilt > PLANE_TOL)
        q[bad] = np.nan
        q[np.isnan(q).any(axis=2)] = np.nan  # a branch is real in full or not at all
        none: BoolArray = np.asarray(np.isnan(q[:, :, 0]).all(axis=1))
        off = np.abs(dz) > PLANE_TOL
        pos_gap = np.where(off, np.hypot(dz, rgap), rgap)  # distance to the annulus / strip
        gap = np.where((tilt > PLANE_TOL) & ~off, tilt, pos_gap)
        return Candidates(
            q=q,
            labels=self.labels,
            singular=singular & ~none,
            free=free & ~none[:, None],
            gap=np.where(none, gap, np.nan),
        )


_LABELS = {
    "planar-2R": ("elbow up", "elbow down"),
    "planar-3R": ("elbow up", "elbow down"),
    "scara": ("right-handed", "left-handed"),
    "planar-PR": ("link forward", "link backward"),
    "planar-PRR": ("link forward", "link backward"),
}


def make_planar_solver(robot: Robot) -> PlanarSolver | None:
    """The closed-form solver of a planar 2R/3R/PR/PRR arm or a SCARA, or ``None``.

    Args:
        robot: Any robot.

    Returns:
        A solver when ``classify(robot).kind`` is one of the planar kinds or
        ``"scara"`` and no link is degenerate (zero length); else ``None``.
    """
    kind = classify(robot).kind
    if kind not in _LABELS:
        return None
    h, p = robot.joint_axes()
    M = robot.fk(np.zeros(robot.dof))
    R_M, t_M = M[:3, :3], M[:3, 3]
    slide_first = kind in ("planar-PR", "planar-PRR")
    k = h[1] if slide_first else h[0]
    plane = Plane.normal_to(k)
    k = plane.k
    sign = np.array([_axis_sign(hi, k) for hi in h])
    last = {"planar-2R": None, "planar-3R": 2, "scara": 3, "planar-PR": None, "planar-PRR": 2}[kind]
    wrist_pt = t_M if last is None else p[last]
    arm, slide, link, lift = None, 0j, 0j, (0.0, 0.0)
    if slide_first:
        origin = p[1]
        slide = complex(plane.c(h[0]))
        link = complex(plane.c(wrist_pt - p[1]))
        if abs(link) <= LENGTH_TOL:
            return None
    else:
        origin = p[0]
        arm = TwoLink(complex(plane.c(p[1] - p[0])), complex(plane.c(wrist_pt - p[1])))
        if not arm.valid:
            return None
        if kind == "scara":
            lift = (float(h[2] @ k), float(p[3] @ k))
    position_only = kind in ("planar-2R", "planar-PR")
    e1 = plane.basis[:, 0]
    return PlanarSolver(
        name=kind,
        position_only=position_only,
        labels=_LABELS[kind],
        n=robot.dof,
        plane=plane,
        sign=sign,
        origin=origin,
        tool0=t_M,
        arm=arm,
        slide=slide,
        link=link,
        wrist=R_M.T @ (wrist_pt - t_M),
        rot0=np.stack([R_M.T @ k, R_M.T @ e1], axis=1),
        lift=lift,
    )
