"""Where the first three joints put a point: RRR or RRP arms, all solutions.

Joints 1 and 2 are revolute (lines ``(h1, p1)``, ``(h2, p2)`` at q = 0); joint 3
is revolute or prismatic. A point ``c`` fixed after joint 3 (the wrist centre)
must reach ``c_t``. Write ``u(q3)`` for the vector from a point ``p2`` of axis 2
to ``c`` once joint 3 has moved, and ``d = c_t - p1``. Joint 1 keeps the height
``ζ = h1ᵀd`` and the distance ``|d|`` of the point from ``p1``, so two
equations in ``(q2, q3)`` remain. In the plane normal to ``h2`` (orthonormal
``e1, e2``, ``e1 × e2 = h2``) joint 2 turns the part ``(u1, u2)`` of ``u`` to
``(v1, v2)``; with ``H = h2ᵀu``, ``L = |u|²``, ``cα = h1ᵀh2``::

    h1ᵀ(x - p1) = ζ      →   g v2 = ζ - cα H                  (g = h1ᵀe2)
    |x - p1|²   = |d|²   →   2 δᵀ(v1 e1 + v2 e2) = |d|² - a² - L
    joint 2 keeps |v|    →   v1² + v2² = u1² + u2²

where ``δ = p2 - p1`` is the common normal of axes 1 and 2 (``|δ| = a``).
Three geometries, decided once per arm:

* ``"meet"`` (axes 1 and 2 meet, ``a = 0``, PUMA, Stanford): ``L(q3) = |d|²``
  gives q3 (two: SP3, or a quadratic for a slide); ``v2`` follows and
  ``v1 = ±sqrt(u1² + u2² - v2²)`` gives two q2 each (the shoulder).
* ``"parallel"`` (axes 1 and 2 parallel): ``H(q3) = cα ζ`` gives q3 (SP4 or
  linear), ``v1`` follows and ``v2 = ±...`` gives two q2 each.
* ``"general"`` (skew axes): ``δ = a e1``, both ``v1, v2`` are known given q3
  and the third line is the one equation left. For a revolute joint 3 it is
  a trigonometric polynomial of degree 2 in q3 (a quartic in ``tan(q3/2)``,
  the classical Pieper/Craig elimination), for a slide a quartic in q3. With
  axes 2 and 3 parallel ``H`` is constant and it is a quadratic in ``L``,
  solved in closed form (shoulder front/back), then SP3-like for q3.

Then ``q2 = atan2(u1 v2 - u2 v1, u1 v1 + u2 v2)`` and q1 is SP1 about axis 1.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from kinematica.ik.analytic import pieper
from kinematica.ik.analytic.subproblems import TRIG_TOL, rowmul

__all__ = ["PositionSolutions", "WristCentrePosition"]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

#: Two axes are parallel when the sine of their angle is below this; lines
#: meet when their distance is below this times the arm's size.
GEOMETRY_TOL = 1e-9
#: A target this close (times the arm's size) to axis 1 leaves q1 free; a
#: wrist centre this close to axis 2 leaves q2 free.
SINGULAR_TOL = 1e-12


@dataclass(frozen=True)
class PositionSolutions:
    """Joint values of the first three joints for N target points.

    Attributes:
        q: ``(N, 4, 3)``, NaN where a branch has no real solution.
        singular: ``(N,)`` True where q1 or q2 is free (point on axis 1 or 2).
        free: ``(N, 3)`` which of q1..q3 are free.
    """

    q: FloatArray
    singular: BoolArray
    free: BoolArray


def _foot_points(
    h1: FloatArray, p1: FloatArray, h2: FloatArray, p2: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """Feet of the common normal of two non-parallel lines."""
    w, b = p1 - p2, float(h1 @ h2)
    d1, e = float(h1 @ w), float(h2 @ w)
    den = 1.0 - b * b
    return p1 + (b * e - d1) / den * h1, p2 + (e - b * d1) / den * h2


@dataclass(frozen=True, eq=False)
class WristCentrePosition:
    """Closed-form placement of a point by joints R, R, R|P (see module doc).

    Build with :meth:`from_axes`; the attributes are precomputed geometry.

    Attributes:
        kind: ``"meet"``, ``"parallel"`` or ``"general"`` (axes 1 and 2).
        prismatic: True when joint 3 slides.
        parallel23: True when axes 2 and 3 are parallel (revolute joint 3).
        labels: ``(4,)`` names of the four position branches.
        h1, h2: Unit directions of axes 1, 2.
        p1, p2: Points on axes 1, 2 (feet of their common normal when skew).
        a: Distance of axes 1 and 2; ``ca``, ``g``: ``h1ᵀh2`` and ``h1ᵀe2``.
        U: ``(3, 3)`` ``u(q3) = U0 + U1 cos q3 + U2 sin q3`` (revolute) or
            ``U0 + q3 U1`` (slide, ``U2 = 0``).
        coef: ``(3, 4)`` the same basis mapped to ``[u1, u2, H, L]``.
        scale: A length of the arm's size (m), for tolerances.
        shell: ``(r_lo, r_hi, z_lo, z_hi)``: bounds of ``|x - p1|`` and, with
            axes 1 and 2 parallel, of ``h1ᵀ(x - p1)`` (else ±inf); see :meth:`gap`.
        frame1: ``(3, 3)`` columns ``h1, a1, b1``, right-handed.
        p1f: ``p1`` in those coordinates.
        xframe: ``(4, 2)`` components along ``a1, b1`` of ``h2, e1, e2, p2 - p1``.
        elbow_sign: ``g · sign(h2ᵀh3)``: with axes 2 ∥ 3 the second q3 root
            of a pair is "elbow up" where ``elbow_sign · v1 > 0``.
        root_signs: ``(2, 2)`` sign of the square root giving each slot's q3
            in the ``"meet"`` geometry (rows: shoulder right, left), ordered so
            that "elbow up" comes first when axes 2 ∥ 3.
        trig: Constants of the SP3/SP4-like equation for a revolute q3
            (``L(q3)`` or, for ``"parallel"``, ``H(q3)``).
    """

    kind: str
    prismatic: bool
    parallel23: bool
    labels: tuple[str, ...]
    h1: FloatArray
    h2: FloatArray
    p1: FloatArray
    p2: FloatArray
    a: float
    ca: float
    g: float
    U: FloatArray
    coef: FloatArray
    scale: float
    shell: tuple[float, float, float, float]
    frame1: FloatArray
    p1f: FloatArray
    xframe: FloatArray
    elbow_sign: float
    root_signs: FloatArray
    trig: FloatArray
    _fourier: FloatArray  # (5, 5): [X0², X0, Y0², Y0, 1] -> Fourier coefficients of F

    @classmethod
    def from_axes(
        cls, h: FloatArray, p: FloatArray, prismatic: bool, c: FloatArray
    ) -> WristCentrePosition | None:
        """Precompute the geometry, or None if the three joints cannot place ``c``.

        Args:
            h: ``(3, 3)`` unit directions of joints 1..3 at q = 0.
            p: ``(3, 3)`` points on the axes.
            prismatic: Joint 3 slides (joints 1, 2 are revolute).
            c: ``(3,)`` the point at q = 0.
        """
        h1, h2, h3 = (np.asarray(v, float) / np.linalg.norm(v) for v in h)
        p1, p2, p3 = (np.asarray(v, float) for v in p)
        c = np.asarray(c, float)
        scale = 1.0 + float(np.linalg.norm(c - p1) + np.linalg.norm(p2 - p1))
        ca, sa = float(h1 @ h2), float(np.linalg.norm(np.cross(h1, h2)))
        if sa < GEOMETRY_TOL:
            delta = (p2 - p1) - ((p2 - p1) @ h1) * h1
            a = float(np.linalg.norm(delta))
            if a < GEOMETRY_TOL * scale:
                return None  # axes 1 and 2 coincide
            kind, p2 = "parallel", p1 + delta
            e1 = delta / a
            e2 = np.cross(h2, e1)
        else:
            f1, f2 = _foot_points(h1, p1, h2, p2)
            a = float(np.linalg.norm(f2 - f1))
            if a < GEOMETRY_TOL * scale:
                kind, p1 = "meet", (f1 + f2) / 2
                p2, a = p1, 0.0
                e2 = (h1 - ca * h2) / sa
                e1 = np.cross(e2, h2)
            else:
                kind, p1, p2 = "general", f1, f2
                e1 = (f2 - f1) / a
                e2 = np.cross(h2, e1)
        if prismatic:
            U = np.array([c - p2, h3, np.zeros(3)])
            parallel23 = False
        else:
            r = c - p3
            rpar = (r @ h3) * h3
            U = np.array([p3 - p2 + rpar, r - rpar, np.cross(h3, r - rpar)])
            if float(np.linalg.norm(U[1])) < GEOMETRY_TOL * scale:
                return None  # the point is on axis 3
            parallel23 = float(np.linalg.norm(np.cross(h3, h2))) < GEOMETRY_TOL
            if kind == "parallel" and parallel23:
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
        g = float(h1 @ e2)
        # |x - p1| = |δ + R2 u| lies in [max(0, umin - a, a - umax), a + umax]; with
        # axes 1 and 2 parallel h1ᵀ(x - p1) = cα H lies in cα [Hmin, Hmax]
        zlo, zhi = sorted(ca * v for v in Hrange) if kind == "parallel" else (-math.inf, math.inf)
        shell = (max(0.0, umin - a, a - umax), a + umax, zlo, zhi)
        fourier = np.zeros((5, 5))
        if kind == "general" and not prismatic:
            fourier = pieper.fourier_matrix(a, sa, ca, np.array(L), coef[:, 2])
        a1 = np.cross(h1, [1.0, 0.0, 0.0])
        if np.linalg.norm(a1) < 0.5:
            a1 = np.cross(h1, [0.0, 1.0, 0.0])
        a1 = a1 / np.linalg.norm(a1)
        frame1 = np.stack([h1, a1, np.cross(h1, a1)], axis=1)
        xframe = np.stack([h2, e1, e2, p2 - p1]) @ frame1[:, 1:]
        # Elbow up: the elbow lies on the side of the shoulder-wrist line that
        # axis 1 points to: sign(h1ᵀ(h2 × R2 u)) s_e > 0 with s_e = uᵀ((e0 - p2) × h2)
        # (e0: the point of axis 3 nearest p2), Lee's ELBOW indicator read
        # geometrically. The first factor is sign(g v1); with axes 2 ∥ 3,
        # s_e = (h2ᵀh3 / 2) dL/dq3, which is -s (resp. +s) times that on the
        # first (second) root of a pair (see _cos_sin). So the second root
        # is "up" exactly when g v1 (h2ᵀh3) > 0.
        elbow_sign = float(h1 @ e2) * float(np.sign(h2 @ h3))
        # "meet": sign(g v1) is the shoulder sign (g > 0), so the order is fixed
        root_signs = np.array([[1.0, -1.0], [1.0, -1.0]])
        if kind == "meet" and parallel23:
            root_signs[0 if elbow_sign > 0 else 1] *= -1.0
        labels = _labels(kind, prismatic, parallel23)
        return cls(
            kind, prismatic, parallel23, labels, h1, h2, p1, p2, a, ca, g, U, coef,
            scale, shell, frame1, p1 @ frame1, xframe, elbow_sign, root_signs,
            _trig_rows(coef[1:, 2 if kind == "parallel" else 3], prismatic), fourier,
        )  # fmt: skip

    # ------------------------------------------------------------------ solve
    def solve(self, ct: FloatArray) -> PositionSolutions:
        """All (q1, q2, q3) putting the point at ``ct``.

        Args:
            ct: ``(N, 3)`` target points, base frame.

        Returns:
            The four branches per target (see :attr:`labels`); :meth:`gap`
            bounds the distance of the targets that have none.
        """
        N = len(ct)
        dz = ct @ self.frame1 - self.p1f  # along h1, a1, b1 (from p1)
        zeta = dz[:, 0, None, None]
        dd = (dz * dz).sum(axis=1)[:, None, None]
        # Slots are laid out (N, A, B) with A·B = 4: (shoulder sign, q3 root) for
        # "meet"/"parallel", (front/back, q3 root) with axes 2 ∥ 3, (1, root) else.
        q3, Hu, selfmotion = self._q3(zeta, dd)
        u1, u2, H, L = Hu[..., 0], Hu[..., 1], Hu[..., 2], Hu[..., 3]
        uperp2 = u1 * u1 + u2 * u2
        if self.kind == "meet":
            v2 = (zeta - self.ca * H) * (1.0 / self.g)
            v1 = _root(uperp2 - v2 * v2, uperp2) * _SIGNS
        elif self.kind == "parallel":
            v1 = (dd - self.a**2 - L) * (0.5 / self.a)
            v2 = _root(uperp2 - v1 * v1, uperp2) * _SIGNS
        else:
            v1 = (dd - self.a**2 - L) * (0.5 / self.a)
            v2 = (zeta - self.ca * H) * (1.0 / self.g)
            if not self.parallel23:
                # the third equation, v1² + v2² = |u⊥|², holds at real roots only;
                # the point misses the target by the difference of the radii
                miss = np.abs(np.sqrt(v1 * v1 + v2 * v2) - np.sqrt(uperp2))
                q3 = np.where(miss <= pieper.ACCEPT_TOL * self.scale, q3, np.nan)
        shape = np.broadcast_shapes(v1.shape, v2.shape)
        q = np.empty((*shape, 3))
        q[..., 2] = q3
        # joint 2 turns (u1, u2) onto (v1, v2)
        q[..., 1] = np.arctan2(u1 * v2 - u2 * v1, u1 * v1 + u2 * v2)
        # the point after joints 2 and 3, x - p1 = (p2 - p1) + H h2 + v1 e1 + v2 e2,
        # normal to axis 1; joint 1 turns it onto d (SP1)
        Y = np.empty((*shape, 3))
        Y[..., 0], Y[..., 1], Y[..., 2] = H, v1, v2
        x = rowmul(Y, self.xframe[:3]) + self.xframe[3]
        q[..., 0] = np.arctan2(dz[:, 2], dz[:, 1])[:, None, None] - np.arctan2(x[..., 1], x[..., 0])
        if self.kind == "general" and not self.parallel23:
            # the elimination loses accuracy near double roots: polish those
            rows = np.nonzero((miss > pieper.POLISH_FROM * self.scale).any(axis=(1, 2)))[0]
            if len(rows):
                q[rows, 0] = pieper.polish_position(self, q[rows, 0], ct[rows] - self.p1)
        if self.parallel23 and self.kind == "general":  # elbow up first in each pair
            swap = (self.elbow_sign * v1[..., :1] > 0)[..., None]
            q = np.where(swap, q[:, :, ::-1], q)
        tol2 = (SINGULAR_TOL * self.scale) ** 2
        free = np.zeros((N, 3), dtype=bool)
        free[:, 0] = dz[:, 1] ** 2 + dz[:, 2] ** 2 < tol2
        free[:, 1] = (uperp2 < tol2).any(axis=(1, 2))
        if selfmotion is not None:
            free |= selfmotion[:, None]
        singular = free[:, 0] | free[:, 1] | free[:, 2]
        return PositionSolutions(q=q.reshape(N, 4, 3), singular=singular, free=free)

    # ---------------------------------------------------------------- helpers
    def _values(self, b: FloatArray) -> FloatArray:
        """``[u1, u2, H, L]`` (new last axis) at q3 = ``b`` (a slide)."""
        c = self.coef
        b = b[..., None]
        return (c[2] * b + c[1]) * b + c[0]

    def _q3(
        self, zeta: FloatArray, dd: FloatArray
    ) -> tuple[FloatArray, FloatArray, BoolArray | None]:
        """q3 per slot, the values ``[u1, u2, H, L]`` there, rows with a self-motion.

        Args:
            zeta: ``(N, 1, 1)`` height of the target along axis 1.
            dd: ``(N, 1, 1)`` squared distance of the target from ``p1``.

        Returns:
            ``q3`` broadcastable to the slots ``(N, A, B)``, the values
            ``(..., 4)`` and the self-motion mask (or None).
        """
        c = self.coef
        if self.kind == "meet":  # L(q3) = |d|²: (2, 2), each shoulder its root order
            if self.prismatic:
                b = c[1, 3] / 2
                q3 = _root(b * b - c[0, 3] + dd, dd) * self.root_signs - b
                return q3, self._values(q3), None
            cs = _cos_sin(self.trig, dd - c[0, 3], self.root_signs)
        elif self.kind == "parallel":  # H(q3) = cα ζ: (1, 2)
            rhs = self.ca * zeta - c[0, 2]
            if self.prismatic:
                q3 = rhs / c[1, 2] + np.array([0.0, np.nan])
                return q3, self._values(q3), None
            cs = _cos_sin(self.trig, rhs, _PAIR)
        elif self.parallel23:
            # H constant: L = |d|² + a² ∓ 2a sqrt(|d|² - H² - ((ζ - cα H)/g)²), (2, 2)
            Hc = c[0, 2]
            disc = dd - Hc * Hc - ((zeta - self.ca * Hc) / self.g) ** 2
            root = (2 * self.a) * _root(disc, dd)
            Ls = dd + self.a**2 - root * _SIGNS  # front (-), back (+)
            cs = _cos_sin(self.trig, Ls - c[0, 3], _PAIR)
        else:
            flat_z, flat_d = zeta[:, 0, 0], dd[:, 0, 0]
            if self.prismatic:
                coeffs = pieper.slide_coefficients(
                    self.a, self.g, self.ca, self.coef[:, 3], self.coef[:, 2], flat_z, flat_d
                )
                q3 = pieper.slide_roots(coeffs)[:, None, :]
                return q3, self._values(q3), None
            X0 = flat_d - self.a**2 - c[0, 3]
            Y0 = flat_z - self.ca * c[0, 2]
            terms = np.stack([X0 * X0, X0, Y0 * Y0, Y0, np.ones_like(X0)], axis=-1)
            q3, selfmotion = pieper.revolute_roots(terms @ self._fourier / self.scale**4)
            q3 = q3[:, None, :]
            cs = np.empty((*q3.shape, 2))
            cs[..., 0], cs[..., 1] = np.cos(q3), np.sin(q3)
            return q3, rowmul(cs, c[1:]) + c[0], selfmotion
        return np.arctan2(cs[..., 1], cs[..., 0]), rowmul(cs, c[1:]) + c[0], None

    def gap(self, ct: FloatArray) -> FloatArray:
        """Lower bound of the distance of points ``ct (N, 3)`` to those reachable.

        Every reachable point lies in the shell ``r_lo <= |x - p1| <= r_hi``
        (triangle inequality on ``x - p1 = δ + R2 u`` with ``umin <= |u| <=
        umax``) and, with axes 1 and 2 parallel, in the slab of heights
        ``z_lo <= h1ᵀ(x - p1) <= z_hi``. The distance to shell and slab bounds
        the distance to the reachable set from below (0 inside them).
        """
        d = ct - self.p1
        r, z = np.linalg.norm(d, axis=-1), d @ self.h1
        r_lo, r_hi, z_lo, z_hi = self.shell
        return np.maximum.reduce([r - r_hi, r_lo - r, z - z_hi, z_lo - z, np.zeros_like(r)])


#: The ± of the two roots of a pair along the last slot axis, and of the
#: shoulder (or elbow) sign along the one before.
_PAIR = np.array([1.0, -1.0])
_SIGNS = np.array([[1.0], [-1.0]])


def _root(x: FloatArray, size: FloatArray | float) -> FloatArray:
    """Square root of ``x``; NaN where ``x`` is negative beyond round-off of ``size``.

    ``max(x, min(0, x + tol))`` is ``max(x, 0)`` when ``x >= -tol`` and stays
    negative (so its root is NaN) below: three cheap ufuncs, no ``where``.
    """
    return np.sqrt(np.maximum(x, np.minimum(0.0, x + 2 * TRIG_TOL * size)))


def _cos_sin(ab: FloatArray, rhs: FloatArray, signs: FloatArray) -> FloatArray:
    """``(cos θ, sin θ)`` (new last axis) of the solutions of ``a cos θ + b sin θ = rhs``.

    ``cos θ = (a rhs - b s) / r²``, ``sin θ = (b rhs + a s) / r²`` with
    ``r² = a² + b²`` and ``s = ±sqrt(r² - rhs²)``, the sign taken from
    ``signs`` (broadcast against ``rhs``): the solutions and tolerance of
    :func:`~kinematica.ik.analytic.subproblems.solve_trig_linear`, without an
    ``atan2`` then ``cos``. NaN where there is no solution.

    Args:
        ab: ``(3, 2)`` from :func:`_trig_rows`: ``[a, b] / r²``, ``[-b, a] / r²``, ``[r², 0]``.
        rhs: Right-hand sides.
        signs: Sign of the root per slot.
    """
    r2 = ab[2, 0]
    s = _root(r2 - rhs * rhs, r2) * signs
    return rhs[..., None] * ab[0] + s[..., None] * ab[1]


def _trig_rows(ab: FloatArray, unused: bool) -> FloatArray:
    """The constants of :func:`_cos_sin` for ``a cos θ + b sin θ`` (NaN if ``unused``)."""
    a, b = float(ab[0]), float(ab[1])
    r2 = a * a + b * b
    if unused or r2 == 0.0:
        return np.full((3, 2), np.nan)
    return np.array([[a / r2, b / r2], [-b / r2, a / r2], [r2, 0.0]])


def _labels(kind: str, prismatic: bool, parallel23: bool) -> tuple[str, ...]:
    if kind == "meet" and parallel23:
        return (
            "shoulder right, elbow up",
            "shoulder right, elbow down",
            "shoulder left, elbow up",
            "shoulder left, elbow down",
        )
    if kind == "general" and parallel23:
        return (
            "shoulder front, elbow up",
            "shoulder front, elbow down",
            "shoulder back, elbow up",
            "shoulder back, elbow down",
        )
    if kind == "meet":
        second = ("slide out", "slide in") if prismatic else ("elbow branch 1", "elbow branch 2")
        return tuple(f"shoulder {s}, {e}" for s in ("right", "left") for e in second)
    return tuple(f"position {k}" for k in range(1, 5))
