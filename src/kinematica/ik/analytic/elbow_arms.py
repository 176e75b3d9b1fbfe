"""3R elbow arms, anthropomorphic or with a shoulder offset: their closed form, built once per arm.

Axis 1 perpendicular to axes 2 and 3, which are parallel; the kernel is
:mod:`kinematica.kernels.solvers.elbow_arms`. Everything is read from the joint
axes at q = 0 and ``M = fk(0)``: any base, tool, offsets and DH convention.

Branch labels (``σ = (p − p1)·(h1 × k1)`` with ``k1`` the current axis-2
direction, ψ the angle of link 3 relative to link 2 about ``k1``):

* ``"shoulder right"``: σ >= 0, the target lies on the ``h1 × k1`` side of
  axis 1. For an arm whose axes 1 and 2 meet this is Lee and Ziegler's right
  arm (a positive joint-2 rotation raises the wrist along h1); for the lecture notes'
  arm, ``q1 = atan2(py, px)``. ``"shoulder left"``: σ <= 0.
* ``"elbow up"``: in the arm's plane, the elbow (axis 3) lies on the side of
  the line from the shoulder (axis 2) to the target toward which ``h1``
  points (ψ has the sign of ``-(p - s)·(h1 × k1)``, ψ <= 0 when that is 0);
  ``"elbow down"``.

A pose target has one solution (in the slot of its branch); a position
target up to four.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from kinematica.dh import DHChain
from kinematica.ik.analytic.planar_arms import LENGTH_TOL, plane_basis
from kinematica.ik.registry import ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features
from kinematica.kernels import fk
from kinematica.kernels.solvers import elbow_arms as kernel
from kinematica.kernels.solvers.elbow_arms import (
    P_A,
    P_B,
    P_E1,
    P_E2,
    P_FOOT,
    P_H1,
    P_HEIGHT,
    P_HK,
    P_K,
    P_OFFSET,
    P_P1,
    P_P2,
    P_POSE,
    P_RE1,
    P_RK,
    P_RMAX,
    P_RMIN,
    P_S2,
    P_S3,
    P_SCALE,
    P_SIZE,
    P_SLACK,
    P_UP,
)

__all__ = ["LABELS", "SPECS", "build", "common_normal"]

FloatArray = NDArray[np.float64]

#: Branch labels of the four candidate slots.
LABELS = (
    "shoulder right, elbow up",
    "shoulder right, elbow down",
    "shoulder left, elbow up",
    "shoulder left, elbow down",
)


def common_normal(
    h1: FloatArray, p1: FloatArray, h2: FloatArray, p2: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """The feet ``(3,), (3,)`` on two non-parallel lines ``p + t h`` of their common normal."""
    A = np.stack([h1, -h2, np.cross(h1, h2)], axis=1)
    t = np.linalg.solve(A, p2 - p1)
    return p1 + t[0] * h1, p2 + t[1] * h2


def build(chain: DHChain, features: Features, target: TargetKind) -> ClosedForm | None:
    """The closed form of a 3R elbow arm, or None when a link is degenerate.

    Args:
        chain: The arm.
        features: Its joint axes at q = 0 (anthropomorphic-3R or elbow-3R).
        target: ``"pose"`` or ``"position"`` targets.
    """
    kind = next((s.kind for s in SPECS if s.handles(features)), None)
    if kind is None:
        return None
    h, p = features.directions, features.points
    M = fk(chain, np.zeros(3))[0]
    R_M, x = M[:3, :3], M[:3, 3]
    h1 = h[0] / np.linalg.norm(h[0])
    k = h[1] / np.linalg.norm(h[1])
    e1, e2 = plane_basis(k)

    def plane(v: FloatArray) -> FloatArray:
        return np.array([v @ e1, v @ e2])

    a, b = plane(p[2] - p[1]), plane(x - p[2])
    if min(np.linalg.norm(a), np.linalg.norm(b)) <= LENGTH_TOL:
        return None
    hk = np.cross(h1, k)
    foot1, foot2 = common_normal(h1, p[0], k, p[1])
    # The tool turns about axis 3 on a circle (centre c3, radius rho3); its
    # distance from foot2 (on axis 2, which turns about itself) spans [rmin, rmax].
    c3 = p[2] + ((x - p[2]) @ k) * k
    rho3 = float(np.linalg.norm(x - c3))
    dh = float(k @ (foot2 - c3))
    dr = float(np.linalg.norm(foot2 - c3 - dh * k))
    offset = float(np.linalg.norm(foot2 - foot1))
    height = float(k @ (x - p[0]))
    params = np.zeros(P_SIZE)
    params[P_POSE] = float(target == "pose")
    params[P_H1 : P_H1 + 3] = h1
    params[P_P1 : P_P1 + 3] = p[0]
    params[P_K : P_K + 3] = k
    params[P_E1 : P_E1 + 3] = e1
    params[P_E2 : P_E2 + 3] = e2
    params[P_HK : P_HK + 3] = hk
    params[P_P2 : P_P2 + 3] = p[1]
    params[P_A : P_A + 2] = a
    params[P_B : P_B + 2] = b
    params[P_UP : P_UP + 2] = plane(hk)
    params[P_S2] = 1.0  # k is axis 2's own direction
    params[P_S3] = 1.0 if float(h[2] @ k) > 0.0 else -1.0
    params[P_HEIGHT] = height
    params[P_RK : P_RK + 3] = R_M.T @ k
    params[P_RE1 : P_RE1 + 3] = R_M.T @ e1
    params[P_FOOT : P_FOOT + 3] = foot1
    params[P_OFFSET] = offset
    params[P_RMIN] = float(np.hypot(dh, abs(dr - rho3)))
    params[P_RMAX] = float(np.hypot(dh, dr + rho3))
    params[P_SCALE] = float(np.linalg.norm(a) + np.linalg.norm(b)) + abs(height) + offset
    # Axis 3 is parallel to axis 2 within the classification's tolerance: a turn
    # about it moves the tool (within `length`) by at most 2 δ length off the ideal.
    length = float(sum(np.linalg.norm(np.diff(np.vstack([p, x]), axis=0), axis=1)))
    params[P_SLACK] = 2.0 * float(np.linalg.norm(np.cross(h[2], k))) * length
    params.flags.writeable = False
    return ClosedForm(
        name=kind,
        labels=LABELS,
        params=params,
        solve_one=kernel.solve,
        solve_batch=kernel.solve_batch,
        position_only=target == "position",
    )


def _elbow(f: Features) -> bool:
    return f.joint_types == "RRR" and f.is_parallel(1, 2) and f.is_perpendicular(0, 1)


SPECS: tuple[SolverSpec, ...] = (
    SolverSpec(
        "anthropomorphic-3R",
        "3R anthropomorphic (shoulder axes meet)",
        lambda f: _elbow(f) and f.meet(0, 1),
        build,
    ),
    SolverSpec(
        "elbow-3R",
        "3R elbow arm with shoulder offset",
        lambda f: _elbow(f) and not f.meet(0, 1),
        build,
    ),
)
