"""The geometric Jacobian in sympy, from the joint axes of the symbolic frames.

Column i is ``[z × (p − o); z]`` for a revolute joint, ``[z; 0]`` for a prismatic
one, with ``p`` the tool origin and ``z``, ``o`` the axis of joint i and a point
on it, all in the world (base) frame: the same as ``robot.jacobian(q)``. The
top half is also ``∂p/∂q_i``, the form the textbook result uses. The axis of
joint i is the z axis of DH frame i−1 in the standard convention (its
``Rot(z, θi)`` comes first in row i) and of frame i in the modified one (row i
ends with ``Rot(z, θi) · Tras(z, di)``, so frame i's origin is on the axis too).
"""

from __future__ import annotations

import sympy as sp

from kinematica.symbolic.kinematics import link_matrices
from kinematica.symbolic.model import RobotLike, symbolic_robot
from kinematica.symbolic.notation import tidy

__all__ = ["jacobian"]


def jacobian(robot: RobotLike, simplify: bool = True) -> sp.Matrix:
    """The geometric Jacobian ``J(q)`` of the tool, base frame, as a sympy matrix.

    Args:
        robot: A ``Robot``, built-in name, robot-file path or ``SymbolicRobot``.
        simplify: Tidy every entry into textbook form (``True``), or keep the
            plain products (``False``: much faster for long general chains; the
            same function of q).

    Returns:
        ``(6, n)`` sympy matrix in ``q1 ... qn``: rows ``vx, vy, vz`` (m per rad
        or m per m), then ``ωx, ωy, ωz``.
    """
    model = symbolic_robot(robot)
    prefix = [sp.Matrix(model.base)]  # base · 0A1 ··· (k-1)Ak, no tool
    for A in link_matrices(model):
        prefix.append(tidy(prefix[-1] * A) if simplify else prefix[-1] * A)
    p = (prefix[-1] * sp.Matrix(model.tool))[:3, 3]
    columns = []
    for i, row in enumerate(model.rows):
        F = prefix[i] if model.convention == "standard" else prefix[i + 1]
        z, o = F[:3, 2], F[:3, 3]
        if row.kind == "P":
            columns.append(sp.Matrix.vstack(z, sp.zeros(3, 1)))
        else:
            columns.append(sp.Matrix.vstack(z.cross(p - o), z))
    J = sp.Matrix.hstack(*columns)
    if not simplify:
        return J
    # The position rows are also ∂p/∂q (the tool origin's velocity): the derivative of
    # p's textbook form folds better than the cross products, whose c1² + s1² stay.
    J[:3, :] = tidy(sp.Matrix(p).jacobian(list(model.q)), fold=False)
    return tidy(J, fold=False)
