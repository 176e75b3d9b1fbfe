"""Robots travel to Dask workers by pickle: the description goes, the core is rebuilt."""

from __future__ import annotations

import pickle

import numpy as np
import pytest

import kinematica as km


@pytest.mark.parametrize("name", ["puma560", "ur5"])
def test_a_pickled_robot_is_the_same_robot(name: str) -> None:
    robot = km.load(name)
    back = pickle.loads(pickle.dumps(robot))
    assert back.name == robot.name and back.dof == robot.dof
    lim = np.clip(robot.qlim, -3, 3)
    q = np.random.default_rng(0).uniform(lim[:, 0], lim[:, 1], (5, robot.dof))
    np.testing.assert_array_equal(back.fk(q), robot.fk(q))
    np.testing.assert_array_equal(back.qlim, robot.qlim)
    T = robot.fk(q[0])
    np.testing.assert_array_equal(back.ik(T).solutions, robot.ik(T).solutions)
