"""Closed-form IK of UR-type arms (axes 2-3-4 parallel): all solutions, exact.

Independent references: EAIK's solution sets for the UR5
(``data/reference/ik_reference.json``), forward kinematics of every candidate,
the product-of-exponentials identity the solver is built on, and a multi-start
damped-least-squares search on the robot's Jacobian (completeness).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from helpers import assert_transform_close, transform_from
from numpy.typing import NDArray
from test_ik_small import dls_solutions, joint_distance, random_arm

from kinematica.dh import Prismatic, Revolute
from kinematica.ik.analytic.parallel import LABELS, make_three_parallel_solver
from kinematica.ik.analytic.parallel_general import GENERAL_LABELS, GeneralThreeParallelSolver
from kinematica.robot import Robot, classify

FloatArray = NDArray[np.float64]
PI = math.pi
EXACT = 1e-12
REFERENCE = Path(__file__).parent / "data" / "reference" / "ik_reference.json"

UR5_ROWS = [
    Revolute(d=0.089159, alpha=PI / 2),
    Revolute(a=-0.425),
    Revolute(a=-0.39225),
    Revolute(d=0.10915, alpha=PI / 2),
    Revolute(d=0.09465, alpha=-PI / 2),
    Revolute(d=0.0823),
]
UR5 = Robot.from_dh(UR5_ROWS, name="UR5")


def twist(rng: np.random.Generator) -> float:
    """A twist well away from 0 and π (keeps the axis off the parallel set)."""
    return float(rng.uniform(0.3, PI - 0.3) * rng.choice([-1.0, 1.0]))


def random_ur(rng: np.random.Generator, modified: bool | None = None) -> Robot:
    """A random UR-type arm: axes 2, 3, 4 parallel, axes 5 and 6 meeting (a5 = 0)."""
    u = rng.uniform
    rows = [
        Revolute(d=u(0.05, 0.4), a=u(-0.1, 0.1), alpha=twist(rng), offset=u(-PI, PI)),
        Revolute(d=u(-0.2, 0.2), a=u(0.2, 0.6) * rng.choice([-1, 1]), alpha=rng.choice([0, PI])),
        Revolute(d=u(-0.2, 0.2), a=u(0.2, 0.6) * rng.choice([-1, 1]), alpha=rng.choice([0, PI])),
        Revolute(d=u(-0.2, 0.2), a=u(-0.1, 0.1), alpha=twist(rng), offset=u(-PI, PI)),
        Revolute(d=u(-0.2, 0.2), alpha=twist(rng), offset=u(-PI, PI)),
        Revolute(d=u(-0.2, 0.2), a=u(-0.1, 0.1), alpha=u(-PI, PI), offset=u(-PI, PI)),
    ]
    base = transform_from(rng.normal(size=4), rng.uniform(-0.5, 0.5, 3))
    tool = transform_from(rng.normal(size=4), rng.uniform(-0.2, 0.2, 3))
    robot = Robot.from_dh(rows, base=base, tool=tool)
    if modified if modified is not None else rng.random() < 0.5:
        robot = robot.to_convention("modified")
    assert classify(robot).kind == "three-parallel-6R"
    return robot


def solve_checked(robot: Robot, T: FloatArray) -> FloatArray:
    """Candidates ``(N, 8, 6)`` for poses ``T``; every real one reproduces its pose exactly."""
    solver = make_three_parallel_solver(robot)
    assert solver is not None
    cand = solver.solve(T)
    q = cand.q
    assert q.shape == (len(T), 8, 6) and cand.labels == LABELS
    nan = np.isnan(q)
    assert (nan.any(axis=2) == nan.all(axis=2)).all(), "a branch is partly NaN"
    real = ~nan.any(axis=2)
    reached = robot.fk(np.where(real[..., None], q, 0.0))
    assert_transform_close(reached[real], np.broadcast_to(T[:, None], reached.shape)[real], EXACT)
    assert np.isnan(cand.gap[real.any(axis=1)]).all()
    return q


def found(q: FloatArray, cand: FloatArray, tol: float = 1e-8) -> NDArray[np.bool_]:
    """``(N,)`` True where ``q[i]`` is among ``cand[i]`` modulo 2π."""
    d = np.abs(np.angle(np.exp(1j * (cand - q[:, None, :])))).max(axis=2)
    return np.asarray(np.nan_to_num(d, nan=np.inf).min(axis=1) < tol)


# --------------------------------------------------------- the model it uses
def exp_twist(h: FloatArray, p: FloatArray, prismatic: bool, q: float) -> FloatArray:
    """Rotation by ``q`` about the line ``(h, p)`` (or slide by ``q`` along ``h``), 4x4."""
    E = np.eye(4)
    if prismatic:
        E[:3, 3] = q * h
        return E
    K = np.array([[0, -h[2], h[1]], [h[2], 0, -h[0]], [-h[1], h[0], 0]])
    R = np.eye(3) + math.sin(q) * K + (1 - math.cos(q)) * K @ K
    E[:3, :3] = R
    E[:3, 3] = p - R @ p
    return E


@pytest.mark.parametrize("seed", range(6))
def test_product_of_exponentials_is_the_forward_kinematics(seed: int) -> None:
    rng = np.random.default_rng(seed)
    kind = ["planar-PRR", "scara", "elbow-3R", "planar-PR", "anthropomorphic-3R", "ur"][seed]
    robot = random_ur(rng) if kind == "ur" else random_arm(kind, rng)
    h, p = robot.joint_axes()
    M = robot.fk(np.zeros(robot.dof))
    for q in rng.uniform(-PI, PI, (20, robot.dof)):
        T = np.eye(4)
        for i in range(robot.dof):
            T = T @ exp_twist(h[i], p[i], bool(robot.is_prismatic[i]), q[i])
        assert_transform_close(T @ M, robot.fk(q), atol=1e-12)


# ---------------------------------------------------------------------- UR5
def test_ur5_round_trip() -> None:
    rng = np.random.default_rng(10)
    q = rng.uniform(-PI, PI, (2000, 6))
    cand = solve_checked(UR5, UR5.fk(q))
    assert found(q, cand).all()
    counts = (~np.isnan(cand).any(axis=2)).sum(axis=1)
    assert set(counts.tolist()) <= {2, 4, 6, 8} and (counts == 8).mean() > 0.6


def test_ur5_matches_eaik_reference_solution_sets() -> None:
    arms = {a["name"]: a for a in json.loads(REFERENCE.read_text())["arms"]}
    ref = arms["ur5"]
    robot = Robot.from_dh(
        [Revolute(d=j["d"], a=j["a"], alpha=j["alpha"], offset=j["theta"]) for j in ref["joints"]]
    )
    assert_transform_close(robot.fk(np.zeros(6)), UR5.fk(np.zeros(6)), atol=0)
    T = np.array([s["T"] for s in ref["samples"]])
    cand = solve_checked(robot, T)
    for i, sample in enumerate(ref["samples"]):
        ours = cand[i][~np.isnan(cand[i]).any(axis=1)]
        theirs = np.array(sample["solutions"]).reshape(-1, 6)
        assert len(ours) == len(theirs), f"sample {i}"
        for s in theirs:  # same set modulo 2π
            assert joint_distance(robot, ours, s).min() < 1e-9, f"sample {i}: missed {s}"
        assert found(np.array([sample["q_generating"]]), cand[i : i + 1]).all()


def test_ur5_labels_mean_what_they_say() -> None:
    rng = np.random.default_rng(11)
    T = UR5.fk(rng.uniform(-PI, PI, (300, 6)))
    cand = solve_checked(UR5, T)
    for slot, label in enumerate(LABELS):
        q = cand[:, slot]
        q = q[~np.isnan(q).any(axis=1)]
        h, p = UR5.joint_axes(q)
        frames = UR5.fk(q, all_frames=True)
        h1, k1, h5, h6 = h[:, 0], h[:, 1], h[:, 4], h[:, 5]
        c = frames[:, 5, :3, 3]  # UR5 DH frame 5 sits where axes 5 and 6 meet
        sigma = np.einsum("ij,ij->i", c - p[:, 0], np.cross(h1, k1))
        assert ((sigma >= -1e-12) if "right" in label else (sigma <= 1e-12)).all(), label
        wrist = np.einsum("ij,ij->i", np.cross(k1, h6), h5)
        assert ((wrist >= -1e-12) if "no-flip" in label else (wrist <= 1e-12)).all(), label
        s, e, w = p[:, 1], p[:, 2], p[:, 3]  # points on axes 2, 3, 4

        def across(x: FloatArray, k1: FloatArray = k1) -> FloatArray:
            return x - np.einsum("ij,ij->i", x, k1)[:, None] * k1

        n = np.cross(k1, across(w - s))
        up = np.einsum("ij,ij->i", across(e - s), n) * np.einsum("ij,ij->i", h1, n)
        assert ((up >= -1e-12) if "up" in label else (up <= 1e-12)).all(), label


def test_single_pose_path_equals_batch_path() -> None:
    rng = np.random.default_rng(12)
    for robot in (UR5, random_ur(rng)):
        solver = make_three_parallel_solver(robot)
        assert solver is not None
        q = rng.uniform(-PI, PI, (40, 6))
        q[:5, 4] = 0.0  # aligned wrist: the representative q6 too
        T = robot.fk(q)
        batch = solver.solve(T)
        for i in range(len(T)):
            one = solver.solve(T[i : i + 1])
            assert (np.isnan(one.q[0]) == np.isnan(batch.q[i])).all()
            d = np.abs(np.angle(np.exp(1j * (one.q[0] - batch.q[i]))))
            assert np.nan_to_num(d).max() < 1e-9
            assert one.singular[0] == batch.singular[i]
            assert (one.free[0] == batch.free[i]).all()


# --------------------------------------------------------------- random arms
@pytest.mark.parametrize("modified", [False, True])
def test_random_ur_type_arms_round_trip(modified: bool) -> None:
    rng = np.random.default_rng(20 + modified)
    for _ in range(8):
        robot = random_ur(rng, modified)
        q = rng.uniform(-PI, PI, (300, 6))
        cand = solve_checked(robot, robot.fk(q))
        assert found(q, cand).all()


def test_complete_against_multistart_search() -> None:
    rng = np.random.default_rng(30)
    for robot in (UR5, random_ur(rng), random_ur(rng)):
        for q in rng.uniform(-PI, PI, (2, 6)):
            T = robot.fk(q)
            cand = solve_checked(robot, T[None])[0]
            ours = cand[~np.isnan(cand).any(axis=1)]
            theirs = dls_solutions(robot, T, rng)
            assert len(theirs) >= 1
            for s in theirs:
                assert joint_distance(robot, ours, s).min() < 1e-6, f"missed {s}"


# ------------------------------------------------------------ special poses
def test_wrist_aligned_is_singular_with_q6_free() -> None:
    rng = np.random.default_rng(40)
    q = rng.uniform(-PI, PI, (50, 6))
    q[:, 4] = rng.choice([0.0, PI], 50)  # UR5: axis 6 parallel to axes 2-4
    T = UR5.fk(q)
    cand = solve_checked(UR5, T)
    got = make_three_parallel_solver(UR5).solve(T)  # type: ignore[union-attr]
    assert got.singular.all()
    assert (got.free == [False, True, True, True, False, True]).all()
    assert (~np.isnan(cand).any(axis=2)).sum(axis=1).min() >= 2


def test_near_aligned_wrist_stays_exact() -> None:
    rng = np.random.default_rng(41)
    q = rng.uniform(-PI, PI, (400, 6))
    beta = 10 ** rng.uniform(-12, -3, 400)  # misalignment of axis 6 from axes 2-4 (rad)
    q[:, 4] = rng.choice([0.0, PI], 400) + rng.choice([-1, 1], 400) * beta
    cand = solve_checked(UR5, UR5.fk(q))  # every candidate exact, however close
    assert (~np.isnan(cand).any(axis=2)).any(axis=1).all()
    # q6 and q4 are determined to about 1e-16 / beta only; q itself is found above 1e-8
    assert found(q[beta > 1e-8], cand[beta > 1e-8], tol=1e-6).all()


def test_shoulder_singular_when_the_wrist_is_on_axis_1() -> None:
    rows = [
        Revolute(d=0.1, alpha=PI / 2),
        Revolute(a=0.4),
        Revolute(a=0.3),
        Revolute(alpha=PI / 2),
        Revolute(d=0.1, alpha=-PI / 2),
        Revolute(d=0.08),
    ]
    robot = Robot.from_dh(rows)
    first5 = Robot.from_dh(rows[:5])  # its tool point is where axes 5 and 6 meet
    q = np.array([0.3, 0.9, -1.2, 0.4, 0.7, -0.5])
    for _ in range(50):  # drive that point onto axis 1 (x = y = 0) with q2, q3, q4
        e = -first5.fk(q[:5])[:2, 3]
        J = first5.jacobian(q[:5])[:2, 1:4]
        q[1:4] += np.linalg.pinv(J) @ e
    assert np.abs(first5.fk(q[:5])[:2, 3]).max() < 1e-14
    T = robot.fk(q)[None]
    solve_checked(robot, T)
    got = make_three_parallel_solver(robot).solve(T)  # type: ignore[union-attr]
    assert got.singular[0] and got.free[0, 0]


def test_unreachable_poses_have_a_gap() -> None:
    solver = make_three_parallel_solver(UR5)
    assert solver is not None
    T = UR5.fk(np.array([[0.1, -1.0, 1.2, 0.3, 0.8, 0.2]] * 2))
    T[0, :3, 3] += [5.0, 0.0, 0.0]  # 5 m away: the distance to reach is under 5 m
    # the wrist point 0.05 m from axis 1, inside the d4 = 0.10915 m shoulder cylinder
    c = UR5.joint_axes()[1][5]  # UR5 DH frame 5: where axes 5 and 6 meet, at q = 0
    Minv = np.linalg.inv(UR5.fk(np.zeros(6)))
    cM = Minv[:3, :3] @ c + Minv[:3, 3]  # c in the tool frame: G(c) = p + R cM
    T[1, :3, 3] = np.array([0.05, 0.0, 0.3]) - T[1, :3, :3] @ cM
    cand = solver.solve(T)
    assert np.isnan(cand.q).all()
    assert 0.0 < cand.gap[0] <= 5.0
    assert cand.gap[1] == pytest.approx(0.10915 - 0.05, abs=1e-12)


def test_factory_refuses_other_arms() -> None:
    puma = Robot.from_dh(
        [
            Revolute(alpha=PI / 2),
            Revolute(a=0.4318),
            Revolute(d=0.15005, a=0.0203, alpha=-PI / 2),
            Revolute(d=0.4318, alpha=PI / 2),
            Revolute(alpha=-PI / 2),
            Revolute(),
        ]
    )
    assert make_three_parallel_solver(puma) is None
    assert make_three_parallel_solver(Robot.from_dh([Revolute(), Prismatic()])) is None


# ------------------------------------------------- axes 5 and 6 apart (a5 != 0)
UR5_A5_ROWS = [*UR5_ROWS[:4], Revolute(d=0.09465, a=0.05, alpha=-PI / 2), UR5_ROWS[5]]


def random_general(rng: np.random.Generator, modified: bool) -> Robot:
    """A random arm with axes 2, 3, 4 parallel and axes 5, 6 apart (a5 != 0 or a tilted a4/d5)."""
    u = rng.uniform
    rows = [
        Revolute(d=u(0.05, 0.4), a=u(-0.1, 0.1), alpha=twist(rng), offset=u(-PI, PI)),
        Revolute(d=u(-0.2, 0.2), a=u(0.2, 0.6) * rng.choice([-1, 1]), alpha=rng.choice([0, PI])),
        Revolute(d=u(-0.2, 0.2), a=u(0.2, 0.6) * rng.choice([-1, 1]), alpha=rng.choice([0, PI])),
        Revolute(d=u(-0.2, 0.2), a=u(-0.1, 0.1), alpha=twist(rng), offset=u(-PI, PI)),
        Revolute(
            d=u(-0.2, 0.2),
            a=u(0.03, 0.15) * rng.choice([-1, 1]),
            alpha=twist(rng),
            offset=u(-PI, PI),
        ),
        Revolute(d=u(-0.2, 0.2), a=u(-0.1, 0.1), alpha=u(-PI, PI), offset=u(-PI, PI)),
    ]
    base = transform_from(rng.normal(size=4), rng.uniform(-0.5, 0.5, 3))
    tool = transform_from(rng.normal(size=4), rng.uniform(-0.2, 0.2, 3))
    robot = Robot.from_dh(rows, base=base, tool=tool)
    if modified:
        robot = robot.to_convention("modified")
    assert classify(robot).kind == "three-parallel-6R"
    return robot


def solve_general(robot: Robot, T: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Candidates ``(N, 8, 6)`` of the general solver; every real one exact. Also the pose error."""
    solver = make_three_parallel_solver(robot)
    assert isinstance(solver, GeneralThreeParallelSolver)
    cand = solver.solve(T)
    q = cand.q
    assert q.shape == (len(T), 8, 6) and cand.labels == GENERAL_LABELS
    nan = np.isnan(q)
    assert (nan.any(axis=2) == nan.all(axis=2)).all(), "a branch is partly NaN"
    real = ~nan.any(axis=2)
    reached = robot.fk(np.where(real[..., None], q, 0.0))
    want = np.broadcast_to(T[:, None], reached.shape)
    assert_transform_close(reached[real], want[real], 1e-10)
    return q, np.abs(reached[real] - want[real]).max(initial=0.0)


@pytest.mark.parametrize("modified", [False, True])
def test_axes_5_6_apart_round_trip(modified: bool) -> None:
    rng = np.random.default_rng(50 + modified)
    robots = [Robot.from_dh(UR5_A5_ROWS)] + [random_general(rng, modified) for _ in range(8)]
    if modified:
        robots[0] = robots[0].to_convention("modified")
    worst = 0.0
    for robot in robots:
        q = rng.uniform(-PI, PI, (300, 6))
        cand, err = solve_general(robot, robot.fk(q))
        worst = max(worst, err)
        assert found(q, cand).all()
        counts = (~np.isnan(cand).any(axis=2)).sum(axis=1)
        assert set(counts.tolist()) <= {2, 4, 6, 8}
    assert worst <= EXACT


def test_axes_5_6_apart_complete_against_multistart_search() -> None:
    rng = np.random.default_rng(51)
    robots = [Robot.from_dh(UR5_A5_ROWS), random_general(rng, False), random_general(rng, True)]
    for robot in robots:
        for q in rng.uniform(-PI, PI, (2, 6)):
            T = robot.fk(q)
            cand = solve_general(robot, T[None])[0][0]
            ours = cand[~np.isnan(cand).any(axis=1)]
            theirs = dls_solutions(robot, T, rng)
            assert len(theirs) >= 1
            for s in theirs:
                assert joint_distance(robot, ours, s).min() < 1e-6, f"missed {s}"


def test_axes_5_6_apart_through_robot_ik() -> None:
    robot = Robot.from_dh(UR5_A5_ROWS)
    q = np.array([0.3, -1.1, 1.4, -0.2, 0.8, 0.5])
    result = robot.ik(robot.fk(q))
    assert result.method == "analytic:three-parallel-6R"


def test_axes_5_6_apart_wrist_aligned_is_singular_with_q6_free() -> None:
    rng = np.random.default_rng(52)
    robot = Robot.from_dh(UR5_A5_ROWS)
    q = rng.uniform(-PI, PI, (50, 6))
    q[:, 4] = rng.choice([0.0, PI], 50)  # axis 6 parallel to axes 2-4
    T = robot.fk(q)
    cand, _ = solve_general(robot, T)
    got = make_three_parallel_solver(robot).solve(T)  # type: ignore[union-attr]
    real = ~np.isnan(cand).any(axis=2)
    assert real.any(axis=1).all()
    assert got.singular.all()
    assert (got.free[:, [1, 2, 3, 5]]).all() and not got.free[:, [0, 4]].any()
