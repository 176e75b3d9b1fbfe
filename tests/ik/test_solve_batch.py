"""One path for one target and for a batch: the answers are identical.

For every built-in arm (each closed-form class and the numeric solver) a batch
of targets of every kind — reachable, beyond the joint limits, singular,
unreachable, malformed — is solved at once and target by target; status,
method, solutions, branches, residuals and message agree exactly.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

import kinematica as km


def targets_of(robot: km.Robot, rng: np.random.Generator) -> np.ndarray:
    n = robot.dof
    lo, hi = robot.qlim[:, 0], robot.qlim[:, 1]
    lo = np.where(np.isfinite(lo), lo, -1.0)
    hi = np.where(np.isfinite(hi), hi, 1.0)
    inside = rng.uniform(lo, hi, (4, n))
    span = hi - lo
    outside = inside[:1] + np.where(robot.has_limits, span * 0.6, 0.0)  # past a limit
    home = np.zeros((1, n))  # often singular (wrist or elbow in line)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", km.KinematicaWarning)
        T = robot.fk(np.concatenate([inside, outside, home]))
    far = T[:1].copy()
    far[0, :3, 3] += 50.0  # beyond any reach
    bad = T[:1].copy()
    bad[0, 0, 3] = np.nan  # malformed: only in the batch
    return np.concatenate([T, far, bad])


@pytest.mark.parametrize("name", km.builtin_names())
def test_batch_and_single_agree(name: str) -> None:
    robot = km.load(name)
    T = targets_of(robot, np.random.default_rng(7))
    many = robot.ik(T, seed=0)
    assert many.shape == (len(T),)
    assert many.status[-1] == "invalid"
    for i in range(len(T) - 1):
        one = robot.ik(T[i], seed=0)
        row = many[i]
        assert one.status == row.status == many.status[i]
        assert one.method == row.method
        assert one.branches == row.branches
        assert one.free_joints == row.free_joints
        np.testing.assert_array_equal(one.solutions, row.solutions)
        np.testing.assert_array_equal(one.residuals, row.residuals)
        np.testing.assert_array_equal(one.out_of_limits, row.out_of_limits)
        assert one.message == row.message == many.message[i]


def test_batch_shape_is_kept() -> None:
    puma = km.load("puma560")
    rng = np.random.default_rng(1)
    q = rng.uniform(-1.0, 1.0, (2, 3, 6))
    many = puma.ik(puma.fk(q))
    assert many.shape == (2, 3) and many.count.shape == (2, 3)
    flat = puma.ik(puma.fk(q.reshape(6, 6)))
    np.testing.assert_array_equal(many.count.ravel(), flat.count)
    for (i, j), k in zip(np.ndindex(2, 3), range(6), strict=True):
        np.testing.assert_array_equal(many[i, j].solutions, flat[k].solutions)
        assert many.message[i, j] == flat.message[k]


def _ur5_a5() -> km.Robot:
    """The UR5 with a5 = 5 cm: axes 5 and 6 apart (the quartic)."""
    ur5 = km.load("ur5")
    rows = list(ur5.links)
    rows[4] = km.Revolute(d=rows[4].d, a=0.05, alpha=rows[4].alpha, offset=rows[4].offset)
    return km.Robot.from_dh(rows, base=ur5.base, tool=ur5.tool, convention="standard").with_limits(
        ur5.qlim
    )


@pytest.mark.parametrize("arm", ["puma560", "ur5", "stanford", "ur5-a5", "puma560-position"])
def test_batch_across_blocks_agrees_with_single(arm: str) -> None:
    # Batches reuse work arrays within blocks of 64 targets: 200 targets of
    # every kind, shuffled, so that blocks hold reachable targets after
    # unreachable, singular and malformed ones.
    robot = _ur5_a5() if arm == "ur5-a5" else km.load(arm.split("-")[0])
    rng = np.random.default_rng(11)
    T = np.concatenate([targets_of(robot, rng) for _ in range(25)])
    T = T[rng.permutation(len(T))]
    if arm.endswith("position"):
        T = T[:, :3, 3]
    many = robot.ik(T)
    for i in range(len(T)):
        if many.status[i] == "invalid":
            continue
        one = robot.ik(T[i])
        assert one.status == many.status[i]
        assert one.branches == many[i].branches
        np.testing.assert_array_equal(one.solutions, many[i].solutions)
        np.testing.assert_array_equal(one.out_of_limits, many[i].out_of_limits)
        assert one.message == many.message[i]


def test_unreachable_targets_get_the_same_answer_alone_and_in_a_batch() -> None:
    arm = km.load("anthropomorphic-3r")
    rng = np.random.default_rng(3)
    q = rng.uniform(-np.pi, np.pi, (200, 3))
    T = arm.fk(q)
    # turn every target's orientation away from what the arm can reach there
    turn = km.rotx(0.4) @ km.roty(0.3)
    T[:, :3, :3] = T[:, :3, :3] @ turn
    many = arm.ik(T)
    for i in range(len(T)):
        one = arm.ik(T[i])
        assert one.status == many.status[i] == "unreachable"
        assert one.message == many.message[i] == many[i].message
        np.testing.assert_array_equal(one.solutions, many[i].solutions)
