"""The first or last joint's value as a move of the targets: the same answers, honestly checked."""

from __future__ import annotations

import math

import numpy as np
import pytest
from support.helpers import assert_transform_close

import kinematica as km
from kinematica.ik.moved import NARROWEST, end_arm, moved_targets, narrowed_tolerance


def arm(offset: float) -> km.Robot:
    """A UR5 whose flange turns about a 7th joint; the tool ``offset`` m off that axis."""
    ur5 = km.load("ur5")
    rows = [*ur5.links, km.Revolute(d=0.04)]
    return km.Robot.from_dh(
        rows, base=ur5.base, tool=np.array(km.transl(offset, 0.0, 0.08)), convention="standard"
    )


@pytest.mark.parametrize("k", [0, 6])
def test_a_moved_target_is_what_the_arm_locked_at_0_reaches(k: int) -> None:
    robot = arm(0.2)
    chain = robot.chain
    locked, G, G_inv = end_arm(chain, k)
    assert end_arm(chain, k)[0] is locked  # built once per joint
    Q = robot.random_q(3, seed=1)
    T = robot.fk(Q)
    moved = moved_targets(bool(chain.prismatic[k]), k, G, G_inv, T, Q[:, k])
    one = moved_targets(bool(chain.prismatic[k]), k, G, G_inv, T[:1], Q[:1, k])
    assert_transform_close(locked.fk(np.delete(Q, k, axis=1))[0], moved, atol=1e-13)
    assert_transform_close(one, moved[:1], atol=1e-15)


@pytest.mark.parametrize(("shift", "narrowed"), [(0.49, True), (0.51, False)])
def test_a_target_moved_past_the_last_joint_keeps_at_least_half_the_tolerance(
    shift: float, narrowed: bool
) -> None:
    # the tool 0.3 m off the last axis: a turn by v moves it by 0.6 sin(v/2)
    chain = arm(0.3).chain
    _, G, G_inv = end_arm(chain, 6)
    v = np.array([2.0 * math.asin(shift / 0.6)])
    narrow = narrowed_tolerance(None, False, 6, G, G_inv, v)
    assert NARROWEST == 0.5
    if narrowed:
        assert narrow == pytest.approx((1e-10 * (1.0 - shift), 1e-10), rel=1e-9)
    else:
        assert narrow is None
