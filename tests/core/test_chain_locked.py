"""Chain.locked: a joint held at a value folds into its neighbours; FK is unchanged.

Checked against the whole chain's own FK (the core's walk, a second path through
the compiled data) and against a product of the chain's fixed parts written here.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from support.helpers import assert_transform_close
from support.urdf import URDF_DIR

import kinematica as km
from kinematica.core import Chain

ARMS = ["panda", "iiwa14", "puma560", "stanford", "scara"]  # modified, standard, slides
URDF = URDF_DIR / "ufactory_xarm7.urdf"


@pytest.mark.parametrize("name", ARMS)
def test_fixed_parts_rebuild_the_fk(name: str) -> None:
    # T = start · Π [M_i(q_i) · fixed_i] · tool, written out with numpy products
    robot = km.load(name)
    chain = robot.chain
    for q in robot.random_q(4, seed=2):
        T = chain.start.copy()
        for i, F in enumerate(chain.fixed_parts):
            T = T @ chain.motion(i, float(q[i])) @ F
        assert_transform_close(T @ chain.tool, robot.fk(q), atol=1e-13)


@pytest.mark.parametrize("name", ARMS)
def test_locking_any_joint_keeps_the_fk(name: str) -> None:
    robot = km.load(name)
    chain = robot.chain
    for q in robot.random_q(3, seed=5):
        for k in range(robot.dof):
            arm = chain.locked(k, float(q[k]))
            assert arm.dof == robot.dof - 1
            assert list(arm.prismatic) == [p for i, p in enumerate(chain.prismatic) if i != k]
            np.testing.assert_array_equal(arm.own_limits, np.delete(chain.own_limits, k, axis=0))
            T = arm.fk(np.delete(q, k))[0]
            assert_transform_close(T, robot.fk(q), atol=1e-13, err_msg=f"{name} joint {k}")


def test_locking_a_urdf_chain_keeps_its_fk() -> None:
    robot = km.load(URDF)
    assert robot.transforms is not None  # general transforms, not DH
    q = robot.random_q(1, seed=1)[0]
    for k in (0, 3, 6):
        T = robot.chain.locked(k, float(q[k])).fk(np.delete(q, k))[0]
        assert_transform_close(T, robot.fk(q), atol=1e-13)


def test_a_two_joint_arm_locks_to_one_and_a_one_joint_arm_refuses() -> None:
    arm = km.Robot.from_dh(
        [km.Revolute(a=1.0), km.Prismatic(theta=0.3, a=0.5)], convention="standard"
    )
    one = arm.chain.locked(1, 0.25)
    q = 0.7
    expected = arm.fk([q, 0.25])
    assert_transform_close(one.fk(np.array([q]))[0], expected, atol=1e-15)
    with pytest.raises(ValueError, match="one joint"):
        one.locked(0, 0.0)


def test_motion_is_a_turn_or_a_slide() -> None:
    arm = km.Robot.from_dh([km.Revolute(), km.Prismatic()], convention="standard")
    c, s = math.cos(0.4), math.sin(0.4)
    np.testing.assert_allclose(arm.chain.motion(0, 0.4)[:2, :2], [[c, -s], [s, c]], atol=0)
    M = arm.chain.motion(1, 0.4)
    np.testing.assert_array_equal(M[:3, :3], np.eye(3))
    assert M[2, 3] == 0.4
    assert isinstance(arm.chain.locked(0, 0.1), Chain)


def test_the_core_refuses_a_lock_it_cannot_make() -> None:
    # the core's own checks (the Python above checks first): an error, never a crash
    core = km.load("puma560").chain.core
    for joint, value in ((6, 0.0), (-1, 0.0), (0, math.nan), (0, math.inf)):
        with pytest.raises((ValueError, IndexError)):
            core.locked(joint, value)
    with pytest.raises(ValueError, match="one joint"):
        km.Robot.from_dh([km.Revolute(a=1.0)], convention="standard").chain.core.locked(0, 0.0)
