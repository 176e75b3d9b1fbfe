"""Robot-file data checked (``io/_parse.py``): joint and parameter counts on both sides, names."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

import kinematica as km
from kinematica.errors import RobotFileError
from kinematica.io import parse_robot_dict
from kinematica.io._parse import MAX_JOINTS, MAX_PARAMETERS
from kinematica.io.robotfile import MAX_FILE_SIZE


def _joints(n: int) -> dict[str, Any]:
    rows = [{"theta": f"q{i}", "d": 0, "a": 0.1, "alpha": 0} for i in range(1, n + 1)]
    return {"convention": "standard", "joints": rows}


def test_max_joints_load_and_one_more_is_refused() -> None:
    assert parse_robot_dict(_joints(MAX_JOINTS)).dof == MAX_JOINTS
    with pytest.raises(RobotFileError, match=rf"key 'joints': {MAX_JOINTS + 1} joints; at most"):
        parse_robot_dict(_joints(MAX_JOINTS + 1))


def test_a_20000_joint_json_is_refused_before_its_joints_are_read(tmp_path: Path) -> None:
    path = tmp_path / "snake.json"
    path.write_text(json.dumps(_joints(20_000), separators=(",", ":")))
    with pytest.raises(RobotFileError, match=f"robot files of at most {MAX_FILE_SIZE:,} bytes"):
        km.load(path)
    with pytest.raises(RobotFileError, match=r"20000 joints; at most 100 are accepted"):
        parse_robot_dict(_joints(20_000))  # the joint count is checked before any joint


def test_max_parameters_load_and_one_more_is_refused() -> None:
    data = _joints(1)
    data["parameters"] = {f"p{i}": i for i in range(MAX_PARAMETERS)}
    assert len(parse_robot_dict(data).parameters) == MAX_PARAMETERS
    data["parameters"][f"p{MAX_PARAMETERS}"] = 0
    with pytest.raises(RobotFileError, match=rf"{MAX_PARAMETERS + 1} parameters; at most"):
        parse_robot_dict(data)


def test_an_unknown_name_lists_a_few_known_names_only() -> None:
    data = _joints(1)
    data["parameters"] = {f"p{i:03d}": i for i in range(500)}
    data["joints"][0]["a"] = "nope"
    with pytest.raises(RobotFileError, match=r"unknown name 'nope'") as info:
        parse_robot_dict(data)
    assert "p000, p001" in str(info.value) and "p499" not in str(info.value)
    assert len(str(info.value)) < 400
