"""The first or last joint held at a value: the targets moved, not the arm rebuilt.

The first joint's value only turns (or slides) the base, the last's only the
tool: the arm locked at 0 serves every value, each target moved instead
(``T' = G₀ M(v)⁻¹ G₀⁻¹ T`` for the first joint, ``T G⁻¹ M(v)⁻¹ G`` for the last,
``G₀`` the chain's start, ``G`` its last fixed part times the tool). The first
joint's move keeps distances and angles: the same problem. The last joint's
moves the tool point, so the locked arm is checked against a narrower position
tolerance (:func:`narrowed_tolerance`).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from kinematica.core import Chain
from kinematica.ik.tolerance import parse_tolerance

__all__ = [
    "NARROWEST",
    "ON_AXIS_TOL",
    "base_move",
    "end_arm",
    "moved_targets",
    "narrowed_tolerance",
    "on_axis",
]

FloatArray = NDArray[np.float64]

#: The least share of the position tolerance a target moved past the last joint may
#: be held to (:func:`narrowed_tolerance`); below it (with equal position and rotation
#: tolerances: the tool point moved by more than 0.5 m) the targets are solved on one
#: locked arm per value instead.
NARROWEST = 0.5
#: How far from the last joint's axis the tool point may lie (m) for the last joint's
#: value to move the target without moving the tool point (:func:`on_axis`): round-off
#: of a tool transform read from a file.
ON_AXIS_TOL = 1e-12


def end_arm(chain: Chain, k: int) -> tuple[Chain, FloatArray, FloatArray]:
    """The first (k = 0) or last joint locked at 0, once per chain, and ``(G, G⁻¹)``.

    ``G``: the chain's start (k = 0), or its last fixed part times the tool.
    """
    per: dict[int, tuple[Chain, FloatArray, FloatArray]]
    per = chain.memo.setdefault("end arms", {})  # type: ignore[assignment]
    found = per.get(k)
    if found is None:
        G = chain.start if k == 0 else chain.fixed_parts[-1] @ chain.tool
        G_inv = np.eye(4)
        G_inv[:3, :3] = G[:3, :3].T
        G_inv[:3, 3] = -G[:3, :3].T @ G[:3, 3]
        found = per[k] = (chain.locked(k, 0.0), np.array(G), G_inv)
    return found


def on_axis(chain: Chain) -> bool:
    """Whether the last joint turns about an axis through the tool point.

    Then ``T G⁻¹ M(v)⁻¹ G`` keeps the target's position (``G``'s translation is on the
    axis ``M`` turns about): a target moved past the last joint is the same problem,
    checked against the same tolerance, whatever the value (:data:`ON_AXIS_TOL`).
    """
    found = chain.memo.get("tool on last axis")
    if found is None:
        G = chain.fixed_parts[-1] @ chain.tool
        found = chain.memo["tool on last axis"] = not bool(chain.prismatic[-1]) and bool(
            math.hypot(G[0, 3], G[1, 3]) <= ON_AXIS_TOL
        )
    return bool(found)


def _inverse_motion(prismatic: bool, value: float) -> FloatArray:
    """``(4, 4)`` ``M(value)⁻¹ = M(-value)``: a joint's motion undone (``Rz`` or ``Tz``)."""
    M = np.eye(4)
    if prismatic:
        M[2, 3] = -value
    else:
        cos, sin = math.cos(value), math.sin(value)
        M[0, 0] = M[1, 1] = cos
        M[0, 1], M[1, 0] = sin, -sin
    return M


def base_move(prismatic: bool, G: FloatArray, G_inv: FloatArray, value: float) -> FloatArray:
    """``(4, 4)`` ``G₀ M(value)⁻¹ G₀⁻¹``: a target times it is the arm locked at 0's target.

    What :func:`moved_targets` puts before one target when the first joint is held
    at ``value`` (``G``: the chain's start, ``G_inv`` its inverse), for a caller
    that moves many targets by one value.
    """
    return G @ _inverse_motion(prismatic, value) @ G_inv


def moved_targets(
    prismatic: bool, k: int, G: FloatArray, G_inv: FloatArray, poses: FloatArray, v: FloatArray
) -> FloatArray:
    """``(N, 4, 4)`` targets of the arm locked at 0 that are ``poses`` with joint k at ``v``."""
    if v.size == 1:  # one target: 4x4 products
        if k == 0:
            return (base_move(prismatic, G, G_inv, float(v[0])) @ poses[0])[None]
        return (poses[0] @ G_inv @ _inverse_motion(prismatic, float(v[0])) @ G)[None]
    inverse = np.zeros((v.size, 4, 4))  # M(v)⁻¹ = M(-v), one per target
    inverse[:, 3, 3] = 1.0
    if prismatic:
        inverse[:, 0, 0] = inverse[:, 1, 1] = inverse[:, 2, 2] = 1.0
        inverse[:, 2, 3] = -v
    else:
        c, s = np.cos(v), np.sin(v)
        inverse[:, 0, 0] = inverse[:, 1, 1] = c
        inverse[:, 0, 1], inverse[:, 1, 0] = s, -s
        inverse[:, 2, 2] = 1.0
    if k == 0:
        return np.ascontiguousarray(G @ (inverse @ (G_inv @ poses)))
    return np.ascontiguousarray(((poses @ G_inv) @ inverse) @ G)


def narrowed_tolerance(
    tol: object, prismatic: bool, k: int, G: FloatArray, G_inv: FloatArray, v: FloatArray
) -> tuple[float, float] | None:
    """The position tolerance a target moved past the last joint is held to, or None.

    The arm's pose is ``F = L Y⁻¹`` for the locked arm's ``L`` checked against
    ``T Y``: its position error is at most the locked arm's plus its rotation error
    times ``|t_Y|`` (``(I - R) x`` is at most ``θ |x|``), so ``P - R max|t_Y|``
    keeps every accepted solution within ``P`` of the real target. None when that
    leaves less than :data:`NARROWEST` of ``P`` (solve those targets as they are).

    Args:
        tol: The tolerance as ``robot.ik`` takes it (None: the defaults).
        prismatic: The last joint slides.
        k: Its index.
        G: ``(4, 4)`` its last fixed part times the tool; ``G_inv`` its inverse.
        G_inv: See ``G``.
        v: ``(N,)`` the values the targets are moved by.

    Returns:
        ``(position m, rotation rad)``, or None.
    """
    given = parse_tolerance(tol)  # type: ignore[arg-type]
    Y = moved_targets(prismatic, k, G, G_inv, np.broadcast_to(np.eye(4), (v.size, 4, 4)), v)
    shift = float(np.linalg.norm(Y[:, :3, 3], axis=1).max())
    position = given.position - given.rotation * shift
    return (position, given.rotation) if position >= NARROWEST * given.position else None
