"""The first or last joint's value as a move of the targets: the same answers, honestly checked."""

from __future__ import annotations

import math

import numpy as np
import pytest
from support.helpers import assert_transform_close

import kinematica as km
from kinematica.ik import IKOptions
from kinematica.ik.moved import (
    NARROWEST,
    ON_AXIS_TOL,
    end_arm,
    moved_targets,
    narrowed_tolerance,
    on_axis,
)
from kinematica.ik.parameter import locked_chain
from kinematica.ik.solve import solve_ik


def arm(offset: float, slides: bool = False) -> km.Robot:
    """A UR5 whose flange turns about (or slides along) a 7th joint; the tool ``offset`` m
    off that axis."""
    ur5 = km.load("ur5")
    last = km.Prismatic(theta=0.0, qlim=(-0.2, 0.2)) if slides else km.Revolute(d=0.04)
    rows = [*ur5.links, last]
    return km.Robot.from_dh(
        rows, base=ur5.base, tool=np.array(km.transl(offset, 0.0, 0.08)), convention="standard"
    )


@pytest.mark.parametrize(("k", "slides"), [(0, False), (6, False), (6, True)])
def test_a_moved_target_is_what_the_arm_locked_at_0_reaches(k: int, slides: bool) -> None:
    robot = arm(0.2, slides)
    chain = robot.chain
    locked = end_arm(chain, k)
    assert end_arm(chain, k) is locked  # built once per joint
    Q = robot.random_q(3, seed=1)
    T = robot.fk(Q)
    moved = moved_targets(chain, k, T, Q[:, k])
    one = moved_targets(chain, k, T[:1], Q[:1, k])
    assert_transform_close(locked.fk(np.delete(Q, k, axis=1))[0], moved, atol=1e-13)
    assert_transform_close(one, moved[:1], atol=1e-15)


@pytest.mark.parametrize(("shift", "narrowed"), [(0.49, True), (0.51, False)])
def test_a_target_moved_past_the_last_joint_keeps_at_least_half_the_tolerance(
    shift: float, narrowed: bool
) -> None:
    # the tool 0.3 m off the last axis: a turn by v moves it by 0.6 sin(v/2)
    chain = arm(0.3).chain
    v = np.array([2.0 * math.asin(shift / 0.6)])
    narrow = narrowed_tolerance(None, chain, 6, v)
    assert NARROWEST == 0.5
    if narrowed:
        assert narrow == pytest.approx((1e-10 * (1.0 - shift), 1e-10), rel=1e-9)
    else:
        assert narrow is None


@pytest.mark.parametrize(
    ("offset", "exact"), [(0.5 * ON_AXIS_TOL, True), (2.0 * ON_AXIS_TOL, False)]
)
def test_the_tool_point_is_on_the_last_axis_within_round_off(offset: float, exact: bool) -> None:
    assert ON_AXIS_TOL == 1e-12
    assert on_axis(arm(offset).chain) is exact


def test_a_last_joint_held_at_a_new_value_each_call_moves_the_target_not_the_arm() -> None:
    # the tool on the last axis: each value is the arm locked at 0 with the target moved,
    # the same answer as the arm locked at that value (built here, apart) gives
    robot = arm(0.0)
    chain = robot.chain
    Q = robot.random_q(6, seed=3)
    T = robot.fk(Q)
    values = [*Q[:3, 6].tolist(), 0.4, -2.5, 3.0]  # the generating values, then others
    for i, v in enumerate(values):
        res = robot.ik(T[i], fixed={6: v})
        alone = solve_ik(chain.locked(6, v), T[i], IKOptions())
        assert str(res.status) == str(alone.status) and res.count == alone.count
        if i < 3:
            assert res.count >= 1
        np.testing.assert_array_equal(res.solutions[:, 6], v)
        np.testing.assert_allclose(res.solutions[:, :6], alone.solutions, atol=1e-9)
        assert res.branches == alone.branches
    assert "locked arms" not in chain.memo  # no arm locked at any of those values
    assert locked_chain(chain, 6, 0.0) is end_arm(chain, 6)
