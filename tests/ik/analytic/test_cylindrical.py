"""The cylindrical arms' closed form, against the lecture notes' formulas and its own bounds.

Seed 001's 4-DOF example: x = (q3 + l4) cos q1, y = (q3 + l4) sin q1, z = l1 + q2,
solved by hand for a position: q1 = atan2(y, x), q3 = sqrt(x² + y²) − l4 (reach
forward) or q1 + π, −sqrt(x² + y²) − l4 (reach backward); q2 = z − l1. Every other
family member (other orders, offsets, tilted reaches, rolls off the tool) is held to
the shared contract by tests/ik/test_registry.py through ``sample_arm``.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import kinematica as km
from kinematica import _core, _core_testing
from kinematica.dh.joints import Prismatic, Revolute

#: Closed-form answers agree with the hand-derived formulas to this (rad, m).
TOL = 1e-12
SINGULAR_TOL = _core_testing.planar.SINGULAR_TOL  # triangle.hpp's, as the planar arms'
MERGE_TOL = _core_testing.planar.MERGE_TOL
L1, L4 = 0.5, 0.1


@pytest.fixture(scope="module")
def notes() -> km.Robot:
    return km.load("cylindrical-4dof")


def _offset_arm(roll: bool = False) -> km.Robot:
    """A cylindrical arm whose reach passes the turn's axis at 0.15 m (a = 0.15 on the lift)."""
    rows = [
        Revolute(d=0.4, a=0.0, alpha=0.0),
        Prismatic(theta=math.pi / 2, a=0.15, alpha=math.pi / 2),
        Prismatic(theta=0.0, a=0.0, alpha=0.0 if not roll else 0.7),
    ]
    if roll:  # the tool 0.05 m off the roll's axis
        rows.append(Revolute(d=0.1, a=0.05, alpha=0.3))
    return km.Robot.from_dh(rows, convention="standard")


def test_the_notes_arm_is_solved_in_closed_form(notes: km.Robot) -> None:
    assert km.classify(notes).kind == "cylindrical-RPPR"
    q = np.array([0.7, 0.3, 0.2, -1.1])
    res = notes.ik(notes.fk(q))
    assert res.method == "analytic:cylindrical-RPPR" and res.status == "ok"
    np.testing.assert_allclose(res.solutions, [q], atol=TOL)
    assert res.branches == ("reach forward",)


def test_position_targets_follow_the_notes_formulas(notes: km.Robot) -> None:
    x, y, z = 0.25, -0.2, 0.8
    r = math.hypot(x, y)
    res = notes.ik(np.array([x, y, z]), respect_limits=False)
    assert res.status == "singular" and res.free_joints == (3,)  # the roll moves no tool origin
    rows = dict(zip(res.branches, res.solutions, strict=True))
    forward = [math.atan2(y, x), z - L1, r - L4, 0.0]
    backward = [math.remainder(math.atan2(y, x) + math.pi, 2 * math.pi), z - L1, -r - L4, 0.0]
    np.testing.assert_allclose(rows["reach forward"], forward, atol=TOL)
    np.testing.assert_allclose(rows["reach backward"], backward, atol=TOL)
    # the backward slide is beyond its limits [0, 0.5] m: within them only the forward one
    within = notes.ik(np.array([x, y, z]))
    assert within.branches == ("reach forward",) and len(within.out_of_limits) == 1


def test_on_the_turns_axis_the_turn_is_free_within_singular_tol(notes: km.Robot) -> None:
    # The notes' arm reaches across the axis (offset 0): a target within SINGULAR_TOL of the
    # reach's size from the axis leaves q1 free; one twice that far does not.
    scale = km.ik.structure.features(notes.chain).size
    inside = notes.ik(np.array([0.5 * SINGULAR_TOL * scale, 0.0, 0.7]), respect_limits=False)
    outside = notes.ik(np.array([2.0 * SINGULAR_TOL * scale, 0.0, 0.7]), respect_limits=False)
    assert inside.status == "singular" and inside.free_joints == (0, 3)
    assert outside.status == "singular" and outside.free_joints == (3,)


def test_near_marks_the_branches_merging_within_merge_tol() -> None:
    robot = _offset_arm()
    scale = km.ik.structure.features(robot.chain).size
    for extra, near in ((0.5, True), (2.0, False)):
        target = np.array([0.15 + extra * MERGE_TOL * scale, 0.0, 0.9])
        res = robot.ik(target, respect_limits=False)
        assert res.status == "ok" and res.near_singular is near, (extra, res.message)


def test_inside_the_reachs_offset_is_unreachable_with_the_exact_gap() -> None:
    robot = _offset_arm()
    for r in (0.0, 0.05, 0.149):  # no tool origin comes closer to axis 1 than 0.15 m
        res = robot.ik(np.array([0.0, r, 0.9]), respect_limits=False)
        assert res.status == "unreachable", res.message
        assert res.gap == pytest.approx(0.15 - r, abs=TOL)
    res = robot.ik(np.array([0.0, 0.151, 0.9]), respect_limits=False)
    assert res.status == "ok" and len(res.solutions) == 2


def test_a_roll_off_the_tool_is_turned_to_reach_a_position() -> None:
    # At q4 = 0 the reach's line passes the axis farther than the target is from it; the
    # representative roll brings it within reach, and every candidate reaches the target.
    robot = _offset_arm(roll=True)
    q = np.array([0.4, 0.2, 0.05, 2.5])
    target = robot.fk(q)[:3, 3]
    res = robot.ik(target, respect_limits=False)
    assert res.method == "analytic:cylindrical-RPPR"
    assert res.status == "singular" and 3 in res.free_joints
    assert len(res.solutions) == 2
    for sol in res.solutions:
        np.testing.assert_allclose(robot.fk(sol)[:3, 3], target, atol=1e-10)
    # the pose of the same q has one solution: q itself
    pose = robot.ik(robot.fk(q), respect_limits=False)
    np.testing.assert_allclose(pose.solutions, [q], atol=1e-10)


def test_targets_at_1e300_give_finite_candidates_and_gaps() -> None:
    # Nothing that grows with the target is squared: across k (the reach) and along it
    # (the lift) a target 1e300 m away gives finite slides, and one inside the offset with
    # a lift of 1e300 m its exact gap.
    robot = _offset_arm()
    closed = km.ik.solve.closed_form(robot.chain, "position")
    assert closed is not None
    for target in ([1e300, 0.0, 0.9], [0.0, 1e300, 1e300], [0.0, 1e-3, 1e300]):
        T = np.eye(4)
        T[:3, 3] = target
        Q = closed.params.candidates(robot.chain.core, T)[0]
        assert np.all(np.isfinite(Q)), (target, Q)
    res = robot.ik(np.array([0.0, 1e-3, 1e300]), respect_limits=False)
    assert res.status == "unreachable" and res.gap == pytest.approx(0.149, abs=TOL)


def test_the_core_builder_reads_the_structure_itself() -> None:
    """The core's builder (a C++ program may hand it any chain) declines other arms, and
    its Params come from it alone (no constructor, no fields to set wrong)."""
    chain = _offset_arm().chain
    assert _core.cylindrical.build(chain.core) is not None
    assert _core.cylindrical.build_position(chain.core) is not None
    assert _core.cylindrical.build(km.load("puma560").chain.core) is None
    assert _core.cylindrical.build(km.load("scara").chain.core) is None
    with pytest.raises(TypeError):
        _core.cylindrical.CylindricalParams()
