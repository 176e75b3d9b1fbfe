"""DH tables extracted by the seed's rules: random chains, round trips, tolerances."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import assume, given
from support.helpers import PROPERTY, assert_transform_close, robot_specs, seeds
from support.urdf import (
    URDF_DIR,
    random_joint_values,
    reference_chain,
    urdf_chains,
    urdf_from_joints,
)
from support.urdf import dh_table as _table
from support.urdf import extraction_rule as _rule
from support.urdf import two_joints as _two_joints

import kinematica as km
from kinematica.dh import (
    AXIS_ANGLE_TOL,
    AXIS_LENGTH_TOL,
    FK_CHECK_TOL,
    line_pair,
)
from kinematica.dh.extract import ROUND_OFF_TOL
from kinematica.io import parse_urdf

#: Random chains: FK of the extracted table equals the URDF's to this (m) (their
#: offsets are never within the line geometry's length tolerance, which the
#: meeting and coinciding rules drop).
CHAIN_ATOL = 1e-10  # the bar: extracted tables reproduce FK to 1e-10


def _wrapped(a: np.ndarray) -> np.ndarray:
    return np.angle(np.exp(1j * a))


def _nearly_parallel_axes(spec, within: float = 1e-6) -> bool:
    """Consecutive axes within ``within`` rad of parallel, not exactly (twists between axes)."""
    twists = [j.alpha for j in spec.joints]
    between = twists[:-1] if spec.convention == "standard" else twists[1:]
    return any(0.0 < abs(math.remainder(t, math.pi)) < within for t in between)


# ------------------------------------------------------------------ random chains
@PROPERTY
@given(joints=urdf_chains(), seed=seeds)
def test_random_urdf_chains_reproduce_fk_in_both_conventions(joints, seed):
    text = urdf_from_joints(joints)
    ref = reference_chain(text, tip="tip")
    model = parse_urdf(text)
    rng = np.random.default_rng(seed)
    q = random_joint_values(ref, rng, (3, 2))
    expected = ref.fk_batch(q)
    for convention in ("standard", "modified"):
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # no FK-check warning on these chains
            ext = km.urdf_to_dh(model, tip="tip", convention=convention)
        robot = ext.robot
        assert robot.convention == convention
        assert robot.dof == ref.dof
        assert_transform_close(robot.fk(q), expected, atol=CHAIN_ATOL)
        assert_transform_close(robot.fk(q[0, 0]), expected[0, 0], atol=CHAIN_ATOL)
        assert_transform_close(robot.fk(q[:1, 0]), expected[:1, 0], atol=CHAIN_ATOL)
        assert ext.fk_error < CHAIN_ATOL
        # the DH frames at q = 0 are the robot's own frames (rows reproduce them)
        frames = robot.fk(np.zeros(robot.dof), all_frames=True)
        assert_transform_close(frames[:-1], ext.frames[:-1], atol=CHAIN_ATOL)
        assert_transform_close(frames[-1], ext.frames[-1] @ robot.tool, atol=CHAIN_ATOL)
        # every frame obeys the DH rules: x_i normal to z_(i-1) (standard) or z_(i+1) (modified)
        F = ext.frames
        if convention == "standard":
            dots = [F[i, :3, 0] @ F[i - 1, :3, 2] for i in range(1, robot.dof + 1)]
        else:
            dots = [F[i, :3, 0] @ F[i + 1, :3, 2] for i in range(robot.dof)]
        assert np.abs(dots).max() < 1e-12


@PROPERTY
@given(spec=robot_specs(max_dof=7), seed=seeds)
def test_dh_robot_to_urdf_and_back_gives_the_same_table(spec, seed):
    robot = spec.build()
    # Nearly parallel consecutive axes are taken as parallel (AXIS_ANGLE_TOL) or get a
    # far-away normal (tested on their own below); between axes at an angle s the normal's
    # direction is only known to 1e-16 / s, which moves theta by as much (FK is unchanged).
    assume(not _nearly_parallel_axes(spec, within=1e-3))
    back = km.urdf_to_dh(parse_urdf(robot.to_urdf()), convention=robot.convention).robot
    assert back.joint_types == robot.joint_types
    assert back.convention == robot.convention
    q = np.random.default_rng(seed).uniform(-2, 2, (4, robot.dof))
    for qq in (np.zeros(robot.dof), *q):
        got, want = back.dh_table(qq), robot.dh_table(qq)
        np.testing.assert_allclose(_wrapped(got[:, [0, 3]] - want[:, [0, 3]]), 0, atol=1e-12)
        np.testing.assert_allclose(got[:, [1, 2]], want[:, [1, 2]], atol=1e-12)
    assert_transform_close(back.base, robot.base, atol=1e-12)
    assert_transform_close(back.tool, robot.tool, atol=1e-12)
    assert back.has_limits.tolist() == robot.has_limits.tolist()
    np.testing.assert_allclose(back.qlim, robot.qlim, atol=0)
    # and through the robot itself, without text
    again = robot.to_dh(robot.convention).robot
    np.testing.assert_allclose(
        _wrapped(again.dh_table()[:, 0] - robot.dh_table()[:, 0]), 0, atol=1e-12
    )


@PROPERTY
@given(spec=robot_specs(max_dof=7), seed=seeds)
def test_to_dh_in_the_other_convention_keeps_fk(spec, seed):
    robot = spec.build()
    assume(not _nearly_parallel_axes(spec))
    other = "modified" if robot.convention == "standard" else "standard"
    ext = robot.to_dh(other)
    q = np.random.default_rng(seed).uniform(-3, 3, (5, robot.dof))
    assert_transform_close(ext.robot.fk(q), robot.fk(q), atol=CHAIN_ATOL)
    assert ext.robot.convention == other
    again = ext.robot.to_dh(robot.convention).robot
    assert_transform_close(again.fk(q), robot.fk(q), atol=CHAIN_ATOL)


# ------------------------------------------------------------------ the seed's rules by hand
def test_seed_arm_rules_by_frame():
    # Seed 000's 6-DOF table: a1 = 0 with alpha1 = 90 (axes 1, 2 meet), alpha2 = 0 with
    # a2 = l2 (axes 2, 3 parallel), then three twists with a = 0: every pair meets.
    ext = km.load("arm6-dh").to_dh("standard")
    assert [r.rule for r in ext.rules] == [
        "frame",
        "intersecting",
        "parallel",
        "intersecting",
        "intersecting",
        "intersecting",
        "frame",
    ]
    assert "x2 from axis 2 to axis 3" in ext.rules[2].text
    assert [link.name for link in ext.robot.links] == [
        link.name for link in km.load("arm6-dh").links
    ]
    assert "S0:" in str(ext.rules[0])
    assert ext.report().count("\n") == 7


def test_craig_first_and_last_frames_when_the_description_has_none():
    # One joint about x: no frame of the description has its x normal to the axis
    # through joint 1, so S0 = S1 (Craig), and S1 is built at the joint.
    text = """<robot name="x"><link name="b"/><link name="t"/>
      <joint name="j" type="continuous"><parent link="b"/><child link="t"/>
        <origin xyz="0 0 0.2" rpy="0 0 0.3"/><axis xyz="1 0 0"/></joint></robot>"""
    ext = km.urdf_to_dh(parse_urdf(text), convention="modified")
    assert [r.rule for r in ext.rules] == ["craig", "craig"]
    np.testing.assert_allclose(ext.robot.dh_table(), np.zeros((1, 4)), atol=1e-15)
    assert_transform_close(ext.robot.base, ext.frames[1], atol=1e-15)
    std = km.urdf_to_dh(parse_urdf(text))
    assert [r.rule for r in std.rules] == ["rule 5", "rule 9"]


def test_puma_urdf_table_by_hand():
    # tests/data/urdf/puma560_robot.urdf: axis 1 vertical through (0, 0, 0.6718); axis 2
    # meets it there; axis 3 parallel to axis 2, its joint at (0.4318, -0.0203, 0.1501) in
    # joint 2's frame; axis 4 meets axis 3 at joint 3; joint 5 0.4331 along axis 4; the tip
    # 0.0558 along axis 6. The file writes 90 degrees as 1.570796325 (1.8e-9 rad short), so
    # its axes are that far from the ideal ones: 1e-9 m over these lengths. Axes 2 and 3
    # parallel leave S2's origin free along axis 3: level with S1 (d2 = 0), so the
    # shoulder offset 0.1501 is d3, where Corke's table has its 0.15005.
    robot = km.load(URDF_DIR / "puma560_robot.urdf")
    theta, d, a, alpha = robot.dh_table().T
    np.testing.assert_allclose(np.abs(a), [0, math.hypot(0.4318, 0.0203), 0, 0, 0, 0], atol=1e-9)
    np.testing.assert_allclose(np.abs(d), [0, 0, 0.1501, 0.4331, 0, 0.0558], atol=1e-9)
    np.testing.assert_allclose(abs(theta[1]), math.atan2(0.0203, 0.4318), atol=1e-9)
    np.testing.assert_allclose(np.abs(alpha), [math.pi / 2, 0, *[math.pi / 2] * 3, 0], atol=1e-8)
    np.testing.assert_allclose(robot.base[:3, 3], [0, 0, 0.6718], atol=1e-12)


def test_kr16_urdf_table_by_hand():
    # ROS-Industrial KR 16-2: joint 2 at x = 0.26 above the base (z = 0.675), joint 3 0.68
    # further along x, joint 4 at (0.67, 0, -0.035) from joint 3, the tool 0.158 past the
    # wrist: KUKA's a1, a2, a3, d4, d6 and the base height.
    robot = km.load(URDF_DIR / "kuka_kr16_2.urdf")
    _, d, a, _ = robot.dh_table().T
    np.testing.assert_allclose(np.abs(a), [0.26, 0.68, 0.035, 0, 0, 0], atol=1e-12)
    np.testing.assert_allclose(np.abs(d), [0, 0, 0, 0.67, 0, 0.158], atol=1e-12)
    np.testing.assert_allclose(robot.base[:3, 3], [0, 0, 0.675], atol=1e-12)


def test_line_pair_by_hand():
    z, x, y = np.eye(3)[2], np.eye(3)[0], np.eye(3)[1]
    skew = line_pair(z, np.zeros(3), x, np.array([0.0, 2.0, 5.0]), 1.0)
    assert skew.kind == "skew"
    np.testing.assert_allclose(skew.normal, y)
    np.testing.assert_allclose(skew.foot_a, [0, 0, 5])
    np.testing.assert_allclose(skew.foot_b, [0, 2, 5])
    assert skew.distance == pytest.approx(2.0)
    meet = line_pair(z, np.array([0, 0, 1.0]), x, np.array([3.0, 0, 2.0]), 1.0)
    assert meet.kind == "intersecting"
    np.testing.assert_allclose(meet.normal, np.cross(z, x))
    np.testing.assert_allclose(meet.foot_b, [0, 0, 2], atol=1e-15)
    par = line_pair(z, np.zeros(3), -z, np.array([0, 3.0, 7.0]), 1.0)
    assert (par.kind, par.distance) == ("parallel", 3.0)
    np.testing.assert_allclose(par.normal, y)
    assert line_pair(z, np.zeros(3), z, np.array([0, 0, 4.0]), 1.0).kind == "collinear"


@pytest.mark.parametrize("convention", ["standard", "modified"])
def test_angle_tolerance_decides_parallel_axes(convention):
    # axis 2 tilted by delta about y, 0.5 m from axis 1: parallel, or meeting far away
    inside = _two_joints("0.5 0 0", f"0 {0.5 * AXIS_ANGLE_TOL!r} 0")
    outside = _two_joints("0.5 0 0", f"0 {2 * AXIS_ANGLE_TOL!r} 0")
    assert _rule(inside, convention) == "parallel"
    assert _rule(outside, convention) == "intersecting"


@pytest.mark.parametrize("convention", ["standard", "modified"])
def test_length_tolerance_decides_meeting_and_coinciding_axes(convention):
    # axis 2 along -y, passing delta away from axis 1 (z): meeting, or skew; the
    # tolerance is relative to the chain's size (0.3 m to joint 2, 1 m to the tip)
    tol = AXIS_LENGTH_TOL * (1.0 + 1.3)

    def crossing(delta: float) -> str:
        return _two_joints(f"{delta!r} 0 0.3", "1.5707963267948966 0 0")

    assert _rule(crossing(0.5 * tol), convention) == "intersecting"
    assert _rule(crossing(2 * tol), convention) == "skew"

    # axis 2 parallel to axis 1, delta beside it: coinciding, or parallel
    def beside(delta: float) -> str:
        return _two_joints(f"{delta!r} 0 0.3", "0 0 0")

    assert _rule(beside(0.5 * tol), convention) == "collinear"
    assert _rule(beside(2 * tol), convention) == "parallel"


def test_fk_check_warns_only_beyond_its_tolerance():
    # Axis 2 tilted by half AXIS_ANGLE_TOL is taken as parallel: with the tip L up
    # axis 2, the table is off by the tilt times L.
    tilt = 0.5 * AXIS_ANGLE_TOL

    def extract(error: float) -> km.DHExtraction:
        tip = f"0 0 {error / tilt!r}"
        return km.urdf_to_dh(parse_urdf(_two_joints("0.5 0 0", f"0 {tilt!r} 0", tip)))

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        inside = extract(0.5 * FK_CHECK_TOL)
    assert 0.3 * FK_CHECK_TOL < inside.fk_error < 0.7 * FK_CHECK_TOL
    with pytest.warns(km.KinematicaWarning, match="reproduces the chain's forward kinematics"):
        outside = extract(2 * FK_CHECK_TOL)
    assert 1.5 * FK_CHECK_TOL < outside.fk_error < 3 * FK_CHECK_TOL


def _slider(tilt: float, stroke: float) -> str:
    """A turn about z, then a slide of +-stroke m along an axis tilted by ``tilt`` rad."""
    return f"""<robot name="s"><link name="b"/><link name="l1"/><link name="l2"/>
    <joint name="j1" type="continuous"><parent link="b"/><child link="l1"/>
      <axis xyz="0 0 1"/></joint>
    <joint name="j2" type="prismatic"><parent link="l1"/><child link="l2"/>
      <origin xyz="0.5 0 0" rpy="0 {tilt!r} 0"/><axis xyz="0 0 1"/>
      <limit lower="{-stroke!r}" upper="{stroke!r}" effort="1" velocity="1"/></joint></robot>"""


@pytest.mark.parametrize("stroke", [2.0, 20.0])
def test_fk_error_is_measured_over_the_joint_limits(stroke):
    # The slider's axis, tilted by half AXIS_ANGLE_TOL, is taken as parallel to axis 1:
    # the table misses the tip by the tilt times the slide, so the largest miss within
    # the limits is tilt * stroke (beyond the tilt of the rotation entries), reached at
    # the ends of the stroke. The figure follows the limits and never exceeds them.
    tilt = 0.5 * AXIS_ANGLE_TOL
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # 20 m: beyond FK_CHECK_TOL, with a warning
        ext = km.urdf_to_dh(parse_urdf(_slider(tilt, stroke)))
    assert ext.rules[1].rule == "parallel"
    assert 0.95 * tilt * stroke < ext.fk_error <= tilt * stroke * (1 + 1e-6)


def test_round_off_tolerance_tidies_lengths_angles_and_transforms():
    # a1 between parallel axes 1 and 2 is the joint-2 offset along x
    def a1(extra: float) -> float:
        return float(_table(_two_joints(f"{0.3 + extra!r} 0 0", "0 0 0"))[0, 2])

    assert a1(0.5 * ROUND_OFF_TOL) == 0.3
    assert a1(20 * ROUND_OFF_TOL) == 0.3 + 20 * ROUND_OFF_TOL

    def alpha1(extra: float) -> float:
        rpy = f"{math.pi / 2 + extra!r} 0 0"
        return float(_table(_two_joints("0 0 0.3", rpy))[0, 3])

    assert alpha1(0.5 * ROUND_OFF_TOL) == math.pi / 2
    assert alpha1(20 * ROUND_OFF_TOL) != math.pi / 2
