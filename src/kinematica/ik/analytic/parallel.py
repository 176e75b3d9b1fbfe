"""Closed-form IK of 6R arms with three consecutive parallel axes 2-3-4 (UR type).

Written as a product of exponentials, ``T(q) = E1(q1)···E6(q6)·M`` with
``M = fk(0)`` and ``Ei`` the rotation about joint i's axis (``hi``, ``pi`` at
q = 0), and with ``G = T·M⁻¹ = E1···E6`` for a target ``T``. Let ``k`` be the
direction of axes 2, 3, 4 and ``c`` the point where axes 5 and 6 meet.
Rotations about axes parallel to ``k`` keep heights along ``k``, and ``E5``,
``E6`` fix ``c``, so (Paden-Kahan subproblems, as in Elias and Wen's IK-Geo):

1. ``k·E1⁻¹(G(c)) = k·c``: q1 by subproblem 4 (two solutions, "shoulder");
2. ``k·R1ᵀ R_G h6 = k·R5 h6``: q5 by subproblem 4 (two, "wrist");
3. ``R_Gᵀ R1 k = R6ᵀ R5ᵀ k``: q6 by subproblem 1 (on the parts of both
   sides across ``h6``, which keeps it well conditioned near alignment);
4. ``R1ᵀ R_G R6ᵀ R5ᵀ = Rot(k, θ234)`` gives ``θ234 = q2 + ±q3 + ±q4``;
5. axis 4 must reach ``E1⁻¹(G(c)) + Rot(k, θ234)(p4 - c)``: q2, q3 from the
   planar 2R triangle (two, "elbow"), then q4 from θ234.

Up to 8 solutions, exact, for any link values, offsets, twists α1, α4, α5,
base, tool and DH convention, as long as axes 5 and 6 meet (all UR-type arms
built: UR3/5/10/16, e-series, and their clones); arms whose axes 5 and 6 do
not meet get the general solver of :mod:`kinematica.ik.analytic.parallel_general`
(IK-Geo subproblem 6, a quartic). A branch without a real root is NaN;
nothing is approximated.

Branch labels, ``k1`` being the current direction of axis 2 and all vectors
current joint axes:

* ``"shoulder right"``: the wrist point ``c`` lies on the ``h1 × k1`` side of
  axis 1 (as :mod:`kinematica.ik.analytic.arm3r`); ``"shoulder left"``.
* ``"elbow up"``: in the arm's plane, the elbow (axis 3) lies on the side of
  the line from axis 2 to axis 4 toward which ``h1`` points (ψ, the angle of
  link 3 relative to link 2 about ``k1``, has the sign of
  ``-(w - s)·(h1 × k1)``; ψ <= 0 when that is 0); ``"elbow down"``.
* ``"wrist no-flip"``: ``(k1 × h6)·h5 >= 0``, the tool axis is turned from
  ``k1`` positively about axis 5 (for the UR5 DH table: ``sin q5 >= 0``);
  ``"wrist flip"``.

Singular poses: with the wrist aligned (axis 6 parallel to ``k``, to within
``ALIGN_TOL`` in sine) q6 is free and q2, q3, q4, q6 are marked free; the
representative q6 puts axis 4 at mid-reach of the 2R triangle. With the
wrist point on axis 1, q1 is free (q1 = 0 given). With axis 4 on axis 2 and
equal links, q2 is free (q2, q4 marked).
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.ik.analytic.arm3r import (
    AxisHeight,
    common_normal,
    height_angles,
    height_angles_one,
)
from kinematica.ik.analytic.parallel_general import (
    GeneralThreeParallelSolver,
    make_general_solver,
)
from kinematica.ik.analytic.planar import (
    REACH_TOL,
    SINGULAR_TOL,
    Plane,
    TwoLink,
    as_complex,
    skew,
    targets_array,
    two_link_one,
)
from kinematica.ik.candidates import Candidates
from kinematica.ik.structure import MEET_TOL, PARALLEL_TOL, line_distance
from kinematica.robot.robot import Robot
from kinematica.robot.structure import classify

__all__ = ["LABELS", "ThreeParallelSolver", "make_three_parallel_solver"]

FloatArray = NDArray[np.float64]
ComplexArray = NDArray[np.complex128]

#: Below this sine of the angle between axis 6 and k the wrist is aligned: q6 is
#: free (a representative is chosen; it misses the exact pose by about this
#: sine times the arm's size, below the 1e-12 the candidates aim at).
ALIGN_TOL = 1e-13

LABELS = tuple(
    f"shoulder {s}, elbow {e}, wrist {w}"
    for s in ("right", "left")
    for w in ("no-flip", "flip")
    for e in ("up", "down")
)


@dataclass
class ThreeParallelSolver:
    """Closed-form IK of a 6R arm with axes 2, 3, 4 parallel and axes 5, 6 meeting.

    Every orientation quantity the steps need is a bilinear form
    ``y2ᵀ R_G y1`` in the target rotation ``R_G = R R_Mᵀ``, weighted by the
    cosines and sines of q1, q5, q6: the factory lists the constant vectors
    once, and a solve is a few matrix products on the batch. One pose runs on
    Python floats (numpy's per-call cost would dominate).

    Attributes:
        name: ``"three-parallel-6R"``.
        position_only: False: targets are tool poses ``(N, 4, 4)``.
        labels: The eight branch names (see module doc), ordered shoulder,
            wrist, elbow (elbow fastest).
        sign: ``(6,)`` +1/-1: ``hi·k`` signs (axes 3, 4 along or against 2).
        p1: ``(3,)`` a point on axis 1.
        cM: ``R_Mᵀ (c - t_M)``: ``G(c) = p + R cM`` for a target ``(R, p)``.
        Wv: ``(3, 8)``: ``v @ Wv`` gives, for ``v = G(c) - p1``, the shoulder
            coefficients ``A, B, C``, ``v·h1`` and the plane coordinates of
            ``v`` and ``h1 × v`` (two pairs).
        height: ``k·(c - p1)``, the height ``E1⁻¹(G(c))`` must have.
        Y2: ``(3, 9)``: ``[1, cos q1, sin q1] @ Y2`` is ``R1 k``, ``R1 e1``, ``R1 e2``.
        Y1: ``(3, 21)`` columns ``R_Mᵀ y1``: ``h6``, ``f1``, ``f2`` (a basis
            across ``h6``, ``f1 × f2 = h6``), then ``R6ᵀ R5ᵀ e_j`` in 3 × 2 × 3
            parts (q5 weight ``[1, cos q5, -sin q5]``, j, q6 weight).
        fa: ``(3, 2)``: ``[1, cos q5, -sin q5] @ fa`` is ``R5ᵀ k`` in ``f1, f2``.
        wrist: ``(A5, B5, C5)`` with ``k·R5 h6 = A5 cos q5 + B5 sin q5 + C5``.
        plane: Plane normal to ``k``; ``zh`` the coordinate of ``h1``, ``zup``
            of ``h1 × k``.
        t0: Coordinate of ``p1 - p2``; ``w0``: of ``p4 - c``.
        arm: The 2R triangle axis 2 -> axis 3 -> axis 4.
        reach: ``(p1 - p1s, bound)``: ``p1s`` the foot on axis 1 of its common
            normal with axis 2; ``|G(c) - p1s|`` is at most ``bound``.
    """

    name: str
    position_only: bool
    labels: tuple[str, ...]
    sign: FloatArray
    p1: FloatArray
    cM: FloatArray
    Wv: FloatArray
    height: float
    Y2: FloatArray
    Y1: FloatArray
    fa: FloatArray
    wrist: tuple[float, float, float]
    plane: Plane
    zh: complex
    zup: complex
    t0: complex
    w0: complex
    arm: TwoLink
    reach: tuple[FloatArray, float]

    def solve(self, targets: FloatArray) -> Candidates:
        """Every branch's solution for each tool pose ``(N, 4, 4)``."""
        T = targets_array(targets, False)
        with np.errstate(invalid="ignore", divide="ignore"):
            if T.shape[0] == 1:
                return self._solve_one(T[0])
            return self._solve_batch(T)

    def _solve_batch(self, T: FloatArray) -> Candidates:
        N = T.shape[0]
        R = T[:, :3, :3]
        v = T[:, :3, 3] + R @ self.cM - self.p1  # G(c) - p1
        V = v @ self.Wv
        # 1. shoulder: θ = -q1 with k·rot(h1, θ) v = k·(c - p1)
        c1, s1, gap1, sing1 = height_angles(V[:, 0], V[:, 1], V[:, 2], self.height)
        w1 = np.stack([np.ones_like(c1), c1, -s1], axis=-1)  # [1, cos q1, sin q1]
        rows = (w1 @ self.Y2).reshape(N, 6, 3)  # R1 k, R1 e1, R1 e2 per shoulder
        Q = ((rows @ R) @ self.Y1).reshape(N, 2, 3, 21)  # bilinear forms y2ᵀ R_G y1
        # 2. wrist: k·R5 h6 = k1·R_G h6 = d5; m = |R1ᵀ R_G h6 across k| (the
        #    sine of the tool axis to k) keeps q5 accurate near alignment
        d5 = Q[:, :, 0, 0]
        m2 = Q[:, :, 1, 0] ** 2 + Q[:, :, 2, 0] ** 2
        c5, s5 = self._wrist_angles(d5, m2)  # (N, 2, 2)
        w5 = np.stack([np.ones_like(c5), c5, -s5], axis=-1)
        # 3. q6: rot(h6, θ6) a = b, a = R5ᵀ k, b = R_Gᵀ k1, in f1, f2; θ6 = -q6
        a = w5 @ self.fa
        b = Q[:, :, None, 0, 1:3]
        x6 = (a * b).sum(axis=-1)
        y6 = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
        n6 = np.hypot(x6, y6)
        zero = n6 == 0.0  # exactly aligned: any q6
        n6 = np.where(zero, 1.0, n6)
        c6, s6 = np.where(zero, 1.0, x6 / n6), y6 / n6  # cos q6, -sin q6
        # 4. θ234: rot(k, -θ234) e1 = R5 R6 R_Gᵀ R1 e1, coordinates x_j
        P = (w5 @ Q[:, :, 1, 3:].reshape(N, 2, 3, 6)).reshape(N, 2, 2, 2, 3)
        vc, vx = as_complex(V[:, 4:8].reshape(N, 2, 2)).T
        hc = self.t0 + c1 * vc[:, None] + s1 * vx[:, None] + (1.0 - c1) * V[:, 3:4] * self.zh
        hc = hc[:, :, None]  # coordinate of E1⁻¹(G(c)) - p2, (N, 2, 1)
        tiny = np.broadcast_to((m2 < ALIGN_TOL**2)[..., None], c6.shape)
        if tiny.any():
            x0 = P[..., 0] + P[..., 1]  # at q6 = 0
            cf, sf = self._free_q6(x0[..., 0] + 1j * x0[..., 1], hc, np.sign(d5)[..., None])
            c6, s6 = np.where(tiny, cf, c6), np.where(tiny, sf, s6)
        x = P[..., 0] + c6[..., None] * P[..., 1] + s6[..., None] * P[..., 2]
        ei = x[..., 0] - 1j * x[..., 1]  # ∝ exp(i θ234)
        # 5. the 2R triangle to axis 4
        t = hc + ei / np.abs(ei) * self.w0
        d2, d3, _, sing2 = self.arm.solve(t)  # (N, 2, 2, 2)
        down = (t * np.conj(self.zup)).real < 0.0  # axis 4 behind: elbow up is ψ >= 0
        d2 = np.where(down[..., None], d2[..., ::-1], d2)
        d3 = np.where(down[..., None], d3[..., ::-1], d3)
        qb = np.empty((N, 2, 2, 2, 6))
        qb[..., 0] = -np.arctan2(s1, c1)[:, :, None, None]
        qb[..., 1] = d2
        qb[..., 2] = self.sign[2] * d3
        qb[..., 3] = self.sign[3] * (np.angle(ei)[..., None] - d2 - d3)
        qb[..., 4] = np.arctan2(s5, c5)[..., None]
        qb[..., 5] = -np.arctan2(s6, c6)[..., None]
        q = qb.reshape(N, 8, 6)
        q[np.isnan(q).any(axis=2)] = np.nan  # a branch is real in full or not at all
        real = ~np.isnan(q[:, :, 0]).reshape(N, 2, 2, 2)
        none: NDArray[np.bool_] = np.asarray(~real.reshape(N, 8).any(axis=1))
        gap = np.full(N, np.nan)
        if none.any():
            gap[none] = self._gap(v[none], gap1[none])
        free = np.zeros((N, 6), dtype=bool)
        free[:, 0] = sing1 & ~none
        aligned = np.asarray((m2 < ALIGN_TOL**2)[:, :, None, None] & real).reshape(N, -1)
        folded = np.asarray(sing2[..., None] & real).reshape(N, -1)  # axis 4 on axis 2
        free[:, [1, 2, 3, 5]] = np.asarray(aligned.any(axis=1))[:, None]
        free[:, [1, 3]] |= np.asarray(folded.any(axis=1))[:, None]
        singular = np.asarray(free.any(axis=1))
        return Candidates(q=q, labels=self.labels, singular=singular, free=free, gap=gap)

    def _solve_one(self, T: FloatArray) -> Candidates:
        """:meth:`_solve_batch` for one pose, step by step on Python floats."""
        R = T[:3, :3]
        v = T[:3, 3] + R @ self.cM - self.p1
        A, B, C, vh, vcr, vci, vxr, vxi = (v @ self.Wv).tolist()
        rho, e = math.hypot(A, B), self.height - C
        sing1 = rho < SINGULAR_TOL and abs(e) < SINGULAR_TOL
        shoulders = [(1.0, 0.0)] * 2 if sing1 else height_angles_one(A, B, e, rho)
        W1 = [[1.0, c, -s] for c, s in shoulders]
        Q = (((np.array(W1) @ self.Y2).reshape(6, 3) @ R) @ self.Y1).tolist()
        (fa0, fb0), (fa1, fb1), (fa2, fb2) = self.fa.tolist()
        vc, vx, zh, w0 = complex(vcr, vci), complex(vxr, vxi), self.zh, self.w0
        q = [[math.nan] * 6 for _ in range(8)]
        free = [sing1, False, False, False, False, False]
        for i, (ci, si) in enumerate(shoulders):
            if math.isnan(ci):
                continue
            F, G1, G2 = Q[3 * i], Q[3 * i + 1], Q[3 * i + 2]
            d5, m2 = F[0], G1[0] ** 2 + G2[0] ** 2
            hc = self.t0 + ci * vc + si * vx + (1.0 - ci) * vh * zh
            for j, (c5, s5) in enumerate(self._wrist_one(d5, m2)):
                if math.isnan(c5):
                    continue
                a1 = fa0 + c5 * fa1 - s5 * fa2
                a2 = fb0 + c5 * fb1 - s5 * fb2
                P = [G1[3 + b] + c5 * G1[9 + b] - s5 * G1[15 + b] for b in range(6)]
                if m2 < ALIGN_TOL**2:
                    x0 = complex(P[0] + P[1], P[3] + P[4])
                    cf, sf = self._free_q6(np.array(x0), np.array(hc), np.sign(d5))
                    c6, s6 = float(cf), float(sf)
                else:
                    x6, y6 = a1 * F[1] + a2 * F[2], a1 * F[2] - a2 * F[1]
                    n6 = math.hypot(x6, y6)
                    c6, s6 = (x6 / n6, y6 / n6) if n6 > 0.0 else (1.0, 0.0)
                ei = complex(P[0] + c6 * P[1] + s6 * P[2], -(P[3] + c6 * P[4] + s6 * P[5]))
                th234 = cmath.phase(ei)
                t = hc + ei / abs(ei) * w0
                d2s, d3s, sing2 = two_link_one(self.arm, t)
                down = int((t * self.zup.conjugate()).real < 0.0)
                for el in range(2):
                    d2, d3 = d2s[el ^ down], d3s[el ^ down]
                    if math.isnan(d2):
                        continue
                    q[4 * i + 2 * j + el] = [
                        -math.atan2(si, ci),
                        d2,
                        self.sign[2] * d3,
                        self.sign[3] * (th234 - d2 - d3),
                        math.atan2(s5, c5),
                        -math.atan2(s6, c6),
                    ]
                    if m2 < ALIGN_TOL**2:
                        free[1] = free[2] = free[3] = free[5] = True
                    free[1] = free[3] = free[1] or sing2
        qa = np.array([q])
        none = bool(np.isnan(qa).all())
        fr = np.array([free]) & (not none)
        gap = np.array([np.nan])
        if none:
            gap = self._gap(v[None], np.array([max(abs(e) - rho, 0.0)]))
        singular = np.asarray(fr.any(axis=1))
        return Candidates(q=qa, labels=self.labels, singular=singular, free=fr, gap=gap)

    def _wrist_angles(self, d5: FloatArray, m2: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Subproblem 4 for q5 (``k·R5 h6 = d5``), accurate near ``d5 = ±1``.

        With ``A5 cos q5 + B5 sin q5 + C5 = d5``, ``q5 = φ ± δ`` and
        ``1 ∓ cos δ`` taken from ``1 ∓ d5 = m² / (1 ± d5)``, ``m²`` being the
        squared part of the unit vector ``R1ᵀ R_G h6`` across ``k``: no
        cancellation when the wrist nears alignment.

        Returns:
            ``cos q5, sin q5`` ``(..., 2)``: branch 0 "no-flip" (δ >= 0).
        """
        A5, B5, C5 = self.wrist
        rho = math.hypot(A5, B5)
        omd = np.where(d5 > 0.0, m2 / (1.0 + d5), 1.0 - d5)  # 1 - d5
        opd = np.where(d5 < 0.0, m2 / (1.0 - d5), 1.0 + d5)  # 1 + d5
        lo = (omd - (1.0 - rho - C5)) / rho  # 1 - cos δ
        hi = (opd - (1.0 - rho + C5)) / rho  # 1 + cos δ
        ok = (lo >= -2.0 * REACH_TOL) & (hi >= -2.0 * REACH_TOL)
        lo, hi = np.maximum(lo, 0.0), np.maximum(hi, 0.0)
        cd = np.where(ok, (hi - lo) / 2.0, np.nan)[..., None]
        sd = np.sqrt(lo * hi)[..., None] * np.array([1.0, -1.0])
        cf, sf = A5 / rho, B5 / rho
        return cf * cd - sf * sd, sf * cd + cf * sd

    def _wrist_one(self, d5: float, m2: float) -> list[tuple[float, float]]:
        """:meth:`_wrist_angles` for one value, on Python floats."""
        A5, B5, C5 = self.wrist
        rho = math.hypot(A5, B5)
        omd = m2 / (1.0 + d5) if d5 > 0.0 else 1.0 - d5
        opd = m2 / (1.0 - d5) if d5 < 0.0 else 1.0 + d5
        lo = (omd - (1.0 - rho - C5)) / rho
        hi = (opd - (1.0 - rho + C5)) / rho
        if lo < -2.0 * REACH_TOL or hi < -2.0 * REACH_TOL:
            return [(math.nan, math.nan)] * 2
        lo, hi = max(lo, 0.0), max(hi, 0.0)
        cd, sd = (hi - lo) / 2.0, math.sqrt(lo * hi)
        cf, sf = A5 / rho, B5 / rho
        return [(cf * cd - sf * sd, sf * cd + cf * sd), (cf * cd + sf * sd, sf * cd - cf * sd)]

    def _free_q6(
        self, x0: ComplexArray, hc: ComplexArray, eps: FloatArray | float
    ) -> tuple[FloatArray, FloatArray]:
        """A representative q6 where the wrist is aligned (axis 6 along ``ε k``).

        Then ``R5 R6 = Rot(ε k, q6) R5``, so ``θ234 = Θ - ε q6`` with
        ``exp(-iΘ) ∝ x0`` the value at q6 = 0, and axis 4 runs on the circle
        ``hc + exp(i(Θ - ε q6)) w0`` as q6 turns: take the point of that
        circle closest to the middle of the 2R triangle's reach.

        Returns:
            ``cos q6, -sin q6``.
        """
        L2, L3 = abs(self.arm.a0), abs(self.arm.b0)
        R0, W = np.abs(hc), abs(self.w0)
        r = np.minimum(np.maximum(max(L2, L3), np.abs(R0 - W)), R0 + W)
        den = np.where(R0 * W > 0.0, 2.0 * R0 * W, 1.0)
        cb = np.minimum(np.maximum((r * r - R0 * R0 - W * W) / den, -1.0), 1.0)
        beta = np.angle(hc) + np.arccos(cb) - np.angle(self.w0)  # = Θ - ε q6
        q6 = eps * (-np.angle(x0) - beta)
        return np.cos(q6), -np.sin(q6)

    def _gap(self, v: FloatArray, gap1: FloatArray) -> FloatArray:
        """Lower bound (m) of the distance to reach, ``v = G(c) - p1`` ``(M, 3)``."""
        off, bound = self.reach
        far = np.sqrt(((v + off) ** 2).sum(axis=-1)) - bound
        return np.maximum(np.maximum(gap1, far), 0.0)


def make_three_parallel_solver(
    robot: Robot,
) -> ThreeParallelSolver | GeneralThreeParallelSolver | None:
    """The closed-form solver of a UR-type 6R arm, or ``None``.

    Args:
        robot: Any robot.

    Returns:
        A solver when ``classify(robot).kind == "three-parallel-6R"``, axis 1
        and axis 5 are not parallel to axes 2-4, axis 6 is not parallel to
        axis 5 and no link of the 2R triangle is degenerate; else ``None``.
        When axes 5 and 6 meet it is this module's solver, otherwise the
        general one of :mod:`kinematica.ik.analytic.parallel_general`.
    """
    if classify(robot).kind != "three-parallel-6R":
        return None
    h, p = robot.joint_axes()
    M = robot.fk(np.zeros(6))
    R_M, t_M = M[:3, :3], M[:3, 3]
    k = h[1] / np.linalg.norm(h[1])

    def parallel(a: FloatArray, b: FloatArray) -> bool:
        return bool(np.linalg.norm(np.cross(a, b)) < PARALLEL_TOL)

    if parallel(h[0], k) or parallel(h[4], k) or parallel(h[5], h[4]):
        return None
    if line_distance(h[4], p[4], h[5], p[5]) > MEET_TOL:
        return make_general_solver(h, p, M, k)
    c = common_normal(h[4], p[4], h[5], p[5])[0]
    plane = Plane.normal_to(k)
    arm = TwoLink(complex(plane.c(p[2] - p[1])), complex(plane.c(p[3] - p[2])))
    if not arm.valid:
        return None
    p1s, p2s = common_normal(h[0], p[0], k, p[1])
    L4c = abs(complex(plane.c(c - p[3])))
    bound = float(np.linalg.norm(p2s - p1s)) + float(
        np.hypot(k @ (c - p2s), abs(arm.a0) + abs(arm.b0) + L4c)
    )
    h1, h5, h6 = h[0], h[4], h[5]
    e1, e2 = plane.basis.T

    def split(x: FloatArray, axis: FloatArray) -> list[FloatArray]:
        """``x`` along ``axis``, across it, and ``axis × x`` (rotation weights 1, cos, sin)."""
        along = (x @ axis) * axis
        return [along, x - along, np.cross(axis, x)]

    Y2 = np.concatenate([np.array(split(x, h1)) for x in (k, e1, e2)], axis=1)
    f = Plane.normal_to(h6).basis  # f1, f2 across h6, f1 × f2 = h6
    # R6ᵀ R5ᵀ e_j: weights [1, cos q5, -sin q5] ⊗ [1, cos q6, -sin q6]
    fifth = [split(e1, h5), split(e2, h5)]
    chain = [sixth for a in range(3) for ej in fifth for sixth in split(ej[a], h6)]
    Y1 = np.concatenate([h6[:, None], f, np.array(chain).T], axis=1)
    W = AxisHeight.about(h1, k).W
    A5, B5, C5 = h6 @ AxisHeight.about(h5, k).W
    return ThreeParallelSolver(
        name="three-parallel-6R",
        position_only=False,
        labels=LABELS,
        sign=np.where(h @ k > 0, 1.0, -1.0),
        p1=p[0],
        cM=R_M.T @ (c - t_M),
        Wv=np.concatenate([W, h1[:, None], plane.basis, skew(h1) @ plane.basis], axis=1),
        height=float(k @ (c - p[0])),
        Y2=Y2,
        Y1=R_M.T @ Y1,
        wrist=(float(A5), float(B5), float(C5)),
        fa=np.array(split(k, h5)) @ f,  # R5ᵀ k: weights [1, cos q5, -sin q5]
        plane=plane,
        zh=complex(plane.c(h1)),
        zup=complex(plane.c(np.cross(h1, k))),
        t0=complex(plane.c(p[0] - p[1])),
        w0=complex(plane.c(p[3] - c)),
        arm=arm,
        reach=(p[0] - p1s, bound),
    )
