"""Makers' URDF files as they are written: UR tips, zero limits, the makers' DH tables.

References: the files in tests/data/urdf (PROVENANCE.md), the hand-written URDF
product of tests/urdf_helpers.py, and the DH tables the makers publish.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from helpers import assert_transform_close
from urdf_helpers import URDF_DIR, reference_file

import kinematica as km
from kinematica.io import parse_urdf

UR5 = URDF_DIR / "ur5_robot.urdf"


def load_quietly(*args, **kwargs):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        robot = km.load(*args, **kwargs)
    return robot, [str(w.message) for w in caught if issubclass(w.category, km.KinematicaWarning)]


# ------------------------------------------------------------- item 4: UR tips
def test_ur5_without_tip_ends_at_tool0_and_says_so():
    robot, said = load_quietly(UR5)
    assert robot.description.endswith("-> tool0")
    assert any("'tool0'" in m and "'wrist_3_link'" in m and "'ee_link'" in m for m in said)
    ref = reference_file("ur5_robot.urdf", None, "tool0")
    q = np.array([0.3, -1.0, 1.2, 0.4, 0.5, -0.6])
    assert_transform_close(robot.fk(q), ref.fk(q), atol=1e-12)


def _without_tool0(text: str) -> str:
    for opening, closing in (
        ('<link name="tool0">', "</link>"),
        ('<joint name="wrist_3_link-tool0', "</joint>"),
    ):
        start = text.index(opening)
        end = text.index(closing, start) + len(closing)
        text = text[:start] + text[end:]
    return text


def test_leaves_on_the_last_link_without_tool0_end_at_that_link(tmp_path):
    # ee_link alone, plus a second fixed frame on wrist_3_link: no tool0 to prefer.
    text = _without_tool0(UR5.read_text())
    text = text.replace(
        "</robot>",
        '<link name="camera"/><joint name="cam" type="fixed"><parent link="wrist_3_link"/>'
        '<child link="camera"/><origin xyz="0 0.1 0"/></joint></robot>',
    )
    path = tmp_path / "ur5_no_tool0.urdf"
    path.write_text(text)
    robot, said = load_quietly(path)
    assert robot.description.endswith("-> wrist_3_link")
    assert any("last moving link 'wrist_3_link'" in m for m in said)


def test_leaves_on_different_links_stay_ambiguous(tmp_path):
    text = UR5.read_text().replace(
        "</robot>",
        '<link name="elbow_cam"/><joint name="ec" type="fixed"><parent link="forearm_link"/>'
        '<child link="elbow_cam"/></joint></robot>',
    )
    path = tmp_path / "ur5_two_bodies.urdf"
    path.write_text(text)
    with pytest.raises(km.RobotFileError, match="choose one as the tip"):
        km.load(path)


# ------------------------------------------------------------ item 5: zero limits
PENDULUM = """<robot name="double_pendulum">
  <link name="base"/><link name="l1"/><link name="l2"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <axis xyz="0 1 0"/><limit lower="0" upper="0" effort="0" velocity="0"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/>
    <origin xyz="0 0 -0.5"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="0" velocity="0"/></joint>
</robot>"""


def test_zero_limits_read_as_no_limits_with_a_warning(tmp_path):
    path = tmp_path / "double_pendulum.urdf"
    path.write_text(PENDULUM)
    robot, said = load_quietly(path)
    assert robot.has_limits.tolist() == [False, True]
    assert any("'j1'" in m and "lower=0 upper=0" in m and "no limits" in m for m in said)
    assert robot.fk([2.5, 0.0])[0, 3] == pytest.approx(
        -0.5 * math.sin(2.5), abs=1e-12
    )  # x = z·sin q1, z = -0.5


def test_equal_nonzero_limits_are_still_refused():
    with pytest.raises(km.RobotFileError, match=r"lower=0\.3 >= upper=0\.3"):
        parse_urdf(PENDULUM.replace('lower="0" upper="0"', 'lower="0.3" upper="0.3"'))
