"""Position targets of longer arms: joints 1-3 place the tool origin, joints 4..n free.

References: EAIK's PUMA 560 solution sets (``data/reference/ik_reference.json``:
on the PUMA the tool origin is the wrist centre, so the first three joints of
the pose solutions are the arm solutions of its position), forward kinematics
of every answer, the generating configuration, and the DH table itself for
the bound on how far the later joints move the tool origin.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from support import DATA as TESTS_DATA
from support.helpers import transform_from
from support.ik_search import joint_distance, random_q

import kinematica as km
from kinematica import _core_testing
from kinematica.dh import Revolute
from kinematica.ik import IKBatchResult, IKResult, closed_form
from kinematica.ik.fallback import PARTIAL_NOTE
from kinematica.robot import Robot

PI = math.pi
DATA = TESTS_DATA / "reference"
ARMS = ["puma560", "irb120", "kr6", "arm6-dh", "stanford", "ur5"]


def seven_dof() -> Robot:
    """A PUMA-like arm with a redundant wrist joint (its first three axes qualify)."""
    rows = [
        Revolute(d=0.4, alpha=PI / 2),
        Revolute(a=0.45),
        Revolute(alpha=PI / 2, offset=PI / 2),
        Revolute(d=0.4, alpha=-PI / 2),
        Revolute(alpha=PI / 2),
        Revolute(d=0.1, alpha=-PI / 2),
        Revolute(d=0.08),
    ]
    return Robot.from_dh(
        rows, tool=transform_from([1, 0.2, 0, 0], [0, 0, 0.05]), name="7-DOF", convention="standard"
    )


def wrist_at_zero(robot: Robot, rng: np.random.Generator, n: int) -> np.ndarray:
    q = random_q(robot, rng, n)
    q[:, 3:] = 0.0
    return q


@pytest.mark.parametrize("name", [*ARMS, "7-DOF"])
def test_arm_solutions_with_the_later_joints_at_zero(name: str) -> None:
    robot = seven_dof() if name == "7-DOF" else km.load(name)
    assert km.classify(robot).kind != "arm-position"  # it names no structure
    rng = np.random.default_rng(41)
    q = wrist_at_zero(robot, rng, 30)
    p = robot.fk(q)[:, :3, 3]
    res = robot.ik(p, respect_limits=False)
    assert isinstance(res, IKBatchResult) and res.method == "analytic:arm-position"
    assert (res.status == "singular").all()
    assert (res.free[:, 3:]).all()
    assert (res.count >= 1).all() and (res.count <= 4).all()
    sols = np.nan_to_num(res.solutions)
    real = ~np.isnan(res.solutions[..., 0])
    assert (sols[..., 3:][real] == 0.0).all()
    reached = robot.fk(sols)[..., :3, 3]
    err = np.linalg.norm(reached - p[:, None, :], axis=-1)
    assert (err[real] <= 1e-10).all()
    d = np.nan_to_num(joint_distance(robot, res.solutions, q[:, None]), nan=np.inf)
    assert (d.min(axis=1) < 1e-7).all()


def test_puma_four_arm_solutions_are_eaik_s_first_three_joints() -> None:
    arms = json.loads((DATA / "ik_reference.json").read_text())["arms"]
    arm = next(a for a in arms if a["name"] == "puma560")
    puma = km.load("puma560")
    for sample in arm["samples"][:20]:
        T = np.array(sample["T"])
        theirs = np.array(sample["solutions"])[:, :3]
        res = puma.ik(T[:3, 3], respect_limits=False)
        assert res.status == "singular" and res.free_joints == (3, 4, 5)
        ours = res.solutions[:, :3]
        d = np.abs(np.angle(np.exp(1j * (ours[:, None, :] - theirs[None, :, :])))).max(axis=-1)
        assert (d.min(axis=0) < 1e-9).all() and (d.min(axis=1) < 1e-9).all()
        assert len(ours) == len({tuple(np.round(t, 6)) for t in theirs})


def test_puma_branches_are_the_seed_decoupling() -> None:
    puma = km.load("puma560")
    solver = closed_form(puma.chain, "position")
    assert solver is not None and solver.position_only and solver.partial
    assert solver.labels == (
        "shoulder right, elbow up",
        "shoulder right, elbow down",
        "shoulder left, elbow up",
        "shoulder left, elbow down",
    )
    res = puma.ik(puma.fk(np.array([0.3, -0.6, 0.2, 0.5, 0.9, -0.4]))[:3, 3], respect_limits=False)
    assert res.count == 4 and set(res.branches) == set(solver.labels)


def test_reach_after_joint_3_bounds_the_tool_origin() -> None:
    rng = np.random.default_rng(42)
    for robot in (km.load("arm6-dh"), km.load("ur5"), km.load("stanford"), seven_dof()):
        bound = _core_testing.decoupled.reach_after_joint3(robot.chain.core)
        q = random_q(robot, rng, 2000)
        moved = (
            robot.fk(q)[:, :3, 3] - robot.fk(np.where(np.arange(robot.dof) < 3, q, 0.0))[:, :3, 3]
        )
        assert np.linalg.norm(moved, axis=1).max() <= bound
    assert (
        _core_testing.decoupled.reach_after_joint3(km.load("puma560").chain.core) == 0.0
    )  # the tool origin is the wrist centre


def test_unreachable_only_with_a_proof() -> None:
    puma = km.load("puma560")  # no tool: joints 4-6 cannot move the tool origin
    res = puma.ik(np.array([3.0, 0.0, 0.0]))
    assert res.status == "unreachable" and res.gap is not None and res.gap > 2.0
    arm = km.load("arm6-dh")  # joint 6's flange sits 0.1 m beyond the wrist centre
    reach = _core_testing.decoupled.reach_after_joint3(arm.chain.core)
    far_arm = np.linalg.norm(arm.fk(np.zeros(6))[:3, 3] - np.array([0.0, 0.0, 0.5]))
    within = arm.ik(np.array([0.0, 0.0, 0.5 + far_arm + 0.5 * reach]))
    # The wrist-at-0 shell (0.9 m about the shoulder) less 2 x 0.1 m proves nothing here;
    # the wrist centre's shell (0.8 m) less the flange's 0.1 m proves the exact distance:
    # the target is 0.9 + 0.1 = 1.0 m above the shoulder, 0.1 m beyond the reach of 0.9 m
    assert far_arm == pytest.approx(0.9, abs=1e-12) and reach == pytest.approx(0.2, abs=1e-12)
    assert within.method == "analytic:arm-position"
    assert within.status == "unreachable" and within.gap is not None
    assert within.gap == pytest.approx(0.1, abs=1e-12)
    beyond = arm.ik(np.array([0.0, 0.0, 0.5 + far_arm + 2.0 * reach]))
    assert beyond.status == "unreachable" and beyond.gap is not None
    assert beyond.gap == pytest.approx(2.0 * reach, abs=1e-12)  # 1.3 m above the shoulder


@pytest.mark.parametrize("batch", [(), (1,), (3, 2)])
def test_batch_shapes_and_single_equals_batch(batch: tuple[int, ...]) -> None:
    arm = km.load("arm6-dh")
    rng = np.random.default_rng(43)
    q = wrist_at_zero(arm, rng, int(np.prod(batch, dtype=int)))
    p = arm.fk(q)[:, :3, 3].reshape(*batch, 3)
    res = arm.ik(p)
    if batch == ():
        assert isinstance(res, IKResult) and res.status == "singular"
        return
    assert isinstance(res, IKBatchResult) and res.status.shape == batch
    flat = p.reshape(-1, 3)
    many = arm.ik(np.concatenate([flat, [[5.0, 0.0, 0.0]]]))
    for i, pi in enumerate([*flat, np.array([5.0, 0.0, 0.0])]):
        one = arm.ik(pi)
        assert one.message == many[i].message and one.branches == many[i].branches
        np.testing.assert_array_equal(one.solutions, many[i].solutions)


def test_pose_targets_of_short_arms_never_use_the_position_solver() -> None:
    rows = [Revolute(d=0.4, alpha=PI / 2), Revolute(a=0.4), Revolute(alpha=PI / 2)]
    rows += [Revolute(d=0.4, alpha=-PI / 2), Revolute(alpha=PI / 2)]  # 5R: no pose solver
    arm = Robot.from_dh(rows, name="5R", convention="standard")
    assert closed_form(arm.chain, "position") is not None
    assert closed_form(arm.chain, "pose") is None
    T = arm.fk(np.array([0.2, 0.3, 0.4, 0.5, 0.6]))
    assert arm.ik(T, seed=0).method == "numeric:lm"


@pytest.mark.filterwarnings("ignore::kinematica.KinematicaWarning")
def test_a_target_no_wrist_at_0_configuration_reaches_goes_to_the_numeric_search() -> None:
    """The IRB 120's tool origin is off its wrist centre: 26 of 300 FK targets are
    reached only with joints 4-6 away from 0 (issue 21: they were "not_found")."""
    arm = km.load("irb120")
    rng = np.random.default_rng(0)
    q = rng.uniform(-3.0, 3.0, (300, 6))
    p = np.ascontiguousarray(arm.fk(q)[:, :3, 3])
    res = arm.ik(p, respect_limits=False)
    assert set(res.status.tolist()) <= {"singular", "ok"}
    assert res.methods and all(m == "numeric:lm" for m in res.methods.values())
    for (i,) in res.methods:
        one = arm.ik(p[i], respect_limits=False)
        assert one.status == "ok" and one.method == "numeric:lm" and not one.complete
        assert PARTIAL_NOTE in one.notes and one.message == res[i].message
        assert np.linalg.norm(arm.fk(one.q)[:3, 3] - p[i]) <= 1e-10
