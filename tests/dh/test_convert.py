"""One arm, one table per convention, whichever way a user asks for it.

``robot.to_convention`` regroups the table (the notes: "las matrices intermedias
varían, pero el resultado final es el mismo": the θ and d columns stay, a and α move
one row); extraction by the rules from the robot (``robot.to_dh``), from its URDF
file (``urdf_to_dh``) and ``kinematica convert <urdf> --to dh-modified`` must give
that same table, base and tool.
"""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from support.helpers import assert_transform_close

import kinematica as km


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


def test_cli_convert_of_the_notes_arm_urdf_gives_to_conventions_table(tmp_path):
    robot = km.load("arm6-dh")
    urdf = tmp_path / "arm6.urdf"
    robot.to_urdf(urdf)
    out = tmp_path / "arm6_mdh.yaml"
    cmd = [sys.executable, "-m", "kinematica.cli.main", "convert", str(urdf)]
    proc = subprocess.run(
        [*cmd, "--to", "dh-modified", "-o", str(out)],
        capture_output=True,
        text=True,
        cwd=tmp_path,
        check=False,
    )
    assert proc.returncode == 0, proc.stderr
    from_file = km.load(out)
    want = robot.to_convention("modified")
    np.testing.assert_allclose(from_file.dh_table(), want.dh_table(), atol=1e-9)
    # row 3 keeps the notes' q3 - 90 and row 5 no 180° offset (the issue's two rows)
    assert from_file.links[2].offset == pytest.approx(-np.pi / 2, abs=1e-12)
    assert from_file.links[4].offset == pytest.approx(0.0, abs=1e-12)
    q = np.random.default_rng(2).uniform(-3, 3, (5, 6))
    assert_transform_close(from_file.fk(q), robot.fk(q), atol=1e-9)
