"""Spherical-wrist IK at the edges (issue 13): honest on singular sets, folds and huge input.

Targets are made by forward kinematics, so a solution always exists: the
answer is never ``unreachable`` or ``not_found``, a continuum is ``singular``
with its free joints, and an ``ok`` answer contains the configuration that
made the target, to within what the pose's round-off allows there (its
Jacobian's conditioning). References are independent of the solver: forward
kinematics, the Jacobian's singular values, and the geometry of the arms
(where the wrist centre is, which axes are aligned), computed here.
"""

from __future__ import annotations

import dataclasses
import math
import warnings

import kinematica._core as _core
import kinematica._core_testing as _core_testing
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.typing import NDArray
from support.helpers import transforms
from support.ik_search import joint_distance, random_q
from support.wrist_arms import moved_target, near_flags, random_wrist_arm, solver

import kinematica as km
from kinematica.dh import Prismatic, Revolute
from kinematica.ik import IKBatchResult, closed_form
from kinematica.ik.analytic.spherical_wrist import GEOMETRIES
from kinematica.robot import Robot

FloatArray = NDArray[np.float64]
PI = math.pi
D = _core.decoupled
DT = _core_testing.decoupled
DOUBLE_ROOT_TOL = DT.DOUBLE_ROOT_TOL
HUGE_REACH = DT.HUGE_REACH
NEAR_SET_TOL = DT.NEAR_SET_TOL
NEAR_TOL = DT.NEAR_TOL
SINGULAR_TOL = DT.SINGULAR_TOL
WRIST_SINGULAR_TOL = DT.WRIST_SINGULAR_TOL
ARM6 = km.load("arm6-dh")
PUMA = km.load("puma560")
#: What the closed form takes for round-off in lengths (relative to the arm's
#: size, with the sizes its radicands multiply in): a configuration whose
#: pose is that close to a fold or singular set is found to within it over
#: the Jacobian's smallest singular value, not better.
POSE_ROUNDOFF = 10 * DOUBLE_ROOT_TOL
#: Two configurations this close in every joint are the same (as the check's dedupe).
SAME = 1e-7


def tolerance_at(robot: Robot, q: FloatArray) -> FloatArray:
    """How close a solution of ``fk(q)`` can be to ``q`` ``(N,)``: the Jacobian's conditioning."""
    s = np.linalg.svd(robot.jacobian(q, workers=1), compute_uv=False)[..., -1]
    return np.maximum(SAME, POSE_ROUNDOFF / np.maximum(s, 1e-300))


def nearest(robot: Robot, res: IKBatchResult, q: FloatArray) -> FloatArray:
    """``(N,)`` distance from each ``q`` to the closest returned solution (inf if none)."""
    d = joint_distance(robot, res.solutions, q[:, None, :])
    return np.nan_to_num(d, nan=np.inf).min(axis=1, initial=np.inf)


def assert_honest(robot: Robot, q: FloatArray, strict: bool = True) -> IKBatchResult:
    """``ik(fk(q))``: solved, never ``unreachable`` or ``not_found``; a continuum is
    ``singular`` with its free joints; an ``ok`` answer contains q to within its
    conditioning, or (``strict=False``: q within 1e-6 of a singular set or a
    fold, where round-off decides) the solver flags the target as near one.
    """
    T = robot.fk(q)
    res = robot.ik(T, respect_limits=False)
    assert isinstance(res, IKBatchResult)
    bad = ~np.isin(res.status, ["ok", "singular"])
    assert not bad.any(), (res.status[bad], q[bad])
    ok = res.status == "ok"
    found = nearest(robot, res, q) < tolerance_at(robot, q)
    if not strict:
        found |= near_flags(robot, T)
    assert (found | ~ok).all(), q[~found & ok]
    singular = res.status == "singular"
    assert res.free[singular].any(axis=1).all()
    return res


# ------------------------------------------------------- placing q on the sets
def wrist_centre(robot: Robot):  # type: ignore[no-untyped-def]
    """``q (..., 6) -> (..., 3)``: where the robot's wrist centre is (base frame)."""
    c = km.classify(robot).wrist_center
    assert c is not None
    M = robot.fk(np.zeros(robot.dof))
    c_tool = M[:3, :3].T @ (c - M[:3, 3])

    def centre(q: FloatArray) -> FloatArray:
        T = robot.fk(q, workers=1)
        return T[..., :3, 3] + T[..., :3, :3] @ c_tool

    return centre


def _bisect(f, q: FloatArray, j: int, lo: FloatArray, hi: FloatArray) -> FloatArray:  # type: ignore[no-untyped-def]
    """Joint ``j`` of each row of ``q`` moved onto a sign change of ``f`` in ``[lo, hi]``."""
    q = q.copy()
    for _ in range(60):
        q[:, j] = lo
        s_lo = np.sign(f(q))
        q[:, j] = mid = (lo + hi) / 2
        same = np.sign(f(q)) == s_lo
        lo, hi = np.where(same, mid, lo), np.where(same, hi, mid)
    q[:, j] = (lo + hi) / 2
    return q


def on_sign_change(f, q: FloatArray, j: int) -> FloatArray:  # type: ignore[no-untyped-def]
    """Rows of ``q`` with joint ``j`` on a zero of ``f`` (a grid, then bisection; rows without
    one are dropped)."""
    grid = np.linspace(-PI, PI, 181)
    scan = np.repeat(q[:, None, :], len(grid), axis=1)
    scan[:, :, j] = grid
    v = f(scan.reshape(-1, q.shape[1])).reshape(len(q), len(grid))
    rows, k = [], []
    for i, row in enumerate(v):
        flips = np.nonzero(np.sign(row[:-1]) * np.sign(row[1:]) < 0)[0]
        if len(flips):
            rows.append(i)
            k.append(flips[0])
    kk = np.array(k, dtype=int)
    return _bisect(f, q[rows], j, grid[kk], grid[kk + 1])


def axis1_offset(robot: Robot):  # type: ignore[no-untyped-def]
    """Signed distance of the wrist centre from axis 1 in the arm's plane (no shoulder offset)."""

    centre = wrist_centre(robot)

    def f(q: FloatArray) -> FloatArray:
        h, p = robot.joint_axes(q)
        side = np.cross(h[..., 0, :], h[..., 1, :])
        return np.sum((centre(q) - p[..., 0, :]) * side, -1)

    return f


def wrist_alignment(robot: Robot):  # type: ignore[no-untyped-def]
    """``(h4 × h6) · h5``: changes sign where axes 4 and 6 line up."""

    def f(q: FloatArray) -> FloatArray:
        h, _ = robot.joint_axes(q)
        return np.sum(np.cross(h[..., 3, :], h[..., 5, :]) * h[..., 4, :], -1)

    return f


def fold(robot: Robot):  # type: ignore[no-untyped-def]
    """det d(wrist centre)/d(q1, q2, q3): zero where two position branches merge."""

    centre = wrist_centre(robot)

    def f(q: FloatArray) -> FloatArray:
        eps = 1e-6
        cols = []
        for j in range(3):
            dq = np.zeros(robot.dof)
            dq[j] = eps
            cols.append((centre(q + dq) - centre(q - dq)) / (2 * eps))
        return np.linalg.det(np.stack(cols, axis=-1))

    return f


# ------------------------------------------------------------ the reproducers
def test_wrist_centre_nanometres_from_axis_1() -> None:
    """Issue 13 item 1: ``unreachable`` before; the wrist centre 3.4 nm from axis 1."""
    q = np.array([[0.0, -2.0165926436, -2.25, 0.2, 0.6, 0.1]])
    res = assert_honest(ARM6, q)
    assert res.status[0] == "ok" and nearest(ARM6, res, q)[0] < SAME


@pytest.mark.parametrize("name", ["arm6-dh", "irb120"])
def test_q2_sweeps_off_the_axis_1_set(name: str) -> None:
    """Issue 13 item 1: q2 1e-12 .. 1e-6 rad off the set where the wrist centre is on axis 1."""
    robot = km.load(name)
    q = on_sign_change(axis1_offset(robot), random_q(robot, np.random.default_rng(31), 200), 1)
    q = q[:150]
    assert len(q) == 150
    for delta in (0.0, 1e-12, 1e-10, 1e-8, 1e-6):
        moved = q.copy()
        moved[:, 1] += delta
        res = assert_honest(robot, moved, strict=delta >= 1e-6)
        if delta == 0.0:
            assert (res.status == "singular").all() and res.free[:, 0].all()
        if delta >= 1e-8:
            assert (res.status == "ok").all()
            assert (nearest(robot, res, moved) < SAME).mean() > 0.8


def test_folded_elbow_of_arm6_dh() -> None:
    """Issue 13 item 2: a2 = d4, q3 = ±π puts the wrist centre on the shoulder: q1, q2 free."""
    rng = np.random.default_rng(32)
    q = random_q(ARM6, rng, 400)
    q[:200, 2] = PI
    q[200:, 2] = -PI
    res = assert_honest(ARM6, q, strict=False)
    assert (res.status == "singular").all()
    assert (res.free[:, :3] == [True, True, False]).all()
    for delta in (1e-12, 1e-10, 1e-8, 1e-6):  # unfolding the elbow
        moved = q[:100].copy()
        moved[:, 2] -= delta * np.sign(moved[:, 2])
        assert_honest(ARM6, moved, strict=delta >= 1e-6)
    stretched = q[:100].copy()
    stretched[:, 2] = 0.0  # the other fold: a double root is one solution
    res = assert_honest(ARM6, stretched, strict=False)
    assert (res.count <= 4).all()


@pytest.mark.parametrize("where", ["a", "alpha", "offset", "d"])
def test_stanford_type_arm_with_joint_2_offset_by_1e_10(where: str) -> None:
    """Issue 13 item 5: ``not_found`` before."""
    joint2 = {"d": 0.154, "a": 0.0, "alpha": PI / 2, "offset": 0.0}
    joint2[where] += 1e-10
    rows: list[Revolute | Prismatic] = [
        Revolute(d=0.412, alpha=-PI / 2),
        Revolute(**joint2),
        Prismatic(theta=-PI / 2, a=0.0203),
        Revolute(alpha=-PI / 2),
        Revolute(alpha=PI / 2),
        Revolute(d=0.263),
    ]
    robot = Robot.from_dh(rows, name="stanford, offset joint 2", convention="standard")
    assert km.classify(robot).kind == "rrp-spherical-wrist"
    rng = np.random.default_rng(33)
    q = random_q(robot, rng, 200)
    res = assert_honest(robot, q)
    assert res.method == "analytic:rrp-spherical-wrist" and (res.status == "ok").all()


@pytest.mark.parametrize("far", [1.4e154, 1e300])
def test_huge_targets_are_unreachable_with_their_gap(far: float) -> None:
    """Issue 13 item 6: ``OverflowError`` before, single target and batch of one."""
    T = np.eye(4)
    T[0, 3] = far
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no overflow warning either
        one = PUMA.ik(T)
        batch = PUMA.ik(T[None])
    assert one.status == "unreachable" and one.gap is not None and one.gap >= 0.99 * far
    assert batch.status[0] == "unreachable" and batch.gap[0] == one.gap
    assert one.message == batch[0].message


def test_readme_arm_wrist_centre_on_axis_1() -> None:
    """The README's arm6-dh example: q1 is free. Its representatives are q1 = 0
    and the q1 turning axis 4 towards the tool's axis (least bent wrist); the
    generating q is the q1 = 0 representative of the target turned by -q1."""
    q = np.radians([30, 20, -40, 10, 60, -20])
    T = ARM6.fk(q)
    res = ARM6.ik(T)
    assert res.status == "singular" and res.free_joints == (0,)
    assert "q1 free" in res.message
    reps = res.solutions
    zero = np.abs(reps[:, 0]) < 1e-12
    assert zero.sum() == 4 and (~zero).sum() == 4
    # the facing representatives bend the wrist least over the whole family
    h, _ = ARM6.joint_axes(reps)
    bend = np.arccos(np.clip(np.sum(h[:, 3] * T[:3, 2], axis=-1), -1, 1))
    for rep, b in zip(reps[~zero], bend[~zero], strict=True):
        family = np.tile(rep, (721, 1))
        family[:, 0] = np.linspace(-PI, PI, 721)
        hf, _ = ARM6.joint_axes(family)
        assert b <= np.arccos(np.clip(hf[:, 3] @ T[:3, 2], -1, 1)).min() + 1e-9
    c, s = math.cos(-q[0]), math.sin(-q[0])
    turned = np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]) @ T
    q_turned = np.concatenate([[0.0], q[1:]])
    again = ARM6.ik(turned)
    assert again.status == "singular"
    assert joint_distance(ARM6, again.solutions, q_turned).min() < 1e-9


# ------------------------------------------------------- random arms (hypothesis)
@st.composite
def wrist_arms(draw: st.DrawFn) -> Robot:
    """Arms of the class with their degenerate geometries built in.

    A meeting shoulder (PUMA, arm6-dh and their kin): equal upper arm and
    forearm (the elbow folds onto the shoulder), offsets of 0 or 1e-10 where
    DH tables have zeros, twists of ±90° (axes 4 and 6 can line up), either
    convention, any base and tool.
    """
    length = st.floats(0.2, 0.6)
    tiny = st.sampled_from([0.0, 1e-10, -1e-10])
    sign = st.sampled_from([-1.0, 1.0])
    upper = draw(length)
    fore = upper if draw(st.booleans()) else draw(length)
    offset = st.sampled_from([0.0, PI / 2, -PI / 2, 0.3])
    rows = [
        Revolute(d=draw(length), a=draw(tiny), alpha=draw(sign) * PI / 2, offset=draw(offset)),
        Revolute(d=draw(tiny), a=upper, alpha=draw(tiny), offset=draw(offset)),
        Revolute(d=draw(tiny), a=draw(tiny), alpha=draw(sign) * PI / 2, offset=draw(offset)),
        Revolute(d=fore, alpha=draw(sign) * PI / 2, offset=draw(offset)),
        Revolute(alpha=draw(sign) * PI / 2, offset=draw(offset)),
        Revolute(d=draw(st.floats(0.0, 0.2)), offset=draw(offset)),
    ]
    robot = Robot.from_dh(
        rows, base=draw(transforms()), tool=draw(transforms()), name="random", convention="standard"
    )
    if draw(st.booleans()):
        robot = robot.to_convention("modified")
    return robot


@settings(max_examples=25, deadline=None, database=None, derandomize=True)
@given(wrist_arms(), st.integers(0, 2**32 - 1), st.sampled_from(["axis 1", "wrist", "fold"]))
def test_random_arms_on_and_off_their_singular_sets(robot: Robot, seed: int, where: str) -> None:
    assert km.classify(robot).kind == "spherical-wrist-6R"
    rng = np.random.default_rng(seed)
    q = random_q(robot, rng, 12)
    assert_honest(robot, q, strict=False)  # generic configurations (a few near a set)
    f = {"axis 1": axis1_offset(robot), "wrist": wrist_alignment(robot), "fold": fold(robot)}
    j = {"axis 1": 1, "wrist": 4, "fold": 2}[where]
    on = on_sign_change(f[where], q, j)
    for delta in (0.0, 1e-12, 1e-10, 1e-8, 1e-6):
        moved = on.copy()
        moved[:, j] += delta
        assert_honest(robot, moved, strict=delta >= 1e-6)


@st.composite
def any_wrist_arms(draw: st.DrawFn) -> Robot:
    """Every shoulder of the class (meeting, parallel, skew; joint 3 R with axes 2 ∥ 3,
    R, or a slide), with an entry of joints 1-3 nudged by 1e-10 (an offset between
    axes meant to meet, a twist between axes meant parallel) or an upper arm as
    long as the forearm, either convention, any base and tool.

    (A wrist whose axes miss each other by 1e-10 is no spherical wrist: it is
    solved as one and polished by the check, which cannot always finish the
    job at its folds; see the README.)
    """
    shoulder, joint3 = draw(st.sampled_from(GEOMETRIES))
    seed = draw(st.integers(0, 2**32 - 1))
    robot = random_wrist_arm(np.random.default_rng(seed), shoulder, joint3)
    rows = list(robot.links)
    change = draw(st.sampled_from(["none", "a1", "d2", "twist2", "equal"]))
    if change == "a1":  # axes 1 and 2 meet but for 1e-10
        rows[0] = dataclasses.replace(rows[0], a=rows[0].a + 1e-10)
    elif change == "d2":
        rows[1] = dataclasses.replace(rows[1], d=rows[1].d + 1e-10)
    elif change == "twist2":  # axes 2 and 3 parallel but for 1e-10
        rows[1] = dataclasses.replace(rows[1], alpha=rows[1].alpha + 1e-10)
    elif change == "equal" and isinstance(rows[3], Revolute):
        rows[3] = dataclasses.replace(rows[3], d=math.copysign(abs(rows[1].a), rows[3].d))
    return Robot.from_dh(
        rows, convention=robot.convention, base=robot.base, tool=robot.tool, name="random"
    )


@settings(max_examples=20, deadline=None, database=None, derandomize=True)
@given(any_wrist_arms(), st.integers(0, 2**32 - 1), st.sampled_from(["wrist", "fold"]))
def test_every_shoulder_on_and_off_its_folds(robot: Robot, seed: int, where: str) -> None:
    if closed_form(robot.chain, "pose") is None:  # a nudge made joints 1-3 degenerate
        return
    rng = np.random.default_rng(seed)
    q = random_q(robot, rng, 10)
    assert_honest(robot, q, strict=False)
    f = wrist_alignment(robot) if where == "wrist" else fold(robot)
    j = 4 if where == "wrist" else 2
    on = on_sign_change(f, q, j)
    for delta in (0.0, 1e-10, 1e-8, 1e-6):
        moved = on.copy()
        moved[:, j] += delta
        assert_honest(robot, moved, strict=delta >= 1e-6)


# ------------------------------------------------------------ batch vs single
def test_batch_equals_single_solution_by_solution_and_message_by_message() -> None:
    rng = np.random.default_rng(34)
    lo, hi = PUMA.qlim.T
    q = rng.uniform(0.9 * lo, 0.9 * hi, (8, 6))  # within the limits
    q[2, 4] = 0.0  # wrist singular
    T = PUMA.fk(q)
    T[3, :3, 3] = [3.0, 0.0, 0.0]  # unreachable
    T[4, :3, 3] = [2e300, 0.0, 0.0]  # far beyond
    reachable_out_of_limits = PUMA.fk(np.array([0.3, -0.6, 0.2, 0.5, 0.9, -0.4]))
    tight = PUMA.with_limits([(-0.1, 0.1)] * 6)
    for robot, targets in ((PUMA, T), (tight, np.stack([reachable_out_of_limits, T[0]]))):
        many = robot.ik(targets)
        for i, Ti in enumerate(targets):
            one = robot.ik(Ti)
            assert str(one.status) == many.status[i] and one.message == many[i].message
            np.testing.assert_array_equal(one.solutions, many[i].solutions)
            np.testing.assert_array_equal(one.out_of_limits, many[i].out_of_limits)
            assert one.branches == many[i].branches and one.free_joints == many[i].free_joints
    assert set(PUMA.ik(T).status) == {"ok", "singular", "unreachable"}
    assert tight.ik(reachable_out_of_limits).status == "out_of_limits"


@pytest.mark.parametrize(("factor", "free"), [(0.5, True), (2.0, False)])
def test_singular_tol_decides_when_q1_is_free(factor: float, free: bool) -> None:
    """A target translated off the README's singular pose by ``factor`` · SINGULAR_TOL · size."""
    T = ARM6.fk(np.radians([30, 20, -40, 10, 60, -20]))
    scale = _core_testing.decoupled.arm_point_values(solver(ARM6).params.arm)["scale"]
    res = ARM6.ik(moved_target(T, np.array([factor * SINGULAR_TOL * scale, 0.0, 0.0])))
    assert (res.status == "singular") == free and (0 in res.free_joints) == free


@pytest.mark.parametrize(("factor", "near"), [(0.5, True), (2.0, False)])
def test_near_set_tol_flags_targets_near_axis_1(factor: float, near: bool) -> None:
    """A target ``factor`` · NEAR_SET_TOL · size off axis 1 is flagged near it, or not."""
    T = ARM6.fk(np.radians([30, 20, -40, 10, 60, -20]))
    scale = _core_testing.decoupled.arm_point_values(solver(ARM6).params.arm)["scale"]
    shifted = moved_target(T, np.array([factor * NEAR_SET_TOL * scale, 0.0, 0.0]))
    assert near_flags(ARM6, shifted[None])[0] == near
    assert ARM6.ik(shifted).status == "ok"


@pytest.mark.parametrize(("factor", "candidate"), [(0.5, True), (2.0, False)])
def test_near_tol_keeps_a_double_root_just_past_the_stretched_arm(
    factor: float, candidate: bool
) -> None:
    """A radicand just below 0 (by NEAR_TOL at most) is a double root for the check to judge."""
    arm = _core_testing.decoupled.arm_point_values(solver(PUMA).params.arm)
    beta, dmax = arm["beta"], arm["dmax"]
    p1 = arm["p1"]  # where axes 1 and 2 meet
    q = np.array([0.3, -0.6, beta, 0.5, 0.9, -0.4])  # stretched: |wrist centre - p1| = Dmax
    T = PUMA.fk(q)  # the PUMA's wrist centre is its flange origin
    assert np.linalg.norm(T[:3, 3] - p1) == pytest.approx(dmax, rel=1e-12)
    # the fold's signed distance Dmax - D against NEAR_TOL · (Dmax + D)
    excess = factor * NEAR_TOL * 2 * dmax
    radial = (T[:3, 3] - p1) / dmax
    res = PUMA.ik(moved_target(T, excess * radial), respect_limits=False)
    assert res.status == "unreachable"
    assert res.gap == pytest.approx(excess, rel=1e-3)
    assert math.isfinite(res.nearest_error[0]) == candidate


@pytest.mark.parametrize(("sine", "singular"), [(0.5, True), (2.0, False)])
def test_wrist_singular_tol(sine: float, singular: bool) -> None:
    q = np.array([0.3, -0.6, 0.2, 0.5, sine * WRIST_SINGULAR_TOL, -0.4])
    res = PUMA.ik(PUMA.fk(q), respect_limits=False)
    assert (res.status == "singular") == singular
    assert (res.free_joints == (3, 5)) == singular


@pytest.mark.parametrize(("coordinate", "early"), [(0.5, False), (2.0, True)])
def test_huge_reach_switches_to_the_coordinate_gap(coordinate: float, early: bool) -> None:
    """Below HUGE_REACH the gap uses |d|; beyond it, its largest coordinate (no squares)."""
    x = coordinate * HUGE_REACH
    T = np.eye(4)
    T[:3, 3] = [x, x, x]
    res = PUMA.ik(T)
    assert res.status == "unreachable" and res.gap is not None
    expected = x if early else math.sqrt(3.0) * x
    assert res.gap == pytest.approx(expected, rel=1e-9)


def test_a_singular_wrist_family_within_the_limits_is_not_out_of_limits() -> None:
    """q4 + q6 = 1.7 with both limited to ±1: the representative q4 = 0 would be
    outside; the family's member (1.0, 0.7) is not."""
    tight = PUMA.with_limits([None, None, None, (-1.0, 1.0), None, (-1.0, 1.0)])
    q = np.array([0.3, -0.6, 0.2, 0.8, 0.0, 0.9])
    T = tight.fk(q)
    res = tight.ik(T)
    assert res.status == "singular" and res.free_joints == (3, 5)
    arm = np.abs(np.angle(np.exp(1j * (res.solutions[:, :3] - q[:3])))).max(axis=1) < 1e-9
    rep = res.solutions[arm]  # the position branch of q
    assert len(rep) == 1 and rep[0, 3] + rep[0, 5] == pytest.approx(1.7, abs=1e-9)
    assert (np.abs(rep[0, 3:]) <= 1.0 + 1e-12).all()
    wide = PUMA.ik(T)  # without those limits the representative keeps q4 = 0
    arm = np.abs(np.angle(np.exp(1j * (wide.solutions[:, :3] - q[:3])))).max(axis=1) < 1e-9
    assert arm.sum() == 1 and wide.solutions[arm][0, 3] == 0.0
