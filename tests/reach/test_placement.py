"""Base placement: a task built from a known base finds that base, and every base it
reports reaches every task pose (checked by IK again, one candidate at a time)."""

from __future__ import annotations

import numpy as np
import pytest

import kinematica as km
from kinematica.errors import ArgumentError
from kinematica.reach.placement import yaw_pose

POSE_TOL = 1e-9


@pytest.fixture(scope="module")
def problem() -> tuple[km.Robot, np.ndarray, np.ndarray]:
    robot = km.load("puma560")
    base = yaw_pose([0.4, -0.2, 0.0], np.pi / 2)  # on the grid below, yaw one of 4
    lim = robot.qlim
    q = np.random.default_rng(3).uniform(0.5 * lim[:, 0], 0.5 * lim[:, 1], (6, 6))
    return robot, base, base @ robot.fk(q)


def test_the_known_base_is_feasible_and_every_feasible_base_reaches(
    problem: tuple[km.Robot, np.ndarray, np.ndarray],
) -> None:
    robot, base, task = problem
    region = [[0.0, -0.6, 0.0], [0.8, 0.2, 0.0]]
    found = km.base_placement(robot, task, region, resolution=0.2, yaw=4)
    assert found.positions.shape == (5 * 5 * 4, 3)
    known = np.flatnonzero(
        np.all(np.abs(found.positions - base[:3, 3]) < 1e-12, axis=1)
        & np.isclose(found.yaws, np.pi / 2)
    )
    assert known.size == 1 and found.feasible[known[0]]
    assert 1 <= found.count < found.positions.shape[0]  # some bases are too far
    for W_B in found.poses():
        local = np.linalg.inv(W_B) @ task
        for T in local:
            res = robot.ik(T)
            assert res.count > 0
            np.testing.assert_allclose(robot.fk(res.solutions[0]), T, atol=POSE_TOL)
    # ranked by the worst manipulability over the task, best first
    from kinematica.reach.placement import TIE_TOL

    worst = found.worst_manipulability[found.order]
    assert np.all(np.diff(worst) <= TIE_TOL * worst[0]) and np.all(worst > 0)
    assert worst[0] >= (1 - TIE_TOL) * worst.max()
    np.testing.assert_allclose(found.best, found.poses()[0])
    # an infeasible candidate misses a task pose
    for i in np.flatnonzero(~found.feasible)[:5]:
        local = np.linalg.inv(yaw_pose(found.positions[i], found.yaws[i])) @ task
        assert any(robot.ik(T).count == 0 for T in local)


def test_no_base_reaches_a_task_wider_than_the_arm(problem) -> None:  # type: ignore[no-untyped-def]
    robot, _, _ = problem
    task = np.stack([km.transl(-5, 0, 0), km.transl(5, 0, 0)])
    found = km.base_placement(robot, task, [[-1, -1, 0], [1, 1, 0]], resolution=0.5)
    assert found.count == 0 and found.best is None and found.poses().shape == (0, 4, 4)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"region": [[0, 0, 0], [-1, 0, 0]]}, "region"),
        ({"resolution": -1}, "resolution"),
        ({"resolution": 1e-4}, "candidate"),
        ({"yaw": 0}, "yaw"),
        ({"yaw": "north"}, "yaw"),
        ({"task_poses": np.eye(3)}, "task_poses"),
    ],
)
def test_bad_arguments(problem, kwargs, match) -> None:  # type: ignore[no-untyped-def]
    robot, _, task = problem
    args = {"task_poses": task, "region": [[0, 0, 0], [1, 1, 0]], **kwargs}
    with pytest.raises(km.KinematicaError, match=match):
        km.base_placement(robot, args.pop("task_poses"), args.pop("region"), **args)
    assert issubclass(ArgumentError, km.KinematicaError)


def test_ties_within_tie_tol_keep_the_grid_order() -> None:
    from kinematica.reach.placement import TIE_TOL, rank

    ok = np.ones(2, dtype=bool)
    inside, outside = 1.0 - 0.9 * TIE_TOL, 1.0 - 1.1 * TIE_TOL
    assert rank(np.array([inside, 1.0]), ok).tolist() == [0, 1]  # equal: grid order
    assert rank(np.array([outside, 1.0]), ok).tolist() == [1, 0]  # better first
    worst = np.array([0.2, np.nan, 0.5, 0.5])
    assert rank(worst, np.array([True, False, True, True])).tolist() == [2, 3, 0]
    assert rank(worst, np.zeros(4, dtype=bool)).size == 0
