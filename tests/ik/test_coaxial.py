"""6R arms with two consecutive joints on one line: a continuum at every pose they reach.

Checked against the geometry by hand (only q_a ± q_(a+1) counts, so the configuration
that made a pose has its other joints and that sum among the representatives), by
forward kinematics on the real arm (every representative exact), and against the
numeric search started from random guesses on the real arm: every configuration it
finds lies on one of the continua given, and on random poses it finds nothing.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinematica as km
from kinematica.dh.joints import Revolute
from kinematica.dh.lines import AXIS_EXACT_TOL
from kinematica.ik.analytic.sampling import random_transform
from kinematica.ik.choice import pose_choice
from kinematica.ik.coaxial import (
    AIM_TOL,
    METHOD,
    CoaxialPair,
    coaxial_pair,
    turn_axis,
    virtual_arm,
)

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")

PI = math.pi
#: Representatives reach their target to this on the real arm (m, rad).
FK_TOL = 1e-10
#: The generating configuration's joints and sum are recovered to this (rad).
MATCH = 1e-7


def _arm(rng: np.random.Generator, k: int, convention: str, twist: float) -> km.Robot:
    """A random 6R arm whose joints k, k + 1 (0-based) are on one line (twist 0 or π)."""
    u = rng.uniform
    rows = [
        Revolute(d=u(-0.4, 0.4), a=u(-0.4, 0.4), alpha=u(-PI, PI), offset=u(-PI, PI))
        for _ in range(6)
    ]
    r = k if convention == "standard" else k + 1  # the row holding a, α between them
    rows[r] = Revolute(d=rows[r].d, a=0.0, alpha=twist, offset=rows[r].offset)
    return km.Robot.from_dh(rows, convention=convention)


def _wrapped(d: np.ndarray) -> np.ndarray:
    return np.abs(np.remainder(d + PI, 2 * PI) - PI)


def _reaches(robot: km.Robot, Q: np.ndarray, T: np.ndarray) -> None:
    F = robot.fk(Q)
    assert np.linalg.norm(F[:, :3, 3] - T[:3, 3], axis=1).max() <= FK_TOL
    assert max(km.rotation_angle(f[:3, :3], T[:3, :3]) for f in F) <= FK_TOL


def _on_continuum(Q: np.ndarray, q: np.ndarray, pair: CoaxialPair) -> bool:
    """A row of Q has q's joints outside the pair and q's sum of the pair."""
    others = [j for j in range(6) if j not in (pair.first, pair.second)]
    same = (_wrapped(Q[:, others] - q[others]).max(axis=1) <= MATCH) & (
        _wrapped(pair.merged(Q) - pair.merged(q[None])) <= MATCH
    )
    return bool(same.any())


CASES = [(k, conv, tw) for k in range(5) for conv in ("standard", "modified") for tw in (0.0, PI)]


@pytest.mark.parametrize(("k", "convention", "twist"), CASES)
def test_a_pose_made_by_fk_is_a_continuum_of_the_pair(
    k: int, convention: str, twist: float
) -> None:
    rng = np.random.default_rng(100 + 10 * k + (convention == "modified") * 5 + int(twist > 0))
    robot = _arm(rng, k, convention, twist)
    pair = coaxial_pair(robot.chain)
    assert pair == CoaxialPair(k, 1.0 if twist == 0.0 else -1.0)
    for _ in range(3):
        q = rng.uniform(-PI, PI, 6)
        T = robot.fk(q)
        res = robot.ik(T)
        assert res.status == "singular", res.message
        assert res.method == METHOD
        assert res.free_joints == (k, k + 1)
        assert res.free_names == (f"q{k + 1}", f"q{k + 2}")
        assert res.complete
        assert np.all(res.solutions[:, k + 1] == 0.0)  # the second held at 0 (no limits)
        _reaches(robot, res.solutions, T)
        assert _on_continuum(res.solutions, q, pair)
        # the numeric search from random guesses lands on one of the continua given
        for seed in range(3):
            found = robot.ik(T, method="numeric", q0=rng.uniform(-PI, PI, 6), seed=seed)
            for s in found.solutions:
                assert _on_continuum(res.solutions, s, pair)


def test_random_poses_are_unreachable_and_the_search_agrees() -> None:
    rng = np.random.default_rng(21)
    for k in range(5):
        robot = _arm(rng, k, "standard", 0.0)
        for _ in range(4):
            T = random_transform(rng, 0.6)
            res = robot.ik(T)
            assert res.status == "unreachable", res.message
            assert res.method == METHOD and res.complete and not len(res.solutions)
            assert "5 degrees of freedom" in res.message
            found = robot.ik(T, method="numeric", seed=1)
            assert found.status != "ok" and not len(found.solutions)


def test_far_targets_are_unreachable_with_a_gap() -> None:
    robot = _arm(np.random.default_rng(3), 2, "standard", 0.0)
    T = np.eye(4)
    T[:3, 3] = (50.0, 0.0, 0.0)
    res = robot.ik(T)
    assert res.status == "unreachable"
    assert res.gap is not None and 40.0 < res.gap < 50.0  # the arm is under 10 m long


def test_limits_hold_the_pair_within_both() -> None:
    rng = np.random.default_rng(8)
    robot = _arm(rng, 1, "standard", 0.0)
    lims = np.tile([-PI, PI], (6, 1))
    lims[1] = (-0.5, 0.5)  # the sum of q2 + q3 beyond ±0.5 needs q3 away from 0
    lims[2] = (0.3, 1.5)
    robot = robot.with_limits(lims)
    q = np.array([0.2, 0.4, 1.2, -0.3, 0.5, 1.0])
    T = robot.fk(q)
    res = robot.ik(T)
    assert res.status == "singular", res.message
    assert _on_continuum(res.solutions, q, CoaxialPair(1, 1.0))
    assert np.all((res.solutions >= lims[:, 0]) & (res.solutions <= lims[:, 1]))
    # q3 as near 0 as the limits allow: its lower limit where q2 can take the rest
    row = res.solutions[_wrapped(res.solutions[:, 0] - q[0]) <= MATCH][0]
    assert row[2] == pytest.approx(max(0.3, row[1] + row[2] - 0.5))
    _reaches(robot, res.solutions, T)
    # a sum beyond both limits together (at most 0.5 + 1.5): outside the limits only
    q[1], q[2] = 1.0, 1.4
    far = robot.ik(robot.fk(q))
    assert far.status == "out_of_limits", far.message
    assert not len(far.solutions) and _on_continuum(far.out_of_limits, q, CoaxialPair(1, 1.0))


def test_a_batch_answers_as_one_call_each() -> None:
    rng = np.random.default_rng(9)
    robot = _arm(rng, 3, "modified", 0.0)
    q = rng.uniform(-PI, PI, (3, 6))
    poses = np.concatenate([robot.fk(q), random_transform(rng, 0.6)[None]])
    batch = robot.ik(poses)
    for i in range(4):
        one = robot.ik(poses[i])
        assert str(batch.status[i]) == str(one.status)
        got = batch[i]
        assert np.array_equal(got.solutions, one.solutions)


def test_the_virtual_arm_is_the_arm_with_the_second_joint_at_0() -> None:
    rng = np.random.default_rng(10)
    robot = _arm(rng, 2, "standard", PI)
    pair = coaxial_pair(robot.chain)
    assert pair is not None
    for line in (0, 1):
        arm = virtual_arm(robot.chain, pair, line)
        q5 = rng.uniform(-PI, PI, (4, 5))
        q = np.insert(q5, 3, 0.0, axis=1)
        got = arm.fk(np.concatenate([q5, np.zeros((4, 1))], axis=1))[0]
        np.testing.assert_allclose(got, robot.fk(q), atol=1e-13)


def test_a_pair_off_one_line_by_more_than_round_off_is_not_coaxial() -> None:
    rng = np.random.default_rng(11)
    for tilt, coaxial in ((0.5 * AXIS_EXACT_TOL, True), (1e3 * AXIS_EXACT_TOL, False)):
        robot = _arm(rng, 2, "standard", tilt)
        assert (coaxial_pair(robot.chain) is not None) is coaxial


def test_show_names_the_solver() -> None:
    robot = _arm(np.random.default_rng(12), 0, "standard", 0.0)
    choice = pose_choice(robot.chain)
    assert choice.method == METHOD and choice.reason is None
    assert robot.ik(robot.fk(np.zeros(6)), method="numeric").method == "numeric:lm"


@pytest.mark.parametrize(("pitch", "turn"), [(0.5 * AIM_TOL, True), (2.0 * AIM_TOL, False)])
def test_an_aimed_line_is_a_turn_of_pitch_within_aim_tol(pitch: float, turn: bool) -> None:
    rng = np.random.default_rng(13)
    z = rng.normal(size=3)
    z /= np.linalg.norm(z)
    c = rng.uniform(-0.3, 0.3, 3)
    phi = 0.7
    K = np.array([[0, -z[2], z[1]], [z[2], 0, -z[0]], [-z[1], z[0], 0]])
    R = np.eye(3) + math.sin(phi) * K + (1 - math.cos(phi)) * K @ K
    E = np.eye(4)
    E[:3, :3] = R
    # a slide along the line: the pitch test is relative to 1 + |t|
    E[:3, 3] = c - R @ c + pitch * (1.0 + np.linalg.norm(c - R @ c)) * z
    W = turn_axis(E)
    assert (W is not None) is turn
    if W is not None:  # the frame's z axis is the turn's line
        assert abs(abs(float(W[:3, 2] @ z)) - 1.0) < 1e-12
        assert np.linalg.norm(np.cross(W[:3, 3] - c, z)) < 1e-9


@pytest.mark.parametrize(("held", "pair"), [(1, (0, 2)), (3, (2, 4)), (5, (4, 6))])
def test_a_7r_arm_held_where_two_axes_become_one_line(held: int, pair: tuple[int, int]) -> None:
    robot = km.load("iiwa14")  # q2, q4 or q6 at 0 puts the axes either side on one line
    rng = np.random.default_rng(14 + held)
    for _ in range(2):
        q = rng.uniform(-1.2, 1.2, 7)
        q[held] = 0.0
        T = robot.fk(q)
        res = robot.ik(T, fixed={held: 0.0}, respect_limits=False)
        assert res.status == "singular", res.message
        assert (res.method, res.free_joints, res.parameter) == (METHOD, pair, (f"q{held + 1}", 0.0))
        F = robot.fk(res.solutions)
        assert np.linalg.norm(F[:, :3, 3] - T[:3, 3], axis=1).max() <= FK_TOL
        others = [j for j in range(7) if j not in pair]
        a, b = pair
        same = (_wrapped(res.solutions[:, others] - q[others]).max(axis=1) <= MATCH) & (
            _wrapped(res.solutions[:, a] + res.solutions[:, b] - q[a] - q[b]) <= MATCH
        )
        assert same.any()
