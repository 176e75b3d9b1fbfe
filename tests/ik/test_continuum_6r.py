"""6R arms of rank 5 everywhere: ``singular``, the free motion named, exact representatives.

Three hand-built arms, one per structure of :mod:`kinematica.ik.rank_five` (four axes
through one point, a spherical shoulder and wrist, three parallel axes before a
spherical wrist), each checked independently of the solver:

- the rank: the Jacobian by central differences of forward kinematics (not the core's)
  has σ6 / σ1 at round-off at random configurations;
- every representative reaches the pose to 1e-10 by forward kinematics;
- the continuum is real: from each representative, a walk along the null direction of
  the finite-difference Jacobian, pulled back onto the pose by Gauss-Newton at each
  step, moves the named free joints by a tenth of a radian and more with the pose kept
  to 1e-10 (an isolated solution would allow no such walk), and keeps the joints not
  named still.

And the same arms moved off their structure (1e-6, 1e-9): isolated solutions, the
generating configuration among them and every one the search finds from random
guesses, or, within round-off of the continuum, ``singular``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinematica as km
from kinematica.dh.joints import Revolute
from kinematica.ik.choice import pose_choice
from kinematica.ik.continuum_6r import DUPLICATE_TOL, METHOD, distinct, exact_rank_five
from kinematica.ik.near_rank_five import CONTINUUM_RATIO, SAME_TOL
from kinematica.ik.near_rank_five import METHOD as NEAR
from kinematica.ik.rank_five import (
    FREE_TOL,
    RANK_EXACT_TOL,
    RANK_NEAR_TOL,
    free_motion,
    rank_five,
    relative_sigma,
)

pytestmark = pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")

PI = math.pi
#: Representatives reach their target to this (m, rad).
FK_TOL = 1e-10
#: The walk along the continuum: steps, and length of each (rad).
WALK_STEPS, WALK_STEP = 20, 0.01
#: A joint not named free keeps still along the walk to this (rad).
STILL_TOL = 1e-8

#: The three structures: DH rows (standard), what the free joints are.
STRUCTURES = ("four-concurrent", "shoulder-wrist", "parallel-concurrent")


def _rows(kind: str, eps: float = 0.0) -> list[Revolute]:
    """The hand-built arm of ``kind``, moved off its structure by ``eps`` (m or rad).

    The second row's d (the axes no longer meet at one point) or, for the parallel
    axes, its twist.
    """
    R = Revolute
    if kind == "four-concurrent":  # axes 1-4 through the origin of frame 1
        return [
            R(d=0.3, a=0.0, alpha=PI / 2),
            R(d=eps, a=0.0, alpha=1.1),
            R(d=0.0, a=0.0, alpha=-0.7),
            R(d=0.1, a=0.4, alpha=PI / 2),
            R(d=0.2, a=0.3, alpha=-PI / 2),
            R(d=0.1, a=0.0, alpha=0.0),
        ]
    if kind == "shoulder-wrist":  # axes 1-3 meet (a1 = a2 = d2 = 0), 4-6 meet (a4 = a5 = d5 = 0)
        return [
            R(d=0.3, a=0.0, alpha=PI / 2),
            R(d=eps, a=0.0, alpha=-PI / 2),
            R(d=0.5, a=0.1, alpha=PI / 2),
            R(d=0.4, a=0.0, alpha=-PI / 2),
            R(d=0.0, a=0.0, alpha=PI / 2),
            R(d=0.1, a=0.0, alpha=0.0),
        ]
    return [  # axes 1-3 parallel (α1 = α2 = 0), 4-6 meet
        R(d=0.3, a=0.4, alpha=0.0),
        R(d=0.0, a=0.35, alpha=eps),
        R(d=0.1, a=0.2, alpha=PI / 2),
        R(d=0.3, a=0.0, alpha=-PI / 2),
        R(d=0.0, a=0.0, alpha=PI / 2),
        R(d=0.1, a=0.0, alpha=0.0),
    ]


def _robot(kind: str, eps: float = 0.0) -> km.Robot:
    return km.Robot.from_dh(_rows(kind, eps), convention="standard")


def _twist(robot: km.Robot, q: np.ndarray) -> np.ndarray:
    """``(6,)`` position and rotation vector of the tool pose (for finite differences)."""
    T = robot.fk(q)
    R = T[:3, :3]
    w = 0.5 * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    return np.concatenate([T[:3, 3], w])


def _jacobian_fd(robot: km.Robot, q: np.ndarray, T: np.ndarray) -> np.ndarray:
    """``(6, 6)`` the pose error's Jacobian by central differences (rotation in T's frame)."""
    h = 1e-6
    J = np.empty((6, 6))
    for j in range(6):
        dq = np.zeros(6)
        dq[j] = h
        J[:, j] = (_error(robot, q + dq, T) - _error(robot, q - dq, T)) / (2 * h)
    return J


def _error(robot: km.Robot, q: np.ndarray, T: np.ndarray) -> np.ndarray:
    F = robot.fk(q)
    E = T[:3, :3].T @ F[:3, :3]
    w = 0.5 * np.array([E[2, 1] - E[1, 2], E[0, 2] - E[2, 0], E[1, 0] - E[0, 1]])
    return np.concatenate([F[:3, 3] - T[:3, 3], w])


def _walk(robot: km.Robot, q: np.ndarray, T: np.ndarray) -> np.ndarray:
    """The configuration reached by walking along the continuum through q (each step on T)."""
    prev = None
    for _ in range(WALK_STEPS):
        J = _jacobian_fd(robot, q, T)
        n = np.linalg.svd(J)[2][-1]
        if prev is not None and n @ prev < 0:
            n = -n
        prev = n
        q = q + WALK_STEP * n
        for _ in range(8):  # back onto the pose: Gauss-Newton, minimum-norm steps
            q = q - np.linalg.lstsq(_jacobian_fd(robot, q, T), _error(robot, q, T), rcond=1e-8)[0]
    return q


def _reaches(robot: km.Robot, Q: np.ndarray, T: np.ndarray) -> None:
    assert len(Q)
    F = robot.fk(Q)
    assert np.linalg.norm(F[:, :3, 3] - T[:3, 3], axis=1).max() <= FK_TOL
    assert max(km.rotation_angle(f[:3, :3], T[:3, :3]) for f in F) <= FK_TOL


@pytest.mark.parametrize("kind", STRUCTURES)
def test_the_arm_has_rank_5_by_finite_differences(kind: str) -> None:
    robot = _robot(kind)
    rng = np.random.default_rng(1)
    for _ in range(4):
        q = rng.uniform(-PI, PI, 6)
        s = np.linalg.svd(_jacobian_fd(robot, q, robot.fk(q)), compute_uv=False)
        assert s[-1] / s[0] < 1e-8  # finite differences' own error: ~1e-10
        assert s[-2] / s[0] > 1e-3
    five = rank_five(robot.chain)
    assert five is not None and five.exact and five.kind == kind


@pytest.mark.parametrize("kind", STRUCTURES)
def test_a_pose_made_by_fk_is_a_continuum_with_exact_representatives(kind: str) -> None:
    robot = _robot(kind)
    rng = np.random.default_rng(7)
    for _ in range(3):
        q = rng.uniform(-PI, PI, 6)
        T = robot.fk(q)
        res = robot.ik(T)
        assert res.method == METHOD
        assert res.status == "singular"
        assert not res.complete
        assert res.free_joints
        _reaches(robot, res.solutions, T)
        assert np.all(res.residuals <= FK_TOL)
        # the generating configuration lies on a continuum too: the same joints move there
        n = np.linalg.svd(_jacobian_fd(robot, q, T))[2][-1]
        assert set(np.flatnonzero(np.abs(n) > 1e-4)) == set(res.free_joints)


@pytest.mark.parametrize("kind", STRUCTURES)
def test_moving_along_the_free_parameter_keeps_the_pose(kind: str) -> None:
    robot = _robot(kind)
    q = np.random.default_rng(11).uniform(-PI, PI, 6)
    T = robot.fk(q)
    res = robot.ik(T)
    still = [j for j in range(6) if j not in res.free_joints]
    for rep in res.solutions[:2]:
        moved = _walk(robot, rep, T)
        _reaches(robot, moved[None], T)
        step = np.abs(np.remainder(moved - rep + PI, 2 * PI) - PI)
        assert step[list(res.free_joints)].max() > 0.1
        if still:
            assert step[still].max() <= STILL_TOL


def test_a_batch_answers_each_target_as_one_does() -> None:
    robot = _robot("shoulder-wrist")
    Q = np.random.default_rng(3).uniform(-PI, PI, (3, 6))
    T = robot.fk(Q)
    batch = robot.ik(T)
    for i in range(3):
        one = robot.ik(T[i])
        assert str(batch.status[i]) == "singular"
        got = batch[i]
        assert np.allclose(got.solutions, one.solutions, atol=1e-12)


def test_show_names_the_continuum_solver() -> None:
    choice = pose_choice(_robot("four-concurrent").chain)
    assert choice.method == METHOD
    assert not choice.complete


def test_rank_tolerances_at_their_boundaries() -> None:
    """Exact arms read as exact, arms moved by 1e-11 (ratio above 1e-13) as near; 1e-2: neither."""
    exact = _robot("four-concurrent")
    near = _robot("four-concurrent", 1e-11)
    far = _robot("four-concurrent", 3e-3)
    Q = np.random.default_rng(0).uniform(-PI, PI, (8, 6))
    assert relative_sigma(exact.chain, Q).max() <= RANK_EXACT_TOL * 1e-2
    assert RANK_EXACT_TOL * 1e1 <= relative_sigma(near.chain, Q).max() <= RANK_NEAR_TOL * 1e-3
    assert relative_sigma(far.chain, Q).max() >= RANK_NEAR_TOL * 1e1
    assert exact_rank_five(exact.chain) is not None
    five = rank_five(near.chain)
    assert five is not None and not five.exact and exact_rank_five(near.chain) is None
    assert rank_five(far.chain) is None


@pytest.mark.parametrize("kind", STRUCTURES)
def test_an_arm_near_rank_5_gets_every_solution_the_search_finds(kind: str) -> None:
    """Moved by 1e-6 off its structure: isolated solutions, the generating one among them."""
    robot = _robot(kind, 1e-6)
    rng = np.random.default_rng(21)
    q = rng.uniform(-PI, PI, 6)
    T = robot.fk(q)
    res = robot.ik(T)
    assert res.method == NEAR
    assert res.status == "ok" and res.near_singular and not res.complete
    _reaches(robot, res.solutions, T)
    sigma = float(relative_sigma(robot.chain, q))
    gap = np.abs(np.remainder(res.solutions - q + PI, 2 * PI) - PI).max(axis=1)
    assert gap.min() <= 1e-6 + FK_TOL / sigma  # a solution is known to the tolerance over σ6
    for _ in range(20):  # every solution of the search from random guesses is among them
        found = robot.ik(T, method="numeric", q0=rng.uniform(-PI, PI, 6)).solutions
        for f in found:  # (the search stops within the tolerance: 1e-10 over σ6 from a root)
            d = np.abs(np.remainder(res.solutions - f + PI, 2 * PI) - PI).max(axis=1)
            assert d.min() <= SAME_TOL + FK_TOL / float(relative_sigma(robot.chain, f))


def test_near_arms_within_round_off_of_the_continuum_are_singular() -> None:
    """σ6/σ1 ~ 1e-11 (moved by 1e-9): arcs within the tolerance; ~1e-7 (3e-6): isolated."""
    T_of = np.random.default_rng(4).uniform(-PI, PI, 6)
    close = _robot("shoulder-wrist", 1e-9)
    res = close.ik(close.fk(T_of))
    assert res.status == "singular" and res.method == NEAR and res.free_joints
    assert float(relative_sigma(close.chain, res.solutions).max()) <= CONTINUUM_RATIO * 1e-1
    _reaches(close, res.solutions, close.fk(T_of))
    apart = _robot("parallel-concurrent", 3e-6)
    res = apart.ik(apart.fk(T_of))
    assert res.status == "ok" and not res.free_joints and res.method == NEAR
    assert float(relative_sigma(apart.chain, res.solutions).max()) >= CONTINUUM_RATIO * 1e2


def test_duplicate_and_same_tolerances_at_their_boundaries() -> None:
    """Representatives 1e-11 apart (round-off) are one; 1e-7 apart, two (DUPLICATE_TOL 1e-9).

    Near solutions 1e-6 apart (known to the tolerance over σ6) are one; the distinct
    solutions of an arm near rank 5 are far more than 1e3 SAME_TOL apart.
    """
    q = np.array([0.1, -0.2, 0.3, 1.0, -1.0, 2.0])
    assert len(distinct(np.stack([q, q + 1e-11]), DUPLICATE_TOL)) == 1
    assert len(distinct(np.stack([q, q + 1e-6]), DUPLICATE_TOL)) == 2
    assert len(distinct(np.stack([q, q + 1e-7]), SAME_TOL)) == 1
    robot = _robot("shoulder-wrist", 1e-6)
    Q = robot.ik(robot.fk(np.random.default_rng(2).uniform(-PI, PI, 6))).solutions
    assert len(Q) >= 2
    d = np.abs(np.remainder(Q[:, None] - Q[None] + PI, 2 * PI) - PI).max(axis=2)
    assert d[~np.eye(len(Q), dtype=bool)].min() >= SAME_TOL * 1e3


def test_free_joints_tolerance_at_its_boundary() -> None:
    """Joints 5, 6 of the four-concurrent arm moved by 3e-9 share 2e-9..1e-9 of the null
    direction (not free: FREE_TOL 1e-6); joints 1-4 share 0.05 and more (free)."""
    robot = _robot("four-concurrent", 3e-9)
    q = np.random.default_rng(2).uniform(-3, 3, 6)
    res = robot.ik(robot.fk(q))
    assert res.status == "singular" and res.free_joints == (0, 1, 2, 3)
    shares = np.array([free_motion(robot.chain, s) for s in res.solutions])
    assert shares[:, 4:].max() >= FREE_TOL * 1e-3  # a tolerance 1000x smaller names them
    assert shares[:, 4:].max() <= FREE_TOL * 1e-2
    assert shares[:, :4].min() >= FREE_TOL * 1e4
