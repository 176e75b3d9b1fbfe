"""Numeric IK (Levenberg-Marquardt): every answer judged by our own forward kinematics.

The solver's flags are never trusted here: each returned configuration is put
through ``robot.fk`` and compared with its target by the position distance and
:func:`kinematica.spatial.rotation_angle` (or the masked components of
:func:`kinematica.spatial.se3_error`), and checked against the joint limits.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from kinematica.ik.numeric_model import evaluate
from kinematica.ik.numeric_problem import LMProblem, compile_setup
from kinematica.ik.numeric_single import kernel_of

from kinematica.dh import Prismatic, Revolute
from kinematica.errors import DimensionError, KinematicaError
from kinematica.ik.numeric import solve_numeric, solve_numeric_detailed
from kinematica.robot import Robot, load
from kinematica.spatial import rotation_angle, se3_error

TOL = 1e-10
PI = math.pi


# ------------------------------------------------------------------ robots
def panda() -> Robot:
    """The built-in Franka Panda (modified DH, Franka's limits, flange as tool)."""
    return load("panda")


def iiwa14() -> Robot:
    """The built-in KUKA LBR iiwa 14 (standard DH, with its limits)."""
    return load("iiwa14")


def puma() -> Robot:
    """A PUMA 560-like 6R arm (standard DH), free joints."""
    joints = [
        Revolute(d=0.6718, alpha=PI / 2),
        Revolute(a=0.4318),
        Revolute(d=0.15005, a=0.0203, alpha=-PI / 2),
        Revolute(d=0.4318, alpha=PI / 2),
        Revolute(alpha=-PI / 2),
        Revolute(),
    ]
    return Robot.from_dh(joints, name="puma")


def stanford() -> Robot:
    """Stanford arm (RRPRRR), prismatic third joint with limits."""
    joints = [
        Revolute(d=0.412, alpha=-PI / 2),
        Revolute(d=0.154, alpha=PI / 2),
        Prismatic(theta=0.0, qlim=(0.3, 0.9)),
        Revolute(alpha=-PI / 2),
        Revolute(alpha=PI / 2),
        Revolute(d=0.263),
    ]
    return Robot.from_dh(joints, name="stanford")


def planar2r() -> Robot:
    """Two revolute joints in the xy plane, links 1.0 and 0.7 m."""
    return Robot.from_dh([Revolute(a=1.0), Revolute(a=0.7)], name="planar 2R")


def random_q(robot: Robot, count: int, seed: int) -> np.ndarray:
    lo, hi = robot.qlim.T
    return np.random.default_rng(seed).uniform(lo, hi, (count, robot.dof))


# ------------------------------------------------------------------ checks
def solved(q: np.ndarray) -> np.ndarray:
    """``(N,)`` True where the single slot holds a configuration."""
    return np.all(np.isfinite(q[:, 0, :]), axis=-1)


def assert_reaches(robot: Robot, q: np.ndarray, targets: np.ndarray, mask=None) -> None:
    """Each configuration ``q (K, n)`` reaches its target by our FK, within limits."""
    T = robot.fk(q)
    if targets.ndim == 2:  # positions
        dist = np.linalg.norm(T[:, :3, 3] - targets, axis=-1)
        assert dist.max() <= TOL, dist.max()
    elif mask is None:
        dist = np.linalg.norm(T[:, :3, 3] - targets[:, :3, 3], axis=-1)
        angle = rotation_angle(T[:, :3, :3], targets[:, :3, :3])
        assert dist.max() <= TOL, dist.max()
        assert angle.max() <= TOL, angle.max()
    else:
        e = se3_error(T, targets) * (np.asarray(mask) > 0)
        assert np.linalg.norm(e[:, :3], axis=-1).max() <= TOL
        assert np.linalg.norm(e[:, 3:], axis=-1).max() <= TOL
    lo, hi = robot.qlim.T
    assert np.all((q >= lo) & (q <= hi))


# ------------------------------------------------- success on 7-DOF arms
@pytest.mark.parametrize("make", [panda, iiwa14], ids=["panda", "iiwa14"])
def test_random_reachable_poses_within_limits(make) -> None:
    robot = make()
    targets = robot.fk(random_q(robot, 1000, seed=11))
    cand = solve_numeric(robot, targets, seed=0)
    ok = solved(cand.q)
    assert ok.mean() >= 0.999
    assert_reaches(robot, cand.q[ok, 0], targets[ok])


def test_solution_at_the_start_takes_no_step() -> None:
    robot = iiwa14()
    q = random_q(robot, 3, seed=2)
    d = solve_numeric_detailed(robot, robot.fk(q), q0=q)
    np.testing.assert_array_equal(d.candidates.q[:, 0], q)
    np.testing.assert_array_equal(d.iterations, 1)  # the evaluation of q0 only
    np.testing.assert_array_equal(d.attempts, 1)


# ------------------------------------------------------------------ masks
def test_position_only_on_a_6dof_arm() -> None:
    robot = puma()
    targets = robot.fk(random_q(robot, 40, seed=3))[:, :3, 3]
    cand = solve_numeric(robot, targets, position_only=True)
    assert solved(cand.q).all()
    assert_reaches(robot, cand.q[:, 0], targets)


def test_position_only_accepts_poses_and_ignores_their_rotation() -> None:
    robot = puma()
    T = robot.fk(random_q(robot, 5, seed=4))
    T[:, :3, :3] = np.eye(3)  # an orientation the arm need not reach
    cand = solve_numeric(robot, T, position_only=True)
    assert solved(cand.q).all()
    assert_reaches(robot, cand.q[:, 0], T[:, :3, 3])


@pytest.mark.parametrize(
    "mask",
    [[1, 1, 1, 1, 1, 0], [1, 1, 1, 0, 1, 1], [0, 1, 1, 1, 1, 1]],
    ids=["free rz", "free rx", "free x"],
)
def test_five_component_mask(mask) -> None:
    robot = puma()
    targets = robot.fk(random_q(robot, 40, seed=5))
    cand = solve_numeric(robot, targets, mask=mask)
    assert solved(cand.q).all()
    assert_reaches(robot, cand.q[:, 0], targets, mask=mask)


def test_five_component_mask_leaves_the_free_component_free() -> None:
    # A target rotated about base z away from a reachable one is still met when
    # rz is free: the solver must not report it unreachable.
    robot = puma()
    T = robot.fk(random_q(robot, 10, seed=6))
    c, s = math.cos(0.7), math.sin(0.7)
    Rz = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
    T[:, :3, :3] = Rz @ T[:, :3, :3]
    mask = [1, 1, 1, 1, 1, 0]
    cand = solve_numeric(robot, T, mask=mask)
    assert solved(cand.q).all()
    assert_reaches(robot, cand.q[:, 0], T, mask=mask)


def test_weighted_mask_still_meets_the_plain_tolerance() -> None:
    robot = iiwa14()
    targets = robot.fk(random_q(robot, 30, seed=7))
    cand = solve_numeric(robot, targets, mask=[3, 3, 3, 0.2, 0.2, 0.2])
    assert solved(cand.q).mean() >= 0.96
    ok = solved(cand.q)
    assert_reaches(robot, cand.q[ok, 0], targets[ok])


# ---------------------------------------------------- honest statuses
def test_target_beyond_reach_is_all_nan_with_a_gap() -> None:
    robot = panda()
    T = np.tile(np.eye(4), (2, 1, 1))
    T[0, :3, 3] = [3.0, 0.0, 0.5]
    T[1, :3, 3] = robot.fk(random_q(robot, 1, seed=8))[0, :3, 3]
    d = solve_numeric_detailed(robot, T)
    assert np.isnan(d.candidates.q[0]).all()
    assert d.candidates.gap[0] > 1.0  # a proven lower bound on the distance (m)
    assert d.attempts[0] == 0  # not searched


def test_unreachable_within_the_bound_is_nan_not_proven() -> None:
    # The 2R arm cannot reach within 0.3 m of its base; the crude bound cannot tell.
    robot = planar2r()
    d = solve_numeric_detailed(robot, np.array([[0.1, 0.0, 0.0]]), position_only=True, restarts=5)
    assert np.isnan(d.candidates.q).all()
    assert d.candidates.gap[0] == 0.0  # unknown
    assert d.attempts[0] == 6
    assert d.position_error[0] > 0.1  # the best it found: 0.3 - 0.1


def test_nothing_is_returned_outside_the_limits() -> None:
    # A pose of the free arm needing q1 = 2.5 rad, with q1 limited to ±1 rad.
    free = puma()
    q = np.array([[2.5, 0.3, -0.4, 0.2, 0.5, 0.1]])
    T = free.fk(q)
    limited = free.with_limits([(-1.0, 1.0)] + [None] * 5)
    cand = solve_numeric(limited, T, restarts=10)
    lo, hi = limited.qlim.T
    for qi in cand.q[:, 0]:
        assert np.isnan(qi).all() or np.all((qi >= lo) & (qi <= hi))


def test_planar_2r_position_target() -> None:
    robot = planar2r()
    q = np.array([[0.3, 1.1], [-2.0, -0.5], [2.9, 2.0]])
    targets = robot.fk(q)[:, :3, 3]
    cand = solve_numeric(robot, targets, position_only=True)
    assert solved(cand.q).all()
    assert_reaches(robot, cand.q[:, 0], targets)


def test_planar_2r_full_pose_target() -> None:
    # A pose: the orientation about z follows from the position here, so the
    # target is reachable and both must be met.
    robot = planar2r()
    targets = robot.fk(np.array([[0.4, -1.3]]))
    cand = solve_numeric(robot, targets)
    assert solved(cand.q).all()
    assert_reaches(robot, cand.q[:, 0], targets)


def test_prismatic_arm_full_pose_within_limits() -> None:
    robot = stanford()
    targets = robot.fk(random_q(robot, 60, seed=9))
    cand = solve_numeric(robot, targets)
    assert solved(cand.q).mean() >= 0.98
    ok = solved(cand.q)
    assert_reaches(robot, cand.q[ok, 0], targets[ok])


def test_prismatic_joint_without_limits() -> None:
    # Cylindrical RPP arm, prismatic joints free: restarts sample them in ±1 m.
    robot = Robot.from_dh(
        [Revolute(d=0.5), Prismatic(alpha=-PI / 2), Prismatic()], name="cylindrical"
    )
    q = np.array([[0.4, 0.8, 1.5], [-2.0, -0.3, 0.6]])
    targets = robot.fk(q)[:, :3, 3]
    cand = solve_numeric(robot, targets, position_only=True)
    assert solved(cand.q).all()
    assert_reaches(robot, cand.q[:, 0], targets)


def test_ignoring_limits_wraps_angles() -> None:
    robot = puma()
    targets = robot.fk(random_q(robot, 20, seed=10))
    cand = solve_numeric(robot, targets, respect_limits=False)
    q = cand.q[:, 0]
    assert solved(cand.q).all()
    assert np.all((q > -PI) & (q <= PI))
    T = robot.fk(q)
    assert np.abs(T - targets).max() < 1e-9


# ------------------------------------------------ batch, determinism
def test_batch_equals_one_by_one() -> None:
    robot = panda()
    targets = robot.fk(random_q(robot, 12, seed=12))
    batch = solve_numeric_detailed(robot, targets, restarts=0)
    single = [solve_numeric_detailed(robot, targets[i : i + 1], restarts=0) for i in range(12)]
    # Same algorithm, step for step: the same first attempts succeed, in as many steps.
    np.testing.assert_array_equal(
        solved(batch.candidates.q), [solved(s.candidates.q)[0] for s in single]
    )
    np.testing.assert_array_equal(batch.iterations, [s.iterations[0] for s in single])
    # And with restarts, both solve everything.
    full = solve_numeric(robot, targets)
    assert solved(full.q).all()
    for i in range(12):
        one = solve_numeric(robot, targets[i : i + 1])
        assert solved(one.q).all()
        assert_reaches(robot, one.q[:, 0], targets[i : i + 1])


def test_deterministic_given_a_seed() -> None:
    robot = panda()
    targets = robot.fk(random_q(robot, 50, seed=13))
    a = solve_numeric(robot, targets, seed=7)
    b = solve_numeric(robot, targets, seed=7)
    c = solve_numeric(robot, targets, seed=np.random.default_rng(7))
    np.testing.assert_array_equal(a.q, b.q)
    np.testing.assert_array_equal(a.q, c.q)
    d = solve_numeric(robot, targets)  # no seed: a fixed default, still reproducible
    np.testing.assert_array_equal(d.q, solve_numeric(robot, targets).q)


# ------------------------------------------------------------- shapes
@pytest.mark.parametrize("N", [1, 3])
def test_shapes(N: int) -> None:
    robot = iiwa14()
    targets = robot.fk(random_q(robot, N, seed=14))
    d = solve_numeric_detailed(robot, targets)
    cand = d.candidates
    assert cand.q.shape == (N, 1, 7)
    assert cand.labels == ("numeric",)
    assert cand.singular.shape == (N,) and not cand.singular.any()
    assert cand.free.shape == (N, 7) and not cand.free.any()
    assert cand.gap.shape == (N,) and np.isnan(cand.gap).all()
    for a in (d.iterations, d.attempts, d.position_error, d.angle_error):
        assert a.shape == (N,)
    assert np.all(d.position_error <= TOL) and np.all(d.angle_error <= TOL)


def test_single_pose_and_q0_forms() -> None:
    robot = puma()  # not redundant: a guess near a solution converges to it
    q = random_q(robot, 3, seed=15)
    T = robot.fk(q)
    assert solve_numeric(robot, T[0]).q.shape == (1, 1, 6)
    near = q + 0.05
    a = solve_numeric(robot, T, q0=near)  # (N, n)
    b = solve_numeric(robot, T, q0=near[0])  # (n,), shared
    assert solved(a.q).all() and solved(b.q).all()
    np.testing.assert_allclose(a.q[:, 0], q, atol=1e-8)  # the nearby solution


# -------------------------------------------------------------- input
def test_bad_input_is_named() -> None:
    robot = iiwa14()
    T = robot.fk(random_q(robot, 2, seed=16))
    with pytest.raises(DimensionError, match="targets"):
        solve_numeric(robot, np.zeros((2, 3)))
    with pytest.raises(DimensionError, match="targets"):
        solve_numeric(robot, np.full((1, 4, 4), np.nan))
    with pytest.raises(DimensionError, match="q0"):
        solve_numeric(robot, T, q0=np.zeros((3, 7)))
    with pytest.raises(DimensionError, match="q0"):
        solve_numeric(robot, T, q0=np.zeros(6))
    with pytest.raises(DimensionError, match="mask"):
        solve_numeric(robot, T, mask=[1, 1, 1])
    with pytest.raises(DimensionError, match="mask"):
        solve_numeric(robot, T, mask=[1, 1, 1, -1, 1, 1])
    with pytest.raises(DimensionError, match="no error component"):
        solve_numeric(robot, T, mask=[0, 0, 0, 1, 1, 1], position_only=True)
    with pytest.raises(KinematicaError, match="tol_position"):
        solve_numeric(robot, T, tol_position=0.0)
    with pytest.raises(KinematicaError, match="restarts"):
        solve_numeric(robot, T, restarts=-1)
    with pytest.raises(KinematicaError, match="max_iterations"):
        solve_numeric(robot, T, max_iterations=0)


def test_base_and_tool_transforms_and_both_conventions() -> None:
    c, s = math.cos(0.4), math.sin(0.4)
    base = np.array([[c, -s, 0, 0.3], [s, c, 0, -0.2], [0, 0, 1, 0.1], [0, 0, 0, 1.0]])
    tool = np.eye(4)
    tool[:3, 3] = [0.02, 0.0, 0.15]
    for robot in (stanford().with_base(base).with_tool(tool), stanford().to_convention("modified")):
        targets = robot.fk(random_q(robot, 30, seed=18))
        cand = solve_numeric(robot, targets)
        ok = solved(cand.q)
        assert ok.mean() >= 0.96
        assert_reaches(robot, cand.q[ok, 0], targets[ok])


def test_empty_batch() -> None:
    robot = iiwa14()
    cand = solve_numeric(robot, np.zeros((0, 4, 4)))
    assert cand.q.shape == (0, 1, 7)


# ----------------------------------------------- the kernels' own model
def _problem(robot: Robot, mask) -> LMProblem:
    weights = np.asarray(mask, dtype=float)
    return compile_setup(robot, weights, True, TOL, TOL, 60).problem


@pytest.mark.parametrize(
    "mask", [[1, 1, 1, 1, 1, 0], [0, 1, 0, 1, 0, 0], [2, 1, 1, 0, 0.5, 0.5]], ids=str
)
def test_error_jacobian_matches_finite_differences(mask) -> None:
    # With only some rotation components counted the rows are the exact
    # derivative -J_r⁻¹(Δω) J_ω of the error, also far from the target.
    robot = stanford()
    problem = _problem(robot, mask)
    q = random_q(robot, 1, seed=19)[0]
    T = robot.fk(random_q(robot, 1, seed=20)[0])
    pt, Rt = T[:3, 3, None], T[:3, :3, None]
    _, J = evaluate(problem, q[:, None], pt, Rt)
    w = np.sqrt(np.asarray(mask, dtype=float)[np.asarray(mask) > 0])
    h = 1e-6
    for i in range(robot.dof):
        dq = np.zeros(robot.dof)
        dq[i] = h
        up = evaluate(problem, (q + dq)[:, None], pt, Rt)[0]
        down = evaluate(problem, (q - dq)[:, None], pt, Rt)[0]
        np.testing.assert_allclose(-(up - down)[:, 0] / (2 * h) * w, J[:, i, 0], atol=1e-7)


@pytest.mark.parametrize("mask", [[1] * 6, [1, 1, 1, 1, 1, 0], [1, 1, 1, 0, 0, 0]], ids=str)
def test_scalar_and_batched_models_agree(mask) -> None:
    for robot in (panda(), stanford()):
        problem = _problem(robot, mask)
        q = random_q(robot, 4, seed=21)
        T = robot.fk(random_q(robot, 4, seed=22))
        err, J = evaluate(problem, q.T, T[:, :3, 3].T, T[:, :3, :3].transpose(1, 2, 0))
        kernel = kernel_of(problem)
        for r in range(4):
            e1, J1 = kernel.evaluate(q[r].tolist(), T[r, :3, 3].tolist(), T[r, :3, :3].tolist())
            np.testing.assert_allclose(e1, err[:, r], atol=1e-13)
            np.testing.assert_allclose(np.array(J1), J[:, :, r], atol=1e-13)
