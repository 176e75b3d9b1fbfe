"""Closed-form IK of arms with a spherical wrist: 6R, and RRP (Stanford type).

The last three axes meet at the wrist centre ``c``, which only joints 1-3 move
(seed 002, "hipótesis de la muñeca esférica"). In product-of-exponentials form
(:mod:`~kinematica.ik.analytic.poe`) the target wrist centre is the point fixed
in the tool frame that sits at ``c`` at q = 0::

    c_t = T_target · M⁻¹ · c

and joints 1-3 must put ``c`` there (:mod:`~kinematica.ik.analytic.position`:
up to four branches; a quartic for general axes). The wrist then supplies the
rotation left over, ``R4 R5 R6 = (R1 R2 R3)ᵀ · R_target · Mᵀ`` (seed 002's
``R36 = (R03)ᵀ R06``), with rotations about the wrist axes at q = 0, which may
meet at any angles:

* ``R4(q4) R5(q5) h6 = w`` (``w`` = the leftover rotation applied to ``h6``)
  is SP2 about ``h4`` and ``h5``: two solutions, "no-flip" and "flip";
* q6 is SP1 about ``h6`` after undoing q4 and q5.

"No-flip" bends the wrist the way it is bent at q = 0 (or, when q = 0 is
itself singular, the way q5 > 0 bends it from there): on the PUMA, sin q5 > 0.
Wrist singularity (axes 4 and 6 aligned, ``w = ±h4``): only ``q4 ± q6`` is
determined. The "no-flip" slot returns the representative with ``q4 = 0``, the
"flip" slot is NaN, the target is flagged singular with q4 and q6 free. Near it
q6 is computed after q4 and q5 so that it absorbs their round-off.

Branch slots: ``4 position × 2 wrist``; label ``k`` is ``2 * position + wrist``.
All candidates are exact to round-off (≤ 1e-12 in the tests); none is wrapped
or filtered beyond NaN for branches without a real solution. One pose at a time
runs on Python floats (:mod:`~kinematica.ik.analytic.wrist_single`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.errors import DimensionError
from kinematica.ik.analytic.poe import Screws
from kinematica.ik.analytic.position import GEOMETRY_TOL, WristCentrePosition
from kinematica.ik.analytic.subproblems import TRIG_TOL, rowmul
from kinematica.ik.analytic.wrist_single import SinglePose
from kinematica.ik.candidates import Candidates
from kinematica.robot import Robot
from kinematica.robot.structure import classify

__all__ = ["SphericalWristSolver", "make_rrp_wrist_solver", "make_spherical_wrist_solver"]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

#: The wrist is singular (axes 4 and 6 aligned) when the sine of the angle
#: between ``h4`` and ``w`` is below this. Above it the two regular solutions
#: are exact (q6 is computed after q4, so an ill-determined q4 is compensated).
WRIST_SINGULAR_TOL = 1e-12

#: Below this sine of the angle between ``h4`` and ``w`` (nearly aligned axes
#: 4 and 6), q6 is recomputed after q4 and q5 so that it compensates their
#: errors; above it q4 and q6 are each accurate to ~1e-16 / this.
NEAR_SINGULAR_TOL = 1e-2

#: Configurations at which the positioning Jacobian of the wrist centre is
#: tested for rank 3 (fixed, so the decision depends on the geometry alone).
_PROBES = np.array([[0.3, -0.7, 1.1], [-1.3, 0.4, -0.6], [2.1, 1.7, 0.2]])
#: Smallest singular value ratio of that Jacobian for a usable arm.
_RANK_TOL = 1e-6


@dataclass(frozen=True, eq=False)
class _Wrist:
    """Precomputed wrist geometry in the frame ``F = [h4, ea, eb]``.

    ``ea`` is the unit part of ``h5`` normal to ``h4``, ``eb = h4 × ea``; so
    ``h5 = (k45, s45, 0)`` and ``h4 × h5 = (0, 0, s45)`` in ``F``.
    """

    F: FloatArray  # (3, 3) columns h4, ea, eb
    k45: float
    s45: float
    k56: float  # h5ᵀh6
    h6: FloatArray  # (3,) base frame
    x6: FloatArray  # (3,) a unit vector normal to h6, base frame
    beta: FloatArray  # (5,) constants of β, β' and γ'/γ (see solve)
    q5_dirs: FloatArray  # (3, 2) h5 × h6 and h6 in F
    q6_dirs: FloatArray  # (4,) h5 and h6 × h5 along x6 and y6 = h6 × x6
    x6_dirs: FloatArray  # (3, 2) h6 × x6 and x6 in F
    gamma_signs: FloatArray  # (2,) sign of γ on the no-flip and flip branches
    K45: FloatArray  # (2, 2, 3, 3) cross-product matrices of h4, h5 in F, and squares

    @classmethod
    def from_axes(cls, h4: FloatArray, h5: FloatArray, h6: FloatArray) -> _Wrist | None:
        k45 = float(h4 @ h5)
        ea = h5 - k45 * h4
        s45 = float(np.linalg.norm(ea))
        if s45 < GEOMETRY_TOL or np.linalg.norm(np.cross(h5, h6)) < GEOMETRY_TOL:
            return None  # consecutive wrist axes coincide: no 3-DOF wrist
        ea = ea / s45
        F = np.stack([h4, ea, np.cross(h4, ea)], axis=1)
        x6 = np.cross(h6, [1.0, 0.0, 0.0])
        if np.linalg.norm(x6) < 0.5:
            x6 = np.cross(h6, [0.0, 1.0, 0.0])
        x6 = x6 / np.linalg.norm(x6)
        y6 = np.cross(h6, x6)
        k56 = float(h5 @ h6)
        s56 = math.sqrt(1.0 - k56 * k56)
        # "no-flip" bends the wrist as at q = 0 (the sign of γ there), or as
        # q5 > 0 bends it from there when γ = 0 at q = 0 (h6 in the plane of
        # h4 and h5, e.g. aligned with h4): (h4 × h5)ᵀ R5(ε) h6 ≈ ε (k45 k56 - h4ᵀh6)
        home = float(np.cross(h4, h5) @ h6)
        bend = k45 * k56 - float(h4 @ h6)
        flip_sign = math.copysign(1.0, home if abs(home) > GEOMETRY_TOL else bend)
        return cls(
            F=F,
            k45=k45,
            s45=s45,
            k56=k56,
            h6=h6,
            x6=x6,
            beta=np.array(
                [k56 / s45**2, k45 / s45**2, k45 / s56**2, k56 / s56**2, -(s45**2) / s56**2]
            ),
            q5_dirs=F.T @ np.stack([np.cross(h5, h6), h6], axis=1),
            q6_dirs=np.array([h5 @ x6, np.cross(h6, h5) @ x6, h5 @ y6, np.cross(h6, h5) @ y6]),
            x6_dirs=F.T @ np.stack([y6, x6], axis=1),
            gamma_signs=flip_sign * np.array([1.0, -1.0]),
            K45=_cross_matrices([np.array([1.0, 0.0, 0.0]), F.T @ h5]),
        )

    def solve(self, V: FloatArray) -> tuple[FloatArray, BoolArray]:
        """(q4, q5, q6) for leftover rotations ``R``, given ``R h6`` and ``R x6`` in F.

        Args:
            V: ``(..., 2, 3)``: rows ``w = R h6`` and ``y = R x6`` in frame F.

        Returns:
            ``q (..., 2, 3)`` (no-flip, flip; NaN where the wrist cannot make
            the rotation) and ``singular (...)``.
        """
        w4, wa, wb = V[..., 0, 0], V[..., 0, 1], V[..., 0, 2]
        off2 = wa * wa + wb * wb  # |w × h4|², exact (no 1 - cos² cancellation)
        # c = R5 h6 = R4ᵀ w = α h4 + β h5 + γ (h4 × h5) = (w4, β s45, γ s45) in F
        beta = self.beta[0] - self.beta[1] * w4
        g2 = off2 * (1.0 / self.s45**2) - beta * beta
        gam = np.sqrt(np.maximum(g2, np.minimum(0.0, g2 + TRIG_TOL)))[..., None] * self.gamma_signs
        ca, cb = beta * self.s45, gam * self.s45  # (...), (..., 2): NaN if unreachable
        w4_, ca_, wa_, wb_ = w4[..., None], ca[..., None], wa[..., None], wb[..., None]
        q = np.empty((*cb.shape, 3))
        # q4 turns c onto w about h4 (the first axis of F)
        q[..., 0] = np.arctan2(ca_ * wb_ - cb * wa_, ca_ * wa_ + cb * wb_)
        # q5 turns h6 onto c about h5: atan2(c · (h5 × h6), c · h6 - (h5ᵀh6)²)
        n, h = self.q5_dirs[:, 0], self.q5_dirs[:, 1]
        q[..., 1] = np.arctan2(
            w4_ * n[0] + ca_ * n[1] + cb * n[2], w4_ * h[0] + ca_ * h[1] + cb * h[2] - self.k56**2
        )
        # q6 turns R_remᵀ h4 onto c' = R5ᵀ h4 about h6. In the frame (h6, x6, y6),
        # R_remᵀ h4 = (w4, y · h4, (w × y) · h4) as R_rem maps (h6, x6, y6) to (w, y, w × y);
        # c' = α' h6 + β' h5 + γ' (h6 × h5) with h6ᵀc' = w4, h5ᵀc' = h5ᵀh4, γ' ∝ -γ.
        y0, wy = V[..., 1, 0, None], (wa * V[..., 1, 2] - wb * V[..., 1, 1])[..., None]
        bp = (self.beta[2] - self.beta[3] * w4)[..., None]
        gp = gam * self.beta[4]
        m = self.q6_dirs
        cx, cy = bp * m[0] + gp * m[1], bp * m[2] + gp * m[3]
        q[..., 2] = np.arctan2(y0 * cy - wy * cx, y0 * cx + wy * cy)
        singular = off2 < WRIST_SINGULAR_TOL**2
        near = off2 < NEAR_SINGULAR_TOL**2
        if near.any():
            q[near] = self._near_singular(V[near], q[near], singular[near])
        return q, singular

    def _near_singular(self, V: FloatArray, q: FloatArray, singular: BoolArray) -> FloatArray:
        """Wrist solutions where axes 4 and 6 are (nearly) aligned.

        There q4 and q6 are ill-determined one by one (only their sum or
        difference is well-determined), so q6 is recomputed after q4 and q5:
        it turns x6 onto ``R5ᵀ R4ᵀ R x6`` about h6 and compensates any error
        in q4. Where the wrist is singular, q4 = 0 (so ``c = w``) represents
        the no-flip family; the flip slot is the same family and is NaN.

        Args:
            V: ``(k, 2, 3)`` as for :meth:`solve`.
            q: ``(k, 2, 3)`` the regular solutions.
            singular: ``(k,)`` rows to replace by the representative.

        Returns:
            ``(k, 2, 3)`` solutions.
        """
        q = q.copy()
        if singular.any():
            w = V[singular, 0]  # c = w: q5 turns h6 onto w about h5
            P = w @ self.q5_dirs
            q[singular, 0] = [0.0, 0.0, 0.0]
            q[singular, 0, 1] = np.arctan2(P[:, 0], P[:, 1] - self.k56**2)
            q[singular, 1] = np.nan
        R = _rot(self.K45, q[..., :2])  # (k, 2, 2, 3, 3)
        z = V[:, None, None, 1, :] @ (R[..., 0, :, :] @ R[..., 1, :, :])  # (k, 2, 1, 3)
        Z = z[..., 0, :] @ self.x6_dirs  # z · (h6 × x6), z · x6
        q[..., 2] = np.arctan2(Z[..., 0], Z[..., 1])
        return q


@dataclass(frozen=True, eq=False)
class SphericalWristSolver:
    """All closed-form IK solutions of a 6R or RRP arm with a spherical wrist.

    Build with :func:`make_spherical_wrist_solver` or :func:`make_rrp_wrist_solver`.

    Attributes:
        name: ``"spherical-wrist"`` or ``"rrp-spherical-wrist"``.
        position_only: False: targets are full poses.
        labels: ``(8,)`` branch names, ``"<position branch>, wrist no-flip|flip"``.
    """

    name: str
    labels: tuple[str, ...]
    position: WristCentrePosition
    wrist: _Wrist
    c_tool: FloatArray  # wrist centre in the tool frame at q = 0: M⁻¹ c
    leftover: FloatArray  # (3, 2): Mᵀ [h6, x6] (rotation part of M)
    Kt: FloatArray  # (3|2, 3, 6) [[k]×ᵀ, [k]×²ᵀ] of the revolute axes among 1-3 (on rows)
    F: FloatArray  # (3, 3) the wrist frame (columns h4, ea, eb)
    single: SinglePose | None = None  # one pose on Python floats
    position_only: bool = False

    @property
    def nrot(self) -> int:
        """Number of revolute joints among joints 1-3 (3, or 2 for RRP)."""
        return len(self.Kt)

    def solve(self, targets: FloatArray) -> Candidates:
        """Every branch's solution for each target pose.

        Args:
            targets: ``(N, 4, 4)`` tool poses in the base frame.

        Returns:
            Candidates with ``q (N, 8, 6)``.
        """
        T = np.asarray(targets, dtype=float)
        if T.ndim != 3 or T.shape[1:] != (4, 4):
            raise DimensionError(f"targets must have shape (N, 4, 4), got {T.shape}")
        N = len(T)
        if N == 1 and self.single is not None:
            return self.single.solve(T[0])
        Rt = T[:, :3, :3]
        with np.errstate(invalid="ignore", divide="ignore"):
            ct = (Rt.reshape(-1, 3) @ self.c_tool).reshape(N, 3) + T[:, :3, 3]
            pos = self.position.solve(ct)
            # leftover rotation R4 R5 R6 = R3ᵀ R2ᵀ R1ᵀ Rt Mᵀ, applied to h6 and x6 (as
            # rows): undo joints 1-3 one by one (Rodrigues), then into the wrist frame
            V = (Rt.reshape(-1, 3) @ self.leftover).reshape(N, 1, 3, 2).swapaxes(-1, -2)
            qr = pos.q[..., : self.nrot, None, None]
            sq, cq1 = np.sin(qr), 1.0 - np.cos(qr)
            for j in range(self.nrot):
                KV = rowmul(V, self.Kt[j])  # [k]× v and [k]×² v, as rows
                V = V - sq[:, :, j] * KV[..., :3] + cq1[:, :, j] * KV[..., 3:]
            qw, wsing = self.wrist.solve(rowmul(V, self.F))  # (N, 4, 2, 3), (N, 4)
        branches = np.empty((N, 4, 2, 6))
        branches[..., 3:] = qw  # all NaN wherever the position or the wrist has no solution
        branches[..., :3] = pos.q[:, :, None, :] + 0.0 * qw[..., 2:]  # ... so the whole branch
        q = branches.reshape(N, 8, 6)
        some = ~np.isnan(q[:, :, 3]).all(axis=1)
        gap = np.full(N, np.nan)
        if not some.all():
            gap[~some] = self.position.gap(ct[~some])
        wrist_free = wsing.any(axis=1)
        free = np.zeros((N, 6), dtype=bool)
        free[:, :3] = pos.free
        free[:, 3] = free[:, 5] = wrist_free
        return Candidates(
            q=q, labels=self.labels, singular=pos.singular | wrist_free, free=free, gap=gap
        )


_EYE = np.eye(3)


def _cross_matrices(axes: list[FloatArray] | FloatArray) -> FloatArray:
    """``(2, m, 3, 3)``: ``[k]×`` (with ``[k]× v = k × v``) and ``[k]×²`` of each axis."""
    K = np.array([[[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]] for k in axes])
    return np.stack([K, K @ K])


def _rot(K: FloatArray, theta: FloatArray) -> FloatArray:
    """Rotations about fixed unit axes, by Rodrigues' formula.

    Args:
        K: ``(2, m, 3, 3)``: the cross-product matrices ``[k]×`` of the axes
            and their squares.
        theta: ``(..., m)`` angles.

    Returns:
        ``(..., m, 3, 3)`` ``I + sin θ [k]× + (1 - cos θ) [k]×²``.
    """
    s, c = np.sin(theta)[..., None, None], np.cos(theta)[..., None, None]
    return (_EYE + K[1]) + s * K[0] - c * K[1]


def _build(robot: Robot, kind: str, types: str) -> SphericalWristSolver | None:
    if robot.dof != 6 or robot.joint_types != types:
        return None
    structure = classify(robot)
    if structure.kind != kind or structure.wrist_center is None:
        return None
    screws = Screws.from_robot(robot)
    h, p = screws.directions, screws.points
    c = np.asarray(structure.wrist_center, dtype=float)
    prismatic3 = types[2] == "P"
    if not _positions_wrist_centre(robot, c):
        return None
    position = WristCentrePosition.from_axes(h[:3], p[:3], prismatic3, c)
    wrist = _Wrist.from_axes(h[3], h[4], h[5])
    if position is None or wrist is None:
        return None
    M = screws.home
    c_tool = M[:3, :3].T @ (c - M[:3, 3])
    K123 = _cross_matrices(h[: 2 if prismatic3 else 3])
    labels = tuple(f"{pos}, wrist {w}" for pos in position.labels for w in ("no-flip", "flip"))
    leftover = M[:3, :3].T @ np.stack([wrist.h6, wrist.x6], axis=1)
    name = "spherical-wrist" if not prismatic3 else "rrp-spherical-wrist"
    return SphericalWristSolver(
        name=name,
        labels=labels,
        position=position,
        wrist=wrist,
        c_tool=c_tool,
        leftover=leftover,
        Kt=np.concatenate([K123[0].swapaxes(1, 2), K123[1].swapaxes(1, 2)], axis=2),
        F=wrist.F,
        single=SinglePose.build(
            position, wrist, labels, c_tool, leftover, h[: len(K123[0])], NEAR_SINGULAR_TOL
        ),
    )


def _positions_wrist_centre(robot: Robot, c: FloatArray) -> bool:
    """True when joints 1-3 move the wrist centre in 3 independent directions."""
    M = robot.fk(np.zeros(robot.dof))
    c_tool = np.linalg.solve(M, np.append(c, 1.0))[:3]
    q = np.zeros((len(_PROBES), robot.dof))
    q[:, :3] = _PROBES
    T = robot.fk(q)
    J = robot.jacobian(q)  # (k, 6, n): linear velocity of the tool origin, then ω
    r = T[:, :3, :3] @ c_tool  # wrist centre relative to the tool origin
    Jc = J[:, :3, :3] + np.cross(J[:, 3:, :3], r[:, :, None], axis=1)
    s = np.linalg.svd(Jc, compute_uv=False)
    return bool(np.any(s[:, -1] > _RANK_TOL * s[:, 0]))


def make_spherical_wrist_solver(robot: Robot) -> SphericalWristSolver | None:
    """A closed-form solver for a 6R arm whose last three axes meet, or None.

    Handles any first three axes (meeting shoulder axes as on the PUMA, a
    shoulder offset as on KUKA/ABB arms, or general skew axes: a quartic) and
    any wrist twists, with any DH convention, base and tool. Returns None when
    the structure is not ``"spherical-wrist-6R"`` or the first three joints
    cannot move the wrist centre in three directions.
    """
    return _build(robot, "spherical-wrist-6R", "RRRRRR")


def make_rrp_wrist_solver(robot: Robot) -> SphericalWristSolver | None:
    """A closed-form solver for an RRP arm with a spherical wrist (Stanford type), or None.

    The slide may be negative in a candidate (joint limits are the caller's);
    the branches are "shoulder right/left" × "slide out/in" when axes 1 and 2
    meet (up to 4 wrist centres), or the real roots of a quartic otherwise.
    """
    return _build(robot, "rrp-spherical-wrist", "RRPRRR")
