"""rtb-data's xacro robot descriptions load without ROS (issue 35, item 2).

Their ``$(find pkg)`` includes are answered by the package map (rtb-data ships the
folders without ``package.xml``). Checked against two independent references:

- the built-in ``kr6`` and ``panda`` (written from KUKA's and Franka's data sheets):
  forward kinematics equal to :data:`BUILTIN_MATCH` at random configurations;
- the expansions the ``xacro`` package made of the same files (``tests/data/xacro/
  reference``): the whole URDF trees equal, element for element, for every robot.
"""

from __future__ import annotations

import json
import warnings
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from support import DATA
from support.xacro import REFERENCE, RTB, RTB_PACKAGES, RTB_ROBOTS, canonical, digest

import kinematica as km
from kinematica.io import read_urdf
from kinematica.io.xacro import xacro_to_urdf

#: Largest difference of an FK entry (m, or unitless for rotations) between a xacro file's
#: chain and the built-in model of the same arm: round-off of a few products (measured
#: 8e-16 for the KR 6, 1.4e-15 for the Panda).
BUILTIN_MATCH = 1e-12

KR6 = "kuka_description/kuka_kr6/urdf/kr6r900sixx.xacro"
PANDA = "qut_frankie_description/robots/panda_arm.urdf.xacro"
IRB140 = "abb_irb140_description/urdf/irb140.xacro"
IIWA = "kuka_description/kuka_lbr_iiwa/urdf/lbr_iiwa_14_r820.xacro"

#: The tip of arms whose file holds several leaves (grippers' fingers, a legacy link), by
#: the start of the file's name.
TIPS = {
    "kr210": "tool0",
    "hand.urdf": "panda_leftfinger",
    "panda_arm_hand": "panda_hand",
    "dual_panda": "panda_1_hand",
    **{
        arm: "/ee_gripper_link"
        for arm in ["px100", "px150", "rx150", "rx200", "vx250", "vx300", "wx200", "wx250"]
    },
}
#: Mobile manipulators whose base joint has limits of ±999,999 rad, beyond what the URDF
#: reader accepts (URDF_MAX_ANGLE): they expand as xacro expands them, and stop there.
BEYOND_URDF_LIMITS = ("frankie_arm", "frankieOmni_arm")


def random_q(robot: km.Robot, n: int, seed: int) -> np.ndarray:
    lo, hi = robot.qlim[:, 0], robot.qlim[:, 1]
    return np.random.default_rng(seed).uniform(lo, hi, size=(n, robot.dof))


@pytest.mark.parametrize(("file", "name"), [(KR6, "kr6"), (PANDA, "panda")])
def test_kr6_and_panda_match_the_builtins(file: str, name: str) -> None:
    robot = km.load(RTB / file, packages=RTB_PACKAGES)
    builtin = km.load(name)
    assert robot.dof == builtin.dof
    q = random_q(builtin, 200, seed=34)
    error = np.abs(robot.fk(q) - builtin.fk(q)).max()
    assert error <= BUILTIN_MATCH
    # the bound is tight enough to see a tool 1e-10 m longer (1000 x it would not)
    builtin_moved = km.Robot.from_dh(
        builtin.links,
        convention=builtin.convention,
        base=builtin.base,
        tool=builtin.tool @ np.array([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 1e-10], [0, 0, 0, 1]]),
    )
    assert np.abs(robot.fk(q) - builtin_moved.fk(q)).max() > BUILTIN_MATCH


@pytest.mark.parametrize("file", [IRB140, IIWA])
def test_irb140_and_iiwa_match_the_reference_expansion(file: str) -> None:
    name = file.rsplit("/", 1)[1].removesuffix(".xacro")
    reference = REFERENCE / f"{name}.urdf"
    ours = ET.fromstring(xacro_to_urdf(RTB / file, max_bytes=2**24, packages=RTB_PACKAGES))
    assert canonical(ours) == canonical(ET.parse(reference).getroot())
    robot = km.load(RTB / file, packages=RTB_PACKAGES)
    expected = km.load(reference)
    q = random_q(expected, 100, seed=35)
    np.testing.assert_array_equal(robot.fk(q), expected.fk(q))


def test_every_robot_expands_as_the_xacro_package_expands_it() -> None:
    digests = json.loads((REFERENCE / "digests.json").read_text())
    assert sorted(digests) == list(RTB_ROBOTS)
    assert len(RTB_ROBOTS) >= 30
    for robot in RTB_ROBOTS:
        if digests[robot].startswith("error:"):
            continue  # the KR 210, below
        tree = ET.fromstring(xacro_to_urdf(RTB / robot, max_bytes=2**24, packages=RTB_PACKAGES))
        assert digest(tree) == digests[robot], robot


def test_the_kr210s_ros1_properties_are_read_as_ros1_read_them() -> None:
    # xacro 2 fails on <property> without the prefix; rtb-data's own URDF of the KR 210 was
    # made by ROS 1's xacro, which read them: the same chain, to the last bit
    digests = json.loads((REFERENCE / "digests.json").read_text())
    file = "kuka_description/kuka_kr210/urdf/kr210l150.xacro"
    assert "name 'deg' is not defined" in digests[file]
    robot = km.load(RTB / file, packages=RTB_PACKAGES, tip="tool0")
    ros1 = km.load(DATA / "urdf" / "kuka_kr210l150.urdf", tip="tool0")
    q = random_q(ros1, 100, seed=210)
    np.testing.assert_array_equal(robot.fk(q), ros1.fk(q))


@pytest.mark.parametrize("file", RTB_ROBOTS)
def test_every_arm_loads_without_ros(file: str) -> None:
    name = file.rsplit("/", 1)[1]
    tip = next((t for key, t in TIPS.items() if name.startswith(key)), None)
    if name.startswith(BEYOND_URDF_LIMITS):
        with pytest.raises(km.RobotFileError, match="999999"):
            read_urdf(RTB / file, packages=RTB_PACKAGES)
        return
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", km.KinematicaWarning)  # limits lower=0 upper=0
        robot = km.load(RTB / file, packages=RTB_PACKAGES, tip=tip)
    assert robot.dof >= (1 if name.startswith("hand") else 2)  # the hand: one finger
    middle = np.where(np.isfinite(robot.qlim).all(axis=1), robot.qlim.mean(axis=1), 0.0)
    assert np.isfinite(robot.fk(middle)).all()
