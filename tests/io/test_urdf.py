"""Reading URDF: hostile and broken files each give one clear line; chain selection."""

from __future__ import annotations

import os
import time
import warnings

import numpy as np
import pytest
from support.helpers import assert_transform_close
from support.urdf import ARM, BOMB, broken, one_line_error, reference_chain, write

import kinematica as km
from kinematica.io import URDF_MAX_BYTES, parse_urdf, read_urdf


def test_plain_arm_loads_with_fk_limits_and_names(tmp_path):
    robot = km.load(write(tmp_path, ARM))
    assert robot.name == "arm"
    assert robot.joint_types == "RP"
    assert [link.name for link in robot.links] == ["j1", "j2"]
    assert robot.qlim.tolist() == [[-2.0, 2.0], [0.0, 0.5]]
    ref = reference_chain(ARM)
    q = np.array([[0.3, 0.2], [-1.0, 0.4]])
    assert_transform_close(robot.fk(q), ref.fk_batch(q), atol=1e-15)
    # by hand: j1 turns about z at height 0.3; j2 slides along x of l1 from 0.1; tool 0.05 above
    # l2's z, which is l1's -y after the rpy roll of 90 degrees: at q1 = 0 the tool sits at
    # (0.1 + q2, -0.05, 0.3)
    np.testing.assert_allclose(robot.fk([0.0, 0.2])[:3, 3], [0.3, -0.05, 0.3], atol=1e-15)


EXTERNAL = """<?xml version="1.0"?>
<!DOCTYPE robot [<!ENTITY secret SYSTEM "file:///etc/passwd">]>
<robot name="&secret;"><link name="base"/></robot>
"""

EXTERNAL_DTD = """<?xml version="1.0"?>
<!DOCTYPE robot SYSTEM "http://example.invalid/robot.dtd">
<robot name="x"><link name="base"/></robot>
"""


def test_entity_bomb_is_refused_at_once(tmp_path):
    start = time.perf_counter()
    one_line_error(write(tmp_path, BOMB), "declares an entity", "XML bombs")
    assert time.perf_counter() - start < 2.0


def test_external_entity_is_refused(tmp_path):
    message = one_line_error(write(tmp_path, EXTERNAL), "entity")
    assert "root:" not in message  # nothing of /etc/passwd leaks


def test_external_dtd_is_not_fetched(tmp_path):
    one_line_error(write(tmp_path, EXTERNAL_DTD), "external")


def test_not_xml_and_not_a_robot(tmp_path):
    one_line_error(write(tmp_path, "<robot><link name='a'></robot>"), "not valid XML", "line 1")
    one_line_error(write(tmp_path, "<sdf><model/></sdf>"), "not a URDF", "<sdf>")
    one_line_error(write(tmp_path, "<robot name='r'/>"), "no <link>")


def test_size_limit_on_both_sides(tmp_path):
    path = write(tmp_path, ARM)
    size = path.stat().st_size
    assert read_urdf(path, max_bytes=size).name == "arm"
    with pytest.raises(km.RobotFileError, match="size limit"):
        read_urdf(path, max_bytes=size - 1)
    huge = tmp_path / "huge.urdf"
    with huge.open("wb") as fh:  # sparse: costs no disk, refused before reading
        fh.truncate(URDF_MAX_BYTES + 1)
    one_line_error(huge, f"size limit of {URDF_MAX_BYTES} bytes")


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs FIFOs")
def test_fifo_and_directory_are_refused_without_hanging(tmp_path):
    fifo = tmp_path / "pipe.urdf"
    os.mkfifo(fifo)
    one_line_error(fifo, "not a regular file")  # opening it would block forever
    folder = tmp_path / "dir.urdf"
    folder.mkdir()
    one_line_error(folder, "is a directory")
    with pytest.raises(km.UnknownRobotError, match="no such URDF file"):
        km.load(tmp_path / "missing.urdf")


@pytest.mark.parametrize(
    ("old", "new", "patterns"),
    [
        (
            '<parent link="l1"/>',
            '<parent link="nowhere"/>',
            ["joint 'j2'", "'nowhere'", "not defined"],
        ),
        ('type="prismatic"', 'type="hinge"', ["joint 'j2'", "unknown type 'hinge'"]),
        ('xyz="0.1 0 0"', 'xyz="nan 0 0"', ["joint 'j2'", "origin xyz", "NaN"]),
        (
            'rpy="1.5707963267948966 0 0"',
            'rpy="inf 0 0"',
            ["joint 'j2'", "origin rpy", "NaN or inf"],
        ),
        ('xyz="0.1 0 0"', 'xyz="0.1 0"', ["joint 'j2'", "must be 3 numbers"]),
        ('xyz="0.1 0 0"', 'xyz="0.1 zero 0"', ["joint 'j2'", "must be 3 numbers"]),
        ('<axis xyz="1 0 0"/>', '<axis xyz="0 0 0"/>', ["joint 'j2'", "zero axis"]),
        ('lower="0" upper="0.5"', 'lower="0.5" upper="0"', ["joint 'j2'", "lower=0.5 >= upper=0"]),
        (
            '<child link="l2"/>',
            '<child link="tool"/>',
            ["link 'tool'", "child of two joints ('j2' and 'j3')", "loops"],
        ),
        ('<child link="l2"/>', "", ["joint 'j2'", "<child"]),
        (
            '<link name="tool"/>',
            '<link name="tool"/><link name="stray"/>',
            ["2 root links", "'stray'"],
        ),
        ('<link name="l2"/>', '<link name="l1"/>', ["two links are named 'l1'"]),
        ('name="j3"', 'name="j2"', ["two joints are named 'j2'"]),
        ('type="fixed"', "", ["joint 'j3'", "has no type"]),
        ('<joint name="j3"', "<joint", ["joint number 3 has no name"]),
    ],
)
def test_broken_urdf_gives_one_line_naming_the_problem(tmp_path, old, new, patterns):
    one_line_error(write(tmp_path, broken(old, new)), *patterns)


def test_loop_without_root(tmp_path):
    text = """<robot name="loop">
      <link name="a"/><link name="b"/>
      <joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
      <joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint>
    </robot>"""
    one_line_error(write(tmp_path, text), "loop", "'a'", "'b'")
    self_loop = ARM.replace(
        '<parent link="l1"/><child link="l2"/>', '<parent link="l2"/><child link="l2"/>'
    )
    one_line_error(write(tmp_path, self_loop), "joint 'j2'", "to itself")


MIMIC = broken(
    '<axis xyz="1 0 0"/>', '<axis xyz="1 0 0"/><mimic joint="j1" multiplier="2" offset="0"/>'
)


def test_mimic_floating_planar_on_the_chain_are_refused(tmp_path):
    one_line_error(write(tmp_path, MIMIC), "joint 'j2' mimics joint 'j1'", "tip")
    for jtype, dof in (("floating", "6 DOF"), ("planar", "3 DOF")):
        text = broken('type="prismatic"', f'type="{jtype}"')
        one_line_error(write(tmp_path, text), f"joint 'j2' is {jtype} ({dof})", "base")
    # ... but a chain that stops before them is fine
    robot = km.load(write(tmp_path, MIMIC), tip="l1")
    assert robot.dof == 1


def test_joints_inside_other_elements_are_not_joints(tmp_path):
    text = ARM.replace(
        "</robot>",
        '<transmission name="t"><joint name="j1"><hardwareInterface>x</hardwareInterface>'
        "</joint></transmission><gazebo><joint name='ghost'/></gazebo></robot>",
    )
    assert km.load(write(tmp_path, text)).dof == 2


# ------------------------------------------------------------------ chain selection
TREE = ARM.replace(
    "</robot>",
    """<link name="camera"/><link name="base_frame"/>
  <joint name="cam" type="fixed"><parent link="l1"/><child link="camera"/>
    <origin xyz="0 0.2 0"/></joint>
  <joint name="ros_base" type="fixed"><parent link="base"/><child link="base_frame"/></joint>
</robot>""",
)


def test_default_tip_is_the_single_moving_leaf_else_the_leaves_are_listed(tmp_path):
    path = write(tmp_path, TREE)
    message = one_line_error(path, "2 leaf links below 'base'", "'tool'", "'camera'", "--tip")
    assert "base_frame" not in message  # hangs from the base by fixed joints only: no candidate
    robot = km.load(path, tip="camera")
    assert robot.dof == 1
    assert_transform_close(
        robot.fk([0.4]), reference_chain(TREE, tip="camera").fk([0.4]), atol=1e-15
    )
    sub = km.load(path, base="l1", tip="tool")
    assert sub.joint_types == "P"
    assert_transform_close(
        sub.fk([0.3]), reference_chain(TREE, base="l1", tip="tool").fk([0.3]), atol=1e-15
    )


def test_bad_base_or_tip_names(tmp_path):
    path = write(tmp_path, TREE)
    one_line_error(path, "tip: no link named 'nope'", "links: 'base'", tip="nope")
    one_line_error(path, "base: no link named 'x'", base="x")
    one_line_error(path, "tip link 'base' is not below base link 'l1'", base="l1", tip="base")
    one_line_error(path, "no movable joint between links 'base' and 'base_frame'", tip="base_frame")
    with pytest.raises(km.KinematicaError, match="only for URDF files"):
        km.load("puma560", tip="tool0")


def test_base_link_that_is_not_the_root(tmp_path):
    robot = km.load(write(tmp_path, ARM), base="l1")
    ref = reference_chain(ARM, base="l1")
    assert robot.dof == 1
    assert_transform_close(robot.fk([0.25]), ref.fk([0.25]), atol=1e-15)


def test_continuous_joint_has_no_limits(tmp_path):
    text = ARM.replace('type="revolute"', 'type="continuous"')
    robot = km.load(write(tmp_path, text))
    assert robot.has_limits.tolist() == [False, True]


def test_limit_without_bounds_means_no_limits():
    model = parse_urdf(ARM.replace('lower="-2" upper="2" ', ""))
    assert model.joints[0].limits is None


def test_a_declared_xacro_namespace_alone_is_plain_urdf(tmp_path):
    text = ARM.replace(
        '<robot name="arm">', '<robot name="arm" xmlns:xacro="http://ros.org/wiki/xacro">'
    )
    assert km.load(write(tmp_path, text)).dof == 2


_NO_LIMIT = """<robot name="r">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="shoulder" type="revolute"><parent link="a"/><child link="b"/>
    <axis xyz="0 0 1"/></joint>
  <joint name="elbow" type="revolute"><parent link="b"/><child link="c"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""


def test_a_moving_joint_without_limit_is_read_free_with_a_warning_naming_it() -> None:
    # Issue 35, item 8: the URDF spec requires <limit> of revolute and prismatic joints
    with pytest.warns(km.KinematicaWarning, match=r"arm.urdf: joint 'shoulder' has no <limit>"):
        model = parse_urdf(_NO_LIMIT, source="arm.urdf")
    by_name = {j.name: j for j in model.joints}
    assert by_name["shoulder"].limits is None and by_name["elbow"].limits == (-1.0, 1.0)
    with warnings.catch_warnings():  # every joint with its <limit>: nothing to say
        warnings.simplefilter("error")
        limit = '<limit effort="1" velocity="1" lower="-2" upper="2"/>'
        parse_urdf(_NO_LIMIT.replace('<axis xyz="0 0 1"/>', f'<axis xyz="0 0 1"/>{limit}'))
