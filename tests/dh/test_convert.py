"""One arm, one table per convention, whichever way a user asks for it.

``robot.to_convention`` regroups the table (the notes: "las matrices intermedias
varían, pero el resultado final es el mismo": the θ and d columns stay, a and α move
one row); extraction by the rules from the robot (``robot.to_dh``), from its URDF
file (``urdf_to_dh``) and ``kinematica convert <urdf> --to dh-modified`` must give
that same table, base and tool, in both directions, also for arms whose frames obey
both conventions' rules (all axes parallel: the planar 3R, the SCARA).
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import assume, given
from support.cli import run_in
from support.helpers import PROPERTY, assert_transform_close, robot_specs, seeds

import kinematica as km
from kinematica.dh import AXIS_ANGLE_TOL, AxisFrame, ChainGeometry, length_tol
from kinematica.errors import KinematicaError
from kinematica.io import parse_urdf

OTHER = {"standard": "modified", "modified": "standard"}


def assert_same_table(got: km.Robot, want: km.Robot) -> None:
    assert got.convention == want.convention
    np.testing.assert_allclose(got.dh_table(), want.dh_table(), atol=1e-12)
    assert_transform_close(got.base, want.base, atol=1e-12)
    assert_transform_close(got.tool, want.tool, atol=1e-12)


@pytest.mark.parametrize("name", ["arm6-dh", "puma560", "ur5", "kr6"])
def test_modified_table_is_the_same_by_every_path(name, tmp_path):
    robot = km.load(name)
    regrouped = robot.to_convention("modified")
    urdf = tmp_path / "arm.urdf"
    robot.to_urdf(urdf)
    assert_same_table(robot.to_dh("modified").robot, regrouped)
    assert_same_table(km.urdf_to_dh(urdf, convention="modified").robot, regrouped)


@pytest.mark.parametrize("name", ["arm6-dh", "puma560", "ur5"])
def test_standard_table_of_a_modified_robot_is_the_same_by_every_path(name, tmp_path):
    modified = km.load(name).to_convention("modified")
    urdf = tmp_path / "arm.urdf"
    modified.to_urdf(urdf)
    want = modified.to_convention("standard")
    assert_same_table(modified.to_dh("standard").robot, want)
    assert_same_table(km.urdf_to_dh(urdf).robot, want)


def cli_convert(robot: km.Robot, target: str, tmp_path) -> km.Robot:
    """``kinematica convert <the robot's URDF> --to dh-<target>``, read back."""
    urdf = tmp_path / "arm.urdf"
    robot.to_urdf(urdf)
    out = tmp_path / "arm_dh.yaml"
    proc = run_in(tmp_path, "convert", str(urdf), "--to", f"dh-{target}", "-o", str(out))
    assert proc.returncode == 0, proc.stderr
    return km.load(out)


def test_cli_convert_of_the_notes_arm_urdf_gives_to_conventions_table(tmp_path):
    robot = km.load("arm6-dh")
    from_file = cli_convert(robot, "modified", tmp_path)
    want = robot.to_convention("modified")
    np.testing.assert_allclose(from_file.dh_table(), want.dh_table(), atol=1e-9)
    # row 3 keeps the notes' q3 - 90 and row 5 no 180° offset (the issue's two rows)
    assert from_file.links[2].offset == pytest.approx(-np.pi / 2, abs=1e-12)
    assert from_file.links[4].offset == pytest.approx(0.0, abs=1e-12)
    q = np.random.default_rng(2).uniform(-3, 3, (5, 6))
    assert_transform_close(from_file.fk(q), robot.fk(q), atol=1e-9)


def _in(robot: km.Robot, convention: str) -> km.Robot:
    return robot if robot.convention == convention else robot.to_convention(convention)


def _quiet_extraction(robot: km.Robot, convention: str, urdf: str | None = None) -> km.Robot:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # FK-check warnings of nearly parallel axes
        if urdf is None:
            return robot.to_dh(convention).robot
        return km.urdf_to_dh(parse_urdf(urdf), convention=convention).robot


@pytest.mark.parametrize("source", ["standard", "modified"])
@pytest.mark.parametrize("name", km.builtin_names())
def test_every_builtin_arm_has_one_table_in_each_convention(name, source):
    robot = _in(km.load(name), source)
    target = OTHER[source]
    want = robot.to_convention(target)
    assert_same_table(robot.to_dh(target).robot, want)
    assert_same_table(_quiet_extraction(robot, target, robot.to_urdf()), want)
    q = np.random.default_rng(3).uniform(-1.0, 1.0, (4, robot.dof))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # q beyond a joint's limits: FK is defined there
        assert_transform_close(want.fk(q), robot.fk(q), atol=1e-12)


def test_the_notes_planar_3r_and_scara_tables():
    # The textbook planar 3R keeps a1, a2, a3 in its rows, with no tool, whichever
    # way its standard table is reached (seed 001, DH example 1).
    planar = km.load("planar-3r")
    modified = planar.to_convention("modified")
    for std in (modified.to_convention("standard"), modified.to_dh("standard").robot):
        np.testing.assert_array_equal(std.dh_table()[:, 2], [0.4, 0.3, 0.2])
        np.testing.assert_array_equal(std.tool, np.eye(4))
    # The SCARA's shoulder height stays in row 1 in Craig's table (θ and d stay).
    scara = km.load("scara").to_dh("modified").robot
    np.testing.assert_allclose(scara.dh_table()[:, 1], [0.387, 0.0, 0.0, 0.0], atol=1e-15)
    np.testing.assert_allclose(scara.dh_table()[:, 2], [0.0, 0.325, 0.275, 0.0], atol=1e-15)


def _nearly_parallel(spec, within: float = 1e-3) -> bool:
    """Consecutive axes within ``within`` rad of parallel, not exactly.

    Their normal's direction is known only to about 1e-16 / angle, which moves
    θ by as much (FK is unchanged).
    """
    twists = [j.alpha for j in spec.joints]
    between = twists[:-1] if spec.convention == "standard" else twists[1:]
    return any(0.0 < abs(math.remainder(t, math.pi)) < within for t in between)


@PROPERTY
@given(spec=robot_specs(max_dof=6), seed=seeds)
def test_random_arms_have_one_table_in_each_convention(spec, seed):
    # Degenerate geometry on purpose (lengths and twists of 0 and ±90°, ±180° often):
    # parallel, meeting and coinciding axes, frames that obey both conventions' rules.
    assume(not _nearly_parallel(spec))
    robot = spec.build()
    target = OTHER[robot.convention]
    want = robot.to_convention(target)
    for got in (
        _quiet_extraction(robot, target),
        _quiet_extraction(robot, target, robot.to_urdf()),
    ):
        g, w = got.dh_table(), want.dh_table()
        np.testing.assert_allclose(
            np.angle(np.exp(1j * (g[:, [0, 3]] - w[:, [0, 3]]))), 0, atol=1e-9
        )
        np.testing.assert_allclose(g[:, [1, 2]], w[:, [1, 2]], atol=1e-9)
        assert_transform_close(got.base, want.base, atol=1e-9)
        assert_transform_close(got.tool, want.tool, atol=1e-9)
    q = np.random.default_rng(seed).uniform(-2.0, 2.0, (4, robot.dof))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # q beyond a joint's limits: FK is defined there
        assert_transform_close(want.fk(q), robot.fk(q), atol=1e-12)
        back = want.to_convention(robot.convention)
        assert_transform_close(back.fk(q), robot.fk(q), atol=1e-12)


@pytest.mark.parametrize(("off_scale", "turn_scale"), [(0.5, 0.5), (2.0, 0.5), (0.5, 2.0)])
def test_a_tool_on_the_last_x_line_goes_to_the_last_row_within_the_line_tolerances(
    off_scale, turn_scale
):
    # A modified planar 3R whose tool is Tras(x, 0.2) but for a sideways offset and a
    # turn of the tool's x, each just inside (0.5x) or outside (2x) the line geometry's
    # tolerance: to_convention and the DH rules agree on each side.
    inside = off_scale < 1 and turn_scale < 1
    off = off_scale * length_tol(0.2)
    turn = turn_scale * AXIS_ANGLE_TOL
    tool = np.eye(4)
    c, s = math.cos(turn), math.sin(turn)
    tool[:3, :3] = [[c, -s, 0], [s, c, 0], [0, 0, 1]]
    tool[:3, 3] = [0.2, off, 0.0]
    modified = km.load("planar-3r").to_convention("modified").with_tool(tool)
    std = modified.to_convention("standard")
    a3 = std.links[-1].a
    assert a3 == (pytest.approx(0.2, abs=1e-15) if inside else 0.0)
    if inside:  # what is left of the tool is the offset and the turn
        assert std.tool[1, 3] == pytest.approx(off, rel=1e-6)
    else:
        np.testing.assert_array_equal(std.tool, tool)
    got = _quiet_extraction(modified, "standard", modified.to_urdf())
    np.testing.assert_allclose(got.dh_table(), std.dh_table(), atol=1e-12)
    assert_transform_close(got.tool, std.tool, atol=1e-12)
    q = np.random.default_rng(5).uniform(-3, 3, (4, 3))
    assert_transform_close(std.fk(q), modified.fk(q), atol=1e-15)


@pytest.mark.parametrize(
    ("name", "source"), [("scara", "standard"), ("cylindrical-4dof", "modified")]
)
def test_cli_convert_of_an_all_parallel_arm_in_both_directions(name, source, tmp_path):
    robot = _in(km.load(name), source)
    target = OTHER[source]
    from_file = cli_convert(robot, target, tmp_path)
    want = robot.to_convention(target)
    assert from_file.convention == target
    np.testing.assert_allclose(from_file.dh_table(), want.dh_table(), atol=1e-9)
    assert_transform_close(from_file.base, want.base, atol=1e-9)
    assert_transform_close(from_file.tool, want.tool, atol=1e-9)


def test_a_urdf_says_which_dh_frames_its_links_are():
    # Frames that obey both conventions' rules read as the file says; a file that says
    # nothing (a hand-written one) reads as standard frames, whose modified table is
    # the standard one regrouped. Same FK either way.
    modified = km.load("cylindrical-4dof").to_convention("modified")
    text = modified.to_urdf()
    assert "each link frame is a modified DH frame" in text
    said = km.urdf_to_dh(parse_urdf(text), convention="modified").robot
    assert_same_table(said, modified)
    silent = text.replace("each link frame is a modified DH frame", "")
    std = km.urdf_to_dh(parse_urdf(silent)).robot
    assert_same_table(
        km.urdf_to_dh(parse_urdf(silent), convention="modified").robot,
        std.to_convention("modified"),
    )
    assert not np.allclose(std.dh_table(), modified.to_convention("standard").dh_table())
    q = np.random.default_rng(6).uniform(0.0, 0.4, (4, 4))
    assert_transform_close(std.fk(q), modified.fk(q), atol=1e-12)


def test_a_chain_says_standard_modified_or_nothing_of_its_frames():
    joint = AxisFrame(kind="R", direction=np.array([0.0, 0.0, 1.0]), frame=np.eye(4))
    for says in (None, "standard", "modified"):
        assert ChainGeometry(joints=(joint,), tip=np.eye(4), dh_frames=says).dh_frames == says
    with pytest.raises(KinematicaError, match="dh_frames must be 'standard', 'modified' or None"):
        ChainGeometry(joints=(joint,), tip=np.eye(4), dh_frames="craig")
