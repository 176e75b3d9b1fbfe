"""Arms near rank 5 (and 4, 3): the sweep's moved targets, its brackets, the two-scale Newton.

Checked independently of the solver: the moved target of an end joint held at 0 against
forward kinematics of the arm with that joint at its value (the identity the sweep rests
on); every answer by forward kinematics (1e-10) and against a search from random guesses;
a batch against single calls; the arm whose six axes nearly meet at one point (rank 3
nearby) found by the two-scale Newton where Newton and the search find nothing.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinematica as km
from kinematica.dh.joints import Revolute
from kinematica.ik.near_cut import cut_arm
from kinematica.ik.near_manifold import SLOW_GAP, slow_newton, slow_rank
from kinematica.ik.near_rank_five import METHOD, SAME_TOL
from kinematica.ik.near_sweep import MOVES_TOL, end_sweeps, moving_joints, newton
from kinematica.ik.rank_five import free_motion, rank_five, relative_sigma
from kinematica.ik.result import IKBatchResult, IKResult
from kinematica.ik.stack import pose_residuals

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")

PI = math.pi
#: Solutions reach their target to this (m, rad).
FK_TOL = 1e-10


def _shoulder_wrist(eps: float) -> km.Robot:
    """A spherical shoulder and wrist (rank 5), axis 2 moved off the shoulder by ``eps`` m."""
    R = Revolute
    rows = [
        R(d=0.3, a=0.0, alpha=PI / 2),
        R(d=eps, a=0.0, alpha=-PI / 2),
        R(d=0.5, a=0.1, alpha=PI / 2),
        R(d=0.4, a=0.0, alpha=-PI / 2),
        R(d=0.0, a=0.0, alpha=PI / 2),
        R(d=0.1, a=0.0, alpha=0.0),
    ]
    return km.Robot.from_dh(rows, convention="standard")


def _concurrent(eps: float) -> km.Robot:
    """Six axes through one point (rank 3), every twist and offset moved by ±``eps``."""
    R = Revolute
    signs = [1, -1, 1, 1, -1, 1]
    rows = [
        R(d=-0.07 + eps, a=eps, alpha=-PI / 2 + eps),
        R(d=-eps, a=eps, alpha=-PI / 2 - eps),
        R(d=eps, a=-eps, alpha=2.0091 + eps),
        R(d=-eps, a=eps, alpha=-PI / 2 + eps),
        R(d=eps, a=eps, alpha=0.4911 - eps),
        R(d=-0.279 + eps * signs[5], a=0.0, alpha=PI / 2),
    ]
    return km.Robot.from_dh(rows, convention="standard")


def _wrapped(d: np.ndarray) -> np.ndarray:
    return np.abs(np.remainder(d + PI, 2 * PI) - PI)


def _reaches(robot: km.Robot, Q: np.ndarray, T: np.ndarray) -> None:
    assert len(Q)
    err = pose_residuals(robot.chain, Q, T)
    assert err.max() <= FK_TOL


def test_an_end_joint_held_at_0_moves_the_target_as_fk_does() -> None:
    """FK(t, q') = G(t) FK(0, q') and FK(q', t) = FK(q', 0) H(t): the sweep's moved target
    solved at q' is the real arm's configuration with the joint at t."""
    robot = _shoulder_wrist(1e-6)
    five = rank_five(robot.chain)
    assert five is not None
    sweeps = end_sweeps(robot.chain, five.rank)
    assert {s.joint for s in sweeps} == {0, 5}
    rng = np.random.default_rng(3)
    for s in sweeps:
        q = rng.uniform(-PI, PI, 6)
        T = robot.fk(q)
        moved = s.moved(robot.chain, T[None], np.array([q[s.joint]]))[0]
        held = q.copy()
        held[s.joint] = 0.0
        assert np.abs(moved - robot.fk(held)).max() <= 1e-14 * 10
        real, theta, count = s.solve(robot.chain, T[None], np.array([q[s.joint]]), _tol())
        got = real[0, : count[0]]
        assert _wrapped(got - q).max(axis=1).min() <= 1e-6  # q itself, θ = 0
        assert np.abs(theta[0, np.argmin(_wrapped(got - q).max(axis=1))]) <= 1e-9


def _tol():  # type: ignore[no-untyped-def]
    from kinematica.ik.tolerance import parse_tolerance

    return parse_tolerance(None)


def test_moving_joints_tolerance_at_its_boundary() -> None:
    """On an arm with axes 2-5 parallel, joints 1 and 6 keep still along the near-continuum
    (shares of 1e-7 and less, far below MOVES_TOL 1e-3); joints 2-5 move (0.1 and more)."""
    R = Revolute
    rows = [
        R(d=0.3, a=0.0, alpha=PI / 2),
        R(d=0.0, a=0.4, alpha=1e-7),
        R(d=0.1, a=0.3, alpha=0.0),
        R(d=0.0, a=0.2, alpha=0.0),
        R(d=0.1, a=0.0, alpha=PI / 2),
        R(d=0.1, a=0.0, alpha=0.0),
    ]
    robot = km.Robot.from_dh(rows, convention="standard")
    five = rank_five(robot.chain)
    assert five is not None and not five.exact
    q = np.random.default_rng(1).uniform(-PI, PI, 6)
    share = free_motion(robot.chain, q, five.rank)
    assert share[[0, 5]].max() <= MOVES_TOL * 1e-3
    assert share[1:5].min() >= MOVES_TOL * 1e2
    assert set(moving_joints(robot.chain, five.rank)) == {1, 2, 3, 4}


@pytest.mark.parametrize("eps", [1e-9, 1e-7])
def test_near_rank_5_every_search_solution_and_the_generating_one(eps: float) -> None:
    robot = _shoulder_wrist(eps)
    rng = np.random.default_rng(8)
    for q in rng.uniform(-PI, PI, (3, 6)):
        T = robot.fk(q)
        res = robot.ik(T)
        assert res.method == METHOD and res.status in ("ok", "singular")
        _reaches(robot, res.solutions, T)
        sigma = float(relative_sigma(robot.chain, q))
        assert _wrapped(res.solutions - q).max(axis=1).min() <= 1e-6 + FK_TOL / sigma
        for s in rng.uniform(-PI, PI, (10, 6)):
            for f in robot.ik(T, method="numeric", q0=s).solutions:
                d = _wrapped(res.solutions - f).max(axis=1).min()
                assert d <= SAME_TOL + FK_TOL / float(relative_sigma(robot.chain, f))


def test_a_batch_answers_as_single_calls_do() -> None:
    robot = _shoulder_wrist(1e-7)
    Q = np.random.default_rng(4).uniform(-PI, PI, (4, 6))
    T = robot.fk(Q)
    batch = robot.ik(T)
    assert isinstance(batch, IKBatchResult)
    for i in range(len(Q)):
        one = robot.ik(T[i])
        assert isinstance(one, IKResult)
        got = batch[i]
        assert str(got.status) == str(one.status)
        np.testing.assert_allclose(got.solutions, one.solutions, atol=1e-12)


def test_near_rank_3_is_found_by_newton_in_two_scales() -> None:
    """Six axes within 1e-7 of one point: Newton from random guesses finds nothing; the
    two-scale Newton finds the generating configuration, and the answer is not
    ``not_found``."""
    robot = _concurrent(1e-7)
    assert slow_rank(robot.chain) == 3
    rng = np.random.default_rng(2)
    q = rng.uniform(-PI, PI, 6)
    T = robot.fk(q)
    seeds = rng.uniform(-PI, PI, (40, 6))
    plain = pose_residuals(robot.chain, newton(robot.chain, seeds, T), T)
    assert not (plain.max(axis=1) <= FK_TOL).any()
    res = robot.ik(T)
    assert isinstance(res, IKResult)
    assert res.method == METHOD and res.status == "ok" and not res.complete
    _reaches(robot, res.solutions, T)
    assert "two scales" in str(res.notes[-1])
    sigma = float(relative_sigma(robot.chain, q))
    assert _wrapped(res.solutions - q).max(axis=1).min() <= 1e-6 + FK_TOL / sigma
    slow = slow_newton(robot.chain, seeds, T, 3)
    err = pose_residuals(robot.chain, newton(robot.chain, slow, T), T)
    assert (err.max(axis=1) <= FK_TOL).any()


def test_slow_gap_at_its_boundary() -> None:
    """σ4 / σ1 of the nearly concurrent arm is 1e-6 and less (small: SLOW_GAP 1e-3), σ3 / σ1
    0.3 and more (large): a gap 1000x larger or smaller would misjudge one of them."""
    robot = _concurrent(1e-7)
    Q = np.random.default_rng(0).uniform(-PI, PI, (8, 6))
    from kinematica.ik.rank_five import scaled_jacobian

    s = np.linalg.svd(scaled_jacobian(robot.chain, Q), compute_uv=False)
    r = s / s[:, :1]
    assert r[:, 3].max() <= SLOW_GAP * 1e-3
    assert r[:, 2].min() >= SLOW_GAP * 1e2


def _parallel_2_5(eps: float) -> km.Robot:
    """Axes 2-5 parallel (rank 5: joints 1 and 6 keep still along its continua), α2 = eps."""
    R = Revolute
    rows = [
        R(d=0.3, a=0.0, alpha=PI / 2),
        R(d=0.0, a=0.4, alpha=eps),
        R(d=0.1, a=0.3, alpha=0.0),
        R(d=0.0, a=0.2, alpha=0.0),
        R(d=0.1, a=0.0, alpha=PI / 2),
        R(d=0.1, a=0.0, alpha=0.0),
    ]
    return km.Robot.from_dh(rows, convention="standard")


def test_the_arm_cut_open_at_a_middle_joint_reaches_the_turn_of_that_joint() -> None:
    """FK of the cut arm at (q_(s+1..6), q_(1..s-1)) is Rz(-q_s), for the target FK(q)."""
    robot = _parallel_2_5(1e-7)
    q = np.random.default_rng(6).uniform(-PI, PI, 6)
    T = robot.fk(q)
    for s in range(1, 5):
        F = np.asarray(cut_arm(robot.chain, s, T).fk(np.concatenate([q[s + 1 :], q[:s]]))[0])
        c, n = math.cos(q[s]), math.sin(q[s])
        turn = np.array([[c, n, 0, 0], [-n, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
        assert np.abs(F - turn).max() <= 1e-12


def test_a_near_arm_whose_end_joints_keep_still_is_swept_in_the_middle() -> None:
    robot = _parallel_2_5(1e-7)
    five = rank_five(robot.chain)
    assert five is not None and end_sweeps(robot.chain, five.rank) == ()
    rng = np.random.default_rng(9)
    for q in rng.uniform(-PI, PI, (2, 6)):
        T = robot.fk(q)
        res = robot.ik(T)
        assert isinstance(res, IKResult)
        assert res.method == METHOD and res.status in ("ok", "singular")
        assert "sweeping q" in str(res.notes[-1])
        _reaches(robot, res.solutions, T)
        sigma = float(relative_sigma(robot.chain, q))
        assert _wrapped(res.solutions - q).max(axis=1).min() <= 1e-6 + FK_TOL / sigma
