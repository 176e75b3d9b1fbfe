"""robot.ik(T, fixed={joint: value}): every solution with a joint held at a value.

Each solution is checked by the whole arm's forward kinematics (not the locked
arm's), and its locked entry must equal the value exactly.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from support.helpers import assert_transform_close, random_7r

import kinematica as km
from kinematica.errors import KinematicaError
from kinematica.ik import IKBatchResult, IKOptions, IKResult
from kinematica.ik.fixed import joint_parameter
from kinematica.ik.parameter import LOCKED_CACHE, locked_chain

TOL = 1e-10  # the default acceptance tolerance of robot.ik (m, rad)


def assert_locked(robot: km.Robot, res: IKResult, T: np.ndarray, k: int, value: float) -> None:
    """Every solution (within and outside the limits) reaches T and holds q_k = value."""
    for Q in (res.solutions, res.out_of_limits):
        assert Q.shape[1:] == (robot.dof,)
        np.testing.assert_array_equal(Q[:, k], value)
        if len(Q):
            assert_transform_close(robot.fk(Q), np.broadcast_to(T, (len(Q), 4, 4)), atol=TOL)
    assert res.parameter == (robot.joint_names[k], value)


def contains(robot: km.Robot, solutions: np.ndarray, q: np.ndarray, tol: float = 1e-9) -> bool:
    d = np.abs(solutions - q)
    d = np.where(robot.is_prismatic, d, np.abs(np.remainder(d + math.pi, 2 * math.pi) - math.pi))
    return bool(len(solutions)) and bool((d.max(axis=1) <= tol).any())


@pytest.mark.parametrize("name", ["panda", "iiwa14", "random"])
@pytest.mark.parametrize("k", [0, 3, 6])
def test_locking_first_middle_last_joint_reaches_the_pose(name: str, k: int) -> None:
    robot = random_7r(4) if name == "random" else km.load(name)
    for q in robot.random_q(3, seed=k + 10):
        T = robot.fk(q)
        res = robot.ik(T, fixed={k: float(q[k])}, respect_limits=False)
        assert isinstance(res, IKResult)
        # an SRS arm's elbow held: the arm angle's circle (tests/ik/test_held_continuum.py)
        assert res.status == ("singular" if (name, k) == ("iiwa14", 3) else "ok"), res.message
        assert_locked(robot, res, T, k, float(q[k]))
        if res.complete:  # a closed form gives every solution: the one that made T too
            assert contains(robot, res.solutions, q), res.solutions


def test_the_iiwa_locked_at_its_first_joint_is_a_spherical_wrist_with_every_solution() -> None:
    # joints 2..7 of the iiwa: 5, 6, 7 meet, a closed form on this and every later branch
    robot = km.load("iiwa14")
    q = np.array([0.3, 0.5, -0.2, -1.2, 0.4, 0.9, 0.2])
    res = robot.ik(robot.fk(q), fixed={0: 0.3}, respect_limits=False)
    assert res.method.startswith("analytic:") and res.complete
    assert res.count == 8
    assert contains(robot, res.solutions, q)


def test_names_qn_and_indices_name_the_same_joint() -> None:
    rows = [km.Revolute(d=0.3, alpha=-math.pi / 2, name="base")] + [
        km.Revolute(d=0.2 * (i % 2), alpha=(-1) ** i * math.pi / 2, name=f"j{i}")
        for i in range(2, 8)
    ]
    robot = km.Robot.from_dh(rows, convention="standard")
    assert robot.joint_names == ("base", "j2", "j3", "j4", "j5", "j6", "j7")
    assert km.load("panda").joint_names == tuple(f"q{i}" for i in range(1, 8))
    q = robot.random_q(1, seed=3)[0]
    T = robot.fk(q)
    answers = [robot.ik(T, fixed={key: float(q[6])}, seed=1) for key in (6, "j7", "q7", "Q7")]
    for res in answers:
        assert isinstance(res, IKResult)
        np.testing.assert_array_equal(res.solutions, answers[0].solutions)
        assert res.parameter == ("j7", float(q[6]))
    by_options = robot.ik(T, options=IKOptions(fixed={"j7": float(q[6])}, seed=1))
    np.testing.assert_array_equal(by_options.solutions, answers[0].solutions)


@pytest.mark.parametrize(
    ("fixed", "match"),
    [
        ({7: 0.1}, "index 7 is out of range: 0..6"),
        ({-1: 0.1}, "index -1 is out of range"),
        ({"q8": 0.1}, "no joint is named 'q8'"),
        ({"elbow": 0.1}, "no joint is named 'elbow'"),
        ({1.5: 0.1}, "by a 0-based index or a name"),
        ({True: 0.1}, "by a 0-based index or a name"),
        ({6: math.nan}, "q7 must be finite"),
        ({6: math.inf}, "q7 must be finite"),
        ({6: "0.1"}, "must be a number"),
        ({6: 3.0}, r"q7 = 3 rad is outside its limits \[-2.8973, 2.8973\] rad"),
        ({5: 0.1, 6: 0.1}, "one joint and its value"),
        ({}, "one joint and its value"),
        ([6, 0.1], "one joint and its value"),
    ],
)
def test_bad_keys_and_values_say_what_is_accepted(fixed: object, match: str) -> None:
    robot = km.load("panda")
    T = robot.fk(np.array([0.1, 0.2, 0.3, -1.5, 0.1, 1.2, 0.4]))
    with pytest.raises(KinematicaError, match=match) as info:
        robot.ik(T, fixed=fixed)  # type: ignore[arg-type]
    assert info.value.arg == "fixed"


def test_a_value_beyond_the_limits_is_solved_when_limits_are_ignored() -> None:
    robot = km.load("iiwa14")
    q = np.array([0.3, 0.5, -0.2, -1.2, 0.4, 0.9, 0.2])
    T = robot.fk(q)
    beyond = 3.0  # q1's limits: ±170 deg = ±2.967 rad
    res = robot.ik(T, fixed={0: beyond}, respect_limits=False)
    assert res.count and res.parameter == ("q1", beyond)
    assert_locked(robot, res, T, 0, beyond)


def test_a_single_joint_arm_has_nothing_left_to_solve() -> None:
    arm = km.Robot.from_dh([km.Revolute(a=1.0)], convention="standard")
    with pytest.raises(KinematicaError, match="one joint") as info:
        arm.ik(np.array([1.0, 0.0, 0.0]), fixed={0: 0.0})
    assert info.value.arg == "fixed"


def test_locking_a_6r_joint_leaves_a_5r_arm_solved_for_the_pose() -> None:
    puma = km.load("puma560")
    q = np.array([0.3, -0.6, 0.2, 0.5, 0.9, -0.4])
    T = puma.fk(q)
    for k in (0, 2, 5):
        res = puma.ik(T, fixed={k: float(q[k])}, respect_limits=False)
        assert res.status == "ok", res.message
        assert_locked(puma, res, T, k, float(q[k]))


def test_position_targets_hold_the_joint_too() -> None:
    robot = km.load("iiwa14")
    q = np.array([0.3, 0.5, -0.2, -1.2, 0.4, 0.9, 0.2])
    p = robot.fk(q)[:3, 3]
    res = robot.ik(p, fixed={6: 0.2}, seed=2)
    assert res.count
    np.testing.assert_array_equal(res.solutions[:, 6], 0.2)
    np.testing.assert_allclose(
        robot.fk(res.solutions)[:, :3, 3], np.tile(p, (res.count, 1)), atol=TOL
    )


def test_unreachable_is_said_of_the_lock_not_of_the_arm() -> None:
    # q1 = 0 puts the iiwa's elbow on a circle in the x-z plane: this pose, to the
    # side, is out of reach there, though the whole arm reaches it (it came from fk)
    robot = km.load("iiwa14")
    T = robot.fk(np.array([1.4, 0.9, 0.3, -1.0, 0.2, 0.6, 0.1]))
    res = robot.ik(T, fixed={0: 0.0})
    assert res.status == "unreachable"
    assert res.message.startswith("unreachable with q1 = 0: ")
    assert "other values of q1 may reach it" in res.message
    assert res.parameter == ("q1", 0.0)
    assert robot.ik(T, method="numeric", seed=1).success  # the arm does reach it
    html = res._repr_html_()
    assert "q1 held at 0" in html


def test_a_batch_equals_single_calls_at_the_first_and_a_middle_joint() -> None:
    robot = km.load("iiwa14")
    Q = robot.random_q(6, seed=8)
    T = robot.fk(Q).reshape(2, 3, 4, 4)
    for k in (0, 3):
        many = robot.ik(T, fixed={k: 0.35})
        assert isinstance(many, IKBatchResult)
        assert many.solutions.shape[-1] == 7
        np.testing.assert_array_equal(many.parameter[1], np.full((2, 3), 0.35))  # type: ignore[index]
        for idx in np.ndindex(2, 3):
            one = robot.ik(T[idx], fixed={k: 0.35})
            got = many[idx]
            assert str(got.status) == str(one.status)
            assert got.message == one.message
            assert got.branches == one.branches
            np.testing.assert_allclose(got.solutions, one.solutions, atol=1e-12)
            np.testing.assert_allclose(got.out_of_limits, one.out_of_limits, atol=1e-12)
            assert got.parameter == one.parameter == ("q1" if k == 0 else "q4", 0.35)


def test_a_middle_joint_at_a_value_per_target_equals_single_calls() -> None:
    robot = km.load("iiwa14")
    Q = robot.random_q(4, seed=9)
    T = robot.fk(Q)
    T[2, 0, 0] = np.nan  # one malformed row: invalid, the others solved
    joint = joint_parameter(robot.chain, 3)
    many = joint.solve(robot.chain, T, Q[:, 3], IKOptions())
    assert isinstance(many, IKBatchResult)
    assert many.status[2] == "invalid"
    for i in (0, 1, 3):
        one = robot.ik(T[i], fixed={3: float(Q[i, 3])})
        assert many[i].message == one.message
        np.testing.assert_allclose(many[i].solutions, one.solutions, atol=1e-12)
        assert_locked(robot, many[i], T[i], 3, float(Q[i, 3]))


@pytest.mark.parametrize(("extra", "kept"), [(LOCKED_CACHE - 1, True), (LOCKED_CACHE, False)])
def test_locked_arms_are_kept_least_recently_used_first_out(extra: int, kept: bool) -> None:
    panda = km.load("panda")
    chain = km.Robot.from_dh(panda.links, convention="modified").chain  # its own cache
    first = locked_chain(chain, 3, -1.0)
    assert locked_chain(chain, 3, -1.0) is first
    for i in range(extra):
        locked_chain(chain, 3, -1.5 + 0.01 * i)
    assert (locked_chain(chain, 3, -1.0) is first) == kept


def test_a_free_joint_is_held_at_its_angle_wrapped_into_a_turn() -> None:
    robot = random_7r(6)  # no limits: its angles come out in (-π, π]
    q = robot.random_q(1, seed=2)[0]
    q[3] = 3.5 - 2 * math.pi
    res = robot.ik(robot.fk(q), fixed={3: 3.5}, seed=1)
    assert res.parameter == ("q4", 3.5 - 2 * math.pi)
    assert res.count and np.all(res.solutions[:, 3] == 3.5 - 2 * math.pi)


def test_q0_of_the_whole_arm_and_a_closed_form_asked_of_the_locked_arm() -> None:
    panda = km.load("panda")
    T = panda.fk(np.array([0.1, 0.2, 0.3, -1.5, 0.1, 1.2, 0.4]))
    with pytest.raises(km.errors.DimensionError, match="q0 must hold 7 joint values") as info:
        panda.ik(T, fixed={6: 0.4}, q0=np.zeros(6))
    assert info.value.arg == "q0"
    with pytest.raises(KinematicaError, match="the arm left with q7 held") as bad:
        panda.ik(T, fixed={6: 0.4}, method="analytic", mask=[1, 1, 1, 1, 1, 0])
    assert bad.value.arg == "method"


def test_free_joints_of_a_singular_answer_are_named_in_the_whole_arm() -> None:
    # q6 = 0 lines up axes 5 and 7: the locked arm's joints 4 and 6 are q5 and q7
    robot = km.load("iiwa14")
    T = robot.fk(np.array([0.3, 0.5, -0.2, -1.2, 0.4, 0.0, 0.2]))
    res = robot.ik(T, fixed={0: 0.3})
    assert res.status == "singular" and res.free_joints == (4, 6)
    assert "(q5, q7 free)" in res.message
    many = robot.ik(np.stack([T, T]), fixed={0: 0.3})
    np.testing.assert_array_equal(many.free[0], [0, 0, 0, 0, 1, 0, 1])
    assert many[1].free_joints == (4, 6)


@pytest.mark.parametrize("first", [True, False])
def test_a_slide_at_either_end_is_held_by_moving_the_targets(first: bool) -> None:
    # a PUMA on a rail (a slide before joint 1), or with a slide after its flange
    puma = km.load("puma560")
    slide = km.Prismatic(theta=0.0, a=0.0, alpha=0.0, qlim=(-1.0, 1.0))
    rows = [slide, *puma.links] if first else [*puma.links, slide]
    robot = km.Robot.from_dh(rows, base=puma.base, tool=puma.tool, convention="standard")
    k = 0 if first else 6
    Q = np.array([[0.3, -0.6, 0.2, 0.5, 0.9, -0.4], [0.1, -0.2, 0.4, -0.5, 0.6, 0.3]])
    Q = np.insert(Q, k, 0.25, axis=1)
    T = robot.fk(Q)
    many = robot.ik(T, fixed={k: 0.25}, respect_limits=False)
    assert isinstance(many, IKBatchResult)
    for i in range(2):
        one = robot.ik(T[i], fixed={k: 0.25}, respect_limits=False)
        assert one.method.startswith("analytic:") and one.count == 8, one.message
        assert_locked(robot, one, T[i], k, 0.25)
        assert contains(robot, one.solutions, Q[i])
        np.testing.assert_allclose(many[i].solutions, one.solutions, atol=1e-12)


@pytest.mark.parametrize("k", [0, 6])
def test_a_mask_is_read_in_the_frames_it_was_given(k: int) -> None:
    # only x matters: every answer puts the tool at x, whatever y and z, with q_k held
    robot = km.load("iiwa14")
    q = np.array([0.3, 0.5, -0.2, -1.2, 0.4, 0.9, 0.2])
    T = robot.fk(q)
    res = robot.ik(T, fixed={k: float(q[k])}, mask=[1, 0, 0, 0, 0, 0], seed=1)
    assert res.count
    np.testing.assert_array_equal(res.solutions[:, k], q[k])
    np.testing.assert_allclose(robot.fk(res.solutions)[:, 0, 3], T[0, 3], atol=TOL)


def slide_at_the_end(offset: float = 0.0) -> km.Robot:
    """A PUMA whose flange turns about a 7th joint; the tool ``offset`` m off its axis."""
    puma = km.load("puma560")
    rows = [*puma.links, km.Revolute(d=0.05)]
    return km.Robot.from_dh(rows, tool=np.array(km.transl(offset, 0.0, 0.1)), convention="standard")


def test_the_last_joint_at_a_value_per_target_equals_single_calls() -> None:
    robot = slide_at_the_end(0.2)
    Q = np.array(
        [[0.3, -0.6, 0.2, 0.5, 0.9, -0.4, 0.2], [0.1, -0.2, 0.4, -0.5, 0.6, 0.3, -1.1],
         [0.2, -0.4, 0.1, 0.3, 0.5, 0.1, 2.5]]
    )  # fmt: skip
    T = robot.fk(Q)
    T[2, :3, 3] = [3.0, 0.0, 0.0]  # far out of reach: a gap, the tool point's own
    joint = joint_parameter(robot.chain, 6)
    many = joint.solve(robot.chain, T, Q[:, 6], IKOptions(q0=Q))
    assert isinstance(many, IKBatchResult)
    assert many.status[2] == "unreachable"
    for i in range(3):
        one = robot.ik(T[i], fixed={6: float(Q[i, 6])}, q0=Q[i])
        got = many[i]
        assert str(got.status) == str(one.status)
        assert got.message == one.message
        assert got.gap == one.gap
        assert got.parameter == one.parameter
        np.testing.assert_allclose(got.solutions, one.solutions, atol=1e-12)
        if one.count:
            assert_locked(robot, got, T[i], 6, float(Q[i, 6]))
