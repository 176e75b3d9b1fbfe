"""Property tests of the small arms' closed forms on degenerate geometry.

Random arms of every class (planar 2R/3R/PR/PRR, SCARA, 3R anthropomorphic and
elbow), both DH conventions, random base and tool, with the geometry users
hit and generic draws miss: equal links, 1e-10 offsets and twists next to the
special values (0, ±90°, 180°), prismatic joints at their limits, and
configurations folded, stretched, or 1e-8..1e-12 rad from it, with the tool
on axis 1. The targets are ``fk(q)``: never ``unreachable`` nor ``not_found``;
every solution is checked here by forward kinematics; ``q`` is among the
solutions whenever the status is ``ok`` and ``q`` is at least 1e-6 from a
singular set (measured here from the geometry: the triangle's angle, the link
across the slide, the distance from axis 1). One test holds a batch and single
calls equal, solution by solution and message by message.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.typing import NDArray
from support.helpers import transform_from
from support.small_arms import KINDS, reached

from kinematica.ik import IKBatchResult
from kinematica.ik.analytic.small_samples import edge_arm
from kinematica.robot import Robot, classify

FloatArray = NDArray[np.float64]
PI = math.pi
TOL = 1e-10
#: A configuration this far (rad, or relative) from a singular set must be among the solutions.
AWAY = 1e-6
#: Twists and offsets of "exactly" special values are off by this in degenerate arms.
TINY = 1e-10
#: Perturbations of folded and stretched configurations (rad).
NUDGES = (0.0, 1e-8, -1e-8, 1e-10, -1e-10, 1e-12, -1e-12)

PROPERTY = settings(max_examples=20, deadline=None, database=None, derandomize=True)


# ------------------------------------------------------------------ the arms
def degenerate_arm(
    kind: str, rng: np.random.Generator, equal: bool, tiny: bool, tilt: bool = False
) -> Robot:
    """A random arm of ``kind`` from the solver specs' own sampler, on the edges asked for.

    ``equal``: triangle links of equal length. ``tiny``: link offsets and lengths
    ``d``, ``a`` and joint offsets that would be 0 are 1e-10. ``tilt``: twists are
    1e-10 off 0, ±90°, 180° (the axes parallel or normal only within the line
    geometry's tolerance).
    """
    arm = edge_arm(kind, rng, equal=equal, tiny=tiny, tilt=tilt)
    robot = Robot.from_dh(arm.links, convention=arm.convention, base=arm.base, tool=arm.tool)
    assert classify(robot).kind == kind
    return robot


# ------------------------------------------------- geometry of singular sets
def _unit(v: FloatArray) -> FloatArray:
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _across(v: FloatArray, k: FloatArray) -> FloatArray:
    return v - np.sum(v * k, axis=-1, keepdims=True) * k


def _triangle(robot: Robot, kind: str, q: FloatArray, position: bool) -> tuple[int, FloatArray]:
    """The joint whose angle closes the arm's triangle, and ``(N,)`` how far from a fold.

    The fold measure is ``|sin ψ|`` of the triangle's angle (0: folded or
    stretched, where two solutions merge), or for a slide and a link the
    cosine of the link against the slide (0: the link across the slide).
    """
    h, p = robot.joint_axes(q)
    tool = robot.fk(q)[..., :3, 3]
    if kind in ("anthropomorphic-3R", "elbow-3R"):
        k = h[..., 1, :]
        s, e, w, joint = p[..., 1, :], p[..., 2, :], tool, 2
    elif kind in ("planar-PR", "planar-PRR"):
        k = h[..., 1, :]
        end = tool if kind == "planar-PR" or position else p[..., 2, :]
        link = _unit(_across(end - p[..., 1, :], k))
        return 1, np.abs(np.sum(link * _unit(h[..., 0, :]), axis=-1))
    else:
        k = h[..., 0, :]
        last = 3 if kind == "scara" else 2
        w = tool if kind == "planar-2R" else p[..., last, :]
        s, e, joint = p[..., 0, :], p[..., 1, :], 1
    a = _unit(_across(e - s, k))
    b = _unit(_across(w - e, k))
    return joint, np.linalg.norm(np.cross(a, b), axis=-1)


def _set_triangle(
    robot: Robot, kind: str, q: FloatArray, position: bool, angle: float
) -> FloatArray:
    """``q`` with the triangle's joint turned so that its angle is ``angle`` (0 or π)."""
    joint, _ = _triangle(robot, kind, q[None], position)
    out = q.copy()
    for _ in range(3):  # the angle is linear in the joint: one secant step lands on it
        psi0 = _psi(robot, kind, out, position)
        probe = out.copy()
        probe[joint] += 0.1
        slope = math.remainder(_psi(robot, kind, probe, position) - psi0, 2 * PI) / 0.1
        out[joint] += math.remainder(angle - psi0, 2 * PI) / slope
    return out


def _psi(robot: Robot, kind: str, q: FloatArray, position: bool) -> float:
    """The triangle's angle (rad), signed about k; for the PR link, its angle to the slide."""
    h, p = robot.joint_axes(q)
    tool = robot.fk(q)[:3, 3]
    if kind in ("planar-PR", "planar-PRR"):
        k = h[1]
        end = tool if kind == "planar-PR" or position else p[2]
        a, b = _across(h[0], k), _across(end - p[1], k)
    else:
        three = kind in ("anthropomorphic-3R", "elbow-3R")
        k = h[1] if three else h[0]
        if three:
            s, e, w = p[1], p[2], tool
        else:
            s, e = p[0], p[1]
            w = tool if kind == "planar-2R" else p[3 if kind == "scara" else 2]
        a, b = _across(e - s, k), _across(w - e, k)
    return math.atan2(float(np.cross(a, b) @ _unit(k)), float(a @ b))


def _axis_distance(robot: Robot, q: FloatArray) -> FloatArray:
    """Distance ``(N,)`` of the tool origin from axis 1 (m)."""
    h, p = robot.joint_axes(q)
    v = robot.fk(q)[..., :3, 3] - p[..., 0, :]
    return np.linalg.norm(_across(v, h[..., 0, :]), axis=-1)


def special_q(robot: Robot, kind: str, rng: np.random.Generator, position: bool) -> FloatArray:
    """Random, folded, stretched and nearly so, slides at their limits, tool on axis 1."""
    lo, hi = np.nan_to_num(robot.qlim, posinf=1.0, neginf=-1.0).T
    qs = [rng.uniform(lo, hi) for _ in range(4)]
    folds = (PI / 2, -PI / 2) if kind in ("planar-PR", "planar-PRR") else (0.0, PI)
    for angle in folds:
        for nudge in NUDGES:
            q = _set_triangle(robot, kind, rng.uniform(lo, hi), position, angle + nudge)
            qs.append(q)
    for j in np.flatnonzero(robot.is_prismatic):
        for bound in (lo[j], hi[j]):
            q = rng.uniform(lo, hi)
            q[j] = bound
            qs.append(q)
    if kind == "anthropomorphic-3R":  # tool on axis 1 (if the arm's plane holds axis 1)
        for nudge in (0.0, 1e-9, -1e-11):
            q = rng.uniform(lo, hi)
            for _ in range(30):  # Newton on q2 for a tool on the axis
                d0 = _signed_axis_offset(robot, q)
                probe = q.copy()
                probe[1] += 1e-6
                slope = (_signed_axis_offset(robot, probe) - d0) / 1e-6
                if abs(slope) < 1e-9:
                    break
                q[1] -= d0 / slope
            q[1] += nudge
            if _axis_distance(robot, q[None])[0] < 1e-6:
                qs.append(q)
    return np.array(qs)


def _signed_axis_offset(robot: Robot, q: FloatArray) -> float:
    """The tool's offset from axis 1 along ``h1 × k`` (m), signed."""
    h, p = robot.joint_axes(q)
    return float((robot.fk(q)[:3, 3] - p[0]) @ _unit(np.cross(h[0], h[1])))


# ---------------------------------------------------------------- properties
def _away(robot: Robot, kind: str, q: FloatArray, position: bool) -> FloatArray:
    """``(N,)`` how far each configuration is from a set where solutions merge."""
    _, away = _triangle(robot, kind, q, position)
    if kind in ("anthropomorphic-3R", "elbow-3R") and position:
        rho = _axis_distance(robot, q)
        h, p = robot.joint_axes(q)
        tool = robot.fk(q)[:, :3, 3]
        side = np.sum((tool - p[:, 0]) * _unit(np.cross(h[:, 0], h[:, 1])), axis=-1)
        away = np.minimum(np.minimum(away, rho), np.abs(side) / np.maximum(rho, 1e-300))
    return np.asarray(away)


def _check(robot: Robot, kind: str, q: FloatArray, position: bool, tilted: bool) -> None:
    """``ik(fk(q))``: honest statuses, exact solutions, ``q`` among them away from singular sets.

    ``tilted``: the arm's axes are parallel only within the classification's
    tolerance (1e-10 off). Its continua (a fold, a free last joint) are those
    of the ideal arm and break: there ``not_found`` and ``out_of_limits``
    (a representative within tolerance beyond a limit) are allowed; a false
    ``unreachable`` never is. Where no candidate of the closed form survives the
    check on the real arm, the numeric search answers (``res.methods``): one
    solution, not necessarily ``q``.
    """
    T = robot.fk(q)
    targets = T[:, :3, 3] if position else T
    res = robot.ik(targets)
    assert isinstance(res, IKBatchResult)
    away = _away(robot, kind, q, position)
    free_last = position and kind in ("planar-3R", "planar-PRR", "scara")
    excused = tilted & (free_last | (away < AWAY))
    for i in np.flatnonzero(res.status != "ok"):
        status, message = res.status[i], res[i].message
        assert status != "unreachable", (q[i].tolist(), message)
        assert status == "singular" or excused[i], (q[i].tolist(), message)
    for i in range(len(q)):
        one = res[i]
        err = reached(robot, one.solutions, targets[i])
        assert (err <= TOL).all(), (q[i].tolist(), err)
        lo, hi = robot.qlim.T
        assert ((one.solutions >= lo - 1e-12) & (one.solutions <= hi + 1e-12)).all()
    searched = np.zeros(len(q), dtype=bool)
    for idx in res.methods:
        searched[idx] = True
    assert tilted or not searched.any()  # only a near-degenerate arm needs the search
    if free_last:  # a continuum: the last joint free (or the first, on a fold)
        solved = np.isin(res.status, ["ok", "singular"]) & ~searched
        assert (res.status[solved] == "singular").all()
        assert (res.free[solved, -1] | res.free[solved, 0]).all()
        return
    unique = not position and kind in ("planar-2R", "planar-PR", "anthropomorphic-3R", "elbow-3R")
    must = (res.status == "ok") & ((away >= AWAY) | unique) & ~searched
    for i in np.flatnonzero(must):
        d = res[i].solutions - q[i]
        rev = ~robot.is_prismatic
        d[:, rev] = np.angle(np.exp(1j * d[:, rev]))
        assert np.abs(d).max(axis=1).min() < 1e-7, (q[i].tolist(), res[i].solutions.tolist())


@PROPERTY
@given(
    kind=st.sampled_from(KINDS),
    seed=st.integers(0, 2**32 - 1),
    equal=st.booleans(),
    tiny=st.booleans(),
    position=st.booleans(),
)
def test_fk_targets_are_solved_at_the_edges(
    kind: str, seed: int, equal: bool, tiny: bool, position: bool
) -> None:
    rng = np.random.default_rng(seed)
    robot = degenerate_arm(kind, rng, equal, tiny)
    _check(robot, kind, special_q(robot, kind, rng, position), position, tilted=False)


@PROPERTY
@given(kind=st.sampled_from(KINDS), seed=st.integers(0, 2**32 - 1), position=st.booleans())
def test_axes_parallel_only_within_tolerance_are_never_falsely_unreachable(
    kind: str, seed: int, position: bool
) -> None:
    rng = np.random.default_rng(seed)
    robot = degenerate_arm(kind, rng, equal=bool(rng.random() < 0.5), tiny=False, tilt=True)
    _check(robot, kind, special_q(robot, kind, rng, position), position, tilted=True)


def test_batch_and_single_agree_solution_by_solution() -> None:
    """Reachable, unreachable, singular and out-of-limits targets of every class."""
    rng = np.random.default_rng(21)
    for kind in KINDS:
        robot = degenerate_arm(kind, rng, equal=True, tiny=False)
        lo, hi = np.nan_to_num(robot.qlim, posinf=1.0, neginf=-1.0).T
        q = np.array([rng.uniform(lo, hi) for _ in range(3)])
        fold = PI / 2 if kind in ("planar-PR", "planar-PRR") else PI
        q[2] = _set_triangle(robot, kind, q[2], False, fold)  # singular for some
        T = robot.fk(q)
        far = T[0].copy()
        far[:3, 3] *= 50.0
        tilted = T[1].copy()
        tilted[:3, :3] = tilted[:3, :3] @ transform_from([1.0, 0.3, 0.2, 0.1], [0, 0, 0])[:3, :3]
        poses = np.concatenate([T, far[None], tilted[None]])
        tight = robot.with_limits([(v - 1e-3, v + 1e-3) for v in q[0] + 0.3])
        for arm in (robot, tight):
            for targets in (poses, poses[:, :3, 3]):
                many = arm.ik(targets)
                assert isinstance(many, IKBatchResult)
                seen = set(many.status)
                for i in range(len(targets)):
                    one = arm.ik(targets[i])
                    assert one.status == many.status[i]
                    assert one.message == many[i].message
                    assert one.branches == many[i].branches
                    assert one.free_joints == many[i].free_joints
                    np.testing.assert_array_equal(one.solutions, many[i].solutions)
                    np.testing.assert_array_equal(one.out_of_limits, many[i].out_of_limits)
                assert "unreachable" in seen
        assert "out_of_limits" in set(tight.ik(poses[:1]).status)
