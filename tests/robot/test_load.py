"""A robot loaded from a file is the robot built in code (``robot/load.py``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import kinematica as km
from kinematica.errors import ArgumentError, KinematicaError

ROW = "  - {theta: q1, d: 0.3, a: 0.2, alpha: 90}\n  - {theta: q2, d: 0, a: 0.4, alpha: 0}\n"


def test_a_tool_written_with_seven_digits_loads_rigid(tmp_path: Path) -> None:
    c, s = float(np.cos(0.3)), float(np.sin(0.3))
    R = [[round(c, 7), round(-s, 7), 0.0], [round(s, 7), round(c, 7), 0.0], [0.0, 0.0, 1.0]]
    matrix = [[*R[0], 0.0], [*R[1], 0.0], [*R[2], 0.05], [0.0, 0.0, 0.0, 1.0]]
    path = tmp_path / "arm.yaml"
    path.write_text(f"name: arm\nconvention: standard\njoints:\n{ROW}tool: {{matrix: {matrix}}}\n")
    robot = km.load(path)
    Rt = robot.tool[:3, :3]
    assert np.abs(Rt.T @ Rt - np.eye(3)).max() < 1e-15
    assert np.abs(robot.tool - np.array(matrix)).max() < 1e-7
    # in code, the same matrix is accepted the same way
    assert np.array_equal(
        km.Robot.from_dh(robot.links, tool=matrix, convention="standard").tool, robot.tool
    )


@pytest.mark.parametrize("bad", [None, 3, 2.5, ["puma560"], b"puma560"])
def test_load_of_a_non_path_is_an_argument_error(bad: object) -> None:
    with pytest.raises(ArgumentError, match="load takes a built-in robot name or"):
        km.load(bad)  # type: ignore[arg-type]


@pytest.mark.parametrize("bad", ["", "   "])
def test_load_of_an_empty_name_is_an_argument_error(bad: str) -> None:
    with pytest.raises(ArgumentError, match="load takes a built-in robot name or a path"):
        km.load(bad)


def test_load_of_a_name_too_long_for_the_file_system_is_unknown() -> None:
    with pytest.raises(km.UnknownRobotError):
        km.load("x" * 5000)
    with pytest.raises(KinematicaError):
        km.load("a\x00b.yaml")
