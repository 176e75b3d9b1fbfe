"""3R elbow arms, anthropomorphic or with a shoulder offset: their closed form, built once per arm.

Axis 1 perpendicular to axes 2 and 3, which are parallel; the solver is
``cpp/include/kinematica/solvers/elbow.hpp`` (:class:`kinematica._core.elbow.ElbowParams`).
Everything is read from the joint axes at q = 0 and ``M = fk(0)``: any base, tool,
offsets and DH convention.

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

from kinematica import _core
from kinematica.core import Chain
from kinematica.dh.lines import cross3, normal_feet
from kinematica.ik.analytic.planar_arms import plane_basis
from kinematica.ik.analytic.small_samples import sampler
from kinematica.ik.registry import ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features

__all__ = ["LABELS", "SPECS", "build"]

FloatArray = NDArray[np.float64]

#: Branch labels of the four candidate slots.
LABELS = (
    "shoulder right, elbow up",
    "shoulder right, elbow down",
    "shoulder left, elbow up",
    "shoulder left, elbow down",
)


def build(chain: Chain, features: Features, target: TargetKind) -> ClosedForm | None:
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
    M = chain.fk(np.zeros(3))[0]
    R_M, x = M[:3, :3], M[:3, 3]
    h1 = h[0] / np.linalg.norm(h[0])
    k = h[1] / np.linalg.norm(h[1])
    e1, e2 = plane_basis(k)

    def plane(v: FloatArray) -> FloatArray:
        return np.array([v @ e1, v @ e2])

    a, b = plane(p[2] - p[1]), plane(x - p[2])
    if min(np.linalg.norm(a), np.linalg.norm(b)) <= features.length_tol:
        return None  # a link that moves nothing, or coinciding axes: degenerate
    hk = cross3(h1, k)
    foot1, foot2 = normal_feet(h1, p[0], k, p[1])
    # The tool turns about axis 3 on a circle (centre c3, radius rho3); its
    # distance from foot2 (on axis 2, which turns about itself) spans [rmin, rmax].
    c3 = p[2] + ((x - p[2]) @ k) * k
    rho3 = float(np.linalg.norm(x - c3))
    dh = float(k @ (foot2 - c3))
    dr = float(np.linalg.norm(foot2 - c3 - dh * k))
    offset = float(np.linalg.norm(foot2 - foot1))
    height = float(k @ (x - p[0]))
    params = _core.elbow.ElbowParams()
    params.pose = target == "pose"
    params.h1 = h1
    params.p1 = p[0]
    params.k = k
    params.e1 = e1
    params.e2 = e2
    params.hk = hk
    params.p2 = p[1]
    params.a = a
    params.b = b
    params.up = plane(hk)
    params.s2 = 1.0  # k is axis 2's own direction
    params.s3 = 1.0 if float(h[2] @ k) > 0.0 else -1.0
    params.height = height
    params.rk = R_M.T @ k
    params.re1 = R_M.T @ e1
    params.foot = foot1
    params.offset = offset
    params.rmin = float(np.hypot(dh, abs(dr - rho3)))
    params.rmax = float(np.hypot(dh, dr + rho3))
    params.scale = float(np.linalg.norm(a) + np.linalg.norm(b)) + abs(height) + offset
    # Axis 3 is parallel to axis 2 within the classification's tolerance: a turn
    # about it moves the tool (within `length`) by at most 2 δ length off the ideal.
    length = float(sum(np.linalg.norm(np.diff(np.vstack([p, x]), axis=0), axis=1)))
    params.slack = 2.0 * float(np.linalg.norm(cross3(h[2], k))) * length
    return ClosedForm(
        name=kind,
        labels=LABELS,
        params=params,
        position_only=target == "position",
    )


def _elbow(f: Features) -> bool:
    return f.joint_types == "RRR" and f.is_parallel(1, 2) and f.is_perpendicular(0, 1)


SPECS: tuple[SolverSpec, ...] = (
    SolverSpec(
        "anthropomorphic-3R",
        "3R anthropomorphic (shoulder axes meet)",
        "brazo antropomórfico 3R (los ejes del hombro se cortan)",
        lambda f: _elbow(f) and f.meet(0, 1),
        build,
        sampler("anthropomorphic-3R"),
        ("pose", "position"),
        derivation="elbow-3R",
        geometric="arm-plane",
        singular=frozenset({"shoulder", "elbow"}),
    ),
    SolverSpec(
        "elbow-3R",
        "3R elbow arm with shoulder offset",
        "brazo 3R de codo con desplazamiento en el hombro",
        lambda f: _elbow(f) and not f.meet(0, 1),
        build,
        sampler("elbow-3R"),
        ("pose", "position"),
        derivation="elbow-3R",
        geometric="arm-plane",
        singular=frozenset({"shoulder", "elbow"}),
    ),
)
