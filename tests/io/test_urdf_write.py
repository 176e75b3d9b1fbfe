"""URDF out: valid XML with the same FK and limits; roll-pitch-yaw."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation
from support.helpers import PROPERTY, assert_transform_close, random_q, robot_specs, seeds
from support.urdf import link_poses, reference_chain

import kinematica as km
from kinematica.io import rpy_from_matrix


# ------------------------------------------------------------------ roll-pitch-yaw
@PROPERTY
@given(quat=st.lists(st.floats(-1, 1, allow_nan=False), min_size=4, max_size=4))
def test_rpy_from_matrix_against_scipy(quat):
    if np.linalg.norm(quat) < 0.1:
        quat = [0.0, 0.0, 0.0, 1.0]
    R = Rotation.from_quat(quat).as_matrix()
    r, p, y = rpy_from_matrix(R)
    assert -math.pi <= r <= math.pi and -math.pi / 2 <= p <= math.pi / 2
    np.testing.assert_allclose(Rotation.from_euler("xyz", [r, p, y]).as_matrix(), R, atol=1e-15)


@pytest.mark.parametrize("pitch", [math.pi / 2, -math.pi / 2])
@pytest.mark.parametrize("miss", [0.0, 1e-14, 1e-10, 1e-8, 1e-6])
def test_rpy_from_matrix_in_and_near_gimbal_lock(pitch, miss):
    p = pitch - math.copysign(miss, pitch)
    R = Rotation.from_euler("xyz", [0.7, p, -2.1]).as_matrix()
    rpy = rpy_from_matrix(R)
    np.testing.assert_allclose(Rotation.from_euler("xyz", rpy).as_matrix(), R, atol=2e-16 * 8)


# ------------------------------------------------------------------ to_urdf
@PROPERTY
@given(spec=robot_specs(max_dof=7), seed=seeds)
def test_to_urdf_is_valid_xml_with_the_same_fk_and_limits(spec, seed):
    robot = spec.build()
    text = robot.to_urdf()
    root = ET.fromstring(text)
    assert root.tag == "robot"
    ref = reference_chain(text, tip="tool0")  # our own XML, read by the independent reference
    assert ref.dof == robot.dof
    q = random_q(spec, np.random.default_rng(seed), (3,))
    assert_transform_close(ref.fk_batch(q), robot.fk(q), atol=1e-12)
    for j, link in zip(ref.movable, robot.links, strict=True):
        limit = j.find("limit")
        if link.qlim is None:
            assert j.get("type") in ("continuous", "prismatic")
            assert limit is None or "lower" not in limit.attrib
        else:
            assert (float(limit.get("lower")), float(limit.get("upper"))) == link.qlim
            assert j.get("type") == ("prismatic" if link.type == "P" else "revolute")


def test_to_urdf_writes_the_file_and_loads_back(tmp_path):
    puma = km.load("puma560")
    path = tmp_path / "puma.urdf"
    text = puma.to_urdf(path)
    assert path.read_text() == text
    back = km.load(path)
    assert back.dof == 6
    assert [link.name for link in back.links] == [f"joint{i}" for i in range(1, 7)]
    np.testing.assert_array_equal(back.qlim, puma.qlim)
    q = np.random.default_rng(0).uniform(-2, 2, (10, 6))
    assert_transform_close(back.fk(q), puma.fk(q), atol=1e-15)
    np.testing.assert_allclose(back.dh_table(), puma.dh_table(), atol=1e-16)
    with pytest.raises(km.RobotFileError, match="cannot write"):
        puma.to_urdf(tmp_path)  # a directory


def test_names_are_escaped_and_kept_when_unique():
    robot = km.Robot.from_dh(
        [km.Revolute(a=0.3, name='shoulder "A" <&>'), km.Prismatic(name="slide")],
        name='arm <&> "quoted"',
        convention="standard",
    )
    root = ET.fromstring(robot.to_urdf())
    assert root.get("name") == 'arm <&> "quoted"'
    names = [j.get("name") for j in root.findall("joint") if j.get("type") != "fixed"]
    assert names == ['shoulder "A" <&>', "slide"]
    twins = km.Robot.from_dh([km.Revolute(name="j"), km.Revolute(name="j")], convention="standard")
    names = [j.get("name") for j in ET.fromstring(twins.to_urdf()).findall("joint")]
    assert names[:2] == ["joint1", "joint2"]


def test_frames_of_the_export_are_the_dh_frames():
    # standard: link i at q = 0 is DH frame S_i; base_link -> link0 is the base transform
    robot = km.load("arm6-dh").with_base(km.transl(0.1, 0.2, 0.3)).with_tool(km.transl(0, 0, 0.05))
    poses = link_poses(reference_chain(robot.to_urdf(), tip="tool0"))
    frames = robot.fk(np.zeros(6), all_frames=True)
    assert_transform_close(poses["link0"], frames[0], atol=1e-15)
    for i in range(1, 7):  # link i holds joint i's motion: its frame at q = 0 is S_(i-1)
        assert_transform_close(poses[f"link{i}"], frames[i - 1], atol=1e-15)
    assert_transform_close(poses["tool0"], frames[6], atol=1e-15)
