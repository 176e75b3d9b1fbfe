"""Planar 2R, 3R, PR and PRR arms and the SCARA: their closed form, built once per arm.

Everything is read from the joint axes at q = 0 and the tool pose ``M =
fk(0)``, so any base, tool, offsets and DH convention are handled alike; the
solver is ``cpp/include/kinematica/solvers/planar.hpp``
(:class:`kinematica._core.planar.PlanarParams`).

Branch labels (angles about ``k``, the first revolute axis's direction, seen
from the side it points to: positive turns are counter-clockwise):

* planar 2R and 3R: ``"elbow up"``, ``"elbow down"``. Elbow up: the elbow lies
  to the left of the line from the shoulder (axis 1) to the wrist (the tool
  origin of a 2R arm, axis 3 of a 3R arm), i.e. link 2 is turned clockwise
  from link 1 (relative angle ψ in [-π, 0]); drawn with the target to the
  right of the shoulder, the elbow is above the line.
* SCARA: ``"right-handed"`` (ψ in [0, π]: the elbow to the right of the
  shoulder-wrist line, as a right arm seen from above) and ``"left-handed"``.
* planar PR and PRR: ``"link forward"`` (the revolute link points along the
  slide direction, the lecture notes' ``q2A = asin(y/l2)``) and ``"link backward"``
  (``q2B = π - asin(y/l2)``).

For position targets of the 3R, PRR and SCARA arms the last revolute joint is
free and the labels describe the representatives.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from kinematica import _core
from kinematica.core import Chain
from kinematica.dh.lines import cross3
from kinematica.ik.analytic.small_samples import sampler
from kinematica.ik.registry import ClosedForm, SolverSpec, TargetKind
from kinematica.ik.structure import Features

__all__ = ["LABELS", "SPECS", "build", "plane_basis"]

FloatArray = NDArray[np.float64]

#: Branch labels of the candidate slots, per kind.
LABELS: dict[str, tuple[str, str]] = {
    "planar-2R": ("elbow up", "elbow down"),
    "planar-3R": ("elbow up", "elbow down"),
    "scara": ("right-handed", "left-handed"),
    "planar-PR": ("link forward", "link backward"),
    "planar-PRR": ("link forward", "link backward"),
}


def plane_basis(k: FloatArray) -> tuple[FloatArray, FloatArray]:
    """A unit basis ``e1, e2 = k × e1`` of the plane normal to the unit vector ``k``."""
    e1 = cross3(k, np.eye(3)[int(np.argmin(np.abs(k)))])
    e1 /= np.linalg.norm(e1)
    return e1, cross3(k, e1)


def _sign(v: float) -> float:
    return 1.0 if v > 0.0 else -1.0


def _kind_of(features: Features) -> str | None:
    for spec in SPECS:
        if spec.handles(features):
            return spec.kind
    return None


def build(chain: Chain, features: Features, target: TargetKind) -> ClosedForm | None:
    """The closed form of a planar arm or a SCARA, or None for degenerate links.

    Args:
        chain: The arm.
        features: Its joint axes at q = 0 (one of the planar kinds or SCARA).
        target: ``"pose"`` or ``"position"`` targets.
    """
    kind = _kind_of(features)
    if kind is None:
        return None
    types = features.joint_types
    h, p = features.directions, features.points
    M = chain.fk(np.zeros(chain.dof))[0]
    R_M, t_M = M[:3, :3], M[:3, 3]
    rev = [i for i, t in enumerate(types) if t == "R"]
    slide = 0 if types[0] == "P" else -1
    lift = types.index("P") if kind == "scara" else -1
    k = h[rev[0]] / np.linalg.norm(h[rev[0]])
    e1, e2 = plane_basis(k)
    origin = p[rev[0]]

    def plane(x: FloatArray) -> FloatArray:
        return np.array([(x - origin) @ e1, (x - origin) @ e2])

    axis = np.array([plane(p[j]) for j in rev])
    tip = plane(t_M)
    links = [*np.diff(axis, axis=0), tip - axis[-1]]  # in-plane links after the first axis
    lengths = [float(np.linalg.norm(v)) for v in links]
    needed = lengths if kind in ("planar-2R", "planar-PR") else lengths[:-1]
    # a link within the line geometry's length tolerance makes the arm degenerate (a
    # joint that moves nothing, or two coinciding axes): the numeric method takes it
    if min(needed, default=math.inf) <= features.length_tol:
        return None
    params = _core.planar.PlanarParams()
    params.n = chain.dof
    params.pose = target == "pose"
    params.swap = kind == "scara"
    params.slide = slide
    params.lift = lift
    if lift >= 0:
        params.lift_sign = _sign(float(h[lift] @ k))
    params.nrev = len(rev)
    params.rev = np.array([*rev, 0, 0][:3])  # the fixed arrays' unused entries: 0
    params.sign = np.array([*(_sign(float(h[j] @ k)) for j in rev), 0.0, 0.0][:3])
    params.k = k
    params.e1 = e1
    params.e2 = e2
    params.origin = origin
    params.tool = t_M
    params.re1 = R_M.T @ e1
    params.wrist = R_M.T @ (p[rev[-1]] - t_M)
    params.axis = np.vstack([axis, np.zeros((3 - len(rev), 2))])
    params.tip = tip
    if slide >= 0:
        u = np.array([h[0] @ e1, h[0] @ e2])
        params.u = u / np.linalg.norm(u)
    reach = sum(lengths)
    params.reach = reach
    params.rmax = reach
    params.rmin = max(0.0, 2.0 * max(lengths) - reach)
    params.qlim = np.vstack([chain.qlim, np.zeros((4 - chain.dof, 2))])
    # How far from the ideal arm this one is (its axes parallel to k within the
    # classification's tolerance): a turn about an axis tilted by δ moves every
    # point within `length` of it by at most 2 δ length more or less.
    length = float(sum(np.linalg.norm(np.diff(np.vstack([p, t_M]), axis=0), axis=1)))
    tilts = [float(np.linalg.norm(cross3(h[j], k))) for j in rev]
    params.length = length
    params.slack = 2.0 * sum(tilts) * length
    if slide >= 0:
        params.slide_tilt = abs(float(h[slide] @ k))
    if lift >= 0:
        params.lift_tilt = float(np.linalg.norm(cross3(h[lift], k)))
    return ClosedForm(
        name=kind,
        labels=LABELS[kind],
        params=params,
        position_only=target == "position",
    )


_BOTH: tuple[TargetKind, ...] = ("pose", "position")

SPECS: tuple[SolverSpec, ...] = (
    SolverSpec(
        "planar-2R",
        "2R planar",
        "brazo plano 2R",
        lambda f: f.joint_types == "RR" and f.is_parallel(0, 1),
        build,
        sampler("planar-2R"),
        _BOTH,
        derivation="planar-2R",
        geometric="planar",
        singular=frozenset({"elbow"}),
    ),
    SolverSpec(
        "planar-PR",
        "PR planar (prismatic then revolute)",
        "brazo plano PR (prismática y rotacional)",
        lambda f: f.joint_types == "PR" and f.is_perpendicular(0, 1),
        build,
        sampler("planar-PR"),
        _BOTH,
        derivation="planar-PR",
        geometric="planar",
    ),
    SolverSpec(
        "planar-3R",
        "3R planar",
        "brazo plano 3R",
        lambda f: f.joint_types == "RRR" and f.all_parallel(range(3)),
        build,
        sampler("planar-3R"),
        _BOTH,
        derivation="planar-3R",
        geometric="planar",
        singular=frozenset({"elbow"}),
    ),
    SolverSpec(
        "planar-PRR",
        "PRR planar (prismatic then two parallel revolute)",
        "brazo plano PRR (prismática y dos rotacionales paralelas)",
        lambda f: f.joint_types == "PRR" and f.is_parallel(1, 2) and f.is_perpendicular(0, 1),
        build,
        sampler("planar-PRR"),
        _BOTH,
        derivation="planar-PRR",
        geometric="planar",
    ),
    SolverSpec(
        "scara",
        "SCARA (RRPR, all axes parallel)",
        "SCARA (RRPR, todos los ejes paralelos)",
        lambda f: f.joint_types == "RRPR" and f.all_parallel(range(4)),
        build,
        sampler("scara"),
        _BOTH,
        derivation="scara",
        geometric=None,
        singular=frozenset({"elbow"}),
    ),
)
