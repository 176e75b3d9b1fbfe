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
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from kinematica.dh.axes import AxisFrame, ChainGeometry, ExtractedTable, FrameRule, NamedFrame
from kinematica.dh.convert import ROUND_OFF_TOL, rx_tx, snap, x_screw
from kinematica.dh.joints import (
    Convention,
    Joint,
    Prismatic,
    Revolute,
    check_convention,
    values_checked,
)
from kinematica.dh.lines import (
    AXIS_ANGLE_TOL,
    cross3,
    frame_from,
    frame_normal_to_axis,
    frame_on_axis,
    length_tol,
    line_pair,
    perpendicular_hint,
)
from kinematica.dh.link import link_matrix
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


def _joint_label(g: ChainGeometry, k: int) -> str:
    name = g.joints[k - 1].name
    return f"joint {k} ({name!r})" if name else f"joint {k}"


def _pair(
    g: ChainGeometry, a: int, frame: int, on_b: bool, prev: FloatArray | None
) -> tuple[FloatArray, FrameRule]:
    """The frame on axis ``a+1`` (``on_b``) or ``a`` by the common normal of axes a, a+1.

    ``prev`` is the DH frame before it (None when not yet placed): where the rules
    leave a choice, d = 0 and an offset of 0 are taken from it (module docstring).
    """
    A, B = g.joints[a - 1], g.joints[a]
    pair = line_pair(A.direction, A.frame[:3, 3], B.direction, B.frame[:3, 3], g.size)
    on = B if on_b else A
    k_on = a + 1 if on_b else a
    z = on.direction
    origin = pair.foot_b if on_b else pair.foot_a
    axes = f"axes {a} and {a + 1}"
    if pair.normal is None:
        x = perpendicular_hint(on.frame, z)
        text = (
            f"{axes} coincide: origin at {_joint_label(g, k_on)}, x{frame} from its frame "
            "(normal to the axis)"
        )
        return frame_from(x, z, origin), FrameRule(frame, "collinear", text)
    x = pair.normal
    along = float(on.frame[:3, 0] @ x)
    if abs(along) > AXIS_ANGLE_TOL:  # the joint's own frame says which way x points
        flipped, why = along < 0.0, f"as the frame of {_joint_label(g, k_on)} has it"
    elif prev is not None and float(prev[:3, 0] @ x) < -AXIS_ANGLE_TOL:
        flipped, why = True, f"so that x{frame - 1} turns onto it by less than 90°"
    else:
        flipped, why = False, ""
    if flipped:
        x = -x
    if pair.kind == "parallel":
        x = x - float(x @ z) * z
        x = x / np.linalg.norm(x)
    if pair.kind == "intersecting":
        za, zb = (frame - 1, frame) if on_b else (frame, frame + 1)
        sense = f"-(z{za} × z{zb})" if flipped else f"z{za} × z{zb}"
        text = f"{axes} meet: origin at the intersection, x{frame} = {sense} (rule 6)"
    else:
        where = f"at {_joint_label(g, k_on)}" if pair.kind == "parallel" else f"on axis {k_on}"
        if pair.kind == "parallel" and prev is not None:
            # the origin is free along the axis: d = 0 (level with the frame before)
            p_on = on.frame[:3, 3]
            ref = prev[:3, 2] if on_b else z  # standard d is along z(k-1), modified along z(k)
            origin = p_on + (float((prev[:3, 3] - p_on) @ ref) / float(z @ ref)) * z
            where = f"on axis {k_on} level with S{frame - 1} (d{frame} = 0)"
        towards = f"from axis {a + 1} to axis {a}" if flipped else f"from axis {a} to axis {a + 1}"
        text = (
            f"{axes} are {pair.kind}: x{frame} on a common normal, origin {where} "
            f"(rules 6-7), x{frame} {towards}"
        )
    if why:
        text += f", {why}"
    if _obeys_rules(on, A if on_b else B):
        # The joint's own frame is already this DH frame, to round-off: keep it whole (the
        # computed normal of nearly parallel axes is known only to about 1e-16 / angle).
        return frame_from(on.frame[:3, 0], z, on.frame[:3, 3]), FrameRule(frame, pair.kind, text)
    return frame_from(x, z, origin), FrameRule(frame, pair.kind, text)


def _obeys_rules(joint: AxisFrame, other: AxisFrame) -> bool:
    """True when the joint's own frame has its x line on the common normal, to round-off.

    That is: x normal to the joint's axis and to the other axis, and meeting the
    other axis (the frame's origin is on the joint's axis), as rules 6-7 place
    the DH frame on the joint's axis.
    """
    x, o = joint.frame[:3, 0], joint.frame[:3, 3]
    h, p = other.direction, other.frame[:3, 3]
    if abs(float(x @ joint.direction)) > ROUND_OFF_TOL or abs(float(x @ h)) > ROUND_OFF_TOL:
        return False
    scale = max(1.0, float(np.abs(o).max()), float(np.abs(p).max()))
    off = float((p - o) @ cross3(x, h))  # distance of the lines (x ⊥ h: |x × h| = 1)
    return abs(off) <= ROUND_OFF_TOL * scale


def _candidates(
    named: tuple[NamedFrame, ...],
    joint: AxisFrame,
    label: str,
    make: Callable[[FloatArray, FloatArray, FloatArray, float], FloatArray | None],
    size: float,
) -> tuple[FloatArray, str] | None:
    """The first named frame (then the joint's own frame) that ``make`` accepts."""
    h, p = joint.direction, joint.frame[:3, 3]
    for f in named:
        F = make(f.pose, h, p, size)
        if F is not None:
            return F, f"link {f.name!r}"
    F = make(joint.frame, h, p, size)
    return None if F is None else (F, f"the frame of {label}")


def _reading(g: ChainGeometry) -> Convention | None:
    """The convention whose rules read the description's frames; the other regroups them.

    Modified when the joint frames are modified DH frames and not standard ones
    (Franka's); standard when they are standard DH frames and not modified ones,
    or neither. Frames that obey both (all axes parallel) are read as the
    description says they are (a URDF kinematica wrote), else as standard. One
    joint: as the description says, else ``None`` (each convention by its rules).
    """
    if len(g.joints) == 1 and g.dh_frames is None:
        return None
    if len(g.joints) == 1:
        return "modified" if g.dh_frames == "modified" else "standard"
    modified, standard = _own_modified_frames(g), _own_standard_frames(g)
    if modified and standard and g.dh_frames == "modified":
        return "modified"
    return "modified" if modified and not standard else "standard"


def _standard_frames(g: ChainGeometry) -> tuple[list[FloatArray], list[FrameRule]]:
    if _reading(g) == "modified":
        return _paul_frames(g, *_modified_rules(g))
    return _standard_rules(g)


def _modified_frames(g: ChainGeometry) -> tuple[list[FloatArray], list[FrameRule]]:
    if _reading(g) == "standard":
        return _craig_frames(*_standard_rules(g))
    return _modified_rules(g)


def _standard_rules(g: ChainGeometry) -> tuple[list[FloatArray], list[FrameRule]]:
    n = len(g.joints)
    j1, jn = g.joints[0], g.joints[-1]
    frames: list[FloatArray] = []
    rules: list[FrameRule] = []
    found = _candidates(g.before, j1, _joint_label(g, 1), frame_on_axis, g.size)
    if found is not None:
        frames.append(found[0])
        rules.append(FrameRule(0, "frame", f"{found[1]} kept (its z is axis 1, its origin on it)"))
    else:
        x = perpendicular_hint(j1.frame, j1.direction)
        frames.append(frame_from(x, j1.direction, j1.frame[:3, 3]))
        rules.append(
            FrameRule(0, "rule 5", f"origin at {_joint_label(g, 1)} on axis 1, x0 from its frame")
        )
    for k in range(1, n):
        S, rule = _pair(g, k, k, on_b=True, prev=frames[-1])
        frames.append(S)
        rules.append(rule)
    h, p = jn.direction, jn.frame[:3, 3]
    last = next(
        (
            (F, f.name)
            for f in g.after
            if (F := frame_normal_to_axis(f.pose, h, p, g.size)) is not None
        ),
        None,
    )
    if last is not None:
        frames.append(last[0])
        text = f"link {last[1]!r} kept (its x is normal to axis {n} and meets it: rule 9)"
        rules.append(FrameRule(n, "frame", text))
        return frames, rules
    tip_o = g.tip[:3, 3]
    foot = p + float((tip_o - p) @ h) * h
    off = tip_o - foot
    dist = float(np.linalg.norm(off))
    if dist > length_tol(g.size):
        x, how = off / dist, f"x{n} from axis {n} towards the tip"
    else:
        x, how = perpendicular_hint(g.tip, h), f"the tip is on axis {n}, x{n} from the tip frame"
        tip_o = foot
    frames.append(frame_from(x, h, tip_o))
    rules.append(FrameRule(n, "rule 9", f"origin at the tip, z{n} = z{n - 1}, {how}"))
    return frames, rules


def _own_modified_frames(g: ChainGeometry) -> bool:
    """True when every joint's own frame but the last is already a modified DH frame.

    That is: each has its x on the common normal to the next axis, meeting it (as
    a description written from a modified table, e.g. Franka's URDF, has them).
    """
    return all(_obeys_rules(a, b) for a, b in zip(g.joints[:-1], g.joints[1:], strict=True))


def _own_standard_frames(g: ChainGeometry) -> bool:
    """True when every joint's own frame but the first is already a standard DH frame."""
    return all(_obeys_rules(b, a) for a, b in zip(g.joints[:-1], g.joints[1:], strict=True))


def _paul_frames(
    g: ChainGeometry, mod: list[FloatArray], rules: list[FrameRule]
) -> tuple[list[FloatArray], list[FrameRule]]:
    """Standard frames of the modified frames ``mod``: the same θ and d columns.

    ``S_k`` (k < n) is on axis k+1 (z of ``S'_(k+1)``) where the x line of ``S'_k``
    meets it, with that x (``S'_k Rot(x, α_k) Tras(x, a_k)``); ``S_n = S'_n``, or
    the tip when the tip is ``S'_n Tras(x, a_n) Rot(x, α_n)`` (its x that of
    ``S'_n``, its origin on that x line): the modified table regrouped (a and α
    moved up a row, a tool that is such a pair into the last row), as
    ``Robot.to_convention`` writes it.
    """
    frames: list[FloatArray] = []
    texts: list[FrameRule] = []
    n = len(mod) - 1
    for k in range(n):
        here, nxt = mod[k], mod[k + 1]
        x = here[:3, 0]
        origin = here[:3, 3] + float((nxt[:3, 3] - here[:3, 3]) @ x) * x
        frames.append(frame_from(x, nxt[:3, 2], origin))
        text = (
            f"on axis {k + 1} where the x line of the modified S{k} meets it, with its x "
            f"(Paul's frame of the modified table: the same θ and d); S{k}: {rules[k].text}"
        )
        texts.append(FrameRule(k, rules[k].rule, text))
    tip = _tip_on_x_line(g, mod[n])
    if tip is None:
        frames.append(mod[n])
        texts.append(rules[n])
    else:
        frames.append(tip)
        text = f"the tip, whose x is that of the modified S{n} and meets axis {n} there (rule 9)"
        texts.append(FrameRule(n, "frame", text))
    return frames, texts


def _tip_on_x_line(g: ChainGeometry, last: FloatArray) -> FloatArray | None:
    """``last · Tras(x, a) · Rot(x, α)`` when the tip is that (:func:`x_screw`), else None.

    ``last`` is the modified ``S'_n``; the test is the one ``Robot.to_convention``
    applies to the modified tool, so that both put the same pair in the last row.
    """
    pair = x_screw(_seen_from(last, g.tip))
    return None if pair is None else last @ rx_tx(pair[1], pair[0])


def _seen_from(F: FloatArray, T: FloatArray) -> FloatArray:
    """``F⁻¹ · T`` for frames ``F`` and ``T`` (rigid: the rotation transposed)."""
    out = np.eye(4)
    out[:3, :3] = F[:3, :3].T @ T[:3, :3]
    out[:3, 3] = F[:3, :3].T @ (T[:3, 3] - F[:3, 3])
    return out


def _craig_frames(
    std: list[FloatArray], rules: list[FrameRule]
) -> tuple[list[FloatArray], list[FrameRule]]:
    """Craig's frames of the standard frames ``std``: the same θ and d columns.

    ``S'_k`` (k >= 1) is on axis k (z of ``S_(k-1)``) where the x line of ``S_k``
    meets it, with that x: ``S'_k = S_(k-1) Rot(z, θk) Tras(z, dk)``, a valid
    modified frame (x on the common normal to axis k+1, origin at its foot). So the
    modified table is the standard one regrouped (a and α moved down a row), as
    ``Robot.to_convention`` writes it: one arm, one modified table.
    """
    frames, out = [std[0]], [rules[0]]
    for k in range(1, len(std)):
        prev, here = std[k - 1], std[k]
        z = prev[:3, 2]
        origin = prev[:3, 3] + float((here[:3, 3] - prev[:3, 3]) @ z) * z
        frames.append(frame_from(here[:3, 0], z, origin))
        text = (
            f"on axis {k} where the x line of the standard S{k} meets it, with its x "
            f"(Craig's frame of the standard table: the same θ{k} and d{k}); S{k}: {rules[k].text}"
        )
        out.append(FrameRule(k, rules[k].rule, text))
    return frames, out


def _modified_rules(g: ChainGeometry) -> tuple[list[FloatArray], list[FrameRule]]:
    n = len(g.joints)
    j1, jn = g.joints[0], g.joints[-1]
    frames: list[FloatArray] = []
    rules: list[FrameRule] = []
    for k in range(1, n):
        S, rule = _pair(g, k, k, on_b=False, prev=frames[-1] if frames else None)
        frames.append(S)
        rules.append(rule)
    F = frame_on_axis(jn.frame, jn.direction, jn.frame[:3, 3], g.size)
    if F is not None:
        rules.append(FrameRule(n, "frame", f"the frame of {_joint_label(g, n)} kept"))
    else:
        x = perpendicular_hint(jn.frame, jn.direction)
        F = frame_from(x, jn.direction, jn.frame[:3, 3])
        text = f"origin at {_joint_label(g, n)}, x{n} from its frame (free in Craig's rules)"
        rules.append(FrameRule(n, "craig", text))
    frames.append(F)
    found = _candidates(g.before, j1, _joint_label(g, 1), frame_normal_to_axis, g.size)
    if found is not None:
        first = found[0]
        rule0 = FrameRule(0, "frame", f"{found[1]} kept (its x is normal to axis 1 and meets it)")
    else:
        first = frames[0]
        rule0 = FrameRule(0, "craig", "S0 is S1 at q1 = 0 (Craig: a0 = alpha0 = 0)")
    return [first, *frames], [rule0, *rules]


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
    build = _standard_frames if conv == "standard" else _modified_frames
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
    tool = snap(_seen_from(frames[-1], geometry.tip))
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
