"""A DH table read off the joint axes of any serial chain, by the Denavit-Hartenberg rules.

Input: each joint's axis as a line in space at q = 0 (direction, and the joint's
own frame, whose origin is on the axis), the tip pose at q = 0, and the named
frames the description has before joint 1 and after joint n (a URDF's link
frames). Output: DH rows in the standard (Paul, distal) or modified (Craig,
proximal) convention, with joint offsets so that q = 0 is the same posture,
and base and tool transforms for whatever DH cannot express. The table
reproduces the chain's forward kinematics for every q: two chains with the
same joint lines and the same home pose have the same FK.

Frames, standard convention (the DH method's rules 4-9): ``S_(k-1)`` has z along
joint k's axis, in the sense of the joint's positive motion.

- ``S_0`` (rule 5: anywhere on axis 1): the maker's base frame (ROS-Industrial's
  ``base``) or the nearest frame of the description before joint 1 whose z is
  axis 1 and whose origin is on it, else the joint-1 frame if it is such a frame,
  else origin at joint 1 with x from its frame.
- ``S_k``, k = 1..n-1 (rules 6-7): skew axes: x along the common normal, origin
  at its foot on axis k+1; axes that meet: origin at the intersection,
  x = ±z_(k-1) × z_k; parallel axes: x normal to both axes, origin on axis k+1
  level with S_(k-1) (d_k = 0: the origin is free along the axis); coinciding
  axes: origin at joint k+1, x from joint k+1's frame. Where the sense of x is
  free, it follows joint k+1's own frame when that frame's x has a component
  along the normal (so a table exported and read back keeps the signs of its
  a's and α's); otherwise the sense that turns x_(k-1) onto x_k by less than 90°
  (an offset of 0 where one is possible), else the normal from axis k to axis
  k+1, or z_(k-1) × z_k. A joint frame that already is the DH frame is kept whole.
- ``S_n`` (rule 9): the nearest frame after joint n whose x is normal to axis
  n and meets it (a valid last DH frame, e.g. a flange or tool frame), else
  origin at the tip with z_n = z_(n-1) and x_n from axis n towards the tip (or
  from the tip frame when the tip is on axis n).

Modified convention (Craig): the standard frames regrouped, ``S'_k = S_(k-1)
Rot(z, θ_k) Tras(z, d_k)`` (on axis k where x_k meets it: a valid modified frame),
so that one arm has one modified table, the one ``Robot.to_convention`` writes,
unless the description's joint frames are modified DH frames and not standard
ones (e.g. Franka's), or obey both conventions' rules (all axes parallel) and the
description says they are modified ones (a URDF kinematica wrote from a modified
table: ``ChainGeometry.dh_frames``). Then by the rules, and the standard frames
are those regrouped the other way, ``S_n`` being the tip when the tip is ``S'_n
Tras(x, a) Rot(x, α)`` (the pair ``Robot.to_convention`` takes back from such a
tool). One joint whose description says nothing: each convention by its rules.
The rules:
``S_k`` has z along joint k's axis; ``S_k``'s x
lies on the common normal to axis k+1 with the origin at its foot on axis k
(same cases and choices, the joint of a parallel pair being joint k); ``S_n``
is joint n's frame made valid (origin at joint n, x from its frame); ``S_0``
is the nearest frame before joint 1 whose x is normal to axis 1 and meets it,
else the joint-1 frame if it is one, else ``S_1`` itself (Craig: a_0 = α_0 =
0, S_0 coincides with S_1 at q1 = 0).

Rules 10-13 then read θ, d, a, α between consecutive frames; ``base = S_0`` and
``tool = S_n⁻¹ · tip``. Every decision is reported as a :class:`FrameRule`.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
from numpy.typing import NDArray

from kinematica.dh.axes import AxisFrame, ChainGeometry, ExtractedTable, FrameRule, NamedFrame
from kinematica.dh.convert import ROUND_OFF_TOL, snap
from kinematica.dh.joints import (
    Convention,
    Joint,
    Prismatic,
    Revolute,
    check_convention,
    values_checked,
)
from kinematica.dh.lines import (
    cross3,
)
from kinematica.dh.link import link_matrix
from kinematica.dh.rule_frames import modified_frames, seen_from, standard_frames
from kinematica.errors import KinematicaWarning
from kinematica.spatial import matrix_from_axis_angle

__all__ = [
    "FK_CHECK_TOL",
    "ROUND_OFF_TOL",
    "AxisFrame",
    "ChainGeometry",
    "ExtractedTable",
    "FrameRule",
    "NamedFrame",
    "extract_dh",
]

FloatArray = NDArray[np.float64]

#: A KinematicaWarning is raised when the extracted table reproduces the chain's
#: forward kinematics worse than this (largest entry of T, m or unitless): only
#: nearly parallel consecutive axes, whose true common normal is far away, cause it.
FK_CHECK_TOL = 1e-9
#: Configurations the FK check compares besides q = 0: a Latin hypercube over the
#: joint limits (seeded, so one chain always gives one figure).
FK_CHECK_SAMPLES = 32


def _row(F0: FloatArray, F1: FloatArray, convention: Convention) -> tuple[float, ...]:
    """``(theta, d, a, alpha)`` between consecutive frames (the DH method's rules 10-13)."""
    x0, y0, z0, o0 = F0[:3, 0], F0[:3, 1], F0[:3, 2], F0[:3, 3]
    x1, z1, o1 = F1[:3, 0], F1[:3, 2], F1[:3, 3]
    step = o1 - o0
    if convention == "standard":  # Rot(z, θ) Tras(z, d) Tras(x, a) Rot(x, α)
        theta = math.atan2(float(x1 @ y0), float(x1 @ x0))
        alpha = math.atan2(float(z1 @ cross3(x1, z0)), float(z1 @ z0))
        return theta, float(step @ z0), float(step @ x1), alpha
    # Rot(x, α) Tras(x, a) Rot(z, θ) Tras(z, d), α and a being α(i-1), a(i-1)
    alpha = math.atan2(-float(z1 @ y0), float(z1 @ z0))
    theta = math.atan2(float(x1 @ cross3(z1, x0)), float(x1 @ x0))
    return theta, float(step @ z1), float(step @ x0), alpha


def _check_configurations(g: ChainGeometry) -> FloatArray:
    """``(1 + FK_CHECK_SAMPLES, n)``: q = 0, then a Latin hypercube over the joint ranges.

    Each joint's range is split into :data:`FK_CHECK_SAMPLES` equal strata, one value
    drawn in each and the strata shuffled joint by joint (seed 0): well spread in
    every joint, the same configurations on every call. The range is the joint's
    limits, else (-π, π) for a revolute joint and (-L, L) for a prismatic one, L
    the chain's size (1 m for a chain of no size). q = 0, the home posture the
    table was read at, comes first even when outside the limits.
    """
    n = len(g.joints)
    reach = g.size if g.size > 0.0 else 1.0
    lo = np.empty(n)
    hi = np.empty(n)
    for k, joint in enumerate(g.joints):
        free = math.pi if joint.kind == "R" else reach
        a, b = joint.qlim if joint.qlim is not None else (-free, free)
        lo[k] = a if math.isfinite(a) else -free
        hi[k] = b if math.isfinite(b) else free
    rng = np.random.default_rng(0)
    strata = np.argsort(rng.random((FK_CHECK_SAMPLES, n)), axis=0)  # a permutation per joint
    u = (strata + rng.random((FK_CHECK_SAMPLES, n))) / FK_CHECK_SAMPLES
    return np.vstack([np.zeros(n), lo + u * (hi - lo)])


def _fk_error(
    g: ChainGeometry, rows: tuple[Joint, ...], conv: Convention, base: FloatArray, tool: FloatArray
) -> float:
    """How far the table's FK is from the chain's: the largest difference of any entry of T.

    ``T`` is the tool pose in the chain's base frame (rotation entries unitless,
    translation entries in metres, the largest of either), compared at the
    configurations of :func:`_check_configurations`. The chain's FK is its own
    product of exponentials, ``exp(q1 ξ1) ... exp(qn ξn) · tip``, about the joint
    axes exactly as ``g`` gives them (the loaded chain, to round-off), not about
    the lines the rules idealised (axes taken as parallel or meeting).
    """
    q = _check_configurations(g)
    m, n = q.shape
    prismatic = np.array([j.kind == "P" for j in g.joints])
    h = np.array([j.direction for j in g.joints])
    p = np.array([j.frame[:3, 3] for j in g.joints])
    theta = np.where(prismatic, [r.theta for r in rows], q + [r.theta for r in rows])
    d = np.where(prismatic, q + [r.d for r in rows], [r.d for r in rows])
    a = np.broadcast_to([r.a for r in rows], q.shape)
    alpha = np.broadcast_to([r.alpha for r in rows], q.shape)
    A = link_matrix(theta, d, a, alpha, conv)
    R = matrix_from_axis_angle(np.broadcast_to(h, (*q.shape, 3)), np.where(prismatic, 0.0, q))
    E = np.zeros((*q.shape, 4, 4))
    E[..., :3, :3] = R
    E[..., :3, 3] = np.where(
        prismatic[:, None], h * q[..., None], p - np.einsum("...ij,...j->...i", R, p)
    )
    E[..., 3, 3] = 1.0
    T_dh = np.broadcast_to(base, (m, 4, 4))
    T_ref = np.broadcast_to(np.eye(4), (m, 4, 4))
    for k in range(n):  # batched 4x4 products over the configurations
        T_dh = T_dh @ A[:, k]
        T_ref = T_ref @ E[:, k]
    return float(np.abs(T_dh @ tool - T_ref @ g.tip).max())


def _tidy_length(v: float) -> float:
    r = round(v, 12)
    return r + 0.0 if abs(r - v) <= ROUND_OFF_TOL else v


def _tidy_angle(v: float) -> float:
    k = round(v / (math.pi / 4))
    r = k * (math.pi / 4)
    if abs(r - v) > ROUND_OFF_TOL:
        return v
    return math.pi if k == -4 else r + 0.0  # wrapped to (-π, π]


def extract_dh(geometry: ChainGeometry, convention: str = "standard") -> ExtractedTable:
    """The DH table of a serial chain, by the rules (see the module docstring).

    Args:
        geometry: The chain's joint axes, tip and named frames at q = 0.
        convention: ``"standard"`` or ``"modified"`` (aliases accepted).

    Returns:
        Rows, base, tool, the rule that placed each frame and ``fk_error``, the
        table's distance from the chain's own FK (:class:`ExtractedTable`). A
        :class:`~kinematica.errors.KinematicaWarning` is raised when it is above
        :data:`FK_CHECK_TOL`.
    """
    conv = check_convention(convention)
    build = standard_frames if conv == "standard" else modified_frames
    frames, rules = build(geometry)
    rows: list[Joint] = []
    for k, joint in enumerate(geometry.joints, start=1):
        theta, d, a, alpha = _row(frames[k - 1], frames[k], conv)
        theta, alpha = _tidy_angle(theta), _tidy_angle(alpha)
        d, a = _tidy_length(d), _tidy_length(a)
        # Derived values: the plausibility warnings are for values people type.
        with values_checked():
            if joint.kind == "R":
                rows.append(
                    Revolute(d=d, a=a, alpha=alpha, offset=theta, qlim=joint.qlim, name=joint.name)
                )
            else:
                rows.append(
                    Prismatic(
                        theta=theta, a=a, alpha=alpha, offset=d, qlim=joint.qlim, name=joint.name
                    )
                )
    base = snap(frames[0])
    tool = snap(seen_from(frames[-1], geometry.tip))
    table = tuple(rows)
    error = _fk_error(geometry, table, conv, base, tool)
    if error > FK_CHECK_TOL:
        warnings.warn(
            f"the extracted {conv} DH table reproduces the chain's forward kinematics only to "
            f"{error:.1e} (consecutive axes nearly parallel: DH cannot place their common "
            "normal accurately)",
            KinematicaWarning,
            stacklevel=2,
        )
    return ExtractedTable(
        rows=table,
        convention=conv,
        base=base,
        tool=tool,
        rules=tuple(rules),
        fk_error=error,
        frames=np.array(frames),
    )
