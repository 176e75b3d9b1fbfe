"""Cartesian paths near a singular set: passages, joint-rate jumps and the end's branch told.

The issue's case: the notes' 6-DOF arm (spherical wrist: the angle between axes 4
and 6 is q5) on the line from q = (30, 40, -30, 10, 10, 0)° to (30, 40, -30, 10,
-10, 0)°, whose wrist passes within 0.37° of aligned. References: |sin q5| from the
joint values, joint steps from np.diff, the goal's branch from its own IK.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinematica as km
from kinematica.motion import cartesian_path
from kinematica.motion.path_checks import (
    END_TOL,
    NEAR_SINGULAR_TOL,
    SPEED_JUMP_RATIO,
    end_branch,
    near_singular_passages,
    speed_jumps,
)

QA = np.radians([30, 40, -30, 10, 10, 0])
QB = np.radians([30, 40, -30, 10, -10, 0])


@pytest.fixture(scope="module")
def arm6():
    return km.load("arm6-dh")


@pytest.fixture(scope="module")
def wrist_path(arm6):
    return cartesian_path(arm6, arm6.fk(QA), arm6.fk(QB), steps=201, q0=QA, q1=QB)


def test_near_wrist_passage_is_an_event_where_q5_is_smallest(wrist_path):
    near = [e for e in wrist_path.events if e.kind == "near_singularity"]
    assert len(near) == 1 and near[0].names == ("wrist",)
    sine = np.abs(np.sin(wrist_path.q[:, 4]))  # the reference measure
    k = int(np.argmin(sine))
    assert near[0].s == wrist_path.s[k]
    assert f"closest at sample {k} " in near[0].message
    assert f"{math.degrees(math.asin(sine[k])):.3g}°" in near[0].message
    inside = np.flatnonzero(sine < NEAR_SINGULAR_TOL)
    assert (near[0].index, near[0].stop) == (inside[0], inside[-1])


def test_joint_rate_jump_is_an_event_with_its_size(wrist_path):
    jumps = [e for e in wrist_path.events if e.kind == "speed_jump"]
    assert len(jumps) == 1
    steps = np.abs(np.diff(wrist_path.q, axis=0))
    k = int(np.argmax(steps.max(axis=1)))
    joint = int(np.argmax(steps[k]))
    assert jumps[0].names == (f"q{joint + 1}",) and joint in (3, 5)  # q4 or q6
    assert jumps[0].s == wrist_path.s[k + 1]
    assert f"turns {math.degrees(steps[k, joint]):.3g}°" in jumps[0].message
    assert math.degrees(steps[k, joint]) > 10.0  # the 15.5° step


def test_end_on_the_other_wrist_branch_is_said(arm6, wrist_path):
    end = [e for e in wrist_path.events if e.kind == "end_branch"]
    assert len(end) == 1 and end[0].index == 200
    # the path ends where fk agrees with T1 but q differs from QB by the wrist flip
    np.testing.assert_allclose(arm6.fk(wrist_path.q[-1]), arm6.fk(QB), atol=1e-9)
    assert np.degrees(np.abs(np.angle(np.exp(1j * (wrist_path.q[-1] - QB)))))[3] > 170
    assert set(end[0].names) >= {"q4", "q6"}
    assert "wrist flip" in end[0].message
    # without q1 nothing was asked of the end
    quiet = cartesian_path(arm6, arm6.fk(QA), arm6.fk(QB), steps=201, q0=QA)
    assert "end_branch" not in [e.kind for e in quiet.events]


def test_a_regular_path_meets_none_of_them(arm6):
    q0 = np.radians([30, 40, -30, 10, 60, 0])
    T0 = arm6.fk(q0)
    T1 = T0.copy()
    T1[:3, 3] += [0.03, -0.03, 0.03]
    path = cartesian_path(arm6, T0, T1, steps=60, q0=q0, q1=q0)  # q1: a branch, not a pose
    assert path.ok, path.events
    flipped = q0 + np.radians([0, 0, 0, 180, 0, 180])
    flipped[4] = -q0[4]
    path = cartesian_path(arm6, T0, T1, steps=60, q0=q0, q1=flipped)
    assert [e.kind for e in path.events] == ["end_branch"]


@pytest.mark.parametrize(("sine", "near"), [(0.049, True), (0.051, False)])
def test_near_singular_tol_is_0_05(arm6, sine, near):
    assert NEAR_SINGULAR_TOL == 0.05
    q = np.tile(np.radians([30, 40, -30, 10, 0, 0]), (3, 1))
    q[:, 4] = math.asin(sine)
    found = near_singular_passages(arm6, np.linspace(0, 1, 3), q)
    assert bool(found) is near


@pytest.mark.parametrize(("ratio", "jump"), [(0.95, False), (1.05, True)])
def test_speed_jump_ratio_is_10(arm6, ratio, jump):
    s = np.linspace(0, 1, 21)
    steps = np.full(20, 0.01)
    steps[10] = 0.01 * SPEED_JUMP_RATIO * ratio
    q = np.zeros((21, 6))
    q[1:, 3] = np.cumsum(steps)
    found = speed_jumps(arm6, s, q)
    assert bool(found) is jump
    if jump:
        assert found[0][1] == 11 and found[0][4] == ("q4",)


@pytest.mark.parametrize(("offset", "said"), [(END_TOL / 2, False), (END_TOL * 2, True)])
def test_end_tol_is_1e_6(arm6, offset, said):
    q = np.tile(QB, (2, 1))
    q[-1, 0] += offset
    found = end_branch(arm6, arm6.fk(QB), q, np.array([0.0, 1.0]), QB, False)
    assert bool(found) is said


def test_relative_elbow_measure_is_the_triangle_sine():
    # Planar 2-link part (l2 = 0.4, l3 = 0.3): by the law of sines the angle at the tip
    # of the triangle shoulder-elbow-tip has sine l2·sin q3 / |tip - shoulder|.
    from kinematica.robot.singularities import singularity_measures

    robot = km.load("anthropomorphic-3r")
    q = np.array([[0.3, 0.5, 0.7], [0.1, -0.4, 2.5], [1.0, 1.0, 0.01]])
    reach = np.sqrt(0.4**2 + 0.3**2 + 2 * 0.4 * 0.3 * np.cos(q[:, 2]))
    expected = 0.4 * np.abs(np.sin(q[:, 2])) / reach
    got = singularity_measures(robot, q, relative=True)["elbow"]
    np.testing.assert_allclose(got, expected, rtol=1e-12)


@pytest.mark.parametrize(("step", "jump"), [(5e-10, False), (5e-9, True)])
def test_step_roundoff_is_1e_9(arm6, step, jump):
    # a path that does not move but for one step: a jump only beyond round-off
    from kinematica.motion.path_checks import STEP_ROUNDOFF

    assert STEP_ROUNDOFF == 1e-9
    q = np.zeros((21, 6))
    q[11:, 0] = step
    assert bool(speed_jumps(arm6, np.linspace(0, 1, 21), q)) is jump
