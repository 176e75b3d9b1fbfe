"""robot.save / km.write_robot_file: a loaded file saved again keeps its writing.

Independent checks: the saved text is compared with the text of the file it
came from (expressions, units, parameters as typed), and the robot read back
is compared by forward kinematics with the robot that was saved.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from support import DATA as TESTS_DATA
from support.helpers import PROPERTY, assert_transform_close

import kinematica as km
from kinematica.errors import ArgumentError
from kinematica.io import read_robot_file
from kinematica.io import write_robot_file as write_spec

DATA = TESTS_DATA / "robots"
SUFFIXES = (".yaml", ".json", ".toml")

ARM = """\
name: Teaching arm
convention: standard
units: {angle: deg, length: mm}
parameters: {l1: 400, l2: 2 * l1 - 350, half: l2 / 2}
joints:
  - {theta: q1, d: l1, a: 25, alpha: -90, limits: [-170, 170]}
  - {theta: q2 - 90, d: 0, a: l2, alpha: 0}
  - {theta: q3 + 90, d: 0, a: half + 10, alpha: 90}
  - {theta: 0, d: q4 + 100, a: 0, alpha: 0, limits: [0, 250]}
tool: {xyz: [0, 0, 50], rpy: [0, 0, 90]}
"""


def _q(robot: km.Robot, seed: int = 0, n: int = 20) -> np.ndarray:
    lo, hi = np.clip(robot.qlim[:, 0], -3, 3), np.clip(robot.qlim[:, 1], -3, 3)
    return np.random.default_rng(seed).uniform(lo, hi, (n, robot.dof))


def _same_kinematics(a: km.Robot, b: km.Robot) -> None:
    q = _q(a)
    assert_transform_close(a.fk(q, all_frames=True), b.fk(q, all_frames=True), atol=1e-12)
    np.testing.assert_array_equal(a.qlim, b.qlim)
    assert (a.name, a.convention, a.joint_types) == (b.name, b.convention, b.joint_types)


@pytest.fixture
def arm(tmp_path: Path) -> Path:
    path = tmp_path / "arm.yaml"
    path.write_text(ARM)
    return path


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_a_loaded_file_saved_again_keeps_units_names_and_expressions(
    arm: Path, tmp_path: Path, suffix: str
) -> None:
    robot = km.load(arm)
    out = tmp_path / f"again{suffix}"
    robot.save(out)
    spec = read_robot_file(out)
    assert dict(spec.units) == {"angle": "deg", "length": "mm"}
    assert dict(spec.parameter_texts) == {"l1": "400", "l2": "2 * l1 - 350", "half": "l2 / 2"}
    assert [j.expr["theta"] for j in spec.joints] == ["q1", "q2 - 90", "q3 + 90", "0"]
    assert [j.expr["a"] for j in spec.joints] == ["25", "l2", "half + 10", "0"]
    assert spec.joints[3].expr["d"] == "q4 + 100"
    text = out.read_text()
    for written in ("q2 - 90", "2 * l1 - 350", "half + 10", "q4 + 100", "-90", "170"):
        assert written in text
    _same_kinematics(km.load(out), robot)


def test_yaml_saved_again_is_the_file_as_written(arm: Path, tmp_path: Path) -> None:
    km.load(arm).save(tmp_path / "again.yaml")
    again = (tmp_path / "again.yaml").read_text()
    for line in ARM.splitlines()[4:9]:  # the joint rows, as typed
        row = line.strip().removeprefix("- ")
        assert row.replace(" ", "") in again.replace(" ", ""), row


def test_write_robot_file_takes_a_robot(arm: Path, tmp_path: Path) -> None:
    robot = km.load(arm)
    km.write_robot_file(robot, tmp_path / "a.toml")
    km.write_robot_file(km.spec_from_robot(robot), tmp_path / "b.toml")
    assert (tmp_path / "a.toml").read_text() == (tmp_path / "b.toml").read_text()
    _same_kinematics(km.load(tmp_path / "a.toml"), robot)


def test_the_io_writer_says_how_to_save_a_robot(tmp_path: Path) -> None:
    with pytest.raises(ArgumentError, match=r"robot\.save\(path\)"):
        write_spec(km.load("puma560"), tmp_path / "x.yaml")  # type: ignore[arg-type]
    with pytest.raises(ArgumentError, match="expected a Robot or a RobotSpec, got str"):
        km.write_robot_file("puma560", tmp_path / "x.yaml")  # type: ignore[arg-type]


def test_a_changed_tool_saves_its_numbers_and_keeps_the_table(arm: Path, tmp_path: Path) -> None:
    robot = km.load(arm).with_tool(km.transl(0.0, 0.0, 0.2))
    robot.save(tmp_path / "tool.yaml")
    spec = read_robot_file(tmp_path / "tool.yaml")
    assert spec.tool is not None and spec.tool.xyz == (0.0, 0.0, 0.2) and spec.tool.rpy is None
    assert "xyz: [0, 0, 200]" in (tmp_path / "tool.yaml").read_text()  # millimetres still
    assert spec.joints[1].expr["theta"] == "q2 - 90"
    _same_kinematics(km.load(tmp_path / "tool.yaml"), robot)


def test_changed_limits_keep_the_joint_texts(arm: Path, tmp_path: Path) -> None:
    loaded = km.load(arm)
    robot = loaded.with_limits([(-1.0, 1.0), None, (-math.pi / 2, math.pi / 2), (0.0, 0.1)])
    robot.save(tmp_path / "limits.json")
    spec = read_robot_file(tmp_path / "limits.json")
    assert spec.joints[0].qlim == (-1.0, 1.0)
    assert spec.joints[2].expr["theta"] == "q3 + 90"
    _same_kinematics(km.load(tmp_path / "limits.json"), robot)


def test_another_convention_saves_numbers(arm: Path, tmp_path: Path) -> None:
    robot = km.load(arm).to_convention("modified")
    robot.save(tmp_path / "craig.toml")
    again = km.load(tmp_path / "craig.toml")
    assert again.convention == "modified"
    assert "l2" not in (tmp_path / "craig.toml").read_text()  # the texts are gone: numbers
    _same_kinematics(again, robot)


def test_a_robot_built_in_code_saves_in_radians_and_metres(tmp_path: Path) -> None:
    robot = km.Robot.from_dh(
        [km.Revolute(d=0.4, alpha=math.pi / 2), km.Revolute(a=0.3), km.Prismatic(alpha=0.1)],
        name="code arm",
        tool=km.transl(0.0, 0.0, 0.1),
        convention="standard",
    )
    for suffix in SUFFIXES:
        robot.save(tmp_path / f"code{suffix}")
        spec = read_robot_file(tmp_path / f"code{suffix}")
        assert dict(spec.units) == {"angle": "rad", "length": "m"}
        _same_kinematics(km.load(tmp_path / f"code{suffix}"), robot)


@pytest.mark.parametrize("name", km.builtin_names())
def test_every_builtin_saved_and_loaded_is_the_same_robot(name: str, tmp_path: Path) -> None:
    robot = km.load(name)
    path = tmp_path / f"{name}.toml"
    robot.save(path)
    again = km.load(path)
    _same_kinematics(again, robot)
    assert again.source_spec is not None and robot.source_spec is not None
    assert dict(again.source_spec.units) == dict(robot.source_spec.units)
    assert [dict(j.expr) for j in again.source_spec.joints] == [
        dict(j.expr) for j in robot.source_spec.joints
    ]


def test_the_sample_files_saved_again_keep_their_writing(tmp_path: Path) -> None:
    for name in ("seed_arm.yaml", "seed_arm_rad_mm.yaml", "craig_rrp.yaml"):
        robot = km.load(DATA / name)
        robot.save(tmp_path / name)
        before, after = read_robot_file(DATA / name), read_robot_file(tmp_path / name)
        assert after == before
        assert [dict(j.expr) for j in after.joints] == [dict(j.expr) for j in before.joints]
        assert dict(after.parameter_texts) == dict(before.parameter_texts)


_length = st.floats(-2.0, 2.0, allow_nan=False) | st.sampled_from([0.0, 1e-10, 0.5])
_angle = st.floats(-math.pi, math.pi, allow_nan=False) | st.sampled_from(
    [0.0, math.pi / 2, -math.pi / 2, math.pi, 1e-10]
)


@st.composite
def _rows(draw: st.DrawFn) -> km.Revolute | km.Prismatic:
    if draw(st.booleans()):
        d, a, alpha, offset = draw(_length), draw(_length), draw(_angle), draw(_angle)
        return km.Revolute(d=d, a=a, alpha=alpha, offset=offset)
    return km.Prismatic(
        theta=draw(_angle), a=draw(_length), alpha=draw(_angle), offset=draw(_length)
    )


@PROPERTY
@given(
    rows=st.lists(_rows(), min_size=1, max_size=7),
    convention=st.sampled_from(["standard", "modified"]),
    suffix=st.sampled_from(SUFFIXES),
    tool_z=_length,
)
def test_random_robots_saved_and_loaded_have_the_same_kinematics(
    tmp_path_factory: pytest.TempPathFactory,
    rows: list[km.Revolute | km.Prismatic],
    convention: str,
    suffix: str,
    tool_z: float,
) -> None:
    robot = km.Robot.from_dh(rows, convention=convention, tool=km.transl(0.0, 0.0, tool_z))
    path = tmp_path_factory.mktemp("random") / f"robot{suffix}"
    robot.save(path)
    again = km.load(path)
    _same_kinematics(again, robot)
    path2 = path.with_name(f"again{suffix}")
    again.save(path2)  # a second round trip writes the very same file
    assert path2.read_text() == path.read_text()
