"""What a followed Cartesian path passes through besides its samples' poses.

A path followed continuously can still be one no robot should run: it may pass near a
singular set without touching it (no determinant changes sign, every step is refined
into continuous sub-steps, yet two joints turn half a turn in a few samples), and it
may end on another IK branch than the configuration it was asked to reach (the same
pose, the wrist flipped). Three checks of the samples ``(s, q)`` say so:

- ``"near_singularity"``: a run of samples where a named singularity's measure
  (:func:`~kinematica.robot.singularities.singularity_measures`; lengths relative to
  the arm's size) is below :data:`NEAR_SINGULAR_TOL`, with where its smallest value
  was sampled and how small it was;
- ``"speed_jump"``: a run of segments where the fastest joint's rate ``|Δq|/Δs``
  exceeds :data:`SPEED_JUMP_RATIO` times its median over the path, with the joint,
  its largest step and the ratio;
- ``"end_branch"``: the last configuration differs from the one asked for (``q1``:
  the IK solution of the end pose nearest to it) by more than :data:`END_TOL`, with
  the branch names when the closed form gives them.

Each check returns plain tuples ``(kind, index, stop, s, names, message)``, which
:func:`kinematica.motion.cartesian.cartesian_path` turns into its events.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from kinematica.ik.result import IKResult
from kinematica.robot.singularities import singularity_measures
from kinematica.spatial import wrap_angle

if TYPE_CHECKING:
    from kinematica.robot import Robot

__all__ = [
    "END_TOL",
    "NEAR_SINGULAR_TOL",
    "SPEED_JUMP_RATIO",
    "RawEvent",
    "end_branch",
    "near_singular_passages",
    "speed_jumps",
]

FloatArray = NDArray[np.float64]
#: ``(kind, index, stop, s, names, message)``; see ``PathEvent``.
RawEvent = tuple[str, int, int, float, tuple[str, ...], str]

#: A named singularity's relative measure below this is a near-singular passage: the
#: sine of the angle between axes 4 and 6 (0.05: q5 within 2.9° of its singular
#: value), the sine of the angle at the elbow point of the shoulder-elbow-point
#: triangle (the elbow rate over the elbow point's distance from the elbow axis: 0
#: stretched or folded), the shoulder distance as a fraction of the arm's size.
#: Joint rates grow as the inverse of the measure: 20 times the arm's regular rates
#: at this bound.
NEAR_SINGULAR_TOL = 0.05
#: A segment whose fastest joint rate exceeds this times the path's median is a jump.
#: Along a regular path the rate changes smoothly (within a factor of 2-3 of its
#: median); passing a singular set within 1° multiplies it by about 50.
SPEED_JUMP_RATIO = 10.0
#: Joint steps (rad or m) below this are round-off, never a jump.
STEP_ROUNDOFF = 1e-9
#: The last configuration is on the branch asked for when within this of it in every
#: joint (rad, angles modulo 2π, or m): the IK check's own duplicate threshold is 1e-7.
END_TOL = 1e-6

_WHAT = {
    "wrist": "axes 4 and 6 at {angle:.3g}° from aligned (sine {m:.2g})",
    "elbow": "the shoulder-elbow-tip triangle's angle at the tip {angle:.3g}° "
    "(elbow rate {raw:.3g} m/rad)",
    "shoulder": "wrist centre {raw:.3g} m from the shoulder's singular plane "
    "({m:.2g} of the arm's size)",
}


def _runs(mask: NDArray[np.bool_]) -> list[tuple[int, int]]:
    """``(first, last)`` index of each run of True in a 1-D mask."""
    out: list[tuple[int, int]] = []
    start = None
    for i, flag in enumerate(mask.tolist()):
        if flag and start is None:
            start = i
        if not flag and start is not None:
            out.append((start, i - 1))
            start = None
    if start is not None:
        out.append((start, len(mask) - 1))
    return out


def near_singular_passages(robot: Robot, s: FloatArray, q: FloatArray) -> list[RawEvent]:
    """Runs of samples near a named singular set (see the module docstring).

    Args:
        robot: The robot.
        s: ``(m,)`` path parameters.
        q: ``(m, n)`` configurations; NaN rows (unsolved samples) are skipped.

    Returns:
        One ``"near_singularity"`` event per run and name, at its smallest sample.
    """
    solved = np.all(np.isfinite(q), axis=1)
    if not solved.any():
        return []
    safe = np.where(solved[:, None], q, 0.0)
    measures = singularity_measures(robot, safe)
    relative = singularity_measures(robot, safe, relative=True)
    out: list[RawEvent] = []
    for name, raw in measures.items():
        rel = relative[name]
        near = solved & (rel < NEAR_SINGULAR_TOL)
        for first, last in _runs(near):
            k = first + int(np.argmin(rel[first : last + 1]))
            m = float(rel[k])
            angle = math.degrees(math.asin(min(m, 1.0)))
            what = _WHAT[name].format(angle=angle, m=m, raw=float(raw[k]))
            message = (
                f"near {name} singularity from sample {first} to {last}: closest at sample "
                f"{k} (s = {float(s[k]):.6g}), {what}; joint rates grow as its inverse"
            )
            out.append(("near_singularity", first, last, float(s[k]), (name,), message))
    return out


def _step_text(robot: Robot, joint: int, step: float) -> str:
    if robot.is_prismatic[joint]:
        return f"q{joint + 1} moves {step:.3g} m"
    return f"q{joint + 1} turns {math.degrees(step):.3g}°"


def speed_jumps(robot: Robot, s: FloatArray, q: FloatArray) -> list[RawEvent]:
    """Runs of segments whose fastest joint rate jumps (see the module docstring).

    Args:
        robot: The robot.
        s: ``(m,)`` path parameters (non-decreasing).
        q: ``(m, n)`` configurations; segments touching a NaN row are skipped.

    Returns:
        One ``"speed_jump"`` event per run of consecutive jumping segments, from
        the sample ending its first segment; ``s`` ends its fastest one.
    """
    dq = np.abs(np.diff(q, axis=0))
    ds = np.diff(s)
    valid = np.all(np.isfinite(dq), axis=1) & (ds > 0.0)
    if valid.sum() < 3:  # too few segments to tell a jump from the rate
        return []
    step = np.where(valid, np.nanmax(np.where(np.isfinite(dq), dq, 0.0), axis=1), 0.0)
    rate = np.where(valid, step / np.where(ds > 0.0, ds, 1.0), 0.0)
    typical = float(np.median(rate[valid]))
    jump = valid & (rate > SPEED_JUMP_RATIO * typical) & (step > STEP_ROUNDOFF)
    out: list[RawEvent] = []
    for first, last in _runs(jump):
        k = first + int(np.argmax(rate[first : last + 1]))
        joint = int(np.argmax(dq[k]))
        ratio = rate[k] / typical if typical > 0.0 else math.inf
        message = (
            f"joint-speed jump from sample {first} to {last + 1}: between samples {k} and "
            f"{k + 1} (s = {float(s[k + 1]):.6g}) {_step_text(robot, joint, float(dq[k, joint]))}"
            f", {ratio:.3g} times the path's median joint rate"
        )
        names = (f"q{joint + 1}",)
        out.append(("speed_jump", first + 1, last + 1, float(s[k + 1]), names, message))
    return out


def _distance(robot: Robot, a: FloatArray, b: FloatArray) -> FloatArray:
    """``(..., n)`` joint differences, revolute ones modulo 2π."""
    d = a - b
    out: FloatArray = np.where(robot.is_prismatic, d, wrap_angle(d))
    return out


def _nearest(robot: Robot, sols: FloatArray, q: FloatArray) -> int:
    return int(np.argmin(np.abs(_distance(robot, sols, q)).max(axis=1)))


def end_branch(
    robot: Robot,
    end: FloatArray,
    q: FloatArray,
    s: FloatArray,
    q1: FloatArray,
    position_only: bool,
) -> list[RawEvent]:
    """A ``"end_branch"`` event when the path ends elsewhere than the configuration asked for.

    Args:
        robot: The robot.
        end: ``(4, 4)`` the path's end pose.
        q: ``(m, n)`` the path's configurations (a NaN last row: not reached).
        s: ``(m,)`` its path parameters.
        q1: ``(n,)`` the configuration asked for at the end: the IK solution of
            ``end`` nearest to it is the goal (``q1`` itself when it reaches ``end``).
        position_only: The path followed the tool position only.

    Returns:
        ``[]`` or one event at the last sample, naming the joints that differ.
    """
    last = q[-1]
    if not np.all(np.isfinite(last)):
        return []  # the path did not get there: its own events say why
    res = robot.ik(end[:3, 3] if position_only else end, respect_limits=False, q0=q1)
    assert isinstance(res, IKResult)  # one target, one result
    sols = res.solutions
    if sols.shape[0] == 0:
        return []
    g = _nearest(robot, sols, q1)
    diff = np.abs(_distance(robot, last, sols[g]))
    if float(diff.max()) <= END_TOL:
        return []
    joints = [i for i in range(robot.dof) if diff[i] > END_TOL]
    moved = ", ".join(
        f"q{i + 1} by {diff[i]:.3g} m" if robot.is_prismatic[i] else
        f"q{i + 1} by {math.degrees(diff[i]):.4g}°"
        for i in joints
    )  # fmt: skip
    here, goal = res.branches[_nearest(robot, sols, last)], res.branches[g]
    which = f" (branch {here!r}, not {goal!r})" if here and goal and here != goal else ""
    kind = "IK branch" if res.complete else "configuration"
    k = q.shape[0] - 1
    message = (
        f"the path ends on another {kind} than the one asked for{which}: its last "
        f"configuration differs from it in {moved}"
    )
    return [("end_branch", k, k, float(s[k]), tuple(f"q{i + 1}" for i in joints), message)]
