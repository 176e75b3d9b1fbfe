"""One pose on Python floats: the spherical-wrist solver without numpy's per-call cost.

Through :meth:`SphericalWristSolver.solve` one pose costs some 150 numpy calls on
arrays of 4 to 8 numbers, each a fraction of a microsecond of overhead; the
same arithmetic on Python floats is about three times faster (as ``robot.fk``
does for one configuration). This module repeats that computation step by
step, for every geometry: closed forms when axes 1 and 2 meet or are
parallel, or are skew with axes 2 and 3 parallel; Pieper's quartic otherwise
(:mod:`~kinematica.ik.analytic.pieper_single`). Rare corners (a wrist near
its singularity, a target out of reach) go to the batched code. The tests
hold the two paths to the same candidates.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from kinematica.ik.analytic.pieper_single import quartic_position
from kinematica.ik.analytic.position import SINGULAR_TOL
from kinematica.ik.analytic.subproblems import TRIG_TOL
from kinematica.ik.candidates import Candidates

if TYPE_CHECKING:
    from kinematica.ik.analytic.position import WristCentrePosition

__all__ = ["SinglePose"]

FloatArray = NDArray[np.float64]
Vec = tuple[float, float, float]
Tup = tuple[Any, ...]
_NAN6 = (math.nan,) * 6


def _t(a: FloatArray) -> Tup:
    """Nested tuples of Python floats."""
    return tuple(_t(x) for x in a) if a.ndim > 1 else tuple(float(x) for x in a)


def _root(x: float, size: float) -> float:
    """Square root; NaN below -2 TRIG_TOL size (as ``position._root``)."""
    if x >= 0.0:
        return math.sqrt(x)
    return 0.0 if x >= -2 * TRIG_TOL * size else math.nan


@dataclass(frozen=True)
class SinglePose:
    """The constants of a spherical-wrist solver as Python floats.

    Attributes mirror :class:`~kinematica.ik.analytic.position.WristCentrePosition`
    and the solver's; ``wrist`` packs the wrist constants in the order
    :meth:`_wrist` unpacks them; ``position``, ``wrist_solver`` and ``labels``
    are the batched objects, for the rare corners.
    """

    position: WristCentrePosition
    wrist_solver: Any
    labels: tuple[str, ...]
    kind: str
    prismatic: bool
    parallel23: bool
    frame1: Tup
    p1f: Tup
    coef: Tup
    trig: Tup
    xframe: Tup
    root_signs: Tup
    a: float
    ca: float
    g: float
    elbow_sign: float
    tol2: float
    c_tool: Tup
    leftover: Tup
    axes: Tup  # unit axes of the revolute joints among 1-3
    Ft: Tup
    wrist: Tup
    near2: float
    quartic: bool  # axes 1, 2 skew, axis 3 not parallel to axis 2
    scale: float
    fourier: Tup  # (5, 5) as ``WristCentrePosition._fourier``
    polish: Tup  # h1, h2, p2 - p1, U0, U1, U2 (``pieper.polish_position``)
    polish_p1: Tup

    @classmethod
    def build(
        cls,
        P: WristCentrePosition,
        W: Any,
        labels: tuple[str, ...],
        c_tool: FloatArray,
        leftover: FloatArray,
        axes: FloatArray,
        near_tol: float,
    ) -> SinglePose:
        """The single-pose path.

        Args:
            P: Position geometry.
            W: The ``_Wrist``.
            labels: Branch names.
            c_tool: Wrist centre in the tool frame at q = 0.
            leftover: ``(3, 2)`` ``Mᵀ [h6, x6]``.
            axes: ``(2|3, 3)`` unit axes of the revolute joints among 1-3.
            near_tol: The wrist's near-singular tolerance (sine).
        """
        wrist = (
            float(W.beta[0]),
            float(W.beta[1]),
            1.0 / W.s45**2,
            W.s45,
            *_t(W.gamma_signs),
            *_t(W.q5_dirs[:, 0]),
            *_t(W.q5_dirs[:, 1]),
            W.k56**2,
            *_t(W.beta[2:]),
            *_t(W.q6_dirs),
        )
        return cls(
            position=P,
            wrist_solver=W,
            labels=labels,
            kind=P.kind,
            prismatic=P.prismatic,
            parallel23=P.parallel23,
            frame1=_t(P.frame1),
            p1f=_t(P.p1f),
            coef=_t(P.coef),
            trig=_t(P.trig),
            xframe=_t(P.xframe),
            root_signs=_t(P.root_signs),
            a=P.a,
            ca=P.ca,
            g=P.g,
            elbow_sign=P.elbow_sign,
            tol2=(SINGULAR_TOL * P.scale) ** 2,
            c_tool=_t(c_tool),
            leftover=_t(leftover.T),
            axes=_t(axes),
            Ft=_t(W.F.T),
            wrist=wrist,
            near2=near_tol**2,
            quartic=P.kind == "general" and not P.parallel23,
            scale=P.scale,
            fourier=_t(P._fourier),
            polish=(_t(P.h1), _t(P.h2), _t(P.p2 - P.p1), *_t(P.U)),
            polish_p1=_t(P.p1),
        )

    # ----------------------------------------------------------------- position
    def _values(self, q3: float, c3: float, s3: float) -> tuple[float, float, float, float]:
        """``u1, u2, H, L`` at q3 (``c3, s3``: cos, sin; or q3, q3² for a slide)."""
        c0, c1, c2 = self.coef
        return (
            c0[0] + c3 * c1[0] + s3 * c2[0],
            c0[1] + c3 * c1[1] + s3 * c2[1],
            c0[2] + c3 * c1[2] + s3 * c2[2],
            c0[3] + c3 * c1[3] + s3 * c2[3],
        )

    def _trig(self, rhs: float, sign: float) -> tuple[float, float, float]:
        """q3, cos q3, sin q3 of one root of ``a cos + b sin = rhs`` (see ``_cos_sin``)."""
        (ac, bc), (as_, bs), (r2, _) = self.trig
        s = _root(r2 - rhs * rhs, r2) * sign
        c3, s3 = rhs * ac + s * as_, rhs * bc + s * bs
        return math.atan2(s3, c3), c3, s3

    def _position(self, ct: list[float]) -> tuple[list[Tup], bool, bool, bool]:
        """The 4 position branches (NaN-filled), the q1, q2 free flags and self-motion."""
        F, p = self.frame1, self.p1f
        dz = [ct[0] * F[0][j] + ct[1] * F[1][j] + ct[2] * F[2][j] - p[j] for j in range(3)]
        on1 = dz[1] ** 2 + dz[2] ** 2 < self.tol2
        if self.quartic:
            out, on2, selfmotion = quartic_position(self, ct, dz)
            return out, on1, on2, selfmotion
        zeta, dd = dz[0], dz[0] ** 2 + dz[1] ** 2 + dz[2] ** 2
        phi = math.atan2(dz[2], dz[1])
        a, ca, g, c = self.a, self.ca, self.g, self.coef
        out, on2 = [], False
        for A in range(2):
            sA = 1.0 if A == 0 else -1.0
            pair = []
            for B in range(2):
                sB = 1.0 if B == 0 else -1.0
                if self.kind == "meet":
                    if self.prismatic:
                        b = c[1][3] / 2
                        q3 = _root(b * b - c[0][3] + dd, dd) * self.root_signs[A][B] - b
                        b1, b2 = q3, q3 * q3
                    else:
                        q3, b1, b2 = self._trig(dd - c[0][3], self.root_signs[A][B])
                elif self.kind == "parallel":
                    rhs = ca * zeta - c[0][2]
                    if self.prismatic:
                        q3 = rhs / c[1][2] if B == 0 else math.nan
                        b1, b2 = q3, q3 * q3
                    else:
                        q3, b1, b2 = self._trig(rhs, sB)
                else:  # skew axes 1, 2 and axes 2 ∥ 3: front (A = 0) or back
                    Hc = c[0][2]
                    disc = dd - Hc * Hc - ((zeta - ca * Hc) / g) ** 2
                    L = dd + a * a - 2 * a * _root(disc, dd) * sA
                    q3, b1, b2 = self._trig(L - c[0][3], sB)
                u1, u2, H, L = self._values(q3, b1, b2)
                up2 = u1 * u1 + u2 * u2
                on2 = on2 or up2 < self.tol2
                if self.kind == "meet":
                    v2 = (zeta - ca * H) / g
                    v1 = _root(up2 - v2 * v2, up2) * sA
                elif self.kind == "parallel":
                    v1 = (dd - a * a - L) * (0.5 / a)
                    v2 = _root(up2 - v1 * v1, up2) * sA
                else:
                    v1 = (dd - a * a - L) * (0.5 / a)
                    v2 = (zeta - ca * H) / g
                q2 = math.atan2(u1 * v2 - u2 * v1, u1 * v1 + u2 * v2)
                X = self.xframe
                xa = H * X[0][0] + v1 * X[1][0] + v2 * X[2][0] + X[3][0]
                xb = H * X[0][1] + v1 * X[1][1] + v2 * X[2][1] + X[3][1]
                pair.append((phi - math.atan2(xb, xa), q2, q3, v1))
            if self.kind == "general" and self.elbow_sign * pair[0][3] > 0:
                pair.reverse()  # elbow up first
            out += [p3[:3] for p3 in pair]
        return out, on1, on2, False

    # -------------------------------------------------------------------- wrist
    def _leftover(self, q: Tup, W0: list[Vec]) -> list[Vec]:
        """``Fᵀ R3ᵀ R2ᵀ R1ᵀ`` applied to the two vectors ``W0`` (Rodrigues)."""
        vs = W0
        for k, qj in zip(self.axes, q, strict=False):
            c, s = math.cos(qj), math.sin(qj)
            c1 = 1.0 - c
            new = []
            for v in vs:
                kx = (
                    k[1] * v[2] - k[2] * v[1],
                    k[2] * v[0] - k[0] * v[2],
                    k[0] * v[1] - k[1] * v[0],
                )
                kv = (k[0] * v[0] + k[1] * v[1] + k[2] * v[2]) * c1
                new.append(
                    (
                        v[0] * c - kx[0] * s + k[0] * kv,
                        v[1] * c - kx[1] * s + k[1] * kv,
                        v[2] * c - kx[2] * s + k[2] * kv,
                    )
                )
            vs = new
        F = self.Ft
        return [
            (
                F[0][0] * v[0] + F[0][1] * v[1] + F[0][2] * v[2],
                F[1][0] * v[0] + F[1][1] * v[1] + F[1][2] * v[2],
                F[2][0] * v[0] + F[2][1] * v[1] + F[2][2] * v[2],
            )
            for v in vs
        ]

    def _wrist(self, w: Vec, y: Vec) -> list[tuple[float, float, float]] | None:
        """(q4, q5, q6) for no-flip and flip as in ``_Wrist.solve``; None near singular."""
        b0, b1, inv, s45, gs0, gs1, n0, n1, n2, h0, h1, h2, k2, bp0, bp1, gp, m0, m1, m2, m3 = (
            self.wrist
        )
        w4, wa, wb = w
        off2 = wa * wa + wb * wb
        if off2 < self.near2:
            return None
        beta = b0 - b1 * w4
        g2 = off2 * inv - beta * beta
        g0 = math.sqrt(g2) if g2 >= 0 else (0.0 if g2 >= -TRIG_TOL else math.nan)
        ca = beta * s45
        wy = wa * y[2] - wb * y[1]
        bp = bp0 - bp1 * w4
        out = []
        for sg in (gs0, gs1):
            gam = g0 * sg
            cb = gam * s45
            q4 = math.atan2(ca * wb - cb * wa, ca * wa + cb * wb)
            q5 = math.atan2(w4 * n0 + ca * n1 + cb * n2, w4 * h0 + ca * h1 + cb * h2 - k2)
            cx, cy = bp * m0 + gam * gp * m1, bp * m2 + gam * gp * m3
            out.append((q4, q5, math.atan2(y[0] * cy - wy * cx, y[0] * cx + wy * cy)))
        return out

    # -------------------------------------------------------------------- solve
    def solve(self, T: NDArray[np.float64]) -> Candidates:
        """Candidates for one pose ``T (4, 4)``, as ``solver.solve(T[None])`` gives."""
        M = T.tolist()
        R = [row[:3] for row in M[:3]]
        c = self.c_tool
        ct = [R[i][0] * c[0] + R[i][1] * c[1] + R[i][2] * c[2] + M[i][3] for i in range(3)]
        branches, on1, on2, selfmotion = self._position(ct)
        on1, on2 = on1 or selfmotion, on2 or selfmotion
        W0 = [
            (
                R[0][0] * v[0] + R[0][1] * v[1] + R[0][2] * v[2],
                R[1][0] * v[0] + R[1][1] * v[1] + R[1][2] * v[2],
                R[2][0] * v[0] + R[2][1] * v[1] + R[2][2] * v[2],
            )
            for v in self.leftover
        ]
        q: list[tuple[float, ...]] = []
        near = []
        for k, pos in enumerate(branches):
            if math.isnan(pos[0] + pos[1] + pos[2]):
                q += [_NAN6, _NAN6]
                continue
            w, y = self._leftover(pos, W0)
            wrist = self._wrist(w, y)
            if wrist is None:
                near.append(k)
                wrist = [(0.0, 0.0, 0.0)] * 2
            for qw in wrist:
                q.append(pos + qw if not math.isnan(qw[0] + qw[1] + qw[2]) else _NAN6)
        qa = np.array(q, dtype=float).reshape(1, 8, 6)
        singular = on1 or on2
        wrist_singular = False
        if near:  # rare: the batched code's near-singular treatment
            V = np.array([self._leftover(branches[k], W0) for k in near])  # (k, 2, 3)
            qw, sing = self.wrist_solver.solve(V)
            for i, k in enumerate(near):
                for j in range(2):
                    row = np.concatenate([branches[k], qw[i, j]])
                    qa[0, 2 * k + j] = row if not np.isnan(row).any() else np.nan
            wrist_singular = bool(sing.any())
        gap = np.full(1, np.nan)
        if np.isnan(qa[0, :, 0]).all():
            gap = self.position.gap(np.array([ct]))
        free = np.array([[on1, on2, selfmotion, wrist_singular, False, wrist_singular]])
        return Candidates(
            q=qa,
            labels=self.labels,
            singular=np.array([singular or wrist_singular]),
            free=free,
            gap=gap,
        )
