"""Makers' URDF files as they are written: UR tips, zero limits, the makers' DH tables.

References: the files in tests/data/urdf (PROVENANCE.md), the hand-written URDF
product of tests/support/urdf.py, and the DH tables the makers publish.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from support.helpers import assert_transform_close
from support.urdf import URDF_DIR, reference_file

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


# ------------------------------------------------- item 6: the makers' DH tables
#: UR's published standard DH parameters (Universal Robots, "DH parameters for
#: calculations of kinematics and dynamics"): d, a (m), alpha (deg); every offset 0.
UR_PUBLISHED = {
    "ur5_robot.urdf": (
        [0.089159, 0, 0, 0.10915, 0.09465, 0.0823],
        [0, -0.425, -0.39225, 0, 0, 0],
    ),
    "ur10_robot.urdf": (
        [0.1273, 0, 0, 0.163941, 0.1157, 0.0922],
        [0, -0.612, -0.5723, 0, 0, 0],
    ),
}
#: The files write π/2 with 11 digits (1.57079632679): angles are off by 5e-12.
ANGLE_ATOL = 1e-10


@pytest.mark.parametrize("name", sorted(UR_PUBLISHED))
def test_ur_urdf_gives_urs_published_table(name):
    robot, _ = load_quietly(URDF_DIR / name)  # tip tool0, base frame 'base' (UR's)
    theta, d, a, alpha = robot.dh_table().T
    d_ref, a_ref = UR_PUBLISHED[name]
    np.testing.assert_allclose(d, d_ref, atol=1e-12)
    np.testing.assert_allclose(a, a_ref, atol=1e-12)
    np.testing.assert_allclose(alpha, np.radians([90, 0, 0, 90, -90, 0]), atol=ANGLE_ATOL)
    np.testing.assert_allclose(theta, 0.0, atol=ANGLE_ATOL)
    # the table with UR's base frame reproduces the file's FK (its own check)
    ref = reference_file(name, None, "tool0")
    rebuilt = km.Robot.from_dh(
        [
            km.Revolute(d=di, a=ai, alpha=al)
            for di, ai, al in zip(d_ref, a_ref, np.radians([90, 0, 0, 90, -90, 0]), strict=True)
        ],
        base=robot.base,
        tool=robot.tool,
        convention="standard",
    )
    q = np.random.default_rng(4).uniform(-3, 3, (10, 6))
    assert_transform_close(rebuilt.fk(q), ref.fk_batch(q), atol=1e-9)


def test_panda_urdf_gives_frankas_modified_table():
    # Franka's documentation ("Robot and interface specifications", DH in Craig's
    # convention): a, d (m), alpha (rad); the flange 0.107 along z7.
    robot = km.load(URDF_DIR / "franka_panda.urdf", tip="panda_link8", convention="modified")
    theta, d, a, alpha = robot.dh_table().T
    np.testing.assert_allclose(a, [0, 0, 0, 0.0825, -0.0825, 0, 0.088], atol=1e-12)
    np.testing.assert_allclose(d, [0.333, 0, 0.316, 0, 0.384, 0, 0], atol=1e-12)
    half = math.pi / 2
    np.testing.assert_allclose(alpha, [0, -half, half, half, -half, half, half], atol=ANGLE_ATOL)
    np.testing.assert_allclose(theta, 0.0, atol=ANGLE_ATOL)
    flange = np.eye(4)
    flange[2, 3] = 0.107
    assert_transform_close(robot.tool, flange, atol=1e-12)


def test_parallel_axes_take_d_0_level_with_the_frame_before():
    # UR5: axes 2, 3, 4 parallel; the file's joints are 0.13585 - 0.1197 = 0.01615 m
    # apart along them, all of it in d4 (0.01615 + 0.093 = 0.10915) and none in d2, d3.
    robot, _ = load_quietly(UR5)
    ext = km.urdf_to_dh(UR5)
    assert "(d2 = 0)" in ext.rules[2].text and "(d3 = 0)" in ext.rules[3].text
    assert robot.links[3].d == pytest.approx(0.13585 - 0.1197 + 0.093, abs=1e-12)


# ------------------------------- derived tables: no warnings meant for typed values
def test_to_dh_of_nearly_parallel_axes_does_not_ask_about_millimetres():
    # The Gen3 Lite's axes 2 and 3 are parallel but for a rounded rpy: their common
    # normal's foot is 38 km away, so the extracted table has d2, d3 of -38 km. That
    # length was derived, not typed: the "is it in millimetres?" UnitWarning is not for it.
    from kinematica.io.plausible import PLAUSIBLE_LENGTH

    path = URDF_DIR.parent / "makers" / "kinova_gen3_lite.urdf"
    robot, _ = load_quietly(path)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        ext = robot.to_dh()
    assert max(abs(j.d) for j in ext.robot.links) > PLAUSIBLE_LENGTH  # the case is live
    assert not [w for w in caught if issubclass(w.category, km.UnitWarning)]
    assert ext.fk_error < 1e-9
    with pytest.warns(km.UnitWarning, match="millimetres"):  # a typed one still warns
        km.Revolute(d=ext.robot.links[1].d)
