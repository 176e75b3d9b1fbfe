"""The geometric method of seed 000: the position from trigonometry, checked against DH.

Planar arms (every revolute axis parallel): each segment of the arm (from one
joint to the next, and to the tool) is rigid; the revolute joints before it
turn it about the common axis by the sum of their angles, and a prismatic
joint stretches it along its axis. So ``p = O + Σ Rot(k, φi) · si⁰`` with
``φi = ±q1 ± ... ± qi`` and ``si⁰`` the segment with every revolute joint at 0.

3R arms whose axis 2 is normal to axis 1 (seed 000, example 2): the arm is a
planar 2R in its own plane (distance ``r`` from axis 1 and height ``h``), and
that plane turns about axis 1 by ``q1``.

Either way the result is derived without the DH product and then compared
with it symbolically: the report says whether both agree.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from kinematica.robot import classify
from kinematica.symbolic.kinematics import factors
from kinematica.symbolic.model import SymbolicRobot, rot
from kinematica.symbolic.notation import tidy

__all__ = ["GeometricDerivation", "derive_geometric"]


@dataclass(frozen=True)
class GeometricDerivation:
    """The position by the geometric method.

    Attributes:
        kind: ``"planar"`` or ``"arm-plane"`` (a planar 2R turned about axis 1).
        segments: ``(angle, vector)`` of each rigid segment, base to tool
            (world frame); for ``"arm-plane"``, those of the arm's own plane.
        extra: Named intermediate quantities shown in the report (``r``, ``h``).
        position: ``(3, 1)`` the position so derived.
        agrees: Whether it equals the DH position symbolically.
    """

    kind: str
    segments: tuple[tuple[sp.Expr, sp.Matrix], ...]
    extra: tuple[tuple[sp.Symbol, sp.Expr], ...]
    position: sp.Matrix
    agrees: bool


def _rodrigues(k: sp.Matrix, angle: sp.Expr) -> sp.Matrix:
    K = sp.Matrix([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return sp.eye(3) + sp.sin(angle) * K + (1 - sp.cos(angle)) * K * K


def _chain(model: SymbolicRobot) -> tuple[list[sp.Matrix], list[int]]:
    """Matrices base, factors..., tool; and after which index each joint's origin point is."""
    mats: list[sp.Matrix] = [sp.Matrix(model.base)]
    axis_at: list[int] = []
    for i in range(1, model.dof + 1):
        for f in factors(model, i):
            if f.kind == "Rot" and f.axis == "z":
                axis_at.append(len(mats))
            mats.append(f.matrix)
    mats.append(sp.Matrix(model.tool))
    return mats, axis_at


def _prefix(mats: list[sp.Matrix], k: int) -> sp.Matrix:
    out = sp.eye(4)
    for M in mats[:k]:
        out = out * M
    return out


def _segments(
    model: SymbolicRobot, mats: list[sp.Matrix], axis_at: list[int], joints: list[int], k: sp.Matrix
) -> list[tuple[sp.Expr, sp.Matrix]]:
    """Rigid segments between consecutive joint points, turned by the joints before them."""
    points = [_prefix(mats, a)[:3, 3] for a in axis_at] + [_prefix(mats, len(mats))[:3, 3]]
    revolute = [model.rows[j - 1].q for j in joints if model.rows[j - 1].kind == "R"]
    zero = {q: 0 for q in revolute}
    out = []
    for i in range(1, len(points)):
        seg = tidy(points[i] - points[i - 1])
        angle = sp.Integer(0)
        for j in joints[:i]:
            row = model.rows[j - 1]
            if row.kind == "R":
                axis = tidy(_prefix(mats, axis_at[j - 1])[:3, 2].xreplace(zero))
                angle += sp.sign(tidy((axis.T * k)[0])) * row.q
        out.append((angle, tidy(seg.xreplace(zero))))
    return out


def _planar(model: SymbolicRobot) -> GeometricDerivation:
    mats, axis_at = _chain(model)
    joints = list(range(1, model.dof + 1))
    first = next(j for j in joints if model.rows[j - 1].kind == "R")
    zero = {row.q: 0 for row in model.rows}
    k = tidy(_prefix(mats, axis_at[first - 1])[:3, 2].xreplace(zero))
    segs = _segments(model, mats, axis_at, joints, k)
    origin = tidy(_prefix(mats, axis_at[0])[:3, 3])
    p = origin + sum((_rodrigues(k, a) * s for a, s in segs), sp.zeros(3, 1))
    p = tidy(p)
    dh = tidy(_prefix(mats, len(mats))[:3, 3])
    agrees = tidy(sp.expand(p - dh)) == sp.zeros(3, 1)
    return GeometricDerivation("planar", tuple(segs), (), p, bool(agrees))


def _arm_plane(model: SymbolicRobot) -> GeometricDerivation | None:
    mats, axis_at = _chain(model)
    i1, i2 = axis_at[0], axis_at[1]
    C = _prefix(mats[i1 + 1 :], i2 - i1 - 1)
    u2 = tidy(C[:3, 2])
    if u2.free_symbols or u2[2] != 0:
        return None
    W = tidy(_prefix(mats[i1 + 1 :], len(mats))[:3, 3])
    beta = sp.atan2(u2[1], u2[0])
    perp = sp.Matrix([-sp.sin(beta), sp.cos(beta), 0])
    e = tidy(sp.expand((u2.T * W)[0]))
    r_expr = tidy(sp.expand((perp.T * W)[0]))
    h_expr = W[2]
    r, h = sp.symbols("r h")
    J = _prefix(mats, i1)
    theta1 = model.rows[0].theta
    local = e * u2 + r * perp + h * sp.Matrix([0, 0, 1])
    p_rh = tidy(J[:3, :3] * rot("z", theta1)[:3, :3] * local + J[:3, 3])
    p = tidy(sp.expand(p_rh.xreplace({r: r_expr, h: h_expr})))
    dh = tidy(_prefix(mats, len(mats))[:3, 3])
    agrees = tidy(sp.expand(p - dh)) == sp.zeros(3, 1)
    extra = ((r, r_expr), (h, h_expr))
    return GeometricDerivation("arm-plane", (), extra, p_rh, bool(agrees))


def derive_geometric(model: SymbolicRobot) -> GeometricDerivation | None:
    """The position by the geometric method, for planar arms and 3R arms; else ``None``."""
    spec = classify(model.robot).spec
    recipe = spec.geometric if spec is not None else None
    if recipe == "planar":
        return _planar(model)
    if recipe == "arm-plane":
        return _arm_plane(model)
    return None
