"""A chain's DH frames placed by the Denavit-Hartenberg rules (:mod:`kinematica.dh.extract`).

:func:`standard_frames` (Paul's rules, distal) and :func:`modified_frames` (Craig's,
proximal) place one frame per joint on the joint axes, and say which rule placed
each; a chain whose own frames already obey one convention's rules is read in
that convention first. :func:`kinematica.dh.extract.extract_dh` reads the DH rows
off consecutive frames.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from kinematica.dh.axes import AxisFrame, ChainGeometry, FrameRule, NamedFrame
from kinematica.dh.convert import ROUND_OFF_TOL, rx_tx, x_screw
from kinematica.dh.joints import (
    Convention,
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

__all__ = ["modified_frames", "seen_from", "standard_frames"]

FloatArray = NDArray[np.float64]


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
    # modified: every joint's own frame but the last has its x on the common normal to the
    # next axis, meeting it (as a description written from a modified table, e.g. Franka's
    # URDF, has them); standard: every one but the first is a standard DH frame
    pairs = list(zip(g.joints[:-1], g.joints[1:], strict=True))
    modified = all(_obeys_rules(a, b) for a, b in pairs)
    standard = all(_obeys_rules(b, a) for a, b in pairs)
    if modified and standard and g.dh_frames == "modified":
        return "modified"
    return "modified" if modified and not standard else "standard"


def standard_frames(g: ChainGeometry) -> tuple[list[FloatArray], list[FrameRule]]:
    """The frames ``S_0 ... S_n`` of the standard convention, and the rule placing each."""
    if _reading(g) == "modified":
        return _paul_frames(g, *_modified_rules(g))
    return _standard_rules(g)


def modified_frames(g: ChainGeometry) -> tuple[list[FloatArray], list[FrameRule]]:
    """The frames of the modified convention, and the rule placing each."""
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
    pair = x_screw(seen_from(last, g.tip))
    return None if pair is None else last @ rx_tx(pair[1], pair[0])


def seen_from(F: FloatArray, T: FloatArray) -> FloatArray:
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
