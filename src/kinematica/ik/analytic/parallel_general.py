"""Closed-form IK of 6R arms with axes 2∥3∥4 whose axes 5 and 6 do not meet.

The general case of :mod:`kinematica.ik.analytic.parallel` (IK-Geo's
"three parallel axes" case, solved with its subproblem 6). Written as a
product of exponentials ``G = T·M⁻¹ = E1···E6`` with ``k`` the direction of
axes 2, 3, 4, ``Ri`` the rotation of ``Ei`` and ``pi`` a point on axis i:

1. ``R1ᵀ R_G = R234 R5 R6`` with ``kᵀ R234 = kᵀ``, so
   ``kᵀ R(h1, -q1) R_G h6 = kᵀ R(h5, q5) h6``;
2. ``E6`` fixes ``p6``, ``E2 E3 E4`` keep heights along ``k``, so
   ``kᵀ R(h1, -q1) (G(p6) - p1) = k·(p5 - p1) + kᵀ R(h5, q5) (p6 - p5)``.

Both are ``A cos θ1 + B sin θ1 + C = D cos q5 + E sin q5 + F`` (θ1 = -q1),
subproblem 6 in ``(q1, q5)``. The right-hand sides' 2x2 matrix ``[D E]`` is
invertible exactly when axes 5 and 6 neither meet nor are parallel, so
``(cos q5, sin q5) = P (cos θ1, sin θ1, 1)`` and ``|P x|² = 1`` is a quartic in
``tan((θ1 - φ0)/2)`` (``φ0`` chosen per target to keep the leading coefficient
away from 0): up to four ``(q1, q5)``, each Newton-polished on the two
original equations. Then ``R(h6, -q6) R5ᵀ k = R_Gᵀ R1 k`` (subproblem 1) gives
q6, ``H = E1⁻¹ G E6⁻¹ E5⁻¹ = E2 E3 E4`` is a planar motion whose angle is
``θ234`` and which takes ``p4`` where the 2R triangle axis 2 -> 3 -> 4 must
put it (two elbows): up to 8 solutions, exact, for any link values, offsets,
twists, base, tool and DH convention. A branch without a real root is NaN.

Branch labels ``"root j, elbow up|down"``: root j is the j-th real
``(q1, q5)`` pair in increasing order of q1 in (-π, π] (roots fill the first
slots; the rest are NaN); elbow up/down as in
:mod:`kinematica.ik.analytic.parallel` (the elbow on the side of the line
axis 2 -> axis 4 toward which ``h1`` points).

Singular poses: axis 6 parallel to ``k`` (the wrist aligned, to ``ALIGN_TOL``
in sine): q6 is free (axes 2, 3, 4, 6 then all parallel); the representative
q6 puts axis 4 at mid-reach of the 2R triangle, and q2, q3, q4, q6 are marked
free. Subproblem 6 met by every θ1 (the quartic vanishes): q1 and q5 are
free, four sample values of q1 are given. Axis 4 on axis 2 with equal links:
q2 is free (q2, q4 marked).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.ik.analytic.arm3r import AxisHeight
from kinematica.ik.analytic.planar import Plane, TwoLink, targets_array
from kinematica.ik.analytic.subproblems import rotation_matrix, solve_quartic, subproblem1
from kinematica.ik.candidates import Candidates

__all__ = ["GENERAL_LABELS", "GeneralThreeParallelSolver", "make_general_solver"]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

#: Sine of the angle between axis 6 and k below which q6 is free (after polish).
ALIGN_TOL = 1e-10
#: Below this sine the wrist is near alignment: subproblem 1 for q6 loses
#: accuracy (the two wrist roots merge), so q6 is taken at mid-reach of the 2R
#: triangle and the candidate is Newton-polished on the pose.
NEAR_ALIGN = 1e-4
#: Pose error (m, rad) a polished near-alignment candidate must reach.
POLISH_OK = 1e-13
#: A quartic root ``t`` is taken as real when ``|Im t| <= ROOT_IMAG * (1 + |t|)``
#: (a double root at a tangency splits into a pair ~1e-8 off the real axis);
#: it is kept only if Newton then meets the equations to ``ROOT_RESIDUAL``.
ROOT_IMAG = 1e-5
#: Residual of the two subproblem-6 equations (relative to their size) a polished
#: root must reach.
ROOT_RESIDUAL = 1e-10
#: Below this (relative) the quartic vanishes at every sample: any θ1 solves.
IDENTICAL_TOL = 1e-12

GENERAL_LABELS = tuple(f"root {j}, elbow {e}" for j in range(1, 5) for e in ("up", "down"))

_SAMPLES = np.linspace(0.0, 2.0 * np.pi, 8, endpoint=False)


@dataclass
class GeneralThreeParallelSolver:
    """Closed-form IK of a 6R arm with axes 2, 3, 4 parallel, axes 5 and 6 apart.

    Attributes:
        name: ``"three-parallel-6R"``.
        position_only: False: targets are tool poses ``(N, 4, 4)``.
        labels: :data:`GENERAL_LABELS`.
        sign: ``(6,)`` +1/-1: ``hi·k``.
        k: ``(3,)`` direction of axes 2-4 (along axis 2).
        h: ``(6, 3)``, p: ``(6, 3)``: the joint axes at q = 0.
        R_M, t_M: home pose ``M = fk(0)``.
        W1: ``(3, 3)``: ``a @ W1`` are ``A, B, C`` of ``kᵀ R(h1, θ) a``.
        Minv: ``(2, 2)`` inverse of ``[[D1, E1], [D2, E2]]``.
        rhs0: ``(2,)`` constants ``F1``, ``F2 + k·(p5 - p1)`` of the right sides.
        plane: Plane normal to ``k``; ``zup`` the coordinate of ``h1 × k``.
        arm: The 2R triangle axis 2 -> axis 3 -> axis 4.
    """

    name: str
    position_only: bool
    labels: tuple[str, ...]
    sign: FloatArray
    k: FloatArray
    h: FloatArray
    p: FloatArray
    R_M: FloatArray
    t_M: FloatArray
    W1: FloatArray
    Minv: FloatArray
    rhs0: FloatArray
    plane: Plane
    zup: complex
    arm: TwoLink

    def solve(self, targets: FloatArray) -> Candidates:
        """Every branch's solution for each tool pose ``(N, 4, 4)``."""
        T = targets_array(targets, False)
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            return self._solve(T)

    def _coefficients(self, T: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """``R_G``, ``t_G`` and ``P (N, 2, 3)``: ``(cos q5, sin q5) = P (cos θ1, sin θ1, 1)``."""
        RG = T[:, :3, :3] @ self.R_M.T
        tG = T[:, :3, 3] - RG @ self.t_M
        h, p = self.h, self.p
        a1 = RG @ h[5]
        a2 = tG + RG @ p[5] - p[0]  # G(p6) - p1
        L = np.stack([a1 @ self.W1, a2 @ self.W1], axis=1)  # (N, 2, 3): A, B, C
        L[:, :, 2] -= self.rhs0
        return RG, tG, np.einsum("ij,njk->nik", self.Minv, L)

    def _solve(self, T: FloatArray) -> Candidates:
        N = T.shape[0]
        RG, tG, P = self._coefficients(T)
        # --- subproblem 6: |P x(θ)|² = 1, θ = φ0 + 2 atan(t)
        cs, sn = np.cos(_SAMPLES), np.sin(_SAMPLES)
        Px = P[:, :, :1] * cs + P[:, :, 1:2] * sn + P[:, :, 2:3]  # (N, 2, 8)
        F = (Px**2).sum(axis=1) - 1.0
        scale = 1.0 + (P**2).sum(axis=(1, 2))
        best = np.argmax(np.abs(F), axis=1)
        identical = np.abs(F[np.arange(N), best]) <= IDENTICAL_TOL * scale
        far = _SAMPLES[best] + np.pi  # the angle at t = ∞: |F| largest there
        phi0 = far - np.pi
        c0, s0 = np.cos(phi0)[:, None], np.sin(phi0)[:, None]
        Pr = np.stack([P[..., 0] * c0 + P[..., 1] * s0, P[..., 1] * c0 - P[..., 0] * s0], axis=-1)
        u0, u1, u2 = Pr[..., 0] + P[..., 2], 2.0 * Pr[..., 1], P[..., 2] - Pr[..., 0]

        def dot(x: FloatArray, y: FloatArray) -> FloatArray:
            return (x * y).sum(axis=1)

        coeffs = np.stack(
            [
                dot(u2, u2) - 1.0,
                2.0 * dot(u1, u2),
                dot(u1, u1) + 2.0 * dot(u0, u2) - 2.0,
                2.0 * dot(u0, u1),
                dot(u0, u0) - 1.0,
            ],
            axis=1,
        )
        coeffs[identical] = [1.0, 0.0, 0.0, 0.0, 0.0]  # any; θ1 samples are taken instead
        t = solve_quartic(coeffs)  # (N, 4)
        real = np.abs(t.imag) <= ROOT_IMAG * (1.0 + np.abs(t))
        th = phi0[:, None] + 2.0 * np.arctan(t.real)
        th = np.where(identical[:, None], _SAMPLES[None, ::2], th)
        real |= identical[:, None]
        th, q5, ok = self._polish(P, th)
        keep = real & ok
        th = np.where(keep, th, np.nan)
        q1 = np.angle(np.exp(-1j * th))
        order = np.argsort(np.where(np.isnan(q1), np.inf, q1), axis=1)
        q1 = np.take_along_axis(q1, order, axis=1)
        q5 = np.where(np.isnan(q1), np.nan, np.take_along_axis(q5, order, axis=1))
        # --- q6 by subproblem 1: R(h6, -q6) R5ᵀ k = R_Gᵀ R1 k
        h, p, k = self.h, self.p, self.k
        R1 = rotation_matrix(h[0], np.nan_to_num(q1))  # (N, 4, 3, 3)
        R5 = rotation_matrix(h[4], np.nan_to_num(q5))
        a = k @ R5  # R5ᵀ k
        b = np.einsum("nji,nrj->nri", RG, R1 @ k)  # R_Gᵀ R1 k
        q6 = -subproblem1(a, b, h[5])
        across = np.linalg.norm(np.cross(a, h[5]), axis=-1)
        near = (across < NEAR_ALIGN) & ~np.isnan(q1)
        # --- H = E1⁻¹ G E6⁻¹ E5⁻¹: its angle about k and the image of p4
        y5 = p[4] + (p[3] - p[4]) @ R5  # E5⁻¹(p4) = p5 + R5ᵀ (p4 - p5)
        v = y5 - p[5]
        lin = np.einsum("nrji,njk->nrik", R1, RG)  # R1ᵀ R_G
        if near.any():  # mid-reach q6 (exact alignment) as a second candidate
            q6 = np.concatenate([q6, np.where(near, self._free_q6(R1, lin, tG, v), np.nan)], 1)
            R1, R5, lin, v = (np.concatenate([x, x], axis=1) for x in (R1, R5, lin, v))
            q1, q5, near = (np.concatenate([x, x], axis=1) for x in (q1, q5, near))
        R6 = rotation_matrix(h[5], q6)
        y = p[5] + np.einsum("nrji,nrj->nri", R6, v)  # E6⁻¹(E5⁻¹(p4))
        z = np.einsum("nij,nrj->nri", RG, y) + tG[:, None] - p[0]  # G(y) - p1
        w = p[0] + np.einsum("nrji,nrj->nri", R1, z) - p[1]  # E1⁻¹(G(y)) - p2
        tc = self.plane.c(w)
        RH = lin @ np.swapaxes(R6, -1, -2) @ np.swapaxes(R5, -1, -2)
        e1, e2 = self.plane.basis.T
        He1 = RH @ e1
        th234 = np.arctan2(He1 @ e2, He1 @ e1)
        d2, d3, _, sing2_ = self.arm.solve(tc)  # (N, r, 2): [ψ <= 0, ψ >= 0]
        r = q1.shape[1]
        sing2: BoolArray = np.asarray(sing2_)
        down = (tc * np.conj(self.zup)).real < 0.0
        d2 = np.where(down[..., None], d2[..., ::-1], d2)
        d3 = np.where(down[..., None], d3[..., ::-1], d3)
        qb = np.empty((N, r, 2, 6))
        qb[..., 0] = q1[..., None]
        qb[..., 1] = d2
        qb[..., 2] = self.sign[2] * d3
        qb[..., 3] = self.sign[3] * np.angle(np.exp(1j * (th234[..., None] - d2 - d3)))
        qb[..., 4] = q5[..., None]
        qb[..., 5] = q6[..., None]
        q = qb.reshape(N, 2 * r, 6)
        q[np.isnan(q).any(axis=2)] = np.nan
        aligned = np.zeros((N, 4), dtype=bool)
        if r == 8:  # near alignment: polish both on the pose, keep the closer
            nb = np.repeat(near, 2, axis=1) & ~np.isnan(q[:, :, 0])
            err = np.full((N, 16), np.inf)
            q[nb], err[nb] = self._polish_pose(q[nb], np.repeat(T, 16, axis=0)[nb.ravel()])
            second = err[:, 8:] < np.minimum(err[:, :8], POLISH_OK)
            q = np.where(second[..., None], q[:, 8:], q[:, :8])
            err = np.where(second, err[:, 8:], err[:, :8])
            q[np.isfinite(err) & (err > POLISH_OK)] = np.nan  # did not converge
            R5n = rotation_matrix(h[4], np.nan_to_num(q[..., 4]))
            tilt = np.linalg.norm(np.cross(k @ R5n, h[5]), axis=-1)
            aligned = (np.isfinite(err) & (tilt < ALIGN_TOL)).reshape(N, 4, 2).any(axis=2)
            sing2 = sing2[:, :4]
        realb = ~np.isnan(q[:, :, 0]).reshape(N, 4, 2)
        free = np.zeros((N, 6), dtype=bool)
        free[:, [0, 4]] = (identical & realb.any(axis=(1, 2)))[:, None]
        al_any: BoolArray = np.asarray((aligned[..., None] & realb).any(axis=(1, 2)))
        fold_any: BoolArray = np.asarray((sing2 & realb.any(axis=2)).any(axis=1))
        free[:, [1, 2, 3, 5]] |= al_any[:, None]
        free[:, [1, 3]] |= fold_any[:, None]
        none = ~realb.any(axis=(1, 2))
        gap = np.where(none, 0.0, np.nan)  # out of reach: distance not bounded here
        singular: BoolArray = np.asarray(free.any(axis=1))
        return Candidates(q=q, labels=self.labels, singular=singular, free=free, gap=gap)

    def _polish(self, P: FloatArray, th: FloatArray) -> tuple[FloatArray, FloatArray, BoolArray]:
        """Newton on ``D c5 + E s5 = P``-rows: ``x(θ) ↦ (cos q5, sin q5)``, both unknowns.

        The equations ``Minv⁻¹ (c5, s5) = Minv⁻¹ P x(θ)`` are equivalent to
        ``(c5, s5) = P x(θ)``; Newton runs on ``e = P x(θ) - (cos q5, sin q5)``
        from q5 = the angle of ``P x(θ)``.

        Returns:
            ``θ (N, 4)``, ``q5 (N, 4)`` and ``ok``: residual below ``ROOT_RESIDUAL``.
        """
        Pn = P[:, None]  # (N, 1, 2, 3)
        size = 1.0 + np.abs(P).sum(axis=(1, 2))[:, None]
        x = np.stack([np.cos(th), np.sin(th), np.ones_like(th)], axis=-1)
        u = (Pn * x[:, :, None, :]).sum(axis=-1)
        q5 = np.arctan2(u[..., 1], u[..., 0])
        for _ in range(4):
            c, s = np.cos(th), np.sin(th)
            x = np.stack([c, s, np.ones_like(th)], axis=-1)
            dx = np.stack([-s, c, np.zeros_like(th)], axis=-1)
            u = (Pn * x[:, :, None, :]).sum(axis=-1)
            du = (Pn * dx[:, :, None, :]).sum(axis=-1)
            c5, s5 = np.cos(q5), np.sin(q5)
            e0, e1 = u[..., 0] - c5, u[..., 1] - s5
            # J = [[du0, s5], [du1, -c5]] (d/dθ, d/dq5)
            det = -du[..., 0] * c5 - du[..., 1] * s5
            good = np.abs(det) > 1e-14 * size
            det = np.where(good, det, 1.0)
            dth = (-c5 * e0 - s5 * e1) / det
            dq5 = (du[..., 0] * e1 - du[..., 1] * e0) / det
            th = th - np.where(good, dth, 0.0)
            q5 = q5 - np.where(good, dq5, 0.0)
        x = np.stack([np.cos(th), np.sin(th), np.ones_like(th)], axis=-1)
        u = (Pn * x[:, :, None, :]).sum(axis=-1)
        res = np.hypot(u[..., 0] - np.cos(q5), u[..., 1] - np.sin(q5))
        return th, q5, np.asarray(res <= ROOT_RESIDUAL * size)

    def _fk(self, q: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """Pose ``(m, 4, 4)`` by the product of exponentials, current axes ``(m, 6, 3)`` x2."""
        T = np.broadcast_to(np.eye(4), (len(q), 4, 4)).copy()
        hs, ps = [], []
        for i in range(6):
            hs.append(T[:, :3, :3] @ self.h[i])
            ps.append(T[:, :3, :3] @ self.p[i] + T[:, :3, 3])
            R = rotation_matrix(self.h[i], q[:, i])
            E = np.zeros_like(T)
            E[:, :3, :3], E[:, 3, 3] = R, 1.0
            E[:, :3, 3] = self.p[i] - R @ self.p[i]
            T = T @ E
        M = np.eye(4)
        M[:3, :3], M[:3, 3] = self.R_M, self.t_M
        return T @ M, np.stack(hs, axis=1), np.stack(ps, axis=1)

    def _polish_pose(self, q: FloatArray, T: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Newton (minimum-norm steps) on the pose for candidates ``q (m, 6)`` near alignment.

        The candidate is within about ``NEAR_ALIGN`` times the arm's size of
        ``T``; the Jacobian loses rank only in the direction that leaves the
        pose unchanged, so minimum-norm steps converge to an exact solution.
        """
        best, err = q.copy(), np.full(len(q), np.inf)
        for _ in range(10):
            X, hs, ps = self._fk(q)
            o = X[:, :3, 3]
            A = T[:, :3, :3] @ np.swapaxes(X[:, :3, :3], 1, 2)
            er = 0.5 * np.stack(
                [A[:, 2, 1] - A[:, 1, 2], A[:, 0, 2] - A[:, 2, 0], A[:, 1, 0] - A[:, 0, 1]], axis=1
            )
            e = np.concatenate([T[:, :3, 3] - o, er], axis=1)
            size = np.abs(e).max(axis=1)
            better = size < err
            best[better], err[better] = q[better], size[better]
            J = np.concatenate([np.cross(hs, o[:, None] - ps), hs], axis=2).transpose(0, 2, 1)
            q = q + (np.linalg.pinv(J, rcond=1e-12) @ e[..., None])[..., 0]
        return best, err

    def _free_q6(
        self, R1: FloatArray, lin: FloatArray, tG: FloatArray, v: FloatArray
    ) -> FloatArray:
        """A representative q6 with the wrist aligned: axis 4 at mid-reach of the 2R.

        ``E1⁻¹ G (p6 + R(h6, -q6) v) - p2`` runs on a circle as q6 turns (axis 6
        is then parallel to k): ``Z0 + cos q6 Z1 - sin q6 Z2`` in the plane.
        """
        h6, p = self.h[5], self.p
        along = (v @ h6)[..., None] * h6
        shift = p[0] - p[1] + np.einsum("nrji,nj->nri", R1, tG - p[0])  # + R1ᵀ (t_G - p1)
        parts = [p[5] + along, v - along, np.cross(h6, v)]
        Z = [self.plane.c(np.einsum("nrij,nrj->nri", lin, x)) for x in parts]
        Z0, Z1, Z2 = Z[0] + self.plane.c(shift), Z[1], Z[2]
        L2, L3 = abs(self.arm.a0), abs(self.arm.b0)
        R0, W = np.abs(Z0), np.abs(Z1)
        r = np.minimum(np.maximum(max(L2, L3), np.abs(R0 - W)), R0 + W)
        den = np.where(R0 * W > 0.0, 2.0 * R0 * W, 1.0)
        cb = np.clip((r * r - R0 * R0 - W * W) / den, -1.0, 1.0)
        uz = W * np.exp(1j * (np.angle(Z0) + np.arccos(cb)))
        # c6 Z1 - s6 Z2 = uz: a 2x2 real system
        a11, a12, a21, a22 = Z1.real, -Z2.real, Z1.imag, -Z2.imag
        det = a11 * a22 - a12 * a21
        det = np.where(det != 0.0, det, 1.0)
        c6 = (uz.real * a22 - a12 * uz.imag) / det
        s6 = (a11 * uz.imag - a21 * uz.real) / det
        return np.asarray(np.arctan2(s6, c6))


def make_general_solver(
    h: FloatArray, p: FloatArray, M: FloatArray, k: FloatArray
) -> GeneralThreeParallelSolver | None:
    """The general solver from the joint axes ``h, p (6, 3)``, home pose ``M``, ``k``.

    Returns ``None`` when axes 5 and 6 are parallel or meet (``[D E]`` singular)
    or the 2R triangle is degenerate.
    """
    plane = Plane.normal_to(k)
    arm = TwoLink(complex(plane.c(p[2] - p[1])), complex(plane.c(p[3] - p[2])))
    if not arm.valid:
        return None
    W5 = AxisHeight.about(h[4], k).W
    D1, E1, F1 = h[5] @ W5
    D2, E2, F2 = (p[5] - p[4]) @ W5
    Dm = np.array([[D1, E1], [D2, E2]])
    if abs(np.linalg.det(Dm)) < 1e-9 * (1.0 + np.abs(Dm).max()):
        return None
    return GeneralThreeParallelSolver(
        name="three-parallel-6R",
        position_only=False,
        labels=GENERAL_LABELS,
        sign=np.where(h @ k > 0, 1.0, -1.0),
        k=k,
        h=np.asarray(h, dtype=float),
        p=np.asarray(p, dtype=float),
        R_M=M[:3, :3],
        t_M=M[:3, 3],
        W1=AxisHeight.about(h[0], k).W,
        Minv=np.linalg.inv(Dm),
        rhs0=np.array([F1, F2 + k @ (p[4] - p[0])]),
        plane=plane,
        zup=complex(plane.c(np.cross(h[0], k))),
        arm=arm,
    )
